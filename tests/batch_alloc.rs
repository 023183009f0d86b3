//! The batch functions allocate nothing: a counting global allocator around every batch
//! function of both precisions, over inputs long enough for several blocks of the chunk driver
//! and with elements that take the scalar fallback (NaN, infinite, grazing, huge footprints).
//! The count is per thread (a `const` thread-local, which itself never allocates), so the test
//! harness's other threads cannot disturb it.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    static COUNT: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: forwards every call to `System` unchanged; only counts on the side.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = COUNT.try_with(|c| c.set(c.get() + 1));
        // SAFETY: the caller's contract is passed on to `System`.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let _ = COUNT.try_with(|c| c.set(c.get() + 1));
        // SAFETY: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made on this thread by `f`.
fn allocations(f: impl FnOnce()) -> usize {
    let before = COUNT.with(Cell::get);
    f();
    COUNT.with(Cell::get) - before
}

macro_rules! check {
    ($prec:ident, $t:ty) => {{
        use filtered_ndf::$prec::{AxisAligned, ClampRules, Isotropic, RoughnessMatrix, batch};
        const N: usize = 1500;
        // Realistic values with every tenth element special (the scalar fallback).
        let col = |seed: usize, scale: $t| -> Vec<$t> {
            (0..N)
                .map(|i| match (i + seed) % 10 {
                    0 => <$t>::NAN,
                    3 => <$t>::INFINITY,
                    5 => 1e30,
                    _ => scale * (((i * 7919 + seed * 104_729) % 1000) as $t / 1000.0 - 0.3),
                })
                .collect()
        };
        let (x, y, z) = (col(1, 0.8), col(2, 0.8), col(3, 1.0));
        let (ux, uy, vx, vy) = (col(4, 3.0), col(5, 3.0), col(6, 3.0), col(7, 3.0));
        let (hx, hy) = (col(8, 0.2), col(9, 0.2));
        let fp = batch::Footprints {
            dh_u_x: &ux,
            dh_u_y: &uy,
            dh_v_x: &vx,
            dh_v_y: &vy,
        };
        let v = batch::Vec3s::new(&x, &y, &z);
        let w = batch::Vec3s::new(&y, &x, &z);
        let fp_dn = batch::Vec3s::new(&ux, &uy, &vx);
        let iso = Isotropic::new(0.1 as $t).unwrap();
        let aa = AxisAligned::new(0.1 as $t, 0.02 as $t).unwrap();
        let mat = RoughnessMatrix::new(0.01 as $t, 0.002 as $t, 0.0009 as $t).unwrap();
        let mut out = vec![0.0 as $t; N];
        let (mut o2, mut o3) = (out.clone(), out.clone());
        // Exact Gaussian-filtered lobes (built outside the count: `new` is scalar), one light
        // (Gauss-Laguerre lanes) and one heavy (trapezoid elements, the scalar fallback).
        let exact = {
            use filtered_ndf::$prec::{Covariance, GaussianFilteredGgx};
            [
                GaussianFilteredGgx::new(aa, Covariance::new(1e-5, 0.0, 1e-5)),
                GaussianFilteredGgx::new(mat, Covariance::new(0.05, 0.01, 0.02)),
            ]
        };
        // Warm-up outside the count: one-time initialisation (the dispatcher's CPU detection
        // reads an environment variable once) is not per call.
        batch::ggx_d(&iso, &x, &y, &z, &mut out);
        let n = allocations(|| {
            batch::ggx_d(&iso, &x, &y, &z, &mut out);
            batch::ggx_d(&aa, &x, &y, &z, &mut out);
            batch::ggx_d(&mat, &x, &y, &z, &mut out);
            batch::beckmann_d(&iso, &x, &y, &z, &mut out);
            batch::beckmann_d(&aa, &x, &y, &z, &mut out);
            batch::beckmann_d(&mat, &x, &y, &z, &mut out);
            batch::ggx_lambda(&aa, &x, &y, &z, &mut out);
            batch::ggx_lambda(&mat, &x, &y, &z, &mut out);
            batch::beckmann_lambda(&aa, &x, &y, &z, &mut out);
            batch::beckmann_lambda(&mat, &x, &y, &z, &mut out);
            batch::ggx_g2(&aa, v, w, v, &mut out);
            batch::beckmann_g2(&mat, v, w, v, &mut out);
            for rules in [ClampRules::default(), ClampRules::NONE, ClampRules::GDC2016] {
                batch::beckmann_d_filtered(&aa, &rules, 0.5, &x, &y, &z, fp, &mut out);
                batch::ggx_d_filtered(&aa, &rules, 0.5, &x, &y, &z, fp, &mut out);
                batch::ggx_d_filtered(&mat, &rules, 0.5, &x, &y, &z, fp, &mut out);
                batch::ggx_d_filtered_projected(&aa, &rules, 0.5, &x, &y, &z, fp, &mut out);
                batch::ggx_d_filtered_projected(&mat, &rules, 0.5, &x, &y, &z, fp, &mut out);
                batch::ggx_d_filtered_exact(&aa, &rules, 0.5, &x, &y, &z, fp, &mut out);
                batch::ggx_d_filtered_exact(&mat, &rules, 0.5, &x, &y, &z, fp, &mut out);
            }
            batch::d_rect(&aa, &x, &y, &z, &hx, &hy, &mut out);
            for rules in [ClampRules::default(), ClampRules::GDC2016] {
                batch::d_rect_filtered(&aa, &rules, &x, &y, &z, fp, &mut out);
                batch::ggx_d_filtered_proxy(&aa, &rules, &x, &y, &z, fp, &mut out);
            }
            for (u1, u2) in [(&hx, &hy), (&ux, &vy)] {
                batch::ggx_sample_visible_normal(&mat, v, u1, u2, &mut out, &mut o2, &mut o3);
                batch::ggx_sample_visible_normal(&iso, w, u2, u1, &mut out, &mut o2, &mut o3);
                batch::beckmann_sample_visible_normal(&mat, v, u1, u2, &mut out, &mut o2, &mut o3);
                batch::beckmann_sample_visible_normal(&aa, w, u2, u1, &mut out, &mut o2, &mut o3);
            }
            batch::ggx_sample_normal(&mat, &hx, &ux, &mut out, &mut o2, &mut o3);
            batch::beckmann_sample_normal(&aa, &ux, &hy, &mut out, &mut o2, &mut o3);
            batch::beckmann_sample_normal(&mat, &hx, &hy, &mut out, &mut o2, &mut o3);
            batch::ggx_normal_pdf(&mat, &x, &y, &z, &mut out);
            batch::beckmann_normal_pdf(&aa, &x, &y, &z, &mut out);
            batch::ggx_visible_normal_pdf(&aa, v, w, &mut out);
            batch::ggx_visible_normal_pdf(&mat, w, v, &mut out);
            batch::beckmann_visible_normal_pdf(&iso, v, w, &mut out);
            batch::beckmann_visible_normal_pdf(&mat, w, v, &mut out);
            batch::ggx_reflection_pdf_from_normal(&iso, v, w, &mut out);
            batch::ggx_reflection_pdf_from_normal(&mat, w, v, &mut out);
            batch::beckmann_reflection_pdf_from_normal(&aa, v, w, &mut out);
            batch::beckmann_reflection_pdf_from_normal(&mat, w, v, &mut out);
            let kernels = batch::Covariances {
                s11: &ux,
                s12: &uy,
                s22: &vx,
            };
            batch::ggx_d_projected(&aa, kernels, &x, &y, &z, &mut out);
            batch::ggx_d_projected(&mat, kernels, &hx, &hy, &z, &mut out);
            for lobe in exact {
                batch::gaussian_filtered_ggx_d(&lobe, &x, &y, &z, &mut out);
                batch::gaussian_filtered_ggx_d(&lobe, &hx, &hy, &z, &mut out);
            }
            for (_, conv) in filtered_ndf::$prec::filter::presets::ALL {
                batch::deferred_filter(&conv, &z, v, fp_dn, &mut out);
            }
        });
        assert_eq!(
            n,
            0,
            "{}: batch functions allocated {n} times",
            stringify!($prec)
        );
    }};
}

#[test]
fn batch_functions_allocate_nothing() {
    // The counter works (else a zero would prove nothing).
    assert!(allocations(|| drop(std::hint::black_box(vec![1u8; 16]))) >= 1);
    check!(f32, f32);
    check!(f64, f64);
}
