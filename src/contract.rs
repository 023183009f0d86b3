//! The crate's robustness contract, in one place: what every public evaluation function does
//! with bad input, and how accurate the kernels are at the edges of their domains.
//!
//! Documentation only; nothing here is code. Both sections are tested: the bad-input
//! statements by `tests/contract.rs` (each row names its test; each test runs in both
//! precisions as `contract_f32::<name>` and `contract_f64::<name>`), the error map by
//! `tests/extremes_ndf.rs` and `tests/extremes_filter.rs`, which print the tables below with
//! `cargo test --release --test extremes_ndf -- --nocapture` (and `extremes_filter`).
//!
//! # Bad input
//!
//! The general rule (every function): an evaluation never panics and never returns NaN for
//! finite input; checked constructors return a [`RoughnessError`](crate::RoughnessError)
//! instead of building an invalid value; `*_clamped` constructors never fail. The table says
//! what each function does outside its domain. "Non-unit" means a finite, non-zero vector of
//! any length; "back-facing" a direction with `z < 0` in the tangent frame.
//!
//! | functions | NaN | infinities | zero vector | non-unit vector | back-facing | roughness `<= 0` | non-symmetric / indefinite matrix | test |
//! |---|---|---|---|---|---|---|---|---|
//! | `Isotropic::new`, `AxisAligned::new`, `RoughnessMatrix::new`, `Ggx::{isotropic, axis_aligned, matrix}`, `Beckmann::{..}` | `Err(NotFinite)` | `Err(NotFinite)` | - | - | - | `Err(NotPositive)` (also `-0`); outside `[ALPHA_MIN, ALPHA_MAX]`: `Err(OutOfRange)` | `det <= 0`: `Err(NotPositiveDefinite)` | `roughness_constructors` |
//! | `RoughnessMatrix::from_mat2`, `new_with_det_clamp`, `with_det_clamp` | `Err(NotFinite)`; a NaN `tau` in `with_det_clamp` means no clamp | as NaN | - | - | - | as above; negative `tau`: `Err(NotPositive)` (`with_det_clamp`: no clamp) | `from_mat2`: asymmetry above 8 ulps `Err(NotSymmetric)`; with `tau > 0`, a determinant `>= -8 eps a11 a22` is accepted (rounding), below it `Err(NotPositiveDefinite)` | `roughness_constructors` |
//! | `*::new_clamped`, `roughness::clamp_alpha` | `ALPHA_MIN` | `+inf`: `ALPHA_MAX`, `-inf`: `ALPHA_MIN` | - | - | - | `ALPHA_MIN` | - | `roughness_constructors` |
//! | `Roughness::inv_quadratic`, `quadratic` (all forms) | NaN | `+inf` | `0` | any length (a quadratic form) | - | - | overflow against the null direction of a clamped singular matrix: `+inf` (fixed here, it returned `0`) | `roughness_forms` |
//! | `Ndf::p22` (GGX, Beckmann, all forms, `TemporalLobe`) | GGX: NaN; Beckmann: `0` | `0` | the peak `1 / (pi sqrt(det A))` | any slope | - | - | - | `ndf_p22` |
//! | `Ndf::d` | `0` | `0` | `0` | homogeneous: `D(k m) = D(m) / k^4` | `0` (`m_z <= 0`, the `chi+`) | - | - | `ndf_d` |
//! | `Ndf::lambda` | GGX: `+inf`; Beckmann: `0` | the limit direction: `w_z = +/-inf` gives `0`, an infinite `w_xy` `+inf` | `0` | homogeneous of degree 0, huge and tiny vectors rescaled | uses `abs(w_z)`; `w_z = 0`: `+inf` | - | - | `ndf_lambda_g` |
//! | `Ndf::g1`, `g2` | through `lambda`: GGX `0`, Beckmann `1` | as `lambda` | `0` | as `lambda` | `w.m <= 0`: `0`; grazing `w`: `0` | - | - | `ndf_lambda_g` |
//! | `NdfSampling::sample_normal` | `u` NaN counts as `0` | `u` clamped to `[0, 1 - eps/2]` | - | - | - | - | - | `sampling` |
//! | `NdfSampling::sample_visible_normal` | `wo`: `None`; `u` as above | `wo`: `None` | `None` | scale-invariant | `wo_z <= 0`: `None` | - | - | `sampling` |
//! | `normal_pdf`, `visible_normal_pdf`, `reflection_pdf`, `reflection_pdf_from_normal` | `0` | `0` | `0` (also `wi = -wo`) | `wo`, `wi` scale-invariant; `m` must be unit | `wo_z <= 0`, `wo.m <= 0` or `m_z <= 0`: `0` | - | - | `sampling` |
//! | `sampling::reflect`, `sample_beckmann::visible_slope_quantile` | quantile: NaN `u` as `0`, NaN angles as normal incidence | `u` clamped; infinite angles: normal incidence | - | angle pair normalised | negative angles: normal incidence | - | - | `sampling` |
//! | `Footprint::from_projected_derivatives_in_slope`, `from_normal_differences`, `from_world_normal_differences` | `Footprint::ZERO` | `Footprint::ZERO` | - | - | `h_z` clamped to `1e-6` (huge, finite); opposite normals: denominator clamped to `1e-6` | - | - | `footprints_and_covariances` |
//! | `Footprint::{covariance, max_extent, bounding_rect}`, `BoundingRect::covariance`, `Covariance::{trace, det, +, *}` | plain arithmetic: NaN propagates (the filters sanitise) | propagate | - | - | - | - | - | `footprints_and_covariances` |
//! | `Covariance::sanitized`, `eigenvalues`, `clamp_eigenvalues`, `LeanMoments::covariance` | `sanitized`: `ZERO`; `clamp_eigenvalues` with NaN bound or entry: `ZERO` | `sanitized`: `KERNEL_MAX I`; `clamp_eigenvalues`: `ZERO` | - | - | - | - | indefinite: projected to PSD (negative variances to `0`, `abs(s12) <= sqrt(s11 s22)`); eigenvalues clamped to `>= 0` | `footprints_and_covariances` |
//! | `filter::{gaussian, gaussian_with_tau, lean, projected}`, `temporal::widen`, `ClampRules::filter_gaussian` | kernel sanitised: a valid SPD matrix, finite positive densities; NaN `tau`: no clamp | as NaN (widest kernel) | zero kernel: the lobe unchanged | - | - | - | indefinite kernel: projected to PSD first | `filters` |
//! | `ClampRules::{footprint, rect, kernel, tau}` | footprint: `ZERO`; rect: half extent `0` (then the floor); NaN `lambda`/`kappa`: `0` | footprint rescaled to `lambda` (unchanged under `NONE`); rect: `lambda` | - | - | - | negative half extents by magnitude; negative `lambda`/`kappa`: `0` | - | `clamp_rules` |
//! | `ggx_rect::p22_rect` | centre: `0`; half extents: `0` | clamped to `1e60` normalised (finite result) | zero half extents: `Ndf::p22` bit for bit | - | - | negative half extents by magnitude | - | `rect_and_proxy` |
//! | `ggx_rect::d_rect`, `d_rect_printed` | `0` | `0` | `0`; zero footprint: `Ndf::d` bit for bit | `0 < h_z < 1e-70`: unfiltered `D`; overflow saturates at `F::MAX` | `h_z <= 0`: `0` | - | - | `rect_and_proxy` |
//! | `ggx_proxy::{effective_alpha, effective_alpha_simple, proxy, proxy_simple}` | half extent as `0` | half extent `F::MAX`; `proxy` clamps into range | - | - | - | negative half extent by magnitude; `alpha <= 0` only through `proxy` (clamped) | - | `rect_and_proxy` |
//! | `isotropic::filtered_alpha`, `KernelConvention::{apply, apply_kernel, kernel}`, all `presets` | `alpha`: `0`; normal differences / kernel: the clamp `kappa` (maximal kernel); result never NaN | `alpha = +inf`: `ALPHA_MAX` (then saturated); infinite differences: maximal kernel | zero differences: `max(bias, 0)` | differences of any length | - | `alpha <= 0`: `0` | indefinite covariance: negative eigenvalues count as `0` | `isotropic_filters` |
//! | `Bandwidth::kernel`, `Norm::eval`, `normal_difference_covariance`, `Domain::{from_alpha, to_alpha}` | NaN (consumed by `apply_kernel` as the maximal kernel) | NaN / `+inf`; `ProjectedAlpha2`: `alpha >= 1` is `+inf`, `+inf` maps back to `1` | - | - | - | - | - | `isotropic_filters` |
//! | `jacobian::*` (all maps, determinants, `sanitize`, `spherical_*`) | treated as the pole `h = n` | treated as the pole | treated as the pole | normalised | below `HZ_MIN`: clamped to the horizon at constant azimuth | - | - | `jacobians_and_slope_maps` |
//! | `slope::*` | propagates through the arithmetic | `sphere_from_slope`: the horizon direction | `sphere_from_projected(0)`: the pole | `sphere_from_projected`: outside the disk to the horizon | `slope_from_sphere`: `h_z` clamped to `MIN_POSITIVE` (finite) | - | - | `jacobians_and_slope_maps` |
//! | `geometry::{half_vector, half_vector_jacobian, half_vector_jacobian_far_field, half_vector_jacobian_deferred, footprint, footprint_projected, tangent_plane_differentials}` | degenerate: `+z` / zero matrix / `Footprint::ZERO` / `None` | as NaN | eye or light on the point, `i + o = 0`: `+z` / zero matrix | normalised | half vector clamped to `H.n >= HZ_MIN abs(H)`; ray parallel to the plane: `None` | - | - | `geometry` |
//! | `implicit::{hit_rates, hit_distance_rate, hit_normal_rate, project, d_normalized}`, `LevelSetSample::*` | zero rates (`HitRates::ZERO`, `0`, zero vectors) | as NaN | zero gradient: zero rates; `project(0, w) = w` | any length (homogeneous) | ray tangent to the surface: zero rates | - | - | `implicit_quadric_temporal` |
//! | `LocalQuadric::new`, `RigidMotion::*`, `temporal::{TemporalRoughness::*, box_shutter_dt, TemporalLobe}` | `LocalQuadric::new`: `None`; rates, `dt`, fractions, cosines: `TemporalRoughness::ZERO` / `0` | as NaN; `alpha_t` capped at `ALPHA_MAX` | zero normal: `None`; zero rate: `ZERO` | normalised | - | `dt <= 0`: `ZERO`; `roughness_matrix` clamps both roughnesses | - | `implicit_quadric_temporal` |
//!
//! # Extremes: measured error map
//!
//! ERROR_MAP_PLACEHOLDER
