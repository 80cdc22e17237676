//! The viewer as an editor that loses nothing: Esc cancels instead of quitting, closing
//! with unsaved changes asks, a recovery file holds unsaved edits across a kill, the
//! title marks unsaved changes, structural edits (curves added, duplicated, deleted;
//! points inserted, removed, typed) are each one undoable edit, refused values change
//! nothing, and picking takes the curve drawn on top. Driven through the window-free
//! interaction model as the window drives it; expected values come from the scene before
//! the input, the camera's own maps, and the curves' exact evaluation.

use std::path::{Path, PathBuf};

use glam::{DVec2, DVec3};
use splinescope_core::geom::{BSpline, Bezier, Curve, Nubmp, ParamCurve};
use splinescope_scene::format::{Scene, to_json_string};
use splinescope_viewer::edit::{Editor, Hit, legacy_recovery_path, recovery_dir, recovery_path};
use splinescope_viewer::interaction::{
    Answer, Button, Input, Interaction, Key, Pending, Prompt, Response, Template,
};

const VIEWPORT: DVec2 = DVec2::new(1000.0, 700.0);

fn cubic() -> Curve {
    Curve::Bezier(Bezier::new(vec![
        DVec3::ZERO,
        DVec3::new(1.0, 2.0, 0.0),
        DVec3::new(3.0, 2.0, 0.0),
        DVec3::new(4.0, 0.0, 0.0),
    ]))
}

fn bspline() -> Curve {
    let pts: Vec<DVec3> = (0..6)
        .map(|i| DVec3::new(f64::from(i), f64::from(i % 2) + 3.0, 0.0))
        .collect();
    Curve::BSpline(
        BSpline::try_new(pts, vec![0., 0., 0., 0., 0.3, 0.6, 1., 1., 1., 1.], 4).unwrap(),
    )
}

fn scene(curves: Vec<Curve>) -> Scene {
    Scene::of_curves(curves)
}

fn model(s: Scene, path: Option<PathBuf>) -> Interaction {
    Interaction::new(Editor::new(s, path), VIEWPORT, 1.0, 260.0)
}

fn key(key: Key, ctrl: bool) -> Input {
    Input::Key {
        key,
        ctrl,
        shift: false,
    }
}

fn pixel_of(m: &Interaction, p: DVec3) -> DVec2 {
    m.camera.pixel_from_world(p, VIEWPORT).expect("on screen")
}

/// A fresh directory holding `scene.json` with `s` saved in it, and the scene as read
/// back from it (as the viewer opens it).
fn saved_scene(tag: &str, s: &Scene) -> (PathBuf, PathBuf, Scene) {
    let dir = std::env::temp_dir().join(format!("splinescope-editor-{tag}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.json");
    s.save(&path).unwrap();
    let back = Scene::load(&path).unwrap();
    (dir, path, back)
}

/// Drags control point `index` of curve `curve` by `by` pixels (press, move, release).
fn drag_point(m: &mut Interaction, at: DVec3, by: DVec2) {
    let p = pixel_of(m, at);
    m.handle(Input::PointerMoved(p));
    m.handle(Input::Pressed(Button::Primary));
    m.handle(Input::PointerMoved(p + by));
    m.handle(Input::Released);
}

/// Two scenes as their files would say (colours are written as 8-bit hex).
fn same_file(a: &Scene, b: &Scene) -> bool {
    to_json_string(a) == to_json_string(b)
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn esc_cancels_a_drag_and_the_selection_and_never_quits() {
    let original = scene(vec![cubic()]);
    let mut m = model(original.clone(), None);
    let p = pixel_of(&m, DVec3::new(1.0, 2.0, 0.0));
    m.handle(Input::PointerMoved(p));
    m.handle(Input::Pressed(Button::Primary));
    m.handle(Input::PointerMoved(p + DVec2::new(40.0, 25.0)));
    assert_ne!(m.scene(), &original, "the drag moves the point live");
    assert_eq!(m.handle(key(Key::Escape, false)), Response::default());
    assert_eq!(m.scene(), &original, "Esc puts the point back");
    assert!(!m.is_editing());
    m.handle(Input::PointerMoved(p + DVec2::new(80.0, 25.0)));
    m.handle(Input::Released);
    assert_eq!(m.scene(), &original, "moving on after Esc edits nothing");
    assert_eq!(
        m.editor.history_len(),
        (0, 0),
        "a cancelled drag is not an edit"
    );
    assert!(!m.editor.is_dirty());
    assert_eq!(m.editor.selected, Some(0));
    assert!(!m.handle(key(Key::Escape, false)).exit);
    assert_eq!(
        m.editor.selected, None,
        "the second Esc clears the selection"
    );
    assert!(!m.handle(key(Key::Escape, false)).exit);
}

#[test]
fn closing_with_unsaved_changes_asks_save_discard_or_cancel() {
    let (dir, path, s) = saved_scene("close", &scene(vec![cubic()]));
    let mut m = model(s.clone(), Some(path.clone()));
    assert!(m.request_close().exit, "nothing unsaved: closes at once");

    let mut m = model(s.clone(), Some(path.clone()));
    drag_point(&mut m, DVec3::new(1.0, 2.0, 0.0), DVec2::new(30.0, 0.0));
    assert!(
        m.editor.title().starts_with("scene.json*"),
        "{}",
        m.editor.title()
    );
    assert!(!m.request_close().exit);
    assert_eq!(
        m.prompt,
        Some(Prompt::Unsaved {
            then: Pending::Close
        })
    );
    // While asking, clicks and keys edit nothing.
    m.handle(Input::Pressed(Button::Primary));
    m.handle(Input::Released);
    assert_eq!(m.editor.history_len(), (1, 0));
    // Cancel (or Esc) keeps the window and the edit.
    assert!(!m.handle(key(Key::Escape, false)).exit);
    assert_eq!(m.prompt, None);
    assert!(m.editor.is_dirty());
    // Save and close: the file holds the edit.
    m.request_close();
    assert!(m.answer(Answer::Accept).exit);
    assert_eq!(Scene::load(&path).unwrap().curves, m.scene().curves);
    assert_eq!(
        files_in(&dir),
        ["scene.json"],
        "no recovery file after a save"
    );

    // Discard: closes, the file keeps the saved scene, the recovery file goes.
    let saved = Scene::load(&path).unwrap();
    let mut m = model(saved.clone(), Some(path.clone()));
    drag_point(&mut m, DVec3::new(3.0, 2.0, 0.0), DVec2::new(0.0, 30.0));
    assert!(recovery_path(&path).exists());
    m.request_close();
    assert!(m.answer(Answer::Discard).exit);
    assert!(same_file(&Scene::load(&path).unwrap(), &saved));
    assert_eq!(files_in(&dir), ["scene.json"]);

    // A save that fails keeps the window open and says why.
    let mut m = model(saved, Some(dir.join("missing-dir").join("x.json")));
    drag_point(&mut m, DVec3::new(3.0, 2.0, 0.0), DVec2::new(0.0, 30.0));
    m.request_close();
    assert!(!m.answer(Answer::Accept).exit);
    assert!(m.editor.message.as_deref().unwrap_or("").contains("cannot"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_recovery_file_keeps_unsaved_edits_across_a_kill_and_is_offered_next_time() {
    let (dir, path, s) = saved_scene("recovery", &scene(vec![cubic(), bspline()]));
    let edited = {
        let mut m = model(s.clone(), Some(path.clone()));
        drag_point(&mut m, DVec3::new(1.0, 2.0, 0.0), DVec2::new(25.0, -10.0));
        m.add_curve(
            Template::of_family("nubmp").expect("a NUBMP template"),
            DVec3::new(2.0, -2.0, 0.0),
        );
        // Kept in the state directory, never beside the scene (a checkout stays clean).
        let r = recovery_path(&path);
        assert!(
            r.starts_with(recovery_dir().expect("a state directory")),
            "{r:?}"
        );
        assert!(!legacy_recovery_path(&path).exists());
        assert!(
            std::fs::read_dir(&dir)
                .unwrap()
                .all(|e| e.unwrap().file_name() == "scene.json"),
            "nothing beside the scene"
        );
        assert!(same_file(&Scene::load(&r).unwrap(), m.scene()));
        m.scene().clone()
        // Dropped without saving or answering: as if the process were killed.
    };
    assert_eq!(
        Scene::load(&path).unwrap().curves,
        s.curves,
        "the file is untouched"
    );

    // Next time the edits are offered; Cancel keeps them for later.
    let mut m = model(s.clone(), Some(path.clone()));
    m.offer_recovery();
    assert!(matches!(m.prompt, Some(Prompt::Recovery { .. })));
    m.answer(Answer::Cancel);
    assert_eq!(m.scene(), &s);
    assert!(recovery_path(&path).exists());

    // Restore: the scene comes back as one undoable, unsaved edit.
    let mut m = model(s.clone(), Some(path.clone()));
    m.offer_recovery();
    m.answer(Answer::Accept);
    assert!(same_file(m.scene(), &edited));
    assert!(m.editor.is_dirty());
    assert_eq!(m.editor.history_len(), (1, 0));
    m.editor.undo();
    assert_eq!(m.scene().curves, s.curves);
    assert!(!recovery_path(&path).exists(), "back at the saved state");
    m.editor.redo();
    assert!(recovery_path(&path).exists());

    // Discard deletes the file; nothing is offered afterwards.
    let mut m = model(s.clone(), Some(path.clone()));
    m.offer_recovery();
    m.answer(Answer::Discard);
    assert!(!recovery_path(&path).exists());
    let mut m = model(s.clone(), Some(path.clone()));
    m.offer_recovery();
    assert_eq!(m.prompt, None);

    // An unreadable recovery file is reported and left in place.
    std::fs::write(recovery_path(&path), "{ not json").unwrap();
    let mut m = model(s, Some(path.clone()));
    m.offer_recovery();
    assert_eq!(m.prompt, None);
    assert!(
        m.editor
            .message
            .as_deref()
            .unwrap_or("")
            .contains("could not be read"),
        "{:?}",
        m.editor.message
    );
    assert!(recovery_path(&path).exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn curves_are_added_from_every_template_duplicated_and_deleted_each_undoably() {
    let original = scene(vec![cubic()]);
    let mut m = model(original.clone(), None);
    let center = DVec3::new(2.0, 1.0, 0.0);
    for (k, t) in Template::all().into_iter().enumerate() {
        let index = m.add_curve(t, center);
        assert_eq!(index, k + 1);
        assert_eq!(m.editor.selected, Some(index));
        let c = &m.scene().curves[index].curve;
        // Centred on the point asked for: the box of the control points holds it.
        let b = c.control_box();
        assert!(b.distance_to(center) == 0.0, "{t:?}: {b:?}");
        assert!(c.eval(c.domain().0).is_finite());
    }
    let templates = Template::all().len();
    assert_eq!(m.scene().curves.len(), templates + 1);
    assert_eq!(m.editor.history_len(), (templates, 0));

    // Duplicate: the copy is the curve moved by the offset, on top.
    m.editor.selected = Some(0);
    m.duplicate_selected();
    let copy = m.scene().curves.last().unwrap().curve.clone();
    let d = m.world_per_pixel(20.0);
    for (a, b) in copy
        .control_points()
        .iter()
        .zip(original.curves[0].curve.control_points())
    {
        assert!((*a - (*b + DVec3::new(d, -d, 0.0))).length() < 1e-12);
    }
    // Delete the original: the others move down one; undo brings it back in place.
    m.editor.selected = Some(0);
    m.editor.selected_point = None;
    let before = m.scene().clone();
    m.delete_selection();
    assert_eq!(m.scene().curves.len(), templates + 1);
    assert_eq!(m.scene().curves[0], before.curves[1]);
    assert!(m.editor.undo());
    assert_eq!(m.scene(), &before);
    for _ in 0..templates + 1 {
        assert!(m.editor.undo());
    }
    assert_eq!(m.scene(), &original);
    assert!(!m.editor.undo());
    while m.editor.redo() {}
    assert_eq!(m.scene().curves.len(), templates + 1);
    let changes = m.editor.take_changed();
    assert!(
        changes.list,
        "the list changed: the GPU copy must be rebuilt"
    );
}

#[test]
fn points_are_inserted_and_deleted_keeping_b_spline_shapes() {
    let mut m = model(scene(vec![cubic(), bspline()]), None);
    // Bézier: the new point goes on the polygon leg nearest the pointer.
    m.editor.selected = Some(0);
    let at = DVec3::new(2.0, 2.3, 0.0);
    m.handle(Input::PointerMoved(pixel_of(&m, at)));
    m.handle(key(Key::Char('i'), false));
    let pts = m.scene().curves[0].curve.control_points().to_vec();
    assert_eq!(pts.len(), 5);
    assert_eq!(m.editor.selected_point, Some(2));
    assert!((pts[2] - at).length() < 1e-9, "{:?}", pts[2]);
    assert_eq!(pts[1], DVec3::new(1.0, 2.0, 0.0));
    assert_eq!(pts[3], DVec3::new(3.0, 2.0, 0.0));
    // Delete removes the selected point: back to the cubic.
    m.handle(key(Key::Delete, false));
    assert_eq!(m.scene().curves[0].curve, cubic());

    // B-spline: knot insertion at the nearest parameter; the curve does not move.
    m.editor.selected = Some(1);
    let before = m.scene().curves[1].curve.clone();
    let near = before.eval(0.45) + DVec3::new(0.0, 0.05, 0.0);
    m.handle(Input::PointerMoved(pixel_of(&m, near)));
    m.insert_point_at_cursor();
    let after = m.scene().curves[1].curve.clone();
    assert_eq!(after.control_points().len(), 7);
    for j in 0..=100 {
        let t = f64::from(j) / 100.0;
        assert!((after.eval(t) - before.eval(t)).length() < 1e-12, "t = {t}");
    }
    // Deleting a B-spline point drops a knot too: 6 points, order 4, 10 knots.
    m.editor.selected_point = Some(3);
    m.delete_selection();
    match &m.scene().curves[1].curve {
        Curve::BSpline(b) => {
            assert_eq!(b.points().len(), 6);
            assert_eq!(b.knots().knots().len(), 10);
        }
        other => panic!("{other:?}"),
    }
    // Down to the minimum: refused with the reason, nothing changes.
    let mut e = Editor::new(scene(vec![cubic()]), None);
    e.delete_point(0, 0).unwrap();
    e.delete_point(0, 0).unwrap();
    let two = e.scene().clone();
    let err = e.delete_point(0, 0).unwrap_err();
    assert!(err.to_string().contains("at least 2 points"), "{err}");
    assert_eq!(e.scene(), &two);
    assert_eq!(e.history_len(), (2, 0));
}

#[test]
fn inserting_into_an_interpolation_passes_through_the_new_point() {
    use splinescope_core::geom::CubicInterpolation;
    let data = vec![
        DVec3::ZERO,
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(3.0, 1.0, 0.0),
    ];
    let c = Curve::Interpolation(CubicInterpolation::try_new(data.clone(), None, None).unwrap());
    let at = DVec3::new(1.5, 0.7, 0.0);
    let (curve, index) = c.with_point_on_polygon(at).unwrap();
    assert_eq!(index, 2);
    let Curve::Interpolation(i) = &curve else {
        panic!()
    };
    // The curve interpolates every point, old and new, at its parameter.
    for (p, &t) in i.points().iter().zip(i.params()) {
        assert!((curve.eval(t) - *p).length() < 1e-12, "{p} at {t}");
    }
    assert!(i.params()[1] < i.params()[2] && i.params()[2] < i.params()[3]);
}

#[test]
fn nubmp_structure_edits_need_the_standard_curve() {
    let pts: Vec<DVec3> = (0..7)
        .map(|i| DVec3::new(f64::from(i), f64::from(i % 2), 0.0))
        .collect();
    let n = Nubmp::try_new(pts, vec![0., 0., 0., 0., 0.3, 0.5, 0.8, 1., 1., 1., 1.], 4).unwrap();
    let c = Curve::Nubmp(n.clone());
    let inserted = c.with_knot_inserted(0.4).unwrap();
    assert_eq!(inserted.control_points().len(), 8);
    for j in 0..=50 {
        let t = f64::from(j) / 50.0;
        assert!((inserted.eval(t) - c.eval(t)).length() < 1e-12);
    }
    let mut bent = n;
    let g = bent
        .groups()
        .iter()
        .position(|g| g.members.len() >= 2 && g.effective)
        .unwrap();
    let values = bent.groups()[g].values.clone();
    let mut moved = values.clone();
    moved[0] = values[0] * 0.5;
    moved[1] = values[1] + values[0] * 0.5;
    bent.set_group(g, &moved).unwrap();
    let err = Curve::Nubmp(bent).with_knot_inserted(0.4).unwrap_err();
    assert!(
        err.to_string().contains("reset the shape parameters"),
        "{err}"
    );
}

#[test]
fn typed_coordinates_are_one_edit_and_bad_ones_change_nothing() {
    let mut e = Editor::new(scene(vec![cubic()]), None);
    e.set_point(0, 1, DVec3::new(1.25, 2.5, 0.0)).unwrap();
    assert_eq!(
        e.scene().curves[0].curve.control_points()[1],
        DVec3::new(1.25, 2.5, 0.0)
    );
    assert_eq!(e.history_len(), (1, 0));
    let before = e.scene().clone();
    let err = e
        .set_point(0, 1, DVec3::new(f64::INFINITY, 0.0, 0.0))
        .unwrap_err();
    assert!(err.to_string().contains("curves[0].points[1]"), "{err}");
    assert!(e.set_point(0, 9, DVec3::ZERO).is_err());
    assert!(e.set_point(3, 0, DVec3::ZERO).is_err());
    assert_eq!(e.scene(), &before);
    assert_eq!(e.history_len(), (1, 0), "refused values leave no undo step");
    e.undo();
    assert_eq!(e.scene().curves[0].curve, cubic());
}

#[test]
fn picking_takes_the_curve_drawn_on_top_and_hover_follows_the_pointer() {
    // Two curves sharing the point (1, 2): the later one is drawn on top.
    let mut other = cubic().control_points().to_vec();
    other[3] = DVec3::new(4.0, 4.0, 0.0);
    let mut m = model(
        scene(vec![cubic(), Curve::Bezier(Bezier::new(other))]),
        None,
    );
    let p = pixel_of(&m, DVec3::new(1.0, 2.0, 0.0));
    m.handle(Input::PointerMoved(p));
    assert_eq!(
        m.hovered,
        Some(Hit::Point {
            curve: 1,
            index: 1,
            at: DVec3::new(1.0, 2.0, 0.0)
        })
    );
    m.handle(Input::Pressed(Button::Primary));
    assert_eq!(m.editor.selected, Some(1));
    m.handle(Input::Released);
    m.handle(Input::PointerMoved(DVec2::new(990.0, 690.0)));
    assert_eq!(m.hovered, None);
}

#[test]
fn clicking_a_curve_that_cannot_be_pulled_selects_it_without_an_error() {
    let mut m = model(scene(vec![bspline()]), None);
    let on = m.scene().curves[0].curve.eval(0.5);
    let p = pixel_of(&m, on);
    m.handle(Input::PointerMoved(p));
    m.handle(Input::Pressed(Button::Primary));
    m.handle(Input::Released);
    assert_eq!(m.editor.selected, Some(0));
    assert_eq!(m.editor.message, None);
    assert_eq!(m.editor.history_len(), (0, 0));
}

#[test]
fn a_right_click_opens_the_menu_and_a_right_drag_pans() {
    let mut m = model(scene(vec![cubic()]), None);
    m.handle(Input::PointerMoved(DVec2::new(600.0, 300.0)));
    m.handle(Input::Pressed(Button::Secondary));
    m.handle(Input::Released);
    assert_eq!(m.context_menu, Some(DVec2::new(600.0, 300.0)));
    m.handle(key(Key::Escape, false));
    assert_eq!(m.context_menu, None);
    let camera = m.camera;
    m.handle(Input::Pressed(Button::Secondary));
    m.handle(Input::PointerMoved(DVec2::new(650.0, 330.0)));
    m.handle(Input::Released);
    assert_eq!(m.context_menu, None);
    assert_ne!(m.camera, camera);
}

#[test]
fn f1_and_question_mark_toggle_the_shortcuts() {
    let mut m = model(scene(vec![cubic()]), None);
    m.handle(key(Key::Help, false));
    assert!(m.show_help);
    m.handle(key(Key::Escape, false));
    assert!(!m.show_help);
    m.handle(key(Key::Char('?'), false));
    assert!(m.show_help);
}

#[test]
fn brackets_select_the_next_and_previous_curve_wrapping_around() {
    let mut m = model(scene(vec![cubic(), bspline(), cubic()]), None);
    let mut seen = Vec::new();
    for _ in 0..4 {
        m.handle(key(Key::Char(']'), false));
        seen.push(m.editor.selected);
    }
    assert_eq!(seen, [Some(0), Some(1), Some(2), Some(0)]);
    m.handle(key(Key::Char('['), false));
    assert_eq!(m.editor.selected, Some(2));
    m.handle(key(Key::Escape, false));
    m.handle(key(Key::Char('['), false));
    assert_eq!(m.editor.selected, Some(2), "from nothing, [ takes the last");
    // Nothing to select in an empty scene.
    let mut m = model(scene(vec![]), None);
    m.handle(key(Key::Char(']'), false));
    assert_eq!(m.editor.selected, None);
}

/// `K` turns the combs on at the scale chosen for the view and off again; a typed scale
/// survives turning them off and on (only "auto" follows the view).
#[test]
fn k_toggles_the_combs_and_keeps_a_typed_scale() {
    let mut m = model(scene(vec![cubic(), bspline()]), None);
    assert!(!m.shape.comb);
    m.handle(key(Key::Char('k'), false));
    assert!(m.shape.comb && m.shape.comb_auto);
    let auto = m.shape.comb_scale;
    assert!(auto.is_finite() && auto > 0.0);
    m.handle(key(Key::Char('K'), false));
    assert!(!m.shape.comb);
    m.shape.set_comb_scale(3.5).expect("positive");
    m.handle(key(Key::Char('k'), false));
    assert!(m.shape.comb);
    assert_eq!(m.shape.comb_scale, 3.5, "a typed scale is kept");
    m.fit_comb();
    assert_eq!(m.shape.comb_scale, auto, "auto again for the same view");
}

/// The viewer's export writes what is shown: with the comb on, its hairs (two-point runs
/// in the SVG, one per hair); with the selected curve's alone, only that curve's; off,
/// none.
#[test]
fn the_exported_view_carries_the_comb_as_shown() {
    let dir = std::env::temp_dir().join(format!("splinescope-comb-export-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let circle = |x: f64| {
        Curve::Nurbs(
            splinescope_core::geom::Nurbs::circle(DVec3::new(x, 0.0, 0.0), 1.0).expect("circle"),
        )
    };
    let mut m = model(scene(vec![circle(0.0), circle(3.0)]), None);
    m.toggles.show_polygons = false;
    m.toggles.show_points = false;
    let hairs = |m: &Interaction, name: &str| {
        let path = dir.join(name);
        m.export_view(&path).expect("export");
        let svg = std::fs::read_to_string(&path).expect("svg");
        svg.split(" d=\"")
            .skip(1)
            .map(|d| d.split('"').next().unwrap_or(""))
            .map(|d| d.matches('M').count() * usize::from(!d.contains('C') && !d.contains('Q')))
            .sum::<usize>()
    };
    let none = hairs(&m, "off.svg");
    m.shape.comb = true;
    m.shape.set_comb_scale(0.3).expect("scale");
    let both = hairs(&m, "on.svg");
    m.shape.comb_selected_only = true;
    m.editor.selected = Some(1);
    let one = hairs(&m, "one.svg");
    assert!(both > none + 100, "{none} → {both}");
    assert!(one > none && one < both, "{none} < {one} < {both}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_recovery_file_beside_the_scene_from_earlier_versions_is_still_offered() {
    let (dir, path, s) = saved_scene("legacy-recovery", &scene(vec![cubic(), bspline()]));
    // Two scenes of one name in different folders keep their recovery files apart.
    let other = dir.join("elsewhere").join("scene.json");
    assert_ne!(recovery_path(&path), recovery_path(&other));
    let mut edited = s.clone();
    edited.curves.truncate(1);
    edited.save(&legacy_recovery_path(&path)).unwrap();
    let mut m = model(s.clone(), Some(path.clone()));
    m.offer_recovery();
    assert!(matches!(m.prompt, Some(Prompt::Recovery { .. })));
    m.answer(Answer::Accept);
    assert_eq!(m.scene().curves, edited.curves);
    // Saving deals with the edits: neither file is left to be offered again.
    m.editor.save(None).expect("saved");
    assert!(!legacy_recovery_path(&path).exists());
    assert!(!recovery_path(&path).exists());
    std::fs::remove_dir_all(&dir).ok();
}
