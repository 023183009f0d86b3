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
//! | `RoughnessMatrix::from_mat2`, `new_with_det_clamp`, `with_det_clamp` | `Err(NotFinite)`; a NaN `det_clamp` in `with_det_clamp` means no clamp | as NaN | - | - | - | as above; negative `det_clamp`: `Err(NotPositive)` (`with_det_clamp`: no clamp) | `from_mat2`: asymmetry above 8 ulps `Err(NotSymmetric)`; with `tau > 0`, a determinant `>= -8 eps a11 a22` is accepted (rounding), below it `Err(NotPositiveDefinite)` | `roughness_constructors` |
//! | `*::new_clamped`, `roughness::clamp_alpha` | `ALPHA_MIN` | `+inf`: `ALPHA_MAX`, `-inf`: `ALPHA_MIN` | - | - | - | `ALPHA_MIN` | - | `roughness_constructors` |
//! | `Roughness::inv_quadratic`, `quadratic` (all forms) | NaN | `+inf` | `0` | any length (a quadratic form) | - | - | a clamped singular matrix evaluates its positive-definite `A_c` | `roughness_forms` |
//! | `Ndf::p22` (GGX, Beckmann, all forms, `TemporalLobe`) | `0` (the NaN policy of `Ndf`: a NaN argument contributes nothing) | `0` | the peak `1 / (pi sqrt(det A))` | any slope | - | - | - | `ndf_p22` |
//! | `Ndf::d` | `0` | `0` | `0` | homogeneous: `D(k m) = D(m) / k^4` | `0` (`m_z <= 0`, the `chi+`) | - | - | `ndf_d` |
//! | `Ndf::lambda` | `+inf` (NaN policy: fully masked) | the limit direction: `w_z = +/-inf` gives `0`, an infinite `w_xy` `+inf` | `0` | homogeneous of degree 0, huge and tiny vectors rescaled | uses `abs(w_z)`; `w_z = 0`: `+inf` | - | - | `ndf_lambda_g` |
//! | `Ndf::g1`, `g2` | `0` (NaN policy; a NaN in `m` too) | as `lambda` | `0` | as `lambda` | `w.m <= 0`: `0`; grazing `w`: `0` | - | - | `ndf_lambda_g` |
//! | `NdfSampling::sample_normal` | `u` NaN counts as `0` | `u` clamped to `[0, 1 - eps/2]` | - | - | - | - | - | `sampling` |
//! | `NdfSampling::sample_visible_normal` | `wo`: `None`; `u` as above | `wo`: `None` | `None` | scale-invariant | `wo_z <= 0`: `None` | - | - | `sampling` |
//! | `normal_pdf`, `visible_normal_pdf`, `reflection_pdf`, `reflection_pdf_from_normal` | `0` | `0` | `0` (also `wi = -wo`) | `wo`, `wi` scale-invariant; `m` must be unit | `wo_z <= 0`, `wo.m <= 0` or `m_z <= 0`: `0` | - | - | `sampling` |
//! | `sampling::reflect`, `sample_beckmann::visible_slope_quantile` | quantile: NaN `u` as `0`, NaN angles as normal incidence | `u` clamped; infinite angles: normal incidence | - | angle pair normalised | negative angles: normal incidence | - | - | `sampling` |
//! | `Footprint::from_projected_derivatives_in_slope`, `from_half_vector_derivatives`, `from_normal_differences`, `from_world_normal_differences`, `from_ray_differentials`, `geometry::{footprint, footprint_projected}` | a NaN derivative entry counts as `0` (the footprint policy below); a NaN or non-finite `h`: `Footprint::ZERO` | infinite derivatives (or a product beyond `F::MAX`): infinite entries, saturated by the clamp rules | `h`: `Footprint::ZERO` | only `h`'s direction is used; the radial part of `dh` is dropped | `h_z` clamped to the horizon `1e-6` at constant azimuth (huge, finite); opposite normals: denominator clamped to `1e-6` | - | - | `footprints_and_covariances` |
//! | `Footprint::{covariance, bounding_rect}` (`Covariance::from_footprint`, `BoundingRect::from_footprint`) | a NaN footprint entry counts as `0` | infinite entries propagate (the filters saturate them) | - | - | - | - | - | `footprints_and_covariances` |
//! | `Footprint::max_extent`, `BoundingRect::covariance`, `Covariance::{trace, det, +, *}` | plain arithmetic: NaN propagates (the filters sanitise) | propagate | - | - | - | - | - | `footprints_and_covariances` |
//! | `Covariance::sanitized`, `eigenvalues`, `clamp_eigenvalues`, `LeanMoments::covariance` | `sanitized`: a NaN entry counts as `0` (beside an infinite entry: `KERNEL_MAX I`); `clamp_eigenvalues` with NaN bound or entry: `ZERO` | `sanitized`: `KERNEL_MAX I`; `clamp_eigenvalues`: `ZERO` | - | - | - | - | `sanitized`: projected to PSD (negative variances to `0`, `abs(s12) <= sqrt(s11 s22)`); `clamp_eigenvalues`: any symmetric input's eigenvalues clamped to `[0, max]` with its eigenvectors kept (negative semi-definite: `ZERO`; infinite `max` acts as `F::MAX`); `eigenvalues` accurate for either sign | `footprints_and_covariances` |
//! | `filter::{gaussian, gaussian_with_det_clamp, lean, projected, projected_with_det_clamp}`, `temporal::widen`, `ClampRules::{filter_gaussian, filter_projected}` | kernel sanitised: a valid SPD matrix, finite positive densities; NaN `det_clamp`: no clamp | as NaN (widest kernel) | zero kernel: the lobe unchanged | - | - | - | indefinite kernel: projected to PSD first | `filters` |
//! | `ClampRules::{footprint, rect, kernel, det_clamp_for}` | footprint: a NaN entry counts as `0`; rect: half extent `0` (then the floor); NaN `lambda`/`kappa`: `0` | footprint: infinite entries keep their sign, rescaled to extent `lambda`, the widest it allows (unchanged under `NONE`); rect: `lambda` | - | - | - | negative half extents by magnitude; negative `lambda`/`kappa`: `0` | - | `clamp_rules` |
//! | `rect::p22_rect` | centre: `0`; half extents: `0` | clamped to `1e60` normalised (finite result) | zero half extents: `Ndf::p22` bit for bit | - | - | negative half extents by magnitude | - | `rect_and_proxy` |
//! | `rect::d_rect`, `d_rect_printed` | `0` | `0` | `0`; zero footprint: `Ndf::d` bit for bit | `0 < h_z < 1e-70`: unfiltered `D`; overflow saturates at `F::MAX` | `h_z <= 0`: `0` | - | - | `rect_and_proxy` |
//! | `rect::lambda_rect`, `RectFilteredGgx::lambda` | `w`: `+inf` (contributes nothing); half extent: `0` | `w_z = +-inf`: `0`; infinite `w_xy`: `+inf` | `0` | homogeneous of degree 0 | uses `abs(w_z)`; `w_z = 0`: `+inf` | negative half extents by magnitude | - | `tests/ggx_rect_lambda.rs` |
//! | `sampling::rect::{sample_normal_rect, sample_visible_normal_rect}` and their pdfs, `RectFilteredGgx::{sample_normal, sample_visible_normal, normal_pdf, visible_normal_pdf}` | `u`: as `0`; `wo`: `None`, pdf `0` | `u` clamped; `wo`: `None` | `wo`: `None` | `wo` scale-invariant | `wo_z <= 0`: `None`, pdf `0` | - | - | `tests/ggx_rect_sampling.rs` |
//! | `GaussianFilteredGgx::{new, p22, d, lambda}` and its samplers | kernel sanitised (a NaN entry counts as `0`); `p22`, `d`: `0`; `lambda`: `+inf` | kernel: `KERNEL_MAX I`; slopes: `0` | zero kernel: GGX itself | `d` homogeneous as GGX's | `d`: `0` | - | indefinite kernel: its sanitised (PSD) part | `tests/gaussian_ggx.rs`, `tests/fuzz_replay_gaussian_ggx.rs` |
//! | the front door `Filterable::filtered` with every `Method` (`Gaussian`, `ExactGaussian`, `Projected`, `Rect`, `Proxy`), `KernelConvention::filter` | footprint: a NaN entry counts as `0` (the lobe's evaluations finite); `filter`: a valid `Isotropic` | footprint: the clamp rules' widest kernel | zero footprint: the unfiltered lobe | - | - | `filter`: roughness `<= 0` gives `ALPHA_MIN` | - | `front_door_never_returns_nan_for_bad_footprints` |
//! | `proxy::{effective_alpha, effective_alpha_simple, proxy, proxy_simple}` | half extent as `0` | half extent taken as `F::MAX`: `effective_alpha` returns `+inf`, `proxy` clamps it to `ALPHA_MAX` | - | - | - | negative half extent by magnitude; `alpha <= 0` only through `proxy` (clamped) | - | `rect_and_proxy` |
//! | `deferred::filtered_alpha`, `KernelConvention::{apply, apply_widening, widening, filter}`, all `presets` | `alpha`: `0`; a NaN entry of a normal difference or of the kernel counts as `0` (the policy below); result never NaN | `alpha = +inf`: `ALPHA_MAX` (then saturated); infinite differences: maximal kernel | zero differences: `max(bias, 0)` | differences of any length | - | `alpha <= 0`: `0` | indefinite covariance: negative eigenvalues count as `0` | `isotropic_filters` |
//! | `Bandwidth::alpha2`, `Norm::eval`, `normal_difference_covariance`, `Domain::{from_alpha, to_alpha}` | `alpha2`, `eval`: a NaN entry counts as `0`; `normal_difference_covariance`: NaN propagates | NaN / `+inf` (consumed by `apply_widening` as the maximal kernel); `ProjectedAlpha2`: `alpha >= 1` is `+inf`, `+inf` maps back to `1` | - | - | - | - | - | `isotropic_filters` |
//! | `jacobian::*` (all maps, determinants, `sanitize`, `spherical_*`) | treated as the pole `h = n` | treated as the pole | treated as the pole | normalised | below `HZ_MIN`: clamped to the horizon at constant azimuth | - | - | `jacobians_and_slope_maps` |
//! | `slope::*` | `slope_from_sphere`: finite for any input (a NaN `h_z` is the horizon clamp, a NaN slope component saturates at `-F::MAX`); `sphere_from_slope`: NaN | `sphere_from_slope`: the horizon direction | `sphere_from_projected(0)`: the pole | `sphere_from_projected`: outside the disk to the horizon | `slope_from_sphere`: `h_z` clamped to `MIN_POSITIVE` (finite) | - | - | `jacobians_and_slope_maps` |
//! | `geometry::{half_vector, half_vector_jacobian, half_vector_jacobian_far_field, half_vector_jacobian_deferred, footprint, footprint_projected, tangent_plane_differentials}` | degenerate: `+z` / zero matrix / `Footprint::ZERO` / `None` | as NaN | eye or light on the point, `i + o = 0`: `+z` / zero matrix | normalised | half vector clamped to `H.n >= HZ_MIN abs(H)`; ray parallel to the plane: `None` | - | - | `geometry` |
//! | `implicit::{hit_rates, hit_distance_rate, hit_normal_rate, project, d_normalized}`, `LevelSetSample::*` | zero rates (`HitRates::ZERO`, `0`, zero vectors) | as NaN | zero gradient: zero rates; `project(0, w) = w` | any length (homogeneous) | ray tangent to the surface: zero rates | - | - | `implicit_quadric_temporal` |
//! | `LocalQuadric::new`, `RigidMotion::*`, `temporal::{TemporalRoughness::*, box_shutter_dt, TemporalLobe}` | `LocalQuadric::new`: `None`; rates, `dt`, fractions, cosines: `TemporalRoughness::ZERO` / `0` | as NaN; `alpha_t` capped at `ALPHA_MAX` | zero normal: `None`; zero rate: `ZERO` | normalised | - | `dt <= 0`: `ZERO`; `roughness_matrix` clamps both roughnesses | - | `implicit_quadric_temporal` |
//!
//! # Footprints and normal differences: one NaN policy
//!
//! Both routes of filtering read derivatives: the forward route a footprint (the slope change
//! per pixel, [`Footprint`](crate::f32::Footprint)), the deferred route the normal
//! differences of a G-buffer ([`KernelConvention`](crate::f32::KernelConvention)). One policy
//! holds for both, entry by entry:
//!
//! - **A NaN entry carries no information and counts as `0`**: it widens nothing; the other
//!   entries filter as they would with a `0` there. Why not "no filtering at all": one bad
//!   derivative (a NaN from a degenerate triangle or a division in the renderer) would throw
//!   away the others and bring back the aliasing the filter exists to remove. Why not "the
//!   widest kernel": a NaN says nothing about the size of the footprint, and the widest kernel
//!   is the strongest bias the clamp rules allow; a pixel would blur for a defect, not for its
//!   geometry.
//! - **A `+-inf` entry saturates** to the largest kernel the clamp rules allow: an infinite
//!   derivative does say "larger than anything representable", so the footprint takes the
//!   widest extent the rules permit (`ClampRules::footprint`: extent `lambda` along the
//!   infinite entries; `ClampRules::rect`: half extent `lambda`; `Covariance::sanitized`:
//!   `KERNEL_MAX I`; a convention's `clamp`).
//!
//! Where it is applied, once per route: the forward route substitutes where a kernel is built
//! from a footprint (`Footprint::nan_to_zero`, used by `Covariance::from_footprint`,
//! `BoundingRect::from_footprint` and `ClampRules::footprint`; the footprint constructors drop
//! NaN derivatives before mapping them and keep infinite results infinite); the deferred route
//! in `Norm::eval` (a NaN entry of `dn_u` or `dn_v` is `0` before any measure is taken, and a
//! NaN widening, which then only an infinite difference can give, is the clamp). A kernel given
//! directly (`Covariance::sanitized`, `Bandwidth::alpha2`) follows the same rule per entry. The
//! WGSL twins (`footprint`, `kernel::{covariance, rect, clamp}`, `filter::deferred`) decide NaN
//! on its bits (`math::is_nan`), so a driver's no-NaN assumption does not change the answer.
//! Tested by `tests/nan_policy.rs` (both precisions, every method and every preset, bit for bit
//! against the input with the NaN entries zeroed by hand) and on the GPU by
//! `gpu/src/checks/nan_policy.rs`.
//!
//! # Extremes: measured error map
//!
//! Worst relative error `|got - ref| / max(|ref|, F::MIN_POSITIVE)` per region (a sample point
//! counts in every region it belongs to), as `f32 / f64`, measured on the grid of the extremes
//! sweep: roughness `alpha` 1e-7, 1e-4, 1, 10; half vectors at the pole, in the lobe, at 89.99
//! degrees and exactly at 90 degrees; footprints 0, 1e-12 and 1e3 (isotropic and 1000:1);
//! matrices of condition number 1e6, near-singular (`det ~ 2 eps a11 a22`) and exactly singular
//! with the TK19 clamp `tau`. Inputs are rounded to the precision first and the reference is
//! evaluated at the rounded input (double-double closed forms, `f64` adaptive quadrature, or
//! `testing::gaussian_reference`), so the numbers are the kernels' own errors. `Lambda` is
//! measured as `1 + Lambda` (what `G1` uses). A `0` means bit-exact (including the documented
//! `0` and `+inf` values at and beyond the horizon); an empty cell, no sample.
//!
//! Tolerances (stated with their reasons in the tests): densities `32 eps` (GGX), `(32 + 8 q) eps`
//! (Beckmann, the conditioning of `exp(-q)`); `1 + Lambda` `32 eps`; pdfs the density's plus `32
//! eps` (plus `4 eps / wo.m` where `wo.m` cancels); Jacobians `16 eps` (determinants) and `64 eps`
//! of the largest entry; `filter::gaussian` `64 (1 + kappa) eps` with `kappa` the condition number
//! of the filtered matrix (its entries are rounded to `F` before the determinant);
//! `filter::projected` additionally `/ (1 - lambda_max)` and `+ kappa(P + 2 Sigma)` (allowing
//! for a projected-space sum formed in `F`; it is formed in `f64`); the rectangle integral
//! `64 eps` (`+ 1e-7` in `f64`, the module's documented worst case); proxy `16 eps`; isotropic
//! filters `8 eps`, presets `64 eps`; normalisation (f64 only) ten times the quadrature goal.
//!
//! Known limits visible in the map: `filter::gaussian` and `filter::projected` in `f32` lose
//! `~kappa eps` for elongated kernels at footprint 1e3 (`3e-4` and `1.5e-4`): the filtered
//! matrix's entries are rounded to `F` (`projected` computes in `f64` and rounds them once)
//! and its determinant cancels; the footprint clamp `lambda = 1` of
//! [`ClampRules`](crate::f32::ClampRules) keeps shading inputs away from this region. The
//! Beckmann densities carry the conditioning of `exp` (`3.4e-6` in `f32` at a few lobe widths).
//!
//! ### NDFs: worst relative error, f32 / f64
//!
//! | region | GGX p22 | GGX D | GGX 1+Lambda | Beckmann p22 | Beckmann D | Beckmann 1+Lambda |
//! |---|---|---|---|---|---|---|
//! | alpha 1e-7 | 2.2e-7 / 9.7e-16 | 2.2e-7 / 4.7e-16 | 6.6e-9 / 0 | 1.8e-6 / 5.8e-15 | 1.8e-6 / 2.6e-14 | 1.0e-10 / 0 |
//! | isotropic | 2.2e-7 / 6.0e-16 | 2.2e-7 / 6.6e-16 | 7.6e-8 / 2.8e-16 | 1.8e-6 / 4.6e-15 | 1.8e-6 / 3.3e-15 | 3.3e-8 / 2.3e-16 |
//! | pole | 1.0e-7 / 0 | 1.0e-7 / 0 | 0 / 0 | 1.0e-7 / 1.5e-15 | 1.3e-7 / 1.7e-15 | 0 / 0 |
//! | lobe | 2.4e-7 / 6.1e-16 | 2.8e-7 / 9.1e-16 | 1.1e-7 / 5.8e-16 | 3.4e-6 / 8.2e-14 | 3.2e-6 / 8.5e-14 | 7.2e-8 / 4.0e-16 |
//! | 89.99 deg | 1.9e-7 / 8.7e-16 | 2.2e-7 / 7.8e-16 | 1.3e-7 / 3.1e-16 | 0 / 0 | 0 / 0 | 5.8e-8 / 4.5e-16 |
//! | 90 deg | 1.7e-80 / 9.7e-16 | 0 / 0 | 0 / 0 | 0 / 0 | 0 / 0 | 0 / 0 |
//! | axis-aligned | 1.9e-7 / 7.2e-16 | 1.9e-7 / 5.3e-16 | 1.1e-7 / 1.5e-16 | 1.8e-6 / 7.2e-15 | 3.2e-6 / 6.4e-15 | 6.0e-8 / 2.7e-16 |
//! | matrix | 1.3e-7 / 6.9e-16 | 1.8e-7 / 9.1e-16 | 1.3e-7 / 2.8e-16 | 1.5e-6 / 1.9e-14 | 2.8e-6 / 2.6e-14 | 4.3e-8 / 4.3e-16 |
//! | cond 1e6 | 1.8e-7 / 9.7e-16 | 2.2e-7 / 6.6e-16 | 1.0e-7 / 5.8e-16 | 1.2e-7 / 2.4e-15 | 1.4e-7 / 2.5e-15 | 7.2e-8 / 4.0e-16 |
//! | alpha 1e-4 | 2.4e-7 / 8.7e-16 | 2.8e-7 / 7.8e-16 | 8.3e-8 / 1.7e-16 | 2.4e-6 / 7.0e-14 | 2.4e-6 / 8.5e-14 | 5.3e-8 / 2.1e-16 |
//! | near-singular | 1.8e-7 / 8.7e-16 | 2.8e-7 / 7.3e-16 | 1.1e-7 / 1.8e-16 | 4.2e-8 / 6.2e-16 | 7.0e-8 / 4.4e-16 | 4.4e-8 / 4.5e-16 |
//! | singular + tau | 2.4e-7 / 6.3e-16 | 1.9e-7 / 7.8e-16 | 1.0e-7 / 3.1e-16 | 3.4e-6 / 8.2e-14 | 2.4e-6 / 8.5e-14 | 5.8e-8 / 3.2e-16 |
//! | alpha 1 | 1.9e-7 / 9.0e-16 | 2.2e-7 / 7.3e-16 | 1.1e-7 / 3.1e-16 | 3.4e-6 / 8.2e-14 | 3.2e-6 / 7.8e-14 | 7.2e-8 / 4.3e-16 |
//! | alpha 10 | 1.9e-7 / 8.3e-16 | 2.1e-7 / 9.1e-16 | 1.3e-7 / 5.8e-16 | 2.2e-6 / 5.1e-14 | 2.7e-6 / 6.3e-14 | 6.0e-8 / 4.5e-16 |
//!
//! ### Sampling pdfs: worst relative error, f32 / f64
//!
//! | region | GGX normal pdf | GGX visible pdf | GGX reflection pdf | Beckmann normal pdf | Beckmann visible pdf | Beckmann reflection pdf |
//! |---|---|---|---|---|---|---|
//! | alpha 1e-7 | 2.3e-7 / 5.0e-16 | 2.4e-7 / 5.9e-16 | 2.4e-7 / 5.3e-16 | 1.8e-6 / 2.6e-14 | 1.8e-6 / 2.6e-14 | 1.8e-6 / 2.6e-14 |
//! | isotropic | 2.2e-7 / 6.6e-16 | 2.6e-7 / 8.0e-16 | 2.4e-7 / 6.6e-16 | 1.8e-6 / 3.3e-15 | 1.8e-6 / 3.5e-15 | 1.8e-6 / 3.4e-15 |
//! | pole | 1.0e-7 / 0 | 1.8e-7 / 3.8e-16 | 1.6e-7 / 3.3e-16 | 1.3e-7 / 1.7e-15 | 1.3e-7 / 1.7e-15 | 1.3e-7 / 1.8e-15 |
//! | wo pole |  | 2.8e-7 / 8.6e-16 | 2.8e-7 / 9.1e-16 |  | 3.1e-6 / 8.5e-14 | 3.2e-6 / 8.5e-14 |
//! | lobe | 2.8e-7 / 8.6e-16 | 3.1e-7 / 8.6e-16 | 2.9e-7 / 9.3e-16 | 3.1e-6 / 8.5e-14 | 3.2e-6 / 8.5e-14 | 3.2e-6 / 8.5e-14 |
//! | 89.99 deg | 2.4e-7 / 7.1e-16 | 2.6e-7 / 7.1e-16 | 3.0e-7 / 8.8e-16 | 0 / 0 | 0 / 0 | 0 / 0 |
//! | 90 deg | 0 / 0 | 0 / 0 | 0 / 0 | 0 / 0 | 0 / 0 | 0 / 0 |
//! | wo 89.99 deg |  | 3.1e-7 / 8.4e-16 | 3.0e-7 / 9.3e-16 |  | 3.2e-6 / 8.5e-14 | 3.1e-6 / 8.5e-14 |
//! | wo 90 deg |  | 0 / 0 | 0 / 0 |  | 0 / 0 | 0 / 0 |
//! | axis-aligned | 2.4e-7 / 5.3e-16 | 2.4e-7 / 5.3e-16 | 2.6e-7 / 5.3e-16 | 3.1e-6 / 6.4e-15 | 3.2e-6 / 6.5e-15 | 3.2e-6 / 6.4e-15 |
//! | matrix | 2.4e-7 / 8.6e-16 | 2.9e-7 / 8.6e-16 | 2.0e-7 / 9.3e-16 | 2.8e-6 / 2.6e-14 | 2.9e-6 / 2.6e-14 | 2.9e-6 / 2.6e-14 |
//! | cond 1e6 | 2.4e-7 / 6.4e-16 | 3.1e-7 / 7.1e-16 | 3.0e-7 / 8.1e-16 | 1.5e-7 / 2.5e-15 | 1.7e-7 / 2.6e-15 | 1.7e-7 / 2.6e-15 |
//! | alpha 1e-4 | 2.8e-7 / 7.1e-16 | 3.1e-7 / 8.0e-16 | 3.0e-7 / 8.8e-16 | 2.4e-6 / 8.5e-14 | 2.4e-6 / 8.5e-14 | 2.4e-6 / 8.5e-14 |
//! | near-singular | 2.8e-7 / 8.1e-16 | 3.1e-7 / 8.2e-16 | 2.8e-7 / 8.0e-16 | 7.0e-8 / 4.4e-16 | 7.9e-8 / 4.7e-16 | 7.0e-8 / 6.8e-16 |
//! | singular + tau | 2.1e-7 / 7.1e-16 | 2.3e-7 / 7.2e-16 | 2.0e-7 / 8.8e-16 | 2.4e-6 / 8.5e-14 | 2.4e-6 / 8.5e-14 | 2.4e-6 / 8.5e-14 |
//! | alpha 1 | 1.9e-7 / 8.1e-16 | 2.9e-7 / 8.2e-16 | 2.4e-7 / 8.1e-16 | 3.1e-6 / 7.8e-14 | 3.2e-6 / 7.8e-14 | 3.2e-6 / 7.8e-14 |
//! | alpha 10 | 2.4e-7 / 8.6e-16 | 3.1e-7 / 8.6e-16 | 2.9e-7 / 9.3e-16 | 2.7e-6 / 6.3e-14 | 2.7e-6 / 6.3e-14 | 2.7e-6 / 6.3e-14 |
//! | normalisation (quadrature) |  | - / 3.3e-16 |  |  | - / 4.4e-16 |  |
//!
//! ### Jacobians: worst relative error, f32 / f64
//!
//! | region | det J(o->perp) | det J(perp->par) | det J(o->par) | J(o->perp) | J(perp->par) | J(par->perp) | J(o->par) |
//! |---|---|---|---|---|---|---|---|
//! | pole | 0 / 0 | 0 / 0 | 0 / 0 | 0 / 0 | 0 / 0 | 0 / 0 | 0 / 0 |
//! | lobe | 1.0e-7 / 1.5e-16 | 5.0e-7 / 7.4e-16 | 3.4e-7 / 6.8e-16 | 5.5e-8 / 1.4e-16 | 1.1e-7 / 7.4e-16 | 3.5e-7 / 3.6e-16 | 2.3e-7 / 4.4e-16 |
//! | 89.99 deg | 6.1e-8 / 1.6e-16 | 2.3e-7 / 1.2e-15 | 2.2e-7 / 6.5e-16 | 4.6e-8 / 2.7e-20 | 1.3e-7 / 4.9e-16 | 2.0e-7 / 4.0e-16 | 7.2e-8 / 4.5e-16 |
//! | 90 deg | 0 / 0 | 3.7e-9 / 0 | 4.5e-8 / 0 | 7.9e-9 / 0 | 6.5e-8 / 3.3e-16 | 3.7e-8 / 2.7e-16 | 4.4e-8 / 1.5e-22 |
//!
//! ### filter::gaussian and filter::projected (through p22): worst relative error, f32 / f64
//!
//! | region | gaussian | projected |
//! |---|---|---|
//! | alpha 1e-7 | 1.6e-7 / 1.3e-11 | 1.7e-7 / 3.9e-11 |
//! | isotropic | 1.2e-7 / 1.9e-12 | 1.7e-7 / 1.5e-13 |
//! | footprint 0 | 2.0e-7 / 8.1e-14 | 1.9e-7 / 8.4e-13 |
//! | kernel isotropic | 5.7e-7 / 4.2e-12 | 1.5e-4 / 3.9e-11 |
//! | kernel 1000:1 | 3.0e-4 / 2.6e-11 | 2.4e-6 / 5.1e-12 |
//! | footprint 1e-12 | 2.0e-7 / 1.3e-11 | 1.9e-7 / 3.9e-11 |
//! | footprint 1e3 | 3.0e-4 / 2.6e-11 | 1.5e-4 / 1.0e-11 |
//! | cond 1e6 | 3.0e-4 / 1.3e-11 | 1.5e-4 / 3.9e-11 |
//! | alpha 1e-4 | 3.0e-4 / 2.6e-11 | 1.6e-7 / 8.4e-13 |
//! | singular + tau | 1.2e-7 / 2.6e-11 | 1.5e-7 / 1.5e-13 |
//! | alpha 1 | 9.2e-5 / 8.1e-14 | 9.9e-8 / 1.0e-11 |
//! | alpha 10 | 1.9e-4 / 5.1e-13 | 1.5e-4 / 5.1e-12 |
//! | quadrature (gaussian_reference) | 4.2e-8 / 0 |  |
//!
//! ### ggx_rect: worst relative error, f32 / f64
//!
//! | region | d_rect | p22_rect |
//! |---|---|---|
//! | alpha 1e-7 | 9.6e-8 / 4.7e-12 | 2.0e-7 / 4.7e-12 |
//! | isotropic | 1.3e-7 / 4.7e-12 | 2.0e-7 / 4.7e-12 |
//! | footprint 0 | 3.0e-7 / 4.1e-16 | 2.0e-7 / 5.5e-16 |
//! | square | 3.0e-7 / 4.7e-12 | 2.0e-7 / 4.7e-12 |
//! | pole | 7.4e-8 / 6.8e-16 | 7.4e-8 / 6.8e-16 |
//! | lobe | 3.0e-7 / 4.0e-15 | 1.5e-7 / 9.3e-15 |
//! | 89.99 deg | 1.8e-7 / 4.7e-12 | 2.0e-7 / 4.7e-12 |
//! | 90 deg | 0 / 0 |  |
//! | 1000:1 | 3.0e-7 / 2.6e-12 | 2.0e-7 / 2.6e-12 |
//! | footprint 1e-12 | 5.6e-8 / 7.6e-16 | 4.4e-8 / 3.7e-16 |
//! | footprint 1e3 | 5.3e-8 / 4.7e-12 | 5.2e-8 / 4.7e-12 |
//! | axis 1:3 | 3.0e-7 / 4.0e-15 | 1.2e-7 / 9.3e-15 |
//! | alpha 1e-4 | 1.8e-7 / 4.7e-12 | 1.8e-7 / 4.7e-12 |
//! | alpha 1 | 5.3e-8 / 4.7e-12 | 9.4e-8 / 4.7e-12 |
//! | alpha 10 | 3.0e-7 / 4.7e-12 | 1.5e-7 / 4.7e-12 |
//!
//! ### ggx_proxy and isotropic filters: worst relative error, f32 / f64
//!
//! | region | effective_alpha | proxy | effective_alpha_simple | filtered_alpha | presets |
//! |---|---|---|---|---|---|
//! | alpha 1e-7 | 1.5e-8 / 2.6e-16 | 1.5e-8 / 2.6e-16 | 5.0e-11 / 0 | 8.9e-9 / 0 | 7.1e-8 / 0 |
//! | footprint 0 | 2.6e-16 / 2.6e-16 | 2.6e-16 / 2.6e-16 | 0 / 0 | 0 / 0 | 7.1e-8 / 0 |
//! | footprint 1e-12 | 6.7e-11 / 1.4e-16 | 6.7e-11 / 1.4e-16 | 5.0e-11 / 0 | 5.0e-11 / 0 | 7.1e-8 / 0 |
//! | footprint 1e3 | 9.9e-8 / 2.0e-16 | 9.9e-8 / 2.0e-16 | 1.2e-8 / 0 | 3.4e-8 / 0 | 7.1e-8 / 0 |
//! | alpha 1e-4 | 1.5e-8 / 2.0e-16 | 1.5e-8 / 2.0e-16 | 5.0e-15 / 0 | 3.4e-8 / 0 | 7.1e-8 / 0 |
//! | alpha 1 | 9.9e-8 / 2.0e-16 | 9.9e-8 / 2.0e-16 | 1.2e-8 / 0 | 0 / 0 | 1.7e-8 / 0 |
//! | alpha 10 | 3.7e-8 / 0 | 3.7e-8 / 0 | 1.1e-8 / 0 | 0 / 0 | 1.7e-8 / 0 |
//! | kernel isotropic |  |  |  | 3.4e-8 / 0 |  |
//! | kernel 1000:1 |  |  |  | 3.4e-8 / 0 |  |
//! | TK19 max (eq. 1) |  |  |  |  | 3.4e-8 / 0 |
//! | TK19 trace (eq. 4) |  |  |  |  | 3.4e-8 / 0 |
//! | TK19 average (eq. 5) |  |  |  |  | 3.4e-8 / 0 |
//! | TK21 listing 5 |  |  |  |  | 3.4e-8 / 0 |
//! | Filament |  |  |  |  | 5.4e-8 / 0 |
//! | Unity HDRP |  |  |  |  | 2.0e-8 / 0 |
//! | Unity HDRP projected |  |  |  |  | 7.1e-8 / 0 |
//! | Godot 4 |  |  |  |  | 2.4e-8 / 0 |
//! | O3DE |  |  |  |  | 3.4e-8 / 0 |
//! | Unreal |  |  |  |  | 7.1e-8 / 0 |
//! | Babylon.js (Vlachos 2015) |  |  |  |  | 7.1e-8 / 0 |
//! | three.js |  |  |  |  | 1.1e-8 / 0 |
