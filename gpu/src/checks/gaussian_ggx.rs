//! `shaders/filter/gaussian_ggx.wgsl`: the exact Gaussian-filtered GGX in f32 against the
//! crate's `f64` `GaussianFilteredGgx` (itself tested against 2D quadrature of the convolution,
//! `tests/gaussian_ggx.rs`).
//!
//! Cases. (1) The front door: materials from `strategies::axis_aligned`, footprints from
//! `strategies::footprint`, the KHPL16 pixel kernel of `ExactGaussian::KHPL16` (`lambda = 1`,
//! `sigma = 0.5`), half vectors from `strategies::upper_hemisphere(89)`, views from
//! `upper_hemisphere(89.9)`: `d`, `p22`, `lambda`, `g1`, `g2`. (2) The domain of
//! `tests/gaussian_ggx.rs`: rotated materials (alpha `1e-4..1`, anisotropy to 100), kernels
//! `sigma^2 (u u^T + v v^T)` from two vectors with standard deviations `1e-3` to `1e3` lobe
//! widths, anisotropy to 100, one in eight rank one; slopes `rho L u` (`L L^T = A + 2 Sigma`)
//! with `rho` to 50: `p22`, `d` of the slope's normal, `lambda`.
//!
//! Tolerances (ulp; `gaussian_ggx.wgsl`'s stated bound, per case): the rules' own error and
//! the f32 node arithmetic, `R = 30` (`1.8e-6` of the rules, 15 more for the exponents, the
//! sums and the polynomial `exp`), plus the set-up's rounding amplified by the density's
//! condition numbers, computed here from the `f64` reference by central differences:
//! `kappa_s = |d ln P22(lambda s) / d ln lambda| = 2 <E>` (the whitened slope's `c_i^2` carry
//! `err_c = 12 + 8 sqrt(cond A_c)` ulp: the rotation into `A_c`'s eigenbasis as `matrix.wgsl`,
//! the scaling by `1 / sqrt(l)`, the kernel's eigenvector), the kernel's eigenvalues `2 l_i`
//! `err_l = 16` ulp, whose effect is at most `<E> + 1/2` each, and the kernel's orientation
//! (its entries from the footprint vectors, `s_xy` absolute `2 eps sqrt(s_xx s_yy)`; the
//! eigenvector of `B^-1 Sigma B^-T`): `kappa_theta = |d ln P22 / d theta|` for the kernel
//! rotated by `theta`, times `err_theta = 16` ulp. Together
//! `R + (kappa_s / 2) err_c + (kappa_s + 1) err_l + kappa_theta err_theta`.
//! `Lambda`: `R = 30` (the rules `3e-7`, the nodes' `exp` and grid), plus its condition
//! numbers with respect to the lobe (`o^T A o`, `err_q` as the matrix form), the kernel
//! (`o^T Sigma o`, formed in f32 with cancellation factor
//! `(|s_xx| o_x^2 + 2 |s_xy o_x o_y| + |s_yy| o_y^2) / o^T Sigma o`, times 4 ulp), and `|w_z|`
//! (4 ulp from the normalisation). `g1`, `g2`: `Lambda`'s relative error times
//! `Lambda / (1 + Lambda)`, plus 4 ulp.

use super::rect::log_sensitivity;
use super::{Check, EPS, Tol, draw};
use crate::reference::{
    AxisAligned, ClampRules, Covariance, DVec2, DVec3, Footprint, GaussianFilteredGgx, Ndf,
    NdfSampling, Roughness, RoughnessMatrix, SplitMix64, matrix_from_eigen, strategies, v2, v3,
};

/// The rules' own error and the f32 arithmetic (module docs), in ulp.
const R: f64 = 30.0;

/// The kernel rotated by `theta`: `R_theta Sigma R_theta^T`.
fn rotated(k: &Covariance, theta: f64) -> Covariance {
    let (c, s) = (theta.cos(), theta.sin());
    let (a, b, d) = (k.s11, k.s12, k.s22);
    Covariance::new(
        c * c * a - 2.0 * c * s * b + s * s * d,
        c * s * (a - d) + (c * c - s * s) * b,
        s * s * a + 2.0 * c * s * b + c * c * d,
    )
}

/// `|d ln F(theta) / d theta|` at 0 by central differences (step `1e-5`).
fn angle_sensitivity(f: impl Fn(f64) -> f64) -> f64 {
    let h = 1e-5;
    let s = (f(h).ln() - f(-h).ln()) / (2.0 * h);
    if s.is_finite() { s.abs() } else { 0.0 }
}

/// The density tolerance (module docs) at slope `s`, in ulp.
pub fn density_ulps(a: &RoughnessMatrix, k: &Covariance, s: DVec2) -> f64 {
    let p = |a: &RoughnessMatrix, k: &Covariance, s: DVec2| GaussianFilteredGgx::new(*a, *k).p22(s);
    let kappa_s = log_sensitivity(1.0, |l| p(a, k, s * l));
    let kappa_t = angle_sensitivity(|t| p(a, &rotated(k, t), s));
    let err_c = 12.0 + 8.0 * super::ndf::clamped_cond(a).sqrt();
    R + 0.5 * kappa_s * err_c + (kappa_s + 1.0) * 16.0 + kappa_t * 16.0
}

/// The `Lambda` tolerance (module docs) at `w`, in ulp.
pub fn lambda_ulps(a: &RoughnessMatrix, k: &Covariance, w: DVec3) -> f64 {
    let l =
        |a: &RoughnessMatrix, k: &Covariance, w: DVec3| GaussianFilteredGgx::new(*a, *k).lambda(w);
    let (a11, a12, a22) = a.entries();
    let scaled_a = |f: f64| {
        RoughnessMatrix::new_with_det_clamp(a11 * f, a12 * f, a22 * f, a.clamped_det() * f * f)
            .map(|m| l(&m, k, w))
            .unwrap_or(f64::NAN)
    };
    let kappa_a = log_sensitivity(1.0, scaled_a);
    let kappa_k = log_sensitivity(1.0, |f| l(a, &(*k * f), w));
    let kappa_z = log_sensitivity(w.z, |z| l(a, k, DVec3::new(w.x, w.y, z)));
    let n = w.length();
    let (ox, oy) = (w.x / n, w.y / n);
    let qs = k.s11 * ox * ox + 2.0 * k.s12 * ox * oy + k.s22 * oy * oy;
    let mag = k.s11.abs() * ox * ox + 2.0 * (k.s12 * ox * oy).abs() + k.s22.abs() * oy * oy;
    let cancel = if qs > 0.0 { mag / qs } else { 1.0 };
    let err_q = 8.0 + 8.0 * super::ndf::clamped_cond(a).sqrt();
    R + kappa_a * err_q + kappa_k * 4.0 * cancel.min(1e12) + kappa_z * 4.0
}

/// `g1 = 1 / (1 + Lambda)`: `Lambda`'s error times `Lambda / (1 + Lambda)` plus 4 ulp.
fn g_ulps(lambda: f64, lambda_ulps: f64) -> f64 {
    let f = if lambda.is_finite() {
        lambda / (1.0 + lambda)
    } else {
        1.0
    };
    lambda_ulps * f + 4.0
}

const IMPORTS: &str = "#import filtered_ndf::ndf::roughness::axis_aligned
#import filtered_ndf::ndf::roughness::matrix
#import filtered_ndf::footprint
#import filtered_ndf::kernel::covariance
#import filtered_ndf::kernel::clamp
#import filtered_ndf::filter::gaussian_ggx
#import filtered_ndf::sampling::gaussian_ggx as gaussian_ggx_sampling";

/// The front-door cases: `ExactGaussian::KHPL16` of an axis-aligned material.
fn front_door(n: usize) -> Check {
    let body = "let r = axis_aligned::from_alpha(x2(0u));
let fp = footprint::from_slope_derivatives(x2(5u), x2(7u));
let g = gaussian_ggx::from_kernel(axis_aligned::to_matrix(r), clamp::pixel_kernel(clamp::KHPL16_RULES, fp, 0.5));
let h = x3(2u);
let w = x3(9u);
let o = x3(12u);
y(0u, gaussian_ggx::d(g, h));
y(1u, gaussian_ggx::p22(g, x2(15u)));
y(2u, gaussian_ggx::lambda(g, w));
y(3u, gaussian_ggx::g1(g, w, h));
y(4u, gaussian_ggx::g2(g, w, o, h));";
    let mut c = Check::new(
        "gaussian_ggx::{d, p22, lambda, g1, g2} (ExactGaussian::KHPL16 of the trade table's points)",
        IMPORTS,
        body,
        17,
        5,
    )
    .tolerance("D, P22: R + (kappa_s / 2) err_c + (kappa_s + 1) 16 + kappa_theta 16 ulp; Lambda: R + kappa_A err_q + kappa_Sigma 4 cancel + kappa_z 4; g1, g2 from Lambda's (checks/gaussian_ggx.rs)");
    let a = draw(strategies::axis_aligned(), n, "exact alpha");
    let hs = draw(strategies::upper_hemisphere(89.0), n, "exact h");
    let ws = draw(strategies::upper_hemisphere(89.9), 2 * n, "exact w");
    let fps = draw(strategies::footprint(), n, "exact fp");
    let rules = ClampRules::KHPL16;
    for k in 0..n {
        let alpha = [a[k].alpha().x as f32, a[k].alpha().y as f32];
        let r = AxisAligned::new(alpha[0].into(), alpha[1].into()).expect("in range");
        let am = r.to_matrix();
        let h = [hs[k].x as f32, hs[k].y as f32, hs[k].z as f32];
        let w = [ws[2 * k].x as f32, ws[2 * k].y as f32, ws[2 * k].z as f32];
        let o = [
            ws[2 * k + 1].x as f32,
            ws[2 * k + 1].y as f32,
            ws[2 * k + 1].z as f32,
        ];
        let du = [fps[k].dh_u.x as f32, fps[k].dh_u.y as f32];
        let dv = [fps[k].dh_v.x as f32, fps[k].dh_v.y as f32];
        let fp = Footprint::from_slope_derivatives(v2(du), v2(dv));
        let kernel = rules.kernel(rules.footprint(fp).covariance(0.5));
        let lobe = GaussianFilteredGgx::new(am, kernel);
        let (hd, wd, od) = (v3(h), v3(w), v3(o));
        let s = [(-hd.x / hd.z) as f32, (-hd.y / hd.z) as f32];
        let sd = v2(s);
        let mut input = alpha.to_vec();
        input.extend(h);
        input.extend(du);
        input.extend(dv);
        input.extend(w);
        input.extend(o);
        input.extend(s);
        let lam = lobe.lambda(wd);
        let lt = lambda_ulps(&am, &kernel, wd);
        let lo = lambda_ulps(&am, &kernel, od);
        let expect = vec![
            lobe.d(hd),
            lobe.p22(sd),
            lam,
            lobe.g1(wd, hd),
            lobe.g2(wd, od, hd),
        ];
        let sh = DVec2::new(-hd.x / hd.z, -hd.y / hd.z);
        let tol = vec![
            Tol::ulps(density_ulps(&am, &kernel, sh)),
            Tol::ulps(density_ulps(&am, &kernel, sd)),
            Tol::ulps(lt),
            Tol::ulps(g_ulps(lam, lt)),
            Tol::ulps(g_ulps(lam + lobe.lambda(od), lt.max(lo))),
        ];
        c.case(input, expect, tol);
    }
    c
}

/// One case of the `tests/gaussian_ggx.rs` domain, as the shaders receive it: a lobe of
/// roughness `alpha` in 1e-4..1, anisotropy to 100:1, rotated by `axis`, and the kernel
/// `sigma^2 (u u^T + v v^T)` (`sigma = 1`) of standard deviations `kw` = 1e-3..1e3 lobe widths,
/// rank one for every eighth case.
struct DomainCase {
    axis: [f32; 2],
    al: [f32; 2],
    am: RoughnessMatrix,
    u: [f32; 2],
    v: [f32; 2],
    kernel: Covariance,
    lobe: GaussianFilteredGgx,
}

/// The next [`DomainCase`] (`None` where the eigen form does not give a valid matrix).
fn domain_case(rng: &mut SplitMix64, made: usize) -> Option<DomainCase> {
    let alpha = 10f64.powf(rng.range(-4.0, 0.0));
    let aniso = 10f64.powf(rng.range(0.0, 2.0));
    let phi = rng.range(0.0, core::f64::consts::PI);
    let axis = [phi.cos() as f32, phi.sin() as f32];
    let al = [alpha as f32, (alpha / aniso) as f32];
    let am = matrix_from_eigen(axis, al)?;
    let kw = 10f64.powf(rng.range(-3.0, 3.0)) * alpha;
    let th = rng.range(0.0, core::f64::consts::PI);
    let ratio = match made % 8 {
        0 => 0.0,
        _ => 10f64.powf(rng.range(-2.0, 0.0)),
    };
    let u = [(kw * th.cos()) as f32, (kw * th.sin()) as f32];
    let v = [
        (-kw * ratio * th.sin()) as f32,
        (kw * ratio * th.cos()) as f32,
    ];
    let kernel = Footprint::from_slope_derivatives(v2(u), v2(v)).covariance(1.0);
    let lobe = GaussianFilteredGgx::new(am, kernel);
    Some(DomainCase {
        axis,
        al,
        am,
        u,
        v,
        kernel,
        lobe,
    })
}

/// The cases of `tests/gaussian_ggx.rs`'s domain (module docs): rotated materials, kernels from
/// two vectors.
fn domain(n: usize) -> Check {
    let body = "let a = matrix::from_eigen(x2(0u), x2(2u));
let k = covariance::from_footprint(footprint::from_slope_derivatives(x2(4u), x2(6u)), 1.0);
let g = gaussian_ggx::from_kernel(a, k);
y(0u, gaussian_ggx::p22(g, x2(8u)));
y(1u, gaussian_ggx::d(g, x3(10u)));
y(2u, gaussian_ggx::lambda(g, x3(13u)));";
    let mut c = Check::new(
        "gaussian_ggx::{p22, d, lambda} (tests/gaussian_ggx.rs domain: rotated lobes, kernels 1e-3..1e3 widths)",
        IMPORTS,
        body,
        16,
        3,
    )
    .tolerance("as the front door (checks/gaussian_ggx.rs)");
    let mut rng = SplitMix64(0x6578_6163);
    let mut made = 0;
    while made < n {
        let Some(DomainCase {
            axis,
            al,
            am,
            u,
            v,
            kernel,
            lobe,
        }) = domain_case(&mut rng, made)
        else {
            continue;
        };
        // s = rho L e with L the Cholesky factor of A + 2 Sigma.
        let (a11, a12, a22) = am.entries();
        let (f11, f12, f22) = (
            a11 + 2.0 * kernel.s11,
            a12 + 2.0 * kernel.s12,
            a22 + 2.0 * kernel.s22,
        );
        let l11 = f11.sqrt();
        let l21 = f12 / l11;
        let l22 = (f22 - l21 * l21).max(0.0).sqrt();
        let rho = if made % 2 == 0 {
            rng.range(0.0, 50.0)
        } else {
            10f64.powf(rng.range(-3.0, 1.7))
        };
        let t = rng.range(0.0, core::f64::consts::TAU);
        let (ex, ey) = (t.cos(), t.sin());
        let s = [
            (rho * l11 * ex) as f32,
            (rho * (l21 * ex + l22 * ey)) as f32,
        ];
        let sd = v2(s);
        let m = DVec3::new(-sd.x, -sd.y, 1.0).normalize();
        let m32 = [m.x as f32, m.y as f32, m.z as f32];
        let md = v3(m32);
        let wt = rng.range(0.0, 0.9999 * core::f64::consts::FRAC_PI_2);
        let wp = rng.range(0.0, core::f64::consts::TAU);
        let w32 = [
            (wt.sin() * wp.cos()) as f32,
            (wt.sin() * wp.sin()) as f32,
            wt.cos() as f32,
        ];
        let wd = v3(w32);
        let p = lobe.p22(sd);
        let d = lobe.d(md);
        if !(p > 1e-30 && d > 1e-30) {
            continue;
        }
        let mut input = axis.to_vec();
        input.extend(al);
        input.extend(u);
        input.extend(v);
        input.extend(s);
        input.extend(m32);
        input.extend(w32);
        let ms = DVec2::new(-md.x / md.z, -md.y / md.z);
        c.case(
            input,
            vec![p, d, lobe.lambda(wd)],
            vec![
                Tol::ulps(density_ulps(&am, &kernel, sd)),
                Tol::ulps(density_ulps(&am, &kernel, ms)),
                Tol::ulps(lambda_ulps(&am, &kernel, wd)),
            ],
        );
        made += 1;
    }
    c
}

/// The shader's split of one uniform number into two (12 bits each, the Rust `f32` build's
/// `split`), in f64 (exact).
fn split12(u: f32) -> (f64, f64) {
    let x = f64::from(u) * 4096.0;
    let hi = x.floor();
    ((hi + 0.5) / 4096.0, x - hi)
}

/// `sample_normal` and `normal_pdf` of the filtered lobe, on the domain of [`domain`]
/// (rotated materials, kernels from two footprint vectors, one in eight rank one).
///
/// Reference: the crate's `f64` sampler splits the bits of an `f64` `u` (26 bits each), the
/// shader those of an `f32` (12 bits each, as the Rust `f32` build): the reference sample is the
/// `f64` composition of the same steps at the shader's four numbers (`split12`): the GGX slope
/// `B t` (`B` the Cholesky factor of `A_c` from `clamped_entries`, `sqrt_det`), plus the kernel
/// slope along the sanitised kernel's principal axes (`Covariance::eigenvalues`, the
/// eigenvector from the row without cancellation), as `gaussian_ggx.rs` writes them.
///
/// Tolerance (absolute, per component): the slope error `|ds|` moves the unit normal by at most
/// `|ds| / sqrt(1 + |s|^2)`, plus `8 EPS` for its normalisation. `|ds|`: `12 EPS r sum |B_ij|`
/// (the GGX radius `r` 5 ulp, `sincos_turns` 3, the warp's entries a few), `17 EPS r_k
/// (sd_1 + sd_2)` (the Box-Muller radius `r_k` 6 ulp, `sincos_turns` 3, the standard
/// deviations 8: the kernel's entries and carried determinant), `|k| delta_theta` for the
/// principal axis (`delta_theta = min(8 EPS l_max / (l_max - l_min), 2)`: the eigenvector of a
/// nearly isotropic kernel is as ill-conditioned as its gap makes it, and rotating the kernel
/// sample moves it by `|k| delta_theta`), and `EPS |s|` for the sum. `normal_pdf`: `d`'s bound
/// (`density_ulps` at the slope of `m`) plus 2 ulp.
fn sampling(n: usize) -> Check {
    let body = "let a = matrix::from_eigen(x2(0u), x2(2u));
let k = covariance::from_footprint(footprint::from_slope_derivatives(x2(4u), x2(6u)), 1.0);
let g = gaussian_ggx::from_kernel(a, k);
y3(0u, gaussian_ggx_sampling::sample_normal(g, x2(8u)));
y(3u, gaussian_ggx_sampling::normal_pdf(g, x3(10u)));";
    let mut c = Check::new(
        "sampling::gaussian_ggx::{sample_normal, normal_pdf} (tests/gaussian_ggx.rs domain)",
        IMPORTS,
        body,
        13,
        4,
    )
    .tolerance("sample: |ds| / sqrt(1 + |s|^2) + 8 EPS absolute, |ds| from the GGX radius, the Box-Muller radius, the kernel's axis (its gap) and the sum (module docs); normal_pdf: density_ulps + 2");
    let mut rng = SplitMix64(0x7361_6d67);
    let mut made = 0;
    while made < n {
        let Some(DomainCase {
            axis,
            al,
            am,
            u,
            v,
            kernel,
            lobe,
        }) = domain_case(&mut rng, made)
        else {
            continue;
        };
        let us: [f32; 2] = match made % 50 {
            0 => [0.0, 0.0],
            1 => [0.99999994, 0.99999994],
            _ => [rng.uniform() as f32, rng.uniform() as f32],
        };
        // The reference sample (docs above).
        let (u1, u3) = split12(us[0]);
        let (u2, u4) = split12(us[1]);
        let tau = core::f64::consts::TAU;
        let r = (u1 / (1.0 - u1)).sqrt();
        let (tx, ty) = (r * (tau * u2).cos(), r * (tau * u2).sin());
        let (a11, a12, _) = am.clamped_entries();
        let b11 = a11.sqrt();
        let (b21, b22) = (a12 / b11, am.sqrt_det() / b11);
        let g = DVec2::new(b11 * tx, b21 * tx + b22 * ty);
        let ks = kernel.sanitized();
        let (lmin, lmax) = ks.eigenvalues();
        let khalf = 0.5 * (ks.s11 - ks.s22);
        let krad = khalf.hypot(ks.s12);
        let (kx, ky) = if krad > 0.0 {
            let (vx, vy) = if khalf >= 0.0 {
                (krad + khalf, ks.s12)
            } else {
                (ks.s12, krad - khalf)
            };
            let nv = vx.hypot(vy);
            (vx / nv, vy / nv)
        } else {
            (1.0, 0.0)
        };
        let rk = (-2.0 * (1.0 - u3).ln()).sqrt();
        let (sd1, sd2) = (lmax.max(0.0).sqrt(), lmin.max(0.0).sqrt());
        let (k1, k2) = (sd1 * rk * (tau * u4).cos(), sd2 * rk * (tau * u4).sin());
        let k = DVec2::new(kx * k1 - ky * k2, ky * k1 + kx * k2);
        let s = g + k;
        let m = DVec3::new(-s.x, -s.y, 1.0).normalize();
        let gap = lmax - lmin;
        let dtheta = if gap > 0.0 {
            (8.0 * EPS * lmax / gap).min(2.0)
        } else if lmax > 0.0 {
            2.0
        } else {
            0.0
        };
        let ds = 12.0 * EPS * r * (b11 + b21.abs() + b22)
            + 17.0 * EPS * rk * (sd1 + sd2)
            + k.length() * dtheta
            + EPS * s.length();
        let t = ds / (1.0 + s.length_squared()).sqrt() + 8.0 * EPS;
        let m32 = [m.x as f32, m.y as f32, m.z as f32];
        let md = v3(m32);
        let pdf = lobe.normal_pdf(md);
        if !(pdf > 1e-30 && md.z > 0.0) {
            continue;
        }
        let ms = DVec2::new(-md.x / md.z, -md.y / md.z);
        let mut input = axis.to_vec();
        input.extend(al);
        input.extend(u);
        input.extend(v);
        input.extend(us);
        input.extend(m32);
        c.case(
            input,
            vec![m.x, m.y, m.z, pdf],
            vec![
                Tol::abs(t),
                Tol::abs(t),
                Tol::abs(t),
                Tol::ulps(density_ulps(&am, &kernel, ms) + 2.0),
            ],
        );
        made += 1;
    }
    c
}

/// The checks of `shaders/filter/gaussian_ggx.wgsl`.
pub fn all() -> Vec<Check> {
    let mut all = vec![front_door(2000), domain(2000)];
    all.extend(settings(2000));
    all.push(sampling(1000));
    all
}

/// The far-tail switches `K` of the reduced settings (`Tolerance::Rel1e4`, `Rel1e3`,
/// `Rel1e2`), read from the Rust rules.
fn far_switches() -> [f64; 3] {
    filtered_ndf::testing::tolerance_rules::reduced_rules().map(|r| r.far)
}

/// The reduced accuracy settings (`gaussian_ggx::TOL_1E4`, `TOL_1E3`, `TOL_1E2`, the Rust
/// `Tolerance`), one check per setting: `p22` and `d` against the `f64` lobe at the full setting
/// (within `1.1e-11` of the convolution, `tests/gaussian_ggx.rs`), on two sets of cases:
/// the cases of [`domain`], and cases on both sides of each setting's far-tail switch
/// `2 l1 (K + 12 ln(1 + q)) <= 1 + q` (the only switch of a reduced setting: the far-tail series
/// on one side, the trapezoid rule on the other): isotropic materials (`alpha` `0.3`, `0.01`),
/// kernels `kw^2 (e1 e1^T + r^2 e2^T e2)` (`r` `1`, `0.1`), `1 + q` from `1` (the peak) to
/// `1e5`, and `2 l1` at `1 -+ 1e-3` and `1 -+ 0.2` times the switch's value for `K` of each
/// setting (the side asserted from the `f64` lobe's `l1` and `q`).
///
/// Tolerance: the setting's proven bound (`1e-4`, `1e-3`, `1e-2` relative, Rust module docs
/// "Tolerance settings"; it includes the `f32` node exponent's `1.6e-5`) plus the full
/// setting's `f32` tolerance of the same case ([`density_ulps`]: the set-up's rounding
/// amplified by the condition numbers, and `R = 30` ulp of rules and arithmetic, of which the
/// full rule's own `1.8e-6` is not in a reduced rule's error: it over-counts by 15 ulp). The
/// shader's set-up is the same at every setting, and its rounding enters a reduced rule as it
/// enters the full one.
fn settings(n: usize) -> Vec<Check> {
    // The cases: inputs, the f64 full-setting p22 and d, and their full-setting f32 ulps.
    let mut cases: Vec<(Vec<f32>, [f64; 2], [f64; 2])> = Vec::new();
    // One case: the material, the footprint vectors and the slope; `None` where the
    // reference underflows.
    let add = |cases: &mut Vec<(Vec<f32>, [f64; 2], [f64; 2])>,
               axis: [f32; 2],
               al: [f32; 2],
               u: [f32; 2],
               v: [f32; 2],
               s: [f32; 2]|
     -> Option<()> {
        let am = matrix_from_eigen(axis, al)?;
        let kernel = Footprint::from_slope_derivatives(v2(u), v2(v)).covariance(1.0);
        let lobe = GaussianFilteredGgx::new(am, kernel);
        let sd = v2(s);
        let m = DVec3::new(-sd.x, -sd.y, 1.0).normalize();
        let m32 = [m.x as f32, m.y as f32, m.z as f32];
        let md = v3(m32);
        let (p, d) = (lobe.p22(sd), lobe.d(md));
        if !(p > 1e-30 && d > 1e-30) {
            return None;
        }
        let mut input = axis.to_vec();
        input.extend(al);
        input.extend(u);
        input.extend(v);
        input.extend(s);
        input.extend(m32);
        let ms = DVec2::new(-md.x / md.z, -md.y / md.z);
        let ulps = [
            density_ulps(&am, &kernel, sd),
            density_ulps(&am, &kernel, ms),
        ];
        cases.push((input, [p, d], ulps));
        Some(())
    };
    let mut rng = SplitMix64(0x701E_0053);
    let mut made = 0;
    while made < n {
        let Some(DomainCase {
            axis,
            al,
            am,
            u,
            v,
            kernel,
            ..
        }) = domain_case(&mut rng, made)
        else {
            continue;
        };
        let (a11, a12, a22) = am.entries();
        let (f11, f12, f22) = (
            a11 + 2.0 * kernel.s11,
            a12 + 2.0 * kernel.s12,
            a22 + 2.0 * kernel.s22,
        );
        let l11 = f11.sqrt();
        let l21 = f12 / l11;
        let l22 = (f22 - l21 * l21).max(0.0).sqrt();
        let rho = if made % 2 == 0 {
            rng.range(0.0, 50.0)
        } else {
            10f64.powf(rng.range(-3.0, 1.7))
        };
        let t = rng.range(0.0, core::f64::consts::TAU);
        let (ex, ey) = (t.cos(), t.sin());
        let s = [
            (rho * l11 * ex) as f32,
            (rho * (l21 * ex + l22 * ey)) as f32,
        ];
        if add(&mut cases, axis, al, u, v, s).is_some() {
            made += 1;
        }
    }
    // Both sides of each setting's far-tail switch.
    let mut sides = [0usize; 2];
    for far in far_switches() {
        for alpha in [0.3f64, 0.01] {
            for r in [1.0f64, 0.1] {
                for beta in [1.0f64, 2.0, 30.0, 1e3, 1e5] {
                    for delta in [-0.2, -1e-3, 1e-3, 0.2] {
                        // 2 l1 = 2 kw^2 / alpha^2 at (1 + delta) times the switch's value.
                        let tl1 = beta / (far + 12.0 * beta.ln()) * (1.0 + delta);
                        let kw = alpha * (0.5 * tl1).sqrt();
                        let phi = rng.range(0.0, core::f64::consts::TAU);
                        let sl = alpha * (beta - 1.0).sqrt();
                        let s = [(sl * phi.cos()) as f32, (sl * phi.sin()) as f32];
                        let (u, v) = ([kw as f32, 0.0], [0.0, (r * kw) as f32]);
                        let (axis, al) = ([1.0f32, 0.0], [alpha as f32, alpha as f32]);
                        // The side, from the f64 lobe of the f32 inputs.
                        let am = matrix_from_eigen(axis, al).expect("an isotropic material");
                        let kernel =
                            Footprint::from_slope_derivatives(v2(u), v2(v)).covariance(1.0);
                        let (l1, _) = GaussianFilteredGgx::new(am, kernel).kernel_ratio();
                        let b = 1.0 + v2(s).length_squared() / (alpha as f32 as f64).powi(2);
                        let switch = 2.0 * l1 * (far + 12.0 * b.ln()) / b;
                        let far_side = switch <= 1.0;
                        assert!(
                            (switch - 1.0).abs() >= 0.5 * delta.abs() && far_side == (delta < 0.0),
                            "switch case K = {far}, 1 + q = {beta}, delta = {delta}: {switch}"
                        );
                        if add(&mut cases, axis, al, u, v, s).is_some() {
                            sides[usize::from(far_side)] += 1;
                        }
                    }
                }
            }
        }
    }
    assert!(
        sides[0] >= 100 && sides[1] >= 100,
        "switch cases per side: {sides:?}"
    );
    [("TOL_1E4", 1e-4), ("TOL_1E3", 1e-3), ("TOL_1E2", 1e-2)]
        .into_iter()
        .map(|(setting, bound)| {
            let body = format!(
                "let a = matrix::from_eigen(x2(0u), x2(2u));
let k = covariance::from_footprint(footprint::from_slope_derivatives(x2(4u), x2(6u)), 1.0);
let g = gaussian_ggx::with_tolerance(gaussian_ggx::from_kernel(a, k), gaussian_ggx::{setting});
y(0u, gaussian_ggx::p22(g, x2(8u)));
y(1u, gaussian_ggx::d(g, x3(10u)));"
            );
            let mut c = Check::new(
                &format!(
                    "gaussian_ggx::{{p22, d}} at {setting} (tests/gaussian_ggx.rs domain; both sides of each far-tail switch)"
                ),
                IMPORTS,
                &body,
                13,
                2,
            )
            .tolerance(&format!(
                "the setting's proven bound {bound:e} / EPS + the full setting's f32 density ulps (checks/gaussian_ggx.rs)"
            ));
            for (input, expect, ulps) in &cases {
                c.case(
                    input.clone(),
                    expect.to_vec(),
                    vec![
                        Tol::ulps(ulps[0] + bound / EPS),
                        Tol::ulps(ulps[1] + bound / EPS),
                    ],
                );
            }
            c
        })
        .collect()
}
