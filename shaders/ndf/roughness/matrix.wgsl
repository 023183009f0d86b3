#define_import_path filtered_ndf::ndf::roughness::matrix

#import filtered_ndf::math

/// A symmetric positive-definite roughness matrix `A = [[a11, a12], [a12, a22]]` (TK19
/// supplement section 1; Heitz 2014 section 5.4), with the TK19 determinant clamp `tau`
/// (supplement, "Practical Implementation"): the density uses `sqrt(max(det A, tau))` and
/// `A^-1 = adj(A) / max(det A, tau)`; Smith's `Lambda` uses `A` itself.
///
/// **Representation: the eigenbasis.** `A = R diag(l1, l2) R^T` with `R = [e1, e2]`,
/// `e1 = axis`, `e2 = (-axis.y, axis.x)`. Both quadratic forms are then sums of two
/// non-negative squares of the rotated vector. The Rust crate evaluates the matrix form in
/// f64 (an LDL form); WGSL has only f32, where the LDL form (and the entries of `A^-1`)
/// cancel to a relative `cond(A) eps`. In the eigenbasis a rotation error `d theta` changes
/// `s^T A^-1 s` by at most `sqrt(cond A) d theta` relative (first order, from the cross term
/// `2 r1 r2 (1/l1 - 1/l2) d theta`, bounded with `|r_i| <= sqrt(l_i q)`), and the rotated
/// components carry at most 4 ulp of `|s|`, so
///
/// `|d q| / q <= eps (8 + 8 sqrt(cond A)) + (relative error of the eigenvalues)`,
///
/// `eps = 2^-23`, `cond A = l1 / l2`. The eigenvalues come from the constructor:
/// [`from_eigen`] takes them exactly (the way to build a rotated anisotropic material);
/// [`from_entries_det`] takes `det A` from the caller (the filters pass it as a sum of
/// non-negative terms), `l1` is a sum of non-negative terms and `l2 = det / l1`, both within
/// a few ulp; [`from_entries`] forms `det A = a11 a22 - a12^2` in f32, which cancels to a
/// relative `cond(A) eps`: use it only for well-conditioned matrices.
struct RoughnessMatrix {
    /// Unit eigenvector `e1 = (c, s)` of `l1`; `e2 = (-s, c)`.
    axis: vec2<f32>,
    /// Eigenvalues `(l1, l2)` of `A` along `(e1, e2)` (both `> 0`).
    eig: vec2<f32>,
    /// Eigenvalues of the clamped inverse `adj(A) / max(det A, tau)` along `(e1, e2)`:
    /// `(l2, l1) / max(det A, tau)`.
    inv_eig: vec2<f32>,
    /// `sqrt(max(det A, tau))`.
    sqrt_det: f32,
}

/// `A = R diag(alpha_x^2, alpha_y^2) R^T` with `R = [axis, perp(axis)]` for a unit `axis`
/// (the tangent-space direction of `alpha_x`), no determinant clamp: a rotated anisotropic
/// material. `alpha` is not clamped (the caller keeps it in `[ALPHA_MIN, ALPHA_MAX]`).
fn from_eigen(axis: vec2<f32>, alpha: vec2<f32>) -> RoughnessMatrix {
    let l = alpha * alpha;
    return RoughnessMatrix(axis, l, 1.0 / l, alpha.x * alpha.y);
}

/// The eigen-decomposition of `A` from its entries and its determinant `det` (computed by
/// the caller without cancellation, e.g. as a sum of non-negative terms), with the
/// determinant clamp `tau >= 0` (0: none). The caller guarantees `a11 > 0`, `a22 > 0` and
/// `max(det, tau) > 0` (the Rust `from_entries_det_clamped`; no checks).
///
/// `l1 = (a11 + a22) / 2 + hypot((a11 - a22) / 2, a12)` (no cancellation), `l2 = det / l1`;
/// the eigenvector of `l1` from whichever row of `A - l2 I` avoids cancellation. Entries up
/// to `1e18` in magnitude (the squares stay finite).
fn from_entries_det(a11: f32, a12: f32, a22: f32, det: f32, tau: f32) -> RoughnessMatrix {
    let half_diff = 0.5 * (a11 - a22);
    let rad = sqrt(half_diff * half_diff + a12 * a12);
    let l1 = 0.5 * (a11 + a22) + rad;
    let l2 = det / l1;
    // e1 from the row whose diagonal part does not cancel: (rad + |d|, a12) when a11 >= a22,
    // else (a12, rad + |d|); any axis when A is isotropic.
    let big = rad + abs(half_diff);
    var v = select(vec2<f32>(big, a12), vec2<f32>(a12, big), half_diff < 0.0);
    if big <= 0.0 {
        v = vec2<f32>(1.0, 0.0);
    }
    let axis = v / length(v);
    let c = max(det, tau);
    return RoughnessMatrix(axis, vec2<f32>(l1, l2), vec2<f32>(l2, l1) / c, sqrt(c));
}

/// [`from_entries_det`] with `det = a11 a22 - a12^2` formed here in f32 (relative error up
/// to `cond(A) eps`, see the type docs) and no clamp. For well-conditioned matrices.
fn from_entries(a11: f32, a12: f32, a22: f32) -> RoughnessMatrix {
    return from_entries_det(a11, a12, a22, a11 * a22 - a12 * a12, 0.0);
}

/// `v` in the eigenbasis: `(v . e1, v . e2)`.
fn rotate(r: RoughnessMatrix, v: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(r.axis.x * v.x + r.axis.y * v.y, r.axis.x * v.y - r.axis.y * v.x);
}

/// `s^T A^-1 s` with `A^-1 = adj(A) / max(det A, tau)`: `u1^2 w1 + u2^2 w2` for the rotated
/// `u` and the clamped inverse eigenvalues `w` (error bound in the type docs).
fn inv_quadratic(r: RoughnessMatrix, s: vec2<f32>) -> f32 {
    let u = rotate(r, s);
    return dot(u * u, r.inv_eig);
}

/// `w^T A w = u1^2 l1 + u2^2 l2` (Smith's projected roughness; never sees the clamp).
fn quadratic(r: RoughnessMatrix, w: vec2<f32>) -> f32 {
    let u = rotate(r, w);
    return dot(u * u, r.eig);
}

/// `sqrt(max(det A, tau))`.
fn sqrt_det(r: RoughnessMatrix) -> f32 {
    return r.sqrt_det;
}

/// The entries `(a11, a12, a22)` of `A`: `l1 e1 e1^T + l2 e2 e2^T` (sums of non-negative
/// terms on the diagonal; within a few ulp of `l1`).
fn entries(r: RoughnessMatrix) -> vec3<f32> {
    let c = r.axis.x;
    let s = r.axis.y;
    let l = r.eig;
    return vec3<f32>(l.x * c * c + l.y * s * s, (l.x - l.y) * c * s, l.x * s * s + l.y * c * c);
}

/// `det A = l1 l2` (without the clamp).
fn determinant(r: RoughnessMatrix) -> f32 {
    return r.eig.x * r.eig.y;
}
