//! The batch kernels, one file per family: each public function builds its kernel (the lane
//! form of the scalar function, its scalar path, per-batch constants) and runs it on the
//! engine (`super::engine`). The kernels import the engine; the engine imports no kernel.

// The names `per_form!` expands to in the kernels' files (`super::Form`, ...).
use super::super::ndf::roughness::Roughness;
use super::super::ndf::roughness::sealed::{Form, Sealed};

mod deferred;
mod exact;
mod filtered;
mod ndf;
mod pdf;
mod projected;
mod proxy;
mod rect;
mod sample;

pub use deferred::deferred_filter;
pub use exact::{gaussian_filtered_ggx_d, ggx_d_filtered_exact};
pub use filtered::{beckmann_d_filtered, ggx_d_filtered};
pub use ndf::{beckmann_d, beckmann_g2, beckmann_lambda, ggx_d, ggx_g2, ggx_lambda};
pub use pdf::{
    beckmann_normal_pdf, beckmann_reflection_pdf_from_normal, beckmann_visible_normal_pdf,
    ggx_normal_pdf, ggx_reflection_pdf_from_normal, ggx_visible_normal_pdf,
};
pub use projected::{ggx_d_filtered_projected, ggx_d_projected};
pub use proxy::ggx_d_filtered_proxy;
pub use rect::{d_rect, d_rect_filtered};
pub use sample::{
    beckmann_sample_normal, beckmann_sample_visible_normal, ggx_sample_normal,
    ggx_sample_visible_normal,
};
