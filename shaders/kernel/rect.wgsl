#define_import_path filtered_ndf::kernel::rect

#import filtered_ndf::footprint as pixel
#import filtered_ndf::kernel::covariance as cov

// The axis-aligned slope-domain rectangle of KHPL16 section 5.3 (the `footprint` of the
// GDC 2016 `GGXRectIntegral`), mirroring `BoundingRect` of `src/.../kernel/rect.rs`.

/// A rectangle centred on the half vector's slope, by its half-extents (slope units, `>= 0`).
/// It bounds the one-pixel parallelogram: `half_extent = (|dh_u| + |dh_v|) / 2`.
struct BoundingRect {
    /// Half-extents along the tangent `x` and bitangent `y`.
    half_extent: vec2<f32>,
}

/// The axis-aligned bounding rectangle of a footprint's one-pixel parallelogram (KHPL16
/// section 5.3; GDC 2016 `fp = (abs(dFdx(hpp)) + abs(dFdy(hpp))) * 0.5`): half-extent
/// `(|dh_u| + |dh_v|) / 2` per axis. The Rust `BoundingRect::from_footprint`; a NaN footprint
/// entry counts as 0 (`pixel::nan_to_zero`).
fn from_footprint(fp_in: pixel::Footprint) -> BoundingRect {
    let fp = pixel::nan_to_zero(fp_in);
    return BoundingRect((abs(fp.dh_u) + abs(fp.dh_v)) * 0.5);
}

/// The Gaussian-equivalent diagonal covariance `diag((2 sigma h_x)^2, (2 sigma h_y)^2)`
/// (`sigma` in pixels; GDC 2016 Beckmann listing `rghns_sq += fp * fp * 2`, TK19 Listing 3).
fn covariance(r: BoundingRect, sigma: f32) -> cov::Covariance {
    let w = r.half_extent * (2.0 * sigma);
    let v = w * w;
    return cov::Covariance(v.x, 0.0, v.y, v.x * v.y);
}
