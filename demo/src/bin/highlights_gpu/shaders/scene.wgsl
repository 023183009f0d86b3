#define_import_path highlights::scene

// The demonstration's scenes on the GPU: the same analytic surfaces as
// `demo/src/scene.rs` (wavy water with its level of detail and five spheres; or the bumpy
// spheres of `demo/src/bumpy.rs`; one point light), with the parameters of that one
// description uploaded as `Scene` (see `demo/src/bin/highlights_gpu/frame.rs`). Each function
// mirrors the Rust one of the same name.

/// Waves and spheres (the sizes of `scene.rs`).
const N_WAVES: u32 = 8u;
const N_SPHERES: u32 = 5u;
/// Wavelength, in pixel footprints, under which a wave starts to fade (`LOD_PIXELS`).
const LOD_PIXELS: f32 = 2.0;
/// The bumpy spheres' march: its minimum step relative to `t` (`BUMPY_MIN_STEP`).
const BUMPY_MIN_STEP: f32 = 4e-4;
/// Visibility codes (`visibility.z`): the sky; the water is object 0, sphere `i` is `i + 1`.
const SKY: f32 = -1.0;

struct Scene {
    /// Eye position (xyz) and the angle one pixel subtends (w), for the water's level of
    /// detail.
    eye: vec4<f32>,
    /// Unnormalised ray direction through the image corner (0, 0) and its change per pixel
    /// step in x and y (the pinhole camera of `camera.rs`).
    corner: vec4<f32>,
    step_x: vec4<f32>,
    step_y: vec4<f32>,
    /// Light position (xyz), normal-incidence Fresnel reflectance `f0` (w).
    light_position: vec4<f32>,
    /// Light intensity (rgb), base roughness `alpha` (w).
    light_intensity: vec4<f32>,
    /// Ambient radiance (rgb).
    ambient: vec4<f32>,
    /// Water: slab half-height `bound`, `slope_bound`, `half_width`, `z_near`.
    water: vec4<f32>,
    /// Water: `z_far` (x); albedo (yzw).
    water_far_albedo: vec4<f32>,
    /// Per wave: `(k_x, k_z, amplitude, phase)` and `(wavelength, -, -, -)`.
    waves: array<vec4<f32>, 8>,
    wavelengths: array<vec4<f32>, 8>,
    /// Per sphere: centre (xyz), radius (w); albedo (rgb). In the bumpy scene, the bumpy
    /// spheres' base spheres.
    spheres: array<vec4<f32>, 5>,
    sphere_albedo: array<vec4<f32>, 5>,
    /// The bumpy scene (x = 1; 0: the water scene), its number of spheres (y), the bumps'
    /// `sum a_i` (z) and the field's Lipschitz constant `L` (w).
    bumpy: vec4<f32>,
    /// Per bump wave: `k` (xyz), amplitude (w); the phases, four per vector.
    bumps: array<vec4<f32>, 8>,
    bump_phases: array<vec4<f32>, 2>,
    /// The background's horizon and zenith radiance (rgb).
    sky: array<vec4<f32>, 2>,
}

@group(0) @binding(0) var<uniform> scene: Scene;

/// One shading point of an object (also where the object is hidden or missed: see
/// `water_surface`, `sphere_surface`).
struct Surface {
    position: vec3<f32>,
    /// Unit shading normal (world).
    normal: vec3<f32>,
    albedo: vec3<f32>,
    /// Isotropic roughness at the point (the water adds the slope variance its level of
    /// detail removed).
    alpha: f32,
}

/// The full-screen triangle's clip-space vertex `i` (0, 1, 2): every draw here covers the
/// image (the spheres' draws are then cut by their scissor rectangles).
fn fullscreen(i: u32) -> vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

/// The unit direction of the primary ray through the image point `pixel` (pixel centres at
/// `i + 0.5`): `Camera::ray`.
fn ray_dir(pixel: vec2<f32>) -> vec3<f32> {
    return normalize(scene.corner.xyz + pixel.x * scene.step_x.xyz + pixel.y * scene.step_y.xyz);
}

/// The background's gradient from horizon to zenith: `Scene::sky`.
fn sky(dir: vec3<f32>) -> vec3<f32> {
    let k = clamp(dir.y, 0.0, 1.0);
    return mix(scene.sky[0].xyz, scene.sky[1].xyz, sqrt(k));
}

/// `(sin x, cos x)` with the reduction of `fast_sin` (Cody-Waite by `pi`) and odd / even
/// Taylor polynomials on `[-pi/2, pi/2]`: the same values on every driver (WGSL's `sin` may
/// err by `2^-11`).
fn fast_sincos(x: f32) -> vec2<f32> {
    let k = round(x * 0.318309886);
    let r = (x - k * 3.140625) - k * 9.676536e-4;
    let rr = r * r;
    var p = -1.0 / 39916800.0;
    p = p * rr + 1.0 / 362880.0;
    p = p * rr - 1.0 / 5040.0;
    p = p * rr + 1.0 / 120.0;
    p = p * rr - 1.0 / 6.0;
    let s = r + r * rr * p;
    var q = 1.0 / 479001600.0;
    q = q * rr - 1.0 / 3628800.0;
    q = q * rr + 1.0 / 40320.0;
    q = q * rr - 1.0 / 720.0;
    q = q * rr + 1.0 / 24.0;
    q = q * rr - 0.5;
    let c = 1.0 + rr * q;
    let odd = (i32(k) & 1) != 0;
    return select(vec2<f32>(s, c), vec2<f32>(-s, -c), odd);
}

/// `1 / len`, the inverse pixel footprint on the water at `(x, z)`: `Water::fades`.
fn inv_footprint(x: f32, z: f32) -> f32 {
    let e = scene.eye.xyz;
    let height = max(e.y, 0.5);
    let dist_sq = (x - e.x) * (x - e.x) + (z - e.z) * (z - e.z);
    return 1.0 / (scene.eye.w * (dist_sq + height * height) / height);
}

/// The amplitude factor of wave `i` at inverse footprint `inv_len`.
fn fade(i: u32, inv_len: f32) -> f32 {
    let pixels = scene.wavelengths[i].x * inv_len;
    let t = clamp((pixels - 0.5 * LOD_PIXELS) / (0.5 * LOD_PIXELS), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

/// The height field `h(x, z)`: `Water::height`.
fn height(x: f32, z: f32) -> f32 {
    let inv_len = inv_footprint(x, z);
    var h = 0.0;
    for (var i = 0u; i < N_WAVES; i++) {
        let w = scene.waves[i];
        h += fade(i, inv_len) * w.z * fast_sincos(w.x * x + w.y * z + w.w).x;
    }
    return h;
}

/// `(h_x, h_z)` and the slope variance the fade removed (`Water::derivatives`).
fn slopes(x: f32, z: f32) -> vec3<f32> {
    let inv_len = inv_footprint(x, z);
    var d = vec3<f32>(0.0);
    for (var i = 0u; i < N_WAVES; i++) {
        let w = scene.waves[i];
        let f = fade(i, inv_len);
        let c = fast_sincos(w.x * x + w.y * z + w.w).y;
        let a = f * w.z;
        d.x += a * w.x * c;
        d.y += a * w.y * c;
        let slope = w.z * length(w.xy);
        d.z += (1.0 - f * f) * slope * slope * 0.5;
    }
    return d;
}

/// Whether `p` lies on the water tile: `Water::inside`.
fn inside(p: vec3<f32>) -> bool {
    return abs(p.x) <= scene.water.z && p.z <= scene.water.w && p.z >= scene.water_far_albedo.x;
}

/// The first crossing of the ray `o + t d` with the height field before `t_max`, or `-1`:
/// `Water::intersect` (half-Lipschitz march, six bisections, one secant step), without the
/// tile test.
fn water_crossing(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> f32 {
    if abs(d.y) < 1e-6 {
        return -1.0;
    }
    let bound = scene.water.x;
    let t_top = (bound - o.y) / d.y;
    let t_bottom = (-bound - o.y) / d.y;
    var t = max(min(t_top, t_bottom), 0.0);
    let t_end = min(max(t_top, t_bottom), t_max);
    let lip = abs(d.y) + 0.5 * scene.water.y * sqrt(d.x * d.x + d.z * d.z);
    var p = o + t * d;
    var f_cur = p.y - height(p.x, p.z);
    if f_cur < 0.0 {
        return -1.0;
    }
    for (var i = 0; i < 400; i++) {
        if t >= t_end {
            return -1.0;
        }
        let step = max(max(f_cur / lip, 2e-3 * t), 1e-4);
        let t_next = min(t + step, t_end);
        p = o + t_next * d;
        let f_next = p.y - height(p.x, p.z);
        if f_next < 0.0 {
            var lo = t;
            var hi = t_next;
            var flo = f_cur;
            var fhi = f_next;
            for (var j = 0; j < 6; j++) {
                let mid = 0.5 * (lo + hi);
                let pm = o + mid * d;
                let fm = pm.y - height(pm.x, pm.z);
                if fm < 0.0 {
                    hi = mid;
                    fhi = fm;
                } else {
                    lo = mid;
                    flo = fm;
                }
            }
            return lo + (hi - lo) * flo / (flo - fhi);
        }
        t = t_next;
        f_cur = f_next;
    }
    return -1.0;
}

/// The water's shading point at distance `t` along `d` from the eye: `Water::hit_at`.
fn water_at(d: vec3<f32>, t: f32) -> Surface {
    let p = scene.eye.xyz + t * d;
    let s = slopes(p.x, p.z);
    let n = normalize(vec3<f32>(-s.x, 1.0, -s.y));
    let alpha = scene.light_intensity.w;
    return Surface(p, n, scene.water_far_albedo.yzw, sqrt(alpha * alpha + s.z));
}

/// The distance along `d` at which the water layer is shaded: the crossing where there is
/// one, else where the ray meets the mean plane (rays at or above the horizon: 1600 m out).
/// A pixel that sees something else still evaluates the water there, as a rasteriser's
/// helper lanes evaluate a triangle's attributes beyond its edge, so that the quad
/// derivatives of the water's visible pixels are differences of the water alone.
fn water_layer_t(d: vec3<f32>, crossing: f32) -> f32 {
    return select(scene.eye.y / max(-d.y, 1e-3), crossing, crossing >= 0.0);
}

/// The nearer ray parameter of sphere `i`, or `-1`: `Sphere::intersect`.
fn sphere_t(i: u32, o: vec3<f32>, d: vec3<f32>) -> f32 {
    let s = scene.spheres[i];
    let oc = o - s.xyz;
    let b = dot(oc, d);
    let c = dot(oc, oc) - s.w * s.w;
    let disc = b * b - c;
    if disc < 0.0 {
        return -1.0;
    }
    let sq = sqrt(disc);
    let t = select(-b + sq, -b - sq, -b - sq > 1e-4);
    return select(-1.0, t, t > 1e-4);
}

/// Sphere `i`'s shading point along `d`; where the ray misses it, the point of the sphere
/// nearest the ray (the surface continued past its silhouette for the quad's helper lanes).
fn sphere_surface(i: u32, d: vec3<f32>) -> Surface {
    let s = scene.spheres[i];
    let o = scene.eye.xyz;
    let t = sphere_t(i, o, d);
    var p = o + t * d;
    if t < 0.0 {
        let q = o + dot(s.xyz - o, d) * d;
        p = s.xyz + s.w * normalize(q - s.xyz);
    }
    let n = (p - s.xyz) / s.w;
    return Surface(p, n, scene.sphere_albedo[i].xyz, scene.light_intensity.w);
}

/// Whether this is the bumpy scene.
fn is_bumpy() -> bool {
    return scene.bumpy.x > 0.5;
}

/// `F(q)` of the bumpy sphere of base radius `radius`: `Bumps::field`.
fn bumpy_field(radius: f32, q: vec3<f32>) -> f32 {
    var h = 0.0;
    for (var i = 0u; i < N_WAVES; i++) {
        let w = scene.bumps[i];
        h += w.w * fast_sincos(dot(w.xyz, q) + scene.bump_phases[i / 4u][i % 4u]).x;
    }
    return length(q) - radius - h;
}

/// The unit normal `grad F / |grad F|` at `q`: `Bumps::normal_and_shape`.
fn bumpy_normal(q: vec3<f32>) -> vec3<f32> {
    var g = normalize(q);
    for (var i = 0u; i < N_WAVES; i++) {
        let w = scene.bumps[i];
        g -= w.xyz * (w.w * fast_sincos(dot(w.xyz, q) + scene.bump_phases[i / 4u][i % 4u]).y);
    }
    return normalize(g);
}

/// The first crossing of the ray `o + t d` with bumpy sphere `i` before `t_max`, or `-1`:
/// `Bumps::crossing` (steps of `max(F / L, BUMPY_MIN_STEP t)` in the shell, six bisections,
/// one secant step).
fn bumpy_t(i: u32, o: vec3<f32>, d: vec3<f32>, t_max: f32) -> f32 {
    let s = scene.spheres[i];
    let oc = o - s.xyz;
    let outer = s.w + scene.bumpy.z;
    let b = dot(oc, d);
    let disc = b * b - (dot(oc, oc) - outer * outer);
    if disc < 0.0 {
        return -1.0;
    }
    let sq = sqrt(disc);
    var t = max(-b - sq, 0.0);
    let t_end = min(-b + sq, t_max);
    if t_end <= t {
        return -1.0;
    }
    var f_cur = bumpy_field(s.w, oc + t * d);
    if f_cur < 0.0 {
        return -1.0;
    }
    for (var k = 0; k < 400; k++) {
        if t >= t_end {
            return -1.0;
        }
        let step = max(max(f_cur / scene.bumpy.w, BUMPY_MIN_STEP * t), 1e-5);
        let t_next = min(t + step, t_end);
        let f_next = bumpy_field(s.w, oc + t_next * d);
        if f_next < 0.0 {
            var lo = t;
            var hi = t_next;
            var flo = f_cur;
            var fhi = f_next;
            for (var j = 0; j < 6; j++) {
                let mid = 0.5 * (lo + hi);
                let fm = bumpy_field(s.w, oc + mid * d);
                if fm < 0.0 {
                    hi = mid;
                    fhi = fm;
                } else {
                    lo = mid;
                    flo = fm;
                }
            }
            return lo + (hi - lo) * flo / (flo - fhi);
        }
        t = t_next;
        f_cur = f_next;
    }
    return -1.0;
}

/// Bumpy sphere `i`'s shading point along `d`; where the ray misses it, the point of the base
/// sphere nearest the ray with the field's normal there (the surface continued past its
/// silhouette for the quad's helper lanes).
fn bumpy_surface(i: u32, d: vec3<f32>) -> Surface {
    let s = scene.spheres[i];
    let o = scene.eye.xyz;
    let t = bumpy_t(i, o, d, 3.4e38);
    var p = o + t * d;
    if t < 0.0 {
        let q = o + dot(s.xyz - o, d) * d;
        p = s.xyz + s.w * normalize(q - s.xyz);
    }
    return Surface(p, bumpy_normal(p - s.xyz), scene.sphere_albedo[i].xyz, scene.light_intensity.w);
}

/// Object `index`'s shading point along `d` (0: the water, at the water layer's distance
/// `layer_t` from the visibility pass; `1 + i`: sphere `i`, or bumpy sphere `i` in the bumpy
/// scene, whose object 0 is the sky alone: a placeholder point, never shown).
fn object_surface(index: u32, d: vec3<f32>, layer_t: f32) -> Surface {
    if is_bumpy() {
        if index == 0u {
            return Surface(scene.eye.xyz + d, vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(0.0), scene.light_intensity.w);
        }
        return bumpy_surface(index - 1u, d);
    }
    if index == 0u {
        return water_at(d, layer_t);
    }
    return sphere_surface(index - 1u, d);
}

/// What the pixel sees, as the CPU demo's `Scene::intersect` decides it:
/// `(water layer t, -, object code, -)` with the object code `SKY`, 0 (water) or
/// `1 + sphere`.
fn visibility(d: vec3<f32>) -> vec4<f32> {
    let o = scene.eye.xyz;
    var best = 3.4e38;
    var object = SKY;
    if is_bumpy() {
        for (var i = 0u; i < u32(scene.bumpy.y); i++) {
            let t = bumpy_t(i, o, d, best);
            if t >= 0.0 {
                best = t;
                object = f32(i + 1u);
            }
        }
        return vec4<f32>(0.0, 0.0, object, 0.0);
    }
    for (var i = 0u; i < N_SPHERES; i++) {
        let t = sphere_t(i, o, d);
        if t > 0.0 && t < best {
            best = t;
            object = f32(i + 1u);
        }
    }
    // The water test first marches up to the nearest sphere (as the CPU does); the water
    // layer itself is marched without that limit where it is hidden.
    let near = water_crossing(o, d, best);
    var crossing = near;
    if near >= 0.0 && inside(o + near * d) {
        object = 0.0;
    } else if near < 0.0 && object > 0.0 {
        crossing = water_crossing(o, d, 3.4e38);
    }
    return vec4<f32>(water_layer_t(d, crossing), 0.0, object, 0.0);
}

/// An orthonormal frame around `n` (Duff et al. 2017), columns `(t, b, n)`: `tangent_frame`.
fn tangent_frame(n: vec3<f32>) -> mat3x3<f32> {
    let sign = select(-1.0, 1.0, n.z >= 0.0);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    return mat3x3<f32>(
        vec3<f32>(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        vec3<f32>(b, sign + n.y * n.y * a, -n.y),
        n,
    );
}

/// `v` in the frame `f` (columns `t, b, n`): `f^T v`.
fn to_local(f: mat3x3<f32>, v: vec3<f32>) -> vec3<f32> {
    return v * f;
}

/// The rotation taking the unit vector `a` to the unit vector `b` (about their common
/// normal; Rodrigues), applied to `v`: `Quat::from_rotation_arc(a, b) * v`.
fn rotate_arc(a: vec3<f32>, b: vec3<f32>, v: vec3<f32>) -> vec3<f32> {
    let c = dot(a, b);
    let k = cross(a, b);
    if c <= -0.999999 {
        return -v;
    }
    return v * c + cross(k, v) + k * (dot(k, v) / (1.0 + c));
}
