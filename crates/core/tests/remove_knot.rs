//! Knot removal within a tolerance: a knot inserted (which does not move the curve) is
//! removed again exactly; on random B-splines and NURBS curves every removal that is
//! allowed moves the curve by at most its bound and the tolerance — measured on dense
//! samples of both curves, independently of the bound; what is refused names the bound.

use glam::DVec3;
use splinescope_core::geom::{BSpline, Bezier, Curve, Nurbs, ParamCurve};
use splinescope_core::ops::{OpError, remove_knot};
use splinescope_core::rng::Rng;

fn random_spline(rng: &mut Rng, rational: bool) -> Curve {
    let order = rng.int(2, 5);
    let n = rng.int(order, order + 6);
    let pts: Vec<DVec3> = (0..n)
        .map(|_| {
            DVec3::new(
                rng.range(-5.0, 5.0),
                rng.range(-5.0, 5.0),
                if rational { 0.0 } else { rng.range(-1.0, 1.0) },
            )
        })
        .collect();
    let inner = n - order;
    let mut knots = vec![0.0; order];
    let mut interior: Vec<f64> = (0..inner)
        .map(|_| (rng.range(0.05, 0.95) * 20.0).round() / 20.0)
        .collect();
    interior.sort_by(f64::total_cmp);
    knots.extend(interior);
    knots.extend(vec![1.0; order]);
    if rational {
        let w: Vec<f64> = (0..n).map(|_| rng.range(0.3, 3.0)).collect();
        Nurbs::try_new(pts, w, knots, order)
            .map(Curve::Nurbs)
            .unwrap_or_else(|_| random_spline(rng, rational))
    } else {
        BSpline::try_new(pts, knots, order)
            .map(Curve::BSpline)
            .unwrap_or_else(|_| random_spline(rng, rational))
    }
}

/// The largest distance between the two curves at the same parameters (dense samples).
fn moved(a: &Curve, b: &Curve) -> f64 {
    let (t0, t1) = a.domain();
    (0..=2000)
        .map(|i| {
            let t = t0 + (t1 - t0) * f64::from(i) / 2000.0;
            (a.eval(t) - b.eval(t)).length()
        })
        .fold(0.0, f64::max)
}

#[test]
fn an_inserted_knot_comes_out_again_exactly() {
    let mut rng = Rng::new(11);
    for _ in 0..200 {
        let rational = rng.unit() < 0.5;
        let c = random_spline(&mut rng, rational);
        let u = (rng.range(0.1, 0.9) * 1000.0).round() / 1000.0;
        let inserted = match &c {
            Curve::BSpline(b) => b.insert_knot(u).map(Curve::BSpline),
            Curve::Nurbs(n) => n.insert_knot(u).map(Curve::Nurbs),
            _ => unreachable!(),
        };
        let Ok(inserted) = inserted else { continue };
        let r = remove_knot(&inserted, u, 1, 0.0).expect("an inserted knot is removable");
        assert!(moved(&r.curve, &c) <= 1e-9, "{}", moved(&r.curve, &c));
        assert_eq!(r.curve.control_points().len(), c.control_points().len());
    }
}

#[test]
fn a_removal_never_moves_the_curve_past_its_bound_or_the_tolerance() {
    // A knot inserted, then the control points around it moved by a random amount: the
    // removal moves the curve by about that much — within some tolerances, past others.
    let mut rng = Rng::new(48);
    let (mut removed, mut refused) = (0, 0);
    for _ in 0..600 {
        let rational = rng.unit() < 0.5;
        let c = random_spline(&mut rng, rational);
        let u = (rng.range(0.1, 0.9) * 1000.0).round() / 1000.0;
        let nudge = [1e-4, 1e-2, 0.3][rng.int(0, 2)];
        let bumped = match &c {
            Curve::BSpline(b) => b.insert_knot(u).ok().and_then(|b| {
                let mut pts = b.points().to_vec();
                let i = b.knots().span(u).min(pts.len() - 1);
                pts[i] += DVec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), 0.0) * nudge;
                BSpline::try_new(pts, b.knots().knots().to_vec(), b.order())
                    .ok()
                    .map(Curve::BSpline)
            }),
            Curve::Nurbs(n) => n.insert_knot(u).ok().and_then(|n| {
                let mut pts = n.points().to_vec();
                let i = n.knots().span(u).min(pts.len() - 1);
                pts[i] += DVec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), 0.0) * nudge;
                Nurbs::try_new(
                    pts,
                    n.weights().to_vec(),
                    n.knots().knots().to_vec(),
                    n.order(),
                )
                .ok()
                .map(Curve::Nurbs)
            }),
            _ => unreachable!(),
        };
        let Some(bumped) = bumped else { continue };
        let tol = [1e-3, 0.05, 0.5][rng.int(0, 2)];
        match remove_knot(&bumped, u, 1, tol) {
            Ok(r) => {
                removed += 1;
                let m = moved(&bumped, &r.curve);
                assert!(r.error <= tol, "bound {} over {tol}", r.error);
                assert!(
                    m <= r.error * (1.0 + 1e-12) + 1e-12,
                    "moved {m}, bound {}",
                    r.error
                );
            }
            Err(OpError::WouldMove {
                bound, tolerance, ..
            }) => {
                refused += 1;
                assert!(bound > tolerance);
            }
            Err(OpError::NotAKnot { .. }) => {}
            Err(e) => panic!("{e}"),
        }
    }
    assert!(
        removed > 60 && refused > 60,
        "{removed} removed, {refused} refused"
    );
}

#[test]
fn what_cannot_be_removed_is_refused_naming_it() {
    let circle = Curve::Nurbs(Nurbs::circle(DVec3::ZERO, 1.0).expect("circle"));
    let e = remove_knot(&circle, 0.25, 1, 1e-6).unwrap_err();
    assert!(matches!(e, OpError::WouldMove { .. }), "{e}");
    assert!(
        e.to_string().contains("knot 0.25") && e.to_string().contains("proven bound"),
        "{e}"
    );
    let e = remove_knot(&circle, 0.3, 1, 1.0).unwrap_err();
    assert!(e.to_string().contains("not an interior knot"), "{e}");
    let e = remove_knot(&circle, 0.25, 3, 1.0).unwrap_err();
    assert!(e.to_string().contains("there 2 time(s), not 3"), "{e}");
    let e = remove_knot(&circle, 0.25, 1, -1.0).unwrap_err();
    assert!(matches!(e, OpError::Tolerance(_)), "{e}");
    let bez = Curve::Bezier(Bezier::new(vec![DVec3::ZERO, DVec3::X]));
    let e = remove_knot(&bez, 0.5, 1, 1.0).unwrap_err();
    assert!(e.to_string().contains("not bezier curves"), "{e}");
}

/// A standard NUBMP curve (paper 001) is its B-spline: a knot inserted there comes out
/// again through it, the result a standard NUBMP curve on the original's points; with a
/// shape parameter set, the removal is refused until it is reset.
#[test]
fn a_standard_nubmp_curve_loses_a_knot_through_its_b_spline() {
    use splinescope_core::geom::Nubmp;
    let pts: Vec<DVec3> = [(0.0, 0.0), (1.0, 2.0), (2.0, -1.0), (3.0, 2.0), (4.0, 0.0)]
        .iter()
        .map(|&(x, y)| DVec3::new(x, y, 0.0))
        .collect();
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
    let original = Nubmp::try_new(pts.clone(), knots.clone(), 4).expect("nubmp");
    let spline = BSpline::try_new(pts.clone(), knots, 4).expect("spline");
    let inserted = spline.insert_knot(0.3).expect("insert");
    let with_knot = Nubmp::try_new(
        inserted.points().to_vec(),
        inserted.knots().knots().to_vec(),
        4,
    )
    .expect("nubmp with the knot");
    let r = remove_knot(&Curve::Nubmp(with_knot.clone()), 0.3, 1, 0.0).expect("removable");
    let Curve::Nubmp(back) = &r.curve else {
        panic!("a NUBMP curve comes back: {:?}", r.curve.family())
    };
    assert!(back.is_standard());
    for (a, b) in back.points().iter().zip(&pts) {
        assert!((*a - *b).length() <= 1e-12, "{a} vs {b}");
    }
    assert!(moved(&r.curve, &Curve::Nubmp(original)) <= 1e-12);
    // A knot that moves it: refused naming the bound, as for a B-spline.
    assert!(matches!(
        remove_knot(&Curve::Nubmp(with_knot.clone()), 0.5, 1, 0.0),
        Err(OpError::WouldMove { .. })
    ));
    // Shape parameters set: refused, saying to reset them.
    let mut shaped = with_knot;
    let j = (0..shaped.groups().len())
        .find(|&j| shaped.groups()[j].members.len() > 1)
        .expect("a group with a free parameter");
    let (i, absorber) = (shaped.groups()[j].members[0], shaped.groups()[j].members[1]);
    let value = shaped.group(j).expect("group").values[0] * 0.5;
    shaped.set_parameter(j, i, value, absorber).expect("set");
    let e = remove_knot(&Curve::Nubmp(shaped), 0.3, 1, 0.0).expect_err("refused");
    assert!(e.to_string().contains("reset the shape parameters"), "{e}");
}
