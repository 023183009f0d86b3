//! The sparkle problem and its cure in a fragment shader: the CPU demonstration's scene
//! (`highlights`: wavy water and glossy spheres, roughness 0.01, one point light)
//! rasterised with wgpu, headless, every filter fed by the GPU's 2x2-quad derivatives
//! (`dpdxFine` / `dpdyFine`) of the shaded quantities, in forward shading (per light, the
//! half vector's derivatives) and in deferred shading (a G-buffer pass that stores the
//! roughness filtered from the normal's derivatives, then a lighting pass); and on the water,
//! the CPU demo's moments route in forward shading (`shaders/moments.wgsl`: the waves' slope
//! moments over the pixel's Gaussian window, from the camera's analytic ray differentials,
//! plus the parallax, nested into each footprint method's kernel; ray differentials on the
//! spheres). The frames are compared with the CPU demo's ray-traced reference of the same
//! camera and scene, and with the CPU demo's own one-sample frames of the same filter inputs.
//!
//! Run: `cargo run --release -p filtered-ndf-demo --features gpu --bin highlights_gpu -- [--quick | --full]
//! [--check] [--width 256] [--height 160] [--spp 512] [--frames 16] [--repeats 31] [--out DIR]
//! [--threads 2] [--seed 1]`; the adapter is chosen by `FILTERED_NDF_GPU_BACKEND=vulkan|gl|any`
//! (as the conformance harness: a real GPU first; Mesa's lavapipe or llvmpipe without one).
//!
//! The scene is rasterised as full-screen draws whose fragment shaders intersect the analytic
//! surfaces (`shaders/scene.wgsl`), one draw per object: the CPU reference ray-traces the
//! exact height field, so a tessellated mesh would move every glint by its tessellation error
//! and the comparison would measure the mesh, not the filter. The derivatives are the
//! fragment shader's, of the values it computed: each object's draw evaluates that object at
//! every pixel of its quads (beyond its silhouette too, as helper lanes do for a triangle) and
//! discards the pixels that see something else, so a quad difference never mixes objects.

// The CPU demonstration's modules (the library of this crate): the one scene description, its
// camera, its methods and renderer (the reference, and its own frames to compare with), its
// images and plots.
use filtered_ndf_demo::{
    camera, image_out, methods, metrics, parallel, peaks, plot, render, scene,
};

mod frame;
mod gpu;
mod passes;
mod report;

use filtered_ndf_gpu::harness::Choice;
use scene::SceneKind;
use std::path::PathBuf;
use std::process::ExitCode;

/// Command-line options.
#[derive(Clone)]
pub struct Options {
    pub width: u32,
    pub height: u32,
    pub spp: usize,
    pub frames: usize,
    pub repeats: usize,
    pub out: PathBuf,
    pub threads: usize,
    pub seed: u64,
    pub exposure: f32,
    /// The size preset chosen (`quick`, `default`, `full`, `custom`).
    pub preset: &'static str,
    /// Fail unless every GPU frame matches the CPU demo's quad-difference frame of the same
    /// method (see [`report::check`]).
    pub check: bool,
    /// Which scenes: `water`, `bumpy` or `all`.
    pub scene: &'static str,
    /// The footprint methods shaded on the moments route (the water only; see
    /// [`passes::Route::Moments`]).
    pub moments: Vec<methods::Method>,
}

/// The footprint methods of the moments route in quick mode (CI's run on software drivers,
/// within its time): the best of each kernel family on the CPU demo's moments route
/// (`docs/highlights.md`), KHPL16's Gaussian on Beckmann and TK19's projected kernel on GGX.
const MOMENTS_QUICK: [methods::Method; 2] = [
    methods::Method::BeckmannParallelogram,
    methods::Method::Tk19Projected,
];

fn usage() -> ! {
    eprintln!(
        "usage: highlights_gpu [--quick | --full] [--check] [--scene water|bumpy|all] [--width N]\n\
         \x20                     [--height N] [--spp N] [--frames N] [--repeats N] [--out DIR]\n\
         \x20                     [--threads N] [--seed N]\n\
         \x20 --scene: the water (images in DIR), the bumpy spheres (DIR/bumpy), or both (default)\n\
         \x20 --quick: 128x80, reference 64 spp, 8 temporal frames, the moments route for two\n\
         \x20          methods (CI, software drivers)\n\
         \x20 default: 256x160, reference 512 spp, 16 frames (the CPU demo's frame)\n\
         \x20 --full:  1280x800, reference 16 spp, 16 frames (for a real GPU; the CPU\n\
         \x20          reference is then the slow part)\n\
         \x20 --check: fail unless each GPU frame agrees with the CPU demo's frame of the same\n\
         \x20          filter inputs (quad differences or the moments route, computed on the\n\
         \x20          CPU) within 0.5 % of the latter's RMSE\n\
         \x20 adapter: FILTERED_NDF_GPU_BACKEND=vulkan|gl|any"
    );
    std::process::exit(2)
}

fn parse_args() -> Options {
    let mut o = Options {
        width: 256,
        height: 160,
        spp: 512,
        frames: 16,
        repeats: 31,
        out: PathBuf::from("target/highlights_gpu"),
        threads: std::thread::available_parallelism().map_or(2, |n| n.get()),
        seed: 1,
        exposure: 1.0,
        preset: "default",
        check: false,
        scene: "all",
        moments: passes::FORWARD
            .into_iter()
            .filter(|m| m.uses_footprint())
            .collect(),
    };
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        match flag.as_str() {
            "--quick" => {
                (o.width, o.height, o.spp, o.frames, o.repeats) = (128, 80, 64, 8, 11);
                o.preset = "quick";
                o.moments = MOMENTS_QUICK.to_vec();
                continue;
            }
            "--full" => {
                (o.width, o.height, o.spp, o.frames, o.repeats) = (1280, 800, 16, 16, 31);
                o.preset = "full";
                continue;
            }
            "--check" => {
                o.check = true;
                continue;
            }
            "--help" | "-h" => usage(),
            _ => {}
        }
        let Some(value) = args.next() else { usage() };
        let num = |v: &str| v.parse::<usize>().unwrap_or_else(|_| usage());
        // Sizes are rounded up to even: whole 2x2 quads.
        let even = |v: usize| (v.max(2).div_ceil(2) * 2) as u32;
        match flag.as_str() {
            "--width" => o.width = even(num(&value)),
            "--height" => o.height = even(num(&value)),
            "--spp" => o.spp = num(&value).max(2),
            "--frames" => o.frames = num(&value),
            "--repeats" => o.repeats = num(&value).max(1),
            "--threads" => o.threads = num(&value).max(1),
            "--seed" => o.seed = num(&value) as u64,
            "--out" => o.out = PathBuf::from(value),
            "--scene" => {
                o.scene = match value.as_str() {
                    "water" => "water",
                    "bumpy" => "bumpy",
                    "all" => "all",
                    _ => usage(),
                }
            }
            _ => usage(),
        }
        if !matches!(flag.as_str(), "--out" | "--threads" | "--scene") {
            o.preset = "custom";
        }
    }
    o
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("highlights_gpu: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), String> {
    let o = parse_args();
    parallel::init_threads(o.threads);
    std::fs::create_dir_all(&o.out).map_err(|e| format!("{}: {e}", o.out.display()))?;
    let start = std::time::Instant::now();
    let gpu = gpu::Gpu::open(Choice::from_env()?)?;
    eprintln!(
        "highlights_gpu: {}x{} ({}), reference {} spp, {} frames; adapter {}",
        o.width,
        o.height,
        o.preset,
        o.spp,
        o.frames,
        gpu.label()
    );
    let kinds: Vec<SceneKind> = [SceneKind::Water, SceneKind::Bumpy]
        .into_iter()
        .filter(|k| o.scene == "all" || o.scene == k.slug())
        .collect();
    let mut renderer = passes::Renderer::new(&gpu)?;
    let t = std::time::Instant::now();
    for &kind in &kinds {
        renderer.prepare(&gpu, &report::routes(kind, &o.moments))?;
    }
    let compile_s = t.elapsed().as_secs_f64();
    let mut md = String::new();
    let (mut passed, mut failures) = (0, Vec::new());
    for kind in kinds {
        // The water's images in `--out`, the other scenes' in a folder of their own.
        let out = match kind {
            SceneKind::Water => o.out.clone(),
            _ => o.out.join(kind.slug()),
        };
        std::fs::create_dir_all(&out).map_err(|e| format!("{}: {e}", out.display()))?;
        let ok = Options { out, ..o.clone() };
        let still = report::still(&ok, kind, &gpu, &mut renderer)?;
        let temporal = report::temporal(&ok, kind, &gpu, &mut renderer)?;
        md.push_str(&report::markdown(&ok, &gpu, compile_s, &still, &temporal));
        let failed = report::check(&still);
        passed += still.rows.len() - failed.len();
        failures.extend(failed.into_iter().map(|f| format!("{}: {f}", kind.name())));
    }
    print!("{md}");
    std::fs::write(o.out.join("results.md"), &md).map_err(|e| e.to_string())?;
    println!(
        "\nTotal {:.1} s. Images, contact sheet, plot and results.md in {}",
        start.elapsed().as_secs_f64(),
        o.out.display()
    );
    if o.check {
        println!(
            "highlights_gpu check: {passed} passed, {} failed",
            failures.len()
        );
        if !failures.is_empty() {
            return Err(failures.join("; "));
        }
    }
    Ok(())
}
