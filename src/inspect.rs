//! The derived data of each curve as JSON (`splinescope inspect`): its Bézier segments and,
//! per family, what the papers define on it. The format is documented in
//! `docs/inspect-format.md`.

use glam::DVec3;
use serde_json::{Map, Value, json};

use crate::geom::exact::format_rational;
use crate::geom::{Curve, GeomError, KnotVector, Lower, Nubmp, ParamCurve};

/// A point as a report writes it: always `[x, y, z]`.
pub(crate) fn point(p: DVec3) -> Value {
    json!([p.x, p.y, p.z])
}

/// Points as a report writes them.
pub(crate) fn points(ps: &[DVec3]) -> Value {
    Value::Array(ps.iter().copied().map(point).collect())
}

/// What a NUBMP curve (or a B-spline, as the standard NUBMP curve) allows at `τ`: the
/// point `P(τ)` and, for each group whose dual B-spline is non-zero there, its weight
/// `N*_j(τ)` and the vertices of the region (segment, triangle, …) that `P(τ)` reaches by
/// changing that group alone. `None` for other families or `τ` outside the domain.
///
/// # Errors
/// A B-spline whose standard NUBMP structure overflows `f64`
/// ([`crate::geom::GeomError::DerivedNotFinite`]).
pub fn at_tau(curve: &Curve, tau: f64) -> Result<Option<Value>, GeomError> {
    let standard;
    let n = match curve {
        Curve::Nubmp(n) => n,
        Curve::BSpline(b) => {
            standard = Nubmp::standard(b.points().to_vec(), b.knots().clone())?;
            &standard
        }
        _ => return Ok(None),
    };
    let (a, b) = n.domain();
    if !(tau >= a && tau <= b) {
        return Ok(None);
    }
    let groups: Vec<Value> = n
        .groups_at(tau)
        .into_iter()
        .map(|j| {
            let region = n.reachable_region(tau, j).unwrap_or_default();
            json!({
                "group": j,
                "members": n.groups()[j].members,
                "weight": n.dual_basis_value(j, tau),
                "region": points(&region),
            })
        })
        .collect();
    Ok(Some(
        json!({"tau": tau, "point": point(n.eval(tau)), "groups": groups}),
    ))
}

/// The report of one curve.
///
/// # Errors
/// A B-spline whose standard NUBMP structure overflows `f64`
/// ([`crate::geom::GeomError::DerivedNotFinite`]).
pub fn curve_report(index: usize, name: Option<&str>, curve: &Curve) -> Result<Value, GeomError> {
    let mut obj = Map::new();
    obj.insert("index".into(), index.into());
    obj.insert("family".into(), curve.family().into());
    if let Some(n) = name {
        obj.insert("name".into(), n.into());
    }
    let (a, b) = curve.domain();
    obj.insert("domain".into(), json!([a, b]));
    obj.insert(
        "segments".into(),
        Value::Array(
            curve
                .lower()
                .iter()
                .map(|s| {
                    json!({
                        "t0": s.t0, "t1": s.t1, "degree": s.bezier.degree(),
                        "points": points(s.bezier.points())
                    })
                })
                .collect(),
        ),
    );
    match curve {
        Curve::Bezier(bz) => {
            obj.insert("degree".into(), bz.degree().into());
            if bz.degree() <= POWER_BASIS_MAX_DEGREE {
                obj.insert("power_basis".into(), power_basis(bz.points()));
            }
            if bz.degree() == 3 {
                // Paper 000 §2.3's classification of the control polygon.
                match crate::solve::shape::cubic_region(bz) {
                    Ok(region) => {
                        let (subtype, meets) = region.subtype();
                        let mut r = json!({"type": region.kind.number(), "subtype": subtype});
                        if let Some(x) = meets {
                            r["lines_meet_at"] = point(x);
                        }
                        obj.insert("cubic_region".into(), r);
                    }
                    Err(e) => {
                        obj.insert("cubic_region_unavailable".into(), e.to_string().into());
                    }
                }
            }
        }
        Curve::Modified(m) => {
            obj.insert("degree".into(), m.base().degree().into());
            obj.insert("t_star".into(), m.t_star().into());
            obj.insert("v".into(), point(m.v()));
            obj.insert("peak".into(), json!({"t": m.t_star(), "q": point(m.base().eval(m.t_star())), "r": point(curve.eval(m.t_star()))}));
        }
        Curve::Interpolation(c) => {
            obj.insert("params".into(), c.params().to_vec().into());
            // Paper 002 §5: chord slopes C_i and the parabola weights α_i behind s_i.
            let (p, t) = (c.points(), c.params());
            let chords: Vec<DVec3> = (0..p.len() - 1)
                .map(|i| (p[i + 1] - p[i]) / (t[i + 1] - t[i]))
                .collect();
            obj.insert("chord_slopes".into(), points(&chords));
            let weights: Vec<f64> = (1..p.len() - 1)
                .map(|i| (t[i] - t[i - 1]) / (t[i + 1] - t[i - 1]))
                .collect();
            obj.insert("parabola_weights".into(), weights.into());
            obj.insert("tangents".into(), points(c.tangents()));
            obj.insert(
                "inner_points".into(),
                Value::Array(
                    c.pieces()
                        .iter()
                        .map(|p| json!([point(p.points()[1]), point(p.points()[2])]))
                        .collect(),
                ),
            );
            if let Some(m) = c.modification() {
                obj.insert(
                    "modification".into(),
                    json!({"t_star": m.t_star, "v": point(m.v), "reading": m.reading.name()}),
                );
            }
        }
        Curve::BSpline(bs) => {
            spline_fields(&mut obj, bs.knots());
            // A B-spline is the standard NUBMP curve on its knots: report that structure.
            nubmp_fields(
                &mut obj,
                &Nubmp::standard(bs.points().to_vec(), bs.knots().clone())?,
            );
        }
        Curve::Nubmp(n) => {
            spline_fields(&mut obj, n.knots());
            nubmp_fields(&mut obj, n);
        }
    }
    Ok(Value::Object(obj))
}

fn spline_fields(obj: &mut Map<String, Value>, knots: &KnotVector) {
    obj.insert("order".into(), knots.order().into());
    obj.insert("knots".into(), knots.knots().to_vec().into());
    obj.insert("clamped".into(), knots.is_clamped().into());
}

/// The highest degree for which `inspect` reports a Bézier curve's power-basis
/// coefficients (their binomial factors grow as 2ⁿ).
pub const POWER_BASIS_MAX_DEGREE: usize = 64;

/// The power-basis coefficients `a_k` of `P(t) = Σ_k a_k t^k`,
/// `a_k = C(n,k) Σ_{i≤k} (−1)^{k−i} C(k,i) P_i`, as exact rationals of each coordinate's
/// shortest decimal form (the decimal written in the scene file, for inputs of up to 15
/// significant digits) and as `f64`.
fn power_basis(pts: &[DVec3]) -> Value {
    use crate::geom::exact::{Rational, parse_decimal};
    use num_traits::{One, Zero};
    let n = pts.len() - 1;
    let exact: Vec<[Rational; 3]> = pts
        .iter()
        .map(|p| {
            p.to_array().map(|c| {
                parse_decimal(&crate::num::Num(c).to_string())
                    .unwrap_or_else(|| unreachable!("a finite coordinate's decimal parses"))
            })
        })
        .collect();
    let binomial = |n: usize, k: usize| -> Rational {
        let mut b = Rational::one();
        for j in 0..k {
            b = b * Rational::from_integer((n - j).into()) / Rational::from_integer((j + 1).into());
        }
        b
    };
    let coefficients: Vec<[Rational; 3]> = (0..=n)
        .map(|k| {
            let mut sum = [Rational::zero(), Rational::zero(), Rational::zero()];
            for (i, p) in exact.iter().enumerate().take(k + 1) {
                let w = binomial(k, i)
                    * if (k - i) % 2 == 0 {
                        Rational::one()
                    } else {
                        -Rational::one()
                    };
                for (s, c) in sum.iter_mut().zip(p) {
                    *s = s.clone() + w.clone() * c.clone();
                }
            }
            let ck = binomial(n, k);
            sum.map(|s| s * ck.clone())
        })
        .collect();
    json!({
        "exact": coefficients
            .iter()
            .map(|c| c.iter().map(format_rational).collect::<Vec<_>>())
            .collect::<Vec<_>>(),
        "values": coefficients
            .iter()
            .map(|c| c.iter().map(crate::geom::exact::Scalar::to_f64).collect::<Vec<_>>())
            .collect::<Vec<_>>(),
    })
}

/// The highest order for which `inspect` reports the elevation coefficients as exact
/// rationals (above it, `exact_omitted` says so; the `f64` values are always there).
pub const EXACT_MAX_ORDER: usize = 16;

/// The most control points for which `inspect` reports exact rational coefficients.
pub const EXACT_MAX_POINTS: usize = 10_000;

fn nubmp_fields(obj: &mut Map<String, Value>, n: &Nubmp) {
    obj.insert(
        "refined_knots".into(),
        n.refined_knots().knots().to_vec().into(),
    );
    // Exact rationals cost about order⁴ big-number operations per coefficient: they are
    // computed up to EXACT_MAX_ORDER, the f64 values always.
    let exact = (n.order() <= EXACT_MAX_ORDER && n.points().len() <= EXACT_MAX_POINTS)
        .then(|| n.exact_coefficients());
    if exact.is_none() {
        obj.insert(
            "exact_omitted".into(),
            format!(
                "exact rational coefficients are computed up to order {EXACT_MAX_ORDER} and {EXACT_MAX_POINTS} points; this curve has order {} and {} points",
                n.order(),
                n.points().len()
            )
            .into(),
        );
    }
    obj.insert(
        "exact_from".into(),
        if n.knots().has_exact() {
            "decimal knots"
        } else {
            "binary f64 knots"
        }
        .into(),
    );
    let f64_rows = crate::geom::bspline::elevation_coefficients(n.knots().knots(), n.order()).rows;
    obj.insert(
        "coefficients".into(),
        Value::Array(
            f64_rows
                .iter()
                .enumerate()
                .map(|(i, frow)| {
                    let mut row = json!({
                        "i": i,
                        "first_group": frow.first,
                        "values": frow.values,
                    });
                    if let Some(e) = &exact {
                        row["exact"] = e.rows[i]
                            .values
                            .iter()
                            .map(format_rational)
                            .collect::<Vec<_>>()
                            .into();
                    }
                    row
                })
                .collect(),
        ),
    );
    obj.insert("free_parameters".into(), n.free_parameter_count().into());
    obj.insert("dual_points".into(), points(n.dual_points()));
    let groups: Vec<Value> = n
        .groups()
        .iter()
        .enumerate()
        .map(|(j, g)| {
            let mut gobj = Map::new();
            gobj.insert("group".into(), j.into());
            gobj.insert("members".into(), g.members.clone().into());
            gobj.insert("standard".into(), g.standard.clone().into());
            gobj.insert("values".into(), g.values.clone().into());
            gobj.insert("effective".into(), g.effective.into());
            gobj.insert(
                "affected_spans".into(),
                Value::Array(
                    n.affected_spans(j)
                        .iter()
                        .map(|(a, b)| json!([a, b]))
                        .collect(),
                ),
            );
            if n.order() == 4 {
                gobj.insert("vd".into(), n.vd_value(j).map_or(Value::Null, Value::from));
                let mut ranges = Vec::new();
                for &i in &g.members {
                    for &l in &g.members {
                        if i == l {
                            continue;
                        }
                        if let Ok(r) = n.permissible_range(j, i, l) {
                            ranges.push(match r {
                                Some(r) => {
                                    json!({"member": i, "absorber": l, "min": r.min, "max": r.max})
                                }
                                None => {
                                    json!({"member": i, "absorber": l, "min": null, "max": null})
                                }
                            });
                        }
                    }
                }
                gobj.insert("permissible_ranges".into(), Value::Array(ranges));
            }
            Value::Object(gobj)
        })
        .collect();
    obj.insert("groups".into(), Value::Array(groups));
}
