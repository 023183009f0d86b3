//! The sparkle scene rendered headless by Bevy, and what `filtered-ndf-bevy` changes.
//!
//! Normal-mapped water at low roughness under a distant point light, seen at a grazing angle
//! (`scene.rs`), over a short camera move, rendered by Bevy into `Rgba16Float` images and
//! read back, for each method:
//!
//! - unfiltered Bevy (`StandardMaterial`);
//! - Bevy with the formula of bevyengine/bevy pull request 24427 (`pr24427.rs`);
//! - the plugin's material (`FilteredNdfMaterial`), at its default (TK19 trace) and, without
//!   `--quick`, every published convention; and the plugin switched off, which must render
//!   what `StandardMaterial` renders;
//! - the plugin with the normal map's LEAN moment chain (`filtered_ndf_bevy::moment_images`,
//!   baked in memory at startup), at the default convention and, without `--quick`, with a
//!   16x anisotropic sampler and TK21's convention;
//! - without `--quick`, unfiltered Bevy and the plugin's default with a mip chain on the
//!   normal map (the box-filtered normals that a texture pipeline would generate);
//!
//! against a reference rendered by Bevy itself: the unfiltered material at `ss` x `ss` times
//! the resolution, box filtered down (stratified supersampling of the pixel's box: its error
//! falls as the grid refines; without `--quick`, the reference at `2 ss` per axis, four times
//! the samples, measures the reference's own error). The scores are the demonstration's
//! (`filtered_ndf_demo::metrics`), printed as a markdown table.
//!
//! ```text
//! cargo run --example sparkle -- [--quick] [--check] [--deferred] [--out DIR] [--docs FILE]
//! ```
//!
//! `--check` exits with status 1 if a pipeline fails (a shader that does not compose, an
//! import that never resolves), a frame is black or not finite, the plugin switched off does
//! not render what `StandardMaterial` renders, the plugin with the moment chain renders what
//! the plugin without it renders, or the plugin's default or its moment-chain row is not
//! closer to the reference than unfiltered Bevy in RMSE (HDR) and lost highlights, by the
//! margins of `RMSE_CLAIM` and `LOST_CLAIM` (not FLIP, not flicker: see docs/bevy.md).
//! `--docs FILE`
//! rewrites the generated part of FILE (between its `sparkle:begin` and `sparkle:end` marks)
//! and writes the images beside it in a folder of the file's name. Runs on Mesa's lavapipe
//! (Vulkan) without a GPU.

mod capture;
mod compare;
mod output;
mod pr24427;
mod scene;

use bevy::app::PluginsState;
use bevy::camera::visibility::RenderLayers;
use bevy::camera::{ClearColorConfig, Exposure, Hdr, RenderTarget};
use bevy::core_pipeline::prepass::{DeferredPrepass, DepthPrepass};
use bevy::core_pipeline::tonemapping::{DebandDither, Tonemapping};
use bevy::image::{Image as BevyImage, ImageSampler};
use bevy::log::LogPlugin;
use bevy::pbr::DefaultOpaqueRendererMethod;
use bevy::prelude::*;
use bevy::render::gpu_readback::{Readback, ReadbackComplete};
use bevy::render::pipelined_rendering::PipelinedRenderingPlugin;
use bevy::render::render_resource::{
    CachedPipelineState, PipelineCache, TextureFormat, TextureUsages,
};
use bevy::render::view::Msaa;
use bevy::render::{Render, RenderApp, RenderPlugin, RenderSystems};
use filtered_ndf_bevy::{
    FilteredNdfExtension, FilteredNdfMaterial, FilteredNdfPlugin, MomentImages, RoughnessFilter,
    SIGMA_BOX_PIXEL,
};
use filtered_ndf_demo::image_out::Image;
use pr24427::{Pr24427Extension, Pr24427Material, Pr24427Plugin};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

/// The command line.
struct Options {
    quick: bool,
    check: bool,
    deferred: bool,
    out: PathBuf,
    docs: Option<PathBuf>,
    width: usize,
    height: usize,
    frames: usize,
    /// The reference's supersampling per axis.
    ss: usize,
    /// The reference check's per axis (0: none).
    ss_check: usize,
}

impl Options {
    fn parse() -> Result<Self, String> {
        let mut o = Options {
            quick: false,
            check: false,
            deferred: false,
            out: PathBuf::from("target/sparkle"),
            docs: None,
            width: 320,
            height: 192,
            frames: 12,
            ss: 4,
            ss_check: 8,
        };
        let mut args = std::env::args().skip(1);
        while let Some(a) = args.next() {
            let mut value = |name: &str| args.next().ok_or(format!("{name} needs a value"));
            match a.as_str() {
                "--quick" => o.quick = true,
                "--check" => o.check = true,
                "--deferred" => o.deferred = true,
                "--out" => o.out = PathBuf::from(value("--out")?),
                "--docs" => o.docs = Some(PathBuf::from(value("--docs")?)),
                other => return Err(format!("unknown argument {other:?}")),
            }
        }
        if o.quick {
            (o.frames, o.ss_check) = (6, 0);
        }
        Ok(o)
    }
}

/// How a view shades the water.
#[derive(Clone)]
enum Shading {
    /// Bevy's `StandardMaterial`.
    Unfiltered,
    /// Bevy with the pull request's formula.
    Pr24427,
    /// The plugin's material.
    Plugin(FilteredNdfExtension),
    /// The plugin's material with the normal map's moment chain, sampled with this sampler
    /// anisotropy (1: trilinear).
    PluginMoments(FilteredNdfExtension, u16),
}

/// The normal map a view's water uses.
#[derive(Clone, Copy, PartialEq, Eq)]
enum NormalMapLevels {
    /// The base level only (as a PNG loads in Bevy).
    Base,
    /// With its box-filtered mip chain.
    Mipmapped,
}

/// One camera: a method at the frame resolution, or a reference at `ss` times it per axis.
struct View {
    label: String,
    shading: Shading,
    normal_map: NormalMapLevels,
    /// Supersampling per axis (1 for the methods).
    ss: usize,
}

/// The label of the plugin's default row.
const PLUGIN_DEFAULT: &str = "plugin: TK19 trace (default)";
/// The label of the plugin switched off.
const PLUGIN_OFF: &str = "plugin: off";
/// `--check`: the claimed RMSE (HDR) of the plugin's rows, at most this fraction of
/// unfiltered Bevy's: a margin of half unfiltered's RMSE, above the reference's own error
/// (its 4x4 against 8x8 supersampling; docs/bevy.md gives the figures).
const RMSE_CLAIM: f64 = 0.5;
/// `--check`: the claimed lost highlights of the plugin's rows, at most this fraction of
/// unfiltered Bevy's: a margin of three quarters of unfiltered's count, above the
/// reference's own (docs/bevy.md).
const LOST_CLAIM: f64 = 0.25;
/// The label of the plugin's default with the moment chain.
const PLUGIN_LEAN: &str = "plugin + moment chain (LEAN)";
/// The label of the plugin's default with the moment chain and a 16x anisotropic sampler.
const PLUGIN_LEAN_ANISOTROPIC: &str = "plugin + moment chain (LEAN), aniso 16x";

fn views(o: &Options) -> Vec<View> {
    let method = |label: &str, shading| View {
        label: label.to_string(),
        shading,
        normal_map: NormalMapLevels::Base,
        ss: 1,
    };
    let mut v = vec![
        method("Bevy, unfiltered", Shading::Unfiltered),
        method("Bevy + PR 24427 formula", Shading::Pr24427),
        method(
            PLUGIN_DEFAULT,
            Shading::Plugin(FilteredNdfExtension::default()),
        ),
        method(
            PLUGIN_OFF,
            Shading::Plugin(FilteredNdfExtension::new(RoughnessFilter::Off)),
        ),
        method(
            PLUGIN_LEAN,
            Shading::PluginMoments(FilteredNdfExtension::default(), 1),
        ),
    ];
    if !o.quick {
        v.push(method(
            PLUGIN_LEAN_ANISOTROPIC,
            Shading::PluginMoments(FilteredNdfExtension::default(), 16),
        ));
        v.push(method(
            "plugin + moment chain (LEAN), TK21 listing 5",
            Shading::PluginMoments(FilteredNdfExtension::new(RoughnessFilter::Tk21), 1),
        ));
        for (label, shading) in [
            (
                "Bevy, unfiltered, normal map with mips",
                Shading::Unfiltered,
            ),
            (
                "plugin: TK19 trace (default), normal map with mips",
                Shading::Plugin(FilteredNdfExtension::default()),
            ),
        ] {
            v.push(View {
                normal_map: NormalMapLevels::Mipmapped,
                ..method(label, shading)
            });
        }
        for f in [
            RoughnessFilter::Tk19Max,
            RoughnessFilter::Tk19Average,
            RoughnessFilter::Tk21,
            RoughnessFilter::Filament,
            RoughnessFilter::UnityHdrp,
            RoughnessFilter::UnityHdrpProjected,
            RoughnessFilter::Godot,
            RoughnessFilter::Unreal,
            RoughnessFilter::ThreeJs,
        ] {
            v.push(method(
                &format!("plugin: {}", f.label()),
                Shading::Plugin(FilteredNdfExtension::new(f)),
            ));
        }
        for f in [RoughnessFilter::Tk19Trace, RoughnessFilter::Tk19Average] {
            v.push(method(
                &format!("plugin: {}, sigma = 1/sqrt(12)", f.label()),
                Shading::Plugin(FilteredNdfExtension::new(f).with_sigma(SIGMA_BOX_PIXEL)),
            ));
        }
    }
    v.push(View {
        label: format!("reference ({0}x{0} supersampled)", o.ss),
        shading: Shading::Unfiltered,
        normal_map: NormalMapLevels::Base,
        ss: o.ss,
    });
    if o.ss_check > 0 {
        v.push(View {
            label: format!("reference ({0}x{0} supersampled)", o.ss_check),
            shading: Shading::Unfiltered,
            normal_map: NormalMapLevels::Base,
            ss: o.ss_check,
        });
    }
    v
}

/// What the render world's pipeline cache holds: errors, and pipelines not yet created.
#[derive(Default)]
struct PipelineReport {
    errors: Vec<String>,
    pending: usize,
    ok: usize,
}

/// The report, shared between the render world (writer) and `main` (reader).
#[derive(Resource, Clone, Default)]
struct SharedPipelineReport(Arc<Mutex<PipelineReport>>);

/// Render-world system: the state of every pipeline after this frame's rendering.
fn watch_pipelines(cache: Res<PipelineCache>, report: Res<SharedPipelineReport>) {
    let mut r = PipelineReport::default();
    for p in cache.pipelines() {
        match &p.state {
            CachedPipelineState::Ok(_) => r.ok += 1,
            CachedPipelineState::Err(e) => r.errors.push(e.to_string()),
            CachedPipelineState::Queued | CachedPipelineState::Creating(_) => r.pending += 1,
        }
    }
    if let Ok(mut shared) = report.0.lock() {
        *shared = r;
    }
}

/// The app: Bevy's default plugins without a window and with pipelines compiled in the frame
/// that needs them, rendering in `update` (no pipelined rendering), and the materials.
fn build_app(o: &Options, report: &SharedPipelineReport) -> App {
    let mut app = App::new();
    app.add_plugins(
        DefaultPlugins
            .set(RenderPlugin {
                synchronous_pipeline_compilation: true,
                ..default()
            })
            .set(LogPlugin {
                // A frame's readbacks are despawned once every target has arrived; the copies
                // still in flight then warn that nobody listens.
                filter: "wgpu=error,naga=warn,bevy_render=info,bevy_render::gpu_readback=error,bevy_app=warn".to_string(),
                ..default()
            })
            .disable::<PipelinedRenderingPlugin>(),
    )
    .add_plugins((FilteredNdfPlugin, Pr24427Plugin))
    .insert_resource(GlobalAmbientLight {
        color: Color::srgb(0.6, 0.75, 1.0),
        brightness: 1.0,
        affects_lightmapped_meshes: true,
    });
    if o.deferred {
        app.insert_resource(DefaultOpaqueRendererMethod::deferred());
    }
    if let Some(render_app) = app.get_sub_app_mut(RenderApp) {
        render_app
            .insert_resource(report.clone())
            .add_systems(Render, watch_pipelines.in_set(RenderSystems::Cleanup));
    }
    app
}

/// `images` with both samplers' anisotropy clamp set to `anisotropy` (1: trilinear).
fn with_anisotropy(images: &MomentImages, anisotropy: u16) -> MomentImages {
    let mut out = images.clone();
    for i in [&mut out.moments, &mut out.moments_xy] {
        if let ImageSampler::Descriptor(d) = &mut i.sampler {
            d.anisotropy_clamp = anisotropy;
        }
    }
    out
}

/// Spawns the water once per method (on its own render layer), the light on every layer, and
/// one camera per view rendering into its own `Rgba16Float` image; returns the images.
fn spawn_scene(
    app: &mut App,
    o: &Options,
    views: &[View],
) -> Result<Vec<Handle<BevyImage>>, String> {
    let map = scene::normal_map();
    let baking = std::time::Instant::now();
    let moments = filtered_ndf_bevy::moment_images(&map).map_err(|e| e.to_string())?;
    eprintln!(
        "sparkle: the normal map's moment chain baked in {:.2} s",
        baking.elapsed().as_secs_f64()
    );
    let world = app.world_mut();
    let (normal_map, normal_map_mipmapped) = {
        let mut images = world.resource_mut::<Assets<BevyImage>>();
        (images.add(map), images.add(scene::normal_map_mipmapped()))
    };
    let mesh = world
        .resource_mut::<Assets<Mesh>>()
        .add(scene::water_mesh());
    // The methods' layers are their indices; the references look at the unfiltered water.
    let layers: Vec<usize> = views
        .iter()
        .enumerate()
        .map(|(i, v)| if v.ss > 1 { 0 } else { i })
        .collect();
    for (i, v) in views.iter().enumerate() {
        if v.ss > 1 {
            continue;
        }
        let layer = RenderLayers::layer(i);
        let water = (Mesh3d(mesh.clone()), scene::lake_transform(), layer);
        let base = scene::water_material(match v.normal_map {
            NormalMapLevels::Base => normal_map.clone(),
            NormalMapLevels::Mipmapped => normal_map_mipmapped.clone(),
        });
        match &v.shading {
            Shading::Unfiltered => {
                let m = world
                    .resource_mut::<Assets<StandardMaterial>>()
                    .add(base.clone());
                world.spawn((water, MeshMaterial3d(m)));
            }
            Shading::Pr24427 => {
                let m = world
                    .resource_mut::<Assets<Pr24427Material>>()
                    .add(Pr24427Material {
                        base: base.clone(),
                        extension: Pr24427Extension::default(),
                    });
                world.spawn((water, MeshMaterial3d(m)));
            }
            Shading::Plugin(extension) => {
                let m =
                    world
                        .resource_mut::<Assets<FilteredNdfMaterial>>()
                        .add(FilteredNdfMaterial {
                            base: base.clone(),
                            extension: extension.clone(),
                        });
                world.spawn((water, MeshMaterial3d(m)));
            }
            Shading::PluginMoments(extension, anisotropy) => {
                let chain = with_anisotropy(&moments, *anisotropy);
                let extension = extension
                    .clone()
                    .with_moment_images(chain, &mut world.resource_mut::<Assets<BevyImage>>());
                let m =
                    world
                        .resource_mut::<Assets<FilteredNdfMaterial>>()
                        .add(FilteredNdfMaterial {
                            base: base.clone(),
                            extension,
                        });
                world.spawn((water, MeshMaterial3d(m)));
            }
        }
    }
    world.spawn((
        PointLight {
            color: Color::srgb(1.0, 0.92, 0.8),
            intensity: 1.0e6,
            range: 1000.0,
            radius: 0.0,
            shadow_maps_enabled: false,
            ..default()
        },
        scene::light_transform(),
        RenderLayers::from_layers(&(0..views.len()).collect::<Vec<_>>()),
    ));
    let mut targets = Vec::new();
    for (i, v) in views.iter().enumerate() {
        let (w, h) = (o.width * v.ss, o.height * v.ss);
        let mut target =
            BevyImage::new_target_texture(w as u32, h as u32, TextureFormat::Rgba16Float, None);
        target.texture_descriptor.usage |= TextureUsages::COPY_SRC;
        let handle = world.resource_mut::<Assets<BevyImage>>().add(target);
        let mut camera = world.spawn((
            Camera3d::default(),
            Camera {
                order: i as isize,
                clear_color: ClearColorConfig::Custom(Color::srgb(0.12, 0.14, 0.2)),
                ..default()
            },
            RenderTarget::Image(handle.clone().into()),
            Projection::Perspective(PerspectiveProjection {
                fov: scene::FOV_Y,
                near: 0.1,
                far: 2000.0,
                aspect_ratio: w as f32 / h as f32,
                ..default()
            }),
            Exposure { ev100: 0.0 },
            Hdr,
            Tonemapping::None,
            DebandDither::Disabled,
            Msaa::Off,
            scene::camera_transform(0, o.frames),
            RenderLayers::layer(layers[i]),
        ));
        if o.deferred {
            camera.insert((DepthPrepass, DeferredPrepass));
        }
        targets.push(handle);
    }
    Ok(targets)
}

/// Runs `update` until the plugins are ready, then finishes the app (what `App::run`'s
/// runner does first).
fn start(app: &mut App) {
    while app.plugins_state() == PluginsState::Adding {
        bevy::tasks::tick_global_task_pools_on_main_thread();
    }
    app.finish();
    app.cleanup();
}

/// Updates until every pipeline is created (or one fails): the first frames compile the
/// pipelines and upload the meshes and images.
fn warm_up(app: &mut App, report: &SharedPipelineReport) -> Result<(), String> {
    const MIN_FRAMES: usize = 4;
    const MAX_FRAMES: usize = 120;
    for frame in 0..MAX_FRAMES {
        app.update();
        let r = report.0.lock().map_err(|e| e.to_string())?;
        if !r.errors.is_empty() {
            return Err(format!("pipeline errors:\n{}", r.errors.join("\n")));
        }
        if frame + 1 >= MIN_FRAMES && r.pending == 0 && r.ok > 0 {
            return Ok(());
        }
    }
    let r = report.0.lock().map_err(|e| e.to_string())?;
    Err(format!(
        "{} pipelines still not created after {MAX_FRAMES} frames (a shader import that never resolves?)",
        r.pending
    ))
}

/// Renders frame `frame` of the move in every view and reads every target back.
fn capture(
    app: &mut App,
    o: &Options,
    views: &[View],
    targets: &[Handle<BevyImage>],
    frame: usize,
) -> Result<Vec<Image>, String> {
    let t = scene::camera_transform(frame, o.frames);
    let world = app.world_mut();
    let mut cameras = world.query_filtered::<&mut Transform, With<Camera3d>>();
    for mut c in cameras.iter_mut(world) {
        *c = t;
    }
    app.update();
    let slots: Arc<Mutex<Vec<Option<Vec<u8>>>>> = Arc::new(Mutex::new(vec![None; targets.len()]));
    let mut readbacks = Vec::new();
    for (i, target) in targets.iter().enumerate() {
        let slots = slots.clone();
        let e = app
            .world_mut()
            .spawn(Readback::texture(target.clone()))
            .observe(move |ev: On<ReadbackComplete>| {
                if let Ok(mut s) = slots.lock() {
                    s[i].get_or_insert_with(|| ev.event().data.clone());
                }
            })
            .id();
        readbacks.push(e);
    }
    const MAX_FRAMES: usize = 60;
    let mut done = false;
    for _ in 0..MAX_FRAMES {
        app.update();
        if slots
            .lock()
            .map_err(|e| e.to_string())?
            .iter()
            .all(Option::is_some)
        {
            done = true;
            break;
        }
    }
    for e in readbacks {
        app.world_mut().despawn(e);
    }
    if !done {
        return Err(format!(
            "frame {frame}: readback incomplete after {MAX_FRAMES} updates"
        ));
    }
    let data = std::mem::take(&mut *slots.lock().map_err(|e| e.to_string())?);
    views
        .iter()
        .zip(data)
        .map(|(v, bytes)| {
            let (w, h) = (o.width * v.ss, o.height * v.ss);
            let img = capture::decode_rgba16f(&bytes.unwrap_or_default(), w, h)
                .ok_or(format!("{}: readback shorter than {w}x{h}", v.label))?;
            Ok(capture::box_downsample(&img, v.ss))
        })
        .collect()
}

/// The display exposure of the LDR metrics and images: the reference's mean luminance to 0.18
/// (middle grey), over the move.
fn display_exposure(reference: &[Image]) -> f32 {
    let mean = reference.iter().map(|r| r.mean_luminance()).sum::<f64>() / reference.len() as f64;
    if mean > 0.0 {
        (0.18 / mean) as f32
    } else {
        1.0
    }
}

fn main() {
    let o = match Options::parse() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("sparkle: {e}");
            std::process::exit(2);
        }
    };
    if let Err(e) = run(&o) {
        eprintln!("sparkle: {e}");
        std::process::exit(1);
    }
}

fn run(o: &Options) -> Result<(), String> {
    let views = views(o);
    let report = SharedPipelineReport::default();
    let mut app = build_app(o, &report);
    let targets = spawn_scene(&mut app, o, &views)?;
    start(&mut app);
    let started = std::time::Instant::now();
    warm_up(&mut app, &report)?;
    eprintln!(
        "sparkle: {} pipelines ready after {:.1} s",
        report.0.lock().map_err(|e| e.to_string())?.ok,
        started.elapsed().as_secs_f64()
    );
    // frames[view][frame]
    let mut frames: Vec<Vec<Image>> = views.iter().map(|_| Vec::new()).collect();
    for f in 0..o.frames {
        for (v, img) in capture(&mut app, o, &views, &targets, f)?
            .into_iter()
            .enumerate()
        {
            frames[v].push(img);
        }
        eprintln!(
            "sparkle: frame {}/{} ({:.1} s)",
            f + 1,
            o.frames,
            started.elapsed().as_secs_f64()
        );
    }
    {
        let r = report.0.lock().map_err(|e| e.to_string())?;
        if !r.errors.is_empty() {
            return Err(format!("pipeline errors:\n{}", r.errors.join("\n")));
        }
    }
    drop(app);

    let methods = views.iter().filter(|v| v.ss == 1).count();
    let reference = &frames[methods];
    let exposure = display_exposure(reference);
    let mut rows: Vec<compare::Row> = (0..methods)
        .map(|i| compare::evaluate(&views[i].label, &frames[i], reference, exposure))
        .collect();
    let mut extra = Vec::new();
    if let Some(check) = frames.get(methods + 1) {
        extra.push(compare::evaluate(
            &format!(
                "{} against {}",
                views[methods].label,
                views[methods + 1].label
            ),
            reference,
            check,
            display_exposure(check),
        ));
    }
    // The plugin switched off is a check, not a method.
    let off = rows.iter().position(|r| r.label == PLUGIN_OFF);
    let off_row = off.map(|i| rows.remove(i));
    let table = compare::table(&rows, &extra);
    let header = format!(
        "{} frames of {}x{}, {} rendering, reference {}x{} supersampled, display exposure {:.3}",
        o.frames,
        o.width,
        o.height,
        if o.deferred { "deferred" } else { "forward" },
        o.ss,
        o.ss,
        exposure
    );
    println!("## Bevy sparkle scene ({header})\n\n{table}");

    std::fs::create_dir_all(&o.out).map_err(|e| format!("{}: {e}", o.out.display()))?;
    let images = output::write_images(o, &views, &frames, methods, exposure, &o.out)?;
    if let Some(docs) = &o.docs {
        output::write_docs(o, docs, &header, &table, &views, &frames, methods, exposure)?;
    }
    eprintln!("sparkle: images in {}", images.display());

    if o.check {
        check(o, &views, &frames, methods, &rows, off_row.as_ref(), off)?;
        println!("sparkle check: ok");
    }
    Ok(())
}

/// `--check`: the render is sound and the plugin helps.
fn check(
    o: &Options,
    views: &[View],
    frames: &[Vec<Image>],
    methods: usize,
    rows: &[compare::Row],
    off_row: Option<&compare::Row>,
    off: Option<usize>,
) -> Result<(), String> {
    let mut failures = Vec::new();
    for (v, seq) in views.iter().zip(frames) {
        for (f, img) in seq.iter().enumerate() {
            if img.data.iter().any(|c| !c.is_finite()) {
                failures.push(format!("{} frame {f}: not finite", v.label));
            }
            // The water's ambient light alone is far above this (the sky is brighter still).
            if img.mean_luminance() < 1e-3 {
                failures.push(format!("{} frame {f}: black", v.label));
            }
        }
    }
    let _ = (o, methods);
    if let (Some(i), Some(_)) = (off, off_row) {
        // The plugin switched off runs StandardMaterial's shading through the plugin's shader:
        // the same arithmetic, so the same pixels up to the half-float target's rounding.
        let worst = frames[i]
            .iter()
            .zip(&frames[0])
            .flat_map(|(a, b)| a.data.iter().zip(&b.data))
            .map(|(p, q)| ((*p - *q).abs() / (q.abs() + glam::Vec3::splat(1e-3))).max_element())
            .fold(0.0f32, f32::max);
        if worst > 1e-3 {
            failures.push(format!(
                "{PLUGIN_OFF} differs from StandardMaterial (largest relative difference {worst:.2e})"
            ));
        }
    }
    // What the figures support (docs/bevy.md): the plugin's default, and the plugin with the
    // moment chain, are closer to the reference than unfiltered Bevy in linear radiance
    // (RMSE) and lose fewer of the reference's highlights, each by a margin above the
    // reference's own error (its 4x4 against 8x8 supersampling). Neither is closer on FLIP,
    // and the flicker error of the 4x4 reference against the 8x8 one exceeds every method's,
    // so neither is claimed.
    let base = &rows[0];
    for label in [PLUGIN_DEFAULT, PLUGIN_LEAN] {
        match rows.iter().find(|r| r.label == label) {
            Some(p) => {
                let mut missing = Vec::new();
                if p.rmse_hdr > RMSE_CLAIM * base.rmse_hdr {
                    missing.push(format!("RMSE (HDR) at most {RMSE_CLAIM} x unfiltered's"));
                }
                if p.lost_highlights as f64 > LOST_CLAIM * base.lost_highlights as f64 {
                    missing.push(format!(
                        "lost highlights at most {LOST_CLAIM} x unfiltered's"
                    ));
                }
                if !missing.is_empty() {
                    failures.push(format!("{label}: not {}", missing.join(", ")));
                }
            }
            None => failures.push(format!("no {label} row")),
        }
    }
    // The moment chain is bound and read: its frames are not the plugin's default ones.
    let find = |label: &str| views.iter().position(|v| v.label == label);
    if let (Some(d), Some(l)) = (find(PLUGIN_DEFAULT), find(PLUGIN_LEAN)) {
        let largest = frames[l]
            .iter()
            .zip(&frames[d])
            .flat_map(|(a, b)| a.data.iter().zip(&b.data))
            .map(|(p, q)| ((*p - *q).abs() / (q.abs() + glam::Vec3::splat(1e-3))).max_element())
            .fold(0.0f32, f32::max);
        if largest <= 1e-3 {
            failures.push(format!(
                "{PLUGIN_LEAN} renders what {PLUGIN_DEFAULT} renders (the moment chain is not read)"
            ));
        }
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(format!("check failed:\n  {}", failures.join("\n  ")))
    }
}
