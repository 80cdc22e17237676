//! `splinescope op`: each curve as cubics or quadratics within the tolerance, written
//! after its original (or in its place with `--replace`), named after it and the
//! operation; bad arguments refused naming them, and nothing written then.

mod common;

use splinescope_core::analysis::CurveAnalysis;
use splinescope_core::geom::{Curve, ParamCurve};
use splinescope_scene::format::Scene;

fn paths() -> String {
    format!("{}/scenes/paths.json", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn op_writes_each_approximation_after_its_original_within_the_tolerance() {
    let dir = common::out_dir("op_cli");
    let out = dir.join("quadratics.json");
    let run = common::run(&[
        "op",
        &paths(),
        "--to-quadratics",
        "0.01",
        "-o",
        out.to_str().expect("utf-8"),
    ]);
    assert!(run.status.success(), "{}", common::text(&run));
    let original = Scene::load(std::path::Path::new(&paths())).expect("paths");
    let made = Scene::load(&out).expect("written");
    assert_eq!(made.curves.len(), 2 * original.curves.len());
    for (k, o) in original.curves.iter().enumerate() {
        let (a, b) = (&made.curves[2 * k], &made.curves[2 * k + 1]);
        assert_eq!(a.curve, o.curve);
        assert_eq!(
            b.name.as_deref(),
            Some(format!("{} · to quadratics 0.01", o.name.as_deref().expect("named")).as_str())
        );
        let Curve::Path(p) = &b.curve else {
            panic!("a path")
        };
        assert!(p.segments().iter().all(|s| s.degree() == 2));
        // Every sample of the result within the tolerance of the original (the nearest
        // point, §10).
        let ao = CurveAnalysis::new(&o.curve);
        let (t0, t1) = b.curve.domain();
        for i in 0..=300 {
            let t = t0 + (t1 - t0) * f64::from(i) / 300.0;
            let d = ao.nearest(b.curve.eval(t)).expect("nearest").distance;
            assert!(d <= 0.01, "{:?} at {t}: {d}", b.name);
        }
    }
    // --replace: the results in place; --curve: one curve only.
    let out2 = dir.join("replaced.json");
    let run = common::run(&[
        "op",
        &paths(),
        "--curve",
        "1",
        "--to-cubics",
        "0.001",
        "--replace",
        "-o",
        out2.to_str().expect("utf-8"),
    ]);
    assert!(run.status.success(), "{}", common::text(&run));
    let replaced = Scene::load(&out2).expect("written");
    assert_eq!(replaced.curves.len(), original.curves.len());
    assert_eq!(replaced.curves[0].curve, original.curves[0].curve);
    let Curve::Path(p) = &replaced.curves[1].curve else {
        panic!("a path")
    };
    assert!(p.segments().iter().all(|s| s.degree() == 3));
}

#[test]
fn op_refuses_bad_arguments_and_writes_nothing() {
    let dir = common::out_dir("op_cli");
    let out = dir.join("never.json");
    let o = out.to_str().expect("utf-8");
    for (args, says) in [
        (vec!["op", &paths(), "-o", o], "--to-cubics"),
        (
            vec!["op", &paths(), "--to-cubics", "0", "-o", o],
            "tolerance 0",
        ),
        (
            vec!["op", &paths(), "--to-quadratics", "nan", "-o", o],
            "must be a finite number",
        ),
        (
            vec!["op", &paths(), "--to-cubics", "1", "--curve", "9", "-o", o],
            "--curve 9",
        ),
        (
            vec!["op", &paths(), "--to-cubics", "1e-300", "-o", o],
            "pieces within tolerance",
        ),
        (
            vec!["op", &paths(), "--offset", "0.5", "-o", o],
            "needs --tolerance",
        ),
        (
            vec![
                "op",
                &paths(),
                "--offset",
                "inf",
                "--tolerance",
                "0.01",
                "-o",
                o,
            ],
            "offset distance inf",
        ),
        (
            vec![
                "op",
                &paths(),
                "--offset",
                "0.1",
                "--tolerance",
                "0.01",
                "--join",
                "miter",
                "--miter-limit",
                "0.5",
                "-o",
                o,
            ],
            "miter limit 0.5",
        ),
        (
            vec![
                "op",
                &paths(),
                "--offset",
                "0.1",
                "--tolerance",
                "0.01",
                "--trim",
                "--caps",
                "round",
                "-o",
                o,
            ],
            "cannot be used with",
        ),
        (
            vec![
                "op",
                &paths(),
                "--to-cubics",
                "0.1",
                "--tolerance",
                "0.01",
                "-o",
                o,
            ],
            "--tolerance is for --offset and --remove-knot",
        ),
    ] {
        let _ = std::fs::remove_file(&out);
        let run = common::run(&args);
        assert!(!run.status.success(), "{args:?}");
        assert!(
            String::from_utf8_lossy(&run.stderr).contains(says),
            "{args:?}: {}",
            common::text(&run)
        );
        assert!(!out.exists(), "{args:?} wrote a file");
    }
    let run = common::run(&["op", &paths(), "--to-cubics", "1", "-o", &paths()]);
    assert!(String::from_utf8_lossy(&run.stderr).contains("the output is the scene being read"));
}

#[test]
fn op_removes_a_knot_within_the_tolerance_or_names_the_bound() {
    let dir = common::out_dir("op_cli");
    let scene = format!("{}/scenes/bsplines.json", env!("CARGO_MANIFEST_DIR"));
    let out = dir.join("removed.json");
    let o = out.to_str().expect("utf-8");
    let run = common::run(&[
        "op",
        &scene,
        "--curve",
        "0",
        "--remove-knot",
        "0.2",
        "--tolerance",
        "2",
        "-o",
        o,
    ]);
    assert!(run.status.success(), "{}", common::text(&run));
    let original = Scene::load(std::path::Path::new(&scene)).expect("scene");
    let made = Scene::load(&out).expect("written");
    let (before, after) = (&original.curves[0].curve, &made.curves[1].curve);
    assert_eq!(
        after.control_points().len(),
        before.control_points().len() - 1
    );
    // It moved by at most the tolerance (dense samples at the same parameters).
    let (t0, t1) = before.domain();
    let moved = (0..=1000)
        .map(|i| {
            let t = t0 + (t1 - t0) * f64::from(i) / 1000.0;
            (before.eval(t) - after.eval(t)).length()
        })
        .fold(0.0, f64::max);
    assert!(moved <= 2.0, "{moved}");
    let run = common::run(&[
        "op",
        &scene,
        "--curve",
        "0",
        "--remove-knot",
        "0.2",
        "--tolerance",
        "0.01",
        "-o",
        o,
    ]);
    assert!(!run.status.success());
    assert!(
        String::from_utf8_lossy(&run.stderr).contains("would move the curve by up to"),
        "{}",
        common::text(&run)
    );
    let run = common::run(&[
        "op",
        &scene,
        "--curve",
        "0",
        "--remove-knot",
        "0.5",
        "-o",
        o,
    ]);
    assert!(
        String::from_utf8_lossy(&run.stderr).contains("not an interior knot"),
        "{}",
        common::text(&run)
    );
}

#[test]
fn op_reduces_a_bezier_curves_degree_or_names_the_best_bound() {
    let dir = common::out_dir("op_cli");
    let gallery = format!("{}/scenes/gallery.json", env!("CARGO_MANIFEST_DIR"));
    let out = dir.join("reduced.json");
    let o = out.to_str().expect("utf-8");
    // The gallery's degree-5 curve: degree 4 is within 0.06 of it, not within 0.05.
    let run = common::run(&[
        "op",
        &gallery,
        "--curve",
        "3",
        "--reduce-degree",
        "0.06",
        "-o",
        o,
    ]);
    assert!(run.status.success(), "{}", common::text(&run));
    let made = Scene::load(&out).expect("written");
    assert_eq!(made.curves[4].curve.control_points().len(), 5);
    let run = common::run(&[
        "op",
        &gallery,
        "--curve",
        "3",
        "--reduce-degree",
        "0.05",
        "-o",
        o,
    ]);
    assert!(
        String::from_utf8_lossy(&run.stderr).contains("the closest, degree 4"),
        "{}",
        common::text(&run)
    );
    let run = common::run(&[
        "op",
        &gallery,
        "--curve",
        "4",
        "--reduce-degree",
        "0.05",
        "-o",
        o,
    ]);
    assert!(
        String::from_utf8_lossy(&run.stderr).contains("is for Bézier curves"),
        "{}",
        common::text(&run)
    );
}

#[test]
fn op_offsets_each_curve_within_the_tolerance_and_outlines_strokes() {
    let dir = common::out_dir("op_cli");
    let out = dir.join("offsets.json");
    let run = common::run(&[
        "op",
        &paths(),
        "--offset",
        "-0.25",
        "--tolerance",
        "0.001",
        "-o",
        out.to_str().expect("utf-8"),
    ]);
    assert!(run.status.success(), "{}", common::text(&run));
    let original = Scene::load(std::path::Path::new(&paths())).expect("paths");
    let made = Scene::load(&out).expect("written");
    assert_eq!(made.curves.len(), 2 * original.curves.len());
    for (k, o) in original.curves.iter().enumerate() {
        let b = &made.curves[2 * k + 1];
        assert_eq!(
            b.name.as_deref(),
            Some(format!("{} · offset -0.25", o.name.as_deref().expect("named")).as_str())
        );
        // Every sample of the offset is 0.25 from the original, within the tolerance
        // (away from kinks, where a round join keeps that distance too).
        let ao = CurveAnalysis::new(&o.curve);
        let (t0, t1) = b.curve.domain();
        for i in 0..=300 {
            let t = t0 + (t1 - t0) * f64::from(i) / 300.0;
            let d = ao.nearest(b.curve.eval(t)).expect("nearest").distance;
            assert!(d <= 0.25 + 0.001, "{:?} at {t}: {d}", b.name);
        }
    }
    // A stroke outline of a closed curve is two paths, both after their original.
    let ring = dir.join("ring.json");
    let run = common::run(&[
        "op",
        &paths(),
        "--curve",
        "0",
        "--offset",
        "0.2",
        "--tolerance",
        "0.001",
        "--caps",
        "butt",
        "--replace",
        "-o",
        ring.to_str().expect("utf-8"),
    ]);
    assert!(run.status.success(), "{}", common::text(&run));
    let made = Scene::load(&ring).expect("written");
    assert_eq!(made.curves.len(), original.curves.len() + 1);
    assert!(
        made.curves[0]
            .name
            .as_deref()
            .is_some_and(|n| n.ends_with("stroke outline 0.2 (1 of 2)"))
    );
    assert!(
        made.curves[1]
            .name
            .as_deref()
            .is_some_and(|n| n.ends_with("stroke outline 0.2 (2 of 2)"))
    );
    assert_eq!(made.curves[2].curve, original.curves[1].curve);
}
