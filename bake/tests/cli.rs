//! The baker end to end: its KTX2 files read back with an independent reader (the `ktx2`
//! crate, the parser Bevy's loader uses) and every level of every chain compared with
//! `filtered_ndf::bake::bake_rows` run here on the same map, whole levels on one thread; the
//! bad inputs and what they leave behind.
//!
//! The comparisons are exact: the baker stores what `bake_rows` computes (bands of rows are
//! independent, the library's tested contract), and the expected bytes are encoded here from
//! the definitions of the formats (`round(255 v)` of the glTF and `KHR_materials_anisotropy`
//! values, `store_f16` and `store_f32` of the moments in the channel order of the files).

use filtered_ndf::bake::fit::{self, AnisotropicAlpha};
use filtered_ndf::bake::{
    Band, BaseRoughness, ChainLayout, Convention, Kernel, NormalFormat, NormalMap, Settings,
    SlopeSource, TexelStats, Texels, bake_rows,
};
use filtered_ndf_bake::{Options, Roughness, run};
use image::{ImageBuffer, Luma, Rgb, Rgb32FImage};
use std::path::{Path, PathBuf};

fn tmp(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("bake-cli-{name}"));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn real_map() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../demo/data/normal_maps/pmndrs_0011.png")
}

/// The levels of a KTX2 file, checked against the header the baker must write.
fn read_ktx2(path: &Path, vk_format: u32, width: u32, height: u32) -> Vec<Vec<u8>> {
    let bytes = std::fs::read(path).unwrap();
    let r = ktx2::Reader::new(&bytes[..]).unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
    let h = r.header();
    assert_eq!(
        h.format.map(|f| f.value()),
        Some(vk_format),
        "{}",
        path.display()
    );
    assert_eq!((h.pixel_width, h.pixel_height), (width, height));
    assert_eq!(h.pixel_depth, 0);
    assert_eq!(h.layer_count, 0);
    assert_eq!(h.face_count, 1);
    assert!(h.supercompression_scheme.is_none());
    let levels = ChainLayout::new(width as usize, height as usize)
        .unwrap()
        .levels();
    assert_eq!(h.level_count as usize, levels, "every mip level");
    // The descriptor block as the reader's own generator builds it for the format (all but
    // the primaries: the chains are data, written as unspecified).
    let dfd = r.basic_dfd().expect("a basic data format descriptor");
    let (want, type_size) = ktx2::dfd::Basic::from_format(h.format.unwrap()).unwrap();
    assert_eq!(type_size, h.type_size);
    assert_eq!(dfd.color_model, want.color_model);
    assert_eq!(dfd.color_primaries, None);
    assert_eq!(dfd.transfer_function, Some(ktx2::TransferFunction::Linear));
    assert_eq!(dfd.transfer_function, want.transfer_function);
    assert_eq!(dfd.flags, want.flags);
    assert_eq!(dfd.texel_block_dimensions, want.texel_block_dimensions);
    assert_eq!(dfd.bytes_planes, want.bytes_planes);
    assert_eq!(dfd.sample_information, want.sample_information);
    // KTX2's string values end in NUL.
    assert_eq!(
        r.writer(),
        Some(format!("{}\0", filtered_ndf_bake::WRITER).as_str())
    );
    r.levels().map(|l| l.data.to_vec()).collect()
}

/// What `bake_rows` gives for every level, one level at a time.
struct Expected {
    layout: ChainLayout,
    moments: Vec<[f32; 5]>,
    moments_f16: Vec<[u16; 5]>,
    iso: Vec<f32>,
    aniso: Vec<[f32; 3]>,
}

fn expected<S: SlopeSource>(src: &S, settings: &Settings<'_>) -> Expected {
    let layout = ChainLayout::new(src.width(), src.height()).unwrap();
    let n = layout.len();
    let mut e = Expected {
        layout,
        moments: vec![[0.0; 5]; n],
        moments_f16: vec![[0; 5]; n],
        iso: vec![0.0; n],
        aniso: vec![[0.0; 3]; n],
    };
    let mut scratch = vec![TexelStats::default(); layout.scratch_len()];
    for k in 0..layout.levels() {
        let lv = layout.level(k);
        let r = lv.rows(0..lv.height);
        bake_rows(
            src,
            settings,
            &layout,
            k,
            0..lv.height,
            &mut scratch,
            Band {
                moments: Some(&mut e.moments[r.clone()]),
                moments_f16: Some(&mut e.moments_f16[r.clone()]),
                ggx: Some(&mut e.iso[r.clone()]),
                ggx_anisotropic: Some(&mut e.aniso[r.clone()]),
                ..Band::default()
            },
        )
        .unwrap();
    }
    e
}

fn u8_of(v: f64) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

fn lobe(a: [f32; 3]) -> AnisotropicAlpha {
    AnisotropicAlpha {
        alpha_x: a[0].into(),
        alpha_y: a[1].into(),
        angle: a[2].into(),
    }
}

fn le16(v: &[u16]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

fn le32(v: &[f32]) -> Vec<u8> {
    v.iter().flat_map(|x| x.to_le_bytes()).collect()
}

/// Checks the moment files (f16 or f32) of a bake against `e`.
fn check_moments(dir: &Path, e: &Expected, f32_storage: bool) {
    let (w, h) = (e.layout.width() as u32, e.layout.height() as u32);
    let (rgba_fmt, r_fmt) = if f32_storage { (109, 100) } else { (97, 76) };
    let rgba = read_ktx2(&dir.join("moments.ktx2"), rgba_fmt, w, h);
    let xy = read_ktx2(&dir.join("moments_xy.ktx2"), r_fmt, w, h);
    for k in 0..e.layout.levels() {
        let lv = e.layout.level(k);
        let r = lv.rows(0..lv.height);
        let (want_rgba, want_xy) = if f32_storage {
            let m = &e.moments[r];
            (
                le32(
                    &m.iter()
                        .flat_map(|t| [t[0], t[1], t[2], t[4]])
                        .collect::<Vec<_>>(),
                ),
                le32(&m.iter().map(|t| t[3]).collect::<Vec<_>>()),
            )
        } else {
            let m = &e.moments_f16[r];
            (
                le16(
                    &m.iter()
                        .flat_map(|t| [t[0], t[1], t[2], t[4]])
                        .collect::<Vec<_>>(),
                ),
                le16(&m.iter().map(|t| t[3]).collect::<Vec<_>>()),
            )
        };
        assert!(rgba[k] == want_rgba, "moments.ktx2 level {k}");
        assert!(xy[k] == want_xy, "moments_xy.ktx2 level {k}");
    }
}

#[test]
fn the_real_map_bakes_to_the_library_chains_in_every_file() {
    let dir = tmp("real");
    let out = dir.join("out");
    // The binary itself, as a user runs it.
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_bake"))
        .arg(real_map())
        .args([
            "--anisotropic",
            "--unit-tolerance",
            "any",
            "--roughness",
            "0.3",
            "--quiet",
        ])
        .arg("--out")
        .arg(&out)
        .status()
        .unwrap();
    assert!(status.success());
    let img = image::open(real_map()).unwrap().into_rgb8();
    let (w, h) = (img.width() as usize, img.height() as usize);
    let raw = img.into_raw();
    let map = NormalMap::new(
        Texels::Unorm8(&raw),
        w,
        h,
        NormalFormat::new(3, Convention::OpenGl).with_tolerance(f64::INFINITY),
    )
    .unwrap();
    let settings = Settings {
        kernel: Kernel::Area,
        base: BaseRoughness::Constant(0.3 * 0.3),
    };
    let e = expected(&map, &settings);
    let rough = read_ktx2(&out.join("roughness.ktx2"), 9, w as u32, h as u32);
    let aniso = read_ktx2(&out.join("anisotropy.ktx2"), 37, w as u32, h as u32);
    for k in 0..e.layout.levels() {
        let lv = e.layout.level(k);
        let r = lv.rows(0..lv.height);
        let want: Vec<u8> = e.aniso[r.clone()]
            .iter()
            .map(|&a| u8_of(lobe(a).khr().roughness))
            .collect();
        assert!(rough[k] == want, "roughness.ktx2 level {k}");
        let want: Vec<u8> = e.aniso[r]
            .iter()
            .flat_map(|&a| {
                let k = lobe(a).khr();
                [
                    u8_of(0.5 * (k.direction.x + 1.0)),
                    u8_of(0.5 * (k.direction.y + 1.0)),
                    u8_of(k.strength),
                    255,
                ]
            })
            .collect();
        assert!(aniso[k] == want, "anisotropy.ktx2 level {k}");
    }
    check_moments(&out, &e, false);
    // The inspection images and the report.
    for k in 0..e.layout.levels() {
        for name in ["roughness", "normal", "variance", "anisotropy"] {
            let p = out.join(format!("levels/{name}_{k}.png"));
            let i = image::open(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            assert_eq!((i.width() as usize, i.height() as usize), (lv_size(&e, k)));
        }
    }
    let r = image::open(out.join("levels/roughness_3.png"))
        .unwrap()
        .into_luma8();
    let lv = e.layout.level(3);
    let want: Vec<u8> = e.aniso[lv.rows(0..lv.height)]
        .iter()
        .map(|&a| u8_of(lobe(a).khr().roughness))
        .collect();
    assert_eq!(r.into_raw(), want, "the roughness PNG is the KTX2 level");
    assert!(image::open(out.join("contact_sheet.png")).is_ok());
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    let rows = md
        .lines()
        .filter(|l| l.starts_with("| ") && l.contains("x"))
        .count();
    assert!(rows > e.layout.levels(), "a row per level:\n{md}");
    // Nothing but the output directory beside it.
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, [std::ffi::OsString::from("out")]);
}

fn lv_size(e: &Expected, k: usize) -> (usize, usize) {
    let lv = e.layout.level(k);
    (lv.width, lv.height)
}

/// A 16-bit RGB normal map of `37 x 23` texels (odd sizes: the kernels differ) whose
/// slopes are sums of sinusoids.
fn procedural(path: &Path) -> Vec<u16> {
    let (w, h) = (37u32, 23u32);
    let img = ImageBuffer::from_fn(w, h, |x, y| {
        let (fx, fy) = (f64::from(x) / f64::from(w), f64::from(y) / f64::from(h));
        let tau = std::f64::consts::TAU;
        let sx = 0.5 * (tau * 3.0 * fx).sin() + 0.2 * (tau * 7.0 * fy).cos();
        let sy = 0.3 * (tau * 5.0 * fy + 0.3).sin() - 0.25 * (tau * 2.0 * fx).cos();
        let l = (1.0 + sx * sx + sy * sy).sqrt();
        let c = |v: f64| ((v * 0.5 + 0.5) * 65535.0).round() as u16;
        Rgb([c(-sx / l), c(-sy / l), c(1.0 / l)])
    });
    img.save(path).unwrap();
    img.into_raw()
}

#[test]
fn a_procedural_map_bakes_to_the_library_chains_with_each_kernel_and_storage() {
    let dir = tmp("procedural");
    let input = dir.join("sines.png");
    let raw = procedural(&input);
    let map = NormalMap::new(
        Texels::Unorm16(&raw),
        37,
        23,
        NormalFormat::new(3, Convention::OpenGl),
    )
    .unwrap();
    for (kernel, name) in [(Kernel::GpuBox, "box"), (Kernel::Area, "area")] {
        let mut o = Options::new(&input, dir.join(name));
        o.kernel = kernel;
        o.anisotropic = true;
        o.store = filtered_ndf_bake::encode::Store::Alpha;
        o.moments = filtered_ndf_bake::encode::Precision::F32;
        o.roughness = Roughness::Constant(0.2);
        o.roughness_perceptual = false;
        o.threads = Some(2);
        o.progress = false;
        run(&o).unwrap();
        let settings = Settings {
            kernel,
            base: BaseRoughness::Constant(0.2),
        };
        let e = expected(&map, &settings);
        let out = dir.join(name);
        check_moments(&out, &e, true);
        let rough = read_ktx2(&out.join("roughness.ktx2"), 97, 37, 23);
        for (k, got) in rough.iter().enumerate() {
            let lv = e.layout.level(k);
            let want: Vec<u16> = e.aniso[lv.rows(0..lv.height)]
                .iter()
                .flat_map(|&a| {
                    let l = lobe(a);
                    // A = R diag(alpha_x^2, alpha_y^2) R^T, from its definition.
                    let (s, c) = l.angle.sin_cos();
                    let (x2, y2) = (l.alpha_x.powi(2), l.alpha_y.powi(2));
                    [
                        c * c * x2 + s * s * y2,
                        c * s * (x2 - y2),
                        s * s * x2 + c * c * y2,
                        1.0,
                    ]
                    .map(|v| fit_f16(v as f32))
                })
                .collect();
            assert!(*got == le16(&want), "{name}: roughness.ktx2 level {k}");
        }
        assert!(
            !out.join("anisotropy.ktx2").exists(),
            "alpha storage keeps A in one file"
        );
    }
    // Isotropic, perceptual, f16: the default files.
    let mut o = Options::new(&input, dir.join("iso"));
    o.progress = false;
    run(&o).unwrap();
    let settings = Settings {
        kernel: Kernel::Area,
        base: BaseRoughness::Constant(0.09),
    };
    let e = expected(&map, &settings);
    check_moments(&dir.join("iso"), &e, false);
    let rough = read_ktx2(&dir.join("iso/roughness.ktx2"), 9, 37, 23);
    for (k, got) in rough.iter().enumerate() {
        let lv = e.layout.level(k);
        let want: Vec<u8> = e.iso[lv.rows(0..lv.height)]
            .iter()
            .map(|&a| u8_of(fit::perceptual(a.into())))
            .collect();
        assert!(*got == want, "iso: roughness.ktx2 level {k}");
    }
}

fn fit_f16(v: f32) -> u16 {
    filtered_ndf::bake::f16::f16_saturating(v)
}

/// Runs a bake expected to fail; returns its message.
fn fails(o: &Options) -> String {
    run(o).expect_err("a bad input").to_string()
}

/// The entries of a directory and their contents.
fn snapshot(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                out.push((p.clone(), std::fs::read(&p).unwrap()));
            }
        }
    }
    out.sort();
    out
}

fn rgb8(path: &Path, w: u32, h: u32, bad: Option<((u32, u32), [u8; 3])>) {
    let img = ImageBuffer::from_fn(w, h, |x, y| match bad {
        Some((at, v)) if at == (x, y) => Rgb(v),
        _ => Rgb([128u8, 128, 255]),
    });
    img.save(path).unwrap();
}

#[test]
fn bad_inputs_name_the_file_and_texel_and_write_nothing() {
    let dir = tmp("bad");
    let good = dir.join("good.png");
    rgb8(&good, 8, 8, None);
    // A previous bake in `kept`, and a directory that must stay absent.
    let kept = dir.join("kept");
    let mut o = Options::new(&good, &kept);
    o.progress = false;
    run(&o).unwrap();
    let before = snapshot(&kept);
    let absent = dir.join("absent");
    let check = |input: &Path, opts: &dyn Fn(&mut Options), expect: &[&str]| {
        for out in [&kept, &absent] {
            let mut o = Options::new(input, out);
            o.progress = false;
            opts(&mut o);
            let msg = fails(&o);
            for e in expect {
                assert!(msg.contains(e), "`{msg}` should say `{e}`");
            }
        }
        assert!(!absent.exists(), "{}: nothing written", input.display());
        assert!(
            snapshot(&kept) == before,
            "{}: the previous bake is untouched",
            input.display()
        );
        let stray: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with('.'))
            .collect();
        assert!(stray.is_empty(), "temporary directories left: {stray:?}");
    };
    let none = |_: &mut Options| {};

    let text = dir.join("notes.png");
    std::fs::write(&text, "not an image").unwrap();
    check(&text, &none, &["notes.png", "not a valid image"]);
    let text = dir.join("notes.txt");
    std::fs::write(&text, "not an image").unwrap();
    check(&text, &none, &["notes.txt", "not an image"]);

    // A PNG whose header says zero width: refused by the decoder.
    let zero = dir.join("zero.png");
    let mut png = vec![0x89, b'P', b'N', b'G', 0x0D, 0x0A, 0x1A, 0x0A];
    let ihdr = [
        b'I', b'H', b'D', b'R', 0, 0, 0, 0, 0, 0, 0, 4, 8, 2, 0, 0, 0,
    ];
    png.extend_from_slice(&13u32.to_be_bytes());
    png.extend_from_slice(&ihdr);
    png.extend_from_slice(&crc32(&ihdr).to_be_bytes());
    std::fs::write(&zero, &png).unwrap();
    check(&zero, &none, &["zero.png", "not a valid image"]);

    let grey = dir.join("grey.png");
    ImageBuffer::from_pixel(4, 4, Luma([7u8]))
        .save(&grey)
        .unwrap();
    check(&grey, &none, &["grey.png", "1 channel", "--height"]);

    let not_unit = dir.join("not_unit.png");
    rgb8(&not_unit, 8, 8, Some(((3, 5), [255, 255, 255])));
    check(
        &not_unit,
        &none,
        &["not_unit.png", "texel (3, 5)", "not a unit normal"],
    );

    let below = dir.join("below.png");
    rgb8(&below, 8, 8, Some(((6, 1), [128, 128, 0])));
    check(
        &below,
        &none,
        &["below.png", "texel (6, 1)", "below the surface"],
    );

    let nan = dir.join("nan.exr");
    let mut f = Rgb32FImage::from_pixel(4, 4, Rgb([0.0, 0.0, 1.0]));
    f.put_pixel(2, 3, Rgb([0.0, f32::NAN, 1.0]));
    image::DynamicImage::ImageRgb32F(f).save(&nan).unwrap();
    check(&nan, &none, &["nan.exr", "texel (2, 3)", "NaN"]);

    let inf = dir.join("inf.exr");
    let mut f = Rgb32FImage::from_pixel(4, 4, Rgb([0.0, 0.0, 1.0]));
    f.put_pixel(1, 0, Rgb([f32::INFINITY, 0.0, 1.0]));
    image::DynamicImage::ImageRgb32F(f).save(&inf).unwrap();
    check(&inf, &none, &["inf.exr", "texel (1, 0)", "inf"]);

    // A roughness texture of another size, and one outside [0, 1].
    let small = dir.join("small_rough.png");
    ImageBuffer::from_pixel(4, 4, Luma([100u8]))
        .save(&small)
        .unwrap();
    let s = small.clone();
    check(
        &good,
        &move |o: &mut Options| o.roughness = Roughness::Texture(s.clone()),
        &["small_rough.png", "4x4", "8x8"],
    );
    let over = dir.join("over.exr");
    let mut f = Rgb32FImage::from_pixel(8, 8, Rgb([0.5, 0.5, 0.5]));
    f.put_pixel(4, 2, Rgb([0.5, 1.5, 0.5]));
    image::DynamicImage::ImageRgb32F(f).save(&over).unwrap();
    let s = over.clone();
    check(
        &good,
        &move |o: &mut Options| o.roughness = Roughness::Texture(s.clone()),
        &["over.exr", "texel (4, 2)", "1.5"],
    );

    // A directory that is not a previous bake is refused before anything is read.
    let foreign = dir.join("foreign");
    std::fs::create_dir_all(&foreign).unwrap();
    std::fs::write(foreign.join("keep.txt"), "mine").unwrap();
    let mut o = Options::new(&good, &foreign);
    o.progress = false;
    assert!(fails(&o).contains("not a previous bake"));
    assert_eq!(
        std::fs::read_to_string(foreign.join("keep.txt")).unwrap(),
        "mine"
    );
}

#[test]
fn the_command_line_parses_and_refuses_what_it_does_not_know() {
    let args = |s: &str| s.split_whitespace().map(String::from).collect::<Vec<_>>();
    let o = Options::parse(args(
        "n.png --out d --height --height-scale 0.5 --edges clamp --roughness r.png --roughness-channel b --roughness-is alpha --convention dx --anisotropic --kernel box --store alpha --moments f32 --ndf beckmann --threads 2 --quiet",
    ))
    .unwrap()
    .unwrap();
    assert!(o.height && o.anisotropic && !o.progress && !o.roughness_perceptual);
    assert_eq!(o.height_scale, 0.5);
    assert_eq!(o.roughness, Roughness::Texture("r.png".into()));
    assert_eq!(o.roughness_channel, Some(2));
    assert_eq!(o.convention, Convention::DirectX);
    assert_eq!(o.kernel, Kernel::GpuBox);
    assert_eq!(o.threads, Some(2));
    assert!(Options::parse(args("--help")).unwrap().is_none());
    for (bad, why) in [
        ("n.png", "--out"),
        ("--out d", "no input"),
        ("n.png --out d --kernel gauss", "box or area"),
        ("n.png --out d --threads 0", "positive"),
        ("n.png --out d --frobnicate", "unknown option"),
        ("n.png m.png --out d", "one map"),
        ("n.png --out d --height-scale nan", "finite"),
    ] {
        let e = Options::parse(args(bad)).unwrap_err().to_string();
        assert!(e.contains(why), "{bad}: {e}");
    }
}

/// CRC-32 (ISO-HDLC, the PNG chunk checksum), bit by bit.
fn crc32(data: &[u8]) -> u32 {
    let mut c = 0xFFFF_FFFFu32;
    for &b in data {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 != 0 {
                (c >> 1) ^ 0xEDB8_8320
            } else {
                c >> 1
            };
        }
    }
    !c
}
