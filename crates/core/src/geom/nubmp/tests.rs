//! NUBMP curves against their definitions: degree elevation, dual points, ranges.

use super::*;

fn paper() -> Nubmp {
    let pts = [
        (0., 0.),
        (1., 2.),
        (2., 2.5),
        (3., 0.5),
        (4., 2.),
        (5., 2.5),
        (6., 0.),
    ]
    .map(|(x, y)| DVec3::new(x, y, 0.0));
    Nubmp::try_new(
        pts.to_vec(),
        vec![0., 0., 0., 0., 0.3, 0.5, 0.89, 1., 1., 1., 1.],
        4,
    )
    .unwrap()
}

#[test]
fn standard_curve_is_the_bspline() {
    let n = paper();
    let b = BSpline::try_new(n.points().to_vec(), n.knots().knots().to_vec(), 4).unwrap();
    for k in 0..=200 {
        let t = f64::from(k) / 200.0;
        assert!((n.eval(t) - b.eval(t)).length() < 1e-13);
        assert!((n.eval_by_basis(t) - b.eval(t)).length() < 1e-13);
    }
    assert!(n.is_standard());
}

#[test]
fn groups_sum_to_one_and_are_non_negative() {
    let n = paper();
    assert_eq!(n.groups().len(), 11);
    for g in n.groups() {
        assert!(g.effective);
        let s: f64 = g.standard.iter().sum();
        assert!((s - 1.0).abs() < 1e-14, "{g:?}");
        assert!(g.standard.iter().all(|&c| c > 0.0));
    }
}

#[test]
fn setting_a_parameter_moves_one_dual_point_along_a_leg() {
    let mut n = paper();
    let j = (0..11).find(|&j| n.groups()[j].members.len() == 2).unwrap();
    let (i0, i1) = (n.groups()[j].members[0], n.groups()[j].members[1]);
    let before = n.dual_points().to_vec();
    n.set_parameter(j, i0, 0.9, i1).unwrap();
    let after = n.dual_points();
    for (jj, (a, b)) in before.iter().zip(after).enumerate() {
        if jj == j {
            let want = 0.9 * n.points()[i0] + 0.1 * n.points()[i1];
            assert!((*b - want).length() < 1e-14);
        } else {
            assert_eq!(a, b);
        }
    }
    // Errors leave the curve as it was.
    let snapshot = n.clone();
    assert!(n.set_parameter(j, i0, 1.5, i1).is_err());
    assert!(n.set_parameter(j, i0, -0.1, i1).is_err());
    assert!(matches!(
        n.set_parameter(j, 99, 0.5, i1),
        Err(GeomError::NotInGroup { .. })
    ));
    assert!(matches!(
        n.set_group(j, &[0.5, 0.6]),
        Err(GeomError::GroupSum { .. })
    ));
    assert!(matches!(
        n.set_group(99, &[1.0]),
        Err(GeomError::NoSuchGroup { .. })
    ));
    assert_eq!(n, snapshot);
}
