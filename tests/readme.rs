//! The README is a manual whose figures come from one generated source: its which-kernel table
//! is the file `src/doc/which_kernel.md` (written by the trade table's run, included by the
//! crate docs) copied between two markers, and the README stays within 300 lines.

const README: &str = include_str!("../README.md");
const WHICH_KERNEL: &str = include_str!("../src/doc/which_kernel.md");

/// The text between `<!-- NAME...-->` and `<!-- /NAME -->`, without the marker lines.
fn generated_block<'a>(text: &'a str, name: &str) -> &'a str {
    let open = format!("<!-- {name}");
    let close = format!("<!-- /{name} -->");
    let start = text
        .find(&open)
        .unwrap_or_else(|| panic!("README lacks the marker {open}"));
    let body = start + text[start..].find('\n').expect("a line after the marker") + 1;
    let end = text[body..]
        .find(&close)
        .unwrap_or_else(|| panic!("README lacks the marker {close}"));
    &text[body..body + end]
}

#[test]
fn which_kernel_table_is_the_generated_file() {
    assert_eq!(
        generated_block(README, "which_kernel"),
        WHICH_KERNEL,
        "README's which-kernel table differs from src/doc/which_kernel.md: rerun the trade \
         table (cargo run --release -p filtered-ndf-demo --bin tradeoff -- --out docs)"
    );
}

#[test]
fn readme_is_a_manual_of_at_most_300_lines() {
    let lines = README.lines().count();
    assert!(
        lines <= 300,
        "README.md has {lines} lines; measurements belong in docs/"
    );
}

#[test]
fn marker_search_fails_on_a_missing_or_edited_block() {
    let text = "a\n<!-- t: x -->\n| 1 |\n<!-- /t -->\n";
    assert_eq!(generated_block(text, "t"), "| 1 |\n");
    assert!(std::panic::catch_unwind(|| generated_block("no markers", "t")).is_err());
}
