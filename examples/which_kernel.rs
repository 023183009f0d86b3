//! Which kernel for which scene: every row of the guide in the README and the crate docs as a
//! runnable function. Each prints the filtered `D(h)` beside the unfiltered one at a few half
//! vectors, so the spreading of a sub-pixel highlight is visible.
//!
//! `cargo run --release --example which_kernel [-- ROW]` with ROW one of the names below
//! (all rows without an argument).

use filtered_ndf::f32::footprint::geometry::{self, Endpoint, ShadingFrame};
use filtered_ndf::f32::prelude::*;
use filtered_ndf::f32::{Covariance, LeanMoments, TemporalLobe, TemporalRoughness, filter};
use glam::{Vec2, Vec3};

/// Half vectors from the peak into the tail of a roughness-0.01 lobe (tangent frame).
fn half_vectors() -> [Vec3; 3] {
    [
        Vec3::Z,
        Vec3::new(0.01, 0.0, 1.0).normalize(),
        Vec3::new(0.03, 0.02, 1.0).normalize(),
    ]
}

fn show(row: &str, unfiltered: &dyn Ndf, filtered: &dyn Ndf) {
    println!("{row}");
    for h in half_vectors() {
        println!(
            "  h = ({:+.3}, {:+.3}, {:.4}): D unfiltered {:>10.2}, filtered {:>10.2}",
            h.x,
            h.y,
            h.z,
            unfiltered.d(h),
            filtered.d(h)
        );
    }
}

/// Forward shading, GGX, any roughness form, per light: ddx/ddy of the tangent-space half
/// vector (a fragment shader's `dpdx(h)`, `dpdy(h)`): TK19's matrix filter.
fn forward_ggx() {
    let material = Ggx::isotropic(0.01).unwrap();
    let h = Vec3::new(0.002, 0.0, 1.0).normalize();
    let (dh_dx, dh_dy) = (Vec3::new(0.012, 0.0, 0.0), Vec3::new(0.0, 0.008, 0.0));
    let footprint = Footprint::from_half_vector_derivatives(h, dh_dx, dh_dy);
    let lobe = material.filtered(footprint, Gaussian::TK19);
    show(
        "forward_ggx: Gaussian::TK19 (A + 2 Sigma)",
        &material,
        &lobe,
    );
}

/// Forward shading, GGX, where the highlight's shape matters (close-ups, baking): the exact
/// Gaussian filter (or the exact box filter, cheaper).
fn forward_ggx_exact() {
    let material = Ggx::axis_aligned(0.01, 0.02).unwrap();
    let footprint = Footprint::from_slope_derivatives(Vec2::new(0.02, 0.0), Vec2::new(0.0, 0.01));
    let exact = material.filtered(footprint, ExactGaussian::KHPL16);
    show(
        "forward_ggx_exact: ExactGaussian::KHPL16",
        &material,
        &exact,
    );
    let boxed = material.filtered(footprint, Rect::KHPL16);
    show("forward_ggx_exact: Rect::KHPL16 (box)", &material, &boxed);
}

/// Forward shading, Beckmann: `A + 2 Sigma` is the exact filter.
fn forward_beckmann() {
    let material = Beckmann::isotropic(0.01).unwrap();
    let footprint = Footprint::from_slope_derivatives(Vec2::new(0.02, 0.0), Vec2::new(0.0, 0.01));
    let lobe = material.filtered(footprint, Gaussian::KHPL16);
    show(
        "forward_beckmann: Gaussian::KHPL16 (exact)",
        &material,
        &lobe,
    );
}

/// A renderer that differentiates the projected half vector `h_xy` (TK19 section 3.2):
/// TK21's projected-space filter.
fn projected() {
    let material = Ggx::isotropic(0.01).unwrap();
    let footprint =
        Footprint::from_projected_derivatives(Vec2::new(0.015, 0.0), Vec2::new(0.0, 0.01));
    let lobe = material.filtered(footprint, Projected::TK21);
    show("projected: Projected::TK21", &material, &lobe);
}

/// A G-buffer that stores an anisotropic roughness: the GGX proxy is a plain axis-aligned GGX.
fn gbuffer_anisotropic() {
    let material = Ggx::isotropic(0.01).unwrap();
    let footprint = Footprint::from_slope_derivatives(Vec2::new(0.02, 0.0), Vec2::new(0.0, 0.01));
    let lobe = material.filtered(footprint, Proxy::KHPL16);
    let a = lobe.roughness.alpha();
    println!(
        "gbuffer_anisotropic: store alpha = ({:.4}, {:.4})",
        a.x, a.y
    );
    show("gbuffer_anisotropic: Proxy::KHPL16", &material, &lobe);
}

/// Deferred shading with one roughness channel: normal differences to the neighbouring
/// pixels and an engine's convention.
fn deferred() {
    let alpha = 0.01;
    let (ddx_normal, ddy_normal) = (Vec3::new(0.012, 0.0, 0.0), Vec3::new(0.0, 0.008, 0.0));
    let material = Ggx::isotropic(alpha).unwrap();
    let lobe = Ggx::new(presets::TK19_TRACE.filter(alpha, ddx_normal, ddy_normal));
    show("deferred: presets::TK19_TRACE", &material, &lobe);
}

/// An offline path tracer: ray differentials through the half-vector Jacobian `M`, the
/// filtered lobe sampled for the next bounce.
fn path_tracer() {
    let frame = ShadingFrame::flat(Vec3::X, Vec3::Y, Vec3::Z);
    let (x, eye, light) = (
        Vec3::ZERO,
        Vec3::new(0.0, -3.0, 4.0),
        Vec3::new(0.0, 3.0, 4.0),
    );
    let m = geometry::half_vector_jacobian(x, Endpoint::Point(eye), Endpoint::Point(light), &frame);
    let (dx_u, dx_v) = (Vec3::new(0.05, 0.0, 0.0), Vec3::new(0.0, 0.05, 0.0));
    let footprint = Footprint::from_ray_differentials(m, &frame, dx_u, dx_v);
    let material = Ggx::isotropic(0.01).unwrap();
    let lobe = material.filtered(footprint, Gaussian::TK19);
    show(
        "path_tracer: ray differentials + Gaussian::TK19",
        &material,
        &lobe,
    );
    let wo = (eye - x).normalize();
    let mn = lobe
        .sample_visible_normal(wo, Vec2::new(0.3, 0.6))
        .expect("wo above the surface");
    let wi = filtered_ndf::f32::sampling::reflect(wo, mn);
    println!(
        "  sampled m = {mn:.4}, wi = {wi:.4}, pdf = {:.3}",
        lobe.reflection_pdf_from_normal(wo, mn)
    );
}

/// A normal-mapped surface: LEAN moments of the normal map nested into the pixel kernel
/// (KHPL16 eq. 21).
fn normal_mapped() {
    let alpha = Isotropic::new(0.01).unwrap();
    let moments = LeanMoments::new(Vec2::new(0.0, 0.0), Covariance::new(4e-4, 0.0, 1e-4));
    let pixel = Footprint::from_slope_derivatives(Vec2::new(0.01, 0.0), Vec2::new(0.0, 0.01))
        .covariance(0.5);
    let lobe = Ggx::new(filter::lean(alpha, pixel, &moments));
    show("normal_mapped: filter::lean", &Ggx::new(alpha), &lobe);
}

/// Motion blur: the temporal NDF of Tessari et al. 2020 (widened `D`, base masking).
fn motion_blur() {
    let alpha = Isotropic::new(0.01).unwrap();
    let temporal = TemporalRoughness::from_normal_rate(Vec2::new(0.4, 0.0), 1.0 / 60.0);
    let lobe = TemporalLobe::ggx(alpha, temporal.covariance());
    show("motion_blur: TemporalLobe", &Ggx::new(alpha), &lobe);
}

const ROWS: [(&str, fn()); 9] = [
    ("forward_ggx", forward_ggx),
    ("forward_ggx_exact", forward_ggx_exact),
    ("forward_beckmann", forward_beckmann),
    ("projected", projected),
    ("gbuffer_anisotropic", gbuffer_anisotropic),
    ("deferred", deferred),
    ("path_tracer", path_tracer),
    ("normal_mapped", normal_mapped),
    ("motion_blur", motion_blur),
];

fn main() {
    let wanted = std::env::args().nth(1);
    let mut ran = false;
    for (name, row) in ROWS {
        if wanted.as_deref().is_none_or(|w| w == name) {
            row();
            ran = true;
        }
    }
    if !ran {
        let names: Vec<&str> = ROWS.iter().map(|r| r.0).collect();
        eprintln!("unknown row; the rows are {}", names.join(", "));
        std::process::exit(2);
    }
}
