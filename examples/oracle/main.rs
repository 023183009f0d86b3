//! Reference oracle for shader authors: reads JSON lines on stdin, writes one JSON line per
//! input line on stdout, in order: `{"ok": VALUE}` or `{"error": "MESSAGE"}`. A bad line gives
//! an error line and the evaluator goes on.
//!
//! ```sh
//! echo '{"op":"ndf","dist":"ggx","roughness":0.1,"m":[0,0,1]}' | cargo run --release --example oracle
//! cargo run --release --example oracle -- --list
//! ```

mod eval;

fn main() {
    if std::env::args().any(|a| a == "--list") {
        print!("{}", eval::list());
        return;
    }
    let stdin = std::io::stdin();
    match eval::serve(stdin.lock(), std::io::stdout().lock()) {
        Ok(()) => {}
        // The reader went away: nothing left to answer.
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {}
        Err(e) => {
            eprintln!("oracle: {e}");
            std::process::exit(1);
        }
    }
}
