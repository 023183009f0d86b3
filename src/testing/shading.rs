//! Seeded, realistic shading inputs shared by every benchmark and by the trade table
//! (`filtered-ndf-demo`'s `tradeoff`), so that cost and error are measured on the same
//! distribution.

pub use super::rng::SplitMix64 as Rng;

/// One shading situation a renderer meets: a material, a half vector and a pixel footprint.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    /// Roughness `(alpha_x, alpha_y)` of an axis-aligned material.
    pub alpha: [f64; 2],
    /// Unit half vector in the tangent frame.
    pub h: [f64; 3],
    /// Slope-domain footprint `dh_u`, `dh_v` (per pixel).
    pub dh_u: [f64; 2],
    /// See `dh_u`.
    pub dh_v: [f64; 2],
}

impl Case {
    /// Slope of `h`: `-h_xy / h_z`.
    pub fn slope(&self) -> [f64; 2] {
        [-self.h[0] / self.h[2], -self.h[1] / self.h[2]]
    }
}

fn unit_from_slope(s: [f64; 2]) -> [f64; 3] {
    let n = (1.0 + s[0] * s[0] + s[1] * s[1]).sqrt();
    [-s[0] / n, -s[1] / n, 1.0 / n]
}

/// `n` realistic cases (seeded) of the situations NDF filtering exists for: glossy materials
/// (alpha log-uniform in `[0.005, 0.5]`, anisotropy ratio up to 4 in one case in four),
/// pixel footprints from a twentieth of the lobe width to twenty times it (extent
/// `alpha * [0.05, 20]` log-uniform, at most 1 slope per pixel, random orientation and
/// shear), half vectors near the lobe (slope Gaussian with twice the roughness plus the
/// footprint scale; one case in eight far in the tail, one in eight grazing, 60 to 89
/// degrees).
pub fn realistic_cases(n: usize, seed: u64) -> Vec<Case> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|i| {
            let a = rng.log_uniform(0.005, 0.5);
            let ratio = if i % 4 == 3 {
                rng.log_uniform(1.0, 4.0)
            } else {
                1.0
            };
            let alpha = [a, (a * ratio).min(1.0)];
            let ext = (a * rng.log_uniform(0.05, 20.0)).min(1.0);
            let (p1, p2) = (
                std::f64::consts::TAU * rng.uniform(),
                std::f64::consts::TAU * rng.uniform(),
            );
            let e2 = ext * rng.log_uniform(0.1, 1.0);
            let dh_u = [ext * p1.cos(), ext * p1.sin()];
            let dh_v = [e2 * p2.cos(), e2 * p2.sin()];
            let h = match i % 8 {
                6 => {
                    let r = 10.0 * a * (1.0 + rng.uniform());
                    let phi = std::f64::consts::TAU * rng.uniform();
                    unit_from_slope([r * phi.cos(), r * phi.sin()])
                }
                7 => {
                    let t = (60.0 + 29.0 * rng.uniform()).to_radians();
                    let phi = std::f64::consts::TAU * rng.uniform();
                    [t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos()]
                }
                _ => {
                    let w = 2.0 * a + ext;
                    unit_from_slope([w * rng.normal(), w * rng.normal()])
                }
            };
            Case {
                alpha,
                h,
                dh_u,
                dh_v,
            }
        })
        .collect()
}
