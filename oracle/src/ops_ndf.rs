// The material NDF ops: densities, Smith terms, the visible-normal sampler and its density,
// and the slope-domain Jacobians (included into `eval::p32` and `eval::p64`; see typed.rs).

/// `D(m)`.
pub fn ndf(v: &Value) -> Result<Value, String> {
    let (d, r, m) = (dist(v)?, roughness_arg(v)?, array::<3>(v, "m")?);
    with_ndf!(d, r, n => out(n.d(v3(m))))
}

/// `P22(slope)`.
pub fn slope_pdf(v: &Value) -> Result<Value, String> {
    let (d, r, s) = (dist(v)?, roughness_arg(v)?, array::<2>(v, "slope")?);
    with_ndf!(d, r, n => out(n.p22(v2(s))))
}

/// Smith `Lambda(w)`.
pub fn lambda(v: &Value) -> Result<Value, String> {
    let (d, r, w) = (dist(v)?, roughness_arg(v)?, array::<3>(v, "w")?);
    with_ndf!(d, r, n => out(n.lambda(v3(w))))
}

/// `G1(w, m)`.
pub fn g1(v: &Value) -> Result<Value, String> {
    let (d, r) = (dist(v)?, roughness_arg(v)?);
    let (w, m) = (array::<3>(v, "w")?, array::<3>(v, "m")?);
    with_ndf!(d, r, n => out(n.g1(v3(w), v3(m))))
}

/// `G2(i, o, m)`, height-correlated.
pub fn g2(v: &Value) -> Result<Value, String> {
    let (d, r) = (dist(v)?, roughness_arg(v)?);
    let (i, o, m) = (
        array::<3>(v, "i")?,
        array::<3>(v, "o")?,
        array::<3>(v, "m")?,
    );
    with_ndf!(d, r, n => out(n.g2(v3(i), v3(o), v3(m))))
}

/// The visible-normal density `D_o(m)` per steradian.
pub fn pdf(v: &Value) -> Result<Value, String> {
    let (d, r) = (dist(v)?, roughness_arg(v)?);
    let (o, m) = (array::<3>(v, "o")?, array::<3>(v, "m")?);
    with_ndf!(d, r, n => out(n.visible_normal_pdf(v3(o), v3(m))))
}

/// The visible micronormal the sampler returns for `u`, or `null` where it returns `None`.
pub fn sample(v: &Value) -> Result<Value, String> {
    let (d, r) = (dist(v)?, roughness_arg(v)?);
    let (o, u) = (array::<3>(v, "o")?, array::<2>(v, "u")?);
    with_ndf!(d, r, n => match n.sample_visible_normal(v3(o), v2(u)) {
        Some(m) => vec_out(&[m.x, m.y, m.z]),
        None => Ok(Value::Null),
    })
}

/// The Jacobians of the slope-domain maps at `h`.
pub fn jacobian(v: &Value) -> Result<Value, String> {
    use p::footprint::jacobian as jac;
    let h = v3(array::<3>(v, "h")?);
    let j = match string(v, "kind")? {
        "sphere_to_slope" => jac::sphere_to_slope(h),
        "sphere_to_projected" => jac::sphere_to_projected(h),
        "projected_to_slope" => jac::projected_to_slope(h),
        kind => return Err(format!("unknown jacobian kind \"{kind}\"; see --list")),
    };
    // glam is column-major: x_axis holds d out / d in_1.
    Ok(json!([
        [out(j.x_axis.x)?, out(j.y_axis.x)?],
        [out(j.x_axis.y)?, out(j.y_axis.y)?]
    ]))
}
