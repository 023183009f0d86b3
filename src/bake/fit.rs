//! Roughness fits: the GGX or Beckmann lobe closest to a mip texel's distribution of normals,
//! for engines that store one roughness channel (glTF's metallic-roughness G channel) or an
//! anisotropic pair.
//!
//! # The texel's distribution and its model
//! The true distribution of a mip texel is its base texels' lobes averaged, each centred on its
//! texel's slope: `P22_true(s) = sum_i w_i P22_base(s - s_i)` (module docs of [`super`]). A fit
//! reads three statistics of it ([`TexelStats`]):
//! - the centre `c`: the slope of the normalised mean normal, `c = -E[n]_xy / E[n]_z`, which is
//!   what an engine's box-filtered normal mip gives after the shader normalises it (the lobe the
//!   engine draws is centred there, whatever the roughness channel says);
//! - the spread about it, `Sigma_c = E[(s - c)(s - c)^T] = Cov[s] + (E[s] - c)(E[s] - c)^T`,
//!   with eigenvalues `lambda_1 >= lambda_2` along the angle `phi` of the first eigenvector;
//! - the base roughness `a = sqrt(E[alpha^2])`.
//!
//! and fits the model `P22_model = P22_base(a) * N(0, Sigma_c)` (the slope-domain convolution
//! that LEAN mapping and KHPL16 eq. 21 assume).
//!
//! # The criterion: total variation
//! `E = integral |P22_model(s) - P22_fit(s)| ds`, which equals `integral |D_model - D_fit|
//! cos(theta_h) d omega_h` (both are densities of projected microfacet area), in `[0, 2]`.
//! Why: it is the largest difference in the fraction of light the two surfaces send into any
//! set of directions; for a view along the normal it is exactly the L1 error of the highlight
//! a small light draws over all light directions (masking and Fresnel aside); and it is finite
//! for any pair of lobes, where moment matching is not (GGX's second moments are infinite).
//! Slope-domain scaling leaves it unchanged, so for GGX the best `alpha` for
//! `GGX(a) * N(0, u^2 a^2 I)` is `a F(u)` for one function `F` ([`ggx_widening`]), tabulated
//! once by `f64` quadrature (`tests/bake_fit.rs` derives the table and checks it; its error is
//! stated at [`ggx_widening`]).
//!
//! # The fits
//! - GGX, anisotropic: `alpha_i = a F(sqrt(lambda_i) / a)` along the eigenvectors of `Sigma_c`
//!   (each axis widened as an isotropic spread of that variance would widen it).
//! - GGX, isotropic: `alpha = a F(sqrt((lambda_1 + lambda_2) / 2) / a)`.
//! - Beckmann, anisotropic: `A = a^2 I + 2 Sigma_c` (KHPL16 eq. 21: the convolution of a
//!   Beckmann lobe with a Gaussian is that Beckmann lobe, exact under the model).
//! - Beckmann, isotropic: `alpha^2 = a^2 + lambda_1 + lambda_2` (the trace of `A` / 2: the
//!   isotropic lobe with the same `E[|s - c|^2]`).
//!
//! The error of each fit against the true distribution (not the model) is measured per level
//! in `docs/bake.md`.

use super::footprint::TexelStats;
use crate::math as m;
use glam::DVec2;

/// A lobe with two roughnesses: `alpha_x` along the direction at `angle` radians from the
/// bake's `+x` (the texture's `+u`) towards `+y` (up the image), `alpha_y` across it;
/// `alpha_x >= alpha_y` and `angle` in `(-pi/2, pi/2]`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AnisotropicAlpha {
    /// Roughness along the major axis.
    pub alpha_x: f64,
    /// Roughness along the minor axis.
    pub alpha_y: f64,
    /// The major axis' angle in radians.
    pub angle: f64,
}

/// A lobe in the encoding of glTF's `KHR_materials_anisotropy`: the metallic-roughness
/// texture's perceptual roughness `r` (`alpha_b = r^2` across the anisotropy direction) and the
/// anisotropy texture's strength and direction, with `alpha_t = mix(alpha_b, 1, strength^2)`
/// along the direction (the extension's definition).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct KhrAnisotropy {
    /// Perceptual roughness `sqrt(alpha_y)`, in `[0, 1]`.
    pub roughness: f64,
    /// `sqrt((alpha_x - alpha_y) / (1 - alpha_y))`, clamped to `[0, 1]` (`alpha_x > 1` cannot
    /// be stored and saturates at `alpha_t = 1`).
    pub strength: f64,
    /// `(cos angle, sin angle)`: the anisotropy texture's red and green channels (in
    /// `[-1, 1]`, stored as `(v + 1) / 2`).
    pub direction: DVec2,
}

impl AnisotropicAlpha {
    /// The lobe in `KHR_materials_anisotropy`'s encoding; `alpha_y` is clamped to `[0, 1]`
    /// first (glTF's roughness range).
    pub fn khr(&self) -> KhrAnisotropy {
        let ay = self.alpha_y.clamp(0.0, 1.0);
        let strength = if ay < 1.0 {
            m::sqrt(((self.alpha_x - ay) / (1.0 - ay)).clamp(0.0, 1.0))
        } else {
            0.0
        };
        KhrAnisotropy {
            roughness: m::sqrt(ay),
            strength,
            direction: DVec2::new(m::cos(self.angle), m::sin(self.angle)),
        }
    }
}

/// glTF's perceptual roughness of an `alpha`: `sqrt(alpha)` (the metallic-roughness texture's
/// G channel stores it; `alpha = r^2`). `alpha` is clamped to `[0, 1]` first.
#[inline]
pub fn perceptual(alpha: f64) -> f64 {
    m::sqrt(alpha.clamp(0.0, 1.0))
}

/// Nodes of the GGX widening table ([`ggx_widening`]).
const GGX_FIT_NODES: usize = GGX_FIT.len();

/// `G(t_j) = F(u_j) / sqrt(1 + 2 u_j^2)` at `t_j = j / 64`, `u_j = t_j / (1 - t_j)`
/// (`t = 1`: the limit `u -> infinity`, the best GGX for a Gaussian alone). Derived by
/// `tests/bake_fit.rs` (`cargo test --release --test bake_fit -- --ignored --nocapture`).
const GGX_FIT: [f64; 65] = include!("ggx_fit_table.in");

/// The widening of the best GGX fit: `F(u)` such that `GGX(a F(u))` minimises the total
/// variation to `GGX(a) * N(0, u^2 a^2 I)` (module docs), `u >= 0`; `F(0) = 1`, and
/// `F(u) / u` tends to the best GGX `alpha` for a unit Gaussian alone. Evaluated as
/// `sqrt(1 + 2 u^2) G(u / (1 + u))` with `G` a Catmull-Rom cubic through the 65 nodes of the
/// table. Error (measured by `tests/bake_fit.rs` against direct minimisation by `f64`
/// quadrature at the 64 midpoints between nodes): at most `1.7e-4` relative in `F`, which
/// costs at most `8e-8` of total variation (the minimum is flat). The minimum itself ranges
/// from `0` at `u = 0` to `0.36` for `u -> inf` (no GGX lobe is close to a Gaussian). NaN or
/// negative `u` give `1`; `+inf` gives `+inf`.
pub fn ggx_widening(u: f64) -> f64 {
    if u.is_nan() || u <= 0.0 {
        return 1.0;
    }
    if u == f64::INFINITY {
        return f64::INFINITY;
    }
    let t = u / (1.0 + u);
    m::sqrt(1.0 + 2.0 * u * u) * table(t)
}

/// The Catmull-Rom interpolant of the table at `t in [0, 1]`, the end slopes taken from
/// one-sided differences.
fn table(t: f64) -> f64 {
    let last = GGX_FIT_NODES - 1;
    let x = t.clamp(0.0, 1.0) * last as f64;
    let j = (x as usize).min(last - 1);
    let f = x - j as f64;
    let p1 = GGX_FIT[j];
    let p2 = GGX_FIT[j + 1];
    let p0 = if j == 0 {
        2.0 * p1 - p2
    } else {
        GGX_FIT[j - 1]
    };
    let p3 = if j + 1 == last {
        2.0 * p2 - p1
    } else {
        GGX_FIT[j + 2]
    };
    let (m1, m2) = (0.5 * (p2 - p0), 0.5 * (p3 - p1));
    let (f2, f3) = (f * f, f * f * f);
    (2.0 * f3 - 3.0 * f2 + 1.0) * p1
        + (f3 - 2.0 * f2 + f) * m1
        + (-2.0 * f3 + 3.0 * f2) * p2
        + (f3 - f2) * m2
}

/// The statistics a fit reads (module docs): the centre `c`, the eigenvalues
/// `lambda_1 >= lambda_2 >= 0` of `Sigma_c` and the first eigenvector's angle, and the base
/// `a = sqrt(E[alpha^2])`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Spread {
    /// The lobe's centre `c`, the slope of the normalised mean normal (`E[s]` if the mean
    /// normal has no positive `z`, which unit normals above the surface never give).
    pub centre: DVec2,
    /// The larger eigenvalue of `Sigma_c`.
    pub lambda_1: f64,
    /// The smaller eigenvalue of `Sigma_c` (`>= 0`).
    pub lambda_2: f64,
    /// The first eigenvector's angle from `+x` towards `+y`, in `(-pi/2, pi/2]`.
    pub angle: f64,
    /// `sqrt(E[alpha^2])`.
    pub alpha: f64,
}

impl Spread {
    /// The spread of a texel's statistics.
    pub fn of(t: &TexelStats) -> Self {
        let n = t.normal;
        let centre = if n.z > 0.0 {
            DVec2::new(-n.x / n.z, -n.y / n.z)
        } else {
            t.mean
        };
        let (c11, c12, c22) = t.covariance();
        let d = t.mean - centre;
        let (s11, s12, s22) = (c11 + d.x * d.x, c12 + d.x * d.y, c22 + d.y * d.y);
        let half_tr = 0.5 * (s11 + s22);
        let half_diff = 0.5 * (s11 - s22);
        let r = m::hypot(half_diff, s12);
        let angle = if r > 0.0 {
            0.5 * m::atan2(s12, half_diff)
        } else {
            0.0
        };
        Self {
            centre,
            lambda_1: half_tr + r,
            lambda_2: (half_tr - r).max(0.0),
            angle,
            alpha: m::sqrt(t.alpha2.max(0.0)),
        }
    }
}

/// `a F(sqrt(lambda) / a)`; for `a = 0` the Gaussian alone, `sqrt(2 lambda) G(1)`.
fn ggx_axis(a: f64, lambda: f64) -> f64 {
    if a > 0.0 {
        a * ggx_widening(m::sqrt(lambda) / a)
    } else {
        m::sqrt(2.0 * lambda) * GGX_FIT[GGX_FIT_NODES - 1]
    }
}

/// The isotropic GGX `alpha` closest to the texel's model (module docs):
/// `a F(sqrt((lambda_1 + lambda_2) / 2) / a)`.
pub fn ggx_isotropic(s: &Spread) -> f64 {
    ggx_axis(s.alpha, 0.5 * (s.lambda_1 + s.lambda_2))
}

/// The anisotropic GGX lobe closest to the texel's model (module docs): `a F(sqrt(lambda_i) /
/// a)` along `Sigma_c`'s eigenvectors.
pub fn ggx_anisotropic(s: &Spread) -> AnisotropicAlpha {
    AnisotropicAlpha {
        alpha_x: ggx_axis(s.alpha, s.lambda_1),
        alpha_y: ggx_axis(s.alpha, s.lambda_2),
        angle: s.angle,
    }
}

/// The isotropic Beckmann `alpha` with the model's `E[|s - c|^2]`:
/// `sqrt(a^2 + lambda_1 + lambda_2)`.
pub fn beckmann_isotropic(s: &Spread) -> f64 {
    m::sqrt(s.alpha * s.alpha + s.lambda_1 + s.lambda_2)
}

/// The anisotropic Beckmann lobe equal to the model, `A = a^2 I + 2 Sigma_c` (KHPL16 eq. 21):
/// `alpha_i = sqrt(a^2 + 2 lambda_i)`.
pub fn beckmann_anisotropic(s: &Spread) -> AnisotropicAlpha {
    let a2 = s.alpha * s.alpha;
    AnisotropicAlpha {
        alpha_x: m::sqrt(a2 + 2.0 * s.lambda_1),
        alpha_y: m::sqrt(a2 + 2.0 * s.lambda_2),
        angle: s.angle,
    }
}
