//! What a renderer needs to filter a lobe, in one import:
//! `use filtered_ndf::f32::prelude::*;` (or `f64`).
//!
//! The material NDFs and their roughness forms, the footprint, the front door
//! ([`Filterable::filtered`] with a [`Method`]: [`Gaussian`], [`ExactGaussian`], [`Projected`], [`Rect`],
//! [`Proxy`], each with a texel's LEAN moments nested in by [`Lean`]; the exact filter's
//! [`Tolerance`]), the clamp rules, the deferred presets, the
//! traits whose methods every lobe has ([`Ndf`], [`NdfSampling`]), and the path tracer's BSDF
//! over any lobe ([`Bsdf`], [`MicrofacetReflection`]).

pub use super::bsdf::{Bsdf, MicrofacetReflection};
pub use super::filter::presets;
pub use super::filter::{
    ExactGaussian, Filterable, Gaussian, GaussianFilteredGgx, Lean, LeanMoments, Method, Projected,
    Proxy, Rect, RectFilteredGgx, Tolerance,
};
pub use super::{
    AxisAligned, Beckmann, ClampRules, Footprint, Ggx, Isotropic, KernelConvention, Ndf,
    NdfSampling, Roughness, RoughnessMatrix,
};
