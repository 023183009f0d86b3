//! Precision-independent NDF test cases and the proptest strategies that draw them: a model
//! (GGX or Beckmann) and a roughness form described in `f64`, built in either precision from
//! the same numbers, so that a test can compare `f32` with `f64` on identical inputs and
//! integrate the `f64` build against quadrature.

use super::linalg::Sym2;
use crate::RoughnessError;
use alloc::boxed::Box;
use proptest::prelude::*;

extern crate alloc;

/// The microfacet model of a case.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Model {
    /// GGX / Trowbridge-Reitz.
    Ggx,
    /// Beckmann.
    Beckmann,
}

/// A roughness form, described in `f64`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Form {
    /// [`crate::f64::Isotropic`] `alpha`.
    Isotropic(f64),
    /// [`crate::f64::AxisAligned`] `(alpha_x, alpha_y)`.
    AxisAligned(f64, f64),
    /// [`crate::f64::RoughnessMatrix`] `A = R(phi) diag(alpha_x^2, alpha_y^2) R(phi)^T`.
    Rotated {
        /// Roughness along the rotated tangent.
        alpha_x: f64,
        /// Roughness along the rotated bitangent.
        alpha_y: f64,
        /// Rotation angle of the lobe, radians.
        phi: f64,
    },
}

impl Form {
    /// The entries `(a11, a12, a22)` of `A` (computed in `f64`).
    pub fn entries(&self) -> (f64, f64, f64) {
        let (ax, ay, phi) = self.axes();
        Sym2::from_eigen(ax * ax, ay * ay, phi).entries()
    }

    /// The eigen-frame widths and angle `(sqrt(l1), sqrt(l2), phi)` of `A`.
    pub fn axes(&self) -> (f64, f64, f64) {
        match *self {
            Form::Isotropic(a) => (a, a, 0.0),
            Form::AxisAligned(ax, ay) => (ax, ay, 0.0),
            Form::Rotated {
                alpha_x,
                alpha_y,
                phi,
            } => (alpha_x, alpha_y, phi),
        }
    }
}

/// A model and a roughness form.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NdfCase {
    /// The model.
    pub model: Model,
    /// The roughness form.
    pub form: Form,
}

macro_rules! build {
    ($prec:ident, $self:expr, $t:ty) => {{
        use crate::$prec::{AxisAligned, Beckmann, Ggx, Isotropic, Ndf, RoughnessMatrix};
        let r = |x: f64| x as $t;
        let nd: Box<dyn Ndf> = match ($self.model, $self.form) {
            (Model::Ggx, Form::Isotropic(a)) => Box::new(Ggx::new(Isotropic::new(r(a))?)),
            (Model::Beckmann, Form::Isotropic(a)) => Box::new(Beckmann::new(Isotropic::new(r(a))?)),
            (Model::Ggx, Form::AxisAligned(x, y)) => {
                Box::new(Ggx::new(AxisAligned::new(r(x), r(y))?))
            }
            (Model::Beckmann, Form::AxisAligned(x, y)) => {
                Box::new(Beckmann::new(AxisAligned::new(r(x), r(y))?))
            }
            (model, form) => {
                let (a11, a12, a22) = form.entries();
                let mtx = RoughnessMatrix::new(r(a11), r(a12), r(a22))?;
                match model {
                    Model::Ggx => Box::new(Ggx::new(mtx)),
                    Model::Beckmann => Box::new(Beckmann::new(mtx)),
                }
            }
        };
        Ok(nd)
    }};
}

impl NdfCase {
    /// The case built in `f64`.
    pub fn build_f64(&self) -> Result<Box<dyn crate::f64::Ndf>, RoughnessError> {
        build!(f64, self, f64)
    }

    /// The case built in `f32` (every parameter rounded to `f32` first).
    #[allow(clippy::cast_possible_truncation)]
    pub fn build_f32(&self) -> Result<Box<dyn crate::f32::Ndf>, RoughnessError> {
        build!(f32, self, f32)
    }

    /// The same case with every parameter that reaches the constructors (`alpha`s, or the
    /// matrix entries) rounded to `f32`, so that `build_f64` and `build_f32` see identical
    /// numbers. A rotated form becomes its rounded entries' eigen-decomposition.
    pub fn rounded_to_f32(&self) -> Self {
        let r = |x: f64| f64::from(x as f32);
        let form = match self.form {
            Form::Isotropic(a) => Form::Isotropic(r(a)),
            Form::AxisAligned(x, y) => Form::AxisAligned(r(x), r(y)),
            f @ Form::Rotated { .. } => {
                let (a11, a12, a22) = f.entries();
                let e = Sym2::new(r(a11), r(a12), r(a22)).eigen();
                Form::Rotated {
                    alpha_x: e.l1.sqrt(),
                    alpha_y: e.l2.max(0.0).sqrt(),
                    phi: e.theta,
                }
            }
        };
        Self {
            model: self.model,
            form,
        }
    }
}

/// Roughness `alpha` log-uniform in `[lo, hi]`.
pub fn alpha(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.ln()..=hi.ln()).prop_map(f64::exp)
}

/// A roughness form with every `alpha` log-uniform in `[1e-4, 2]`, anisotropy ratios
/// log-uniform up to `1e3` (then clamped into the range) and uniform rotations.
pub fn form() -> impl Strategy<Value = Form> {
    let aniso =
        || (alpha(1e-4, 2.0), alpha(1e-3, 1e3)).prop_map(|(a, r)| (a, (a * r).clamp(1e-4, 2.0)));
    prop_oneof![
        alpha(1e-4, 2.0).prop_map(Form::Isotropic),
        aniso().prop_map(|(x, y)| Form::AxisAligned(x, y)),
        (aniso(), 0.0..core::f64::consts::PI).prop_map(|((alpha_x, alpha_y), phi)| {
            Form::Rotated {
                alpha_x,
                alpha_y,
                phi,
            }
        }),
    ]
}

/// Either model.
pub fn model() -> impl Strategy<Value = Model> {
    prop_oneof![Just(Model::Ggx), Just(Model::Beckmann)]
}

/// An [`NdfCase`] from [`model`] and [`form`].
pub fn case() -> impl Strategy<Value = NdfCase> {
    (model(), form()).prop_map(|(model, form)| NdfCase { model, form })
}

/// A unit direction `(x, y, z)` at polar angle uniform in `[0, max_theta_deg]` degrees from
/// the normal and uniform azimuth.
pub fn direction(max_theta_deg: f64) -> impl Strategy<Value = [f64; 3]> {
    (
        0.0..=max_theta_deg.to_radians(),
        0.0..core::f64::consts::TAU,
    )
        .prop_map(|(t, p)| {
            let (st, ct) = t.sin_cos();
            let (sp, cp) = p.sin_cos();
            [st * cp, st * sp, ct]
        })
}
