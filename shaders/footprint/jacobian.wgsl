#define_import_path filtered_ndf::footprint::jacobian

#import filtered_ndf::math

// Jacobians between the three half-vector domains (TK19 supplement section 2, eq. 1-7) and
// the error propagation of TK19 section 3.1, mirroring `src/.../footprint/jacobian.rs`.
// Matrices are the paper's `J[i][j] = d out_i / d in_j` stored column-major (WGSL
// `mat2x2<f32>` like glam's `Mat2`): column `j` is the derivative with respect to input `j`,
// and `J * v` is the paper's product. Spherical changes are the arc lengths `(psi_x, psi_y)`
// along `e_x = (cos theta cos phi, cos theta sin phi, -sin theta)` and
// `e_y = (-sin phi, cos phi, 0)`. Input: `h` is normalised here; a zero `h` is the pole;
// `h_z` is clamped to `HZ_MIN` at constant azimuth; at the pole `phi = 0`.
// (Non-finite input: WGSL lets a driver assume it never occurs.)

/// Smallest `h_z` the Jacobians use (`1 / HZ_MIN^4 = 1e24` stays finite in f32).
const HZ_MIN: f32 = 1e-6;

/// A half vector reduced to what the Jacobians need: the sanitised unit `h` and
/// `(cos phi, sin phi)`.
struct Polar {
    /// The sanitised unit half vector.
    h: vec3<f32>,
    /// `(cos phi, sin phi)` of its azimuth (`(1, 0)` at the pole).
    cs: vec2<f32>,
}

/// Normalise (after scaling by the largest component), take the azimuth from `h_xy` scaled
/// to unit size, clamp `h_z >= HZ_MIN` keeping the azimuth.
fn polar(h_in: vec3<f32>) -> Polar {
    let big = max(max(abs(h_in.x), abs(h_in.y)), abs(h_in.z));
    if big <= 0.0 {
        return Polar(vec3<f32>(0.0, 0.0, 1.0), vec2<f32>(1.0, 0.0));
    }
    let h0 = h_in / big;
    let h = h0 / length(h0);
    let qs = max(abs(h.x), abs(h.y));
    var cs = vec2<f32>(1.0, 0.0);
    if qs > 0.0 {
        let q = h.xy / qs;
        cs = q / length(q);
    }
    if h.z >= HZ_MIN {
        return Polar(h, cs);
    }
    let st = sqrt(1.0 - HZ_MIN * HZ_MIN);
    return Polar(vec3<f32>(st * cs, HZ_MIN), cs);
}

/// The unit half vector the Jacobians use for input `h` (normalised, zero -> the pole,
/// `h_z >= HZ_MIN` at constant azimuth).
fn sanitize(h: vec3<f32>) -> vec3<f32> {
    return polar(h).h;
}

/// The spherical basis `(e_x, e_y)` at `h` (TK19 supplement eq. 3, columns 1 and 2).
struct SphericalBasis {
    /// `e_x`, along the great circle through `h` and `n`, away from `n`.
    e_x: vec3<f32>,
    /// `e_y = n x h / |n x h|`.
    e_y: vec3<f32>,
}

/// `(e_x, e_y)` at `h`: `e_x = (cos theta cos phi, cos theta sin phi, -sin theta)`,
/// `e_y = (-sin phi, cos phi, 0)`; `(+x, +y)` at the pole.
fn spherical_basis(h: vec3<f32>) -> SphericalBasis {
    let p = polar(h);
    let st = length(p.h.xy);
    return SphericalBasis(
        vec3<f32>(p.h.z * p.cs, -st),
        vec3<f32>(-p.cs.y, p.cs.x, 0.0),
    );
}

/// `(dh . e_x, dh . e_y)` (radians) of a tangent change `dh` of the unit half vector (TK19
/// section 3.1).
fn spherical_components(h: vec3<f32>, dh: vec3<f32>) -> vec2<f32> {
    let b = spherical_basis(h);
    return vec2<f32>(dot(dh, b.e_x), dot(dh, b.e_y));
}

/// `J(o->perp) = [[h_z cos phi, -sin phi], [h_z sin phi, cos phi]]` (TK19 supplement eq. 4),
/// determinant `h_z`; `I` at the pole.
fn sphere_to_projected(h: vec3<f32>) -> mat2x2<f32> {
    let p = polar(h);
    return mat2x2<f32>(p.h.z * p.cs, vec2<f32>(-p.cs.y, p.cs.x));
}

/// `J(perp->par) = -1 / h_z^3 [[h_x^2 + h_z^2, h_x h_y], [h_x h_y, h_y^2 + h_z^2]]` (TK19
/// supplement eq. 6, with `1 - h_y^2` written as `h_x^2 + h_z^2` for accuracy at the
/// horizon); determinant `1 / h_z^4`; `-I` at the pole.
fn projected_to_slope(h_in: vec3<f32>) -> mat2x2<f32> {
    let h = polar(h_in).h;
    let k = -1.0 / (h.z * h.z * h.z);
    let xy = h.x * h.y;
    return mat2x2<f32>(
        vec2<f32>(h.x * h.x + h.z * h.z, xy) * k,
        vec2<f32>(xy, h.y * h.y + h.z * h.z) * k,
    );
}

/// `J(par->perp) = -h_z [[h_y^2 + h_z^2, -h_x h_y], [-h_x h_y, h_x^2 + h_z^2]]`, the inverse
/// of [`projected_to_slope`]; determinant `h_z^4`; `-I` at the pole.
fn slope_to_projected(h_in: vec3<f32>) -> mat2x2<f32> {
    let h = polar(h_in).h;
    let xy = h.x * h.y;
    return mat2x2<f32>(
        vec2<f32>(h.y * h.y + h.z * h.z, -xy) * -h.z,
        vec2<f32>(-xy, h.x * h.x + h.z * h.z) * -h.z,
    );
}

/// `J(o->par) = -1 / h_z^2 [[cos phi, -h_z sin phi], [sin phi, h_z cos phi]]` (TK19
/// supplement eq. 7; section 3.1); determinant `1 / h_z^3`; `-I` at the pole.
fn sphere_to_slope(h: vec3<f32>) -> mat2x2<f32> {
    let p = polar(h);
    let k = -1.0 / (p.h.z * p.h.z);
    return mat2x2<f32>(p.cs * k, vec2<f32>(-p.h.z * p.cs.y, p.h.z * p.cs.x) * k);
}

/// `det J(o->perp) = h_z` (TK19 section 3.2), in `[HZ_MIN, 1]`.
fn det_sphere_to_projected(h: vec3<f32>) -> f32 {
    return polar(h).h.z;
}

/// `det J(perp->par) = 1 / h_z^4`, in `[1, 1e24]`.
fn det_projected_to_slope(h: vec3<f32>) -> f32 {
    let z = polar(h).h.z;
    let z2 = z * z;
    return 1.0 / (z2 * z2);
}

/// `det J(o->par) = 1 / h_z^3` (TK19 section 3.1), in `[1, 1e18]`.
fn det_sphere_to_slope(h: vec3<f32>) -> f32 {
    let z = polar(h).h.z;
    return 1.0 / (z * z * z);
}

/// A spherical error `(eps_x, eps_y)` mapped to the slope domain, `J(o->par) eps` (TK19
/// section 3.1).
fn spherical_to_slope(h: vec3<f32>, e: vec2<f32>) -> vec2<f32> {
    return sphere_to_slope(h) * e;
}

/// The same error mapped to the projected disk, `J(o->perp) eps` (TK19 section 3.2).
fn spherical_to_projected(h: vec3<f32>, e: vec2<f32>) -> vec2<f32> {
    return sphere_to_projected(h) * e;
}
