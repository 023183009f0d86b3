// The temporal lobe of Tessari et al. 2020 (included into `eval::p32` and `eval::p64`; see
// typed.rs).

/// `TemporalLobe`: `D` from `A + alpha_t^2 a a^T` (eq. 16), `Lambda` from `A` (eq. 17).
pub fn temporal(v: &Value) -> Result<Value, String> {
    use p::temporal::{TemporalLobe, TemporalRoughness, box_shutter_dt};
    let (d, r) = (dist(v)?, roughness_arg(v)?);
    let rate = array::<2>(v, "dn_dt")?;
    let dt = match (opt_number(v, "dt")?, opt_number(v, "shutter")?) {
        (Some(dt), None) => f(dt),
        (None, Some(t)) => box_shutter_dt(f(t)),
        (Some(_), Some(_)) => return Err("give one of `dt` and `shutter`, not both".into()),
        (None, None) => return Err("missing argument `dt` (or `shutter`)".into()),
    };
    let (cos_theta, fraction) = (opt_number(v, "cos_theta")?, opt_number(v, "fraction")?);
    let point = point(v)?;
    let mut t = TemporalRoughness::from_normal_rate(v2(rate), dt);
    if let Some(c) = cos_theta {
        t = t.cosine_weighted(f(c));
    }
    if let Some(x) = fraction {
        t = t.share(f(x));
    }
    let describe = |widened: &p::RoughnessMatrix| {
        let a = t.axis();
        Ok(json!({
            "alpha_t": out(t.alpha())?,
            "axis": vec_out(&[a.x, a.y])?,
            "roughness": matrix_of(widened)?,
        }))
    };
    with_roughness!(r, rr => match d {
        Dist::Ggx => {
            let lobe = TemporalLobe::ggx(rr, t.covariance());
            lobe_out(&lobe, point, |l| describe(&l.widened.roughness))
        }
        Dist::Beckmann => {
            let lobe = TemporalLobe::beckmann(rr, t.covariance());
            lobe_out(&lobe, point, |l| describe(&l.widened.roughness))
        }
    })
}
