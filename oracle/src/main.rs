//! Reference oracle for shader authors: reads JSON lines on stdin, writes one JSON line per
//! input line on stdout, in order: `{"ok": VALUE}` or `{"error": "MESSAGE"}`. A bad line gives
//! an error line and the evaluator goes on.
//!
//! ```sh
//! echo '{"op":"ndf","dist":"ggx","roughness":0.1,"m":[0,0,1]}' | cargo run --release -p filtered-ndf-oracle
//! cargo run --release -p filtered-ndf-oracle -- --list
//! ```
//!
//! `--backend cpu` (the default) evaluates with the library. `--backend gpu` (every op that has
//! a shader, through the WGSL modules of `shaders/` in f32) is the binary `oracle` of the
//! workspace member `filtered-ndf-gpu`, which depends on wgpu:
//! `cargo run --release -p filtered-ndf-gpu --bin oracle-gpu -- --backend gpu`.

use filtered_ndf_oracle::eval;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.iter().any(|a| a == "--list") {
        print!("{}", eval::list());
        return;
    }
    if let Some(i) = args.iter().position(|a| a == "--backend") {
        match args.get(i + 1).map(String::as_str) {
            Some("cpu") => {}
            Some("gpu") => {
                eprintln!(
                    "oracle: --backend gpu lives in the workspace member filtered-ndf-gpu (it \
                     depends on wgpu): cargo run --release -p filtered-ndf-gpu --bin oracle-gpu -- \
                     --backend gpu"
                );
                std::process::exit(2);
            }
            other => {
                eprintln!("oracle: --backend must be `cpu` or `gpu`, got {other:?}");
                std::process::exit(2);
            }
        }
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
