//! The bake's inputs: decoding against hand-computed texels, every error path naming its
//! texel and value, and the `f16` encoder against the exact decoder over every `f16`.

use filtered_ndf::bake::f16::{F16_MAX, f16_from_f32, f16_to_f32};
use filtered_ndf::bake::{
    BakeError, Band, BaseRoughness, ChainLayout, Convention, Edges, HeightFormat, HeightMap,
    Kernel, NormalFormat, NormalMap, RoughnessMap, Settings, SlopeMap, SlopeSource, TexelStats,
    Texels, bake_rows,
};
use glam::DVec2;

fn band(o: &mut [[f32; 5]]) -> Band<'_> {
    Band {
        moments: Some(o),
        ..Band::default()
    }
}

fn gl(ch: usize) -> NormalFormat {
    NormalFormat::new(ch, Convention::OpenGl)
}

/// 8-bit texels decode as `2 v / 255 - 1`; DirectX negates green; two channels rebuild `z`.
#[test]
fn normal_maps_decode_as_documented() {
    // (128, 200, 230): n = (1/255, 145/255, 205/255) before normalising.
    let t = [128u8, 200, 230];
    let (nx, ny, nz) = (1.0 / 255.0, 145.0 / 255.0, 205.0 / 255.0);
    let map = NormalMap::new(Texels::Unorm8(&t), 1, 1, gl(3).with_tolerance(0.5)).unwrap();
    let (s, n) = map.texel(0, 0);
    let tol = 1e-15;
    assert!(
        (s.x + nx / nz).abs() < tol && (s.y + ny / nz).abs() < tol,
        "{s}"
    );
    let len = (nx * nx + ny * ny + nz * nz).sqrt();
    assert!((n.z - nz / len).abs() < tol);
    let dx = NormalMap::new(
        Texels::Unorm8(&t),
        1,
        1,
        NormalFormat::new(3, Convention::DirectX).with_tolerance(0.5),
    )
    .unwrap();
    assert!((dx.texel(0, 0).0.y - ny / nz).abs() < tol);
    // Two channels, 16-bit: z = sqrt(1 - x^2 - y^2).
    let t16 = [40000u16, 20000];
    let (x, y) = (2.0 * 40000.0 / 65535.0 - 1.0, 2.0 * 20000.0 / 65535.0 - 1.0);
    let z = (1.0f64 - x * x - y * y).sqrt();
    let bc5 = NormalMap::new(Texels::Unorm16(&t16), 1, 1, gl(2)).unwrap();
    let (s, _) = bc5.texel(0, 0);
    assert!((s.x + x / z).abs() < tol && (s.y + y / z).abs() < tol);
}

/// Every refusal names what is wrong: the texel (column, row from the top left) and value.
#[test]
fn bad_inputs_name_the_texel_and_value() {
    let ok = [0.0f32, 0.0, 1.0];
    assert_eq!(
        NormalMap::new(Texels::F32(&[]), 0, 1, gl(3)).unwrap_err(),
        BakeError::ZeroSize
    );
    assert_eq!(
        NormalMap::new(Texels::F32(&ok), 1, 1, gl(5)).unwrap_err(),
        BakeError::Channels(5)
    );
    assert_eq!(
        NormalMap::new(Texels::F32(&ok), 2, 1, gl(3)).unwrap_err(),
        BakeError::Length {
            expected: 6,
            got: 3
        }
    );
    // 2 x 2 map, texel (1, 1) bad in each way.
    let mut t = [0.0f32, 0.0, 1.0].repeat(4);
    t[10] = f32::NAN;
    match NormalMap::new(Texels::F32(&t), 2, 2, gl(3)).unwrap_err() {
        BakeError::NotFinite { x: 1, y: 1, value } => assert!(value.is_nan()),
        e => panic!("{e:?}"),
    }
    t[10] = f32::INFINITY;
    assert!(matches!(
        NormalMap::new(Texels::F32(&t), 2, 2, gl(3)).unwrap_err(),
        BakeError::NotFinite { x: 1, y: 1, value } if value == f32::INFINITY
    ));
    t[10] = 0.0;
    t[11] = 1.5;
    assert_eq!(
        NormalMap::new(Texels::F32(&t), 2, 2, gl(3)).unwrap_err(),
        BakeError::NotUnit {
            x: 1,
            y: 1,
            length: 1.5
        }
    );
    t[11] = -1.0;
    assert_eq!(
        NormalMap::new(Texels::F32(&t), 2, 2, gl(3)).unwrap_err(),
        BakeError::BelowSurface {
            x: 1,
            y: 1,
            z: -1.0
        }
    );
    t[9] = 1.0;
    t[11] = 1e-4;
    let e = NormalMap::new(Texels::F32(&t), 2, 2, gl(3)).unwrap_err();
    assert!(
        matches!(e, BakeError::TooSteep { x: 1, y: 1, slope } if (slope - 1e4).abs() < 1.0),
        "{e:?}"
    );
    // Two channels outside the unit disc.
    let t2 = [255u8, 255, 128, 128];
    let e = NormalMap::new(Texels::Unorm8(&t2), 2, 1, gl(2)).unwrap_err();
    assert!(matches!(e, BakeError::NotUnit { x: 0, y: 0, .. }), "{e:?}");
    // Negative tolerance.
    assert!(matches!(
        NormalMap::new(Texels::F32(&ok), 1, 1, gl(3).with_tolerance(-1.0)).unwrap_err(),
        BakeError::Parameter("tolerance", _)
    ));
    // Height maps: parameters and steepness.
    let h = [0.0f32, 0.0, 0.0, 1e6];
    let f = |d: f64, s: f64| HeightFormat {
        channels: 1,
        texel_spacing: d,
        height_scale: s,
        edges: Edges::Clamp,
    };
    assert!(matches!(
        HeightMap::new(Texels::F32(&h), 2, 2, f(0.0, 1.0)).unwrap_err(),
        BakeError::Parameter("texel_spacing", _)
    ));
    assert!(matches!(
        HeightMap::new(Texels::F32(&h), 2, 2, f(1.0, f64::NAN)).unwrap_err(),
        BakeError::Parameter("height_scale", _)
    ));
    let e = HeightMap::new(Texels::F32(&h), 2, 2, f(1.0, 1.0)).unwrap_err();
    assert!(matches!(e, BakeError::TooSteep { x: 1, y: 0, .. }), "{e:?}");
    // Slopes.
    let s = [DVec2::ZERO, DVec2::new(0.0, f64::NAN)];
    assert!(matches!(
        SlopeMap::new(&s, 2, 1).unwrap_err(),
        BakeError::NotFinite { x: 1, y: 0, .. }
    ));
    // Roughness texture out of range.
    let r = [0.5f32, 1.5];
    assert_eq!(
        RoughnessMap::new(Texels::F32(&r), 2, 1, 1, 0, true).unwrap_err(),
        BakeError::OutOfRange {
            x: 1,
            y: 0,
            value: 1.5
        }
    );
    // Bake: too short an output, too short a scratch, rows outside the level, a bad alpha.
    let slopes = vec![DVec2::ZERO; 16];
    let map = SlopeMap::new(&slopes, 4, 4).unwrap();
    let layout = ChainLayout::new(4, 4).unwrap();
    let good = Settings {
        kernel: Kernel::Area,
        base: BaseRoughness::Constant(0.1),
    };
    let mut scratch = vec![TexelStats::default(); layout.scratch_len()];
    let mut out = vec![[0f32; 5]; 3];
    assert_eq!(
        bake_rows(&map, &good, &layout, 0, 0..1, &mut scratch, band(&mut out)).unwrap_err(),
        BakeError::Output {
            expected: 4,
            got: 3
        }
    );
    let mut out = vec![[0f32; 5]; 16];
    assert!(bake_rows(&map, &good, &layout, 0, 0..5, &mut scratch, band(&mut out)).is_err());
    assert!(
        bake_rows(
            &map,
            &good,
            &layout,
            0,
            0..4,
            &mut scratch[..3],
            band(&mut out)
        )
        .is_err()
    );
    let bad = Settings {
        base: BaseRoughness::Constant(f64::NAN),
        ..good
    };
    assert!(matches!(
        bake_rows(&map, &bad, &layout, 0, 0..4, &mut scratch, band(&mut out)).unwrap_err(),
        BakeError::Parameter("alpha", _)
    ));
    // Nothing was written by the refusals.
    assert!(out.iter().all(|t| *t == [0.0; 5]));
}

/// Every finite `f16` survives encode(decode(h)) bit for bit; every midpoint between two
/// consecutive `f16` (exact in `f32`) rounds to the even one, and the `f32` values one ulp
/// either side round to the nearer: with the encoder monotone (checked on the same sweep) that
/// is round-to-nearest-even for every `f32`. Overflow to infinity starts at 65520.
#[test]
fn f16_encoder_rounds_to_nearest_even_over_every_f16() {
    let mut prev = f32::NEG_INFINITY;
    for h in 0u16..=0x7bff {
        for sign in [0u16, 0x8000] {
            let v = f16_to_f32(h | sign);
            assert_eq!(f16_from_f32(v), h | sign, "{h:#06x}");
        }
        let lo = f16_to_f32(h);
        assert!(lo > prev || h == 0);
        prev = lo;
        if h == 0x7bff {
            break;
        }
        let hi = f16_to_f32(h + 1);
        let mid = 0.5 * (lo + hi); // exact: f16 has 11 significant bits, f32 24
        assert_eq!(mid as f64, 0.5 * (lo as f64 + hi as f64));
        let even = if h % 2 == 0 { h } else { h + 1 };
        assert_eq!(f16_from_f32(mid), even, "tie at {mid}");
        assert_eq!(f16_from_f32(-mid), even | 0x8000);
        assert_eq!(
            f16_from_f32(f32::from_bits(mid.to_bits() - 1)),
            h,
            "below {mid}"
        );
        assert_eq!(
            f16_from_f32(f32::from_bits(mid.to_bits() + 1)),
            h + 1,
            "above {mid}"
        );
    }
    assert_eq!(f16_from_f32(65519.996), 0x7bff);
    assert_eq!(f16_from_f32(65520.0), 0x7c00);
    assert_eq!(f16_to_f32(0x7bff), F16_MAX);
    assert_eq!(f16_from_f32(f32::INFINITY), 0x7c00);
    assert!(f16_to_f32(f16_from_f32(f32::NAN)).is_nan());
    // Below half the smallest subnormal: zero, keeping the sign.
    assert_eq!(f16_from_f32(2f32.powi(-26)), 0);
    assert_eq!(f16_from_f32(-2f32.powi(-26)), 0x8000);
}
