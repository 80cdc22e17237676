//! Split, reverse and join, exact: the pieces of a split trace the curve (their points
//! are the curve's at the matching parameters, their lengths add up), a reversed curve is
//! the curve traced backwards (`C_r(a + b − t) = C(t)` where the family is kept), and
//! joined curves are one path with every segment kept; a parameter outside the domain
//! and curves that do not meet are refused.

use glam::DVec3;
use splinescope_core::analysis::CurveAnalysis;
use splinescope_core::geom::{
    BSpline, Bezier, Curve, ModifiedBezier, Nurbs, ParamCurve, RationalBezier,
};
use splinescope_core::ops::{OpError, as_path, join, reverse, split};

fn p(x: f64, y: f64) -> DVec3 {
    DVec3::new(x, y, 0.0)
}

fn curves() -> Vec<Curve> {
    let base = Bezier::new(vec![p(-3.0, 0.0), p(-2.0, 2.0), p(0.0, 2.0), p(1.0, 0.5)]);
    vec![
        Curve::Bezier(Bezier::new(vec![
            p(0.0, 0.0),
            p(4.0, 3.0),
            p(-1.0, 3.0),
            p(3.0, 0.0),
        ])),
        Curve::ModifiedBezier(ModifiedBezier::try_new(base, 0.4, p(0.0, 0.6)).expect("bump")),
        Curve::RationalBezier(
            RationalBezier::try_new(
                vec![p(-1.0, -4.0), p(0.0, -2.0), p(1.5, -4.5), p(3.0, -3.0)],
                vec![1.0, 3.0, 0.5, 2.0],
            )
            .expect("rational"),
        ),
        Curve::Nurbs(Nurbs::circle(p(3.0, 2.0), 1.5).expect("circle")),
        Curve::BSpline(
            BSpline::try_new(
                vec![
                    p(-4.0, 2.5),
                    p(-3.0, 3.5),
                    p(-2.0, 2.0),
                    p(-1.0, 3.5),
                    p(0.0, 2.5),
                    p(1.0, 0.0),
                ],
                vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 1.0, 1.0, 1.0, 1.0],
                4,
            )
            .expect("spline"),
        ),
    ]
}

fn length(c: &Curve) -> f64 {
    let (a, b) = c.domain();
    CurveAnalysis::new(c)
        .length(a, b, 1e-13)
        .expect("length")
        .value
}

#[test]
fn a_split_traces_the_curve_and_its_lengths_add_up() {
    for c in curves() {
        let (a, b) = c.domain();
        for f in [0.1, 0.37, 0.5, 0.9] {
            let t = a + f * (b - a);
            let (l, r) = split(&c, t).expect("split");
            let (la, lb) = l.domain();
            let (ra, rb) = r.domain();
            assert!((l.eval(la) - c.eval(a)).length() <= 1e-12, "{}", c.family());
            assert!((l.eval(lb) - c.eval(t)).length() <= 1e-12, "{}", c.family());
            assert!((r.eval(ra) - c.eval(t)).length() <= 1e-12, "{}", c.family());
            assert!((r.eval(rb) - c.eval(b)).length() <= 1e-12, "{}", c.family());
            // Every point of each piece on the curve: its nearest point is 0 away.
            let ac = CurveAnalysis::new(&c);
            for piece in [&l, &r] {
                let (pa, pb) = piece.domain();
                for i in 0..=20 {
                    let q = piece.eval(pa + (pb - pa) * f64::from(i) / 20.0);
                    assert!(
                        ac.nearest(q).expect("nearest").distance <= 1e-12,
                        "{}",
                        c.family()
                    );
                }
            }
            assert!(
                (length(&l) + length(&r) - length(&c)).abs() <= 1e-11,
                "{}",
                c.family()
            );
        }
        // At or beyond the ends: refused naming the parameter.
        for bad in [a, b, a - 1.0, f64::NAN] {
            let e = split(&c, bad).unwrap_err();
            assert!(matches!(e, OpError::Geom(_)), "{e}");
        }
    }
}

#[test]
fn a_reversed_curve_is_the_curve_traced_backwards() {
    for c in curves() {
        let r = reverse(&c).expect("reverse");
        let (a, b) = c.domain();
        if r.family() == c.family() {
            assert_eq!(r.domain(), (a, b));
            for i in 0..=50 {
                let t = a + (b - a) * f64::from(i) / 50.0;
                assert!(
                    (r.eval(a + b - t) - c.eval(t)).length() <= 1e-12,
                    "{}",
                    c.family()
                );
            }
        } else {
            // A path of the exact segments, backwards: same ends swapped, same length.
            let (ra, rb) = r.domain();
            assert!((r.eval(ra) - c.eval(b)).length() <= 1e-12);
            assert!((r.eval(rb) - c.eval(a)).length() <= 1e-12);
        }
        assert!((length(&r) - length(&c)).abs() <= 1e-11, "{}", c.family());
        // Twice: the curve again, at the same parameters.
        let back = reverse(&r).expect("reverse");
        let (ba, bb) = back.domain();
        for i in 0..=20 {
            let f = f64::from(i) / 20.0;
            let want = if r.family() == c.family() {
                c.eval(a + f * (b - a))
            } else {
                r.eval(r.domain().1 - f * (r.domain().1 - r.domain().0))
            };
            assert!(
                (back.eval(ba + f * (bb - ba)) - want).length() <= 1e-12,
                "{}",
                c.family()
            );
        }
    }
}

#[test]
fn joined_curves_are_one_path_and_a_gap_is_refused() {
    let a = Curve::Bezier(Bezier::new(vec![p(0.0, 0.0), p(1.0, 1.0), p(2.0, 0.0)]));
    let b = Curve::RationalBezier(
        RationalBezier::try_new(
            vec![p(2.0, 0.0), p(3.0, -1.0), p(4.0, 0.0)],
            vec![1.0, 2.0, 1.0],
        )
        .expect("rational"),
    );
    let c = Curve::Bezier(Bezier::new(vec![p(4.0, 0.0), p(2.0, -3.0), p(0.0, 0.0)]));
    let joined = join(&[a.clone(), b.clone(), c.clone()], true).expect("joined");
    assert!(joined.is_closed());
    assert_eq!(joined.segments().len(), 3);
    let path = Curve::Path(joined);
    assert!((length(&path) - (length(&a) + length(&b) + length(&c))).abs() <= 1e-11);
    let far = Curve::Bezier(Bezier::new(vec![p(9.0, 9.0), p(10.0, 9.0)]));
    let e = join(&[a.clone(), far], false).unwrap_err();
    assert!(e.to_string().contains("joint 0"), "{e}");
    assert!(matches!(join(&[], false), Err(OpError::NothingToJoin)));
    // A family as its exact path: the same points at every segment's parameters.
    let spline = &curves()[4];
    let path = as_path(spline).expect("path");
    assert!((Curve::Path(path).eval(0.0) - spline.eval(0.0)).length() == 0.0);
}
