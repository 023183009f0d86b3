//! Shared machinery of the extremes sweep (`tests/extremes_*.rs`): double-double arithmetic for
//! references that must survive cancellation, the error map that the sweep prints, and a
//! piecewise quadrature for narrow lobes inside wide intervals.
//!
//! Nothing here calls the code under test.
#![allow(dead_code)]

use filtered_ndf::testing::quadrature::{Estimate, Tolerance, integrate_estimates};
use std::collections::BTreeMap;

/// A double-double number `hi + lo` (about 106 bits), for references whose `f64` evaluation
/// would cancel (determinants and quadratic forms of near-singular matrices).
#[derive(Clone, Copy, Debug)]
pub struct Dd(pub f64, pub f64);

fn two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    let bb = s - a;
    Dd(s, (a - (s - bb)) + (b - bb))
}

fn fast_two_sum(a: f64, b: f64) -> Dd {
    let s = a + b;
    Dd(s, b - (s - a))
}

impl Dd {
    pub fn from(x: f64) -> Self {
        Dd(x, 0.0)
    }
    pub fn prod(a: f64, b: f64) -> Self {
        let p = a * b;
        Dd(p, a.mul_add(b, -p))
    }
    pub fn add(self, o: Dd) -> Dd {
        let s = two_sum(self.0, o.0);
        let t = two_sum(self.1, o.1);
        let r = fast_two_sum(s.0, s.1 + t.0);
        fast_two_sum(r.0, r.1 + t.1)
    }
    pub fn sub(self, o: Dd) -> Dd {
        self.add(Dd(-o.0, -o.1))
    }
    pub fn mul(self, o: Dd) -> Dd {
        let p = Dd::prod(self.0, o.0);
        fast_two_sum(p.0, p.1 + (self.0 * o.1 + self.1 * o.0))
    }
    pub fn div(self, o: Dd) -> Dd {
        let q1 = self.0 / o.0;
        let r = self.sub(o.mul(Dd::from(q1)));
        let q2 = r.0 / o.0;
        let r = r.sub(o.mul(Dd::from(q2)));
        let q3 = r.0 / o.0;
        let q = fast_two_sum(q1, q2);
        q.add(Dd::from(q3))
    }
    pub fn sqrt(self) -> Dd {
        if self.0 <= 0.0 {
            return Dd(0.0, 0.0);
        }
        let s = self.0.sqrt();
        let r = self.sub(Dd::prod(s, s));
        fast_two_sum(s, r.0 / (2.0 * s))
    }
    pub fn f(self) -> f64 {
        self.0 + self.1
    }
}

/// A symmetric 2x2 matrix in double-double.
#[derive(Clone, Copy, Debug)]
pub struct DdSym {
    pub a11: Dd,
    pub a12: Dd,
    pub a22: Dd,
}

impl DdSym {
    pub fn new(a11: f64, a12: f64, a22: f64) -> Self {
        Self {
            a11: Dd::from(a11),
            a12: Dd::from(a12),
            a22: Dd::from(a22),
        }
    }
    /// `[[p, a12], [a12, (a12^2 + c) / p]]`, the matrix of determinant `c` with pivot `p`: a
    /// clamped `RoughnessMatrix`'s `A_c` from its pivot and `c = max(det A, tau)`.
    pub fn ldl(p: f64, a12: f64, c: f64) -> Self {
        Self {
            a11: Dd::from(p),
            a12: Dd::from(a12),
            a22: Dd::prod(a12, a12).add(Dd::from(c)).div(Dd::from(p)),
        }
    }
    pub fn det(&self) -> Dd {
        self.a11.mul(self.a22).sub(self.a12.mul(self.a12))
    }
    pub fn add(&self, o: &DdSym) -> DdSym {
        DdSym {
            a11: self.a11.add(o.a11),
            a12: self.a12.add(o.a12),
            a22: self.a22.add(o.a22),
        }
    }
    pub fn scale(&self, k: f64) -> DdSym {
        DdSym {
            a11: self.a11.mul(Dd::from(k)),
            a12: self.a12.mul(Dd::from(k)),
            a22: self.a22.mul(Dd::from(k)),
        }
    }
    /// `s^T adj(A) s` (exact up to double-double rounding).
    pub fn adj_quadratic(&self, x: f64, y: f64) -> Dd {
        let (xx, xy, yy) = (Dd::prod(x, x), Dd::prod(x, y), Dd::prod(y, y));
        self.a22
            .mul(xx)
            .sub(self.a12.mul(xy).mul(Dd::from(2.0)))
            .add(self.a11.mul(yy))
    }
    /// `w^T A w`.
    pub fn quadratic(&self, x: f64, y: f64) -> Dd {
        let (xx, xy, yy) = (Dd::prod(x, x), Dd::prod(x, y), Dd::prod(y, y));
        self.a11
            .mul(xx)
            .add(self.a12.mul(xy).mul(Dd::from(2.0)))
            .add(self.a22.mul(yy))
    }
    /// `A B` for symmetric `A`, `B` whose product is symmetric (commuting matrices, e.g.
    /// functions of one another): returns the symmetrised product.
    pub fn mul_sym(&self, b: &DdSym) -> DdSym {
        let c11 = self.a11.mul(b.a11).add(self.a12.mul(b.a12));
        let c12 = self.a11.mul(b.a12).add(self.a12.mul(b.a22));
        let c21 = self.a12.mul(b.a11).add(self.a22.mul(b.a12));
        let c22 = self.a12.mul(b.a12).add(self.a22.mul(b.a22));
        DdSym {
            a11: c11,
            a12: c12.add(c21).mul(Dd::from(0.5)),
            a22: c22,
        }
    }
    /// `adj(A)`.
    pub fn adj(&self) -> DdSym {
        DdSym {
            a11: self.a22,
            a12: Dd(-self.a12.0, -self.a12.1),
            a22: self.a11,
        }
    }
    pub fn div(&self, k: Dd) -> DdSym {
        DdSym {
            a11: self.a11.div(k),
            a12: self.a12.div(k),
            a22: self.a22.div(k),
        }
    }
    pub fn identity_minus(&self) -> DdSym {
        DdSym {
            a11: Dd::from(1.0).sub(self.a11),
            a12: Dd(-self.a12.0, -self.a12.1),
            a22: Dd::from(1.0).sub(self.a22),
        }
    }
    pub fn identity_plus(&self) -> DdSym {
        DdSym {
            a11: Dd::from(1.0).add(self.a11),
            a12: self.a12,
            a22: Dd::from(1.0).add(self.a22),
        }
    }
}

/// Reference GGX slope density for a roughness matrix `a` (double-double) with determinant
/// clamp `tau`: `1 / (pi sqrt(max(det A, tau)) (1 + s^T A^-1 s)^2)`.
pub fn ggx_p22_ref(a: &DdSym, tau: f64, x: f64, y: f64) -> f64 {
    let det = max_dd(a.det(), tau);
    let q = a.adj_quadratic(x, y).div(det).f().max(0.0);
    let t = 1.0 + q;
    1.0 / (std::f64::consts::PI * det.sqrt().f() * t * t)
}

/// Reference Beckmann slope density: `exp(-s^T A^-1 s) / (pi sqrt(max(det A, tau)))`, with the
/// normalisation moved into the exponent so that it never underflows early.
pub fn beckmann_p22_ref(a: &DdSym, tau: f64, x: f64, y: f64) -> f64 {
    let det = max_dd(a.det(), tau);
    let q = a.adj_quadratic(x, y).div(det).f().max(0.0);
    (-q - (std::f64::consts::PI * det.sqrt().f()).ln()).exp()
}

pub fn max_dd(d: Dd, tau: f64) -> Dd {
    if d.f() >= tau { d } else { Dd::from(tau) }
}

/// Reference GGX `Lambda` from `q = w_xy^T A w_xy` (double-double) and `w_z`:
/// `x / (2 (sqrt(1 + x) + 1))`, `x = q / w_z^2`.
pub fn ggx_lambda_ref(q: Dd, wz: f64) -> f64 {
    if q.f() <= 0.0 {
        return 0.0;
    }
    if wz == 0.0 {
        return f64::INFINITY;
    }
    let x = q.div(Dd::prod(wz, wz)).f();
    if !x.is_finite() {
        return f64::INFINITY;
    }
    x / (2.0 * ((1.0 + x).sqrt() + 1.0))
}

/// Reference Beckmann `Lambda` for `a = |w_z| / sqrt(q)`: the direct formula
/// `(exp(-a^2) / (a sqrt(pi)) - erfc(a)) / 2` below `a = 5` (cancellation `2 a^2 eps_f64 <=
/// 1.1e-14`), the asymptotic series `exp(-a^2) / (2 a sqrt(pi)) sum_{n>=1} (-1)^(n+1)
/// (2n-1)!! / (2 a^2)^n` above (terms decrease while `n < a^2`; truncated below `1e-17`).
pub fn beckmann_lambda_ref(q: Dd, wz: f64) -> f64 {
    if q.f() <= 0.0 {
        return 0.0;
    }
    if wz == 0.0 {
        return f64::INFINITY;
    }
    let a = Dd::from(wz.abs()).div(q.sqrt()).f();
    let sqrt_pi = std::f64::consts::PI.sqrt();
    if a < 5.0 {
        let e = (-a * a).exp() * (1.0 - a.mul_add(a, -(a * a)));
        return (0.5 * (e / (a * sqrt_pi) - libm::erfc(a))).max(0.0);
    }
    let x = 1.0 / (2.0 * a * a);
    let mut term = 1.0;
    let mut sum = 0.0;
    let mut n = 1.0;
    loop {
        term *= (2.0 * n - 1.0) * x;
        let signed = if (n as i64) % 2 == 1 { term } else { -term };
        sum += signed;
        if term < 1e-17 * sum.abs() || n > 60.0 {
            break;
        }
        n += 1.0;
    }
    // exp(-a^2) with a^2 split, for a up to ~27 (Lambda underflows beyond).
    let a2 = a * a;
    let e = (-a2).exp() * (1.0 - a.mul_add(a, -a2));
    e / (2.0 * a * sqrt_pi) * sum
}

/// `|got - reference|` relative to `max(|reference|, floor)`; `inf` for a NaN `got`.
pub fn rel_err(got: f64, reference: f64, floor: f64) -> f64 {
    if got.is_nan() {
        return f64::INFINITY;
    }
    if got == reference {
        return 0.0;
    }
    (got - reference).abs() / reference.abs().max(floor)
}

/// Worst errors per (kernel, region), per precision, with every failed check listed.
#[derive(Default)]
pub struct ErrorMap {
    title: String,
    kernels: Vec<String>,
    regions: Vec<String>,
    worst: BTreeMap<(String, String), [Option<f64>; 2]>,
    failures: Vec<String>,
    checks: usize,
}

pub const F32: usize = 0;

/// The roughness grid of the sweep, with region labels.
pub const ALPHAS: [(f64, &str); 4] = [
    (1e-7, "alpha 1e-7"),
    (1e-4, "alpha 1e-4"),
    (1.0, "alpha 1"),
    (10.0, "alpha 10"),
];

/// The unit roundoff of precision `prec` ([`F32`] or f64), as f64.
pub fn unit_eps(prec: usize) -> f64 {
    if prec == F32 {
        f32::EPSILON as f64
    } else {
        f64::EPSILON
    }
}

/// The smallest normal number of precision `prec`, as f64.
pub fn min_positive(prec: usize) -> f64 {
    if prec == F32 {
        f32::MIN_POSITIVE as f64
    } else {
        f64::MIN_POSITIVE
    }
}
pub const F64: usize = 1;

impl ErrorMap {
    pub fn new(title: &str) -> Self {
        Self {
            title: title.to_string(),
            ..Self::default()
        }
    }

    fn note_names(&mut self, kernel: &str, regions: &[&str]) {
        if !self.kernels.iter().any(|k| k == kernel) {
            self.kernels.push(kernel.to_string());
        }
        for r in regions {
            if !self.regions.iter().any(|x| x == r) {
                self.regions.push(r.to_string());
            }
        }
    }

    /// Records an error `err` (relative, see [`rel_err`]) of `kernel` in every region of
    /// `regions`, checked against `tol`.
    pub fn record(
        &mut self,
        kernel: &str,
        regions: &[&str],
        prec: usize,
        err: f64,
        tol: f64,
        ctx: impl FnOnce() -> String,
    ) {
        self.checks += 1;
        self.note_names(kernel, regions);
        for r in regions {
            let e = self
                .worst
                .entry((kernel.to_string(), r.to_string()))
                .or_insert([None, None]);
            let w = e[prec].get_or_insert(0.0);
            if err > *w || err.is_nan() {
                *w = err;
            }
        }
        if err.is_nan() || err > tol {
            self.failures.push(format!(
                "{kernel} [{}] {}: error {err:.3e} > tolerance {tol:.1e}: {}",
                regions.join(", "),
                if prec == F32 { "f32" } else { "f64" },
                ctx()
            ));
        }
    }

    /// A check without a numeric error (the contract: finite, non-negative, a documented
    /// value).
    /// A density check: `got` must be finite and non-negative, and its error against
    /// `reference` (relative, with `floor` as in [`rel_err`]) is recorded against `tol`.
    #[allow(clippy::too_many_arguments)]
    pub fn record_density(
        &mut self,
        kernel: &str,
        regions: &[&str],
        prec: usize,
        (got, reference, floor): (f64, f64, f64),
        tol: f64,
        ctx: impl Fn() -> String,
    ) {
        self.require(got.is_finite() && got >= 0.0, || {
            format!("{kernel} not finite/non-negative: {got} ({})", ctx())
        });
        self.record(
            kernel,
            regions,
            prec,
            rel_err(got, reference, floor),
            tol,
            ctx,
        );
    }

    pub fn require(&mut self, ok: bool, ctx: impl FnOnce() -> String) {
        self.checks += 1;
        if !ok {
            self.failures.push(ctx());
        }
    }

    /// The markdown table: one row per region, one column per kernel, `f32 / f64` worst
    /// relative errors.
    pub fn table(&self) -> String {
        let mut s = format!("#### {}\n\n| region |", self.title);
        for k in &self.kernels {
            s += &format!(" {k} |");
        }
        s += "\n|---|";
        for _ in &self.kernels {
            s += "---|";
        }
        s += "\n";
        for r in &self.regions {
            s += &format!("| {r} |");
            for k in &self.kernels {
                let cell = match self.worst.get(&(k.clone(), r.clone())) {
                    None => "".to_string(),
                    Some([a, b]) => format!("{} / {}", fmt(*a), fmt(*b)),
                };
                s += &format!(" {cell} |");
            }
            s += "\n";
        }
        s
    }

    /// Prints the table and panics with every failure.
    pub fn finish(&self) {
        println!("\n{}", self.table());
        println!("({} checks)", self.checks);
        if !self.failures.is_empty() {
            for f in self.failures.iter().take(60) {
                println!("FAIL {f}");
            }
            panic!("{} of {} checks failed", self.failures.len(), self.checks);
        }
    }
}

fn fmt(e: Option<f64>) -> String {
    match e {
        None => "-".to_string(),
        Some(0.0) => "0".to_string(),
        Some(x) => format!("{x:.1e}"),
    }
}

/// `integral_a^b f` for an integrand with a narrow feature of width `w` at `c`: split at
/// `c +/- w {0, 1, 4, 16, ...}` inside `[a, b]` so the adaptive rule cannot step over it. `f`
/// returns a value and its own absolute error (`0` for a plain integrand; an inner integral's
/// estimate, integrated alongside); the result's estimate sums the pieces'.
pub fn integrate_feature(
    mut f: impl FnMut(f64) -> (f64, f64),
    a: f64,
    b: f64,
    c: f64,
    w: f64,
    tol: Tolerance,
) -> Estimate {
    let mut pts = vec![a, b];
    let mut k = 0.0;
    while k < 1e30 {
        for p in [c - k * w, c + k * w] {
            if p > a && p < b {
                pts.push(p);
            }
        }
        k = if k == 0.0 { 1.0 } else { k * 4.0 };
        if k * w > (b - a) * 4.0 {
            break;
        }
    }
    pts.sort_by(|x, y| x.total_cmp(y));
    pts.dedup();
    let mut total = Estimate {
        value: 0.0,
        error: 0.0,
    };
    for p in pts.windows(2) {
        let e = integrate_estimates(&mut f, p[0], p[1], tol);
        total.value += e.value;
        total.error += e.error;
    }
    total
}
