//! The one switch for the float math backend (glam's `math.rs` pattern).
//!
//! Every formula in the crate calls these functions, never `f32::sqrt` or `libm::sqrtf`
//! directly, so `no_std` is a build flag, not a rewrite. With the `std` feature (and without
//! `libm`) the standard library intrinsics are used; otherwise `libm`. Functions that `std`
//! does not provide on stable (`erf`, `erfc`) always come from `libm`.

/// The float operations the crate needs, for `f32` and `f64`.
///
/// Sealed: implemented for `f32` and `f64` only.
pub trait Real: Copy + PartialOrd + sealed::Sealed {
    /// Square root.
    fn sqrt(self) -> Self;
    /// Natural exponential.
    fn exp(self) -> Self;
    /// Natural logarithm.
    fn ln(self) -> Self;
    /// Arc tangent, in radians.
    fn atan(self) -> Self;
    /// Four-quadrant arc tangent of `self / x`, in radians.
    fn atan2(self, x: Self) -> Self;
    /// Sine.
    fn sin(self) -> Self;
    /// Cosine.
    fn cos(self) -> Self;
    /// Error function.
    fn erf(self) -> Self;
    /// Complementary error function, `1 - erf(x)` without cancellation.
    fn erfc(self) -> Self;
    /// `self^p` for a real exponent.
    fn powf(self, p: Self) -> Self;
    /// Fused (or at least accurate) multiply-add `self * a + b`.
    fn mul_add(self, a: Self, b: Self) -> Self;
    /// `sqrt(self^2 + y^2)` without undue overflow or underflow.
    fn hypot(self, y: Self) -> Self;
    /// Widening (or identity) conversion to `f64`.
    fn to_f64(self) -> f64;
    /// Rounding (or identity) conversion from `f64`.
    fn from_f64(x: f64) -> Self;
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

macro_rules! impl_real {
    ($t:ty, $sqrt:path, $exp:path, $ln:path, $atan:path, $atan2:path, $sin:path, $cos:path,
     $erf:path, $erfc:path, $pow:path, $fma:path, $hypot:path) => {
        impl Real for $t {
            #[inline(always)]
            fn sqrt(self) -> Self {
                #[cfg(all(feature = "std", not(feature = "libm")))]
                return <$t>::sqrt(self);
                #[cfg(not(all(feature = "std", not(feature = "libm"))))]
                return $sqrt(self);
            }
            #[inline(always)]
            fn exp(self) -> Self {
                #[cfg(all(feature = "std", not(feature = "libm")))]
                return <$t>::exp(self);
                #[cfg(not(all(feature = "std", not(feature = "libm"))))]
                return $exp(self);
            }
            #[inline(always)]
            fn ln(self) -> Self {
                #[cfg(all(feature = "std", not(feature = "libm")))]
                return <$t>::ln(self);
                #[cfg(not(all(feature = "std", not(feature = "libm"))))]
                return $ln(self);
            }
            #[inline(always)]
            fn atan(self) -> Self {
                #[cfg(all(feature = "std", not(feature = "libm")))]
                return <$t>::atan(self);
                #[cfg(not(all(feature = "std", not(feature = "libm"))))]
                return $atan(self);
            }
            #[inline(always)]
            fn atan2(self, x: Self) -> Self {
                #[cfg(all(feature = "std", not(feature = "libm")))]
                return <$t>::atan2(self, x);
                #[cfg(not(all(feature = "std", not(feature = "libm"))))]
                return $atan2(self, x);
            }
            #[inline(always)]
            fn sin(self) -> Self {
                #[cfg(all(feature = "std", not(feature = "libm")))]
                return <$t>::sin(self);
                #[cfg(not(all(feature = "std", not(feature = "libm"))))]
                return $sin(self);
            }
            #[inline(always)]
            fn cos(self) -> Self {
                #[cfg(all(feature = "std", not(feature = "libm")))]
                return <$t>::cos(self);
                #[cfg(not(all(feature = "std", not(feature = "libm"))))]
                return $cos(self);
            }
            #[inline(always)]
            fn erf(self) -> Self {
                $erf(self)
            }
            #[inline(always)]
            fn erfc(self) -> Self {
                $erfc(self)
            }
            #[inline(always)]
            fn powf(self, p: Self) -> Self {
                #[cfg(all(feature = "std", not(feature = "libm")))]
                return <$t>::powf(self, p);
                #[cfg(not(all(feature = "std", not(feature = "libm"))))]
                return $pow(self, p);
            }
            #[inline(always)]
            fn mul_add(self, a: Self, b: Self) -> Self {
                #[cfg(all(feature = "std", not(feature = "libm")))]
                return <$t>::mul_add(self, a, b);
                #[cfg(not(all(feature = "std", not(feature = "libm"))))]
                return $fma(self, a, b);
            }
            #[inline(always)]
            #[allow(clippy::unnecessary_cast)]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline(always)]
            #[allow(clippy::unnecessary_cast)]
            fn from_f64(x: f64) -> Self {
                x as $t
            }
            #[inline(always)]
            fn hypot(self, y: Self) -> Self {
                #[cfg(all(feature = "std", not(feature = "libm")))]
                return <$t>::hypot(self, y);
                #[cfg(not(all(feature = "std", not(feature = "libm"))))]
                return $hypot(self, y);
            }
        }
    };
}

impl_real!(
    f32,
    libm::sqrtf,
    libm::expf,
    libm::logf,
    libm::atanf,
    libm::atan2f,
    libm::sinf,
    libm::cosf,
    libm::erff,
    libm::erfcf,
    libm::powf,
    libm::fmaf,
    libm::hypotf
);
impl_real!(
    f64,
    libm::sqrt,
    libm::exp,
    libm::log,
    libm::atan,
    libm::atan2,
    libm::sin,
    libm::cos,
    libm::erf,
    libm::erfc,
    libm::pow,
    libm::fma,
    libm::hypot
);

macro_rules! free_fns {
    ($($name:ident($($arg:ident),*)),* $(,)?) => {
        $(
            #[doc = concat!("[`Real::", stringify!($name), "`] as a free function, for formula code.")]
            #[inline(always)]
            pub fn $name<T: Real>(x: T $(, $arg: T)*) -> T {
                T::$name(x $(, $arg)*)
            }
        )*
    };
}

free_fns!(
    sqrt(),
    exp(),
    ln(),
    atan(),
    atan2(x_),
    sin(),
    cos(),
    erf(),
    erfc(),
    powf(p),
    mul_add(a, b),
    hypot(y),
);

/// A uniform sample in `[0, 1)` from a 64-bit linear congruential step of `state` (Knuth's
/// MMIX constants; the top 53 bits): the unit tests' seeded inputs, without the `testing`
/// feature's generator.
#[cfg(test)]
pub(crate) fn test_uniform(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6_364_136_223_846_793_005)
        .wrapping_add(1_442_695_040_888_963_407);
    (*state >> 11) as f64 / (1u64 << 53) as f64
}
