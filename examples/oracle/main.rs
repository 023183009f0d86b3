//! Reference oracle for shader authors: reads JSON lines on stdin, writes one JSON line per
//! input line on stdout, in order: `{"ok": VALUE}` or `{"error": "MESSAGE"}`. A bad line gives
//! an error line and the evaluator goes on.
//!
//! ```sh
//! echo '{"op":"ndf","dist":"ggx","roughness":0.1,"m":[0,0,1]}' | cargo run --release --example oracle
//! cargo run --release --example oracle -- --list
//! ```

mod eval;

use std::io::{BufRead, BufWriter, Write};

fn main() {
    if std::env::args().any(|a| a == "--list") {
        println!("Every op takes optional \"precision\": \"f32\" | \"f64\" (default f64).");
        println!("Roughness: number (isotropic alpha), [ax, ay], or [[a11, a12], [a12, a22]].");
        println!("Infinite results are written as the strings \"inf\" / \"-inf\".\n");
        for op in eval::OPS {
            println!(
                "{}\n  args:    {}\n  returns: {}\n",
                op.name, op.args, op.returns
            );
        }
        return;
    }
    let stdin = std::io::stdin();
    let mut stdout = BufWriter::new(std::io::stdout().lock());
    for line in stdin.lock().lines() {
        let reply = match line {
            Ok(l) if l.trim().is_empty() => continue,
            Ok(l) => eval::eval_line(&l),
            Err(e) => format!("{{\"error\":\"unreadable line: {e}\"}}"),
        };
        if writeln!(stdout, "{reply}").is_err() {
            return;
        }
    }
    let _ = stdout.flush();
}
