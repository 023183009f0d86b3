#define_import_path filtered_ndf::footprint::slope

#import filtered_ndf::math

// The three half-vector domains and the maps between them (TK19 supplement eq. 1-5),
// mirroring `src/.../footprint/slope.rs`: the sphere (unit `h`, tangent frame, `z` = shading
// normal), the projected disk `p = h_xy` (TK19 section 3.2) and the slope plane
// `s = -h_xy / h_z` (TK19 supplement eq. 5; KHPL16 writes `h_xy / h_z`, which flips only
// signs of derivatives). Every map is defined on the upper hemisphere; outside it the
// functions return a finite answer, as in Rust.

/// Slope of a unit vector, `s = -h_xy / h_z` (TK19 supplement eq. 5). For `h_z <= 0` the
/// slope of `h` with `h_z` raised to the smallest normal f32 (far in every NDF's tail),
/// clamped to `+-F32_MAX`. Within 2.5 ulp per component.
fn slope_from_sphere(h: vec3<f32>) -> vec2<f32> {
    let z = max(h.z, math::F32_MIN_POSITIVE);
    return clamp(-h.xy / z, vec2<f32>(-math::F32_MAX), vec2<f32>(math::F32_MAX));
}

/// Unit vector of a slope, `h = (-s_x, -s_y, 1) / sqrt(1 + |s|^2)` (the inverse of
/// [`slope_from_sphere`]). The vector is first scaled by `1 / max(1, |s_x|, |s_y|)`, so a
/// huge slope tends to the horizon direction `-s / |s|` without overflow. Within 6 ulp per
/// component (of the largest component).
fn sphere_from_slope(s: vec2<f32>) -> vec3<f32> {
    let k = max(max(abs(s.x), abs(s.y)), 1.0);
    let v = vec3<f32>(-s / k, 1.0 / k);
    return v / length(v);
}

/// Projection on the unit disk, `p = (h_x, h_y)` (TK19 section 3.2). Exact.
fn projected_from_sphere(h: vec3<f32>) -> vec2<f32> {
    return h.xy;
}

/// The upper-hemisphere unit vector over a disk point, `(p_x, p_y, sqrt(1 - |p|^2))`;
/// points on or outside the unit circle map to the horizon (`p` rescaled to unit length).
/// `h_z` carries the cancellation of `1 - |p|^2` near the rim (a property of the map).
fn sphere_from_projected(p: vec2<f32>) -> vec3<f32> {
    let r2 = dot(p, p);
    if r2 < 1.0 {
        return vec3<f32>(p, sqrt(1.0 - r2));
    }
    let q = p / max(max(abs(p.x), abs(p.y)), math::F32_MIN_POSITIVE);
    return vec3<f32>(q / length(q), 0.0);
}

/// Slope of a disk point, `s = -p / sqrt(1 - |p|^2)` (TK19 supplement eq. 5); points on or
/// outside the unit circle as in [`slope_from_sphere`].
fn slope_from_projected(p: vec2<f32>) -> vec2<f32> {
    return slope_from_sphere(sphere_from_projected(p));
}

/// Disk point of a slope, `p = -s / sqrt(1 + |s|^2)`.
fn projected_from_slope(s: vec2<f32>) -> vec2<f32> {
    return projected_from_sphere(sphere_from_slope(s));
}
