//! no_std proof: every public family is called from a `#![no_std]` staticlib.
#![no_std]

use core::panic::PanicInfo;
use filtered_ndf::f32::{
    Beckmann, ClampRules, Footprint, Ggx, Isotropic, Ndf, NdfSampling, RoughnessMatrix,
    TemporalLobe, TemporalRoughness, filter::presets, filter::proxy, filter::rect,
    footprint::jacobian,
};
use glam::{Vec2, Vec3};

#[panic_handler]
fn panic(_: &PanicInfo) -> ! {
    loop {}
}

/// Evaluates one member of every family; exported so that nothing is optimised away.
#[unsafe(no_mangle)]
pub extern "C" fn ndf_consumer(alpha: f32, x: f32, y: f32) -> f32 {
    let iso = Isotropic::new_clamped(alpha);
    let m = Vec3::new(x, y, 1.0).normalize_or_zero();
    let mat =
        RoughnessMatrix::new(alpha * alpha, 0.0, alpha * alpha).unwrap_or_else(|_| iso.into());
    let fp = Footprint::from_slope_derivatives(Vec2::new(x, 0.0), Vec2::new(0.0, y));
    let filtered = ClampRules::default().filter_gaussian(iso, fp, 0.5);
    let rect = rect::d_rect(iso.into(), m, fp.bounding_rect().half_extent);
    let proxy = Ggx::new(proxy::proxy(iso.into(), Vec2::new(x, y))).d(m);
    let jac = jacobian::sphere_to_slope(m).determinant();
    let deferred = presets::TK19_TRACE.apply(alpha, Vec3::new(x, 0.0, 0.0), Vec3::ZERO);
    let sampled = Ggx::new(mat)
        .sample_visible_normal(Vec3::Z, Vec2::new(x.abs().min(0.99), y.abs().min(0.99)))
        .map_or(0.0, |s| s.z);
    let temporal = TemporalRoughness::from_normal_rate(Vec2::new(x, y), 0.01);
    let lobe = TemporalLobe::ggx(iso, temporal.covariance());
    Ggx::new(iso).d(m)
        + Beckmann::new(filtered).d(m)
        + Ggx::new(mat).p22(Vec2::new(x, y))
        + Beckmann::new(mat).lambda(m)
        + rect
        + proxy
        + jac
        + deferred
        + sampled
        + lobe.d(m)
        + lobe.g1(m, m)
}
