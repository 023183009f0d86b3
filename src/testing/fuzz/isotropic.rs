//! The contract of isotropic (deferred) roughness filtering and its presets.

use super::Bytes;
use super::dec::{d32, d64};

macro_rules! isotropic_prec {
    ($d:ident, $prec:ident, $b:expr) => {{
        use crate::$prec::filter::deferred::{
            Bandwidth, Combine, Domain, KAPPA, KernelConvention, Norm, filtered_alpha,
            normal_difference_covariance,
        };
        use crate::$prec::{ALPHA_MAX, Covariance, Vec3, filter::presets};
        use $d::{TOL, f, v3};
        let b: &mut Bytes<'_> = $b;
        let head = b.byte();
        let alpha = f(b);
        let (dn_u, dn_v) = (v3(b), v3(b));
        let cov = Covariance::new(f(b), f(b), f(b));
        let (kappa, sigma, k) = (f(b), f(b), f(b));
        let pick = b.byte();
        let conv = KernelConvention {
            domain: [
                Domain::Alpha2,
                Domain::Alpha,
                Domain::Perceptual,
                Domain::ProjectedAlpha2,
            ][usize::from(pick % 4)],
            norm: [
                Norm::SumSquared,
                Norm::MaxSquared,
                Norm::MaxEigenvalue,
                Norm::MaxAbsComponent,
            ][usize::from((pick >> 2) % 4)],
            scale: f(b),
            exponent: f(b),
            bias: f(b),
            clamp: f(b),
            combine: if pick & 16 != 0 {
                Combine::Add
            } else {
                Combine::Max
            },
            saturate: pick & 32 != 0,
            perceptual_floor: f(b),
        };
        let bw = [Bandwidth::Max, Bandwidth::Trace, Bandwidth::Average][usize::from(head % 3)];
        let in_range = |a: F, what: &str| {
            assert!(
                (0.0..=ALPHA_MAX).contains(&a),
                "{what} = {a:?} (alpha {alpha:?})"
            );
        };
        use crate::$prec::F;

        // Bandwidth kernels: a NaN entry counts as 0 (the NaN policy); documented NaN for an
        // infinite entry of `Max`, `>= 0` for a finite PSD covariance.
        let kv = bw.alpha2(&cov);
        let z = |x: F| if x.is_nan() { 0.0 } else { x };
        let zeroed = Covariance::new(z(cov.s11), z(cov.s12), z(cov.s22));
        let same = bw.alpha2(&zeroed);
        assert!(
            kv.to_bits() == same.to_bits() || (kv.is_nan() && same.is_nan()),
            "{bw:?}.kernel({cov:?}) = {kv:?}, with NaN entries zeroed {same:?}"
        );
        let inf = [zeroed.s11, zeroed.s12, zeroed.s22]
            .iter()
            .any(|x| x.is_infinite());
        match bw {
            Bandwidth::Max => {
                if inf {
                    assert!(kv.is_nan(), "{bw:?}.kernel({cov:?}) = {kv:?}");
                } else {
                    assert!(kv >= 0.0, "{bw:?}.kernel({cov:?}) = {kv:?}");
                }
            }
            _ => {
                if zeroed.s11 >= 0.0 && zeroed.s22 >= 0.0 {
                    assert!(kv >= 0.0, "{bw:?}.kernel({cov:?}) = {kv:?}");
                }
            }
        }
        let fa = filtered_alpha(alpha, &cov, bw, kappa);
        in_range(fa, "filtered_alpha");
        let fk = filtered_alpha(alpha, &cov, bw, KAPPA);
        in_range(fk, "filtered_alpha(KAPPA)");
        // From ALPHA_MIN: the square of a smaller alpha may underflow to 0 (f32).
        let in_dom = alpha == 0.0 || (crate::$prec::ALPHA_MIN..=1.0).contains(&alpha);
        if in_dom {
            assert!(
                fk >= alpha * (1.0 - TOL),
                "filtered_alpha({alpha:?}) = {fk:?} sharpened"
            );
        }
        let _ = normal_difference_covariance(dn_u, dn_v, sigma);

        // Domains: non-negative, NaN-free maps of non-negative input; round trip.
        for dom in [
            Domain::Alpha2,
            Domain::Alpha,
            Domain::Perceptual,
            Domain::ProjectedAlpha2,
        ] {
            if alpha >= 0.0 {
                let v = dom.from_alpha(alpha);
                assert!(v >= 0.0, "{dom:?}.from_alpha({alpha:?}) = {v:?}");
                let back = dom.to_alpha(v);
                assert!(back >= 0.0, "{dom:?}.to_alpha({v:?}) = {back:?}");
                if (1e-3..=0.9).contains(&alpha) {
                    let err = ((back - alpha) / alpha).abs();
                    assert!(err <= TOL, "{dom:?} round trip {alpha:?} -> {back:?}");
                }
            }
            if k >= 0.0 {
                let a = dom.to_alpha(k);
                assert!(a >= 0.0, "{dom:?}.to_alpha({k:?}) = {a:?}");
            }
        }
        // Norms: >= 0; a NaN entry counts as 0 (MaxEigenvalue NaN on an infinite entry or a
        // Gram overflow).
        for norm in [
            Norm::SumSquared,
            Norm::MaxSquared,
            Norm::MaxEigenvalue,
            Norm::MaxAbsComponent,
        ] {
            let v = norm.eval(dn_u, dn_v);
            let zero_nan = |d: Vec3| Vec3::select(d.is_nan_mask(), Vec3::ZERO, d);
            let same = norm.eval(zero_nan(dn_u), zero_nan(dn_v));
            assert!(
                v.to_bits() == same.to_bits() || (v.is_nan() && same.is_nan()),
                "{norm:?}.eval({dn_u:?}, {dn_v:?}) = {v:?}, with NaN entries zeroed {same:?}"
            );
            let (dn_u, dn_v) = (zero_nan(dn_u), zero_nan(dn_v));
            if dn_u.is_finite() && dn_v.is_finite() && norm != Norm::MaxEigenvalue {
                assert!(v >= 0.0, "{norm:?}.eval({dn_u:?}, {dn_v:?}) = {v:?}");
            } else {
                assert!(
                    v >= 0.0 || (norm == Norm::MaxEigenvalue && v.is_nan()),
                    "{norm:?}: {v:?}"
                );
            }
        }

        // Arbitrary conventions: kernel in [0, clamp], result in [0, ALPHA_MAX], never NaN.
        let kc = conv.widening(dn_u, dn_v);
        if conv.clamp >= 0.0 {
            assert!((0.0..=conv.clamp).contains(&kc), "{conv:?}.kernel = {kc:?}");
        }
        in_range(conv.apply(alpha, dn_u, dn_v), "apply");
        in_range(conv.apply_widening(alpha, k), "apply_widening");

        // Presets: in range, and (for alpha in [0, 1], finite differences) never sharper than
        // the material roughness, except where the saturate caps it.
        let conventions = presets::ALL.iter().map(|(name, c)| (*name, *c)).chain(
            [Bandwidth::Max, Bandwidth::Trace, Bandwidth::Average].map(|w| ("bw", w.convention())),
        );
        for (name, c) in conventions {
            let a = c.apply(alpha, dn_u, dn_v);
            in_range(a, name);
            if in_dom && dn_u.is_finite() && dn_v.is_finite() {
                let cap = if c.saturate {
                    c.domain.to_alpha(1.0)
                } else {
                    F::INFINITY
                };
                let want = alpha.min(cap);
                assert!(
                    a >= want * (1.0 - TOL),
                    "{name}.apply({alpha:?}, {dn_u:?}, {dn_v:?}) = {a:?}"
                );
            }
        }
    }};
}

/// The isotropic-filtering contract on fuzzer bytes, in both precisions. Panics on a
/// violation of: `Bandwidth::kernel` equal to its value with the NaN entries zeroed (the NaN
/// policy), NaN for an infinite entry (`Max`) and `>= 0` otherwise for a PSD diagonal; `filtered_alpha` in
/// `[0, ALPHA_MAX]` for any input, never below `alpha` for `alpha` in `[0, 1]` with `KAPPA`;
/// `Domain::{from_alpha, to_alpha}` `>= 0` for `>= 0` input and inverse to each other;
/// `Norm::eval` equal to its value with the NaN entries zeroed, `>= 0` (NaN for `MaxEigenvalue`
/// only on an infinite entry or a Gram overflow);
/// `KernelConvention` with arbitrary fields: `kernel` in `[0, clamp]`, `apply` and
/// `apply_widening` in `[0, ALPHA_MAX]`; every preset of `presets::ALL` and
/// `Bandwidth::convention` in range and never below `min(alpha, saturation cap)`.
pub fn check_isotropic(data: &[u8]) {
    isotropic_prec!(d64, f64, &mut Bytes::new(data));
    isotropic_prec!(d32, f32, &mut Bytes::new(data));
}
