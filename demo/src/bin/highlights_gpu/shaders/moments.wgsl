#define_import_path highlights::moments

#import highlights::scene
#import filtered_ndf::math
#import filtered_ndf::footprint as pixel
#import filtered_ndf::kernel::covariance

// The moments route's filter inputs, the CPU demo's `FootprintRoute::Moments`
// (`GBuffer::moment_derivatives` in `demo/src/render.rs`): on the water, the kernel is the
// covariance of the normal's slope over the pixel's Gaussian window (the waves' windowed
// moments, `Water::gradient_moments`) plus the first-order parallax of the view and light
// directions, centred on the window's mean normal; on the spheres, the footprint of the ray
// differentials through the half-vector Jacobian (`GBuffer::analytic_derivatives`). The
// window is the CPU's: the camera's analytic ray differentials (`Camera::ray`) carried onto
// the hit's tangent plane (`DiffRay::footprint_on_plane`), no quad derivative involved. Each
// function mirrors the Rust one it names.

/// A method's inputs at one shading point: the slope footprint whose Gaussian kernel is the
/// filter's, and the local half vector at which the lobe is read (the pixel's half vector
/// turned by the rotation taking the kernel's mean normal to the shading normal).
struct FilterInput {
    fp: pixel::Footprint,
    h: vec3<f32>,
}

/// World offsets on the tangent plane per pixel step in x (`u`) and y (`v`).
struct PlaneDifferentials {
    u: vec3<f32>,
    v: vec3<f32>,
}

/// The ray differentials of the pixel centre `centre` (Igehy 1999, `Camera::ray`:
/// `dD/dx = (s - D (D . s)) / |d|` for the unnormalised direction `d` and its step `s`)
/// carried onto the tangent plane at `p` with normal `n`, at the ray parameter `|p - eye|`
/// (`DiffRay::footprint_on_plane`: `dP = t dD + dt D`, `dt = -(t dD . n) / (D . n)`, 0 where
/// the ray grazes the plane).
fn plane_differentials(centre: vec2<f32>, p: vec3<f32>, n: vec3<f32>) -> PlaneDifferentials {
    let step_x = scene::scene.step_x.xyz;
    let step_y = scene::scene.step_y.xyz;
    let raw = scene::scene.corner.xyz + centre.x * step_x + centre.y * step_y;
    let len = length(raw);
    let dir = raw / len;
    let dd_x = (step_x - dir * dot(dir, step_x)) / len;
    let dd_y = (step_y - dir * dot(dir, step_y)) / len;
    let t = distance(p, scene::scene.eye.xyz);
    let dn = dot(dir, n);
    let dp_x = t * dd_x;
    let dp_y = t * dd_y;
    let grazing = abs(dn) <= 1e-6;
    let dt_x = select(-dot(dp_x, n) / dn, 0.0, grazing);
    let dt_y = select(-dot(dp_y, n) / dn, 0.0, grazing);
    return PlaneDifferentials(dp_x + dt_x * dir, dp_y + dt_y * dir);
}

/// The pixel's Gaussian window on the water (`GBuffer::window`): the pixel filter
/// (`pixel::SIGMA_PIXEL`) carried by the plane differentials, as the world covariance
/// `(c_xx, c_xz, c_zz)`.
fn window(d: PlaneDifferentials) -> vec3<f32> {
    let sig2 = pixel::SIGMA_PIXEL * pixel::SIGMA_PIXEL;
    return vec3<f32>(
        sig2 * (d.u.x * d.u.x + d.v.x * d.v.x),
        sig2 * (d.u.x * d.u.z + d.v.x * d.v.z),
        sig2 * (d.u.z * d.u.z + d.v.z * d.v.z),
    );
}

/// The moments of the height gradient `g = (h_x, h_z)` over a Gaussian window.
struct GradientMoments {
    /// `E[g]`.
    mean: vec2<f32>,
    /// `Cov[g]` as `(xx, xz, zz)`.
    cov: vec3<f32>,
}

/// `k^T c k` for the window `c = (c_xx, c_xz, c_zz)`: the variance of the phase `k . p` over
/// the window.
fn phase_variance(k: vec2<f32>, c: vec3<f32>) -> f32 {
    return k.x * k.x * c.x + 2.0 * k.x * k.y * c.y + k.y * k.y * c.z;
}

/// `Water::gradient_moments`: the moments of the height gradient over the Gaussian window
/// `c` centred on `(x, z)`, each wave's fade frozen at the centre. With the phase
/// `theta_i = k_i . p + phase_i` Gaussian of variance `v_i = k_i^T c k_i`:
/// `E[cos theta_i] = cos(theta_i) exp(-v_i / 2)` and
/// `E[cos theta_i cos theta_j] = (cos(theta_i + theta_j) exp(-v_{i+j} / 2)
/// + cos(theta_i - theta_j) exp(-v_{i-j} / 2)) / 2`, `v_{i+-j} = (k_i +- k_j)^T c (k_i +- k_j)`;
/// `Cov[g] = E[g g^T] - E[g] E[g]^T`. The same sums as the Rust double loop, arranged to
/// cost less: each unordered pair of waves once (the term is symmetric in `i, j`),
/// `cos(theta_i +- theta_j)` from the waves' own sines and cosines, on the diagonal
/// `cos(0) exp(0) = 1` and `exp(-v_{i+i} / 2) = exp(-v_i / 2)^4`: 8 exponentials, then 2 per
/// pair of waves, 64 in all, by WGSL's `exp` (a GPU's special-function unit; WGSL allows it
/// `3 + 2 |x|` ulp, under 2e-5 relative for the arguments `x >= -87` that do not underflow,
/// far below the check's tolerance, `report::CHECK_TOLERANCE`).
fn gradient_moments(x: f32, z: f32, c: vec3<f32>) -> GradientMoments {
    let inv_len = scene::inv_footprint(x, z);
    var a: array<f32, 8>;
    var sc: array<vec2<f32>, 8>;
    var damp: array<f32, 8>;
    var mean = vec2<f32>(0.0);
    for (var i = 0u; i < scene::N_WAVES; i++) {
        let w = scene::scene.waves[i];
        a[i] = scene::fade(i, inv_len) * w.z;
        sc[i] = scene::fast_sincos(w.x * x + w.y * z + w.w);
        damp[i] = exp(-0.5 * phase_variance(w.xy, c));
        mean += w.xy * (a[i] * sc[i].y * damp[i]);
    }
    var second = vec3<f32>(0.0);
    for (var i = 0u; i < scene::N_WAVES; i++) {
        let ki = scene::scene.waves[i].xy;
        let d2 = damp[i] * damp[i];
        let cos_2i = sc[i].y * sc[i].y - sc[i].x * sc[i].x;
        second += 0.5 * a[i] * a[i] * (cos_2i * d2 * d2 + 1.0) * vec3<f32>(ki.x * ki.x, ki.x * ki.y, ki.y * ki.y);
        for (var j = i + 1u; j < scene::N_WAVES; j++) {
            let kj = scene::scene.waves[j].xy;
            let cc = sc[i].y * sc[j].y;
            let ss = sc[i].x * sc[j].x;
            let plus = (cc - ss) * exp(-0.5 * phase_variance(ki + kj, c));
            let minus = (cc + ss) * exp(-0.5 * phase_variance(ki - kj, c));
            // The pairs (i, j) and (j, i).
            let e = a[i] * a[j] * (plus + minus);
            second += e * vec3<f32>(ki.x * kj.x, 0.5 * (ki.x * kj.y + kj.x * ki.y), ki.y * kj.y);
        }
    }
    let cov = second - vec3<f32>(mean.x * mean.x, mean.x * mean.y, mean.y * mean.y);
    return GradientMoments(mean, cov);
}

/// `geometry::slope_derivative` without twist: `d sigma / dx_k` of the unit half vector `h`
/// (world) changing at `dh` (world) along the frame's tangent `k`, the frame `f` (columns
/// `s, t, n`) turning with the shape operator's column `w_k` (KHPL16 eq. 6, both terms).
fn slope_derivative(f: mat3x3<f32>, h: vec3<f32>, dh: vec3<f32>, w_k: vec2<f32>) -> vec2<f32> {
    let a = dot(h, f[0]);
    let b = dot(h, f[1]);
    let c = max(dot(h, f[2]), 1e-6);
    let da = dot(dh, f[0]) - c * w_k.x;
    let db = dot(dh, f[1]) - c * w_k.y;
    let dc = dot(dh, f[2]) + a * w_k.x + b * w_k.y;
    return (vec2<f32>(a, b) * (dc / c) - vec2<f32>(da, db)) / c;
}

/// `geometry::half_vector_jacobian` for a point eye and a point light: `M = d sigma / dx` on
/// the tangent plane at `x` (KHPL16 eq. 4 and 6), `M = T(x) h_w' + T'(x) h_w` with
/// `h_w' = (I - h h^T)(i' + o') / |i + o|`, `i' = -(I - i i^T) / |light - x|` (likewise `o'`),
/// the frame `f` (columns `s, t, n`) turning with the shape operator `w` (column `k`: the
/// normal's change along tangent `k`, in `(s, t)`). Column `k` is `d sigma / dx_k`. The zero
/// matrix where `i + o = 0`.
fn half_vector_jacobian(x: vec3<f32>, eye: vec3<f32>, light: vec3<f32>, f: mat3x3<f32>, w: mat2x2<f32>) -> mat2x2<f32> {
    let to_eye = eye - x;
    let to_light = light - x;
    let ko = 1.0 / length(to_eye);
    let ki = 1.0 / length(to_light);
    let o = to_eye * ko;
    let i = to_light * ki;
    let len = length(i + o);
    if !(len > 0.0) {
        return mat2x2<f32>(0.0, 0.0, 0.0, 0.0);
    }
    let h = (i + o) / len;
    return mat2x2<f32>(
        slope_derivative(f, h, half_vector_change(i, ki, o, ko, h, len, f[0]), w[0]),
        slope_derivative(f, h, half_vector_change(i, ki, o, ko, h, len, f[1]), w[1]),
    );
}

/// The change of the unit half vector `h = (i + o) / len` (world) per unit step along the
/// tangent `u`: `(I - h h^T)(i' + o') u / len` with `i' u = -(u - i (i . u)) k_i` (`k_i`: the
/// inverse distance to the light), likewise `o'` (`half_vector_jacobian`'s columns).
fn half_vector_change(i: vec3<f32>, ki: f32, o: vec3<f32>, ko: f32, h: vec3<f32>, len: f32, u: vec3<f32>) -> vec3<f32> {
    let dhw = (u - i * dot(i, u)) * -ki + (u - o * dot(o, u)) * -ko;
    return (dhw - h * dot(h, dhw)) / len;
}

/// `methods::footprint_from_ray_differentials` (`geometry::footprint`): the slope footprint
/// `(M dx_u, M dx_v)` of the plane differentials `d` at `x` (frame `f`, shape operator `w`).
fn ray_footprint(x: vec3<f32>, light: vec3<f32>, f: mat3x3<f32>, w: mat2x2<f32>, d: PlaneDifferentials) -> pixel::Footprint {
    let m = half_vector_jacobian(x, scene::scene.eye.xyz, light, f, w);
    let u = vec2<f32>(dot(d.u, f[0]), dot(d.u, f[1]));
    let v = vec2<f32>(dot(d.v, f[0]), dot(d.v, f[1]));
    return pixel::from_slope_derivatives(m * u, m * v);
}

/// `render::footprint_of`: a footprint whose Gaussian kernel at `sigma` is `k`, its
/// eigenvectors scaled by the square roots of its eigenvalues over `sigma`.
fn footprint_of(k: covariance::Covariance, sigma: f32) -> pixel::Footprint {
    let ev = covariance::eigenvalues(k);
    let l1 = max(ev.x, ev.y);
    let l2 = min(ev.x, ev.y);
    var e1 = vec2<f32>(1.0, 0.0);
    if abs(k.s_xy) > 1e-12 * (abs(l1) + 1e-30) {
        let e = vec2<f32>(l1 - k.s_yy, k.s_xy);
        let n = length(e);
        if n > 0.0 && n <= math::F32_MAX {
            e1 = e / n;
        }
    } else if k.s_xx < k.s_yy {
        e1 = vec2<f32>(0.0, 1.0);
    }
    let e2 = vec2<f32>(-e1.y, e1.x);
    return pixel::from_slope_derivatives(e1 * (sqrt(max(l1, 0.0)) / sigma), e2 * (sqrt(max(l2, 0.0)) / sigma));
}

/// The window's slope moments at the shading point `s` of object `index` seen through the
/// pixel centre `centre`: on the water (object 0) the waves' moments over the pixel's Gaussian
/// window ([`gradient_moments`] over [`window`]), zero on the spheres (which the moments route
/// filters by their ray differentials). Independent of the light: the deferred route stores
/// them in its G-buffer.
fn window_moments(index: u32, s: scene::Surface, centre: vec2<f32>) -> GradientMoments {
    if index != 0u {
        return GradientMoments(vec2<f32>(0.0), vec3<f32>(0.0));
    }
    let d = plane_differentials(centre, s.position, s.normal);
    return gradient_moments(s.position.x, s.position.z, window(d));
}

/// The moments route's inputs at the shading point `s` of object `index` (0: the water;
/// `1 + i`: sphere `i` of the water scene) seen through the pixel centre `centre`, for the
/// light direction `wi` at squared distance `dist_sq` and the world half vector `h_w`
/// (`GBuffer::moment_derivatives`, then `render::component_d`'s rotation of `h`).
fn filter_input(index: u32, s: scene::Surface, centre: vec2<f32>, wi: vec3<f32>, dist_sq: f32, h_w: vec3<f32>) -> FilterInput {
    return filter_input_with(index, s, centre, wi, dist_sq, h_w, window_moments(index, s, centre));
}

/// [`filter_input`] with the window's moments `g` given ([`window_moments`], e.g. read back
/// from a G-buffer).
fn filter_input_with(index: u32, s: scene::Surface, centre: vec2<f32>, wi: vec3<f32>, dist_sq: f32, h_w: vec3<f32>, g: GradientMoments) -> FilterInput {
    let f = scene::tangent_frame(s.normal);
    let light = s.position + wi * sqrt(dist_sq);
    let d = plane_differentials(centre, s.position, s.normal);
    let h = scene::to_local(f, h_w);
    if index != 0u {
        // A sphere of radius r: the shape operator I / r, no twist.
        let r = scene::scene.spheres[index - 1u].w;
        let w = mat2x2<f32>(1.0 / r, 0.0, 0.0, 1.0 / r);
        return FilterInput(ray_footprint(s.position, light, f, w, d), h);
    }
    // The parallax: the ray-differential footprint of a flat surface.
    let parallax = ray_footprint(s.position, light, f, mat2x2<f32>(0.0, 0.0, 0.0, 0.0), d);
    // Height gradient -> slope of the normal in this frame: the normal is
    // (-h_x, 1, -h_z) / L, so d(slope) = (s . e, t . e) / L per unit gradient change.
    let j = mat2x2<f32>(vec2<f32>(f[0].x, f[1].x), vec2<f32>(f[0].z, f[1].z)) * max(s.normal.y, 1e-3);
    let k = j * mat2x2<f32>(g.cov.xy, g.cov.yz) * transpose(j);
    let p = covariance::from_footprint(parallax, pixel::SIGMA_PIXEL);
    let total = covariance::from_entries(p.s_xx + k[0].x, p.s_xy + 0.5 * (k[1].x + k[0].y), p.s_yy + k[1].y);
    let mean_normal = normalize(vec3<f32>(-g.mean.x, 1.0, -g.mean.y));
    let shifted = scene::rotate_arc(scene::to_local(f, mean_normal), vec3<f32>(0.0, 0.0, 1.0), h);
    return FilterInput(footprint_of(covariance::sanitized(total), pixel::SIGMA_PIXEL), shifted);
}
