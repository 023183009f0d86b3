#define_import_path filtered_ndf::footprint

#import filtered_ndf::math
#import filtered_ndf::footprint::jacobian

// Pixel footprints in the slope domain (KHPL16 sections 4.2, 4.3; TK19 section 2.2),
// mirroring `Footprint` of `src/.../footprint/mod.rs`: the slope change of the half vector
// across one pixel step in `x` (`dh_u`) and in `y` (`dh_v`). A Gaussian pixel filter of
// standard deviation `sigma` pixels carried into the slope domain has covariance
// `Sigma = sigma^2 (dh_u dh_u^T + dh_v dh_v^T)`; the kernel stage builds it
// (`kernel::covariance::from_footprint`) and the bounding rectangle
// (`kernel::rect::from_footprint`).

// NaN policy (the Rust `contract`, as in `src/.../footprint/mod.rs`): a NaN derivative entry
// carries no information and counts as 0 (`math::nan_to_zero`, decided on the bits, so it
// holds whatever a driver assumes about floats); an infinite entry saturates: the clamp
// rules turn it into the widest kernel they allow (where the driver keeps infinities).

/// The standard deviation of the pixel filter of KHPL16 and TK19, in pixels.
const SIGMA_PIXEL: f32 = 0.5;

/// A slope-domain pixel footprint.
struct Footprint {
    /// Slope change per pixel step along the image `x` axis.
    dh_u: vec2<f32>,
    /// Slope change per pixel step along the image `y` axis.
    dh_v: vec2<f32>,
}

/// From slope-domain derivatives, e.g. `dpdx`/`dpdy` of the slope of `h` (KHPL16 section
/// 5.1).
fn from_slope_derivatives(dh_u: vec2<f32>, dh_v: vec2<f32>) -> Footprint {
    return Footprint(dh_u, dh_v);
}

/// From derivatives of the projected half vector `p = h_xy` (TK19 section 3.2, Listing 1:
/// `ddx(halfvectorTS.xy)`), used as slope changes directly, as TK19 does (no Jacobian: the
/// bandwidth shrinks by `h_z` at grazing half vectors relative to the sphere).
fn from_projected_derivatives(dp_u: vec2<f32>, dp_v: vec2<f32>) -> Footprint {
    return Footprint(dp_u, dp_v);
}

/// The slope-domain footprint of disk derivatives at the half vector `h`:
/// `dh = J(perp->par) dp` (TK19 supplement eq. 6, [`jacobian::projected_to_slope`]: `h`
/// normalised, clamped to the horizon `h_z >= 1e-6` at constant azimuth). A zero `h` gives a
/// zero footprint; a NaN derivative entry counts as 0 (module docs).
fn from_projected_derivatives_in_slope(
    h: vec3<f32>,
    dp_u: vec2<f32>,
    dp_v: vec2<f32>,
) -> Footprint {
    let big = max(max(abs(h.x), abs(h.y)), abs(h.z));
    if big <= 0.0 {
        return Footprint(vec2<f32>(0.0), vec2<f32>(0.0));
    }
    let j = jacobian::projected_to_slope(h);
    return Footprint(j * math::nan_to_zero2(dp_u), j * math::nan_to_zero2(dp_v));
}

/// The deferred footprint from normal differences to the neighbouring pixels (TK19 section
/// 4.4, eq. 3) in the tangent frame of the current normal: `2 (dn)_xy / |2 e_z + dn|` per
/// difference (the derivative of the half-way normal on the disk, whose length is `|dn|`
/// for unit normals), the denominator clamped to `>= 1e-6`. A NaN entry of a difference counts
/// as 0 (module docs).
fn from_normal_differences(dn_u_in: vec3<f32>, dn_v_in: vec3<f32>) -> Footprint {
    let dn_u = math::nan_to_zero3(dn_u_in);
    let dn_v = math::nan_to_zero3(dn_v_in);
    let lu = max(length(vec3<f32>(0.0, 0.0, 2.0) + dn_u), 1e-6);
    let lv = max(length(vec3<f32>(0.0, 0.0, 2.0) + dn_v), 1e-6);
    return Footprint(dn_u.xy * (2.0 / lu), dn_v.xy * (2.0 / lv));
}

/// The footprint with each NaN entry replaced by 0 (the Rust `Footprint::nan_to_zero`), as
/// the kernel stage reads a footprint (module docs).
fn nan_to_zero(fp: Footprint) -> Footprint {
    return Footprint(math::nan_to_zero2(fp.dh_u), math::nan_to_zero2(fp.dh_v));
}

/// The largest centre-to-vertex distance of the one-pixel parallelogram,
/// `max(|dh_u + dh_v|, |dh_u - dh_v|) / 2`: the extent clamped by KHPL16 section 5.2.
fn max_extent(fp: Footprint) -> f32 {
    return 0.5 * max(length(fp.dh_u + fp.dh_v), length(fp.dh_u - fp.dh_v));
}
