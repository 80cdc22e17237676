//! The editor's undo, gestures and structure edits, driven without a window.

use super::*;
use glam::DVec2;

use splinescope_core::geom::{Bezier, Nubmp, ParamCurve};
use splinescope_encoding::Color;
use splinescope_encoding::camera::{Camera, Camera2d};
use splinescope_scene::format::{Style, ViewSpec};

fn scene() -> Scene {
    let cubic = Bezier::new(vec![
        DVec3::ZERO,
        DVec3::new(1., 2., 0.),
        DVec3::new(3., 2., 0.),
        DVec3::new(4., 0., 0.),
    ]);
    let pts: Vec<DVec3> = (0..7)
        .map(|i| DVec3::new(f64::from(i), f64::from(i % 2), 0.0))
        .collect();
    let nub = Nubmp::try_new(pts, vec![0., 0., 0., 0., 0.3, 0.5, 0.89, 1., 1., 1., 1.], 4).unwrap();
    Scene {
        name: None,
        unit: None,
        background: Color::WHITE,
        samples_per_segment: Some(64),
        view: ViewSpec::Auto,
        curves: vec![
            SceneCurve {
                name: None,
                curve: Curve::Bezier(cubic),
                style: Style::default_for(0),
            },
            SceneCurve {
                name: None,
                curve: Curve::Nubmp(nub),
                style: Style::default_for(1),
            },
        ],
        annotations: Vec::new(),
    }
}

const VIEW: DVec2 = DVec2::new(800.0, 600.0);

fn camera() -> Camera {
    Camera::Ortho2d(Camera2d {
        center: DVec2::new(2.0, 1.0),
        pixels_per_unit: 50.0,
    })
}

#[test]
fn picking_prefers_control_points_then_curves() {
    let e = Editor::new(scene(), None);
    let cam = camera();
    let px = cam.pixel_from_world(DVec3::new(1., 2., 0.), VIEW).unwrap();
    assert_eq!(
        e.pick(&cam, VIEW, px + DVec2::new(3.0, 0.0), 8.0, true),
        Some(Hit::Point {
            curve: 0,
            index: 1,
            at: DVec3::new(1., 2., 0.)
        })
    );
    // A point on the cubic far from its control points.
    let on = Bezier::new(scene().curves[0].curve.control_points().to_vec()).eval(0.5);
    let px = cam.pixel_from_world(on, VIEW).unwrap();
    match e.pick(&cam, VIEW, px, 8.0, true) {
        Some(Hit::Curve { curve: 0, t, .. }) => assert!((t - 0.5).abs() < 1e-6),
        other => panic!("{other:?}"),
    }
    assert_eq!(e.pick(&cam, VIEW, DVec2::new(5.0, 5.0), 8.0, true), None);
}

#[test]
fn every_edit_is_undoable_and_redoable() {
    let original = scene();
    let mut e = Editor::new(original.clone(), None);
    e.begin_point_drag(0, 1);
    e.drag_to(DVec3::new(1.5, 3.0, 0.0));
    e.drag_to(DVec3::new(2.0, 3.5, 0.0));
    e.finish();
    let after_drag = e.scene().clone();
    assert_eq!(
        after_drag.curves[0].curve.control_points()[1],
        DVec3::new(2.0, 3.5, 0.0)
    );
    // A NUBMP point keeps its shape parameters.
    let mut nub = match &e.scene().curves[1].curve {
        Curve::Nubmp(n) => n.clone(),
        _ => unreachable!(),
    };
    nub.set_group(4, &[0.3, 0.7]).unwrap();
    e.set_curve(1, Curve::Nubmp(nub.clone()), "group 4");
    nub.set_group(4, &[0.35, 0.65]).unwrap();
    e.set_curve(1, Curve::Nubmp(nub), "group 4");
    e.begin_point_drag(1, 3);
    e.drag_to(DVec3::new(3.0, 2.0, 0.0));
    e.finish();
    match &e.scene().curves[1].curve {
        Curve::Nubmp(n) => assert_eq!(n.groups()[4].values, vec![0.35, 0.65]),
        _ => unreachable!(),
    }
    // Three edits: the drag, the slider (one edit), the NUBMP drag.
    assert_eq!(e.history_len(), (3, 0));
    assert!(e.undo());
    assert!(e.undo());
    assert_eq!(e.scene(), &after_drag);
    assert!(e.undo());
    assert_eq!(e.scene(), &original);
    assert!(!e.undo());
    assert!(e.redo());
    assert_eq!(e.scene(), &after_drag);
    assert_eq!(e.history_len(), (1, 2));
    // A new edit drops the redo branch.
    e.begin_point_drag(0, 2);
    e.drag_to(DVec3::new(3.0, 1.0, 0.0));
    e.finish();
    assert_eq!(e.history_len(), (2, 0));
}

#[test]
fn pulling_a_curve_passes_it_through_the_pointer() {
    let mut e = Editor::new(scene(), None);
    e.begin_pull(0, 0.4).unwrap();
    let target = DVec3::new(1.5, 2.5, 0.0);
    e.drag_to(DVec3::new(1.4, 2.2, 0.0));
    e.drag_to(target);
    e.finish();
    assert!((e.scene().curves[0].curve.eval(0.4) - target).length() < 1e-12);
    assert!(
        e.begin_pull(1, 0.4).is_err(),
        "NUBMP curves are edited by their points"
    );
    assert!(e.begin_pull(0, 0.0).is_err(), "the ends are fixed");
}

#[test]
fn pulling_a_rational_curve_keeps_its_weights_and_undoes() {
    let mut sc = scene();
    let circle = splinescope_core::geom::Nurbs::circle(DVec3::ZERO, 2.0).unwrap();
    sc.curves[1].curve = Curve::Nurbs(circle.clone());
    let mut e = Editor::new(sc, None);
    assert!(e.can_pull(1));
    e.begin_pull(1, 0.3).unwrap();
    let target = DVec3::new(-0.5, 2.8, 0.0);
    e.drag_to(DVec3::new(-0.4, 2.4, 0.0));
    e.drag_to(target);
    e.finish();
    let Curve::Nurbs(pulled) = &e.scene().curves[1].curve else {
        panic!("still a NURBS curve");
    };
    assert!((pulled.eval(0.3) - target).length() < 1e-12);
    assert_eq!(pulled.weights(), circle.weights());
    assert!(e.undo());
    assert_eq!(e.scene().curves[1].curve, Curve::Nurbs(circle));
}

#[test]
fn saving_is_atomic_and_tracks_unsaved_changes() {
    let dir = std::env::temp_dir().join(format!("splinescope-edit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.json");
    let mut e = Editor::new(scene(), Some(path.clone()));
    assert!(!e.is_dirty());
    e.begin_point_drag(0, 1);
    e.drag_to(DVec3::new(1.0, 3.0, 0.0));
    assert!(e.is_dirty());
    assert_eq!(e.save(None).unwrap(), path);
    assert!(!e.is_dirty());
    let back = Scene::load(&path).unwrap();
    assert_eq!(back.curves[0].curve, e.scene().curves[0].curve);
    e.undo();
    assert!(e.is_dirty());
    e.redo();
    assert!(!e.is_dirty());
    // No leftover temporary files.
    let entries: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert_eq!(entries.len(), 1);
    std::fs::remove_dir_all(&dir).unwrap();
    let mut unsaved = Editor::new(scene(), None);
    assert!(unsaved.save(None).is_err());
}

#[test]
fn invalid_drags_leave_the_curve_and_say_why() {
    let mut e = Editor::new(scene(), None);
    e.begin_point_drag(0, 1);
    e.drag_to(DVec3::new(f64::NAN, 0.0, 0.0));
    assert!(e.message.is_some());
    assert_eq!(e.scene(), &scene());
}

#[test]
fn a_point_past_the_gpu_maximum_degree_is_refused_where_it_is_inserted() {
    let mut ed = Editor::new(scene(), None);
    let max = splinescope_gpu::layout::MAX_GPU_DEGREE;
    // Insert points until the cubic reaches the maximum: each is accepted.
    for _ in 3..max {
        ed.insert_point(0, DVec3::new(2.0, 1.5, 0.0))
            .expect("under the maximum");
    }
    let at_max = ed.scene().curves[0].clone();
    assert_eq!(at_max.curve.control_points().len(), max + 1);
    let undo_depth = ed.history.len();
    // One more would be undrawable: refused, the curve and the history as they were.
    let e = ed.insert_point(0, DVec3::new(2.0, 1.5, 0.0)).unwrap_err();
    assert!(
        matches!(e, EditError::Undrawable { degree, .. } if degree == max + 1),
        "{e}"
    );
    assert!(e.to_string().contains("kept as it was"), "{e}");
    assert_eq!(ed.scene().curves[0], at_max);
    assert_eq!(ed.history.len(), undo_depth);
}

#[test]
fn a_failed_save_is_a_warning_that_says_where_the_edits_are() {
    // No file yet: the edits are in the window only.
    let mut ed = Editor::new(scene(), None);
    ed.set_point(0, 1, DVec3::new(1.0, 3.0, 0.0)).unwrap();
    let nowhere = std::path::Path::new("/nonexistent-directory/scene.json");
    assert!(ed.save(Some(nowhere)).is_err());
    let w = ed.warning.clone().expect("a warning");
    assert!(
        w.contains("nonexistent-directory") && w.contains("this window only"),
        "{w}"
    );
    // A scene with a file: its recovery file holds the edits when the save fails.
    let dir = std::env::temp_dir().join(format!("ed-warning-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("s.json");
    let mut ed = Editor::new(scene(), None);
    ed.save(Some(&path)).expect("saved");
    ed.set_point(0, 1, DVec3::new(1.0, 3.0, 0.0)).unwrap();
    assert!(recovery_path(&path).exists());
    assert!(ed.save(Some(nowhere)).is_err());
    let w = ed.warning.clone().expect("a warning");
    assert!(
        w.contains(&recovery_path(&path).display().to_string()),
        "{w}"
    );
    // A save that succeeds clears it.
    ed.save(Some(&path)).expect("saved");
    assert!(ed.warning.is_none());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Curves replaced from outside during a drag (a solver run on each move): the drag
/// goes on over them, and the gesture with the replacement is one undo step back to the
/// scene before the drag; outside a drag a replacement is its own undo step.
#[test]
fn curves_replaced_during_a_drag_fold_into_the_drag() {
    let mut e = Editor::new(scene(), None);
    let start = e.scene().curves.clone();
    e.begin_point_drag(0, 1);
    e.drag_to(DVec3::new(1.5, 2.5, 0.0));
    // What a callback hands back: the other end point moved too.
    let mut replaced = e.scene().curves.clone();
    replaced[0].curve = replaced[0]
        .curve
        .with_control_point(3, DVec3::new(5.0, 0.0, 0.0))
        .unwrap();
    e.replace_curves(replaced);
    assert!(e.is_open(), "the drag goes on");
    e.drag_to(DVec3::new(2.0, 3.0, 0.0));
    let pts = e.scene().curves[0].curve.control_points().to_vec();
    assert_eq!(
        pts[1],
        DVec3::new(2.0, 3.0, 0.0),
        "the drag moved its point"
    );
    assert_eq!(pts[3], DVec3::new(5.0, 0.0, 0.0), "the replacement stayed");
    assert_eq!(e.selected, Some(0));
    assert_eq!(e.selected_point, Some(1));
    e.finish();
    assert_eq!(e.history_len(), (1, 0), "one edit for the whole gesture");
    assert!(e.undo());
    assert_eq!(e.scene().curves, start, "undo goes back to before the drag");
    assert!(e.redo());
    assert_eq!(
        e.scene().curves[0].curve.control_points()[3],
        DVec3::new(5.0, 0.0, 0.0)
    );

    // Outside a drag: one edit; replacing with the same curves records nothing.
    let mut e = Editor::new(scene(), None);
    let mut fewer = e.scene().curves.clone();
    fewer.pop();
    e.selected = Some(1);
    e.replace_curves(fewer.clone());
    assert_eq!(e.scene().curves, fewer);
    assert_eq!(e.selected, None, "the selected curve is gone");
    e.replace_curves(fewer);
    assert_eq!(e.history_len(), (1, 0));
    assert!(e.undo());
    assert_eq!(e.scene().curves, start);

    // A drag whose point the new curves lack is committed first, then replaced.
    let mut e = Editor::new(scene(), None);
    e.begin_point_drag(1, 6);
    e.drag_to(DVec3::new(6.0, 2.0, 0.0));
    let mut short = start.clone();
    short.truncate(1);
    e.replace_curves(short.clone());
    assert!(!e.is_open());
    assert_eq!(e.history_len(), (2, 0));
    assert_eq!(e.scene().curves, short);

    // Esc during a folded drag restores the scene from before the drag.
    let mut e = Editor::new(scene(), None);
    e.begin_point_drag(0, 2);
    e.drag_to(DVec3::new(3.0, 3.0, 0.0));
    let mut other = e.scene().curves.clone();
    other[1].name = Some("renamed".into());
    e.replace_curves(other);
    assert!(e.cancel());
    assert_eq!(e.scene().curves, start);
    assert_eq!(e.history_len(), (0, 0));
}
