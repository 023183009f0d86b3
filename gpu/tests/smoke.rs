use filtered_ndf_gpu::harness::{run, Kernel, gpu};
#[test]
fn smoke() {
    eprintln!("{}", gpu().unwrap().label());
    let k = Kernel { imports: "#import filtered_ndf::math", body: "y(0u, atan(x(0u)) * math::PI);", n_in: 1, n_out: 1 };
    let xs: Vec<f32> = (0..1000).map(|i| i as f32 * 0.01).collect();
    let out = run(&k, &xs).unwrap();
    let mut worst = 0.0f64;
    for (x, o) in xs.iter().zip(&out) { let r = (*x as f64).atan() * (std::f32::consts::PI as f64); if r != 0.0 { worst = worst.max(((*o as f64) - r).abs() / r); } }
    eprintln!("worst {worst:e}");
}
