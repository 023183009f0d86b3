//! The normalised rectangle of the box filter (`filter::rect`, module docs) in `f64`, from the
//! inputs as the batch precision rounded them: the ratios `H / L` of its axes (which tell the
//! elements that the documented case analysis integrates by Gauss-Legendre rules, both ratios
//! below `0.25` in both precisions, from those with a long side), and the magnitude of the
//! four-edge closed form's terms (module docs, case 3), by libm's `atan2`: the scale against
//! which the form cancels. Shared by `tests/batch.rs` and `tests/batch_bounds.rs`.
#![allow(dead_code)]

/// The rectangle `[uc +/- hu] x [vc +/- hv]` in units of the roughness, with the factor
/// `k = 1 / (pi a b)` and the Jacobian `1 / h_z^4` of `d_rect`.
pub struct UnitRect {
    pub uc: f64,
    pub vc: f64,
    pub hu: f64,
    pub hv: f64,
    pub k: f64,
    pub ihz4: f64,
}

/// Largest normalised coordinate (`filter::rect::BIG`, module docs "Inputs outside the
/// domain").
const BIG: f64 = 1e60;

/// The unit rectangle of `d_rect(alpha, h, half)` as the module docs define it; `None` where
/// `d_rect` answers before the integral (non-finite `h`, `h_z <= 0`, `h_z < 1e-70`, a zero
/// footprint, a NaN centre).
pub fn unit_rect(alpha: (f64, f64), h: [f64; 3], half: (f64, f64)) -> Option<UnitRect> {
    if !h.iter().all(|v| v.is_finite()) || h[2] <= 0.0 || h[2] < 1e-70 {
        return None;
    }
    if half.0 == 0.0 && half.1 == 0.0 {
        return None;
    }
    let san = |v: f64, a: f64| {
        let v = (v / a).abs();
        if v.is_nan() { 0.0 } else { v.min(BIG) }
    };
    let (uc, vc) = (-h[0] / h[2] / alpha.0, -h[1] / h[2] / alpha.1);
    if uc.is_nan() || vc.is_nan() {
        return None;
    }
    Some(UnitRect {
        uc: uc.clamp(-BIG, BIG),
        vc: vc.clamp(-BIG, BIG),
        hu: san(half.0, alpha.0),
        hv: san(half.1, alpha.1),
        k: 1.0 / (std::f64::consts::PI * alpha.0 * alpha.1),
        ihz4: h[2].powi(-4),
    })
}

impl UnitRect {
    /// `H / L` per axis: `L_u^2 = 1 + u_c^2 + d_v^2`, `L_v^2 = 1 + v_c^2 + d_u^2`, `d` the
    /// distance of the rectangle from the peak along the other axis (module docs).
    pub fn ratios(&self) -> (f64, f64) {
        let du = (self.uc.abs() - self.hu).max(0.0);
        let dv = (self.vc.abs() - self.hv).max(0.0);
        let lu = (1.0 + self.uc * self.uc + dv * dv).sqrt();
        let lv = (1.0 + self.vc * self.vc + du * du).sqrt();
        (self.hu / lu, self.hv / lv)
    }

    /// Both axes in a Gauss-Legendre tier (ratios below `0.25`, with a margin of `1e-9` for
    /// the rounding of the ratios here and in the crate).
    pub fn short(&self) -> bool {
        let (a, b) = self.ratios();
        a < 0.25 * (1.0 - 1e-9) && b < 0.25 * (1.0 - 1e-9)
    }

    /// A long side (a ratio at least `0.25`, same margin): the closed forms.
    pub fn long(&self) -> bool {
        let (a, b) = self.ratios();
        a >= 0.25 * (1.0 + 1e-9) || b >= 0.25 * (1.0 + 1e-9)
    }

    /// `M = k / h_z^4 0.5 sum |e| / (4 H_u H_v)`, the four edge terms
    /// `e = u / S atan2(dv S, S^2 + v0 v1)` (`S = sqrt(1 + u^2)`) in absolute value, scaled as
    /// the form scales their sum into `d_rect`.
    pub fn edge_magnitude(&self) -> f64 {
        let (u0, u1) = (self.uc - self.hu, self.uc + self.hu);
        let (v0, v1) = (self.vc - self.hv, self.vc + self.hv);
        let e = |u: f64, d: f64, w01: f64| {
            let s = (1.0 + u * u).sqrt();
            (u / s * (d * s).atan2(s * s + w01)).abs()
        };
        let (du, dv) = (2.0 * self.hu, 2.0 * self.hv);
        let sum = e(u1, dv, v0 * v1) + e(u0, dv, v0 * v1) + e(v1, du, u0 * u1) + e(v0, du, u0 * u1);
        self.k * self.ihz4 * 0.5 * sum / (du * dv)
    }
}
