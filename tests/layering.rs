//! The source layout follows the pipeline: no module imports a later stage, and no two source
//! files import each other (directly or around a longer cycle).
//!
//! Stages, in order: the foundation (`math`, `error`, `contract`, `tables`, the precision
//! roots' `F`/`Vec2`/`Vec3`/`Mat2`/`PI`, `vector`) -> `ndf` -> `footprint` -> `kernel` ->
//! `filter` -> `sampling` -> `bsdf` (the BSDF layer samples and filters lobes, so it comes
//! after both). Beside them: `temporal`, `batch`, `bake` (crate level, both precisions) and
//! `testing`, which may import any stage and which no stage imports; `prelude`, which gathers
//! every stage. No exceptions: no file may import a later stage or sit on a cycle. The precision-generic
//! modules are loaded twice by `precision_modules!` in `src/lib.rs` (`crate::f32::...`,
//! `crate::f64::...`); both count as the module of the file they load.
//!
//! The test reads every `.rs` file under `src/` (comments and literals blanked), collects every
//! `use` tree and every `crate::`, `super::`, `self::` path in code, resolves each through the
//! modules' definitions and re-exports to the file that defines the item (following `pub use`
//! chains and the parents' imports that children reach through `super::`), and then checks:
//!
//! 1. every module on the way and the defining file belong to a stage no later than the
//!    importing file's (a stage file may not name `temporal`, `batch`, `testing` or `prelude`);
//! 2. the graph of files, with an edge for each private `use` and each path in code (a `pub
//!    use` re-export is a facade, followed through, not an edge of its own), has no cycle.
//!
//! Each failure names the importing file, its line, the path and the stage it reaches.
//!
//! The WGSL mirror under `shaders/` follows the same stages: each `#import filtered_ndf::...`
//! of a module names a stage no later than the module's own (naga_oil itself rejects cycles).

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// Cycles between files that are known and owned elsewhere: each entry names both files.
/// Empty: every cycle fails the test.
const KNOWN_CYCLES: &[(&str, &str, &str)] = &[];

/// The crates a path may start with that are not this crate.
const EXTERNAL: &[&str] = &[
    "glam", "core", "std", "alloc", "libm", "proptest", "pulp", "rayon", "approx",
];

// ---------------------------------------------------------------------------------------------
// Stages.

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Stage {
    /// `lib.rs`, `f32.rs`, `f64.rs`: the facades that declare the modules.
    Root,
    /// Math backend, errors, the contract, the precision aliases, vector helpers.
    Foundation,
    Ndf,
    Footprint,
    Kernel,
    Filter,
    Sampling,
    /// The BSDF layer (`bsdf`): lobes, Fresnel and the sampled, filtered reflection.
    Bsdf,
    /// `temporal`, `batch`, `bake`, `testing`: beside the pipeline, importing any stage.
    Beside,
    /// `prelude`: gathers every stage.
    Prelude,
}

impl Stage {
    /// The rank of a pipeline stage (`None` for the roots, the modules beside and the prelude).
    fn rank(self) -> Option<u8> {
        Some(match self {
            Stage::Foundation => 0,
            Stage::Ndf => 1,
            Stage::Footprint => 2,
            Stage::Kernel => 3,
            Stage::Filter => 4,
            Stage::Sampling => 5,
            Stage::Bsdf => 6,
            _ => return None,
        })
    }

    /// Whether a file of stage `self` may name a module or item of stage `target`.
    fn may_import(self, target: Stage) -> bool {
        match (self.rank(), target) {
            (_, Stage::Root) => true,
            (None, _) => true,
            (Some(_), Stage::Beside | Stage::Prelude) => false,
            (Some(a), t) => t.rank().is_some_and(|b| b <= a),
        }
    }
}

/// The stage of a module path (`["crate", "P", "kernel", ...]`; `P` is either precision).
fn stage_of(module: &[String]) -> Stage {
    let seg = |i: usize| module.get(i).map(String::as_str);
    match (seg(1), seg(2)) {
        (None, _) => Stage::Root,
        (Some("P"), None) => Stage::Root,
        (Some("P"), Some(s)) => match s {
            "ndf" => Stage::Ndf,
            "footprint" => Stage::Footprint,
            "kernel" => Stage::Kernel,
            "filter" => Stage::Filter,
            "sampling" => Stage::Sampling,
            "bsdf" => Stage::Bsdf,
            "temporal" | "batch" => Stage::Beside,
            "prelude" => Stage::Prelude,
            "vector" => Stage::Foundation,
            other => panic!("src/lib.rs loads a precision module `{other}` of no known stage"),
        },
        (Some("testing" | "bake"), _) => Stage::Beside,
        (Some("math" | "error" | "contract" | "tables"), _) => Stage::Foundation,
        (Some(other), _) => panic!("crate module `{other}` of no known stage"),
    }
}

// ---------------------------------------------------------------------------------------------
// Source text: comments and literals blanked, line numbers kept.

/// `src` with comments, string and character literals replaced by spaces (newlines kept).
fn blank_comments_and_literals(src: &str) -> String {
    let b: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let mut i = 0;
    let blank = |c: char| if c == '\n' { '\n' } else { ' ' };
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < b.len() && b[i] != '\n' {
                out.push(' ');
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == '/' && b.get(i + 1) == Some(&'*') {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if b[i] == '*' && b.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    out.push(blank(b[i]));
                    i += 1;
                }
            }
        } else if c == 'r'
            && (next == Some('"') || next == Some('#'))
            && !b[..i]
                .last()
                .is_some_and(|p| p.is_alphanumeric() || *p == '_')
        {
            // A raw string r"..." or r#"..."# (or an identifier starting with r#).
            let mut j = i + 1;
            let mut hashes = 0;
            while b.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if b.get(j) != Some(&'"') {
                out.push(c);
                i += 1;
                continue;
            }
            j += 1;
            loop {
                if j >= b.len() {
                    break;
                }
                if b[j] == '"' && (0..hashes).all(|k| b.get(j + 1 + k) == Some(&'#')) {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            for &ch in &b[i..j.min(b.len())] {
                out.push(blank(ch));
            }
            i = j;
        } else if c == '"' {
            out.push(' ');
            i += 1;
            while i < b.len() && b[i] != '"' {
                if b[i] == '\\' {
                    out.push(' ');
                    i += 1;
                }
                if i < b.len() {
                    out.push(blank(b[i]));
                    i += 1;
                }
            }
            out.push(' ');
            i += 1;
        } else if c == '\'' {
            // A character literal ('x', '\n', '\u{..}') or a lifetime / label ('a).
            if next == Some('\\') {
                let mut j = i + 2;
                while j < b.len() && b[j] != '\'' {
                    j += 1;
                }
                for _ in i..=j.min(b.len() - 1) {
                    out.push(' ');
                }
                i = j + 1;
            } else if b.get(i + 2) == Some(&'\'') {
                out.push_str("   ");
                i += 3;
            } else {
                out.push(c);
                i += 1;
            }
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Ident(String),
    Punct(&'static str),
    Other(char),
}

/// Tokens of blanked source with their (1-based) line numbers.
fn tokens(src: &str) -> Vec<(Tok, usize)> {
    let b: Vec<char> = src.chars().collect();
    let mut out = Vec::new();
    let (mut i, mut line) = (0, 1);
    while i < b.len() {
        let c = b[i];
        if c == '\n' {
            line += 1;
            i += 1;
        } else if c.is_whitespace() {
            i += 1;
        } else if c.is_alphabetic() || c == '_' {
            let s = i;
            while i < b.len() && (b[i].is_alphanumeric() || b[i] == '_') {
                i += 1;
            }
            let word: String = b[s..i].iter().collect();
            // `r#ident`
            let word = word.strip_prefix("r#").map(str::to_owned).unwrap_or(word);
            out.push((Tok::Ident(word), line));
        } else if c.is_ascii_digit() {
            while i < b.len() && (b[i].is_alphanumeric() || b[i] == '_' || b[i] == '.') {
                // A range `0..n` must not swallow the dots.
                if b[i] == '.' && b.get(i + 1) == Some(&'.') {
                    break;
                }
                i += 1;
            }
            out.push((Tok::Other('0'), line));
        } else if c == ':' && b.get(i + 1) == Some(&':') {
            out.push((Tok::Punct("::"), line));
            i += 2;
        } else {
            out.push((
                match c {
                    '{' => Tok::Punct("{"),
                    '}' => Tok::Punct("}"),
                    ',' => Tok::Punct(","),
                    ';' => Tok::Punct(";"),
                    '*' => Tok::Punct("*"),
                    '(' => Tok::Punct("("),
                    ')' => Tok::Punct(")"),
                    '!' => Tok::Punct("!"),
                    '#' => Tok::Punct("#"),
                    '[' => Tok::Punct("["),
                    ']' => Tok::Punct("]"),
                    other => Tok::Other(other),
                },
                line,
            ));
            i += 1;
        }
    }
    out
}

fn ident(t: &Tok) -> Option<&str> {
    match t {
        Tok::Ident(s) => Some(s),
        _ => None,
    }
}

// ---------------------------------------------------------------------------------------------
// Modules: what each defines, imports and re-exports.

/// One `use` leaf: the path as written (relative to the module that holds it), the name it
/// binds (`None` for a glob), whether it is a re-export, and its line.
#[derive(Clone, Debug)]
struct UseLeaf {
    path: Vec<String>,
    binds: Option<String>,
    public: bool,
    line: usize,
}

/// A path named in code (outside `use`): segments from `crate`/`super`/`self` on.
#[derive(Clone, Debug)]
struct CodePath {
    path: Vec<String>,
    line: usize,
}

#[derive(Default, Debug)]
struct Module {
    /// The source file (relative to the crate root).
    file: String,
    /// Item names defined here (functions, types, traits, constants, macros).
    items: BTreeSet<String>,
    /// Child modules by name.
    children: BTreeSet<String>,
    uses: Vec<UseLeaf>,
    code_paths: Vec<CodePath>,
}

type ModPath = Vec<String>;

/// Parses a use tree at `toks[*i..]` with `prefix` already read; pushes its leaves.
fn parse_use_tree(
    toks: &[(Tok, usize)],
    i: &mut usize,
    prefix: Vec<String>,
    public: bool,
    leaves: &mut Vec<UseLeaf>,
) {
    let mut path = prefix;
    loop {
        match toks.get(*i).map(|t| &t.0) {
            Some(Tok::Punct("{")) => {
                *i += 1;
                loop {
                    match toks.get(*i).map(|t| &t.0) {
                        Some(Tok::Punct("}")) => {
                            *i += 1;
                            return;
                        }
                        Some(Tok::Punct(",")) => *i += 1,
                        None => return,
                        _ => parse_use_tree(toks, i, path.clone(), public, leaves),
                    }
                }
            }
            Some(Tok::Punct("*")) => {
                leaves.push(UseLeaf {
                    path: path.clone(),
                    binds: None,
                    public,
                    line: toks[*i].1,
                });
                *i += 1;
                return;
            }
            Some(Tok::Ident(name)) => {
                path.push(name.clone());
                let line = toks[*i].1;
                *i += 1;
                if toks.get(*i).map(|t| &t.0) == Some(&Tok::Punct("::")) {
                    *i += 1;
                    continue;
                }
                let mut binds = name.clone();
                if toks.get(*i).and_then(|t| ident(&t.0)) == Some("as") {
                    *i += 1;
                    if let Some(alias) = toks.get(*i).and_then(|t| ident(&t.0)) {
                        binds = alias.to_owned();
                        *i += 1;
                    }
                }
                if binds == "self" {
                    path.pop();
                    binds = path.last().cloned().unwrap_or_default();
                }
                leaves.push(UseLeaf {
                    path: path.clone(),
                    binds: Some(binds),
                    public,
                    line,
                });
                return;
            }
            _ => return,
        }
    }
}

/// The modules of one source file (the file's module and its inline modules), given the
/// file's module path. `lines` restricts parsing to a line range (for the macro body in
/// `lib.rs`); `skip` to the complement of one.
fn parse_file(
    file: &str,
    text: &str,
    base: &ModPath,
    modules: &mut BTreeMap<ModPath, Module>,
    keep_line: &dyn Fn(usize) -> bool,
) {
    let blanked = blank_comments_and_literals(text);
    let toks: Vec<(Tok, usize)> = tokens(&blanked)
        .into_iter()
        .filter(|(_, l)| keep_line(*l))
        .collect();
    // A stack of (module path, brace depth at which it closes).
    let mut stack: Vec<(ModPath, usize)> = vec![(base.clone(), usize::MAX)];
    let mut depth = 0usize;
    let entry = |modules: &mut BTreeMap<ModPath, Module>, p: &ModPath| {
        let m = modules.entry(p.clone()).or_default();
        if m.file.is_empty() {
            m.file = file.to_owned();
        }
    };
    entry(modules, base);
    let mut i = 0;
    let mut pending_mod: Option<String> = None;
    while i < toks.len() {
        let cur = stack.last().unwrap().0.clone();
        let (t, line) = (&toks[i].0, toks[i].1);
        match t {
            Tok::Punct("{") => {
                depth += 1;
                if let Some(name) = pending_mod.take() {
                    let mut p = cur.clone();
                    p.push(name);
                    entry(modules, &p);
                    stack.push((p, depth));
                }
                i += 1;
            }
            Tok::Punct("}") => {
                if stack.last().unwrap().1 == depth {
                    stack.pop();
                }
                depth = depth.saturating_sub(1);
                i += 1;
            }
            Tok::Punct(";") => {
                pending_mod = None;
                i += 1;
            }
            Tok::Ident(w) if w == "use" => {
                let public = i > 0
                    && (ident(&toks[i - 1].0) == Some("pub")
                        || (toks[i - 1].0 == Tok::Punct(")")
                            && toks[..i]
                                .iter()
                                .rev()
                                .take(6)
                                .any(|t| ident(&t.0) == Some("pub"))));
                i += 1;
                let mut leaves = Vec::new();
                parse_use_tree(&toks, &mut i, Vec::new(), public, &mut leaves);
                modules.get_mut(&cur).unwrap().uses.extend(leaves);
            }
            Tok::Ident(w) if w == "mod" => {
                if let Some(name) = toks.get(i + 1).and_then(|t| ident(&t.0)) {
                    modules
                        .get_mut(&cur)
                        .unwrap()
                        .children
                        .insert(name.to_owned());
                    if toks.get(i + 2).map(|t| &t.0) == Some(&Tok::Punct("{")) {
                        pending_mod = Some(name.to_owned());
                    }
                }
                i += 2;
            }
            Tok::Ident(w)
                if matches!(
                    w.as_str(),
                    "fn" | "struct" | "enum" | "trait" | "const" | "static" | "type" | "union"
                ) =>
            {
                if let Some(name) = toks.get(i + 1).and_then(|t| ident(&t.0)) {
                    let body = if stack.len() == 1 {
                        0
                    } else {
                        stack.last().unwrap().1
                    };
                    if depth == body {
                        modules.get_mut(&cur).unwrap().items.insert(name.to_owned());
                    }
                }
                i += 1;
            }
            Tok::Ident(w) if w == "macro_rules" => {
                if let Some(name) = toks.get(i + 2).and_then(|t| ident(&t.0)) {
                    modules.get_mut(&cur).unwrap().items.insert(name.to_owned());
                }
                i += 1;
            }
            Tok::Ident(w) if w == "in" && i > 0 && toks[i - 1].0 == Tok::Punct("(") => {
                // `pub(in path)`: a visibility, not a reference.
                while i < toks.len() && toks[i].0 != Tok::Punct(")") {
                    i += 1;
                }
            }
            Tok::Ident(w)
                if toks.get(i + 1).map(|t| &t.0) == Some(&Tok::Punct("::"))
                    && !(i > 0 && toks[i - 1].0 == Tok::Punct("::")) =>
            {
                // A path in code: from `crate`, `super`, `self`, or a name (a module or item
                // bound here, resolved later; an unbound name is an external crate).
                let mut path = vec![w.clone()];
                let mut j = i + 1;
                while toks.get(j).map(|t| &t.0) == Some(&Tok::Punct("::")) {
                    match toks.get(j + 1).and_then(|t| ident(&t.0)) {
                        Some(s) => {
                            path.push(s.to_owned());
                            j += 2;
                        }
                        None => break,
                    }
                }
                modules
                    .get_mut(&cur)
                    .unwrap()
                    .code_paths
                    .push(CodePath { path, line });
                i = j;
            }
            _ => i += 1,
        }
    }
}

/// The module path of a file under `src/` (`None` for files that are not modules of the
/// crate, e.g. a `#[path]` target loaded elsewhere is mapped by the caller).
fn module_path_of(rel: &Path, precision: &BTreeSet<String>) -> ModPath {
    let mut segs: Vec<String> = rel
        .iter()
        .map(|s| s.to_string_lossy().into_owned())
        .collect();
    let last = segs.pop().unwrap();
    let stem = last.trim_end_matches(".rs").to_owned();
    if stem != "mod" && stem != "lib" {
        segs.push(stem);
    }
    let mut p: ModPath = vec!["crate".into()];
    match segs.first().map(String::as_str) {
        Some("f32" | "f64") if segs.len() == 1 => p.push("P".into()),
        Some(first) if precision.contains(first) => {
            p.push("P".into());
            p.extend(segs);
        }
        _ => p.extend(segs),
    }
    p
}

struct Crate {
    modules: BTreeMap<ModPath, Module>,
}

/// A resolved reference: every module visited on the way and the defining module.
#[derive(Default, Debug)]
struct Resolution {
    via: Vec<ModPath>,
    defined_in: Vec<ModPath>,
}

impl Crate {
    fn load(root: &Path) -> Self {
        let src = root.join("src");
        let lib = fs::read_to_string(src.join("lib.rs")).expect("src/lib.rs");
        // The precision modules: `#[path = "X"] pub mod name;` inside `precision_modules!`.
        let macro_start = lib
            .lines()
            .position(|l| l.contains("macro_rules! precision_modules"))
            .expect("precision_modules! in src/lib.rs")
            + 1;
        let macro_end = {
            let mut depth = 0i32;
            let mut end = macro_start;
            for (n, l) in lib.lines().enumerate().skip(macro_start - 1) {
                depth += l.matches('{').count() as i32 - l.matches('}').count() as i32;
                if depth == 0 && n >= macro_start {
                    end = n + 1;
                    break;
                }
            }
            end
        };
        let mut precision = BTreeSet::new();
        for l in lib.lines().skip(macro_start).take(macro_end - macro_start) {
            let l = l.trim();
            if let Some(rest) = l.strip_prefix("#[path = \"") {
                let file = rest.split('"').next().unwrap();
                let top = file.split('/').next().unwrap().trim_end_matches(".rs");
                precision.insert(top.to_owned());
            }
        }
        assert!(
            precision.contains("filter") && precision.contains("ndf"),
            "precision modules not found in src/lib.rs: {precision:?}"
        );
        let mut modules = BTreeMap::new();
        let mut files = Vec::new();
        collect_rs(&src, &mut files);
        files.sort();
        for f in &files {
            let rel = f.strip_prefix(&src).unwrap();
            let name = format!("src/{}", rel.to_string_lossy());
            let text = fs::read_to_string(f).unwrap();
            if name == "src/lib.rs" {
                let crate_root: ModPath = vec!["crate".into()];
                let p: ModPath = vec!["crate".into(), "P".into()];
                parse_file(&name, &text, &crate_root, &mut modules, &|l| {
                    l < macro_start || l > macro_end
                });
                parse_file(&name, &text, &p, &mut modules, &|l| {
                    l > macro_start && l < macro_end
                });
                // `pub mod f32; pub mod f64;` are the precision module.
                let root = modules.get_mut(&crate_root).unwrap();
                root.children.remove("f32");
                root.children.remove("f64");
                root.children.insert("P".into());
            } else {
                let mp = module_path_of(rel, &precision);
                parse_file(&name, &text, &mp, &mut modules, &|_| true);
            }
        }
        // f32.rs and f64.rs share `P`; keep the file name of the macro for the module.
        if let Some(p) = modules.get_mut(&vec!["crate".to_owned(), "P".to_owned()]) {
            p.file = "src/lib.rs".into();
        }
        Crate { modules }
    }

    /// The absolute start of a path written in module `at`: `crate`, `super`, `self`, a child
    /// module or a name bound in `at`; `None` for an external crate.
    fn anchor(&self, at: &ModPath, path: &[String]) -> Option<(ModPath, Vec<String>)> {
        let mut base = at.clone();
        let mut rest = path;
        match path.first().map(String::as_str) {
            Some("crate") => {
                base = vec!["crate".into()];
                rest = &path[1..];
                if matches!(rest.first().map(String::as_str), Some("f32" | "f64")) {
                    base.push("P".into());
                    rest = &rest[1..];
                }
            }
            Some("super" | "self") => {
                while let Some(s) = rest.first().map(String::as_str) {
                    match s {
                        "super" => {
                            base.pop();
                            rest = &rest[1..];
                        }
                        "self" => rest = &rest[1..],
                        _ => break,
                    }
                }
            }
            Some(first) if EXTERNAL.contains(&first) => return None,
            Some(_) => {}
            None => return None,
        }
        Some((base, rest.to_vec()))
    }

    /// Resolves `rest` inside module `at` (depth-limited against cyclic `use`).
    fn resolve_in(&self, at: &ModPath, rest: &[String], out: &mut Resolution, depth: usize) {
        if depth > 24 {
            return;
        }
        let Some(m) = self.modules.get(at) else {
            return;
        };
        out.via.push(at.clone());
        let Some(name) = rest.first() else {
            out.defined_in.push(at.clone());
            return;
        };
        let tail = &rest[1..];
        let mut found = false;
        if m.children.contains(name) {
            let mut child = at.clone();
            child.push(name.clone());
            if self.modules.contains_key(&child) {
                found = true;
                self.resolve_in(&child, tail, out, depth + 1);
                if !tail.is_empty() {
                    return;
                }
            }
        }
        if m.items.contains(name) {
            out.defined_in.push(at.clone());
            return;
        }
        for u in &m.uses {
            if u.binds.as_deref() == Some(name.as_str()) {
                if let Some((base, mut p)) = self.anchor(at, &u.path) {
                    found = true;
                    p.extend_from_slice(tail);
                    self.resolve_in(&base, &p, out, depth + 1);
                }
            }
        }
        if !found {
            for u in m.uses.iter().filter(|u| u.binds.is_none()) {
                if let Some((base, p)) = self.anchor(at, &u.path) {
                    let mut target = base.clone();
                    target.extend(p);
                    if target == *at {
                        continue;
                    }
                    let mut sub = Resolution::default();
                    let mut path = vec![name.clone()];
                    path.extend_from_slice(tail);
                    self.resolve_in(&target, &path, &mut sub, depth + 1);
                    if !sub.defined_in.is_empty() {
                        out.via.extend(sub.via);
                        out.defined_in.extend(sub.defined_in);
                    }
                }
            }
        }
    }

    /// Resolves a path written in module `at`.
    fn resolve(&self, at: &ModPath, path: &[String]) -> Resolution {
        let mut out = Resolution::default();
        if let Some((base, rest)) = self.anchor(at, path) {
            // A bare first segment that is neither a child module nor bound here is external.
            if !matches!(
                path.first().map(String::as_str),
                Some("crate" | "super" | "self")
            ) {
                let m = &self.modules[at];
                let first = &path[0];
                let bound = m.children.contains(first)
                    || m.items.contains(first)
                    || m.uses.iter().any(|u| u.binds.as_deref() == Some(first));
                if !bound {
                    return out;
                }
            }
            self.resolve_in(&base, &rest, &mut out, 0);
        }
        out
    }

    /// The file of a module.
    fn file(&self, m: &ModPath) -> &str {
        &self.modules[m].file
    }
}

fn collect_rs(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            collect_rs(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// One reference from a file, resolved.
struct Reference {
    from_file: String,
    from_module: ModPath,
    line: usize,
    written: String,
    /// A `pub use` re-export (a facade: no edge of the file graph).
    reexport: bool,
    resolution: Resolution,
}

fn references(krate: &Crate) -> Vec<Reference> {
    let mut out = Vec::new();
    for (mp, m) in &krate.modules {
        for u in &m.uses {
            out.push(Reference {
                from_file: m.file.clone(),
                from_module: mp.clone(),
                line: u.line,
                written: u.path.join("::"),
                reexport: u.public,
                resolution: krate.resolve(mp, &u.path),
            });
        }
        for c in &m.code_paths {
            out.push(Reference {
                from_file: m.file.clone(),
                from_module: mp.clone(),
                line: c.line,
                written: c.path.join("::"),
                reexport: false,
                resolution: krate.resolve(mp, &c.path),
            });
        }
    }
    out
}

/// The later-stage imports: `file:line: path -> stage`.
fn later_stage_imports(krate: &Crate) -> Vec<String> {
    let mut bad = Vec::new();
    for r in references(krate) {
        let from = stage_of(&r.from_module);
        let reached: BTreeSet<Stage> = r
            .resolution
            .via
            .iter()
            .chain(&r.resolution.defined_in)
            .map(|m| stage_of(m))
            .collect();
        if let Some(worst) = reached.iter().rev().find(|s| !from.may_import(**s)) {
            bad.push(format!(
                "{}:{}: `{}` ({:?}) imports {:?} (defined in {})",
                r.from_file,
                r.line,
                r.written,
                from,
                worst,
                r.resolution
                    .defined_in
                    .iter()
                    .map(|m| krate.file(m))
                    .collect::<BTreeSet<_>>()
                    .into_iter()
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
    }
    bad.sort();
    bad.dedup();
    bad
}

/// The file graph: `from -> to -> lines of from`.
fn file_graph(krate: &Crate) -> BTreeMap<String, BTreeMap<String, BTreeSet<usize>>> {
    // Each file's own module (the shortest module path it holds; inline modules are longer).
    let mut file_module: BTreeMap<&str, &ModPath> = BTreeMap::new();
    for (mp, m) in &krate.modules {
        let e = file_module.entry(m.file.as_str()).or_insert(mp);
        if mp.len() < e.len() {
            *e = mp;
        }
    }
    let mut g: BTreeMap<String, BTreeMap<String, BTreeSet<usize>>> = BTreeMap::new();
    for r in references(krate) {
        if r.reexport {
            continue;
        }
        let own = file_module[r.from_file.as_str()];
        for d in &r.resolution.defined_in {
            let to = krate.file(d);
            // A module declares its submodules (`mod`): it depends on them by construction,
            // so its own uses of them are not edges (else every child's `super::` import
            // would close a cycle with its parent).
            let descendant = d.len() > own.len() && d.starts_with(own);
            if to == r.from_file || stage_of(d) == Stage::Root || descendant {
                continue;
            }
            g.entry(r.from_file.clone())
                .or_default()
                .entry(to.to_owned())
                .or_default()
                .insert(r.line);
        }
    }
    g
}

/// The strongly connected components of more than one file (Tarjan).
fn cycles(g: &BTreeMap<String, BTreeMap<String, BTreeSet<usize>>>) -> Vec<Vec<String>> {
    struct T<'a> {
        g: &'a BTreeMap<String, BTreeMap<String, BTreeSet<usize>>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on: BTreeSet<&'a str>,
        next: usize,
        out: Vec<Vec<String>>,
    }
    fn visit<'a>(t: &mut T<'a>, v: &'a str) {
        t.index.insert(v, t.next);
        t.low.insert(v, t.next);
        t.next += 1;
        t.stack.push(v);
        t.on.insert(v);
        if let Some(edges) = t.g.get(v) {
            for w in edges.keys() {
                let w = w.as_str();
                if !t.index.contains_key(w) {
                    visit(t, w);
                    let lw = t.low[w];
                    let lv = t.low.get_mut(v).unwrap();
                    *lv = (*lv).min(lw);
                } else if t.on.contains(w) {
                    let iw = t.index[w];
                    let lv = t.low.get_mut(v).unwrap();
                    *lv = (*lv).min(iw);
                }
            }
        }
        if t.low[v] == t.index[v] {
            let mut comp = Vec::new();
            loop {
                let w = t.stack.pop().unwrap();
                t.on.remove(w);
                comp.push(w.to_owned());
                if w == v {
                    break;
                }
            }
            if comp.len() > 1 {
                comp.sort();
                t.out.push(comp);
            }
        }
    }
    let mut t = T {
        g,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on: BTreeSet::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in g.keys() {
        if !t.index.contains_key(v.as_str()) {
            visit(&mut t, v);
        }
    }
    t.out
}

/// The tree to check: this crate, or the checkout named by `FILTERED_NDF_LAYERING_ROOT` (to
/// run the checker against another revision).
fn root() -> PathBuf {
    std::env::var_os("FILTERED_NDF_LAYERING_ROOT")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")))
}

fn krate() -> Crate {
    Crate::load(&root())
}

#[test]
fn no_module_imports_a_later_stage() {
    let bad = later_stage_imports(&krate());
    assert!(
        bad.is_empty(),
        "{} imports of a later stage (or of a module beside the pipeline):\n{}",
        bad.len(),
        bad.join("\n")
    );
}

#[test]
fn no_import_cycle_between_files() {
    let g = file_graph(&krate());
    let mut report = Vec::new();
    for comp in cycles(&g) {
        let known = KNOWN_CYCLES.iter().any(|(a, b, _)| {
            comp.len() == 2 && comp.contains(&(*a).to_owned()) && comp.contains(&(*b).to_owned())
        });
        if known {
            continue;
        }
        let mut lines = Vec::new();
        for a in &comp {
            for b in &comp {
                if let Some(ls) = g.get(a).and_then(|e| e.get(b)) {
                    let ls: Vec<String> = ls.iter().map(|l| l.to_string()).collect();
                    lines.push(format!("  {a}:{} -> {b}", ls.join(",")));
                }
            }
        }
        report.push(format!(
            "cycle between {}:\n{}",
            comp.join(", "),
            lines.join("\n")
        ));
    }
    assert!(report.is_empty(), "{}", report.join("\n"));
}

/// The stage of a WGSL import path `filtered_ndf::a::...`.
fn wgsl_stage(path: &str) -> Stage {
    let mut segs = path.split("::");
    assert_eq!(segs.next(), Some("filtered_ndf"), "import path {path}");
    match segs.next() {
        None => Stage::Root,
        Some("math") => Stage::Foundation,
        // `bake` is crate level in Rust (both precisions): beside the pipeline.
        Some("bake") => Stage::Beside,
        Some(s) => stage_of(&["crate", "P", s].map(String::from)),
    }
}

fn collect_wgsl(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            if p.file_name().is_some_and(|n| n != "generated") {
                collect_wgsl(&p, out);
            }
        } else if p.extension().is_some_and(|x| x == "wgsl") {
            out.push(p);
        }
    }
}

/// `file:line: import -> stage` for each WGSL import of a later stage.
fn wgsl_later_stage_imports(shaders: &Path) -> Vec<String> {
    let mut files = Vec::new();
    collect_wgsl(shaders, &mut files);
    files.sort();
    assert!(files.len() > 10, "WGSL modules under {}", shaders.display());
    let mut bad = Vec::new();
    for f in files {
        let text = fs::read_to_string(&f).unwrap();
        let rel = f
            .strip_prefix(shaders)
            .unwrap()
            .to_string_lossy()
            .into_owned();
        let own = text
            .lines()
            .find_map(|l| l.trim().strip_prefix("#define_import_path"))
            .map(|p| wgsl_stage(p.trim()))
            .unwrap_or_else(|| panic!("shaders/{rel}: no #define_import_path"));
        for (n, line) in text.lines().enumerate() {
            let Some(rest) = line.trim().strip_prefix("#import") else {
                continue;
            };
            let path = rest.split(" as ").next().unwrap().trim();
            let target = wgsl_stage(path);
            if !own.may_import(target) {
                bad.push(format!(
                    "shaders/{rel}:{}: `{path}` ({own:?}) imports {target:?}",
                    n + 1
                ));
            }
        }
    }
    bad
}

#[test]
fn no_wgsl_module_imports_a_later_stage() {
    let shaders = root().join("shaders");
    let bad = wgsl_later_stage_imports(&shaders);
    assert!(
        bad.is_empty(),
        "{} WGSL imports of a later stage:\n{}",
        bad.len(),
        bad.join("\n")
    );
}

/// The checker itself: it sees the imports it must see (a test that cannot fail is no test).
#[test]
fn the_checker_resolves_known_imports() {
    let k = krate();
    let g = file_graph(&k);
    // `ndf/ggx.rs` uses the `Ndf` trait of `ndf/mod.rs` and the roughness forms.
    let ggx = &g["src/ndf/ggx.rs"];
    assert!(ggx.contains_key("src/ndf/mod.rs"), "{ggx:?}");
    assert!(
        ggx.contains_key("src/ndf/roughness/isotropic.rs"),
        "{ggx:?}"
    );
    // Through a re-export of the precision root: `F` resolves to the root (no edge), and
    // `super::super::ndf::roughness::ALPHA_MAX` from the kernel to the roughness module.
    let cov = &g["src/kernel/covariance.rs"];
    assert!(cov.contains_key("src/ndf/roughness/mod.rs"), "{cov:?}");
    // A made-up later-stage import is caught: the footprint stage naming the filter stage.
    let fp: ModPath = ["crate", "P", "footprint"].map(String::from).to_vec();
    let r = k.resolve(&fp, &["super", "filter", "presets"].map(String::from));
    let reached: Vec<Stage> = r.via.iter().map(|m| stage_of(m)).collect();
    assert!(reached.contains(&Stage::Filter), "{r:?}");
    assert!(!Stage::Footprint.may_import(Stage::Filter));
    assert!(Stage::Filter.may_import(Stage::Footprint));
    assert!(!Stage::Kernel.may_import(Stage::Beside));
    assert!(Stage::Beside.may_import(Stage::Sampling));
    assert!(Stage::Bsdf.may_import(Stage::Sampling) && Stage::Bsdf.may_import(Stage::Filter));
    assert!(!Stage::Sampling.may_import(Stage::Bsdf) && !Stage::Filter.may_import(Stage::Bsdf));
    assert!(!Stage::Bsdf.may_import(Stage::Beside) && Stage::Beside.may_import(Stage::Bsdf));
    assert_eq!(
        stage_of(&["crate", "bake"].map(String::from)),
        Stage::Beside
    );
    // A cycle is found.
    let mut toy: BTreeMap<String, BTreeMap<String, BTreeSet<usize>>> = BTreeMap::new();
    toy.entry("a".into())
        .or_default()
        .insert("b".into(), [1].into());
    toy.entry("b".into())
        .or_default()
        .insert("c".into(), [2].into());
    toy.entry("c".into())
        .or_default()
        .insert("a".into(), [3].into());
    assert_eq!(cycles(&toy), vec![vec!["a", "b", "c"]]);
}
