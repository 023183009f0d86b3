// The filtering ops: the front door (`filtered`), the kernels beneath it (Gaussian, projected,
// rectangle, proxy) and the deferred conventions (TK19 variants, engine presets), included
// into `eval::p32` and `eval::p64` (see typed.rs).

/// TK19 eq. 1, 4, 5: the isotropic deferred roughness.
pub fn isotropic_roughness(v: &Value) -> Result<Value, String> {
    use p::filter::deferred::{Bandwidth, filtered_alpha, normal_difference_covariance};
    use p::kernel::SIGMA_PIXEL;
    let alpha = number(v, "alpha")?;
    let (du, dv) = (array::<3>(v, "dn_u")?, array::<3>(v, "dn_v")?);
    let kappa = opt_number(v, "kappa")?.unwrap_or(0.18);
    if alpha < 0.0 {
        return Err("alpha must be >= 0".into());
    }
    let bw = match v.get("variant").and_then(Value::as_str) {
        Some("max") => Bandwidth::Max,
        Some("trace") => Bandwidth::Trace,
        Some("average") => Bandwidth::Average,
        _ => return Err("variant must be \"max\", \"trace\" or \"average\"".into()),
    };
    let kernel = normal_difference_covariance(v3(du), v3(dv), SIGMA_PIXEL);
    out(filtered_alpha(f(alpha), &kernel, bw, f(kappa)))
}

/// An engine preset by its name in `presets::ALL`.
pub fn preset(v: &Value) -> Result<Value, String> {
    let name = string(v, "name")?;
    let alpha = number(v, "alpha")?;
    let (du, dv) = (array::<3>(v, "dn_u")?, array::<3>(v, "dn_v")?);
    let raw = flag(v, "raw", false)?;
    let all = &p::filter::presets::ALL;
    let Some((_, convention)) = all.iter().find(|(n, _)| *n == name) else {
        let names: Vec<String> = all.iter().map(|(n, _)| format!("\"{n}\"")).collect();
        return Err(format!(
            "unknown preset \"{name}\"; the presets are {}",
            names.join(", ")
        ));
    };
    if raw {
        out(convention.apply(f(alpha), v3(du), v3(dv)))
    } else {
        out(convention.filter(f(alpha), v3(du), v3(dv)).alpha())
    }
}

/// `sigma` (pixels, default 0.5) of the Gaussian pixel filter.
fn sigma_or_half(v: &Value) -> Result<p::F, String> {
    Ok(f(opt_non_negative(v, "sigma")?.unwrap_or(0.5)))
}

/// KHPL16 eq. 13-15: `A + 2 Sigma`, unclamped.
pub fn filter_roughness(v: &Value) -> Result<Value, String> {
    let (r, fp) = (roughness_arg(v)?, footprint_arg(v)?);
    let sigma = sigma_or_half(v)?;
    let fp = footprint(fp)?;
    with_roughness!(r, rr => matrix_of(&p::filter::gaussian(rr, fp.covariance(sigma))))
}

/// TK21: `A + 2 Sigma` in projected space, unclamped.
pub fn projected_roughness(v: &Value) -> Result<Value, String> {
    let (r, fp) = (roughness_arg(v)?, footprint_arg(v)?);
    let sigma = sigma_or_half(v)?;
    let fp = footprint(fp)?;
    with_roughness!(r, rr => matrix_of(&p::filter::projected(rr, fp.covariance(sigma))))
}

/// The checked axis-aligned roughness of a box-filter op.
fn axis_aligned(r: RoughnessArg, what: &str) -> Result<p::AxisAligned, String> {
    let (ax, ay) = r.axis_aligned(what)?;
    p::AxisAligned::new(f(ax), f(ay)).map_err(|e| e.to_string())
}

/// KHPL16 eq. 16: the exact box filter over a given rectangle.
pub fn ggx_rect(v: &Value) -> Result<Value, String> {
    let r = roughness_arg(v)?;
    let (c, h) = (array::<2>(v, "center")?, array::<2>(v, "half_extent")?);
    let r = axis_aligned(r, "ggx_rect")?;
    out(p::filter::rect::p22_rect(r, v2(c), v2(h)))
}

/// The box filter on a full footprint: bounding rectangle, rectangle clamps, then eq. 16.
pub fn ggx_rect_footprint(v: &Value) -> Result<Value, String> {
    use p::filter::rect;
    let (r, fp) = (roughness_arg(v)?, footprint_arg(v)?);
    let (clamps, point) = (clamps_arg(v)?, point(v)?);
    let r = axis_aligned(r, "ggx_rect_footprint")?;
    let rules = clamp_rules(p::ClampRules::DEFAULT, clamps);
    let h = rules
        .rect(footprint(fp)?.bounding_rect(), r.alpha())
        .half_extent;
    match point {
        Point::D(m) => out(rect::d_rect(r, v3(m), h)),
        Point::P22(s) => out(rect::p22_rect(r, v2(s), h)),
        Point::Lambda(w) => out(rect::lambda_rect(r, h, v3(w))),
        Point::Lobe => vec_out(&[h.x, h.y]),
    }
}

/// KHPL16 eq. 19-20: the effective roughness of one axis.
pub fn ggx_proxy(v: &Value) -> Result<Value, String> {
    let (alpha, h) = (number(v, "alpha")?, number(v, "half_extent")?);
    let a = p::Isotropic::new(f(alpha))
        .map_err(|e| e.to_string())?
        .alpha();
    match v.get("variant").and_then(Value::as_str) {
        Some("exact") => out(p::filter::proxy::effective_alpha(a, f(h))),
        Some("simple") => out(p::filter::proxy::effective_alpha_simple(a, f(h))),
        _ => Err("variant must be \"exact\" or \"simple\"".into()),
    }
}

/// The methods of the front door, by their oracle names.
#[derive(Clone, Copy, PartialEq, Eq)]
enum MethodName {
    GaussianTk19,
    GaussianKhpl16,
    ProjectedTk21,
    RectKhpl16,
    RectGdc2016,
    ProxyKhpl16,
    GaussianExact,
}

fn method_name(v: &Value) -> Result<(MethodName, &str), String> {
    let name = string(v, "method")?;
    let m = match name {
        "gaussian_tk19" => MethodName::GaussianTk19,
        "gaussian_khpl16" => MethodName::GaussianKhpl16,
        "projected_tk21" => MethodName::ProjectedTk21,
        "rect_khpl16" => MethodName::RectKhpl16,
        "rect_gdc2016" => MethodName::RectGdc2016,
        "proxy_khpl16" => MethodName::ProxyKhpl16,
        "gaussian_exact" => MethodName::GaussianExact,
        _ => {
            return Err(format!(
                "unknown method \"{name}\"; the methods are \"gaussian_tk19\", \
                 \"gaussian_khpl16\", \"gaussian_exact\", \"projected_tk21\", \"rect_khpl16\", \
                 \"rect_gdc2016\", \"proxy_khpl16\""
            ));
        }
    };
    Ok((m, name))
}

/// The front door: `material.filtered(footprint, method)`, then `D`, `P22`, `Lambda` or the
/// lobe itself.
pub fn filtered(v: &Value) -> Result<Value, String> {
    use MethodName as M;
    use p::filter::{ExactGaussian, Gaussian, Projected, Proxy, Rect};
    let (d, r) = (dist(v)?, roughness_arg(v)?);
    let (method, name) = method_name(v)?;
    let fp = footprint_arg(v)?;
    let (clamps, sigma, point) = (clamps_arg(v)?, opt_non_negative(v, "sigma")?, point(v)?);
    let gaussian = matches!(
        method,
        M::GaussianTk19 | M::GaussianKhpl16 | M::GaussianExact
    );
    if d == Dist::Beckmann && !gaussian {
        return Err(format!(
            "method \"{name}\" is not defined for Beckmann: the projected space (TK21), the box \
             filter and its proxy (KHPL16 sec. 5.3-5.4) are GGX constructions; use \
             \"gaussian_tk19\", \"gaussian_khpl16\" or \"gaussian_exact\" (all exact for \
             Beckmann)"
        ));
    }
    let boxed = matches!(method, M::RectKhpl16 | M::RectGdc2016 | M::ProxyKhpl16);
    if boxed && sigma.is_some() {
        return Err(format!(
            "method \"{name}\" takes no `sigma`: its kernel is the footprint's bounding rectangle"
        ));
    }
    if boxed && matches!(r, RoughnessArg::Matrix(_)) {
        r.axis_aligned(&format!("method \"{name}\""))?;
    }
    let fp = footprint(fp)?;
    match method {
        M::GaussianTk19 | M::GaussianKhpl16 => {
            let base = if method == M::GaussianTk19 {
                Gaussian::TK19
            } else {
                Gaussian::KHPL16
            };
            let g = Gaussian {
                clamps: clamp_rules(base.clamps, clamps),
                sigma: sigma.map_or(base.sigma, f),
            };
            with_ndf!(d, r, n => lobe_out(&n.filtered(fp, g), point, |l| matrix_of(&l.roughness)))
        }
        M::GaussianExact => {
            let base = ExactGaussian::KHPL16;
            let g = ExactGaussian {
                clamps: clamp_rules(base.clamps, clamps),
                sigma: sigma.map_or(base.sigma, f),
                ..base
            };
            with_roughness!(r, rr => match d {
                Dist::Ggx => lobe_out(&p::Ggx::new(rr).filtered(fp, g), point, |_| {
                    Err("the exact Gaussian-filtered GGX is not a roughness: give a point \
                         (m, slope or w)"
                        .into())
                }),
                Dist::Beckmann => lobe_out(&p::Beckmann::new(rr).filtered(fp, g), point, |l| {
                    matrix_of(&l.roughness)
                }),
            })
        }
        M::ProjectedTk21 => {
            let base = Projected::TK21;
            let m = Projected {
                clamps: clamp_rules(base.clamps, clamps),
                sigma: sigma.map_or(base.sigma, f),
            };
            with_roughness!(r, rr => {
                lobe_out(&p::Ggx::new(rr).filtered(fp, m), point, |l| matrix_of(&l.roughness))
            })
        }
        M::RectKhpl16 | M::RectGdc2016 => {
            let base = if method == M::RectKhpl16 {
                Rect::KHPL16
            } else {
                Rect::GDC2016
            };
            let m = Rect {
                clamps: clamp_rules(base.clamps, clamps),
            };
            let describe = |l: &p::filter::RectFilteredGgx| {
                let (a, h) = (l.roughness.alpha(), l.half_extent);
                Ok(
                    json!({ "roughness": vec_out(&[a.x, a.y])?, "half_extent": vec_out(&[h.x, h.y])? }),
                )
            };
            match r {
                RoughnessArg::Iso(a) => {
                    let rr = p::Isotropic::new(f(a)).map_err(|e| e.to_string())?;
                    lobe_out(&p::Ggx::new(rr).filtered(fp, m), point, describe)
                }
                _ => lobe_out(
                    &p::Ggx::new(axis_aligned(r, name)?).filtered(fp, m),
                    point,
                    describe,
                ),
            }
        }
        M::ProxyKhpl16 => {
            let m = Proxy {
                clamps: clamp_rules(Proxy::KHPL16.clamps, clamps),
            };
            let describe = |l: &p::Ggx<p::AxisAligned>| {
                let a = l.roughness.alpha();
                vec_out(&[a.x, a.y])
            };
            match r {
                RoughnessArg::Iso(a) => {
                    let rr = p::Isotropic::new(f(a)).map_err(|e| e.to_string())?;
                    lobe_out(&p::Ggx::new(rr).filtered(fp, m), point, describe)
                }
                _ => lobe_out(
                    &p::Ggx::new(axis_aligned(r, name)?).filtered(fp, m),
                    point,
                    describe,
                ),
            }
        }
    }
}

/// The exact Gaussian filter of a slope density with a given kernel (issue 17): GGX by the
/// mixture identity (`GaussianFilteredGgx`), Beckmann by `A + 2 Sigma` (KHPL16 eq. 15).
pub fn gaussian_filtered(v: &Value) -> Result<Value, String> {
    let (d, r) = (dist(v)?, roughness_arg(v)?);
    let k = kernel_arg(v)?;
    let s = v2(array::<2>(v, "slope")?);
    let kernel = p::Covariance::new(f(k[0]), f(k[1]), f(k[2]));
    with_roughness!(r, rr => match d {
        Dist::Ggx => out(p::GaussianFilteredGgx::new(rr, kernel).p22(s)),
        Dist::Beckmann => out(p::Beckmann::new(p::filter::gaussian(rr, kernel)).p22(s)),
    })
}
