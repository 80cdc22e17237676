//! The `path` family end to end: a scene's paths read, measured against closed forms,
//! written back exactly, and bad paths refused naming the segment or the joint.

use std::f64::consts::PI;

use splinescope_core::analysis::CurveAnalysis;
use splinescope_core::geom::{Curve, Family, Lower, ParamCurve};
use splinescope_scene::format::{Scene, from_json_str, to_json_string};

fn paths() -> Scene {
    Scene::load(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/paths.json"
    )))
    .expect("scenes/paths.json")
}

#[test]
fn a_circle_of_four_rational_quarter_arcs_has_the_circles_length_and_area() {
    let scene = paths();
    let circle = &scene.curves[0].curve;
    assert_eq!(circle.family(), "path");
    let a = CurveAnalysis::new(circle);
    let r = 2.0;
    let length = a.length(0.0, 4.0, 1e-13).expect("length");
    assert!(
        (length.value - 2.0 * PI * r).abs() <= 1e-12,
        "length {} against 2πr = {}",
        length.value,
        2.0 * PI * r
    );
    let area = a.signed_area().expect("area");
    assert!((area - PI * r * r).abs() <= 1e-12, "area {area}");
    // Every point at distance r from the centre (4, 3), joints included.
    for k in 0..=400 {
        let t = 4.0 * f64::from(k) / 400.0;
        let p = circle.eval(t);
        let d = ((p.x - 4.0).hypot(p.y - 3.0) - r).abs();
        assert!(d <= 4e-15 * r, "t = {t}: {p} is {d} off the circle");
    }
}

#[test]
fn segments_are_kept_exactly_and_written_back_bit_for_bit() {
    let scene = paths();
    let text = to_json_string(&scene);
    let back = from_json_str(&text).expect("written scene reads back");
    for (a, b) in scene.curves.iter().zip(&back.curves) {
        let (Curve::Path(pa), Curve::Path(pb)) = (&a.curve, &b.curve) else {
            panic!("paths stay paths");
        };
        assert_eq!(pa, pb);
        assert_eq!(pa.is_closed(), pb.is_closed());
    }
    let Curve::Path(open) = &scene.curves[1].curve else {
        panic!("a path")
    };
    let degrees: Vec<usize> = open.segments().iter().map(|s| s.degree()).collect();
    assert_eq!(degrees, [1, 2, 3, 5], "each segment as given");
    // Lowered one for one, segment k on [k, k + 1], its points as given.
    for (k, (s, l)) in open.segments().iter().zip(open.lower()).enumerate() {
        assert_eq!((l.t0, l.t1), (k as f64, (k + 1) as f64));
        assert_eq!(l.bezier.points(), s.points.as_slice());
    }
    // The shared end points are listed once: 2 + 2 + 3 + 5 points after the first.
    assert_eq!(open.control_points().len(), 1 + 1 + 2 + 3 + 5);
}

/// A one-curve scene around `curve`.
fn scene_with(curve: &str) -> String {
    format!(r#"{{"version": 1, "curves": [{curve}]}}"#)
}

#[test]
fn bad_paths_are_refused_naming_the_segment_or_the_joint() {
    let cases = [
        (
            r#"{"type": "path", "segments": [{"points": [[0, 0], [1, 0]]}, {"points": [[1, 0.001], [2, 0]]}]}"#,
            "curves[0].segments",
            "joint 0",
        ),
        (
            r#"{"type": "path", "segments": [{"points": [[0, 0], [1, 0]]}], "closed": true}"#,
            "curves[0].segments",
            "joint 0",
        ),
        (
            r#"{"type": "path", "segments": []}"#,
            "curves[0].segments",
            "at least 1 segment",
        ),
        (
            r#"{"type": "path", "segments": [{"points": [[0, 0], [1, 0]]}, {"points": [[1, 0], [2, 0]], "weights": [1, 0]}]}"#,
            "curves[0].segments[1].weights[1]",
            "weight 0",
        ),
        (
            r#"{"type": "path", "segments": [{"points": [[0, 0], [1, 0]]}, {"points": [[1, 0], [2, 0]], "weights": [1]}]}"#,
            "curves[0].segments[1].weights",
            "1 weights for 2",
        ),
        (
            r#"{"type": "path", "segments": [{"points": [[0, 0]]}]}"#,
            "curves[0].segments[0].points",
            "at least 2 points",
        ),
        (
            r#"{"type": "path", "segments": [{"points": [[0, 0], [1, 0]], "knots": [0]}]}"#,
            "curves[0].segments[0].knots",
            "",
        ),
        (r#"{"type": "path"}"#, "curves[0].segments", ""),
        (
            r#"{"type": "path", "segments": [{"points": [[0, 0], [1, 0]]}], "closed": 1}"#,
            "curves[0].closed",
            "",
        ),
    ];
    for (curve, path, words) in cases {
        let e = from_json_str(&scene_with(curve)).expect_err(curve);
        assert_eq!(e.path, path, "{curve}: {e}");
        assert!(e.to_string().contains(words), "{curve}: {e}");
    }
}

#[test]
fn moving_a_joint_moves_both_segments_and_keeps_the_path_joined() {
    let scene = paths();
    let c = &scene.curves[1].curve;
    // Point 1 is where the line meets the quadratic.
    let moved = c
        .with_control_point(1, glam::DVec3::new(9.5, 2.0, 0.0))
        .expect("moved");
    let Curve::Path(p) = &moved else {
        panic!("a path")
    };
    assert_eq!(p.segments()[0].points[1], p.segments()[1].points[0]);
    assert_eq!(moved.eval(1.0), glam::DVec3::new(9.5, 2.0, 0.0));
    assert_eq!(moved.domain(), (0.0, 4.0));
}

#[test]
fn a_piece_between_two_parameters_traces_the_same_points() {
    // Every path of the scene (rational quarter arcs, mixed degrees): the piece from t0 to
    // t1 is open and, at each of its segments' local parameters, the original's point at
    // the matching parameter — the cut segments by de Casteljau, homogeneous for the
    // rational ones; its length is the original's between t0 and t1.
    let scene = paths();
    for sc in &scene.curves {
        let Curve::Path(p) = &sc.curve else {
            continue;
        };
        let end = p.segments().len() as f64;
        for (t0, t1) in [
            (0.0, end),
            (0.25, 0.75),
            (0.3, end - 0.4),
            (1.0, 2.0),
            (0.5, 1.0),
        ] {
            if t1 > end {
                continue;
            }
            let piece = p.between(t0, t1).expect("a piece");
            assert!(!piece.is_closed());
            let (k0, k1) = (t0.floor() as usize, (t1.ceil() as usize).max(1) - 1);
            assert_eq!(piece.segments().len(), k1 - k0 + 1, "{t0}..{t1}");
            for (j, _) in piece.segments().iter().enumerate() {
                let k = k0 + j;
                let a = if j == 0 { t0 - k as f64 } else { 0.0 };
                let b = if k == k1 { t1 - k as f64 } else { 1.0 };
                for u in [0.0_f64, 0.2, 0.5, 0.9, 1.0] {
                    let got = piece.eval(j as f64 + u.min(0.999_999_999_999));
                    let want = p.eval(k as f64 + a + (b - a) * u.min(0.999_999_999_999));
                    assert!(
                        (got - want).length() <= 1e-12 * (1.0 + want.length()),
                        "{t0}..{t1}, segment {j} at {u}: {got} against {want}"
                    );
                }
            }
            let whole = CurveAnalysis::new(&sc.curve)
                .length(t0, t1, 1e-12)
                .expect("length");
            let cut = CurveAnalysis::new(&piece)
                .length(0.0, piece.segments().len() as f64, 1e-12)
                .expect("length");
            assert!((whole.value - cut.value).abs() <= 1e-10, "{t0}..{t1}");
        }
        // Outside the domain, or backwards: refused.
        assert!(p.between(-0.5, 1.0).is_err());
        assert!(p.between(0.6, 0.4).is_err());
    }
}
