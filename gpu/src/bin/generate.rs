//! Writes `shaders/generated/` from the WGSL modules of `shaders/` (the concatenated WGSL
//! file and naga's GLSL 330, GLSL ES 310, HLSL SM 5.1 and MSL translations).
//!
//! ```text
//! cargo run -p filtered-ndf-gpu --bin generate            # regenerate
//! cargo run -p filtered-ndf-gpu --bin generate -- --check # fail if out of date (CI)
//! ```

fn main() {
    let check = std::env::args().any(|a| a == "--check");
    match filtered_ndf_gpu::generate::run(check) {
        Ok(differ) if differ.is_empty() => {
            println!("shaders/generated/ is up to date");
        }
        Ok(differ) if check => {
            eprintln!(
                "shaders/generated/ is out of date; run `cargo run -p filtered-ndf-gpu --bin generate` and commit:"
            );
            for d in differ {
                eprintln!("  {d}");
            }
            std::process::exit(1);
        }
        Ok(differ) => {
            for d in differ {
                println!("wrote {d}");
            }
        }
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(2);
        }
    }
}
