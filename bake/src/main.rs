//! `bake`: the command-line baker (`filtered_ndf_bake::USAGE`).

use filtered_ndf_bake::{Options, USAGE, run};
use std::process::ExitCode;

fn main() -> ExitCode {
    let options = match Options::parse(std::env::args().skip(1)) {
        Ok(Some(o)) => o,
        Ok(None) => {
            print!("{USAGE}");
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            eprintln!("bake: {e}");
            return ExitCode::from(2);
        }
    };
    match run(&options) {
        Ok(s) => {
            println!(
                "bake: wrote {} files to {} ({} levels)",
                s.files.len(),
                s.out.display(),
                s.levels.len()
            );
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("bake: {e}");
            ExitCode::FAILURE
        }
    }
}
