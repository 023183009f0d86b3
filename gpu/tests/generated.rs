//! `shaders/generated/`: up to date with the WGSL modules, validated by naga (in the
//! generator) and, for the SPIR-V translation, by `spirv-val`. No GPU needed.

use filtered_ndf_gpu::generate;

#[test]
fn generated_files_are_up_to_date() {
    let differ = generate::run(true).expect("generation succeeds (naga parses and validates)");
    assert!(
        differ.is_empty(),
        "shaders/generated/ is out of date; run `cargo run -p filtered-ndf-gpu --bin generate` and commit: {differ:?}"
    );
}

#[test]
fn spirv_translation_passes_spirv_val() {
    let wgsl = generate::with_entry(&generate::concatenated().expect("concatenation"));
    let (module, info) = generate::parse_and_validate(&wgsl, "concatenated").expect("valid");
    let words = generate::spirv(&module, &info).expect("SPIR-V");
    let path = std::env::temp_dir().join(format!("filtered_ndf_{}.spv", std::process::id()));
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
    std::fs::write(&path, bytes).expect("write SPIR-V");
    let out = std::process::Command::new("spirv-val")
        .arg(&path)
        .output()
        .unwrap_or_else(|e| {
            panic!("spirv-val not found ({e}): install it with `apt-get install spirv-tools`")
        });
    let _ = std::fs::remove_file(&path);
    assert!(
        out.status.success(),
        "spirv-val rejects naga's SPIR-V: {}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}
