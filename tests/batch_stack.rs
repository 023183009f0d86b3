//! Every batch function runs on a thread of 2 MiB of stack, the default of a spawned thread
//! and of a test, in unoptimised builds too: each kernel family in both precisions, over
//! inputs long enough for several blocks of the chunk driver and with elements that take every
//! path of it (the lanes, the gathered second lanes, the sorted blocks of the exact Gaussian
//! filter, the scalar fallback). A function whose frames need more overflows the thread's
//! stack, which aborts the test process. CI runs this file without `--release`, with and
//! without `dispatch` (each instruction set's loop has its own frames).

/// The stack of the thread that runs the batch functions (`std::thread`'s default).
const STACK: usize = 2 << 20;

macro_rules! every_function {
    ($prec:ident, $t:ty) => {{
        use filtered_ndf::$prec::{
            AxisAligned, ClampRules, Covariance, GaussianFilteredGgx, Isotropic, RoughnessMatrix,
            batch, filter::presets,
        };
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
        // Small footprints and half vectors near the peak: the filtered lanes' common case.
        let (sx, sy) = (col(10, 0.02), col(11, 0.02));
        let fp = batch::Footprints {
            dh_u_x: &ux,
            dh_u_y: &uy,
            dh_v_x: &vx,
            dh_v_y: &vy,
        };
        let small = batch::Footprints {
            dh_u_x: &sx,
            dh_u_y: &sy,
            dh_v_x: &sy,
            dh_v_y: &sx,
        };
        let v = batch::Vec3s::new(&x, &y, &z);
        let w = batch::Vec3s::new(&y, &x, &z);
        let dn = batch::Vec3s::new(&ux, &uy, &vx);
        let iso = Isotropic::new(0.1 as $t).unwrap();
        let aa = AxisAligned::new(0.1 as $t, 0.02 as $t).unwrap();
        let mat = RoughnessMatrix::new(0.01 as $t, 0.002 as $t, 0.0009 as $t).unwrap();
        let mut out = vec![0.0 as $t; N];
        let (mut o2, mut o3) = (out.clone(), out.clone());
        // One light lobe (Gauss-Laguerre lanes), one heavy (the trapezoid lane, sorted
        // blocks, the scalar fallback for kernels of several lobe variances).
        let exact = [
            GaussianFilteredGgx::new(aa, Covariance::new(1e-5, 0.0, 1e-5)),
            GaussianFilteredGgx::new(iso, Covariance::new(5e-3, 0.0, 5e-3)),
            GaussianFilteredGgx::new(mat, Covariance::new(0.05, 0.01, 0.02)),
        ];
        let kernels = batch::Covariances {
            s11: &ux,
            s12: &uy,
            s22: &vx,
        };
        let mut written = vec![
            batch::ggx_d(&iso, &x, &y, &z, &mut out),
            batch::ggx_d(&aa, &x, &y, &z, &mut out),
            batch::ggx_d(&mat, &x, &y, &z, &mut out),
            batch::beckmann_d(&mat, &x, &y, &z, &mut out),
            batch::ggx_lambda(&mat, &x, &y, &z, &mut out),
            batch::beckmann_lambda(&mat, &x, &y, &z, &mut out),
            batch::ggx_g2(&mat, v, w, v, &mut out),
            batch::beckmann_g2(&mat, v, w, v, &mut out),
        ];
        for rules in [ClampRules::default(), ClampRules::NONE, ClampRules::GDC2016] {
            for f in [fp, small] {
                for h in [v, batch::Vec3s::new(&hx, &hy, &z)] {
                    let (a, b, c) = (h.x, h.y, h.z);
                    written.push(batch::beckmann_d_filtered(
                        &mat, &rules, 0.5, a, b, c, f, &mut out,
                    ));
                    written.push(batch::ggx_d_filtered(
                        &mat, &rules, 0.5, a, b, c, f, &mut out,
                    ));
                    written.push(batch::ggx_d_filtered_projected(
                        &mat, &rules, 0.5, a, b, c, f, &mut out,
                    ));
                    written.push(batch::ggx_d_filtered_exact(
                        &mat, &rules, 0.5, a, b, c, f, &mut out,
                    ));
                    written.push(batch::ggx_d_filtered_exact(
                        &iso, &rules, 0.5, a, b, c, f, &mut out,
                    ));
                    written.push(batch::d_rect_filtered(&aa, &rules, a, b, c, f, &mut out));
                    written.push(batch::ggx_d_filtered_proxy(
                        &aa, &rules, a, b, c, f, &mut out,
                    ));
                }
            }
        }
        written.push(batch::d_rect(&aa, &x, &y, &z, &hx, &hy, &mut out));
        written.push(batch::d_rect(&aa, &hx, &hy, &z, &sx, &sy, &mut out));
        written.push(batch::ggx_d_projected(&mat, kernels, &x, &y, &z, &mut out));
        for lobe in &exact {
            written.push(batch::gaussian_filtered_ggx_d(lobe, &x, &y, &z, &mut out));
            written.push(batch::gaussian_filtered_ggx_d(lobe, &hx, &hy, &z, &mut out));
        }
        for (_, conv) in presets::ALL {
            written.push(batch::deferred_filter(&conv, &z, v, dn, &mut out));
        }
        written.push(batch::ggx_normal_pdf(&mat, &x, &y, &z, &mut out));
        written.push(batch::beckmann_normal_pdf(&mat, &x, &y, &z, &mut out));
        written.push(batch::ggx_visible_normal_pdf(&mat, v, w, &mut out));
        written.push(batch::beckmann_visible_normal_pdf(&mat, v, w, &mut out));
        written.push(batch::ggx_reflection_pdf_from_normal(&mat, v, w, &mut out));
        written.push(batch::beckmann_reflection_pdf_from_normal(
            &mat, v, w, &mut out,
        ));
        written.push(batch::ggx_sample_visible_normal(
            &mat, v, &hx, &hy, &mut out, &mut o2, &mut o3,
        ));
        written.push(batch::beckmann_sample_visible_normal(
            &mat, v, &hx, &hy, &mut out, &mut o2, &mut o3,
        ));
        written.push(batch::ggx_sample_normal(
            &mat, &hx, &hy, &mut out, &mut o2, &mut o3,
        ));
        written.push(batch::beckmann_sample_normal(
            &mat, &hx, &hy, &mut out, &mut o2, &mut o3,
        ));
        assert!(
            written.iter().all(|&n| n == N),
            "{}: {written:?}",
            stringify!($prec)
        );
    }};
}

/// Runs `f` on a thread of [`STACK`] bytes of stack and waits for it.
fn on_small_stack(f: impl FnOnce() + Send + 'static) {
    std::thread::Builder::new()
        .stack_size(STACK)
        .spawn(f)
        .expect("a thread")
        .join()
        .expect("the batch functions returned");
}

#[test]
fn every_batch_function_runs_on_a_2_mib_stack_f32() {
    on_small_stack(|| every_function!(f32, f32));
}

#[test]
fn every_batch_function_runs_on_a_2_mib_stack_f64() {
    on_small_stack(|| every_function!(f64, f64));
}
