//! The GPU conformance harness: every WGSL function of `shaders/` on seeded cases against
//! the crate's f64 references (`gpu/src/checks/`). The backend is chosen by
//! `FILTERED_NDF_GPU_BACKEND` (`vulkan`, `gl`, `any`); a missing adapter fails these tests
//! with a message naming the package to install.

use filtered_ndf_gpu::checks::{self, assert_group};

#[test]
fn math() {
    assert_group("math", &checks::math::all());
}

#[test]
fn ndf() {
    assert_group("ndf", &checks::ndf::all());
}

#[test]
fn footprint_and_kernel() {
    assert_group("footprint", &checks::footprint::all());
}

#[test]
fn filters() {
    assert_group("filters", &checks::filters::all());
}

#[test]
fn sampling() {
    assert_group("sampling", &checks::sampling::all());
}

#[test]
fn sampling_beckmann() {
    assert_group("sampling_beckmann", &checks::sampling_beckmann::all());
}

#[test]
fn rect() {
    assert_group("rect", &checks::rect::all());
}

#[test]
fn rect_sample() {
    assert_group("rect_sample", &checks::rect_sample::all());
}

#[test]
fn nan_policy() {
    assert_group("nan_policy", &checks::nan_policy::all());
}

#[test]
fn gaussian_ggx() {
    assert_group("gaussian_ggx", &checks::gaussian_ggx::all());
}

#[test]
fn method() {
    assert_group("method", &checks::method::all());
}
