#define_import_path filtered_ndf::kernel::covariance

#import filtered_ndf::math
#import filtered_ndf::footprint as pixel

// A symmetric positive semi-definite slope-domain covariance (KHPL16 section 4.3, TK19
// section 2.2), mirroring `Covariance` of `src/.../kernel/covariance.rs`.

/// The largest kernel eigenvalue kept by [`sanitized`]: `ALPHA_MAX^2` (slope^2).
const KERNEL_MAX: f32 = 1e8;

/// `[[s_xx, s_xy], [s_xy, s_yy]]` (slope^2) and its determinant.
///
/// **`det`, a field the Rust type does not have.** In f32, `s_xx s_yy - s_xy^2` cancels for
/// the elongated kernels of grazing footprints (the Rust crate forms it in f64), and the
/// filters need it: `det(A + 2 Sigma)` decides the filtered lobe's minor axis. So the
/// determinant is computed once, where it is accurate, and carried: from footprint vectors
/// as `sigma^4 (dh_u x dh_v)^2`, from a clamp as the product of the new eigenvalues, from a
/// sum as `det a + det b + (a_xx b_yy + a_yy b_xx - 2 a_xy b_xy)`. Build covariances with the
/// functions of this module (e.g. [`from_footprint`]), not the struct constructor.
struct Covariance {
    /// Variance along the tangent `x`.
    s_xx: f32,
    /// Covariance of `x` and `y`.
    s_xy: f32,
    /// Variance along the bitangent `y`.
    s_yy: f32,
    /// `s_xx s_yy - s_xy^2`, computed accurately where the covariance was made.
    det: f32,
}

/// The zero kernel (no filtering).
fn zero() -> Covariance {
    return Covariance(0.0, 0.0, 0.0, 0.0);
}

/// From the three entries, with `det = s_xx s_yy - s_xy^2` formed in f32 (within
/// `eps (s_xx s_yy + s_xy^2)` absolute).
fn from_entries(s_xx: f32, s_xy: f32, s_yy: f32) -> Covariance {
    return Covariance(s_xx, s_xy, s_yy, s_xx * s_yy - s_xy * s_xy);
}

/// The Gaussian pixel kernel of a footprint, `Sigma = sigma^2 (dh_u dh_u^T + dh_v dh_v^T)`
/// (TK19 section 2.2), `sigma` in pixels, with `det Sigma = sigma^4 (dh_u x dh_v)^2` from the
/// vectors (accurate for elongated kernels). The Rust `Covariance::from_footprint`; a NaN
/// footprint entry counts as 0 (`pixel::nan_to_zero`).
fn from_footprint(fp_in: pixel::Footprint, sigma: f32) -> Covariance {
    let fp = pixel::nan_to_zero(fp_in);
    let u = fp.dh_u;
    let v = fp.dh_v;
    let s2 = sigma * sigma;
    let cross = (u.x * v.y - u.y * v.x) * s2;
    return Covariance(
        (u.x * u.x + v.x * v.x) * s2,
        (u.x * u.y + v.x * v.y) * s2,
        (u.y * u.y + v.y * v.y) * s2,
        cross * cross,
    );
}

/// `tr(Sigma) = lambda_min + lambda_max` (TK19 eq. 2).
fn trace(c: Covariance) -> f32 {
    return c.s_xx + c.s_yy;
}

/// `Sigma k` (determinant `det k^2`).
fn scaled(c: Covariance, k: f32) -> Covariance {
    return Covariance(c.s_xx * k, c.s_xy * k, c.s_yy * k, c.det * k * k);
}

/// `a + b`: independent kernels add (KHPL16 eq. 15, 21);
/// `det(a + b) = det a + det b + (a_xx b_yy + a_yy b_xx - 2 a_xy b_xy)`. The cross term is
/// non-negative but cancels, to within `4 eps (|a_xx b_yy| + |a_yy b_xx| + 2 |a_xy b_xy|)`,
/// when both kernels are elongated along one direction.
fn add(a: Covariance, b: Covariance) -> Covariance {
    let cross = a.s_xx * b.s_yy + a.s_yy * b.s_xx - 2.0 * a.s_xy * b.s_xy;
    return Covariance(a.s_xx + b.s_xx, a.s_xy + b.s_xy, a.s_yy + b.s_yy, a.det + b.det + cross);
}

/// Eigenvalues `(lambda_min, lambda_max)`: `lambda_max = mean + hypot(half difference,
/// s_xy)` (no cancellation), `lambda_min = det / lambda_max` (as accurate as `det`); both
/// `>= 0`.
fn eigenvalues(c: Covariance) -> vec2<f32> {
    let mean = 0.5 * (c.s_xx + c.s_yy);
    let lmax = max(mean + math::hypot(0.5 * (c.s_xx - c.s_yy), c.s_xy), 0.0);
    let lmin = select(0.0, max(c.det / lmax, 0.0), lmax > 0.0);
    return vec2<f32>(lmin, lmax);
}

/// Both eigenvalues clamped to `<= max_eig` without rotating the eigenvectors,
/// `Sigma' = V min(Lambda, max) V^T`: the matrix form of TK19 eq. 1's `min(2 lambda, kappa)`.
/// As in Rust: `max P_max + lambda_min P_min` with the spectral projectors (no eigenvector
/// formed, every term non-negative) when only `lambda_max` exceeds the bound, `max I` when
/// both do; the matrix is scaled to unit size first. A negative `max_eig` gives [`zero`].
fn clamp_eigenvalues(c: Covariance, max_eig: f32) -> Covariance {
    if !(max_eig >= 0.0) {
        return zero();
    }
    let scale = max(max(abs(c.s_xx), abs(c.s_yy)), abs(c.s_xy));
    if scale <= 0.0 {
        return c;
    }
    let a = c.s_xx / scale;
    let b = c.s_xy / scale;
    let e = c.s_yy / scale;
    let d = 0.5 * (a - e);
    let r = sqrt(d * d + b * b);
    let lmax = (0.5 * (a + e) + r) * scale;
    if lmax <= max_eig {
        return c;
    }
    let lmin = max(c.det / lmax, 0.0);
    if lmin >= max_eig || r < 1e-18 {
        return Covariance(max_eig, 0.0, max_eig, max_eig * max_eig);
    }
    let p = r + abs(d);
    let q = select(0.0, b * b / p, p > 0.0);
    let ee = select(vec2<f32>(q, p), vec2<f32>(p, q), d >= 0.0);
    let inv = 1.0 / (2.0 * r);
    let p11 = ee.x * inv;
    let p12 = b * inv;
    let p22 = ee.y * inv;
    return Covariance(
        max_eig * p11 + lmin * p22,
        (max_eig - lmin) * p12,
        max_eig * p22 + lmin * p11,
        max_eig * lmin,
    );
}

/// A finite, positive semi-definite covariance with eigenvalues at most `KERNEL_MAX`. A
/// covariance with non-negative variances and a non-negative (carried) determinant is PSD
/// and kept as it is: testing `s_xy^2 <= s_xx s_yy` in f32 instead would misjudge the
/// nearly singular kernels of elongated footprints by rounding, and recomputing their
/// determinant would cancel. Otherwise negative variances are raised to 0 and `|s_xy|`
/// lowered to `sqrt(s_xx s_yy)` (the nearest PSD matrix with the same diagonal, determinant
/// 0). An infinite entry (where the driver keeps infinities) gives the widest kernel
/// `KERNEL_MAX I`; otherwise a NaN entry counts as 0 (decided on its bits, `math::nan_to_zero`;
/// a NaN determinant is recomputed from the entries). Then [`clamp_eigenvalues`] with
/// `KERNEL_MAX`. As the Rust `Covariance::sanitized`.
fn sanitized(c_in: Covariance) -> Covariance {
    let inf = abs(c_in.s_xx) > math::F32_MAX || abs(c_in.s_xy) > math::F32_MAX || abs(c_in.s_yy) > math::F32_MAX;
    if inf {
        return Covariance(KERNEL_MAX, 0.0, KERNEL_MAX, KERNEL_MAX * KERNEL_MAX);
    }
    var c = Covariance(math::nan_to_zero(c_in.s_xx), math::nan_to_zero(c_in.s_xy), math::nan_to_zero(c_in.s_yy), c_in.det);
    if math::is_nan(c.det) || math::is_nan(c_in.s_xx) || math::is_nan(c_in.s_xy) || math::is_nan(c_in.s_yy) {
        c.det = c.s_xx * c.s_yy - c.s_xy * c.s_xy;
    }
    if c.s_xx >= 0.0 && c.s_yy >= 0.0 && c.det >= 0.0 {
        return clamp_eigenvalues(c, KERNEL_MAX);
    }
    let s_xx = max(c.s_xx, 0.0);
    let s_yy = max(c.s_yy, 0.0);
    let bound = sqrt(s_xx) * sqrt(s_yy);
    let s_xy = clamp(c.s_xy, -bound, bound);
    return clamp_eigenvalues(Covariance(s_xx, s_xy, s_yy, 0.0), KERNEL_MAX);
}
