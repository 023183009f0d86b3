//! The WGSL modules under `shaders/` (the `filtered-ndf-wgsl` crate): discovery, import
//! graph and naga_oil composition.
//!
//! Layout rule (checked here): the file `shaders/a/b/c.wgsl` declares
//! `#define_import_path filtered_ndf::a::b::c`, and `shaders/a/mod.wgsl` declares
//! `filtered_ndf::a`, mirroring the Rust module tree one to one. Imports are written in one of
//! two forms, `#import filtered_ndf::a::b` (items used as `b::item`) or
//! `#import filtered_ndf::a::b as x` (items used as `x::item`); the concatenated file
//! ([`crate::concat`]) relies on that.

use naga_oil::compose::{
    ComposableModuleDescriptor, Composer, NagaModuleDescriptor, ShaderLanguage, ShaderType,
};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, OnceLock};

/// The root of every import path.
pub const ROOT: &str = "filtered_ndf";

/// The `shaders/` directory of the repository.
pub fn shaders_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../shaders")
}

/// One `#import` line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Import {
    /// The name the importing module uses (`x` in `x::item`).
    pub alias: String,
    /// The imported module's import path.
    pub path: String,
}

/// A WGSL module of the `shaders/` tree.
#[derive(Clone, Debug)]
pub struct Module {
    /// Its import path, e.g. `filtered_ndf::ndf::ggx`.
    pub path: String,
    /// The file, relative to `shaders/`, with `/` separators.
    pub file: String,
    /// The source text.
    pub source: String,
    /// Its imports, in order.
    pub imports: Vec<Import>,
}

impl Module {
    /// The module's short name: the last segment of its import path.
    pub fn short_name(&self) -> &str {
        self.path.rsplit("::").next().unwrap_or(&self.path)
    }
}

/// The import path a file must declare: `filtered_ndf::` and the file's path without the
/// extension, `mod` dropped.
pub fn expected_import_path(file: &str) -> String {
    let stem = file.strip_suffix(".wgsl").unwrap_or(file);
    let mut parts: Vec<&str> = stem.split('/').collect();
    if parts.last() == Some(&"mod") {
        parts.pop();
    }
    let mut p = String::from(ROOT);
    for s in parts {
        p.push_str("::");
        p.push_str(s);
    }
    p
}

/// Parses the `#import` lines of a source (the two forms of the module docs).
pub fn parse_imports(source: &str) -> Result<Vec<Import>, String> {
    let mut out = Vec::new();
    for line in source.lines() {
        let Some(rest) = line.trim().strip_prefix("#import") else {
            continue;
        };
        let rest = rest.trim().trim_end_matches(';').trim();
        let (path, alias) = match rest.split_once(" as ") {
            Some((p, a)) => (p.trim(), a.trim().to_string()),
            None => (rest, rest.rsplit("::").next().unwrap_or(rest).to_string()),
        };
        if path.contains(['{', '}', ',', '*']) || !path.starts_with(ROOT) {
            return Err(format!(
                "unsupported import `{rest}`: write `#import {ROOT}::a::b [as x]`"
            ));
        }
        out.push(Import {
            alias,
            path: path.to_string(),
        });
    }
    Ok(out)
}

/// The `#define_import_path` of a source.
pub fn declared_path(source: &str) -> Option<String> {
    source.lines().find_map(|l| {
        l.trim()
            .strip_prefix("#define_import_path")
            .map(|p| p.trim().to_string())
    })
}

fn walk(dir: &Path, base: &Path, out: &mut Vec<String>) -> std::io::Result<()> {
    let mut entries: Vec<_> = std::fs::read_dir(dir)?.collect::<Result<_, _>>()?;
    entries.sort_by_key(|e| e.path());
    for e in entries {
        let p = e.path();
        if p.is_dir() {
            if p.file_name().is_some_and(|n| n == "generated") {
                continue;
            }
            walk(&p, base, out)?;
        } else if p.extension().is_some_and(|x| x == "wgsl") {
            let rel = p.strip_prefix(base).expect("under base");
            let rel: Vec<String> = rel
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            out.push(rel.join("/"));
        }
    }
    Ok(())
}

/// Every module of `shaders/` as the `filtered-ndf-wgsl` crate ships it
/// (`filtered_ndf_wgsl::MODULES`, the one source the composer, the harness and a Bevy plugin
/// read), checked against the layout rule and sorted so that each module comes after
/// everything it imports (ties by path).
pub fn load_all() -> Result<Vec<Module>, String> {
    checked(
        filtered_ndf_wgsl::MODULES
            .iter()
            .map(|m| (m.file.to_string(), m.source.to_string())),
    )
}

/// Every `.wgsl` file under `shaders/` (outside `generated/`) as read from disk now, checked
/// and sorted as [`load_all`]: what `generate` writes the crate's table from.
/// `gpu/tests/composition.rs` requires the two to agree.
pub fn load_from_disk() -> Result<Vec<Module>, String> {
    let base = shaders_dir();
    let mut files = Vec::new();
    walk(&base, &base, &mut files).map_err(|e| format!("reading {}: {e}", base.display()))?;
    let mut sources = Vec::new();
    for file in files {
        let source = std::fs::read_to_string(base.join(&file))
            .map_err(|e| format!("reading shaders/{file}: {e}"))?;
        sources.push((file, source));
    }
    checked(sources)
}

/// Modules from `(file, source)` pairs: each checked against the layout rule and the import
/// forms, sorted in import order.
fn checked(sources: impl IntoIterator<Item = (String, String)>) -> Result<Vec<Module>, String> {
    let mut by_path = BTreeMap::new();
    for (file, source) in sources {
        let expected = expected_import_path(&file);
        match declared_path(&source) {
            Some(p) if p == expected => {}
            other => {
                return Err(format!(
                    "shaders/{file} must declare `#define_import_path {expected}` (found {other:?})"
                ));
            }
        }
        let imports = parse_imports(&source).map_err(|e| format!("shaders/{file}: {e}"))?;
        // naga_oil reads `name::` as a module path even where `name` is a function of the
        // module: an item may not share its name with an import alias.
        let names = crate::syntax::top_level_names(&source);
        if let Some(i) = imports.iter().find(|i| names.contains(&i.alias)) {
            return Err(format!(
                "shaders/{file}: `{}` is both an item and an import alias: import `{}` with `as`",
                i.alias, i.path
            ));
        }
        let module = Module {
            path: expected.clone(),
            file,
            source,
            imports,
        };
        if let Some(old) = by_path.insert(expected, module) {
            return Err(format!(
                "shaders/{}: a second module {}",
                old.file, old.path
            ));
        }
    }
    // Topological order (depth first, dependencies first).
    let mut order: Vec<Module> = Vec::new();
    let mut state: BTreeMap<String, u8> = BTreeMap::new();
    fn visit(
        p: &str,
        all: &BTreeMap<String, Module>,
        state: &mut BTreeMap<String, u8>,
        order: &mut Vec<Module>,
    ) -> Result<(), String> {
        match state.get(p) {
            Some(2) => return Ok(()),
            Some(1) => return Err(format!("import cycle through {p}")),
            _ => {}
        }
        let m = all.get(p).ok_or_else(|| format!("unknown module {p}"))?;
        state.insert(p.to_string(), 1);
        for i in &m.imports {
            visit(&i.path, all, state, order)
                .map_err(|e| format!("{e} (imported by {})", m.path))?;
        }
        state.insert(p.to_string(), 2);
        order.push(m.clone());
        Ok(())
    }
    for p in by_path.keys() {
        visit(p, &by_path, &mut state, &mut order)?;
    }
    Ok(order)
}

/// A naga_oil composer holding every module of `shaders/`.
pub fn composer() -> Result<Composer, String> {
    let mut c = Composer::default();
    for m in load_all()? {
        let file_path = format!("shaders/{}", m.file);
        let err = c
            .add_composable_module(ComposableModuleDescriptor {
                source: &m.source,
                file_path: &file_path,
                language: ShaderLanguage::Wgsl,
                ..Default::default()
            })
            .err();
        if let Some(e) = err {
            return Err(e.emit_to_string(&c));
        }
    }
    Ok(c)
}

/// Composes a top-level WGSL shader (which `#import`s modules of `shaders/`) into one
/// validated naga module, with a composer shared by the whole process.
pub fn compose(source: &str, file_path: &str) -> Result<naga::Module, String> {
    static COMPOSER: OnceLock<Result<Mutex<Composer>, String>> = OnceLock::new();
    let c = COMPOSER
        .get_or_init(|| composer().map(Mutex::new))
        .as_ref()
        .map_err(Clone::clone)?;
    let mut c = c.lock().unwrap_or_else(|e| e.into_inner());
    c.make_naga_module(NagaModuleDescriptor {
        source,
        file_path,
        shader_type: ShaderType::Wgsl,
        ..Default::default()
    })
    .map_err(|e| e.emit_to_string(&c))
}
