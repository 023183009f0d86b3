#define_import_path filtered_ndf::kernel::clamp

#import filtered_ndf::math
#import filtered_ndf::footprint as pixel
#import filtered_ndf::kernel::covariance
#import filtered_ndf::kernel::rect as bounding
#import filtered_ndf::ndf::roughness::matrix

// The clamping rules of NDF filtering as one configurable set (KHPL16 section 5.2, GDC 2016,
// TK19 eq. 1 and supplement), mirroring `ClampRules` of `src/.../kernel/clamp.rs`. A rule is
// off when its bound is `F32_MAX` (`max_extent`, `kappa`; the Rust `F::INFINITY`),
// `FLOOR_NONE`, or `det_clamp = false`. Constants mirror `ClampRules::DEFAULT`, `KHPL16`,
// `NONE`, `GDC2016` (`*_RULES`: WGSL names may not end in a digit here, see shaders/README.md).
// The rules are data: the filters apply them (`filter::gaussian::filter_gaussian`,
// `filter::projected::filter_projected`).

/// No rectangle floor.
const FLOOR_NONE: u32 = 0u;
/// Half-extents `>= floor` on both axes (KHPL16 section 5.2, `epsilon = 1e-3`).
const FLOOR_CONSTANT: u32 = 1u;
/// Half-extents `>= min(alpha_axis, floor)` per axis (GDC 2016 `min(roughness, 0.1)`).
const FLOOR_ALPHA_CAPPED: u32 = 2u;

/// The clamping rules.
struct ClampRules {
    /// `lambda`: the largest centre-to-vertex extent of the parallelogram and the largest
    /// rectangle half-extent (slope units).
    max_extent: f32,
    /// `FLOOR_NONE`, `FLOOR_CONSTANT` or `FLOOR_ALPHA_CAPPED`.
    floor_kind: u32,
    /// The floor's constant (`epsilon`, or the cap of `FLOOR_ALPHA_CAPPED`).
    floor: f32,
    /// `kappa`: the largest kernel roughness^2 `2 lambda_i(Sigma)` per eigen-direction.
    kappa: f32,
    /// Evaluate filtered matrices with `tau = det(A_unfiltered)`.
    det_clamp: bool,
}

/// The papers' defaults: `lambda = 1`, `epsilon = 1e-3`, `kappa = 0.18`, `tau = det A`.
const DEFAULT_RULES: ClampRules = ClampRules(1.0, FLOOR_CONSTANT, 1e-3, 0.18, true);
/// KHPL16's rules for its exact kernels: `lambda = 1` (section 5.2) and the determinant clamp;
/// no rectangle floor (the exact rectangle integral needs none), no `kappa` (a TK19 addition).
const KHPL16_RULES: ClampRules = ClampRules(1.0, FLOOR_NONE, 0.0, math::F32_MAX, true);
/// No clamping (unbiased; for references and the exact rectangle integral).
const NO_RULES: ClampRules = ClampRules(math::F32_MAX, FLOOR_NONE, 0.0, math::F32_MAX, false);
/// The GDC 2016 listing: `fp = clamp(fp, min(roughness, 0.1), 1)`, no `kappa`, with `tau`.
const GDC2016_RULES: ClampRules = ClampRules(1.0, FLOOR_ALPHA_CAPPED, 0.1, math::F32_MAX, true);

/// The maximum-extent rule on a parallelogram (KHPL16 section 5.2): both vectors scaled by
/// `min(1, lambda / max_extent)`, keeping the shape. The extent is measured on the
/// footprint scaled to unit size (no overflow). A negative `lambda` counts as 0. The NaN
/// policy, as the Rust `ClampRules::footprint`: a NaN entry counts as 0; infinite entries
/// (where the driver keeps them) keep their sign, the finite ones become 0, and the result
/// has extent `lambda`, the widest footprint the rule allows.
fn footprint(rules: ClampRules, fp_in: pixel::Footprint) -> pixel::Footprint {
    let fp = pixel::nan_to_zero(fp_in);
    let l = max(rules.max_extent, 0.0);
    let scale = max(max(abs(fp.dh_u.x), abs(fp.dh_u.y)), max(abs(fp.dh_v.x), abs(fp.dh_v.y)));
    if scale <= 0.0 {
        return fp;
    }
    if scale > math::F32_MAX {
        let iu = select(vec2<f32>(0.0), sign(fp.dh_u), abs(fp.dh_u) > vec2<f32>(math::F32_MAX));
        let iv = select(vec2<f32>(0.0), sign(fp.dh_v), abs(fp.dh_v) > vec2<f32>(math::F32_MAX));
        let e = pixel::max_extent(pixel::Footprint(iu, iv));
        return pixel::Footprint(iu / e * l, iv / e * l);
    }
    let unit = pixel::Footprint(fp.dh_u / scale, fp.dh_v / scale);
    let e = pixel::max_extent(unit);
    if e * scale <= l {
        return fp;
    }
    return pixel::Footprint(unit.dh_u / e * l, unit.dh_v / e * l);
}

/// The rectangle rules: half-extents taken by magnitude, clamped to `[floor, lambda]` per
/// axis (KHPL16 section 5.2; GDC 2016 `clamp(fp, fp_min, fp_max)`), `alpha` the lobe's
/// per-axis roughness for `FLOOR_ALPHA_CAPPED`; if the floor exceeds `lambda` the floor wins.
fn rect(rules: ClampRules, r: bounding::BoundingRect, alpha: vec2<f32>) -> bounding::BoundingRect {
    var f = vec2<f32>(0.0);
    if rules.floor_kind == FLOOR_CONSTANT {
        f = vec2<f32>(rules.floor);
    } else if rules.floor_kind == FLOOR_ALPHA_CAPPED {
        f = min(abs(alpha), vec2<f32>(rules.floor));
    }
    let lambda = max(rules.max_extent, 0.0);
    let h = min(abs(r.half_extent), vec2<f32>(lambda));
    return bounding::BoundingRect(max(h, max(f, vec2<f32>(0.0))));
}

/// The kernel-roughness rule of TK19 eq. 1 in matrix form: `2 Sigma'` has the eigenvalues
/// `min(2 lambda_i, kappa)` and `Sigma`'s eigenvectors, after `covariance::sanitized`. A
/// negative `kappa` counts as 0.
fn kernel(rules: ClampRules, k: covariance::Covariance) -> covariance::Covariance {
    let s = covariance::sanitized(k);
    if rules.kappa >= math::F32_MAX {
        return s;
    }
    return covariance::clamp_eigenvalues(s, 0.5 * max(rules.kappa, 0.0));
}

/// The determinant clamp `tau` for filtering `a` (the Rust `det_clamp_for`): `det A_c` of the
/// unfiltered lobe (`alpha_x^2 alpha_y^2` for an axis-aligned one, TK19 supplement; for a
/// clamped matrix its `max(det A, tau)`) if `det_clamp`, else the material's own clamp
/// ([`matrix::own_det_clamp`]: 0 unless it is a clamped matrix).
fn det_clamp_for(rules: ClampRules, a: matrix::RoughnessMatrix) -> f32 {
    return select(matrix::own_det_clamp(a), matrix::clamped_det(a), rules.det_clamp);
}

/// The clamped pixel kernel of a footprint: [`footprint`] -> `covariance::from_footprint` (`sigma`
/// pixels) -> [`kernel`] (sanitised once).
fn pixel_kernel(rules: ClampRules, fp: pixel::Footprint, sigma: f32) -> covariance::Covariance {
    return kernel(rules, covariance::from_footprint(footprint(rules, fp), sigma));
}
