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

fn glslang(path: &std::path::Path) -> std::process::Output {
    std::process::Command::new("glslangValidator")
        .arg(path)
        .output()
        .unwrap_or_else(|e| {
            panic!(
                "glslangValidator not found ({e}): install it with `apt-get install glslang-tools`"
            )
        })
}

/// The GLSL translations compile with the Khronos reference compiler, and so does the
/// README's GLSL example pasted into the 330 file (before the translation's entry point).
#[test]
fn glsl_translations_pass_glslang() {
    let dir = generate::generated_dir();
    let tmp = std::env::temp_dir().join(format!("filtered_ndf_glsl_{}", std::process::id()));
    std::fs::create_dir_all(&tmp).expect("temp dir");
    let readme =
        std::fs::read_to_string(filtered_ndf_gpu::modules::shaders_dir().join("README.md"))
            .expect("shaders/README.md");
    let start = readme.find("```glsl\n").expect("a GLSL block") + "```glsl\n".len();
    let example = &readme[start..start + readme[start..].find("```").expect("closed")];
    for name in ["filtered_ndf.330.glsl", "filtered_ndf.310es.glsl"] {
        let src = std::fs::read_to_string(dir.join(name)).expect("generated file");
        let path = tmp.join(name.replace(".glsl", ".frag"));
        std::fs::write(&path, &src).expect("write");
        let out = glslang(&path);
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stdout)
        );
        if name.contains("330") {
            let at = src.rfind("void main()").expect("the entry point");
            let with_example = format!("{}{example}\n{}", &src[..at], &src[at..]);
            let path = tmp.join("readme_example.frag");
            std::fs::write(&path, with_example).expect("write");
            let out = glslang(&path);
            assert!(
                out.status.success(),
                "README GLSL example: {}",
                String::from_utf8_lossy(&out.stdout)
            );
        }
    }
    let _ = std::fs::remove_dir_all(&tmp);
}
