//! The roughness bakes that engines and papers use, re-implemented from their published
//! formulas for the bake's accuracy study (`bin/bake_accuracy`). Each returns the GGX
//! `alpha` (`alpha = r^2` for a perceptual roughness `r`) that the engine would draw, centred
//! on its normal mip's normalised normal.
//!
//! - Toksvig (2005), "Mipmapping normal maps": with `L = |E[n]|` the length of the mean unit
//!   normal, a Blinn-Phong exponent `p` becomes `p' = L p / (L + p (1 - L))`; with the usual
//!   GGX correspondence `p = 2 / alpha^2 - 2` (Walter et al. 2007), `alpha'^2 = 2 / (p' + 2)`.
//! - Unreal Engine 4, composite texture (`CTM_NormalRoughnessTo*`, the texture's Composite
//!   Texture and Composite Power settings): `TextureCompressorModule.cpp`, function
//!   `ApplyCompositeTexture`: `V = max(0, (1 - L) / L - 0.00004) * power`, then with
//!   `a2 = alpha^2`: `a2' = (B - a2) / (B - 1)`, `B = 2 V (a2 - 1)`, which is Toksvig's
//!   formula in that correspondence (its disabled branch reads `p' = p / (1 + V p)`), with a
//!   small bias. `L` is the length of Unreal's own normal mip (built with a blurring mip
//!   kernel); here it is the footprint's mean normal, as for the other bakes.
//! - three.js `RoughnessMipmapper` (examples/jsm/utils/RoughnessMipmapper.js, removed from
//!   three.js later): each level from the one below: the four children's roughness averaged
//!   (a bilinear fetch at their common corner), mapped to a "variance" by the piecewise-linear
//!   `roughnessToVariance` (nodes `(r, v)` = `(1.0, 0.339)`, `(0.8, 0.276)`, `(0.4, 0.046)`,
//!   `(0.305, 0.016)`, and `v = 1.79 r^4` below `0.305`), plus `1 - |mean of the four children's
//!   normalised normal-mip normals|`, mapped back by the inverse (`r = (0.559 v)^(1/4)` below
//!   `v = 0.016`).
//! - LEAN (Olano and Baker 2010) nested as in KHPL16 eq. 21: GGX with `A = alpha^2 I + 2
//!   Cov[s]` centred on `E[s]` (the crate's `filter::lean` with no pixel footprint).

use filtered_ndf::f64::filter::{LeanMoments, lean};
use filtered_ndf::f64::{Covariance, Isotropic};
use glam::DVec2;

/// Toksvig's `alpha` for a base `alpha` and a mean-normal length `l` in `(0, 1]`.
pub fn toksvig(alpha: f64, l: f64) -> f64 {
    let l = l.clamp(1e-9, 1.0);
    let p = 2.0 / (alpha * alpha) - 2.0;
    let p2 = l * p / (l + p * (1.0 - l));
    (2.0 / (p2 + 2.0)).sqrt()
}

/// Unreal's composite-texture `alpha` (composite power 1).
pub fn unreal(alpha: f64, l: f64) -> f64 {
    let l = l.clamp(1e-9, 1.0);
    let v = ((1.0 - l) / l - 0.00004).max(0.0);
    let a2 = alpha * alpha;
    let b = 2.0 * v * (a2 - 1.0);
    ((b - a2) / (b - 1.0)).sqrt()
}

/// three.js's piecewise map from perceptual roughness to its "variance".
pub fn three_roughness_to_variance(r: f64) -> f64 {
    const R: [f64; 4] = [1.0, 0.8, 0.4, 0.305];
    const V: [f64; 4] = [0.339, 0.276, 0.046, 0.016];
    for i in 0..3 {
        if r >= R[i + 1] {
            return (R[i] - r) * (V[i + 1] - V[i]) / (R[i] - R[i + 1]) + V[i];
        }
    }
    1.79 * r.powi(4)
}

/// The inverse of [`three_roughness_to_variance`] (three.js's `varianceToRoughness`).
pub fn three_variance_to_roughness(v: f64) -> f64 {
    const R: [f64; 4] = [1.0, 0.8, 0.4, 0.305];
    const V: [f64; 4] = [0.339, 0.276, 0.046, 0.016];
    for i in 0..3 {
        if v >= V[i + 1] {
            return (V[i] - v) * (R[i + 1] - R[i]) / (V[i] - V[i + 1]) + R[i];
        }
    }
    (0.559 * v).powf(0.25)
}

/// One step of three.js's mipmapper: the perceptual roughness of a texel from its four
/// children's roughness `r` and normal-mip normals `n` (not necessarily unit).
pub fn three_step(r: [f64; 4], n: [glam::DVec3; 4]) -> f64 {
    let mean_r = 0.25 * r.iter().sum::<f64>();
    let mean_n = 0.25 * n.iter().map(|v| v.normalize()).sum::<glam::DVec3>();
    three_variance_to_roughness(three_roughness_to_variance(mean_r) + 1.0 - mean_n.length())
}

/// LEAN's GGX lobe (KHPL16 eq. 21): `(centre E[s], A = (a11, a12, a22))`.
pub fn lean_lobe(alpha: f64, mean: DVec2, second: (f64, f64, f64)) -> (DVec2, (f64, f64, f64)) {
    let m = LeanMoments::new(mean, Covariance::new(second.0, second.1, second.2));
    let a = lean(Isotropic::new_clamped(alpha), Covariance::ZERO, &m);
    (mean, a.entries())
}
