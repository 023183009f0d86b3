//! naga_oil composition of the modules of `shaders/`, as Bevy composes its shaders: every
//! module composes on its own, and a fragment shader in Bevy's style imports and calls them;
//! the modules come from the `filtered-ndf-wgsl` crate's table, which holds every file on
//! disk. No GPU needed.

use filtered_ndf_gpu::modules::{compose, load_all, load_from_disk};

#[test]
fn the_crates_table_holds_every_file_on_disk() {
    let key = |m: &filtered_ndf_gpu::modules::Module| (m.path.clone(), m.file.clone());
    let shipped = load_all().expect("the crate's modules load");
    let disk = load_from_disk().expect("the files load");
    assert_eq!(
        shipped.iter().map(key).collect::<Vec<_>>(),
        disk.iter().map(key).collect::<Vec<_>>(),
        "shaders/src/modules.rs is out of date: run `cargo run -p filtered-ndf-gpu --bin generate`"
    );
    for (s, d) in shipped.iter().zip(&disk) {
        assert!(
            s.source == d.source,
            "{}: the crate's source differs",
            s.file
        );
    }
}

#[test]
fn every_module_composes_alone() {
    let modules = load_all().expect("modules load");
    assert!(modules.len() >= 10, "found {} modules", modules.len());
    for m in &modules {
        let src = format!(
            "#import {}\n@fragment\nfn main() -> @location(0) vec4<f32> {{\n    return vec4<f32>(0.0);\n}}\n",
            m.path
        );
        compose(&src, "alone.wgsl").unwrap_or_else(|e| panic!("{}: {e}", m.path));
    }
}

/// The fenced block of `language` in `shaders/README.md` (its first).
fn readme_block(language: &str) -> String {
    let readme =
        std::fs::read_to_string(filtered_ndf_gpu::modules::shaders_dir().join("README.md"))
            .expect("shaders/README.md");
    let fence = format!("```{language}\n");
    let start = readme.find(&fence).expect("a fenced block") + fence.len();
    let len = readme[start..].find("```").expect("closed");
    readme[start..start + len].to_string()
}

#[test]
fn readme_fragment_shader_composes() {
    let src = readme_block("wgsl");
    let module = compose(&src, "shaders/README.md").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(module.entry_points.len(), 1);
}
