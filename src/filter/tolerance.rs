//! The accuracy parameter of the exact Gaussian-filtered GGX ([`super::GaussianFilteredGgx`]):
//! a requested relative tolerance, one of four settings, each a fixed set of quadrature rules
//! with a proven bound (the derivations and where each setting's rules switch are in the
//! module docs of [`super::GaussianFilteredGgx`], "Tolerance settings").

/// The relative accuracy of the exact Gaussian-filtered GGX's density (`p22`, `d`): a setting
/// of its quadrature rules, each with a proven bound on the relative error of the density
/// ([`Tolerance::bound`]; derivations in the module docs of
/// [`GaussianFilteredGgx`](super::GaussianFilteredGgx), "Tolerance settings").
///
/// | setting | bound (`f32` lobe) | bound (`f64` lobe) | rules |
/// |---|---:|---:|---|
/// | [`Tolerance::Full`] (default) | `1.8e-6` | `1.1e-11` | far-tail series, Gauss-Laguerre (8 / 12 nodes), trapezoid in `ln w` (step `0.5` / `0.3`) |
/// | [`Tolerance::Rel1e4`] | `1e-4` | `1e-4` | far-tail series where `2 l1 (1500 + 12 ln(1 + q)) <= 1 + q`, else trapezoid in `ln w`, step `0.6` |
/// | [`Tolerance::Rel1e3`] | `1e-3` | `1e-3` | far-tail series where `2 l1 (500 + 12 ln(1 + q)) <= 1 + q`, else trapezoid in `ln w`, step `0.75` |
/// | [`Tolerance::Rel1e2`] | `1e-2` | `1e-2` | far-tail series where `2 l1 (160 + 12 ln(1 + q)) <= 1 + q`, else trapezoid in `ln w`, step `1` |
///
/// `Full` is the precision's own rule (what [`GaussianFilteredGgx::new`] and
/// [`ExactGaussian`](super::ExactGaussian) give unless asked otherwise); the others trade
/// accuracy for fewer nodes. The setting applies to the density; `Lambda` and the samplers
/// use the full rules at every setting.
///
/// ```
/// use filtered_ndf::f32::filter::Tolerance;
///
/// assert_eq!(Tolerance::default(), Tolerance::Full);
/// assert_eq!(Tolerance::relative(2e-3), Tolerance::Rel1e3);
/// assert_eq!(Tolerance::relative(1e-5), Tolerance::Full);
/// assert!(Tolerance::Rel1e3.bound() <= 1e-3);
/// ```
///
/// [`GaussianFilteredGgx::new`]: super::GaussianFilteredGgx::new
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Tolerance {
    /// The precision's own rules: relative error at most `1.8e-6` in `f32`, `1.1e-11` in
    /// `f64`.
    #[default]
    Full,
    /// Relative error at most `1e-4`.
    Rel1e4,
    /// Relative error at most `1e-3`.
    Rel1e3,
    /// Relative error at most `1e-2`.
    Rel1e2,
}

impl Tolerance {
    /// Every setting, from the most accurate to the cheapest.
    pub const ALL: [Self; 4] = [Self::Full, Self::Rel1e4, Self::Rel1e3, Self::Rel1e2];

    /// The cheapest setting whose bound is at most `eps` (relative): [`Tolerance::Full`] for
    /// `eps < 1e-4` and for NaN, [`Tolerance::Rel1e2`] for `eps >= 1e-2` (and `+inf`).
    #[inline]
    pub const fn relative(eps: f64) -> Self {
        if eps >= 1e-2 {
            Self::Rel1e2
        } else if eps >= 1e-3 {
            Self::Rel1e3
        } else if eps >= 1e-4 {
            Self::Rel1e4
        } else {
            Self::Full
        }
    }

    /// The setting's proven bound on the relative error of the density, in this precision
    /// (the table above).
    #[inline]
    pub const fn bound(self) -> f64 {
        match self {
            Self::Full => {
                if super::gaussian_ggx_quad::WIDE {
                    1.1e-11
                } else {
                    1.8e-6
                }
            }
            Self::Rel1e4 => 1e-4,
            Self::Rel1e3 => 1e-3,
            Self::Rel1e2 => 1e-2,
        }
    }
}
