//! The shading methods compared by the demo, behind one function: [`filtered_d`].
//!
//! Every method answers the same question: the (filtered) microfacet density `D(h)` per
//! steradian at the half vector `h` of one shading point, given its slope-domain pixel
//! footprint. The renderer multiplies it by the same Fresnel, Smith `G2` (base roughness) and
//! light terms for every method, so the images differ only by the NDF filter.
//!
//! Every method calls the crate; nothing here re-implements a kernel.

use filtered_ndf::f32::prelude::{ExactGaussian, Filterable};
use filtered_ndf::f32::{
    AxisAligned, Beckmann, ClampRules, Endpoint, ExtentFloor, Footprint, Ggx, Isotropic, Ndf,
    ShadingFrame, filter, filter::presets, filter::proxy, filter::rect, footprint::geometry,
};
use glam::Vec3;

/// The microfacet distribution a method filters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    Beckmann,
    Ggx,
}

impl Family {
    /// Unfiltered `D(h)` of this family at roughness `alpha`.
    pub fn d(self, alpha: f32, h: Vec3) -> f32 {
        let r = Isotropic::new_clamped(alpha);
        match self {
            Family::Beckmann => Beckmann::new(r).d(h),
            Family::Ggx => Ggx::new(r).d(h),
        }
    }

    /// Unfiltered Smith `G2` of this family at roughness `alpha` (tangent frame).
    pub fn g2(self, alpha: f32, wi: Vec3, wo: Vec3, h: Vec3) -> f32 {
        let r = Isotropic::new_clamped(alpha);
        match self {
            Family::Beckmann => Beckmann::new(r).g2(wi, wo, h),
            Family::Ggx => Ggx::new(r).g2(wi, wo, h),
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Family::Beckmann => "Beckmann",
            Family::Ggx => "GGX",
        }
    }
}

/// The isotropic deferred roughness variants of TK19 (eq. 1, 2/4, 5).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IsoVariant {
    Max,
    Trace,
    Average,
}

/// One way of shading a pixel with a single sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// The NDF at the pixel centre, no filtering.
    Unfiltered(Family),
    /// KHPL16 parallelogram (Gaussian) kernel on Beckmann: `A' = A + 2 Sigma`.
    BeckmannParallelogram,
    /// KHPL16 axis-aligned rectangle, exact box integral of GGX.
    GgxRectExact,
    /// KHPL16 / GDC GGX proxy: an effective isotropic roughness for the rectangle.
    GgxProxy,
    /// TK19 projected-derivative kernel on full-matrix GGX (`A + 2 Sigma`).
    Tk19Projected,
    /// Tokuyoshi-Kaplanyan 2021 projected-space filtering of full-matrix GGX.
    Tk21Projected,
    /// TK19 isotropic deferred roughness from world-space normal differences.
    Tk19Isotropic(IsoVariant),
    /// The exact Gaussian filter of GGX (`ExactGaussian::KHPL16`: the GGX slope density
    /// convolved with the pixel kernel, `GaussianFilteredGgx`), the kernel TK19 approximates.
    ExactGaussianGgx,
    /// An engine convention from `presets::ALL` (index), applied to the G-buffer normal
    /// differences, on GGX.
    Preset(usize),
}

impl Method {
    /// Every method, in display order.
    pub const ALL: [Method; 11] = [
        Method::Unfiltered(Family::Beckmann),
        Method::Unfiltered(Family::Ggx),
        Method::BeckmannParallelogram,
        Method::GgxRectExact,
        Method::GgxProxy,
        Method::Tk19Projected,
        Method::Tk21Projected,
        Method::Tk19Isotropic(IsoVariant::Max),
        Method::Tk19Isotropic(IsoVariant::Trace),
        Method::Tk19Isotropic(IsoVariant::Average),
        Method::ExactGaussianGgx,
    ];

    /// Every engine preset of the crate (`presets::ALL`), as methods.
    pub fn presets() -> Vec<Method> {
        (0..presets::ALL.len()).map(Method::Preset).collect()
    }

    /// The NDF this method filters (its reference is rendered with the same family).
    pub fn family(self) -> Family {
        match self {
            Method::Unfiltered(f) => f,
            Method::BeckmannParallelogram => Family::Beckmann,
            _ => Family::Ggx,
        }
    }

    /// Whether the method filters over the half vector's footprint (the others read the
    /// normal differences, or nothing).
    pub fn uses_footprint(self) -> bool {
        !matches!(
            self,
            Method::Unfiltered(_) | Method::Tk19Isotropic(_) | Method::Preset(_)
        )
    }

    /// Short command-line / file name.
    pub fn slug(self) -> &'static str {
        match self {
            Method::Unfiltered(Family::Beckmann) => "unfiltered-beckmann",
            Method::Unfiltered(Family::Ggx) => "unfiltered-ggx",
            Method::BeckmannParallelogram => "khpl16-beckmann",
            Method::GgxRectExact => "ggx-rect-exact",
            Method::GgxProxy => "ggx-proxy",
            Method::Tk19Projected => "tk19-projected",
            Method::Tk21Projected => "tk21-projected",
            Method::Tk19Isotropic(IsoVariant::Max) => "tk19-iso-max",
            Method::Tk19Isotropic(IsoVariant::Trace) => "tk19-iso-trace",
            Method::Tk19Isotropic(IsoVariant::Average) => "tk19-iso-average",
            Method::ExactGaussianGgx => "exact-gaussian-ggx",
            Method::Preset(i) => PRESET_SLUGS[i.min(PRESET_SLUGS.len() - 1)],
        }
    }

    /// Human-readable label (contact sheet, tables).
    pub fn label(self) -> &'static str {
        match self {
            Method::Unfiltered(Family::Beckmann) => "Unfiltered Beckmann",
            Method::Unfiltered(Family::Ggx) => "Unfiltered GGX",
            Method::BeckmannParallelogram => "KHPL16 Beckmann A+2S",
            Method::GgxRectExact => "GGX rect exact",
            Method::GgxProxy => "GGX proxy",
            Method::Tk19Projected => "TK19 projected",
            Method::Tk21Projected => "TK21 projected",
            Method::Tk19Isotropic(IsoVariant::Max) => "TK19 iso max",
            Method::Tk19Isotropic(IsoVariant::Trace) => "TK19 iso trace",
            Method::Tk19Isotropic(IsoVariant::Average) => "TK19 iso average",
            Method::ExactGaussianGgx => "Exact Gaussian GGX",
            Method::Preset(i) => presets::ALL[i.min(presets::ALL.len() - 1)].0,
        }
    }

    /// Parses a slug (see [`Method::slug`]).
    pub fn parse(s: &str) -> Option<Method> {
        Method::ALL
            .into_iter()
            .chain(Method::presets())
            .find(|m| m.slug() == s)
    }
}

/// File names of the presets, in the order of `presets::ALL`.
const PRESET_SLUGS: [&str; 12] = [
    "preset-tk19-max",
    "preset-tk19-trace",
    "preset-tk19-average",
    "preset-tk21",
    "preset-filament",
    "preset-unity-hdrp",
    "preset-unity-hdrp-projected",
    "preset-godot",
    "preset-o3de",
    "preset-unreal",
    "preset-babylon",
    "preset-threejs",
];

/// Everything a method may use at one shading point. Vectors in the shading point's tangent
/// frame (`z` = shading normal) unless marked world.
#[derive(Clone, Copy, Debug)]
pub struct ShadingPoint {
    /// Unit half vector.
    pub h: Vec3,
    /// Base (unfiltered) isotropic roughness.
    pub alpha: f32,
    /// Slope-domain footprint: slope change of `h` per pixel step in x and y.
    pub footprint: Footprint,
    /// World-space shading-normal difference per pixel step in x and y (deferred methods).
    pub dn_dx: Vec3,
    /// See `dn_dx`.
    pub dn_dy: Vec3,
}

/// The standard deviation of the Gaussian pixel filter in pixels (KHPL16, TK19).
pub const SIGMA_PIXEL: f32 = filtered_ndf::f32::kernel::SIGMA_PIXEL;

/// The (filtered) `D(h)` per steradian of `method` at `sp`.
pub fn filtered_d(method: Method, sp: &ShadingPoint) -> f32 {
    match method {
        Method::Unfiltered(family) => family.d(sp.alpha, sp.h),
        Method::BeckmannParallelogram => beckmann_parallelogram(sp),
        Method::GgxRectExact => ggx_rect_exact(sp),
        Method::GgxProxy => ggx_proxy(sp),
        Method::Tk19Projected => tk19_projected(sp),
        Method::Tk21Projected => tk21_projected(sp),
        Method::Tk19Isotropic(variant) => tk19_isotropic(sp, variant),
        Method::ExactGaussianGgx => Ggx::new(Isotropic::new_clamped(sp.alpha))
            .filtered(sp.footprint, ExactGaussian::KHPL16)
            .d(sp.h),
        Method::Preset(i) => {
            let conv = presets::ALL[i.min(presets::ALL.len() - 1)].1;
            let alpha = conv.apply(sp.alpha, sp.dn_dx, sp.dn_dy);
            Ggx::new(Isotropic::new_clamped(alpha)).d(sp.h)
        }
    }
}

/// KHPL16's clamping for the parallelogram kernels: the maximum extent `lambda = 1`
/// (section 5.2) and the TK19 determinant clamp, no rectangle floor and no `kappa`.
const KHPL16: ClampRules = ClampRules {
    max_extent: 1.0,
    floor: ExtentFloor::None,
    kappa: f32::INFINITY,
    det_clamp: true,
};

/// KHPL16 eq. 13-15: the Gaussian footprint `Sigma = sigma^2 U^T U` convolved with Beckmann
/// is Beckmann with `A' = A + 2 Sigma`, evaluated with the TK19 determinant clamp
/// `tau = det A = alpha^4` (filtering only grows the determinant).
fn beckmann_parallelogram(sp: &ShadingPoint) -> f32 {
    let r = Isotropic::new_clamped(sp.alpha);
    Beckmann::new(KHPL16.filter_gaussian(r, sp.footprint, SIGMA_PIXEL)).d(sp.h)
}

/// The KHPL16 section 5.3 rectangle: the axis-aligned bounding rectangle of the footprint,
/// half-extents clamped to `lambda = 1` (no lower floor: the crate's integral is exact).
fn rect_half_extent(sp: &ShadingPoint) -> glam::Vec2 {
    KHPL16
        .rect(sp.footprint.bounding_rect(), glam::Vec2::splat(sp.alpha))
        .half_extent
}

/// KHPL16 eq. 16 / section 5.3: exact box integral of GGX `P22` over the bounding rectangle,
/// per steradian (`/ h_z^4`).
fn ggx_rect_exact(sp: &ShadingPoint) -> f32 {
    let r = AxisAligned::from(Isotropic::new_clamped(sp.alpha));
    rect::d_rect(r, sp.h, rect_half_extent(sp))
}

/// KHPL16 eq. 19-20: the GGX proxy, the effective roughness whose peak matches the
/// rectangle-filtered peak (per axis), then unfiltered GGX `D(h)` with it.
fn ggx_proxy(sp: &ShadingPoint) -> f32 {
    let r = AxisAligned::from(Isotropic::new_clamped(sp.alpha));
    Ggx::new(proxy::proxy(r, rect_half_extent(sp))).d(sp.h)
}

/// TK19 section 3.2: the kernel built from the derivatives of the projected half vector
/// `h_xy` (narrower at grazing half vectors), `A' = A + 2 Sigma` on full-matrix GGX with the
/// TK19 clamps (`kappa = 0.18`, `tau = det A`).
fn tk19_projected(sp: &ShadingPoint) -> f32 {
    let r = Isotropic::new_clamped(sp.alpha);
    let fp = geometry::footprint_projected(sp.footprint, sp.h);
    Ggx::new(ClampRules::default().filter_gaussian(r, fp, SIGMA_PIXEL)).d(sp.h)
}

/// Tokuyoshi and Kaplanyan 2021: the same projected-derivative kernel added in projected
/// space, `P = A (I - A)^-1`, `A' = P' (I + P')^-1`, then full-matrix GGX `D(h)`.
fn tk21_projected(sp: &ShadingPoint) -> f32 {
    let r = Isotropic::new_clamped(sp.alpha);
    let rules = ClampRules::default();
    let fp = rules.footprint(geometry::footprint_projected(sp.footprint, sp.h));
    Ggx::new(filter::projected(
        r,
        rules.kernel(fp.covariance(SIGMA_PIXEL)),
    ))
    .d(sp.h)
}

/// TK19 eq. 1 / 2,4 / 5: isotropic deferred roughness from `sp.dn_dx`, `sp.dn_dy`
/// (`sigma^2 = 0.25`, `kappa = 0.18`, saturate), then isotropic GGX `D(h)` with it.
fn tk19_isotropic(sp: &ShadingPoint, variant: IsoVariant) -> f32 {
    use filtered_ndf::f32::filter::deferred::Bandwidth;
    let bw = match variant {
        IsoVariant::Max => Bandwidth::Max,
        IsoVariant::Trace => Bandwidth::Trace,
        IsoVariant::Average => Bandwidth::Average,
    };
    let alpha = bw.convention().apply(sp.alpha, sp.dn_dx, sp.dn_dy);
    Ggx::new(Isotropic::new_clamped(alpha)).d(sp.h)
}

/// The offline-renderer route: footprint `(dx_u M, dx_v M)` from the tangent-plane ray
/// differentials `dx_u`, `dx_v` (world, per pixel step) and the half-vector Jacobian `M` at
/// the hit (KHPL16 eq. 4-6), expressed in the tangent frame `input.frame` (slope
/// convention `-h_xy / h_z`). Selected with `--footprint rays`.
pub fn footprint_from_ray_differentials(g: &AnalyticInput) -> Footprint {
    let [t, b, n] = g.frame;
    // The scene provides the shape operator but not the frame's twist about `n`; the twist
    // only rotates `h_xy`, which is small near a highlight, so it is taken as zero here.
    let frame = ShadingFrame::from_derivatives(t, b, n, [g.dn_dt, g.dn_db], [Vec3::ZERO; 2]);
    let m = geometry::half_vector_jacobian(
        g.position,
        Endpoint::Point(g.eye),
        Endpoint::Point(g.light),
        &frame,
    );
    geometry::footprint(m, &frame, g.dx_u, g.dx_v)
}

/// Input of [`footprint_from_ray_differentials`] (all world space; the light is a point).
#[derive(Clone, Copy, Debug)]
pub struct AnalyticInput {
    pub position: Vec3,
    pub eye: Vec3,
    pub light: Vec3,
    /// Tangent, bitangent, normal.
    pub frame: [Vec3; 3],
    /// Normal change along the tangent and the bitangent (shape operator columns).
    pub dn_dt: Vec3,
    pub dn_db: Vec3,
    /// Ray-differential offsets on the tangent plane per pixel step in x and y.
    pub dx_u: Vec3,
    pub dx_v: Vec3,
}
