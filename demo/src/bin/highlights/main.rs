//! The sparkle problem and its cure, on the CPU: wavy water and small glossy spheres under a
//! point light, GGX / Beckmann at roughness 0.01, shaded with one sample per pixel by each
//! filtering method and compared with a supersampled reference.
//!
//! Run: `cargo run --release -p filtered-ndf-demo --bin highlights -- [--width 256] [--height 160]
//! [--spp 512] [--frames 16] [--out target/highlights] [--methods a,b,..|all]
//! [--presets on|off] [--investigate on|off] [--fix on|off] [--scene both|water|normal-map]
//! [--footprint quad|rays|moments] [--threads 2] [--seed 1]`.

use filtered_ndf_demo::camera::camera_at;
use filtered_ndf_demo::image_out::{Image, Rgb8, contact_sheet};
use filtered_ndf_demo::methods::{Family, Method};
use filtered_ndf_demo::options::{FIX_ROUTES, Options};
use filtered_ndf_demo::render::FootprintRoute;
use filtered_ndf_demo::scene::{Scene, SceneKind};
use filtered_ndf_demo::{glints, image_out, metrics, normal_map, parallel, render, temporal};
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

fn usage() -> ! {
    let slugs: Vec<&str> = Method::ALL.iter().map(|m| m.slug()).collect();
    eprintln!(
        "usage: highlights [--width N] [--height N] [--spp N] [--frames N] [--out DIR]\n\
         \x20                 [--methods all|{}] [--footprint quad|rays|moments] [--threads N] [--seed N]\n\
         \x20                 [--presets on|off]",
        slugs.join(",")
    );
    std::process::exit(2)
}

fn parse_args() -> Options {
    let mut o = Options {
        width: 256,
        height: 160,
        spp: 512,
        frames: 16,
        out: PathBuf::from("target/highlights"),
        methods: Method::ALL.to_vec(),
        route: FootprintRoute::RayDifferentials,
        threads: 2,
        seed: 1,
        exposure: 1.0,
        presets: true,
        investigate: true,
        fix: true,
        scene: "all",
    };
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let Some(value) = args.next() else { usage() };
        let num = |v: &str| v.parse::<usize>().unwrap_or_else(|_| usage());
        match flag.as_str() {
            "--width" => o.width = num(&value).max(2),
            "--height" => o.height = num(&value).max(2),
            "--spp" => o.spp = num(&value).max(2),
            "--frames" => o.frames = num(&value),
            "--threads" => o.threads = num(&value).max(1),
            "--seed" => o.seed = num(&value) as u64,
            "--presets" => o.presets = value != "off",
            "--investigate" => o.investigate = value != "off",
            "--fix" => o.fix = value != "off",
            "--scene" => {
                o.scene = match value.as_str() {
                    "water" => "water",
                    "normal-map" => "normal-map",
                    "bumpy" => "bumpy",
                    "all" => "all",
                    _ => usage(),
                }
            }
            "--out" => o.out = PathBuf::from(value),
            "--footprint" => {
                o.route = match value.as_str() {
                    "quad" => FootprintRoute::Quad,
                    "rays" => FootprintRoute::RayDifferentials,
                    "moments" => FootprintRoute::Moments,
                    _ => usage(),
                }
            }
            "--methods" => {
                o.methods = if value == "all" {
                    Method::ALL.to_vec()
                } else {
                    value
                        .split(',')
                        .map(|s| Method::parse(s.trim()).unwrap_or_else(|| usage()))
                        .collect()
                }
            }
            _ => usage(),
        }
    }
    o
}

fn main() -> std::io::Result<()> {
    let o = parse_args();
    parallel::init_threads(o.threads);
    std::fs::create_dir_all(&o.out)?;
    let start = Instant::now();
    let mut md = String::new();
    let mut times = Vec::new();
    for name in ["water", "normal-map", "bumpy"] {
        if o.scene != "all" && o.scene != name {
            continue;
        }
        let t = Instant::now();
        let section = match name {
            "water" => run_scene(&o, SceneKind::Water)?,
            "normal-map" => normal_map::run(&o)?,
            _ => {
                // The bumpy spheres: no texture, so no windowed moments (the fix routes would
                // repeat the ray-differential rows), and no false-glint investigation.
                let b = Options {
                    out: o.out.join("bumpy"),
                    fix: false,
                    investigate: false,
                    ..o.clone()
                };
                std::fs::create_dir_all(&b.out)?;
                run_scene(&b, SceneKind::Bumpy)?
            }
        };
        print!("{section}");
        md.push_str(&section);
        times.push(format!("{name} {:.0} s", t.elapsed().as_secs_f64()));
    }
    std::fs::write(o.out.join("results.md"), md)?;
    println!(
        "\nTotal {:.1} s ({}). Images, contact sheets, plots and results.md in {}",
        start.elapsed().as_secs_f64(),
        times.join(", "),
        o.out.display()
    );
    Ok(())
}

/// The water or the bumpy spheres: the still frame of every method and preset against the
/// reference (and the reference's own error), the fix routes, the investigation, the other
/// footprint route, the temporal test; images into `o.out`, the results as markdown.
fn run_scene(o: &Options, kind: SceneKind) -> std::io::Result<String> {
    // The water's sections keep their titles; the other scenes' name themselves.
    let title = match kind {
        SceneKind::Water => String::new(),
        _ => format!("{}: ", capitalise(kind.name())),
    };
    let cam = camera_at(0, o.width, o.height);
    let scene = Scene::of(kind, cam.lod());
    eprintln!(
        "highlights, {}: {}x{}, reference {} spp, {} frames, {} threads, footprints: {:?}",
        kind.name(),
        o.width,
        o.height,
        o.spp,
        o.frames,
        o.threads,
        o.route
    );

    let t = Instant::now();
    let reference = render::reference(
        &scene,
        &cam,
        o.width,
        o.height,
        o.spp,
        o.seed,
        Some("reference"),
    );
    let ref_time = t.elapsed().as_secs_f64();
    // The reference's own error: against an independent reference of four times the samples.
    let t = Instant::now();
    let reference_4n = render::reference(
        &scene,
        &cam,
        o.width,
        o.height,
        4 * o.spp,
        o.seed ^ render::SEED_4N,
        Some("reference x4 (its error)"),
    );
    let ref4_time = t.elapsed().as_secs_f64();
    let reference_error = [Family::Beckmann, Family::Ggx].map(|f| {
        metrics::reference_error(
            (reference.full(f), reference.specular(f)),
            (reference_4n.full(f), reference_4n.specular(f)),
            o.exposure,
        )
    });

    let t = Instant::now();
    let gb = render::gbuffer(&scene, &cam, o.width, o.height);
    let derivs = gb.derivatives(&scene, o.route);
    let base_ms = t.elapsed().as_secs_f64() * 1e3;

    let mut tiles: Vec<(String, Rgb8)> = Vec::new();
    let mut table = String::new();
    writeln!(table, "| method | NDF | RMSE (HDR) | RMSE (display) | RMSE change, spp {} -> {} | mean luminance / reference | ms per frame |", o.spp / 2, o.spp).unwrap();
    writeln!(table, "|---|---|---:|---:|---:|---:|---:|").unwrap();
    for family in [Family::Beckmann, Family::Ggx] {
        let img = reference.full(family);
        let name = format!("reference-{}", family.name().to_lowercase());
        save(o, &name, img)?;
        tiles.push((
            format!("Reference {} {}spp", family.name(), o.spp),
            img.to_rgb8(o.exposure),
        ));
    }
    let mut worst_change: f64 = 0.0;
    // Issue 21's metrics of every method and preset (the flicker comes from the temporal
    // test below), and the LDR-FLIP maps.
    let mut scores: Vec<(Method, FootprintRoute, metrics::Scores)> = Vec::new();
    let mut flip_tiles: Vec<(String, Rgb8)> = Vec::new();
    // Per method on `o.route`: the shading time (ms, this machine, one run).
    let mut shade_times: Vec<(Method, f64)> = Vec::new();
    for &method in &o.methods {
        let t = Instant::now();
        let frame = render::shade_frame(&scene, &gb, &derivs, method);
        shade_times.push((method, t.elapsed().as_secs_f64() * 1e3));
        let ms = base_ms + t.elapsed().as_secs_f64() * 1e3;
        let img = &frame.total;
        let fam = method.family();
        let (sc, map) = metrics::score(
            (img, &frame.specular),
            (reference.full(fam), reference.specular(fam)),
            o.exposure,
        );
        scores.push((method, o.route, sc));
        let map = map.to_rgb8();
        image_out::save(&map, &o.out.join(format!("flip-{}.png", method.slug())))?;
        flip_tiles.push((format!("{} {:.3}", method.label(), sc.flip_ldr), map));
        let (full, half) = (
            reference.full(method.family()),
            reference.half(method.family()),
        );
        let (rmse, rmse_half) = (img.rmse(full), img.rmse(half));
        let change = (rmse_half - rmse).abs() / rmse.max(1e-30);
        worst_change = worst_change.max(change);
        writeln!(
            table,
            "| {} | {} | {:.4} | {:.4} | {:.2}% | {:.3} | {:.1} |",
            method.label(),
            method.family().name(),
            rmse,
            img.rmse_display(full, o.exposure),
            100.0 * change,
            img.mean_luminance() / full.mean_luminance(),
            ms
        )
        .unwrap();
        save(o, method.slug(), img)?;
        tiles.push((method.label().to_string(), img.to_rgb8(o.exposure)));
    }
    // The false-glint fix: the footprint methods again on each fix route (windowed moments,
    // then the sub-window mixture).
    let fixed: Vec<Method> = if o.fix && !FIX_ROUTES.contains(&o.route) {
        o.methods
            .iter()
            .copied()
            .filter(|m| m.uses_footprint())
            .collect()
    } else {
        Vec::new()
    };
    // Per fix route: the time to build the per-pixel filters and the mean time to shade a
    // frame with them (ms, this machine, one run).
    let mut fix_cost = String::new();
    // Per fix route: (filter inputs, mean shading), ms per frame.
    let mut fix_times: Vec<(FootprintRoute, f64, f64)> = Vec::new();
    if !fixed.is_empty() {
        writeln!(fix_cost, "| route | filter inputs, ms per frame | shading, ms per frame (mean over {} methods) |", fixed.len()).unwrap();
        writeln!(fix_cost, "|---|---:|---:|").unwrap();
    }
    for route in FIX_ROUTES.into_iter().filter(|_| !fixed.is_empty()) {
        let t = Instant::now();
        let mixtures = gb.mixtures(&scene, route);
        let build_ms = t.elapsed().as_secs_f64() * 1e3;
        let mut shade_ms = 0.0;
        let mut fixed_tiles = vec![
            (
                "Reference Beckmann".to_string(),
                reference.full(Family::Beckmann).to_rgb8(o.exposure),
            ),
            (
                "Reference GGX".to_string(),
                reference.full(Family::Ggx).to_rgb8(o.exposure),
            ),
        ];
        for &method in &fixed {
            let t = Instant::now();
            let frame = render::shade_mixture(&scene, &gb, &mixtures, method);
            shade_ms += t.elapsed().as_secs_f64() * 1e3;
            let fam = method.family();
            let (sc, map) = metrics::score(
                (&frame.total, &frame.specular),
                (reference.full(fam), reference.specular(fam)),
                o.exposure,
            );
            scores.push((method, route, sc));
            let slug = format!("{}-{}", method.slug(), route_slug(route));
            image_out::save(&map.to_rgb8(), &o.out.join(format!("flip-{slug}.png")))?;
            save(o, &slug, &frame.total)?;
            fixed_tiles.push((
                temporal::variant_label(method, route),
                frame.total.to_rgb8(o.exposure),
            ));
        }
        writeln!(
            fix_cost,
            "| {} | {build_ms:.1} | {:.1} |",
            route_name(route),
            shade_ms / fixed.len() as f64
        )
        .unwrap();
        fix_times.push((route, build_ms, shade_ms / fixed.len() as f64));
        let zoom = if o.width <= 320 { 2 } else { 1 };
        image_out::save(
            &contact_sheet(&fixed_tiles, 3, zoom),
            &o.out
                .join(format!("contact_sheet_{}.png", route_slug(route))),
        )?;
    }
    // Engine conventions (issue: which one over- or under-filters on this scene): the same
    // still frame, table only; mean luminance / reference < 1 means over-filtering.
    let mut preset_table = String::new();
    writeln!(preset_table, "| engine preset (GGX, deferred) | RMSE (HDR) | RMSE (display) | mean luminance / reference | peak / reference peak |").unwrap();
    writeln!(preset_table, "|---|---:|---:|---:|---:|").unwrap();
    if o.presets {
        for method in Method::presets() {
            let frame = render::shade_frame(&scene, &gb, &derivs, method);
            let img = &frame.total;
            let full = reference.full(method.family());
            let (sc, _) = metrics::score(
                (img, &frame.specular),
                (full, reference.specular(method.family())),
                o.exposure,
            );
            scores.push((method, o.route, sc));
            writeln!(
                preset_table,
                "| {} | {:.4} | {:.4} | {:.3} | {:.3} |",
                method.label(),
                img.rmse(full),
                img.rmse_display(full, o.exposure),
                img.mean_luminance() / full.mean_luminance(),
                img.peak() as f64 / full.peak() as f64,
            )
            .unwrap();
        }
    }
    // The other footprint route on the same frame (RMSE only): analytic ray differentials
    // (offline) against 2x2-quad differences (what a GPU does).
    let other = match o.route {
        FootprintRoute::Quad => FootprintRoute::RayDifferentials,
        _ => FootprintRoute::Quad,
    };
    let other_derivs = gb.derivatives(&scene, other);
    let mut route_table = String::new();
    writeln!(
        route_table,
        "| method | RMSE (HDR), {} | RMSE (HDR), {} |",
        route_name(o.route),
        route_name(other)
    )
    .unwrap();
    writeln!(route_table, "|---|---:|---:|").unwrap();
    for &method in &o.methods {
        let full = reference.full(method.family());
        let a = render::shade(&scene, &gb, &derivs, method).rmse(full);
        let b = render::shade(&scene, &gb, &other_derivs, method).rmse(full);
        writeln!(route_table, "| {} | {a:.4} | {b:.4} |", method.label()).unwrap();
    }
    let zoom = if o.width <= 320 { 2 } else { 1 };
    let sheet_path = o.out.join("contact_sheet.png");
    image_out::save(&contact_sheet(&tiles, 3, zoom), &sheet_path)?;
    image_out::save(
        &contact_sheet(&flip_tiles, 3, zoom),
        &o.out.join("flip_sheet.png"),
    )?;

    let glints_md = if o.investigate {
        glints::investigate(o, &scene, &cam, &gb, &reference)?
    } else {
        String::new()
    };
    let presets = if o.presets {
        Method::presets()
    } else {
        Vec::new()
    };
    let temporal = (o.frames >= 2)
        .then(|| temporal::run(o, kind, &presets, &fixed))
        .transpose()?;
    let temporal_md = temporal
        .as_ref()
        .map_or(String::new(), |t| t.markdown.clone());
    let (rows, references) = lead_rows(&scores, temporal.as_ref(), &reference_error, o.spp);
    let lead = metrics::lead_table_with(&rows, &references);
    let groups = route_groups(
        &scores,
        o.route,
        (base_ms, &shade_times),
        &fix_times,
        (o.width, o.height),
    );
    let standing = metrics::standing_table(&groups, &rows, &references);
    let mut md = String::new();
    writeln!(
        md,
        "## {title}Where each route stands ({})\n\nPer route, its best method against unfiltered of the same NDF: the metrics it beats unfiltered on by more than the reference's own error (the first rows of the next table), and what the route costs on the CPU (this machine, one run).\n\n{standing}",
        kind.name()
    )
    .unwrap();
    writeln!(
        md,
        "## {title}What a viewer sees (still frame and temporal test)\n\n{lead}"
    )
    .unwrap();
    md.push_str(&glints_md);
    writeln!(
        md,
        "## {title}Still frame ({}x{}, 1 shading sample per pixel, footprints: {})\n\n{table}",
        o.width,
        o.height,
        route_name(o.route)
    )
    .unwrap();
    if o.presets {
        writeln!(
            md,
            "## {title}Engine presets on the same frame\n\n{preset_table}"
        )
        .unwrap();
    }
    writeln!(
        md,
        "## {title}Both footprint routes on the same frame\n\n{route_table}"
    )
    .unwrap();
    if !fix_cost.is_empty() {
        writeln!(
            md,
            "## The false-glint fix's cost on the still frame\n\n{fix_cost}"
        )
        .unwrap();
    }
    writeln!(md, "Reference: {} spp ({ref_time:.1} s; its error against {} spp, {ref4_time:.1} s: the lead table's first rows); doubling {} -> {} spp changes each RMSE by at most {:.2}%.\n{temporal_md}", o.spp, 4 * o.spp, o.spp / 2, o.spp, 100.0 * worst_change).unwrap();
    Ok(md)
}

/// `s` with its first letter upper case.
fn capitalise(s: &str) -> String {
    let mut c = s.chars();
    c.next()
        .map_or(String::new(), |f| f.to_uppercase().chain(c).collect())
}

/// Issue 21's rows for the CPU demo's methods, presets and variants, and the references' own
/// errors as the verdicts' margins (one row per NDF; [`metrics::lead_table_with`]).
fn lead_rows(
    scores: &[(Method, FootprintRoute, metrics::Scores)],
    temporal: Option<&temporal::Temporal>,
    reference_error: &[metrics::Scores; 2],
    spp: usize,
) -> (Vec<metrics::LeadRow>, Vec<metrics::LeadRow>) {
    let flicker = |m: Method, r: FootprintRoute| {
        temporal.and_then(|tp| {
            let i = tp.methods.iter().position(|&x| x == (m, r))?;
            Some(metrics::Flicker {
                error: tp.flicker_error[i],
                energy: tp.flicker[i],
                peak_variation: tp.peak_variation[i],
            })
        })
    };
    let rows: Vec<metrics::LeadRow> = scores
        .iter()
        .map(|&(m, route, s)| metrics::LeadRow {
            label: temporal::variant_label(m, route),
            ndf: m.family().name(),
            baseline: m == Method::Unfiltered(m.family()),
            scores: s,
            flicker: flicker(m, route),
        })
        .collect();
    let references: Vec<metrics::LeadRow> = [Family::Beckmann, Family::Ggx]
        .into_iter()
        .map(|f| metrics::LeadRow {
            label: format!(
                "{}, {}",
                metrics::reference_error_label(spp, temporal.map(|tp| tp.spp)),
                f.name()
            ),
            ndf: f.name(),
            baseline: false,
            scores: reference_error[f as usize],
            flicker: temporal.map(|tp| metrics::Flicker {
                error: tp.reference_error[f as usize],
                energy: f64::NAN,
                peak_variation: f64::NAN,
            }),
        })
        .collect();
    (rows, references)
}

/// The routes of the "where each route stands" table, over the rows of `scores` (in its
/// order): unfiltered; the footprint methods on `route`; the deferred conventions (TK19's
/// isotropic kernels and the engine presets, from normal differences); each fix route. Costs:
/// `base` = (G-buffer and `route`'s derivatives, per-method shading) and `fixes` = (route,
/// filter inputs, mean shading), ms per frame at `size`.
fn route_groups(
    scores: &[(Method, FootprintRoute, metrics::Scores)],
    route: FootprintRoute,
    (base_ms, shade): (f64, &[(Method, f64)]),
    fixes: &[(FootprintRoute, f64, f64)],
    (w, h): (usize, usize),
) -> Vec<metrics::RouteGroup> {
    let mean_shade = |keep: &dyn Fn(Method) -> bool| {
        let v: Vec<f64> = shade
            .iter()
            .filter(|(m, _)| keep(*m))
            .map(|x| x.1)
            .collect();
        v.iter().sum::<f64>() / v.len().max(1) as f64
    };
    let cost = |inputs: f64, shading: f64| {
        format!("{inputs:.0} ms inputs + {shading:.1} ms shading per frame ({w}x{h}, CPU)")
    };
    let indices = |keep: &dyn Fn(Method, FootprintRoute) -> bool| {
        scores
            .iter()
            .enumerate()
            .filter(|(_, (m, r, _))| keep(*m, *r))
            .map(|(i, _)| i)
            .collect::<Vec<_>>()
    };
    let unfiltered = |m: Method| matches!(m, Method::Unfiltered(_));
    let deferred = |m: Method| !m.uses_footprint() && !unfiltered(m);
    let mut groups = vec![
        metrics::RouteGroup {
            name: "unfiltered".to_string(),
            rows: indices(&|m, _| unfiltered(m)),
            cost: cost(base_ms, mean_shade(&unfiltered)),
        },
        metrics::RouteGroup {
            name: format!("footprint methods, {}", route_name(route)),
            rows: indices(&|m, r| m.uses_footprint() && r == route),
            cost: cost(base_ms, mean_shade(&|m| m.uses_footprint())),
        },
        metrics::RouteGroup {
            name: "deferred conventions (normal differences)".to_string(),
            rows: indices(&|m, _| deferred(m)),
            cost: cost(base_ms, mean_shade(&deferred)),
        },
    ];
    for &(fix, inputs, shading) in fixes {
        groups.push(metrics::RouteGroup {
            name: format!("footprint methods, {}", route_name(fix)),
            rows: indices(&|m, r| m.uses_footprint() && r == fix),
            cost: cost(inputs, shading),
        });
    }
    groups
}

fn save(o: &Options, name: &str, img: &Image) -> std::io::Result<()> {
    image_out::save(&img.to_rgb8(o.exposure), &o.out.join(format!("{name}.png")))
}

/// File-name part of a fix route.
fn route_slug(r: FootprintRoute) -> &'static str {
    match r {
        FootprintRoute::SubWindows => "subwindows",
        FootprintRoute::SubFootprints => "subfootprints",
        FootprintRoute::KurtosisSplit => "kurtosis",
        _ => "moments",
    }
}

fn route_name(r: FootprintRoute) -> &'static str {
    match r {
        FootprintRoute::Quad => "2x2-quad differences (GPU)",
        FootprintRoute::RayDifferentials => "ray differentials + M (offline)",
        FootprintRoute::Moments => "windowed slope moments (the false-glint fix)",
        FootprintRoute::SubWindows => "windowed moments of 4x4 traced sub-windows (the mixture)",
        FootprintRoute::SubFootprints => {
            "windowed moments of 2x2 sub-footprints on the tangent plane (4 lookups)"
        }
        FootprintRoute::KurtosisSplit => {
            "windowed moments split in two by the slopes' fourth moment (kurtosis)"
        }
    }
}
