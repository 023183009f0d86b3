//! The normal-mapped floor's reference (issue 51) by integration of its glints instead of
//! sampling them.
//!
//! Why: at `alpha = 0.01` a texel's glint is far narrower than the texel, and away from the
//! camera a pixel covers thousands of texels, so a sampled pixel converges only as the
//! binomial noise of the small fraction of its area that glints. Sampled with 256 to 16384
//! rays a pixel, the glitter path stays speckled and the reference's own error (against four
//! times the rays) exceeds the margins it judges.
//!
//! What: the pixel's specular value is `S = int w(X(p)) |J(p)| K(p) P22(s_h(p) - mu(p)) dp`
//! over the floor `p = (x, 0, z)`: `w` the Gaussian pixel filter (sigma 0.5 pixel, cut at
//! [`CUT_SIGMAS`] standard deviations, a mass of `exp(-8) = 3e-4` left out) of the image point
//! `X(p)`, `J` the plane-to-image Jacobian, `K` the smooth factors of the shading (irradiance,
//! Fresnel, Smith, cosines, `1 / cos^4 theta_h`), `s_h` the half vector's slope and `mu` the
//! level-0 map's bilinear slope. The camera of the demonstration has neither yaw nor roll, so
//! the image row of a floor point depends on `z` alone and its column is affine in `x` at a
//! given `z`: the integral runs over lines of constant `z`. On the cell between four texel
//! centres the slope is bilinear, `mu(f_u, f_v) = A(f_v) + B(f_v) f_u`, so along each line the
//! Beckmann lobe `exp(-|s - A - B f_u|^2 / alpha^2) / (pi alpha^2)` is a Gaussian in `f_u`:
//! its integral is a closed form in `erf`, with `w |J| K` taken at the lobe's peak (it
//! varies over a pixel, the peak over a small fraction of a cell); `K` and `s_h` are taken
//! linear along the pixel's stretch of the line, between their values at its two ends (they
//! change over metres, the stretch is at most a few). Across the lines (`f_v`)
//! each cell is bisected while the bounding box of its sub-patch's slopes (the hull of the
//! four corners bounds a bilinear patch) still reaches within [`REACH`] `alpha` of `s_h`,
//! until the box is under `leaf` alpha across; the leaves are integrated by Gauss-Legendre
//! rules in `f_v`. Everything but the specular term (ambient, diffuse, the sky) is smooth and
//! sampled, as the other references.

use crate::camera::Camera;
use crate::image_out::Image;
use crate::methods::SIGMA_PIXEL;
use crate::normal_map::{Frame, NormalMap, TEXELS, TILE, geometry, shade};
use crate::render;
use crate::scene::Scene;
use glam::{Vec2, Vec3};

/// The pixel filter's cut, in standard deviations.
pub const CUT_SIGMAS: f32 = 4.0;
/// How far (in `alpha`) from `s_h` a patch's slopes must stay to be skipped: the lobe is
/// down by `exp(-REACH^2) = 1.1e-7` there (and so is its mass beyond).
pub const REACH: f32 = 4.0;
/// The deepest bisection of a cell along `f_v`.
const DEPTH: u32 = 10;
/// The floor's far edge (`z`) and half width, as `normal_map`'s ray test.
const Z_FAR: f32 = -250.0;
const HALF_WIDTH: f32 = 120.0;

/// The integration's resolution.
#[derive(Clone, Copy, Debug)]
pub struct Quadrature {
    /// A leaf's largest slope extent, in `alpha`.
    pub leaf: f32,
    /// Gauss-Legendre nodes per leaf along `f_v`.
    pub nodes: usize,
    /// The largest extent of a line segment in image pixels (the pixel filter is read once a
    /// segment: finer in the near field, where a cell spans a good part of a pixel).
    pub segment: f32,
    /// Samples a pixel of the smooth part (ambient, diffuse, sky).
    pub rest_spp: usize,
}

impl Quadrature {
    /// The demonstration's resolution.
    pub const DEFAULT: Quadrature = Quadrature {
        leaf: 2.0,
        nodes: 3,
        segment: 0.1,
        rest_spp: 128,
    };

    /// The resolution that measures [`Self::DEFAULT`]'s own error: leaves a quarter as wide in
    /// slope, twice the nodes, segments half as long, four times the samples.
    pub fn finer(self) -> Quadrature {
        Quadrature {
            leaf: 0.25 * self.leaf,
            nodes: 2 * self.nodes,
            segment: 0.5 * self.segment,
            rest_spp: 4 * self.rest_spp,
        }
    }
}

/// The reference frame: the specular term integrated, the rest sampled (`seed`'s streams).
pub fn render(
    scene: &Scene,
    nm: &NormalMap,
    cam: &Camera,
    (w, h): (usize, usize),
    q: Quadrature,
    (seed, exposure): (u64, f32),
) -> Frame {
    let alpha = scene.alpha;
    let (gl_x, gl_w) = gauss_legendre(q.nodes);
    let cells = Cells::new(nm);
    let rows: Vec<(Vec3, Vec3)> = crate::parallel::rows(h, None, |y| {
        (0..w)
            .map(|x| {
                let i = y * w + x;
                let mut rng = render::pixel_rng(seed, i as u64);
                let samples = render::Samples::Each(q.rest_spp);
                let ([rest], _) =
                    render::sample_pixel(&samples, i, &mut rng, (SIGMA_PIXEL, exposure), |o| {
                        let ray = cam.ray(x as f32 + 0.5 + o.0, y as f32 + 0.5 + o.1).ray;
                        match crate::normal_map::hit(&ray) {
                            None => [scene.sky(ray.dir)],
                            Some(p) => [shade(scene, &geometry(scene, cam.eye, p), 0.0).0],
                        }
                    });
                let centre = (x as f32 + 0.5, y as f32 + 0.5);
                let spec = pixel_specular(scene, &cells, cam, centre, q, alpha, (&gl_x, &gl_w));
                (rest + spec, spec)
            })
            .collect()
    });
    let (total, specular): (Vec<Vec3>, Vec<Vec3>) = rows.into_iter().unzip();
    Frame {
        total: Image::new(w, h, total),
        specular: Image::new(w, h, specular),
    }
}

/// The floor's point seen through the image point `(X, Y)`, if the ray meets it (within
/// its extent or not).
fn plane_point(cam: &Camera, (px, py): (f32, f32)) -> Option<Vec3> {
    let ray = cam.ray(px, py).ray;
    (ray.dir.y < -1e-6).then(|| ray.origin + ray.dir * (-ray.origin.y / ray.dir.y))
}

/// The specular value of the pixel centred on `(cx, cy)` (see the module's documentation).
fn pixel_specular(
    scene: &Scene,
    cells: &Cells,
    cam: &Camera,
    (cx, cy): (f32, f32),
    q: Quadrature,
    alpha: f32,
    (gl_x, gl_w): (&[f32], &[f32]),
) -> Vec3 {
    let r = CUT_SIGMAS * SIGMA_PIXEL;
    let sig2 = SIGMA_PIXEL * SIGMA_PIXEL;
    let norm = 1.0 / (std::f32::consts::TAU * sig2);
    // The z-range: the rows cy -+ r (the upper one may see the sky: the floor's far edge).
    let Some(near) = plane_point(cam, (cx, cy + r)) else {
        return Vec3::ZERO;
    };
    let z_max = near.z;
    let z_min = plane_point(cam, (cx, cy - r)).map_or(Z_FAR, |p| p.z.max(Z_FAR));
    if z_min >= z_max {
        return Vec3::ZERO;
    }
    let n = TEXELS as f32 / TILE;
    // Cell coordinates: texel centres at integers, `v = z n - 1/2`.
    let (v_lo, v_hi) = (z_min * n - 0.5, z_max * n - 0.5);
    let mut total = Vec3::ZERO;
    let cell_area = 1.0 / (n * n);
    for j in v_lo.floor() as i64..=v_hi.floor() as i64 {
        let (f_lo, f_hi) = ((v_lo - j as f32).max(0.0), (v_hi - j as f32).min(1.0));
        if f_hi <= f_lo {
            continue;
        }
        // The row's image geometry at its middle: Y(z), dY/dz, and X = a + b x.
        let z_mid = (j as f32 + 0.5 * (f_lo + f_hi) + 0.5) / n;
        let Some(row) = Row::new(cam, z_mid) else {
            continue;
        };
        if (row.y - cy).abs() > r + row.dy_dz.abs() / n {
            continue;
        }
        // The x-range of the pixel's cut filter on this row, in cell coordinates.
        let (x0, x1) = ((cx - r - row.a) / row.b, (cx + r - row.a) / row.b);
        let (x0, x1) = (x0.max(-HALF_WIDTH), x1.min(HALF_WIDTH));
        if x1 <= x0 {
            continue;
        }
        let (u_lo, u_hi) = (x0 * n - 0.5, x1 * n - 0.5);
        // s_h and the shading's smooth factors K along the row, linear in x between the
        // range's ends (both change over metres, the range is at most a few).
        let ends = [x0, x1].map(|x| geometry(scene, cam.eye, Vec3::new(x, 0.0, z_mid)));
        let (s0, s1) = (ends[0].s_h, ends[1].s_h);
        let (k0, k1) = (shade(scene, &ends[0], 1.0).1, shade(scene, &ends[1], 1.0).1);
        let along = |x: f32| {
            if x1 > x0 {
                ((x - x0) / (x1 - x0)).clamp(0.0, 1.0)
            } else {
                0.0
            }
        };
        let s_at = |u: f32| s0.lerp(s1, along((u + 0.5) / n));
        let jacobian = row.b * row.dy_dz.abs();
        // Pixels per cell along x: the segments along f_u.
        let per_cell = row.b / n;
        let pieces = ((per_cell / q.segment).ceil() as usize).max(1);
        for i in u_lo.floor() as i64..=u_hi.floor() as i64 {
            let (g_lo, g_hi) = ((u_lo - i as f32).max(0.0), (u_hi - i as f32).min(1.0));
            if g_hi <= g_lo {
                continue;
            }
            let s = s_at(i as f32 + 0.5);
            let cell = cells.at(i, j);
            let reach = REACH * alpha;
            if !(s.cmpge(cell.lo - reach).all() && s.cmple(cell.hi + reach).all()) {
                continue;
            }
            // The integrand's factor at a point of this cell (`w |J| K`).
            let factor = |fu: f32, fv: f32| {
                let x = (i as f32 + fu + 0.5) / n;
                let z = (j as f32 + fv + 0.5) / n;
                let gy = (row.y + row.dy_dz * (z - z_mid) - cy).powi(2);
                let gx = (row.a + row.b * x - cx).powi(2);
                let weight = norm * (-(gx + gy) / (2.0 * sig2)).exp();
                k0.lerp(k1, along(x)) * (weight * jacobian)
            };
            let patch = Patch {
                corners: cell.corners,
                s,
                alpha,
            };
            let step = (g_hi - g_lo) / pieces as f32;
            for k in 0..pieces {
                let (a, b) = (g_lo + k as f32 * step, g_lo + (k + 1) as f32 * step);
                total +=
                    patch.integrate((a, b), (f_lo, f_hi), q, (gl_x, gl_w), &factor) * cell_area;
            }
        }
    }
    total
}

/// One bilinear cell of the level-0 map: its corner slopes `[m00, m10, m01, m11]` and their
/// bounding box (which holds the whole patch).
#[derive(Clone, Copy)]
struct Cell {
    corners: [Vec2; 4],
    lo: Vec2,
    hi: Vec2,
}

/// Every cell of the tile ([`NormalMap::cell`]), with its bounding box.
struct Cells {
    cells: Vec<Cell>,
}

impl Cells {
    fn new(nm: &NormalMap) -> Self {
        let n = TEXELS as i64;
        let cells = (0..n * n)
            .map(|k| {
                let corners = nm.cell(k % n, k / n);
                let lo = corners.iter().fold(Vec2::splat(f32::MAX), |m, c| m.min(*c));
                let hi = corners.iter().fold(Vec2::splat(f32::MIN), |m, c| m.max(*c));
                Cell { corners, lo, hi }
            })
            .collect();
        Self { cells }
    }

    /// Cell `(i, j)`, wrapping.
    fn at(&self, i: i64, j: i64) -> &Cell {
        let n = TEXELS as i64;
        &self.cells[(j.rem_euclid(n) * n + i.rem_euclid(n)) as usize]
    }
}

/// The image geometry of the floor's line at `z`: its row `y`, `dY/dz`, and its columns
/// `X = a + b x`.
struct Row {
    y: f32,
    dy_dz: f32,
    a: f32,
    b: f32,
}

impl Row {
    fn new(cam: &Camera, z: f32) -> Option<Row> {
        let p = |x: f32, z: f32| cam.project(Vec3::new(x, 0.0, z), 1e-3);
        let (x0, y0) = p(0.0, z)?;
        let (x1, _) = p(1.0, z)?;
        let dz = 1e-3 * z.abs().max(1.0);
        let (_, y1) = p(0.0, z + dz)?;
        let (_, y2) = p(0.0, z - dz)?;
        Some(Row {
            y: y0,
            dy_dz: (y1 - y2) / (2.0 * dz),
            a: x0,
            b: x1 - x0,
        })
    }
}

/// A cell's bilinear slope patch (corners `m00, m10, m01, m11`: `mu(f_u, f_v)`), the half
/// vector's slope `s` there and the lobe's `alpha`.
struct Patch {
    corners: [Vec2; 4],
    s: Vec2,
    alpha: f32,
}

impl Patch {
    /// `mu(f_u, f_v)` as the line `A + B f_u` at `f_v`.
    fn line(&self, fv: f32) -> (Vec2, Vec2) {
        let [m00, m10, m01, m11] = self.corners;
        let a = m00 + (m01 - m00) * fv;
        let b = (m10 - m00) + (m11 - m10 - m01 + m00) * fv;
        (a, b)
    }

    /// The bounding box of the sub-patch `f_v in [v0, v1]` (the hull of its corners holds a
    /// bilinear patch): its extent, and whether it reaches within [`REACH`] alpha of `s`.
    fn bbox(&self, v0: f32, v1: f32) -> (f32, bool) {
        let (a0, b0) = self.line(v0);
        let (a1, b1) = self.line(v1);
        let pts = [a0, a0 + b0, a1, a1 + b1];
        let lo = pts.iter().fold(Vec2::splat(f32::MAX), |m, p| m.min(*p));
        let hi = pts.iter().fold(Vec2::splat(f32::MIN), |m, p| m.max(*p));
        let reach = REACH * self.alpha;
        let inside = self.s.cmpge(lo - reach).all() && self.s.cmple(hi + reach).all();
        ((hi - lo).max_element(), inside)
    }

    /// `int_{f_v} int_{f_u} factor P22(s - mu) df_u df_v` over `f_u in fu`, `f_v in fv`:
    /// bisection in `f_v` down to leaves under `q.leaf` alpha (or [`DEPTH`]), Gauss-Legendre
    /// across each leaf, the closed form along `f_u`.
    fn integrate(
        &self,
        fu: (f32, f32),
        (v0, v1): (f32, f32),
        q: Quadrature,
        (gl_x, gl_w): (&[f32], &[f32]),
        factor: &dyn Fn(f32, f32) -> Vec3,
    ) -> Vec3 {
        let mut out = Vec3::ZERO;
        let mut stack = vec![(v0, v1, 0u32)];
        while let Some((a, b, depth)) = stack.pop() {
            let (extent, inside) = self.bbox(a, b);
            if !inside {
                continue;
            }
            if extent > q.leaf * self.alpha && depth < DEPTH {
                let mid = 0.5 * (a + b);
                stack.push((a, mid, depth + 1));
                stack.push((mid, b, depth + 1));
                continue;
            }
            for (&t, &wt) in gl_x.iter().zip(gl_w) {
                let fv = a + 0.5 * (b - a) * (t + 1.0);
                let (lobe, peak) = self.along_u(fv, fu);
                if lobe > 0.0 {
                    out += factor(peak, fv) * (lobe * 0.5 * (b - a) * wt);
                }
            }
        }
        out
    }

    /// `int P22(s - A - B f_u) df_u` over `f_u in [u0, u1]` at `f_v` (the Beckmann lobe of
    /// roughness `alpha`, `exp(-|d|^2 / alpha^2) / (pi alpha^2)`), and where on the segment the
    /// lobe peaks. With `d = s - A`: `|d - B f_u|^2 = |B|^2 (f_u - t)^2 + p^2`, `t = d.B /
    /// |B|^2`, `p^2 = |d|^2 - (d.B)^2 / |B|^2`, so the integral is `exp(-p^2 / alpha^2) /
    /// (pi alpha^2) * alpha sqrt(pi) / (2 |B|) * (erf((u1 - t) |B| / alpha) - erf((u0 - t) |B|
    /// / alpha))` (in f64: the difference of two `erf` near 1).
    fn along_u(&self, fv: f32, (u0, u1): (f32, f32)) -> (f32, f32) {
        let (a, b) = self.line(fv);
        let d = (self.s - a).as_dvec2();
        let b = b.as_dvec2();
        let alpha = f64::from(self.alpha);
        let bb = b.length_squared();
        let norm = 1.0 / (std::f64::consts::PI * alpha * alpha);
        let (u0, u1) = (f64::from(u0), f64::from(u1));
        if bb * (u1 - u0) * (u1 - u0) < 1e-6 * alpha * alpha {
            // The slope barely changes along the segment: the lobe at its middle.
            let m = 0.5 * (u0 + u1);
            let e = (d - b * m).length_squared() / (alpha * alpha);
            return ((norm * (-e).exp() * (u1 - u0)) as f32, m as f32);
        }
        let t = d.dot(b) / bb;
        let p2 = (d.length_squared() - d.dot(b) * d.dot(b) / bb).max(0.0);
        let r = f64::from(REACH) * alpha;
        if p2 > r * r {
            return (0.0, 0.0);
        }
        let bl = bb.sqrt();
        let k = bl / alpha;
        let span = erf_difference((u0 - t) * k, (u1 - t) * k);
        let value = norm * (-p2 / (alpha * alpha)).exp() * alpha * std::f64::consts::PI.sqrt()
            / (2.0 * bl)
            * span;
        (value.max(0.0) as f32, t.clamp(u0, u1) as f32)
    }
}

/// `erf(b) - erf(a)` for `a <= b`, through `erfc` on the side where both are large so
/// that the difference keeps its digits; `erfc(x) = t P(t) exp(-x^2)`, `t = 1 / (1 + p x)`
/// for `x >= 0` (Abramowitz and Stegun 7.1.26, absolute error under 1.5e-7).
fn erf_difference(a: f64, b: f64) -> f64 {
    let erfc = |x: f64| {
        let t = 1.0 / (1.0 + 0.327_591_1 * x);
        let poly = t
            * (0.254_829_592
                + t * (-0.284_496_736
                    + t * (1.421_413_741 + t * (-1.453_152_027 + t * 1.061_405_429))));
        poly * (-x * x).exp()
    };
    if a >= 0.0 {
        erfc(a) - erfc(b)
    } else if b <= 0.0 {
        erfc(-b) - erfc(-a)
    } else {
        2.0 - erfc(b) - erfc(-a)
    }
}

/// The `n`-point Gauss-Legendre rule on `[-1, 1]`: nodes (roots of `P_n`, by Newton's method
/// from `cos(pi (i + 3/4) / (n + 1/2))`, in f64) and weights `2 / ((1 - x^2) P_n'(x)^2)`.
pub fn gauss_legendre(n: usize) -> (Vec<f32>, Vec<f32>) {
    let n = n.max(1);
    let legendre = |x: f64| {
        // (P_n(x), P_n'(x)) by the three-term recurrence.
        let (mut p0, mut p1) = (1.0f64, x);
        for k in 2..=n {
            let k = k as f64;
            (p0, p1) = (p1, ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k);
        }
        let p = if n == 1 { x } else { p1 };
        let prev = if n == 1 { 1.0 } else { p0 };
        let dp = n as f64 * (x * p - prev) / (x * x - 1.0);
        (p, dp)
    };
    let (mut xs, mut ws) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        for _ in 0..100 {
            let (p, dp) = legendre(x);
            let dx = p / dp;
            x -= dx;
            if dx.abs() < 1e-15 {
                break;
            }
        }
        let (_, dp) = legendre(x);
        xs.push(x as f32);
        ws.push((2.0 / ((1.0 - x * x) * dp * dp)) as f32);
    }
    (xs, ws)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Gauss-Legendre rules integrate `x^k` exactly up to degree `2 n - 1` on `[-1, 1]`
    /// (`2 / (k + 1)` for even `k`, 0 for odd), to f32 rounding (1e-6).
    #[test]
    fn gauss_legendre_rules_are_exact_to_their_degree() {
        for n in 1..=8 {
            let (x, w) = gauss_legendre(n);
            for k in 0..2 * n {
                let m: f64 = x
                    .iter()
                    .zip(&w)
                    .map(|(&x, &w)| f64::from(w) * f64::from(x).powi(k as i32))
                    .sum();
                let exact = if k % 2 == 1 {
                    0.0
                } else {
                    2.0 / (k as f64 + 1.0)
                };
                assert!((m - exact).abs() < 1e-6, "n = {n}, k = {k}: {m} vs {exact}");
            }
        }
    }

    /// One cell's lobe integral, `int int P22(s - mu(f_u, f_v)) df_u df_v` over the unit
    /// square, against an independent midpoint rule on a 4000 x 4000 grid in f64 (its error:
    /// the lobe spans about `alpha / |B| = 0.1` of the cell, 400 grid steps, so the midpoint
    /// rule's relative error is far under 1e-4), for patches with the lobe inside, on an edge,
    /// and missing; the unit factor. Tolerance: 1e-3 of the exact value (the default leaves and
    /// nodes; the finer resolution 1e-4), and 1e-6 absolute where the lobe misses.
    /// `erf(b) - erf(a)` against `2 / sqrt(pi) int_a^b exp(-t^2) dt` by a 32-point
    /// Gauss-Legendre rule on each of 64 pieces (exact to far below the formula's 1.5e-7), on
    /// both sides of zero, across it, and in the far tail where `erf` alone loses the
    /// difference. Tolerance: A&S 7.1.26's bound, 1.5e-7 for each of the two `erfc` values.
    #[test]
    fn erf_difference_matches_quadrature() {
        let (x, w) = gauss_legendre(32);
        let integral = |a: f64, b: f64| {
            let pieces = 64;
            let h = (b - a) / pieces as f64;
            (0..pieces)
                .map(|k| {
                    let mid = a + h * (k as f64 + 0.5);
                    x.iter()
                        .zip(&w)
                        .map(|(&xi, &wi)| {
                            let t = mid + 0.5 * h * f64::from(xi);
                            0.5 * h * f64::from(wi) * (-t * t).exp()
                        })
                        .sum::<f64>()
                })
                .sum::<f64>()
                * 2.0
                / std::f64::consts::PI.sqrt()
        };
        for (a, b) in [
            (0.1, 0.7),
            (-2.0, -0.3),
            (-1.5, 2.5),
            (3.0, 3.5),
            (-4.5, -4.0),
        ] {
            let (got, want) = (erf_difference(a, b), integral(a, b));
            assert!(
                (got - want).abs() <= 3e-7,
                "[{a}, {b}]: {got} against {want}"
            );
        }
    }

    #[test]
    fn cell_integral_matches_a_dense_midpoint_rule() {
        let alpha = 0.01f32;
        let corners = [
            Vec2::new(-0.04, 0.01),
            Vec2::new(0.06, 0.02),
            Vec2::new(-0.03, 0.09),
            Vec2::new(0.05, 0.07),
        ];
        let (gx, gw) = gauss_legendre(Quadrature::DEFAULT.nodes);
        let (fx, fw) = gauss_legendre(Quadrature::DEFAULT.finer().nodes);
        for s in [
            Vec2::new(0.01, 0.04),
            Vec2::new(-0.035, 0.05),
            Vec2::new(0.3, 0.3),
        ] {
            let patch = Patch { corners, s, alpha };
            let dense = {
                let n = 4000;
                let mut sum = 0.0f64;
                for i in 0..n {
                    let fu = (i as f64 + 0.5) / n as f64;
                    for j in 0..n {
                        let fv = (j as f64 + 0.5) / n as f64;
                        let [m00, m10, m01, m11] = corners.map(|c| c.as_dvec2());
                        let mu = m00
                            + (m10 - m00) * fu
                            + (m01 - m00) * fv
                            + (m11 - m10 - m01 + m00) * fu * fv;
                        let d = s.as_dvec2() - mu;
                        let a2 = f64::from(alpha) * f64::from(alpha);
                        sum += (-d.length_squared() / a2).exp() / (std::f64::consts::PI * a2);
                    }
                }
                sum / (n * n) as f64
            };
            let one = |_: f32, _: f32| Vec3::ONE;
            for (q, rule, tol) in [
                (Quadrature::DEFAULT, (&gx[..], &gw[..]), 1e-3),
                (Quadrature::DEFAULT.finer(), (&fx[..], &fw[..]), 1e-4),
            ] {
                let v = f64::from(patch.integrate((0.0, 1.0), (0.0, 1.0), q, rule, &one).x);
                assert!(
                    (v - dense).abs() <= tol * dense + 1e-6,
                    "s = {s}: {v} vs {dense} ({q:?})"
                );
            }
        }
    }

    /// Whole pixels of the integrated reference against brute-force sampling of the same
    /// pixel filter (untruncated Gaussian, `2^19` samples from a seeded generator, the
    /// level-0 map's bilinear slope at each: `NormalMap::slope`), in the glitter path near the
    /// camera and in the middle distance (64x40 frame, so that a pixel covers some 10^4 to
    /// 10^5 texels). Tolerance: five standard errors of the sampled mean (its binomial noise
    /// where a small fraction of the pixel glints) plus 1 % (the filter's cut at 4 sigma, the
    /// leaves, f32 sums over up to 10^5 cells).
    #[test]
    fn integrated_pixels_match_brute_force_sampling() {
        use crate::camera::camera_at;
        use crate::normal_map::hit;
        use filtered_ndf::f32::{Beckmann, Isotropic, Ndf};
        let (w, h) = (64, 40);
        let cam = camera_at(0, w, h);
        let scene = Scene::new(cam.lod());
        let nm = NormalMap::new();
        let lobe = Beckmann::new(Isotropic::new_clamped(scene.alpha));
        let (gx, gw) = gauss_legendre(Quadrature::DEFAULT.nodes);
        let cells = Cells::new(&nm);
        let mut rng = filtered_ndf::testing::rng::SplitMix64(7);
        let mut checked = 0;
        for (px, py) in [(32usize, 34usize), (32, 24)] {
            let centre = (px as f32 + 0.5, py as f32 + 0.5);
            let exact = crate::image_out::luminance(pixel_specular(
                &scene,
                &cells,
                &cam,
                centre,
                Quadrature::DEFAULT,
                scene.alpha,
                (&gx, &gw),
            ));
            let n = 1 << 19;
            let (mut sum, mut sum2) = (0.0f64, 0.0f64);
            for _ in 0..n {
                let u1 = crate::render::uniform_f32(&mut rng);
                let u2 = crate::render::uniform_f32(&mut rng);
                let r = SIGMA_PIXEL * (-2.0 * u1.ln()).sqrt();
                let (sn, cs) = (std::f32::consts::TAU * u2).sin_cos();
                let ray = cam.ray(centre.0 + r * cs, centre.1 + r * sn).ray;
                let v = hit(&ray).map_or(0.0, |p| {
                    let geo = geometry(&scene, cam.eye, p);
                    let d = lobe.p22(geo.s_h - nm.slope(p.x, p.z));
                    f64::from(crate::image_out::luminance(shade(&scene, &geo, d).1))
                });
                sum += v;
                sum2 += v * v;
            }
            let mean = sum / n as f64;
            let se = ((sum2 / n as f64 - mean * mean).max(0.0) / n as f64).sqrt();
            eprintln!("pixel ({px}, {py}): integrated {exact}, sampled {mean} +- {se}");
            assert!(
                (f64::from(exact) - mean).abs() <= 5.0 * se + 0.01 * mean,
                "pixel ({px}, {py}): integrated {exact}, sampled {mean} +- {se}"
            );
            checked += usize::from(mean > 0.0);
        }
        assert_eq!(checked, 2, "the pixels chosen must see glints");
    }
}
