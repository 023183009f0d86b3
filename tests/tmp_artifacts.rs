use filtered_ndf::testing::fuzz::*;
#[test]
fn artifacts() {
    let t = std::env::var("T").unwrap();
    let check: fn(&[u8]) = match t.as_str() {
        "filter" => check_filter,
        "rect" => check_rect,
        "isotropic" => check_isotropic,
        "jacobian" => check_jacobian,
        "sampling" => check_sampling,
        "temporal" => check_temporal,
        _ => check_ndf,
    };
    std::panic::set_hook(Box::new(|_| {}));
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fuzz/artifacts")
        .join(&t);
    let mut fails = 0;
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        let b = std::fs::read(&p).unwrap();
        if let Err(err) = std::panic::catch_unwind(|| check(&b)) {
            fails += 1;
            let msg = err
                .downcast_ref::<String>()
                .cloned()
                .or(err.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            println!(
                "FAIL {} :: {}",
                p.file_name().unwrap().to_string_lossy(),
                &msg[..msg.len().min(400)]
            );
        }
    }
    println!("fails: {fails}");
}
