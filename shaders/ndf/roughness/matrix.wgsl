#define_import_path filtered_ndf::ndf::roughness::matrix

#import filtered_ndf::math

/// A symmetric positive-definite roughness matrix `A = [[a11, a12], [a12, a22]]` (TK19
/// supplement section 1; Heitz 2014 section 5.4) with the TK19 determinant clamp `tau`
/// (supplement, "Practical Implementation"; `det_clamp` in the Rust API), mirroring
/// `RoughnessMatrix` of `src/.../ndf/roughness/matrix.rs`.
///
/// **The determinant clamp: one clamped matrix.** Every function (`D`, `P22`, `Lambda`, the
/// sampler's warp) evaluates one matrix `A_c`: `A` itself when `det A >= tau`, else
/// `A_c = A + t I` with `t > 0` the root of `det(A + t I) = tau`,
/// `t = (tau - det A) / (tr(A) / 2 + sqrt(tr(A)^2 / 4 + tau - det A))` (no cancellation). So
/// `det A_c = max(det A, tau)` and the density is normalised for `A_c` (TK19's literal
/// `sqrt(max(det A, tau))` with `A^-1 = adj(A) / max(det A, tau)` is not: its integral is
/// `sqrt(tau / det A)`). `A_c - A = t I` shares `A`'s eigenvectors, so in the eigenbasis
/// `A_c = R diag(l1 + t, l2 + t) R^T`, and with `(l1 + t)(l2 + t) = tau` the clamped minor
/// eigenvalue is `tau / (l1 + t)`, a quotient of positive numbers (no cancellation whatever
/// `t`). Filters add their kernel to `A` as given ([`entries`], [`determinant`]) and clamp the
/// result with `det A_c` ([`clamped_det`]), as the Rust filters do.
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
/// `|d q| / q <= eps (8 + 8 sqrt(cond A_c)) + (relative error of the eigenvalues)`,
///
/// `eps = 2^-23`, `cond A_c = (l1 + t) / (l2 + t)`. The eigenvalues come from the constructor:
/// [`from_eigen`] takes them exactly (the way to build a rotated anisotropic material);
/// [`from_entries_det`] takes `det A` from the caller (the filters pass it as a sum of
/// non-negative terms), `l1` is a sum of non-negative terms and `l2 = det / l1`, both within
/// a few ulp; [`from_entries`] forms `det A = a11 a22 - a12^2` in f32, which cancels to a
/// relative `cond(A) eps`: use it only for well-conditioned matrices. The clamp adds at most
/// 5 ulp to the clamped eigenvalues (`t` within 4 ulp of its own value; `l1 + t` a sum of
/// positive terms; `tau / (l1 + t)` one division).
///
/// NaN: none of these functions tests for NaN (WGSL lets a driver assume none occurs).
struct RoughnessMatrix {
    /// Unit eigenvector `e1 = (c, s)` of `l1`; `e2 = (-s, c)`.
    axis: vec2<f32>,
    /// Eigenvalues `(l1, l2)` of `A` as given, along `(e1, e2)` (both `> 0`).
    eig: vec2<f32>,
    /// Eigenvalues of `A_c`: `(l1 + t, tau / (l1 + t))`, or `eig` when the clamp is inactive.
    eig_c: vec2<f32>,
    /// Eigenvalues of `A_c^-1` along `(e1, e2)`: `1 / eig_c`.
    inv_eig: vec2<f32>,
    /// `sqrt(det A_c) = sqrt(max(det A, tau))`.
    sqrt_det: f32,
    /// `det A` as the constructor had it (`l1 l2`, or the caller's sum of non-negative terms).
    det: f32,
    /// The clamp `tau` (0: none).
    tau: f32,
}

/// `A = R diag(alpha_x^2, alpha_y^2) R^T` with `R = [axis, perp(axis)]` for a unit `axis`
/// (the tangent-space direction of `alpha_x`), no determinant clamp: a rotated anisotropic
/// material. `alpha` is not clamped (the caller keeps it in `[ALPHA_MIN, ALPHA_MAX]`).
fn from_eigen(axis: vec2<f32>, alpha: vec2<f32>) -> RoughnessMatrix {
    let l = alpha * alpha;
    return RoughnessMatrix(axis, l, l, 1.0 / l, alpha.x * alpha.y, l.x * l.y, 0.0);
}

/// The clamped eigenvalues `(l1 + t, tau / (l1 + t))` of `A_c` for `A`'s eigenvalues `l`
/// (`l1 >= l2`), `det = l1 l2` as the caller has it and the clamp `tau`; `l` itself when
/// `det >= tau` (type docs).
fn clamped_eigenvalues(l: vec2<f32>, det: f32, tau: f32) -> vec2<f32> {
    if det >= tau {
        return l;
    }
    let h = 0.5 * (l.x + l.y);
    let gap = tau - det;
    let t = gap / (h + sqrt(h * h + gap));
    let l1 = l.x + t;
    return vec2<f32>(l1, tau / l1);
}

/// A matrix from its eigenbasis, its eigenvalues `l` (`l1 >= l2`, `l2 >= 0`), the
/// determinant `det` of `A` as the caller has it (`l1 l2`, or a sum of non-negative terms) and
/// the clamp `tau >= 0` (0: none).
fn from_eigenbasis(axis: vec2<f32>, l: vec2<f32>, det: f32, tau: f32) -> RoughnessMatrix {
    let lc = clamped_eigenvalues(l, det, tau);
    return RoughnessMatrix(axis, l, lc, 1.0 / lc, sqrt(max(det, tau)), det, tau);
}

/// The eigen-decomposition of `A` from its entries and its determinant `det` (computed by
/// the caller without cancellation, e.g. as a sum of non-negative terms), with the
/// determinant clamp `tau >= 0` (0: none; the type docs for `A_c`). The caller guarantees
/// `a11 > 0`, `a22 > 0` and `max(det, tau) > 0` (the Rust `from_entries`; no checks).
///
/// `l1 = (a11 + a22) / 2 + hypot((a11 - a22) / 2, a12)` (no cancellation), `l2 = det / l1`;
/// the eigenvector of `l1` from whichever row of `A - l2 I` avoids cancellation. Entries up
/// to `1e18` in magnitude (the squares stay finite).
fn from_entries_det(a11: f32, a12: f32, a22: f32, det: f32, tau: f32) -> RoughnessMatrix {
    let half_diff = 0.5 * (a11 - a22);
    let rad = sqrt(half_diff * half_diff + a12 * a12);
    let l1 = 0.5 * (a11 + a22) + rad;
    let l2 = max(det, 0.0) / l1;
    // e1 from the row whose diagonal part does not cancel: (rad + |d|, a12) when a11 >= a22,
    // else (a12, rad + |d|); any axis when A is isotropic.
    let big = rad + abs(half_diff);
    var v = select(vec2<f32>(big, a12), vec2<f32>(a12, big), half_diff < 0.0);
    if big <= 0.0 {
        v = vec2<f32>(1.0, 0.0);
    }
    let axis = v / length(v);
    return from_eigenbasis(axis, vec2<f32>(l1, l2), det, tau);
}

/// [`from_entries_det`] with `det = a11 a22 - a12^2` formed here in f32 (relative error up
/// to `cond(A) eps`, see the type docs) and no clamp. For well-conditioned matrices.
fn from_entries(a11: f32, a12: f32, a22: f32) -> RoughnessMatrix {
    return from_entries_det(a11, a12, a22, a11 * a22 - a12 * a12, 0.0);
}

/// The same matrix `A` evaluated with the determinant clamp `tau = det_clamp` (the Rust
/// `with_det_clamp`; `<= 0`: none): `A_c` recomputed from `A`'s eigenvalues.
fn with_det_clamp(r: RoughnessMatrix, det_clamp: f32) -> RoughnessMatrix {
    return from_eigenbasis(r.axis, r.eig, r.det, max(det_clamp, 0.0));
}

/// `v` in the eigenbasis: `(v . e1, v . e2)`.
fn rotate(r: RoughnessMatrix, v: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(r.axis.x * v.x + r.axis.y * v.y, r.axis.x * v.y - r.axis.y * v.x);
}

/// `s^T A_c^-1 s = u1^2 / (l1 + t) + u2^2 / (l2 + t)` for the rotated `u` (error bound in the
/// type docs).
fn inv_quadratic(r: RoughnessMatrix, s: vec2<f32>) -> f32 {
    let u = rotate(r, s);
    return dot(u * u, r.inv_eig);
}

/// `w^T A_c w = u1^2 (l1 + t) + u2^2 (l2 + t)` (Smith's projected roughness of the matrix the
/// density evaluates).
fn quadratic(r: RoughnessMatrix, w: vec2<f32>) -> f32 {
    let u = rotate(r, w);
    return dot(u * u, r.eig_c);
}

/// `sqrt(det A_c) = sqrt(max(det A, tau))`.
fn sqrt_det(r: RoughnessMatrix) -> f32 {
    return r.sqrt_det;
}

/// The entries `(a11, a12, a22)` of the matrix with eigenvalues `l` in `r`'s eigenbasis: sums
/// of non-negative terms on the diagonal (within a few ulp of `l1`).
fn entries_of(r: RoughnessMatrix, l: vec2<f32>) -> vec3<f32> {
    let c = r.axis.x;
    let s = r.axis.y;
    return vec3<f32>(l.x * c * c + l.y * s * s, (l.x - l.y) * c * s, l.x * s * s + l.y * c * c);
}

/// The entries `(a11, a12, a22)` of `A` as given: what a filter adds its kernel to.
fn entries(r: RoughnessMatrix) -> vec3<f32> {
    return entries_of(r, r.eig);
}

/// The entries of `A_c`, the matrix every function evaluates (`A`'s own when the clamp is
/// inactive).
fn clamped_entries(r: RoughnessMatrix) -> vec3<f32> {
    return entries_of(r, r.eig_c);
}

/// `det A` (without the clamp), as the constructor had it.
fn determinant(r: RoughnessMatrix) -> f32 {
    return r.det;
}

/// `det A_c = max(det A, tau)`: the clamp a filter of this lobe uses (the Rust
/// `clamped_det`, `lobe_det`), so that a kernel too small to change the entries meets the
/// clamp with equality (and returns the lobe unchanged).
fn clamped_det(r: RoughnessMatrix) -> f32 {
    return max(r.det, r.tau);
}

/// The lobe's own clamp: `det A_c = tau` where the clamp is active (`tau > det A`), else 0
/// (the Rust `own_det_clamp`). Every filter clamps with at least this, so that filtering never
/// drops a clamped matrix's clamp (its entries may be far sharper than `A_c`).
fn own_det_clamp(r: RoughnessMatrix) -> f32 {
    return select(0.0, r.tau, r.tau > r.det);
}
