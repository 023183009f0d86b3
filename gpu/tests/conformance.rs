//! The GPU conformance harness: every WGSL function of `shaders/` on seeded cases against
//! the crate's f64 references (`gpu/src/checks/`). The backend is chosen by
//! `FILTERED_NDF_GPU_BACKEND` (`vulkan`, `gl`, `any`); a missing adapter fails these tests
//! with a message naming the package to install.

use filtered_ndf_gpu::checks::{self, assert_group};

/// One test per group of `checks::GROUPS` (run in parallel), and a test that the list here is
/// that list.
macro_rules! groups {
    ($($name:ident),* $(,)?) => {
        $(
            #[test]
            fn $name() {
                assert_group(stringify!($name), &checks::group(stringify!($name)));
            }
        )*

        #[test]
        fn every_group_has_a_test() {
            let here = [$(stringify!($name)),*];
            let groups: Vec<&str> = checks::GROUPS.iter().map(|(n, _)| *n).collect();
            assert_eq!(here.as_slice(), groups.as_slice());
        }
    };
}

groups!(
    math,
    ndf,
    footprint,
    filters,
    rect,
    rect_sample,
    nan_policy,
    gaussian_ggx,
    method,
    lean_nested,
    bake,
    sampling,
    sampling_beckmann,
);
