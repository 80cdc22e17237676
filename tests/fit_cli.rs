//! `splinescope fit`: points from CSV or JSON as a B-spline within a smoothing budget or a
//! path of cubics within a tolerance, written as a scene; bad files refused naming the
//! line, and nothing written.

mod common;

use splinescope_core::analysis::CurveAnalysis;
use splinescope_core::geom::Curve;
use splinescope_scene::format::Scene;

fn spiral_csv(dir: &std::path::Path) -> (std::path::PathBuf, Vec<glam::DVec3>) {
    let pts: Vec<glam::DVec3> = (0..400)
        .map(|i| {
            let a = f64::from(i) / 399.0 * std::f64::consts::TAU;
            glam::DVec3::new(a * a.cos(), a * a.sin(), 0.0)
        })
        .collect();
    let mut text = String::from("x,y\n");
    for p in &pts {
        text.push_str(&format!("{},{}\n", p.x, p.y));
    }
    let path = dir.join("spiral.csv");
    std::fs::write(&path, text).expect("write");
    (path, pts)
}

#[test]
fn fit_writes_a_scene_within_the_budget_or_the_tolerance() {
    let dir = common::out_dir("fit_cli");
    let (csv, pts) = spiral_csv(&dir);
    let out = dir.join("fit.json");
    for (flag, value) in [("--smoothing", "0.01"), ("--tolerance", "0.001")] {
        let run = common::run(&[
            "fit",
            csv.to_str().expect("utf-8"),
            flag,
            value,
            "-o",
            out.to_str().expect("utf-8"),
        ]);
        assert!(run.status.success(), "{}", common::text(&run));
        let scene = Scene::load(&out).expect("written");
        let curve = &scene.curves[0].curve;
        let a = CurveAnalysis::new(curve);
        let d: Vec<f64> = pts
            .iter()
            .map(|p| a.nearest(*p).expect("nearest").distance)
            .collect();
        if flag == "--tolerance" {
            assert!(matches!(curve, Curve::Path(_)));
            assert!(d.iter().all(|x| *x <= 0.001 * (1.0 + 1e-9)));
        } else {
            assert!(matches!(curve, Curve::BSpline(_)));
            // The nearest distances are at most the residuals at the fit's parameters.
            assert!(d.iter().map(|x| x * x).sum::<f64>() <= 0.01);
        }
    }
}

#[test]
fn fit_refuses_bad_points_naming_the_line() {
    let dir = common::out_dir("fit_cli");
    let out = dir.join("never.json");
    let _ = std::fs::remove_file(&out);
    for (name, text, says) in [
        ("bad.csv", "x,y\n1,2\n3,oops\n", "bad.csv:3"),
        ("four.csv", "1,2,3,4\n", "4 numbers"),
        ("bad.json", "[[1, 2], [3]]", "point 1 has 1 coordinates"),
        ("nan.csv", "0,0\n1,NaN\n2,0\n3,1\n", "not a finite point"),
    ] {
        let p = dir.join(name);
        std::fs::write(&p, text).expect("write");
        let run = common::run(&[
            "fit",
            p.to_str().expect("utf-8"),
            "-o",
            out.to_str().expect("utf-8"),
        ]);
        assert!(!run.status.success(), "{name}");
        assert!(
            String::from_utf8_lossy(&run.stderr).contains(says),
            "{name}: {}",
            common::text(&run)
        );
        assert!(!out.exists(), "{name} wrote a file");
    }
}
