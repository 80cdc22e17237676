//! Saving keeps the file's form: a scene opened, edited at one point and saved differs
//! from the original in that point only; unchanged curves, implicit styles and knot
//! shorthands stay as written; an unedited save rewrites nothing. Checked on every
//! shipped scene file and on hand-written ones, by comparing the files' lines and
//! reading the saved file back.

use std::path::{Path, PathBuf};

use glam::DVec3;
use splinescope_scene::format::{Scene, from_json_str, to_json_string, to_json_string_keeping};
use splinescope_viewer::edit::Editor;

/// Two scenes as their files would say (colours are written as 8-bit hex).
fn same_file(a: &Scene, b: &Scene) -> bool {
    to_json_string(a) == to_json_string(b)
}

/// The point that differs between two lines that are otherwise the same: its numbers
/// before and after (panics when anything outside that point's brackets differs).
fn changed_point(before: &str, after: &str) -> (Vec<f64>, Vec<f64>) {
    let prefix = before
        .bytes()
        .zip(after.bytes())
        .take_while(|(a, b)| a == b)
        .count();
    let open = before[..prefix].rfind('[').expect("a point");
    let close_b = open + before[open..].find(']').unwrap();
    let close_a = open + after[open..].find(']').unwrap();
    assert_eq!(&before[close_b..], &after[close_a..], "outside the point");
    let parse = |t: &str| serde_json::from_str::<Vec<f64>>(t).unwrap();
    (
        parse(&before[open..=close_b]),
        parse(&after[open..=close_a]),
    )
}

fn fresh_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("splinescope-keep-{tag}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The lines of `a` and `b` that differ (both files must have the same number of lines).
fn changed_lines(a: &str, b: &str) -> Vec<(String, String)> {
    let (la, lb): (Vec<&str>, Vec<&str>) = (a.lines().collect(), b.lines().collect());
    assert_eq!(la.len(), lb.len(), "line counts differ:\n{a}\n---\n{b}");
    la.iter()
        .zip(&lb)
        .filter(|(x, y)| x != y)
        .map(|(x, y)| ((*x).to_owned(), (*y).to_owned()))
        .collect()
}

/// Opens `path` in an editor, moves control point `point` of curve `curve` to `to`,
/// saves, and returns the saved text.
fn edit_one_point(path: &Path, curve: usize, point: usize, to: DVec3) -> (String, Scene) {
    let (scene, text) = Scene::read(path).unwrap();
    let mut e = Editor::of_file(scene, path.to_path_buf(), text);
    e.set_point(curve, point, to).unwrap();
    let edited = e.scene().clone();
    e.save(None).unwrap();
    (std::fs::read_to_string(path).unwrap(), edited)
}

#[test]
fn every_shipped_scene_edited_at_one_point_differs_in_that_point_only() {
    let dir = fresh_dir("shipped");
    let mut checked = 0;
    for entry in std::fs::read_dir("scenes").unwrap() {
        let src = entry.unwrap().path();
        if src.extension().is_none_or(|e| e != "json") {
            continue;
        }
        let original = std::fs::read_to_string(&src).unwrap();
        let scene = from_json_str(&original).unwrap();
        for (c, sc) in scene.curves.iter().enumerate() {
            let pts = sc.curve.control_points();
            // A point inside the polygon (the first and last are often on one line with
            // the bracket in hand-written files).
            let k = pts.len() / 2;
            let p = pts[k];
            let to = DVec3::new(p.x + 0.125, p.y - 2.5, p.z);
            let path = dir.join(src.file_name().unwrap());
            std::fs::write(&path, &original).unwrap();
            let (saved, edited) = edit_one_point(&path, c, k, to);
            assert!(
                same_file(&from_json_str(&saved).unwrap(), &edited),
                "{}: curve {c} reads back as edited",
                src.display()
            );
            let diff = changed_lines(&original, &saved);
            // A point is written once, except where a path's segments meet: there each
            // segment writes it.
            let copies = match &sc.curve {
                splinescope_core::geom::Curve::Path(path) => path
                    .segments()
                    .iter()
                    .map(|s| s.points.iter().filter(|&&q| q == p).count())
                    .sum(),
                _ => 1,
            };
            assert_eq!(diff.len(), copies, "{} curve {c}: {diff:#?}", src.display());
            for (before, after) in &diff {
                // Only the point's numbers changed on that line (hand-written files keep
                // several points on a line: the edited one is found by its old value).
                let coords = |v: DVec3| {
                    if v.z == 0.0 {
                        vec![v.x, v.y]
                    } else {
                        vec![v.x, v.y, v.z]
                    }
                };
                assert_eq!(
                    changed_point(before, after),
                    (coords(p), coords(to)),
                    "{} curve {c}: {before} → {after}",
                    src.display()
                );
            }
            checked += 1;
        }
    }
    assert!(checked > 30, "{checked} curves");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_unedited_save_rewrites_nothing_and_shorthands_and_implicit_styles_stay() {
    let dir = fresh_dir("hand");
    let path = dir.join("hand.json");
    // Written by hand: points inline, knots as a shorthand, no styles, keys in an
    // unusual order, numbers spelt 1.0 and 0.50.
    let original = r#"{
  "curves": [
    {"points": [[0, 0], [1.0, 2], [3, 2], [4, 0]], "type": "bezier"},
    {
      "type": "bspline",
      "order": 4,
      "knots": "clamped_uniform",
      "points": [[5, 0], [6, 2], [7, 0.50], [8, 2], [9, 0]]
    }
  ],
  "version": 1
}
"#;
    std::fs::write(&path, original).unwrap();
    let (scene, text) = Scene::read(&path).unwrap();
    let mut e = Editor::of_file(scene, path.clone(), text);
    e.save(None).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), original);

    let (saved, edited) = edit_one_point(&path, 1, 2, DVec3::new(7.0, 1.75, 0.0));
    assert!(same_file(&from_json_str(&saved).unwrap(), &edited));
    assert_eq!(
        saved,
        original.replace("[7, 0.50]", "[7, 1.75]"),
        "the shorthand, the other curve and every other spelling stay"
    );

    // A second save of the same edit changes nothing more.
    let (again, text) = Scene::read(&path).unwrap();
    assert!(same_file(&again, &edited));
    let mut e = Editor::of_file(again, path.clone(), text);
    e.save(None).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), saved);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn deleting_and_adding_curves_touch_only_their_own_lines() {
    let text = std::fs::read_to_string("scenes/bsplines.json").unwrap();
    let scene = from_json_str(&text).unwrap();
    // Delete the middle curve: the saved text is the original without its lines. The
    // third curve's implicit style now defaults to another colour, so it gains exactly
    // the style that keeps its own (three lines, and a comma on the line before).
    let mut fewer = scene.clone();
    fewer.curves.remove(1);
    let saved = to_json_string_keeping(&fewer, &text);
    assert!(same_file(&from_json_str(&saved).unwrap(), &fewer));
    let kept: Vec<&str> = text.lines().collect();
    let out: Vec<&str> = saved.lines().collect();
    let missing = kept.iter().filter(|l| !out.contains(l)).count();
    assert!(
        missing > 0 && out.iter().filter(|l| !kept.contains(l)).count() <= 4,
        "{saved}"
    );
    // Add a copy of the first curve at the end: everything before it is as it was.
    let mut more = scene.clone();
    let mut copy = more.curves[0].clone();
    copy.curve = copy
        .curve
        .with_control_points(
            copy.curve
                .control_points()
                .iter()
                .map(|p| *p + DVec3::new(0.0, 10.0, 0.0))
                .collect(),
        )
        .unwrap();
    more.curves.push(copy);
    let saved = to_json_string_keeping(&more, &text);
    assert!(same_file(&from_json_str(&saved).unwrap(), &more));
    let cut = text.rfind("    }").unwrap();
    assert!(saved.starts_with(&text[..cut]), "{saved}");
}
