//! The reference oracle for shader authors: JSON lines in, one JSON line out per input line
//! (`{"ok": VALUE}` or `{"error": "MESSAGE"}`), every value computed by `filtered-ndf` in the
//! precision the line asks for. [`eval::eval_line`] answers one line, [`eval::serve`] a
//! stream, [`eval::list`] documents every op with its equation; [`args`] parses and checks
//! the arguments (shared with the GPU backend of `filtered-ndf-gpu`).

pub mod args;
pub mod eval;
