//! Errors of the checked constructors and of the batch kernels' SIMD level request (precision
//! independent).

use core::fmt;

/// Why a checked roughness constructor refused its input.
///
/// Every checked constructor (`Isotropic::new`, `AxisAligned::new`, `RoughnessMatrix::new`,
/// ...) returns one of these instead of panicking; the unchecked or clamping variants document
/// what they do with the same input.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RoughnessError {
    /// A roughness value or matrix entry is NaN or infinite.
    NotFinite,
    /// A roughness value or a diagonal entry of the matrix is zero or negative.
    NotPositive,
    /// A roughness is outside the supported range `[ALPHA_MIN, ALPHA_MAX]` (for a matrix: an
    /// eigenvalue outside `[ALPHA_MIN^2, ALPHA_MAX^2]`), where densities would overflow or
    /// underflow the float type.
    OutOfRange,
    /// A matrix given as four entries has `a12 != a21` beyond rounding.
    NotSymmetric,
    /// A symmetric matrix is not positive definite (`det(A) <= 0` with no clamp, or clearly
    /// negative with a clamp).
    NotPositiveDefinite,
}

impl fmt::Display for RoughnessError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            RoughnessError::NotFinite => "roughness is NaN or infinite",
            RoughnessError::NotPositive => "roughness is zero or negative",
            RoughnessError::OutOfRange => "roughness is outside [ALPHA_MIN, ALPHA_MAX]",
            RoughnessError::NotSymmetric => "roughness matrix is not symmetric",
            RoughnessError::NotPositiveDefinite => "roughness matrix is not positive definite",
        })
    }
}

impl core::error::Error for RoughnessError {}

/// A name that is no SIMD level of the batch kernels (`batch::simd_available`, the value of
/// `FILTERED_NDF_SIMD` in `batch::simd_requested`): the levels are `sse2`, `sse2-lanes`,
/// `avx2`, `avx512` (x86-64) and `baseline` (elsewhere).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct UnknownSimdLevel;

impl fmt::Display for UnknownSimdLevel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(
            "not a SIMD level of the batch kernels: expected sse2, sse2-lanes, avx2, avx512 \
             (x86-64) or baseline",
        )
    }
}

impl core::error::Error for UnknownSimdLevel {}

/// Why a checked Fresnel constructor refused its input (`Dielectric::new`,
/// `Conductor::new`, `Schlick::new` of the `bsdf` stage).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FresnelError {
    /// An index of refraction, extinction coefficient or reflectance is NaN or infinite.
    NotFinite,
    /// A value is outside its domain: an index of refraction `<= 0`, an extinction
    /// coefficient `< 0`, a normal-incidence reflectance outside `[0, 1]`.
    OutOfRange,
}

impl fmt::Display for FresnelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            FresnelError::NotFinite => "Fresnel parameter is NaN or infinite",
            FresnelError::OutOfRange => "Fresnel parameter is outside its domain",
        })
    }
}

impl core::error::Error for FresnelError {}
