//! The BSDF tests' shared parts (`tests/bsdf.rs`, `tests/bsdf_chi2.rs`, included with
//! `#[path = "common/bsdf_cases.rs"] mod bsdf_cases;` next to `mod common;`): every lobe of
//! the front door as a `MicrofacetReflection` behind `dyn Bsdf`, and the test side's own
//! integration over the directions `wi` above the surface.
//!
//! ## Integrating over `wi`
//! A lobe of roughness `1e-2` covers `1e-4` of the hemisphere, so `wi` is parametrised by the
//! half vector `m = normalize(wo + wi)` on the whitened grid of `tests/sampling_chi2.rs`: the
//! slope `s = -m_xy / m_z` is `B w` with `B` the symmetric square root of a roughness matrix
//! of about the lobe's width (the test's own eigen-decomposition, `common::whitening`),
//! `w = sqrt(q) (cos phi, sin phi)`, `r = q / (1 + q)`. With `dwi = 4 (wo.m) dm` (Walter et
//! al. 2007 eq. 14), `dm = m_z^3 ds`, `ds = sqrt(det B^2) dw`, `dw = dq dphi / 2`:
//!
//! `integral g(wi) dwi = integral g(wi(r, phi)) 4 (wo.m) m_z^3 sqrt(det A) (dq/dr) / 2 dr dphi`.
//!
//! **The horizon.** `wi` is above the surface for `r < r*(phi)`: along the ray `s = t d`,
//! `d = B (cos phi, sin phi)`, the sign of `wi_z` is that of
//! `wo_z - 2 t (wo_xy.d) - wo_z |d|^2 t^2` (from `wi = 2 (wo.m) m - wo` with
//! `m ~ (-t d, 1)`), a downward parabola positive at `t = 0`, so `t < t*` with
//! `t* = wo_z / (p + sqrt(p^2 + wo_z^2 |d|^2))`, `p = wo_xy.d`. The inner integral over `r`
//! stops there, so the BSDF's cut at the horizon (a jump of the pdf) is never inside a
//! quadrature panel.
#![allow(dead_code)]

use crate::common::whitening::Whitening;
use filtered_ndf::f64::bsdf::{Bsdf, Fresnel, FresnelOne, MicrofacetReflection};
use filtered_ndf::f64::prelude::*;
use filtered_ndf::testing::quadrature::{Estimate, Tolerance, integrate, integrate_estimates};
use glam::{DVec2, DVec3};
use std::f64::consts::PI;

/// One lobe of the tests: its name, the BSDF (`F = 1`) and the grid's roughness matrix.
pub struct Case {
    pub label: String,
    pub bsdf: Box<dyn Bsdf<Value = f64>>,
    pub grid: RoughnessMatrix,
}

/// The footprint of the filtered lobes: a sheared parallelogram of about `0.04` in slope.
pub fn footprint() -> Footprint {
    Footprint::from_slope_derivatives(DVec2::new(0.05, 0.01), DVec2::new(-0.01, 0.03))
}

/// Every lobe type of the front door at roughness `alpha` (the unfiltered NDFs in the three
/// roughness forms, and each method's lobe over [`footprint`]), with `F = 1`.
pub fn cases(alpha: f64) -> Vec<Case> {
    cases_with(alpha, FresnelOne)
}

/// [`cases`] with the Fresnel term `fresnel`.
pub fn cases_with<Fr>(alpha: f64, fresnel: Fr) -> Vec<Case>
where
    Fr: Fresnel<Value = f64> + Copy + 'static,
{
    macro_rules! case {
        ($label:expr, $lobe:expr, $grid:expr) => {
            Case {
                label: format!("{} {alpha}", $label),
                bsdf: Box::new(MicrofacetReflection::new($lobe, fresnel)),
                grid: $grid,
            }
        };
    }
    let a2 = alpha * alpha;
    let iso = Isotropic::new(alpha).unwrap();
    let axis = AxisAligned::new(alpha, 0.4 * alpha).unwrap();
    let matrix = RoughnessMatrix::new(a2, 0.3 * a2, 0.5 * a2).unwrap();
    let fp = footprint();
    let ggx = Ggx::new(iso);
    let ggx_axis = Ggx::new(axis);
    let beckmann = Beckmann::new(iso);
    // The filtered lobes' grid: A + 2 Sigma of the footprint's kernel (the Gaussian method's
    // own matrix is a valid grid whatever it is: any fixed partition is a valid test).
    let tk19 = ggx.filtered(fp, Gaussian::TK19);
    let wide = tk19.roughness;
    let rect = ggx_axis.filtered(fp, Rect::KHPL16);
    let h = rect.half_extent;
    let (ax, ay) = (alpha, 0.4 * alpha);
    let rect_grid = RoughnessMatrix::new(ax * ax + h.x * h.x, 0.0, ay * ay + h.y * h.y).unwrap();
    vec![
        case!("GGX iso", ggx, iso.to_matrix()),
        case!("GGX axis", ggx_axis, axis.to_matrix()),
        case!("GGX matrix", Ggx::new(matrix), matrix),
        case!("Beckmann iso", beckmann, iso.to_matrix()),
        case!("Beckmann axis", Beckmann::new(axis), axis.to_matrix()),
        case!("Beckmann matrix", Beckmann::new(matrix), matrix),
        case!("GGX Gaussian::TK19", tk19, wide),
        case!(
            "Beckmann Gaussian::KHPL16",
            beckmann.filtered(fp, Gaussian::KHPL16),
            wide
        ),
        case!(
            "GGX ExactGaussian::KHPL16",
            ggx.filtered(fp, ExactGaussian::KHPL16),
            wide
        ),
        case!(
            "GGX Projected::TK21",
            ggx.filtered(fp, Projected::TK21),
            wide
        ),
        case!("GGX Rect::KHPL16", rect, rect_grid),
        case!(
            "GGX Proxy::KHPL16",
            ggx_axis.filtered(fp, Proxy::KHPL16),
            rect_grid
        ),
    ]
}

/// The unit view at `theta_deg` from the normal and azimuth `phi` (radians).
pub fn view(theta_deg: f64, phi: f64) -> DVec3 {
    let t = theta_deg.to_radians();
    DVec3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), t.cos())
}

/// The whitened half-vector grid of one view (module docs).
pub struct Grid {
    wh: Whitening,
    wo: DVec3,
}

impl Grid {
    /// `wo` must be a unit vector above the surface.
    pub fn new(grid: &RoughnessMatrix, wo: DVec3) -> Self {
        assert!((wo.length() - 1.0).abs() < 1e-12 && wo.z > 0.0);
        Self {
            wh: Whitening::new(grid),
            wo,
        }
    }

    /// `(r, phi)` of the direction `wi` (through its half vector).
    pub fn coordinates(&self, wi: DVec3) -> (f64, f64) {
        let m = (self.wo + wi).normalize();
        assert!(m.is_finite() && m.z > 0.0, "half vector {m} of {wi}");
        let s = DVec2::new(-m.x / m.z, -m.y / m.z);
        let w = Whitening::apply(&self.wh.b_inv, s);
        let q = w.length_squared();
        (q / (1.0 + q), w.y.atan2(w.x).rem_euclid(2.0 * PI))
    }

    /// The slope direction `d = B (cos phi, sin phi)`.
    fn direction(&self, phi: f64) -> DVec2 {
        Whitening::apply(&self.wh.b, DVec2::new(phi.cos(), phi.sin()))
    }

    /// `r*(phi)`: `wi` is above the surface for `r < r*` (module docs).
    pub fn horizon(&self, phi: f64) -> f64 {
        let d = self.direction(phi);
        let (z, p) = (self.wo.z, self.wo.x * d.x + self.wo.y * d.y);
        let t = z / (p + (p * p + z * z * d.length_squared()).sqrt());
        let q = t * t;
        q / (1.0 + q)
    }

    /// `wi` at `(r, phi)` and the Jacobian `dwi / (dr dphi)` (module docs).
    pub fn direction_at(&self, r: f64, phi: f64) -> (DVec3, f64) {
        let q = r / (1.0 - r);
        let dq = 1.0 / ((1.0 - r) * (1.0 - r));
        let s = self.direction(phi) * q.sqrt();
        let m = DVec3::new(-s.x, -s.y, 1.0).normalize();
        let wom = self.wo.dot(m);
        let wi = 2.0 * wom * m - self.wo;
        (wi, 4.0 * wom * m.z.powi(3) * self.wh.sqrt_det * dq * 0.5)
    }

    /// `integral g(wi) dwi` over the cell `r in [r0, r1]`, `phi in [p0, p1]`, cut at the
    /// horizon (module docs); nested adaptive Gauss-Kronrod with the error estimate of
    /// `filtered_ndf::testing::quadrature`.
    pub fn integrate(
        &self,
        g: &dyn Fn(DVec3) -> f64,
        (r0, r1): (f64, f64),
        (p0, p1): (f64, f64),
        tol: Tolerance,
    ) -> Estimate {
        let inner = Tolerance {
            abs: 0.1 * tol.abs,
            rel: 0.1 * tol.rel,
            ..tol
        };
        integrate_estimates(
            |phi| {
                let hi = r1.min(self.horizon(phi));
                if hi <= r0 {
                    return (0.0, 0.0);
                }
                let e = integrate(
                    |r| {
                        let (wi, jac) = self.direction_at(r, phi);
                        if wi.z <= 0.0 {
                            return 0.0;
                        }
                        let v = g(wi) * jac;
                        if v.is_finite() { v } else { 0.0 }
                    },
                    r0,
                    hi,
                    inner,
                );
                (e.value, e.error)
            },
            p0,
            p1,
            tol,
        )
    }

    /// `integral g(wi) dwi` over the whole upper hemisphere: the grid's `n x n` panels summed.
    pub fn integrate_hemisphere(
        &self,
        g: &dyn Fn(DVec3) -> f64,
        n: usize,
        tol: Tolerance,
    ) -> Estimate {
        let mut total = Estimate {
            value: 0.0,
            error: 0.0,
        };
        for i in 0..n {
            for j in 0..n {
                let r = (i as f64 / n as f64, (i + 1) as f64 / n as f64);
                let p = (
                    j as f64 / n as f64 * 2.0 * PI,
                    (j + 1) as f64 / n as f64 * 2.0 * PI,
                );
                let e = self.integrate(g, r, p, tol);
                total.value += e.value;
                total.error += e.error;
            }
        }
        total
    }
}
