//! The WGSL modules of `filtered-ndf`: microfacet NDFs (GGX, Beckmann; isotropic,
//! axis-aligned and full-matrix roughness), pixel footprints, filter kernels and clamps, and
//! the filtered NDFs of KHPL16, TK19/TK21 and Tessari et al. 2020, as shader code.
//!
//! Each module is one file that starts with `#define_import_path filtered_ndf::<path>` (the
//! file `ndf/ggx.wgsl` is `filtered_ndf::ndf::ggx`, `ndf/mod.wgsl` is `filtered_ndf::ndf`) and
//! imports the others by path, as naga_oil composes them (Bevy's shader imports). [`MODULES`]
//! holds every module's import path, file and source, in import order (each after the modules
//! it imports); [`module`] finds one by import path. No dependencies, `no_std`.
//!
//! In Bevy, add each module as a shader asset (keeping the handles alive) and import them by
//! path from your own shaders:
//!
//! ```ignore
//! for m in filtered_ndf_wgsl::MODULES {
//!     handles.push(shaders.add(Shader::from_wgsl(m.source, m.file)));
//! }
//! ```
//!
//! With naga_oil directly, add them to a `Composer` in the order of [`MODULES`]
//! (`add_composable_module` with `source: m.source`, `file_path: m.file`).
//!
//! The repository's `shaders/README.md` documents the modules; every exported function is
//! tested on GPU drivers against the Rust crate's `f64` references (the `filtered-ndf-gpu`
//! harness).
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

mod modules;

pub use modules::MODULES;

/// One WGSL module.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Module {
    /// Its import path, the argument of its `#define_import_path`
    /// (`filtered_ndf::ndf::ggx`).
    pub import_path: &'static str,
    /// Its file, relative to the crate root with `/` separators (`ndf/ggx.wgsl`).
    pub file: &'static str,
    /// Its WGSL source.
    pub source: &'static str,
}

/// The module of [`MODULES`] whose import path is `import_path` (`None` for any other).
pub fn module(import_path: &str) -> Option<&'static Module> {
    MODULES.iter().find(|m| m.import_path == import_path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_module_declares_its_import_path() {
        assert!(!MODULES.is_empty());
        for m in MODULES {
            let declared = m
                .source
                .lines()
                .find_map(|l| l.trim().strip_prefix("#define_import_path"))
                .map(str::trim);
            assert_eq!(declared, Some(m.import_path), "{}", m.file);
            assert_eq!(module(m.import_path), Some(m));
        }
        assert_eq!(module("filtered_ndf::no_such_module"), None);
    }

    #[test]
    fn modules_come_after_their_imports() {
        for (i, m) in MODULES.iter().enumerate() {
            for line in m.source.lines() {
                let Some(rest) = line.trim().strip_prefix("#import") else {
                    continue;
                };
                let path = rest.split(" as ").next().unwrap_or(rest).trim();
                let at = MODULES.iter().position(|d| d.import_path == path);
                assert!(
                    at.is_some_and(|at| at < i),
                    "{} imports {path}, which is not before it",
                    m.import_path
                );
            }
        }
    }
}
