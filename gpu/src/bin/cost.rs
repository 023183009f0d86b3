//! The cost of each trade-table row in WGSL, relative to unfiltered GGX:
//!
//! 1. static SPIR-V instruction counts (naga's SPIR-V of the composed row, instructions in
//!    function bodies, calls not inlined), beside KHPL16 Table 3 (which counts GPU ISA
//!    instructions: +19 Beckmann filtering, +272 GGX rectangle, +22 GGX proxy);
//! 2. evaluations per second on the adapter `FILTERED_NDF_GPU_BACKEND` selects, each row in
//!    dispatches of the same size, as a ratio to unfiltered GGX. On software drivers (Mesa
//!    llvmpipe, lavapipe) only the ratios mean anything.
//!
//! ```text
//! FILTERED_NDF_GPU_BACKEND=vulkan cargo run --release -p filtered-ndf-gpu --bin cost \
//!     [-- --static] [--cases 65536] [--reps 64]
//! ```
//!
//! Each dispatch evaluates `cases x reps` rows (each case `reps` times, its half vector nudged
//! each time) and is timed from submission to completion, so a dispatch must be long enough
//! for that overhead (tens of microseconds) not to count: the defaults suit a software driver;
//! a discrete GPU needs about `--cases 4194304 --reps 256` (a millisecond for unfiltered GGX).

use filtered_ndf_gpu::harness::{self, Kernel};
use filtered_ndf_gpu::{generate, kernels, modules};

fn khpl16(name: &str) -> &'static str {
    match name {
        "Beckmann KHPL16 A+2Sigma (exact)" => "+19 (over Beckmann)",
        "GGX printed 8-term rect (GDC, eps floor)" => "+272",
        "GGX proxy exact (eq. 19)" | "GGX proxy simple (eq. 20)" => "+22",
        _ => "",
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let static_only = args.iter().any(|a| a == "--static");
    let flag = |name: &str, default: usize| -> usize {
        args.iter().position(|a| a == name).map_or(default, |i| {
            match args.get(i + 1).and_then(|v| v.parse().ok()) {
                Some(v) if v > 0 => v,
                _ => {
                    eprintln!("cost: {name} takes a positive integer");
                    std::process::exit(2)
                }
            }
        })
    };
    let (n, reps) = (flag("--cases", 1 << 16), flag("--reps", 64) as u32);
    let rows = kernels::rows();
    let mut counts = Vec::new();
    for (name, expr) in &rows {
        let k = Kernel {
            imports: kernels::IMPORTS,
            body: &kernels::body(expr, 1),
            n_in: kernels::N_IN,
            n_out: 1,
        };
        let module =
            modules::compose(&k.shader(), "cost.wgsl").unwrap_or_else(|e| panic!("{name}: {e}"));
        let info = naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::default(),
        )
        .validate(&module)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
        let words = generate::spirv(&module, &info).unwrap_or_else(|e| panic!("{name}: {e}"));
        counts.push(kernels::spirv_instructions(&words));
    }
    let (ggx, beck) = (counts[0] as i64, counts[rows.len() - 3] as i64);
    println!(
        "Static SPIR-V instructions (naga {}), added over unfiltered GGX ({ggx}):\n",
        generate::naga_version()
    );
    println!("| row | SPIR-V | added over GGX | KHPL16 Table 3 |");
    println!("|---|---:|---:|---|");
    for ((name, _), c) in rows.iter().zip(&counts) {
        let c = *c as i64;
        let extra = if name.starts_with("Beckmann") && c != beck {
            format!(" ({:+} over Beckmann)", c - beck)
        } else {
            String::new()
        };
        println!("| {name} | {c} | {:+}{extra} | {} |", c - ggx, khpl16(name));
    }
    if static_only {
        return;
    }
    let gpu = harness::gpu().unwrap_or_else(|e| panic!("{e}"));
    println!(
        "\nEvaluations per second on {} ({n} cases x {reps} evaluations a dispatch; only the \
         ratios mean anything on a software driver):\n",
        gpu.label()
    );
    // Seeded cases (SplitMix64): alpha log-uniform in [1e-3, 1], h within 80 degrees,
    // footprints log-uniform in [1e-4, 0.1].
    let mut rng = filtered_ndf_gpu::reference::SplitMix64(0x636f_7374);
    let mut input = Vec::with_capacity(n * kernels::N_IN);
    for _ in 0..n {
        let (ax, ay) = (rng.log_uniform(1e-3, 1.0), rng.log_uniform(1e-3, 1.0));
        let t = rng.range(0.0, 80f64.to_radians());
        let p = rng.range(0.0, std::f64::consts::TAU);
        let h = [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()];
        let mut fpv = || {
            let l = rng.log_uniform(1e-4, 0.1);
            let a = rng.range(0.0, std::f64::consts::TAU);
            [l * a.cos(), l * a.sin()]
        };
        let (u, v) = (fpv(), fpv());
        for x in [ax, ay, h[0], h[1], h[2], u[0], u[1], v[0], v[1]] {
            input.push(x as f32);
        }
    }
    // Rounds over all rows, so that a slow drift of a shared machine hits every row alike;
    // the median of each row's runs.
    let modules: Vec<naga::Module> = rows
        .iter()
        .map(|(name, expr)| {
            let k = Kernel {
                imports: kernels::IMPORTS,
                body: &kernels::body(expr, reps),
                n_in: kernels::N_IN,
                n_out: 1,
            };
            modules::compose(&k.shader(), "cost.wgsl").unwrap_or_else(|e| panic!("{name}: {e}"))
        })
        .collect();
    let mut times: Vec<Vec<f64>> = vec![Vec::new(); rows.len()];
    for _round in 0..5 {
        for (k, m) in modules.iter().enumerate() {
            let t = harness::time_module(m.clone(), n, &input, 1, 3)
                .unwrap_or_else(|e| panic!("{}: {e}", rows[k].0));
            times[k].extend(t);
        }
    }
    let rates: Vec<f64> = times
        .iter_mut()
        .map(|t| {
            t.sort_by(f64::total_cmp);
            (n * reps as usize) as f64 / t[t.len() / 2]
        })
        .collect();
    println!("| row | evaluations / s | relative to unfiltered GGX |");
    println!("|---|---:|---:|");
    for ((name, _), r) in rows.iter().zip(&rates) {
        println!("| {name} | {r:.3e} | {:.2} |", r / rates[0]);
    }
}
