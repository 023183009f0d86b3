//! The chains as texel bytes: the KTX2 levels and the inspection images.
//!
//! | file | KTX2 format | channels |
//! |---|---|---|
//! | `roughness.ktx2`, perceptual (default) | `R8_UNORM` | glTF's perceptual roughness `sqrt(alpha)` of the isotropic fit; with `--anisotropic`, `KHR_materials_anisotropy`'s roughness `sqrt(alpha_y)` |
//! | `anisotropy.ktx2` (`--anisotropic`, perceptual) | `R8G8B8A8_UNORM` | `KHR_materials_anisotropy`'s texture: direction `(cos, sin)` of the major axis as `(v + 1) / 2`, strength, `A = 1` |
//! | `roughness.ktx2`, `--store alpha` | `R16_SFLOAT` | `alpha` of the isotropic fit |
//! | `roughness.ktx2`, `--store alpha --anisotropic` | `R16G16B16A16_SFLOAT` | the roughness matrix `A = R diag(alpha_x^2, alpha_y^2) R^T`: `(A11, A12, A22, 1)` |
//! | `moments.ktx2` | `R16G16B16A16_SFLOAT` (`--moments f32`: `R32G32B32A32_SFLOAT`) | `(E[s_x], E[s_y], E[s_x^2], E[s_y^2])` |
//! | `moments_xy.ktx2` | `R16_SFLOAT` (`R32_SFLOAT`) | `E[s_x s_y]` |
//!
//! The moments are split RGBA + R because no filterable three-channel float format exists in
//! WebGPU or Vulkan's required set, and this split keeps the mean and both variances in one
//! fetch (an isotropic consumer, which needs `tr Cov[s]` only, reads the first texture alone);
//! the covariance's off-diagonal term is the second fetch.

use crate::chain::Chains;
use filtered_ndf::bake::f16::f16_saturating;
use filtered_ndf::bake::fit::{self, AnisotropicAlpha};

/// How the roughness chain is stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Store {
    /// glTF: perceptual roughness in 8 bits (and `KHR_materials_anisotropy`'s texture).
    Perceptual,
    /// `alpha` (or the roughness matrix) in `f16`.
    Alpha,
}

/// The moment chain's precision.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Precision {
    /// IEEE binary16 (filterable on every WebGPU device).
    F16,
    /// IEEE binary32 (filterable only where the device has `float32-filterable`).
    F32,
}

/// `round(255 v)` of `v` clamped to `[0, 1]`.
pub fn unorm8(v: f64) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// The anisotropic fit of a texel.
pub fn lobe(a: [f32; 3]) -> AnisotropicAlpha {
    AnisotropicAlpha {
        alpha_x: f64::from(a[0]),
        alpha_y: f64::from(a[1]),
        angle: f64::from(a[2]),
    }
}

/// The roughness matrix `(A11, A12, A22)` of an anisotropic lobe:
/// `R(angle) diag(alpha_x^2, alpha_y^2) R(angle)^T`.
pub fn matrix(a: &AnisotropicAlpha) -> (f64, f64, f64) {
    let (s, c) = a.angle.sin_cos();
    let (x2, y2) = (a.alpha_x * a.alpha_x, a.alpha_y * a.alpha_y);
    (
        c * c * x2 + s * s * y2,
        c * s * (x2 - y2),
        s * s * x2 + c * c * y2,
    )
}

fn f16_bytes(v: impl Iterator<Item = f32>) -> Vec<u8> {
    v.flat_map(|x| f16_saturating(x).to_le_bytes()).collect()
}

fn f32_bytes(v: impl Iterator<Item = f32>) -> Vec<u8> {
    v.flat_map(f32::to_le_bytes).collect()
}

/// The roughness chain's texels of texels `range` (one level), in its KTX2 format.
pub fn roughness(c: &Chains, range: std::ops::Range<usize>, store: Store) -> Vec<u8> {
    match (store, &c.anisotropic) {
        (Store::Perceptual, None) => c.isotropic[range]
            .iter()
            .map(|&a| unorm8(fit::perceptual(f64::from(a))))
            .collect(),
        (Store::Perceptual, Some(an)) => an[range]
            .iter()
            .map(|&a| unorm8(lobe(a).khr().roughness))
            .collect(),
        (Store::Alpha, None) => f16_bytes(c.isotropic[range].iter().copied()),
        (Store::Alpha, Some(an)) => f16_bytes(an[range].iter().flat_map(|&a| {
            let (a11, a12, a22) = matrix(&lobe(a));
            [a11 as f32, a12 as f32, a22 as f32, 1.0]
        })),
    }
}

/// `KHR_materials_anisotropy`'s texture of one anisotropic lobe, RGBA8.
pub fn khr_texel(a: [f32; 3]) -> [u8; 4] {
    let k = lobe(a).khr();
    [
        unorm8(0.5 * (k.direction.x + 1.0)),
        unorm8(0.5 * (k.direction.y + 1.0)),
        unorm8(k.strength),
        255,
    ]
}

/// The anisotropy texture's texels of `range` (perceptual storage with `--anisotropic`).
pub fn anisotropy(an: &[[f32; 3]], range: std::ops::Range<usize>) -> Vec<u8> {
    an[range].iter().flat_map(|&a| khr_texel(a)).collect()
}

/// The moment texture `(E[s_x], E[s_y], E[s_x^2], E[s_y^2])` of `range`.
pub fn moments_rgba(m: &[[f32; 5]], range: std::ops::Range<usize>, p: Precision) -> Vec<u8> {
    let it = m[range].iter().flat_map(|t| [t[0], t[1], t[2], t[4]]);
    match p {
        Precision::F16 => f16_bytes(it),
        Precision::F32 => f32_bytes(it),
    }
}

/// The moment texture `E[s_x s_y]` of `range`.
pub fn moments_xy(m: &[[f32; 5]], range: std::ops::Range<usize>, p: Precision) -> Vec<u8> {
    let it = m[range].iter().map(|t| t[3]);
    match p {
        Precision::F16 => f16_bytes(it),
        Precision::F32 => f32_bytes(it),
    }
}

/// `tr Cov[s] = E[s_x^2] - E[s_x]^2 + E[s_y^2] - E[s_y]^2` of a stored texel (in `f64`,
/// negative rounding residues as `0`): the slope variance the level's filtering adds.
pub fn variance(t: &[f32; 5]) -> f64 {
    let (mx, my) = (f64::from(t[0]), f64::from(t[1]));
    ((f64::from(t[2]) - mx * mx).max(0.0) + (f64::from(t[4]) - my * my).max(0.0)).max(0.0)
}

/// The mean slope `E[s]` as an RGB normal-map texel (OpenGL convention):
/// `n = (-E[s], 1) / |(-E[s], 1)|`, each component as `(n + 1) / 2`.
pub fn mean_normal(t: &[f32; 5]) -> [u8; 3] {
    let (sx, sy) = (f64::from(t[0]), f64::from(t[1]));
    let l = (1.0 + sx * sx + sy * sy).sqrt();
    [
        unorm8(0.5 * (-sx / l + 1.0)),
        unorm8(0.5 * (-sy / l + 1.0)),
        unorm8(0.5 * (1.0 / l + 1.0)),
    ]
}
