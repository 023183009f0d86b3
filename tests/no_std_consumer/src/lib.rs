//! no_std proof: every public family is called from a `#![no_std]` staticlib.
#![no_std]

use core::panic::PanicInfo;
use filtered_ndf::f32::{Beckmann, Ggx, Isotropic, Ndf, RoughnessMatrix};
use glam::{Vec2, Vec3};

#[panic_handler]
fn panic(_: &PanicInfo) -> ! {
    loop {}
}

/// Evaluates the NDFs; exported so that nothing is optimised away.
#[unsafe(no_mangle)]
pub extern "C" fn ndf_consumer(alpha: f32, x: f32, y: f32) -> f32 {
    let iso = Isotropic::new_clamped(alpha);
    let m = Vec3::new(x, y, 1.0).normalize_or_zero();
    let mat =
        RoughnessMatrix::new(alpha * alpha, 0.0, alpha * alpha).unwrap_or_else(|_| iso.into());
    Ggx::new(iso).d(m)
        + Beckmann::new(iso).d(m)
        + Ggx::new(mat).p22(Vec2::new(x, y))
        + Beckmann::new(mat).lambda(m)
}
