//! Rational curves against closed forms: the quarter circle as a quadratic rational
//! Bézier curve and the nine-point NURBS circle stay on the circle within 4·ε·R, their
//! tangents are perpendicular to the radius and equal finite differences; every weight 1
//! is the polynomial curve bit for bit; knot insertion, elevation and Bézier extraction do
//! not move the curve; a projective map of the homogeneous control points maps the curve.

use glam::{DMat4, DVec3, DVec4};

use splinescope_core::geom::{BSpline, Bezier, GeomError, Nurbs, ParamCurve, RationalBezier};

const EPS: f64 = f64::EPSILON;

fn quarter_circle() -> RationalBezier {
    RationalBezier::try_new(
        vec![DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
        vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0],
    )
    .expect("a quarter circle")
}

/// The nine-point circle of radius `r` about `c` (knots 0,0,0,¼,¼,½,½,¾,¾,1,1,1).
fn circle(c: DVec3, r: f64) -> Nurbs {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let corners = [
        (1.0, 0.0),
        (1.0, 1.0),
        (0.0, 1.0),
        (-1.0, 1.0),
        (-1.0, 0.0),
        (-1.0, -1.0),
        (0.0, -1.0),
        (1.0, -1.0),
        (1.0, 0.0),
    ];
    Nurbs::try_new(
        corners
            .iter()
            .map(|(x, y)| c + r * DVec3::new(*x, *y, 0.0))
            .collect(),
        (0..9).map(|i| if i % 2 == 0 { 1.0 } else { s }).collect(),
        vec![
            0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
        ],
        3,
    )
    .expect("the nine-point circle")
}

/// `breaks`: parameters where the parameterisation's derivatives may jump (knots); finite
/// differences are not taken across them.
fn check_circle(curve: &impl ParamCurve, c: DVec3, r: f64, breaks: &[f64], what: &str) {
    let (a, b) = curve.domain();
    for j in 0..=4000 {
        let t = a + (b - a) * f64::from(j) / 4000.0;
        let p = curve.eval(t);
        let off = ((p - c).length() - r).abs();
        assert!(
            off <= 4.0 * EPS * r,
            "{what}: t = {t}: |P − C| − R = {off:e}"
        );
        let d = curve.eval_deriv(t);
        // Tangent ⟂ radius.
        assert!(
            d.dot(p - c).abs() <= 1e-13 * d.length() * r,
            "{what}: t = {t}: tangent not perpendicular"
        );
        // Against central differences (away from the ends).
        let h = 1e-6 * (b - a);
        if j > 0 && j < 4000 && breaks.iter().all(|k| (t - k).abs() > 2.0 * h) {
            let fd = (curve.eval(t + h) - curve.eval(t - h)) / (2.0 * h);
            assert!(
                (fd - d).length() <= 1e-6 * d.length().max(1.0),
                "{what}: t = {t}: P′ = {d} vs finite differences {fd}"
            );
            let fd2 = (curve.eval_deriv(t + h) - curve.eval_deriv(t - h)) / (2.0 * h);
            let d2 = curve.eval_second_deriv(t);
            assert!(
                (fd2 - d2).length() <= 1e-5 * d2.length().max(1.0),
                "{what}: t = {t}: P″ = {d2} vs finite differences {fd2}"
            );
        }
    }
}

#[test]
fn the_quarter_circle_is_exact() {
    check_circle(&quarter_circle(), DVec3::ZERO, 1.0, &[], "quarter circle");
    // The middle of the arc is at 45°.
    let m = quarter_circle().eval(0.5);
    assert!((m - DVec3::new(1.0, 1.0, 0.0) * std::f64::consts::FRAC_1_SQRT_2).length() < 4.0 * EPS);
}

#[test]
fn the_nine_point_nurbs_circle_is_exact() {
    for (c, r) in [
        (DVec3::ZERO, 1.0),
        (DVec3::new(3.0, -2.0, 0.0), 2.5),
        (DVec3::ZERO, 1e-3),
        (DVec3::ZERO, 1e6),
    ] {
        check_circle(
            &circle(c, r),
            c,
            r,
            &[0.25, 0.5, 0.75],
            &format!("circle about {c} of radius {r}"),
        );
    }
}

#[test]
fn weights_one_are_the_polynomial_curves_bit_for_bit() {
    let pts: Vec<DVec3> = (0..7)
        .map(|i| DVec3::new(f64::from(i), f64::from((i * 5) % 3), f64::from(i % 2)))
        .collect();
    let rb = RationalBezier::try_new(pts.clone(), vec![1.0; 7]).expect("rational");
    let b = Bezier::new(pts.clone());
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 0.8, 1.0, 1.0, 1.0, 1.0];
    let n = Nurbs::try_new(pts.clone(), vec![1.0; 7], knots.clone(), 4).expect("nurbs");
    let s = BSpline::try_new(pts, knots, 4).expect("spline");
    for j in 0..=100 {
        let t = f64::from(j) / 100.0;
        assert_eq!(rb.eval(t), b.eval(t));
        assert_eq!(rb.eval_deriv(t), b.eval_deriv(t));
        assert_eq!(n.eval(t), s.eval(t));
        assert_eq!(n.eval_second_deriv(t), s.eval_second_deriv(t));
    }
}

#[test]
fn insertion_elevation_and_extraction_keep_the_curve() {
    let c = circle(DVec3::new(1.0, 2.0, 0.0), 3.0);
    let inserted = c.insert_knot(0.4).expect("insert");
    let elevated = c.elevate();
    assert_eq!(inserted.points().len(), 10);
    assert_eq!(elevated.order(), 4);
    let segments = c.bezier_segments();
    assert_eq!(segments.len(), 4);
    for j in 0..=1000 {
        let t = f64::from(j) / 1000.0;
        let p = c.eval(t);
        assert!(
            (inserted.eval(t) - p).length() <= 1e-14 * 3.0,
            "insert, t = {t}"
        );
        assert!(
            (elevated.eval(t) - p).length() <= 1e-14 * 3.0,
            "elevate, t = {t}"
        );
        let (t0, t1, seg) = segments
            .iter()
            .find(|(t0, t1, _)| t >= *t0 && t <= *t1)
            .expect("a segment");
        let u = (t - t0) / (t1 - t0);
        assert!(
            (seg.eval(u) - p).length() <= 1e-14 * 3.0,
            "extraction, t = {t}"
        );
    }
    let q = quarter_circle();
    let e = q.elevate().elevate();
    assert_eq!(e.degree(), 4);
    for j in 0..=100 {
        let t = f64::from(j) / 100.0;
        assert!((e.eval(t) - q.eval(t)).length() <= 4.0 * EPS);
        let sub = q.subsegment(0.25, 0.75);
        assert!((sub.eval(t) - q.eval(0.25 + 0.5 * t)).length() <= 4.0 * EPS);
    }
}

/// A projective map applied to the homogeneous control points `(w P, w)` maps every
/// point of the curve: `C′(t) = M·C(t)` (projective invariance).
#[test]
fn a_projective_map_of_the_control_points_maps_the_curve() {
    let m = DMat4::from_cols(
        DVec4::new(1.2, 0.1, 0.0, 0.05),
        DVec4::new(-0.3, 0.9, 0.2, 0.02),
        DVec4::new(0.0, 0.1, 1.0, 0.0),
        DVec4::new(0.5, -1.0, 2.0, 1.0),
    );
    let apply = |p: DVec3, w: f64| {
        let h = m * (p * w).extend(w);
        (h.truncate() / h.w, h.w)
    };
    let c = circle(DVec3::new(0.5, 0.5, 0.0), 1.0);
    let (points, weights): (Vec<DVec3>, Vec<f64>) = c
        .points()
        .iter()
        .zip(c.weights())
        .map(|(p, w)| apply(*p, *w))
        .unzip();
    let mapped = Nurbs::try_new(points, weights, c.knots().knots().to_vec(), 3).expect("mapped");
    for j in 0..=500 {
        let t = f64::from(j) / 500.0;
        let (want, _) = apply(c.eval(t), 1.0);
        assert!((mapped.eval(t) - want).length() <= 1e-13, "t = {t}");
    }
}

#[test]
fn bad_weights_are_refused_naming_the_weight() {
    let pts = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
    let e = RationalBezier::try_new(pts.clone(), vec![1.0, 1.0]).unwrap_err();
    assert!(
        matches!(
            e,
            GeomError::WeightCount {
                weights: 2,
                points: 3
            }
        ),
        "{e:?}"
    );
    assert_eq!(e.field(), "weights");
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = RationalBezier::try_new(pts.clone(), vec![1.0, bad, 1.0]).unwrap_err();
        assert_eq!(e.field(), "weights[1]", "{bad}");
        assert!(e.to_string().contains("greater than 0"), "{e}");
    }
    let e = Nurbs::try_new(
        pts,
        vec![1.0, 1.0, -2.0],
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        3,
    )
    .unwrap_err();
    assert_eq!(e.field(), "weights[2]");
}

/// Paper 000's least-squares modification with the weights held fixed: the curve passes
/// through its targets, the weights do not change, the change is the minimum-norm one
/// (its moves lie along the rational basis values), and with weights 1 it is the
/// polynomial solver's change.
#[test]
fn rational_solves_pass_through_keep_weights_and_are_minimal() {
    use splinescope_core::solve::rational::{multi_target, rational_basis, single_target};
    let arc = RationalBezier::try_new(
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(3.0, 2.5, 0.0),
            DVec3::new(5.0, 1.0, 0.0),
            DVec3::new(6.0, 0.0, 0.0),
        ],
        vec![1.0, 0.6, 2.0, 0.8, 1.0],
    )
    .expect("curve");
    let target = DVec3::new(3.0, 3.5, 0.0);
    let s = single_target(&arc, target, Some(0.45), None, None).expect("single");
    assert!(s.residuals[0] < 1e-12, "{:?}", s.residuals);
    assert_eq!(s.curve.weights(), arc.weights());
    // Minimal: ε_i = R_i(t) d / Σ R_j² over the moved window.
    let r = rational_basis(arc.weights(), 0.45);
    let d = target - arc.eval(0.45);
    let denom: f64 = s.moved.iter().map(|&i| r[i] * r[i]).sum();
    for (&i, e) in s.moved.iter().zip(&s.deltas) {
        assert!((*e - d * (r[i] / denom)).length() < 1e-12, "point {i}");
    }
    let targets = [DVec3::new(1.0, 1.8, 0.0), DVec3::new(4.5, 1.6, 0.0)];
    let m = multi_target(&arc, &targets, Some(&[0.2, 0.8]), None).expect("multi");
    for (res, (t, want)) in m.residuals.iter().zip([0.2, 0.8].iter().zip(&targets)) {
        assert!(*res < 1e-12 && (m.curve.eval(*t) - *want).length() < 1e-12);
    }
    assert_eq!(m.curve.points()[0], arc.points()[0]);
    assert_eq!(m.curve.points()[4], arc.points()[4]);
    // Weights 1: the polynomial solver's change.
    let poly = Bezier::new(arc.points().to_vec());
    let unit = RationalBezier::try_new(arc.points().to_vec(), vec![1.0; 5]).expect("unit");
    let a = multi_target(&unit, &targets, Some(&[0.2, 0.8]), None).expect("rational");
    let b = splinescope_core::solve::shape::multi_target(&poly, &targets, Some(&[0.2, 0.8]), None)
        .expect("polynomial");
    for (p, q) in a.curve.points().iter().zip(b.curve.points()) {
        assert!((*p - *q).length() < 1e-12);
    }
    // Refusals.
    assert!(single_target(&arc, target, Some(1.0), None, None).is_err());
    assert!(single_target(&arc, target, Some(0.5), Some((0, 2)), None).is_err());
    assert!(multi_target(&arc, &targets, Some(&[0.5]), None).is_err());
}

/// The minimum-norm solution of `A x = d` for a full-row-rank `A` (rows × cols), written
/// out independently of the solver: `x = Aᵀ (A Aᵀ)⁻¹ d` by Gaussian elimination on the
/// small Gram matrix.
fn min_norm(a: &[Vec<f64>], d: &[f64]) -> Vec<f64> {
    let m = a.len();
    let mut g: Vec<Vec<f64>> = (0..m)
        .map(|i| {
            let mut row: Vec<f64> = (0..m)
                .map(|j| a[i].iter().zip(&a[j]).map(|(x, y)| x * y).sum())
                .collect();
            row.push(d[i]);
            row
        })
        .collect();
    for c in 0..m {
        let p = (c..m)
            .max_by(|&x, &y| g[x][c].abs().total_cmp(&g[y][c].abs()))
            .unwrap();
        g.swap(c, p);
        let pivot = g[c].clone();
        for (r, row) in g.iter_mut().enumerate() {
            if r != c {
                let f = row[c] / pivot[c];
                for (x, p) in row.iter_mut().zip(&pivot).skip(c) {
                    *x -= f * p;
                }
            }
        }
    }
    let lambda: Vec<f64> = (0..m).map(|i| g[i][m] / g[i][i]).collect();
    (0..a[0].len())
        .map(|k| (0..m).map(|i| a[i][k] * lambda[i]).sum())
        .collect()
}

/// NURBS solves: through the targets, weights and knots kept, the end points fixed, and
/// the moves the minimum-norm ones (against `Aᵀ(AAᵀ)⁻¹d` computed here per coordinate).
#[test]
fn nurbs_multi_target_passes_through_and_is_the_minimum_norm_change() {
    use splinescope_core::solve::rational::{RationalCurve, multi_target, single_target};
    let pts: Vec<DVec3> = (0..7)
        .map(|i| DVec3::new(f64::from(i), f64::from((i * 5) % 3), 0.0))
        .collect();
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 0.8, 1.0, 1.0, 1.0, 1.0];
    let n = Nurbs::try_new(pts, vec![1.0, 2.0, 0.5, 1.5, 3.0, 0.7, 1.0], knots, 4).expect("n");
    let targets = [DVec3::new(1.5, 2.5, 0.0), DVec3::new(4.2, -0.5, 0.0)];
    let params = [0.25, 0.7];
    let s = multi_target(&n, &targets, Some(&params), None).expect("solve");
    for (t, want) in params.iter().zip(&targets) {
        assert!((s.curve.eval(*t) - *want).length() < 1e-12);
    }
    assert_eq!(s.curve.weights(), n.weights());
    assert_eq!(s.curve.knots(), n.knots());
    assert_eq!(s.curve.points()[0], n.points()[0]);
    assert_eq!(s.curve.points()[6], n.points()[6]);
    let a: Vec<Vec<f64>> = params
        .iter()
        .map(|&t| s.moved.iter().map(|&i| n.basis(t)[i]).collect())
        .collect();
    for c in 0..3 {
        let d: Vec<f64> = params
            .iter()
            .zip(&targets)
            .map(|(&t, want)| (*want - n.eval(t))[c])
            .collect();
        let x = min_norm(&a, &d);
        for (k, delta) in s.deltas.iter().enumerate() {
            assert!((delta[c] - x[k]).abs() < 1e-12, "coordinate {c}, move {k}");
        }
    }
    // The rational basis sums to 1 and is the curve's own: Σ R_i P_i = C.
    for t in [0.0, 0.1, 0.45, 0.8, 1.0] {
        let r = n.basis(t);
        assert!((r.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        let c: DVec3 = r.iter().zip(n.points()).map(|(r, p)| *r * *p).sum();
        assert!((c - n.eval(t)).length() < 1e-13);
    }
    // One target, projected: the curve passes through it.
    let target = DVec3::new(3.1, 2.2, 0.0);
    let one = single_target(&n, target, None, None, None).expect("single");
    assert!(one.residuals[0] < 1e-12);
    assert!((one.curve.eval(one.params[0]) - target).length() < 1e-12);
}

/// Paper 000 §2.2 on a rational curve: ends and end tangent directions kept, the target
/// met, and the change (μ₁, μ₂, ε_i) the minimum-norm one.
#[test]
fn tangent_kept_on_rational_curves_keeps_the_end_tangents() {
    use splinescope_core::solve::rational::{RationalCurve, tangent_kept};
    let arc = RationalBezier::try_new(
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(3.0, 2.5, 0.0),
            DVec3::new(5.0, 1.0, 0.0),
            DVec3::new(6.0, 0.0, 0.0),
        ],
        vec![1.0, 0.6, 2.0, 0.8, 1.0],
    )
    .expect("curve");
    let target = DVec3::new(3.0, 3.2, 0.0);
    let s = tangent_kept(&arc, target, Some(0.5), None).expect("solve");
    let q = s.solution.curve.points();
    let p = arc.points();
    assert!((s.solution.curve.eval(0.5) - target).length() < 1e-12);
    assert_eq!(s.solution.curve.weights(), arc.weights());
    assert_eq!((q[0], q[4]), (p[0], p[4]));
    // P₁ stays on the line P₀P₁, P₃ on P₄P₃, in the same direction.
    let (e1, e2) = ((p[1] - p[0]).normalize(), (p[3] - p[4]).normalize());
    assert!((q[1] - p[0]).normalize().dot(e1) > 1.0 - 1e-12);
    assert!((q[3] - p[4]).normalize().dot(e2) > 1.0 - 1e-12);
    // Minimum norm: unknowns (μ₁, μ₂, ε₂ₓ, ε₂ᵧ), two equations (x, y).
    let r = arc.basis(0.5);
    let d = target - arc.eval(0.5);
    let a = vec![
        vec![r[1] * e1.x, r[3] * e2.x, r[2], 0.0],
        vec![r[1] * e1.y, r[3] * e2.y, 0.0, r[2]],
    ];
    let x = min_norm(&a, &[d.x, d.y]);
    assert!((s.mu[0] - x[0]).abs() < 1e-12 && (s.mu[1] - x[1]).abs() < 1e-12);
    assert!((s.solution.deltas[0] - DVec3::new(x[2], x[3], 0.0)).length() < 1e-12);
    // Too few points, coincident ends: typed refusals.
    let short = RationalBezier::try_new(p[..3].to_vec(), vec![1.0, 2.0, 1.0]).expect("short");
    assert!(tangent_kept(&short, target, Some(0.5), None).is_err());
}

/// The panel's weight controls: a typed weight is applied, `w ≤ 0` and non-finite values
/// are refused naming the weight (nothing clamped), elevation keeps the curve.
#[test]
fn weight_controls_apply_refuse_and_elevation_keeps_the_curve() {
    use splinescope_core::geom::Family;
    use splinescope_present::{ControlId, ControlKind, ControlValue, Present};
    let c = Nurbs::circle(DVec3::ZERO, 2.0).expect("circle");
    let controls = c.controls();
    let weights: Vec<_> = controls.iter().filter(|k| k.id.key == "w").collect();
    assert_eq!(weights.len(), 9);
    assert!(
        matches!(weights[1].kind, ControlKind::Number { value, .. } if value == std::f64::consts::FRAC_1_SQRT_2)
    );
    let id = ControlId {
        key: "w",
        index: [1, 0],
    };
    let heavier = c
        .apply_control(id, ControlValue::Number(2.0))
        .expect("w = 2");
    assert_eq!(heavier.weights()[1], 2.0);
    assert_eq!(heavier.points(), c.points());
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = c.apply_control(id, ControlValue::Number(bad)).unwrap_err();
        assert!(
            matches!(
                e,
                splinescope_present::ControlError::Geom(GeomError::BadWeight { index: 1, .. })
            ),
            "{bad}: {e}"
        );
        assert_eq!(e.field(), "weights[1]");
    }
    let none = ControlId {
        key: "w",
        index: [9, 0],
    };
    assert!(c.apply_control(none, ControlValue::Number(1.0)).is_err());
    let up = c
        .apply_control(ControlId::new("elevate"), ControlValue::Press)
        .expect("elevate");
    assert_eq!(up.order(), 4);
    for j in 0..=400 {
        let t = f64::from(j) / 400.0;
        assert!((up.eval(t) - c.eval(t)).length() < 1e-14 * 2.0 * 8.0);
    }
    // Structure edits keep one weight per point.
    let fewer = c.with_point_removed(3).expect("remove");
    assert_eq!(fewer.weights().len(), fewer.points().len());
    let rb = RationalBezier::quarter_ellipse(DVec3::ZERO, 2.0, 1.0);
    let (more, at) = rb
        .with_point_on_polygon(DVec3::new(2.0, 0.5, 0.0))
        .expect("insert");
    assert_eq!((at, more.weights().len()), (1, 4));
    assert!(more.weights()[1] > 0.0);
}

/// The templates the editor offers, the conic type `inspect` reports, and scene files:
/// written and read back to the same curves.
#[test]
fn templates_conic_types_and_scene_round_trip() {
    use splinescope_core::geom::{Conic, Curve};
    use splinescope_present::Present;
    let labels: Vec<&str> = Curve::templates(DVec3::ZERO, 1.0)
        .iter()
        .map(|(l, _)| *l)
        .collect();
    for want in ["circle", "ellipse arc", "NURBS curve"] {
        assert!(labels.contains(&want), "{want} in {labels:?}");
    }
    for (w1, want) in [
        (0.4, Conic::Ellipse),
        (1.0, Conic::Parabola),
        (3.0, Conic::Hyperbola),
    ] {
        let c = RationalBezier::try_new(
            vec![
                DVec3::ZERO,
                DVec3::new(1.0, 2.0, 0.0),
                DVec3::new(2.0, 0.0, 0.0),
            ],
            vec![1.0, w1, 1.0],
        )
        .expect("conic");
        assert_eq!(c.details().expect("details").conic, Some(want));
        // Independent check of the type: a parabola's arc has its tangents' crossing at
        // P₁ and its midpoint halfway to the chord's midpoint; an ellipse's midpoint is
        // nearer P₁, a hyperbola's nearer the chord (the shoulder point
        // (M + w₁P₁)/(1 + w₁)).
        let mid = c.eval(0.5);
        let shoulder = (DVec3::new(1.0, 0.0, 0.0) + w1 * DVec3::new(1.0, 2.0, 0.0)) / (1.0 + w1);
        assert!((mid - shoulder).length() < 1e-14);
    }
    let scene = splinescope_scene::format::gallery::gallery();
    let text = splinescope_scene::format::to_json_string(&scene);
    let back = splinescope_scene::format::from_json_str(&text).expect("read back");
    for (a, b) in scene.curves.iter().zip(&back.curves) {
        assert_eq!(a.curve, b.curve, "{:?}", a.name);
    }
    assert!(back.curves.iter().any(|c| c.curve.family() == "nurbs"));
    assert!(
        back.curves
            .iter()
            .any(|c| c.curve.family() == "rational_bezier")
    );
}

/// The batch sampler (what `eval`, Python and the benchmarks use) evaluates rational
/// pieces through their homogeneous parts: points, first and second derivatives agree
/// with each family's own evaluation.
#[test]
fn the_batch_sampler_agrees_with_the_rational_curves() {
    use splinescope_core::geom::Curve;
    use splinescope_core::geom::batch::CurveSampler;
    let curves = [
        Curve::Nurbs(circle(DVec3::new(3.0, -2.0, 0.0), 2.5)),
        Curve::RationalBezier(
            RationalBezier::try_new(
                vec![
                    DVec3::ZERO,
                    DVec3::new(1.0, 2.0, 1.0),
                    DVec3::new(3.0, 2.5, -1.0),
                    DVec3::new(5.0, 1.0, 0.5),
                ],
                vec![1.0, 4.0, 0.25, 2.0],
            )
            .expect("cubic"),
        ),
        // Planar (every z = 0): its own path, x, y and the weight only.
        Curve::RationalBezier(
            RationalBezier::try_new(
                vec![
                    DVec3::new(-1.0, 0.5, 0.0),
                    DVec3::new(1.0, 2.0, 0.0),
                    DVec3::new(3.0, -2.5, 0.0),
                    DVec3::new(5.0, 1.0, 0.0),
                ],
                vec![0.5, 3.0, 0.125, 2.0],
            )
            .expect("planar cubic"),
        ),
    ];
    for c in &curves {
        let sampler = CurveSampler::new(c);
        let (a, b) = c.domain();
        let ts: Vec<f64> = (0..=997)
            .map(|j| a + (b - a) * f64::from(j) / 997.0)
            .collect();
        for (order, want) in [
            (0u32, &(|t: f64| c.eval(t)) as &dyn Fn(f64) -> DVec3),
            (1, &|t: f64| c.eval_deriv(t)),
            (2, &|t: f64| c.eval_second_deriv(t)),
        ] {
            let s = if order == 0 {
                sampler.clone()
            } else {
                sampler.derivative(order)
            };
            let mut out = vec![DVec3::ZERO; ts.len()];
            s.eval_into(&ts, &mut out);
            let scale = ts.iter().map(|&t| want(t).length()).fold(1.0, f64::max);
            for (t, got) in ts.iter().zip(&out) {
                assert!(
                    (*got - want(*t)).length() <= 1e-12 * scale,
                    "{} order {order} at {t}: {got} vs {}",
                    c.family(),
                    want(*t)
                );
            }
        }
    }
}

/// A solve passes through its targets or is refused (never a curve that misses silently):
/// a window whose basis is 0 at the target's parameter (the circle's knot t = 0.5 lies in
/// no span of P_1) is refused naming the points that could move it; next to an end, the
/// target is met however far the points move, or the solve is refused naming `t`; a
/// several-target system whose rank rounding lost is refused, not solved in least squares.
#[test]
fn rational_solves_meet_their_targets_or_are_refused() {
    use splinescope_core::solve::SolveError;
    use splinescope_core::solve::rational::{multi_target, single_target, tangent_kept};
    let c = circle(DVec3::ZERO, 1.0);
    let target = DVec3::new(-1.5, 0.2, 0.0);
    match single_target(&c, target, Some(0.5), Some((1, 1)), None) {
        Err(e @ SolveError::NoInfluence { .. }) => {
            let m = e.to_string();
            assert!(
                m.contains("(P_1)") && m.contains("P_4") && m.contains("t = 0.5"),
                "{m}"
            );
        }
        other => panic!("{other:?}"),
    }
    let s = single_target(&c, target, Some(0.5), None, None).expect("default window");
    assert!((s.curve.eval(0.5) - target).length() < 1e-12);
    let target = DVec3::new(1.5, 0.5, 0.0);
    let mut refused = 0;
    for t in [
        5e-324,
        1e-300,
        1e-200,
        1e-100,
        1e-20,
        1.0 - f64::EPSILON / 2.0,
    ] {
        match single_target(&c, target, Some(t), None, None) {
            Ok(s) => {
                assert!(s.curve.points().iter().all(|p| p.is_finite()));
                let gap = (s.curve.eval(t) - target).length();
                assert!(gap <= 1e-9, "t = {t:e}: misses by {gap}");
                assert!(s.residuals[0] <= 1e-9);
            }
            Err(
                SolveError::NoInfluence { value, .. }
                | SolveError::MovesOverflow { value, .. }
                | SolveError::Missed { value, .. },
            ) => {
                assert_eq!(value, t);
                refused += 1;
            }
            Err(e) => panic!("t = {t:e}: {e}"),
        }
    }
    assert!(refused >= 1, "t = 5e-324 cannot be met in f64");
    // Two targets, three free points: not over-determined; the second target's basis is
    // tiny, so rounding drops the rank. Refused rather than returned in least squares.
    let arc = RationalBezier::try_new(
        vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(3.0, 0.0, 0.0),
            DVec3::new(4.0, 3.0, 0.0),
            DVec3::new(5.0, -1.0, 0.0),
        ],
        vec![1.0, 0.5, 2.0, 1.0, 1.0],
    )
    .expect("arc");
    let targets = [DVec3::new(1.0, 1.0, 0.0), DVec3::new(3.0, 2.0, 0.0)];
    match multi_target(&arc, &targets, Some(&[0.3, 1e-300]), None) {
        Err(SolveError::Missed { index: 1, .. } | SolveError::MovesOverflow { .. }) => {}
        Ok(m) => {
            for (l, t) in [0.3, 1e-300].iter().enumerate() {
                assert!(
                    (m.curve.eval(*t) - targets[l]).length() <= 1e-9,
                    "target {l}"
                );
            }
        }
        Err(e) => panic!("{e}"),
    }
    // Over-determined by structure (four targets, three free points): least squares, said.
    // (Parameters symmetric about ½ would make this shift reachable exactly.)
    let params = [0.1, 0.3, 0.6, 0.7];
    let four = params.map(|t| arc.eval(t) + DVec3::new(0.0, 0.3, 0.0));
    let m = multi_target(&arc, &four, Some(&params), None).expect("least squares");
    assert!(
        m.least_squares && m.residuals.iter().any(|r| *r > 1e-6),
        "{} {:?}",
        m.least_squares,
        m.residuals
    );
    // The tangent-kept solve at a parameter where nothing moves the curve: refused.
    assert!(tangent_kept(&arc, DVec3::new(2.0, 2.0, 0.0), Some(5e-324), None).is_err());
    // The polynomial solvers: the same rules.
    let poly = Bezier::new(arc.points().to_vec());
    assert!(
        splinescope_core::solve::shape::multi_target(&poly, &targets, Some(&[0.3, 1e-300]), None)
            .is_err()
    );
}
