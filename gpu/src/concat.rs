//! The single concatenated WGSL file, for those who paste instead of composing.
//!
//! Every module of `shaders/` in import order, its `#define_import_path` and `#import` lines
//! dropped and its top-level names prefixed with its path below `filtered_ndf`, joined by
//! `_`, `mod` dropped: `ggx::d_isotropic` of `filtered_ndf::ndf::ggx` becomes
//! `ndf_ggx_d_isotropic`, `math::PI` becomes `math_PI`. The rewrite is a consistent renaming
//! of identifier tokens outside comments: in a module, every token that names one of its own
//! top-level items (and is not a member: not preceded by `.`, not a field declaration in
//! a struct body) gets the module's
//! prefix, and every `alias::item` of an import becomes `prefix_item`. A local that shares a
//! name with a top-level item of its module is renamed with it, consistently, so meaning is
//! preserved; the result is validated by naga ([`crate::generate`]) and evaluated on the GPU
//! against the composed modules (`gpu/tests/concat.rs`).

use crate::modules::{Module, ROOT};
use std::collections::{BTreeMap, BTreeSet};

/// The prefix of a module's names in the concatenated file: its path below `filtered_ndf`
/// joined by `_` (`filtered_ndf::ndf::ggx` -> `ndf_ggx`).
pub fn prefix(path: &str) -> String {
    path.strip_prefix(ROOT)
        .unwrap_or(path)
        .trim_start_matches("::")
        .replace("::", "_")
}

/// The top-level item names a module declares (`fn`, `struct`, `const`, `alias`,
/// `override`, `var` at brace depth 0).
pub fn top_level_names(source: &str) -> BTreeSet<String> {
    let mut names = BTreeSet::new();
    let mut depth = 0i32;
    let toks = tokens(source);
    let mut i = 0;
    while i < toks.len() {
        match &toks[i] {
            Tok::Punct('{') => depth += 1,
            Tok::Punct('}') => depth -= 1,
            Tok::Ident(k)
                if depth == 0
                    && matches!(
                        k.as_str(),
                        "fn" | "struct" | "const" | "alias" | "override" | "var"
                    ) =>
            {
                // The next identifier (past whitespace, comments and the template list of
                // `var<private> name`).
                let mut j = i + 1;
                while j < toks.len() && !matches!(toks[j], Tok::Ident(_)) {
                    j += 1;
                }
                if let Some(Tok::Ident(n)) = toks.get(j) {
                    names.insert(n.clone());
                }
            }
            _ => {}
        }
        i += 1;
    }
    names
}

/// A lexical token: enough of WGSL to rename identifiers safely.
#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    Punct(char),
    /// Anything else kept verbatim: whitespace, comments, numbers, `#` lines.
    Other(String),
}

fn tokens(src: &str) -> Vec<Tok> {
    let b: Vec<char> = src.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c == '/' && b.get(i + 1) == Some(&'/') {
            let s = i;
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
            out.push(Tok::Other(b[s..i].iter().collect()));
        } else if c == '/' && b.get(i + 1) == Some(&'*') {
            let s = i;
            i += 2;
            while i + 1 < b.len() && !(b[i] == '*' && b[i + 1] == '/') {
                i += 1;
            }
            i = (i + 2).min(b.len());
            out.push(Tok::Other(b[s..i].iter().collect()));
        } else if c == '#' {
            let s = i;
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
            out.push(Tok::Other(b[s..i].iter().collect()));
        } else if c.is_ascii_alphabetic() || c == '_' {
            let s = i;
            while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == '_') {
                i += 1;
            }
            out.push(Tok::Ident(b[s..i].iter().collect()));
        } else if c.is_ascii_digit() {
            // A number, including exponents and suffixes (`1e-8`, `2.5f`, `3u`).
            let s = i;
            while i < b.len()
                && (b[i].is_ascii_alphanumeric()
                    || b[i] == '.'
                    || ((b[i] == '-' || b[i] == '+') && matches!(b[i - 1], 'e' | 'E')))
            {
                i += 1;
            }
            out.push(Tok::Other(b[s..i].iter().collect()));
        } else if c.is_whitespace() {
            let s = i;
            while i < b.len() && b[i].is_whitespace() {
                i += 1;
            }
            out.push(Tok::Other(b[s..i].iter().collect()));
        } else {
            out.push(Tok::Punct(c));
            i += 1;
        }
    }
    out
}

/// Rewrites one source: drops `#define_import_path` and `#import` lines, prefixes its own
/// top-level names with `own` (if given) and replaces `alias::item` by `prefix_item` for
/// the aliases in `imports` (alias -> prefix).
pub fn rewrite(
    source: &str,
    own: Option<(&str, &BTreeSet<String>)>,
    imports: &BTreeMap<String, String>,
) -> Result<String, String> {
    let toks = tokens(source);
    let mut out = String::new();
    // Inside a struct body, field declarations keep their names (members are never
    // renamed): `struct` seen (1), its body open (2).
    let mut in_struct = 0u8;
    let mut i = 0;
    while i < toks.len() {
        match &toks[i] {
            Tok::Ident(k) if k == "struct" => in_struct = 1,
            Tok::Punct('{') if in_struct == 1 => in_struct = 2,
            Tok::Punct('}') if in_struct == 2 => in_struct = 0,
            _ => {}
        }
        match &toks[i] {
            Tok::Other(s) if s.starts_with("#define_import_path") || s.starts_with("#import") => {
                // Drop the directive and the line break after it.
                i += 1;
                if let Some(Tok::Other(ws)) = toks.get(i)
                    && ws.trim().is_empty()
                {
                    out.push_str(ws.strip_prefix('\n').unwrap_or(ws));
                    i += 1;
                }
                continue;
            }
            Tok::Ident(name) => {
                let is_path = matches!(toks.get(i + 1), Some(Tok::Punct(':')))
                    && matches!(toks.get(i + 2), Some(Tok::Punct(':')));
                if is_path {
                    let Some(p) = imports.get(name) else {
                        return Err(format!("`{name}::` is not an imported module"));
                    };
                    let Some(Tok::Ident(item)) = toks.get(i + 3) else {
                        return Err(format!("`{name}::` must be followed by a name"));
                    };
                    out.push_str(&format!("{p}_{item}"));
                    i += 4;
                    continue;
                }
                let member = (i > 0 && toks[i - 1] == Tok::Punct('.')) || in_struct == 2;
                match own {
                    Some((p, names)) if !member && names.contains(name) => {
                        out.push_str(&format!("{p}_{name}"));
                    }
                    _ => out.push_str(name),
                }
            }
            Tok::Punct(c) => out.push(*c),
            Tok::Other(s) => out.push_str(s),
        }
        i += 1;
    }
    Ok(out)
}

/// The alias -> prefix map of a module's imports.
pub fn import_prefixes(m: &Module) -> BTreeMap<String, String> {
    m.imports
        .iter()
        .map(|i| (i.alias.clone(), prefix(&i.path)))
        .collect()
}

/// The concatenated file of `modules` (in import order, as [`crate::modules::load_all`]
/// returns them), with a header.
pub fn concatenate(modules: &[Module]) -> Result<String, String> {
    let mut out = String::from(
        "// filtered-ndf: every WGSL module of shaders/ in one file, for pasting.\n\
         // Generated by `cargo run -p filtered-ndf-gpu --bin generate`; do not edit.\n\
         // Each module's names carry its path as a prefix: `ggx::d_isotropic` of\n\
         // `filtered_ndf::ndf::ggx` is `ndf_ggx_d_isotropic` here, `math::PI` is `math_PI`.\n\
         // The documentation of each function is the one of its module under shaders/.\n",
    );
    for m in modules {
        let names = top_level_names(&m.source);
        let p = prefix(&m.path);
        let body = rewrite(&m.source, Some((&p, &names)), &import_prefixes(m))
            .map_err(|e| format!("shaders/{}: {e}", m.file))?;
        out.push_str(&format!(
            "\n// ---- {} (shaders/{}) ----\n{}",
            m.path,
            m.file,
            body.trim_start_matches('\n')
        ));
        if !out.ends_with('\n') {
            out.push('\n');
        }
    }
    Ok(out)
}

/// A top-level shader written against the modules (`#import`s of the two supported forms)
/// rewritten to run against the concatenated file: its `alias::item` references become the
/// prefixed names; its own names are kept.
pub fn rewrite_user_shader(source: &str) -> Result<String, String> {
    let imports = crate::modules::parse_imports(source)?;
    let map = imports
        .iter()
        .map(|i| (i.alias.clone(), prefix(&i.path)))
        .collect();
    rewrite(source, None, &map)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_rewrite() {
        let s = "#import filtered_ndf::math\nstruct A {\n    x: f32,\n}\nconst K: f32 = 1.0;\nfn f(a: A) -> f32 {\n    let f = a.x;\n    return f * K + math::PI;\n}\n";
        let names = top_level_names(s);
        let toks = tokens(s);
        assert_eq!(
            names.iter().cloned().collect::<Vec<_>>(),
            ["A", "K", "f"],
            "{toks:?}"
        );
        let mut imports = BTreeMap::new();
        imports.insert("math".to_string(), "math".to_string());
        let r = rewrite(s, Some(("m", &names)), &imports).unwrap();
        assert_eq!(
            r,
            "struct m_A {\n    x: f32,\n}\nconst m_K: f32 = 1.0;\nfn m_f(a: m_A) -> f32 {\n    let m_f = a.x;\n    return m_f * m_K + math_PI;\n}\n"
        );
    }
}
