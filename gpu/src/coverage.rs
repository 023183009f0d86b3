//! Which exported WGSL functions the conformance checks call.
//!
//! **Exported.** naga_oil exports every top-level item of a module (it has no private items),
//! and the project has no private-name convention: every top-level `fn` of every module of
//! `shaders/` is public API ([`exported`]).
//!
//! **Covered.** A function is covered when the WGSL snippet of some check of
//! [`crate::checks::GROUPS`] calls it as `alias::name(...)`, the alias resolved through the
//! check's own `#import` lines ([`called`]). A check declares what it covers by calling it:
//! nothing is registered by hand, so a check cannot claim a function it does not run, and a
//! function that moves to another module is found under its new import path.
//!
//! **Through callers.** A function that no snippet calls may be listed in the registry
//! `gpu/src/checks/through_callers.txt` ([`REGISTRY`]) with a checked function that reaches it
//! and a one-line reason. Each entry is verified: the function exists, no snippet calls it
//! directly (else the entry is redundant), the named caller is itself called by a snippet, and
//! the caller reaches the function through the modules' call graph ([`call_graph`]).

use crate::checks::Check;
use crate::modules::{Module, parse_imports};
use crate::syntax::{calls_by_fn, qualified_refs, top_level_fns};
use std::collections::{BTreeMap, BTreeSet};

/// The registry of functions covered through their callers (format in its header).
pub const REGISTRY: &str = include_str!("checks/through_callers.txt");

/// A function listed as covered through a checked caller.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ThroughCaller {
    /// The function: import path and name (`filtered_ndf::filter::method::d_rect_filtered`).
    pub function: String,
    /// A function called by a check that reaches it.
    pub caller: String,
    /// Why checking the caller checks the function (one line).
    pub reason: String,
}

/// The entries of a registry text: `path::{f, g} <- caller: reason` or `path::f <- caller:
/// reason` per line, `#` comments and blank lines skipped. An error names the bad line.
pub fn parse_registry(text: &str) -> Result<Vec<ThroughCaller>, String> {
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let bad = |why: &str| format!("through_callers.txt line {}: {why}: `{line}`", n + 1);
        let (functions, rest) = line.split_once(" <- ").ok_or_else(|| bad("no ` <- `"))?;
        let (caller, reason) = rest.split_once(": ").ok_or_else(|| bad("no `: reason`"))?;
        let (path, names) = match functions.split_once("::{") {
            Some((p, names)) => {
                let names = names.strip_suffix('}').ok_or_else(|| bad("unclosed `{`"))?;
                (p, names.split(',').map(str::trim).collect::<Vec<_>>())
            }
            None => functions
                .rsplit_once("::")
                .map(|(p, f)| (p, vec![f]))
                .ok_or_else(|| bad("not a path"))?,
        };
        if reason.trim().is_empty() || names.iter().any(|f| f.is_empty()) {
            return Err(bad("empty name or reason"));
        }
        for name in names {
            out.push(ThroughCaller {
                function: full(path, name),
                caller: caller.trim().to_string(),
                reason: reason.trim().to_string(),
            });
        }
    }
    Ok(out)
}

/// `import path::name` of a function.
fn full(path: &str, name: &str) -> String {
    format!("{path}::{name}")
}

/// Every exported function: each top-level `fn` of each module, as `import path::name`.
pub fn exported(modules: &[Module]) -> BTreeSet<String> {
    modules
        .iter()
        .flat_map(|m| {
            top_level_fns(&m.source)
                .into_iter()
                .map(|f| full(&m.path, &f))
        })
        .collect()
}

/// The exported functions a check's snippet calls (`alias::name(...)` with `alias` one of its
/// imports and `name` a function of that module).
pub fn called(check: &Check, exported: &BTreeSet<String>) -> Result<BTreeSet<String>, String> {
    let imports = parse_imports(&check.imports).map_err(|e| format!("{}: {e}", check.name))?;
    let alias: BTreeMap<&str, &str> = imports
        .iter()
        .map(|i| (i.alias.as_str(), i.path.as_str()))
        .collect();
    let mut out = BTreeSet::new();
    // The snippet is the body of `eval()`: its calls are those of one function.
    let wrapped = format!("fn eval() {{\n{}\n}}", check.body);
    let calls = calls_by_fn(&wrapped).into_iter().flat_map(|(_, c)| c);
    for (a, name) in calls {
        let Some(a) = a else { continue };
        if let Some(path) = alias.get(a.as_str()) {
            let f = full(path, &name);
            if exported.contains(&f) {
                out.insert(f);
            }
        }
    }
    // Every qualified name must resolve to an import (else the snippet would not compose).
    if let Some((a, item)) = qualified_refs(&check.body)
        .into_iter()
        .find(|(a, _)| !alias.contains_key(a.as_str()))
    {
        return Err(format!(
            "{}: `{a}::{item}` names no import of the check",
            check.name
        ));
    }
    Ok(out)
}

/// The functions each function's body calls (`import path::name` to the same), resolved
/// within its module (bare names) and through its imports (`alias::name`).
pub fn call_graph(
    modules: &[Module],
    exported: &BTreeSet<String>,
) -> BTreeMap<String, BTreeSet<String>> {
    let mut graph = BTreeMap::new();
    for m in modules {
        let alias: BTreeMap<&str, &str> = m
            .imports
            .iter()
            .map(|i| (i.alias.as_str(), i.path.as_str()))
            .collect();
        for (f, calls) in calls_by_fn(&m.source) {
            let callees = calls
                .into_iter()
                .filter_map(|(a, name)| match a {
                    None => Some(full(&m.path, &name)),
                    Some(a) => alias.get(a.as_str()).map(|p| full(p, &name)),
                })
                .filter(|c| exported.contains(c))
                .collect();
            graph.insert(full(&m.path, &f), callees);
        }
    }
    graph
}

/// What the coverage check found.
#[derive(Debug, Default)]
pub struct Coverage {
    /// Exported functions, in all.
    pub exported: usize,
    /// Functions a snippet calls.
    pub called: BTreeSet<String>,
    /// Exported functions that no check calls and the registry does not list.
    pub uncovered: Vec<String>,
    /// Registry entries that fail their verification, with why.
    pub bad_entries: Vec<String>,
}

impl Coverage {
    /// Whether every exported function is covered and every list entry holds.
    pub fn is_complete(&self) -> bool {
        self.uncovered.is_empty() && self.bad_entries.is_empty()
    }
}

/// Whether `from` reaches `to` through `graph` (one call or more).
fn reaches(graph: &BTreeMap<String, BTreeSet<String>>, from: &str, to: &str) -> bool {
    let mut seen = BTreeSet::new();
    let mut stack = vec![from.to_string()];
    while let Some(f) = stack.pop() {
        for c in graph.get(&f).into_iter().flatten() {
            if c == to {
                return true;
            }
            if seen.insert(c.clone()) {
                stack.push(c.clone());
            }
        }
    }
    false
}

/// Checks the coverage of `modules` by `checks` against the registry entries `through`
/// (normally `parse_registry(REGISTRY)`).
pub fn coverage(
    modules: &[Module],
    checks: &[Check],
    through: &[ThroughCaller],
) -> Result<Coverage, String> {
    let exported = exported(modules);
    let mut called_set = BTreeSet::new();
    for c in checks {
        called_set.extend(called(c, &exported)?);
    }
    let graph = call_graph(modules, &exported);
    let mut bad = Vec::new();
    let mut listed = BTreeSet::new();
    for t in through {
        let (f, caller) = (t.function.as_str(), t.caller.as_str());
        if !listed.insert(f) {
            bad.push(format!("{f}: listed twice"));
        } else if !exported.contains(f) {
            bad.push(format!("{f}: no such function"));
        } else if called_set.contains(f) {
            bad.push(format!("{f}: a check calls it directly; remove the entry"));
        } else if !called_set.contains(caller) {
            bad.push(format!(
                "{f}: its caller {caller} is not called by any check"
            ));
        } else if !reaches(&graph, caller, f) {
            bad.push(format!("{f}: {caller} does not reach it"));
        }
    }
    let uncovered = exported
        .iter()
        .filter(|f| !called_set.contains(*f) && !listed.contains(f.as_str()))
        .cloned()
        .collect();
    Ok(Coverage {
        exported: exported.len(),
        called: called_set,
        uncovered,
        bad_entries: bad,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn module(path: &str, source: &str) -> Module {
        Module {
            path: path.to_string(),
            file: String::new(),
            source: source.to_string(),
            imports: parse_imports(source).expect("imports"),
        }
    }

    fn modules() -> Vec<Module> {
        vec![
            module(
                "filtered_ndf::a",
                "#define_import_path filtered_ndf::a\nconst K: f32 = 2.0;\nfn helper(x: f32) -> f32 {\n    return x * K;\n}\nfn f(x: f32) -> f32 {\n    return helper(x) + 1.0;\n}\nfn g(x: f32) -> f32 {\n    return x;\n}\n",
            ),
            module(
                "filtered_ndf::b",
                "#define_import_path filtered_ndf::b\n#import filtered_ndf::a as other\nfn h(x: f32) -> f32 {\n    return other::g(x);\n}\n",
            ),
        ]
    }

    fn check(imports: &str, body: &str) -> Check {
        Check::new("test", imports, body, 1, 1)
    }

    #[test]
    fn names_each_function_no_check_calls() {
        let checks = [check(
            "#import filtered_ndf::a as z",
            "y(0u, z::f(x(0u)) * z::K);",
        )];
        let c = coverage(&modules(), &checks, &[]).expect("coverage");
        assert_eq!(c.exported, 4);
        assert_eq!(
            c.called.iter().collect::<Vec<_>>(),
            ["filtered_ndf::a::f"],
            "a constant is not a function"
        );
        assert_eq!(
            c.uncovered,
            [
                "filtered_ndf::a::g",
                "filtered_ndf::a::helper",
                "filtered_ndf::b::h"
            ]
        );
        assert!(!c.is_complete());
    }

    #[test]
    fn registry_entries_are_verified() {
        let checks = [
            check("#import filtered_ndf::a", "y(0u, a::f(x(0u)) + a::g(1.0));"),
            check("#import filtered_ndf::b", "y(0u, b::h(x(0u)));"),
        ];
        let entry = |line: &str| parse_registry(line).expect("parses");
        let good = entry("filtered_ndf::a::helper <- filtered_ndf::a::f: a reason");
        let c = coverage(&modules(), &checks, &good).expect("coverage");
        assert!(c.is_complete(), "{c:?}");
        for (bad, why) in [
            (
                "filtered_ndf::a::nothing <- filtered_ndf::a::f: r",
                "no such function",
            ),
            (
                "filtered_ndf::a::g <- filtered_ndf::b::h: r",
                "calls it directly",
            ),
            (
                "filtered_ndf::a::helper <- filtered_ndf::a::g: r",
                "does not reach it",
            ),
            (
                "filtered_ndf::a::{helper, helper} <- filtered_ndf::a::f: r",
                "listed twice",
            ),
        ] {
            let c = coverage(&modules(), &checks, &entry(bad)).expect("coverage");
            assert!(
                c.bad_entries.len() == 1 && c.bad_entries[0].contains(why),
                "{bad}: {c:?}"
            );
        }
        // A caller that is not itself checked covers nothing.
        let only_h = [check("#import filtered_ndf::b", "y(0u, b::h(x(0u)));")];
        let c = coverage(&modules(), &only_h, &good).expect("coverage");
        assert!(
            c.bad_entries[0].contains("not called by any check"),
            "{c:?}"
        );
        // Reached through two calls: b::h -> a::g in a checked snippet; a::f -> a::helper.
        let deep = [check("#import filtered_ndf::a", "y(0u, a::f(x(0u)));")];
        let c = coverage(&modules(), &deep, &good).expect("coverage");
        assert_eq!(c.uncovered, ["filtered_ndf::a::g", "filtered_ndf::b::h"]);
    }

    #[test]
    fn registry_lines_parse_or_name_the_line() {
        let e = parse_registry(
            "# comment\n\nfiltered_ndf::a::{x, y} <- filtered_ndf::a::f: two\nfiltered_ndf::b::z <- filtered_ndf::b::h: one\n",
        )
        .expect("parses");
        let f: Vec<&str> = e.iter().map(|t| t.function.as_str()).collect();
        assert_eq!(
            f,
            [
                "filtered_ndf::a::x",
                "filtered_ndf::a::y",
                "filtered_ndf::b::z"
            ]
        );
        assert_eq!(e[2].caller, "filtered_ndf::b::h");
        assert_eq!(e[2].reason, "one");
        for bad in [
            "filtered_ndf::a::x filtered_ndf::a::f: r",
            "filtered_ndf::a::x <- filtered_ndf::a::f",
            "filtered_ndf::a::{x <- filtered_ndf::a::f: r",
            "filtered_ndf::a::x <- filtered_ndf::a::f: ",
        ] {
            let err = parse_registry(bad).expect_err(bad);
            assert!(err.contains("line 1"), "{err}");
        }
    }

    #[test]
    fn the_registry_parses() {
        assert!(!parse_registry(REGISTRY).expect("parses").is_empty());
    }

    #[test]
    fn a_qualified_name_without_its_import_is_an_error() {
        let checks = [check("#import filtered_ndf::a", "y(0u, q::f(1.0));")];
        assert!(coverage(&modules(), &checks, &[]).is_err());
    }
}
