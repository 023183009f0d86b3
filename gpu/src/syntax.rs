//! A lexical scan of WGSL: enough of the language to find a module's top-level items and the
//! qualified names (`alias::item`) a source refers to, and to rename identifiers safely
//! ([`crate::concat`]). Comments, `#` directives, numbers and whitespace are kept verbatim.

use std::collections::BTreeSet;

/// The top-level item names a module declares (`fn`, `struct`, `const`, `alias`,
/// `override`, `var` at brace depth 0).
pub fn top_level_names(source: &str) -> BTreeSet<String> {
    top_level_items(source)
        .into_iter()
        .map(|(_, name)| name)
        .collect()
}

/// The top-level functions a module declares (`fn` at brace depth 0), in source order.
pub fn top_level_fns(source: &str) -> Vec<String> {
    top_level_items(source)
        .into_iter()
        .filter(|(kind, _)| kind == "fn")
        .map(|(_, name)| name)
        .collect()
}

/// `(keyword, name)` of every top-level item (`fn`, `struct`, `const`, `alias`, `override`,
/// `var` at brace depth 0), in source order.
fn top_level_items(source: &str) -> Vec<(String, String)> {
    let mut names = Vec::new();
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
                let mut template = 0i32;
                while j < toks.len() && (template > 0 || !matches!(toks[j], Tok::Ident(_))) {
                    match toks[j] {
                        Tok::Punct('<') => template += 1,
                        Tok::Punct('>') => template -= 1,
                        _ => {}
                    }
                    j += 1;
                }
                if let Some(Tok::Ident(n)) = toks.get(j) {
                    names.push((k.clone(), n.clone()));
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
pub enum Tok {
    /// An identifier or keyword.
    Ident(String),
    /// One punctuation character.
    Punct(char),
    /// Anything else kept verbatim: whitespace, comments, numbers, `#` lines.
    Other(String),
}

/// The tokens of a WGSL source, in order; concatenated, they give the source back.
pub fn tokens(src: &str) -> Vec<Tok> {
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

/// Every qualified reference `alias::item` of a source, in order (`(alias, item)`): the
/// items of imported modules it names (functions, constants, types).
pub fn qualified_refs(source: &str) -> Vec<(String, String)> {
    let toks = tokens(source);
    let mut out = Vec::new();
    for w in toks.windows(4) {
        if let [
            Tok::Ident(alias),
            Tok::Punct(':'),
            Tok::Punct(':'),
            Tok::Ident(item),
        ] = w
        {
            out.push((alias.clone(), item.clone()));
        }
    }
    out
}

/// A call in a function body: `(Some(alias), item)` for `alias::item(...)`, `(None, name)` for
/// `name(...)` (which includes value constructors such as `f32(x)` and struct constructors:
/// the caller resolves names against the functions it knows).
pub type Call = (Option<String>, String);

/// The calls in the body of every top-level function of a source: `(function, calls)` in
/// source order.
pub fn calls_by_fn(source: &str) -> Vec<(String, Vec<Call>)> {
    // The tokens that matter (identifiers and punctuation), with positions kept in order.
    let toks: Vec<Tok> = tokens(source)
        .into_iter()
        .filter(|t| !matches!(t, Tok::Other(_)))
        .collect();
    let mut out = Vec::new();
    let mut depth = 0i32;
    let mut i = 0;
    while i < toks.len() {
        match &toks[i] {
            Tok::Punct('{') => depth += 1,
            Tok::Punct('}') => depth -= 1,
            Tok::Ident(k) if depth == 0 && k == "fn" => {
                let Some(Tok::Ident(name)) = toks.get(i + 1) else {
                    i += 1;
                    continue;
                };
                // The body: from the first `{` after the signature to its matching `}`.
                let mut j = i + 2;
                while j < toks.len() && toks[j] != Tok::Punct('{') {
                    j += 1;
                }
                let start = j;
                let mut d = 0i32;
                while j < toks.len() {
                    match toks[j] {
                        Tok::Punct('{') => d += 1,
                        Tok::Punct('}') => {
                            d -= 1;
                            if d == 0 {
                                break;
                            }
                        }
                        _ => {}
                    }
                    j += 1;
                }
                let body = &toks[start.min(toks.len())..j.min(toks.len())];
                out.push((name.clone(), calls(body)));
                i = j + 1;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    out
}

/// The calls among tokens without whitespace or comments.
fn calls(toks: &[Tok]) -> Vec<Call> {
    let mut out = Vec::new();
    for (k, t) in toks.iter().enumerate() {
        let Tok::Ident(name) = t else { continue };
        if toks.get(k + 1) != Some(&Tok::Punct('(')) {
            continue;
        }
        let qualified = k >= 3 && toks[k - 1] == Tok::Punct(':') && toks[k - 2] == Tok::Punct(':');
        match (qualified, toks.get(k.wrapping_sub(3))) {
            (true, Some(Tok::Ident(alias))) => out.push((Some(alias.clone()), name.clone())),
            (false, _) if k == 0 || toks[k - 1] != Tok::Punct('.') => {
                out.push((None, name.clone()));
            }
            _ => {}
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const SRC: &str = "#import filtered_ndf::math\n// fn not_an_item() {}\nstruct A {\n    x: f32,\n}\nconst K: f32 = 1.0;\nvar<private> v: f32;\nfn f(a: A) -> f32 {\n    let f = a.x;\n    return f * K + math::PI + math::atan(1e-8);\n}\nfn g() -> f32 {\n    return f(A(1.0));\n}\n";

    #[test]
    fn tokens_give_the_source_back() {
        let s: String = tokens(SRC)
            .into_iter()
            .map(|t| match t {
                Tok::Ident(s) | Tok::Other(s) => s,
                Tok::Punct(c) => c.to_string(),
            })
            .collect();
        assert_eq!(s, SRC);
    }

    #[test]
    fn items_at_depth_zero_outside_comments() {
        assert_eq!(
            top_level_names(SRC).into_iter().collect::<Vec<_>>(),
            ["A", "K", "f", "g", "v"]
        );
        assert_eq!(top_level_fns(SRC), ["f", "g"]);
    }

    #[test]
    fn calls_per_function_body() {
        let c = calls_by_fn(SRC);
        assert_eq!(c.len(), 2);
        assert_eq!(c[0].0, "f");
        assert_eq!(
            c[0].1,
            [(Some("math".to_string()), "atan".to_string())],
            "`math::PI` is not a call"
        );
        assert_eq!(c[1].0, "g");
        assert_eq!(c[1].1, [(None, "f".to_string()), (None, "A".to_string())]);
    }

    #[test]
    fn qualified_references_in_order() {
        assert_eq!(
            qualified_refs(SRC),
            [
                ("math".to_string(), "PI".to_string()),
                ("math".to_string(), "atan".to_string())
            ]
        );
    }
}
