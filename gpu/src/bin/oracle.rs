//! The reference oracle with its GPU backend: the evaluator of `filtered-ndf-oracle` plus
//! `--backend gpu`, which answers every op that has a shader through the WGSL modules in f32
//! ([`filtered_ndf_gpu::oracle_backend`]; ops without one answer an error naming the op).
//! The GPU backend lives here, in the workspace member that depends on wgpu, so that the
//! library's `cargo test` does not build wgpu nor need a GPU driver.
//!
//! ```text
//! cargo run --release -p filtered-ndf-gpu --bin oracle-gpu -- --backend gpu < queries.jsonl
//! FILTERED_NDF_GPU_BACKEND=gl cargo run --release -p filtered-ndf-gpu --bin oracle-gpu -- --backend gpu
//! cargo run --release -p filtered-ndf-gpu --bin oracle-gpu -- --backend cpu    # as the example
//! ```
//!
//! With `--backend gpu` the whole input is read first and answered in order, batched into one
//! dispatch per op's kernel; the adapter is chosen by `FILTERED_NDF_GPU_BACKEND` (`vulkan`,
//! `gl`, `any`), and a missing adapter answers each line with an error naming the package to
//! install.

use filtered_ndf_gpu::oracle_backend as gpu_backend;
use filtered_ndf_oracle::eval;

use std::io::{Read, Write};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut backend = "cpu".to_string();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--list" => {
                print!("{}", eval::list());
                println!(
                    "--backend gpu answers through the WGSL modules in f32: {}",
                    gpu_backend::GPU_OPS
                );
                return;
            }
            "--backend" => backend = it.next().cloned().unwrap_or_default(),
            other => {
                eprintln!("oracle: unknown argument `{other}` (--list, --backend cpu|gpu)");
                std::process::exit(2);
            }
        }
    }
    match backend.as_str() {
        "cpu" => {
            let stdin = std::io::stdin();
            if let Err(e) = eval::serve(stdin.lock(), std::io::stdout().lock()) {
                if e.kind() != std::io::ErrorKind::BrokenPipe {
                    eprintln!("oracle: {e}");
                    std::process::exit(1);
                }
            }
        }
        "gpu" => {
            let mut input = String::new();
            if let Err(e) = std::io::stdin().read_to_string(&mut input) {
                eprintln!("oracle: reading stdin: {e}");
                std::process::exit(1);
            }
            let lines: Vec<&str> = input.lines().filter(|l| !l.trim().is_empty()).collect();
            let answers = gpu_backend::answer_session(&lines, &eval::eval_line);
            let mut out = std::io::stdout().lock();
            for a in answers {
                if writeln!(out, "{a}").is_err() {
                    return;
                }
            }
        }
        other => {
            eprintln!("oracle: --backend must be `cpu` or `gpu`, got `{other}`");
            std::process::exit(2);
        }
    }
}
