//! Evaluates GGX and Beckmann at one micronormal, unfiltered and in every roughness form.
//! Run: `cargo run --release --example basic`.

use filtered_ndf::f64::{AxisAligned, Beckmann, Ggx, Isotropic, Ndf, RoughnessMatrix};
use glam::DVec3;

fn main() {
    let alpha = 0.05;
    let m = DVec3::new(0.02, 0.01, 1.0).normalize();
    let iso = Isotropic::new(alpha).expect("valid roughness");
    let aniso = AxisAligned::new(alpha, 2.0 * alpha).expect("valid roughness");
    let matrix = RoughnessMatrix::new(alpha * alpha, 0.5 * alpha * alpha, 4.0 * alpha * alpha)
        .expect("valid roughness");
    println!("micronormal m = {m:?}");
    println!(
        "{:<28} {:>14} {:>14}",
        "roughness", "GGX D(m)", "Beckmann D(m)"
    );
    println!(
        "{:<28} {:>14.6} {:>14.6}",
        "isotropic 0.05",
        Ggx::new(iso).d(m),
        Beckmann::new(iso).d(m)
    );
    println!(
        "{:<28} {:>14.6} {:>14.6}",
        "axis-aligned (0.05, 0.1)",
        Ggx::new(aniso).d(m),
        Beckmann::new(aniso).d(m)
    );
    println!(
        "{:<28} {:>14.6} {:>14.6}",
        "matrix [[a2, a2/2], [., 4a2]]",
        Ggx::new(matrix).d(m),
        Beckmann::new(matrix).d(m)
    );
}
