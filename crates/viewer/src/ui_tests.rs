//! The panel, the canvas's menus and prompts and the file dialog driven headless through
//! egui's test harness (`egui_kittest`, AccessKit queries): the widgets a user clicks and
//! types into, with the same drawing ([`ui::draw`]) and the same handling of what they
//! asked for ([`ui::apply`]) as the window. Expected values come from the scene before
//! the input and the files the tests write.

use std::path::PathBuf;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glam::{DVec2, DVec3};

use super::digest::SceneDigest;
use super::edit::Editor;
use super::interaction::{Interaction, Pending, Prompt};
use super::ui::{self, Actions, PanelInfo};
use splinescope_core::geom::{Bezier, Curve, ModifiedBezier};
use splinescope_scene::format::Scene;

/// What the window keeps between frames, for the harness.
struct Viewer {
    model: Interaction,
    digest: SceneDigest,
}

impl Viewer {
    fn new(scene: Scene, path: Option<PathBuf>) -> Viewer {
        let digest = SceneDigest::of(&scene);
        Viewer {
            model: Interaction::new(
                Editor::new(scene, path),
                DVec2::new(1200.0, 800.0),
                1.0,
                ui::PANEL_WIDTH_POINTS,
            ),
            digest,
        }
    }

    /// One frame as the window runs it.
    fn frame(&mut self, ui: &mut egui::Ui) {
        let camera = self.model.camera;
        let info = PanelInfo {
            digest: &self.digest,
            adapter: "test",
            fps: 60.0,
            samples_per_frame: 0,
            capped: false,
            stage_ms: None,
            overlays_locked: None,
            camera: &camera,
            solving: None,
            markers: &[],
            offset_status: None,
        };
        let mut actions = Actions::default();
        ui::draw(ui, &info, &mut self.model, &mut actions);
        ui::apply(&mut self.model, actions);
        if !self.model.is_editing() && ui.input(|i| i.pointer.any_released()) {
            self.model.editor.finish();
        }
        let changed = self.model.editor.take_changed();
        self.digest.update(self.model.scene(), &changed, &[]);
    }
}

fn harness(scene: Scene, path: Option<PathBuf>) -> Harness<'static, Viewer> {
    let mut h = Harness::builder()
        .with_size(egui::vec2(1200.0, 800.0))
        .build_ui_state(|ui, v: &mut Viewer| v.frame(ui), Viewer::new(scene, path));
    h.run();
    h
}

fn cubic(y: f64) -> Curve {
    Curve::Bezier(Bezier::new(vec![
        DVec3::new(0.0, y, 0.0),
        DVec3::new(1.0, y + 2.0, 0.0),
        DVec3::new(3.0, y + 2.0, 0.0),
        DVec3::new(4.0, y, 0.0),
    ]))
}

fn modified() -> Curve {
    let base = Bezier::new(vec![
        DVec3::ZERO,
        DVec3::new(1.0, 2.0, 0.0),
        DVec3::new(3.0, 2.0, 0.0),
        DVec3::new(4.0, 0.0, 0.0),
    ]);
    Curve::ModifiedBezier(ModifiedBezier::try_new(base, 0.3, DVec3::new(0.0, 1.0, 0.0)).unwrap())
}

#[test]
fn clicking_a_listed_curve_selects_it_and_duplicate_undo_redo_work_from_the_panel() {
    let mut h = harness(Scene::of_curves([cubic(0.0), cubic(5.0)]), None);
    assert_eq!(h.state().model.editor.selected, None);
    h.get_by_label("1: bezier").click();
    h.run();
    assert_eq!(h.state().model.editor.selected, Some(1));
    h.get_by_label("duplicate").click();
    h.run();
    let scene = h.state().model.scene().clone();
    assert_eq!(scene.curves.len(), 3);
    assert_eq!(scene.curves[2].curve.control_points().len(), 4);
    // The list and the undo button follow.
    h.get_by_label("2: bezier");
    h.get_by_label("undo (1)").click();
    h.run();
    assert_eq!(h.state().model.scene().curves.len(), 2);
    assert!(h.query_by_label("2: bezier").is_none());
    h.get_by_label("redo (1)").click();
    h.run();
    assert_eq!(h.state().model.scene(), &scene);
    // Delete from the panel, undone the same way.
    h.get_by_label("2: bezier").click();
    h.run();
    h.get_by_label("delete curve").click();
    h.run();
    assert_eq!(h.state().model.scene().curves.len(), 2);
    h.get_by_label("undo (2)").click();
    h.run();
    assert_eq!(h.state().model.scene(), &scene);
}

/// Types `text` into the number field whose current value reads `value`, then Enter.
fn type_into(h: &mut Harness<'static, Viewer>, value: &str, text: &str) {
    type_then(h, value, text, egui::Key::Enter);
}

/// Types `text` into the number field whose current value reads `value`, then presses
/// `key`, and lets a few frames pass (egui applies a field's text a frame after it loses
/// the keyboard).
fn type_then(h: &mut Harness<'static, Viewer>, value: &str, text: &str, key: egui::Key) {
    h.get_by_value(value).click();
    h.run();
    // The field being edited has the keyboard: select its text and type over it.
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    h.get_by_label("file").type_text(text);
    h.run();
    h.key_press(key);
    for _ in 0..4 {
        h.run();
    }
}

#[test]
fn a_typed_parameter_is_one_edit_and_an_out_of_range_one_is_refused_whole() {
    let mut h = harness(Scene::of_curves([modified()]), None);
    h.get_by_label("0: modified_bezier · t* = 0.3, v = (0, 1)")
        .click();
    h.run();
    type_into(&mut h, "0.30", "0.45");
    let Curve::ModifiedBezier(m) = &h.state().model.scene().curves[0].curve else {
        panic!()
    };
    assert_eq!(m.t_star(), 0.45);
    assert_eq!(h.state().model.editor.history_len(), (1, 0));
    // The label follows the value.
    h.get_by_label("0: modified_bezier · t* = 0.45, v = (0, 1)");
    // 1.5 is outside (0, 1): refused with the reason; nothing changes, no undo step.
    let before = h.state().model.scene().clone();
    type_into(&mut h, "0.45", "1.5");
    assert_eq!(h.state().model.scene(), &before);
    assert_eq!(h.state().model.editor.history_len(), (1, 0));
    let message = h.state().model.editor.message.clone().unwrap_or_default();
    assert!(message.contains("1.5"), "{message}");
    h.get_by_label(&message);
    // And next to the field it was typed in.
    h.get_by_label(&format!("refused: {message}"));
    // The next accepted value clears it.
    type_into(&mut h, "0.45", "0.5");
    assert!(h.query_by_label(&format!("refused: {message}")).is_none());
}

/// Thousands of curves (the stress scenes) are summarised, not listed row by row.
#[test]
fn a_large_scene_is_summarised_instead_of_listed() {
    let curves: Vec<Curve> = (0..300).map(|i| cubic(f64::from(i))).collect();
    let mut h = harness(Scene::of_curves(curves), None);
    h.get_by_label("300 curves: bezier × 300 (4 points each)");
    assert!(h.query_by_label("0: bezier").is_none());
    assert!(h.query_by_label("150: bezier").is_none());
    h.state_mut().model.editor.selected = Some(7);
    h.run();
    h.get_by_label("7: bezier");
}

#[test]
fn the_unsaved_changes_prompt_answers_from_its_buttons() {
    let mut h = harness(Scene::of_curves([cubic(0.0)]), None);
    h.state_mut()
        .model
        .editor
        .set_point(0, 1, DVec3::new(1.0, 3.0, 0.0))
        .unwrap();
    h.state_mut().model.request_close();
    h.run();
    assert_eq!(
        h.state().model.prompt,
        Some(Prompt::Unsaved {
            then: Pending::Close
        })
    );
    h.get_by_label("unsaved changes");
    h.get_by_label("cancel").click();
    h.run();
    assert_eq!(h.state().model.prompt, None);
    assert!(!h.state().model.exit_requested);
    h.state_mut().model.request_close();
    h.run();
    h.get_by_label("close without saving").click();
    h.run();
    assert!(h.state().model.exit_requested);
}

#[test]
fn the_file_dialog_opens_a_clicked_file_and_the_file_menu_saves_as() {
    let dir = std::env::temp_dir().join(format!("splinescope-ui-files-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    let a = dir.join("a.json");
    Scene::of_curves([cubic(0.0)]).save(&a).unwrap();
    let other = Scene::of_curves([cubic(3.0), cubic(6.0)]);
    other.save(&dir.join("other.json")).unwrap();
    let mut h = harness(Scene::load(&a).unwrap(), Some(a.clone()));
    h.get_by_label("file").click();
    h.run();
    h.get_by_label_contains("open…").click();
    h.run();
    h.get_by_label("open a scene");
    h.get_by_label("other.json").click();
    h.run();
    h.get_by_label("open").click();
    h.run();
    assert_eq!(h.state().model.dialog, None);
    let want = Scene::load(&dir.join("other.json")).unwrap();
    assert_eq!(h.state().model.scene(), &want);
    assert_eq!(
        h.state().digest.summaries.len(),
        2,
        "the list shows the new scene"
    );

    // Save as, typing a new name.
    h.get_by_label("file").click();
    h.run();
    h.get_by_label_contains("save as…").click();
    h.run();
    h.get_by_label("save the scene as");
    // The name field has the keyboard as the dialog opens, proposing the file's name
    // with its stem selected: typing replaces the stem and keeps the extension.
    assert_eq!(
        h.state().model.dialog.as_ref().map(|d| d.name.as_str()),
        Some("other.json")
    );
    h.get_by_label("save the scene as").type_text("copy");
    h.run();
    assert_eq!(
        h.state().model.dialog.as_ref().map(|d| d.name.as_str()),
        Some("copy.json")
    );
    h.get_by_label("save").click();
    h.run();
    let copy = dir.join("copy.json");
    assert_eq!(Scene::load(&copy).unwrap(), want);
    assert_eq!(h.state().model.editor.path(), Some(copy.as_path()));
    std::fs::remove_dir_all(&dir).ok();
}

/// The open dialog lists SVG files; one opens as path curves, saved beside it as
/// NAME.json (never over the SVG), and the panel says so and what was left out. A file
/// dropped on the window takes the same way; a bad one leaves the scene as it was.
#[test]
fn an_svg_file_opens_as_path_curves_and_saves_beside_it() {
    let dir = std::env::temp_dir().join(format!("splinescope-ui-svg-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("logo.svg");
    let text = r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10"><circle cx="5" cy="5" r="3" stroke="red" fill="none"/><path d="M 1 1 L 9 1" stroke="blue"/><text>t</text></svg>"#;
    std::fs::write(&svg, text).unwrap();
    let a = dir.join("a.json");
    Scene::of_curves([cubic(0.0)]).save(&a).unwrap();
    let mut h = harness(Scene::load(&a).unwrap(), Some(a.clone()));
    h.get_by_label("file").click();
    h.run();
    h.get_by_label_contains("open…").click();
    h.run();
    h.get_by_label("logo.svg").click();
    h.run();
    h.get_by_label("open").click();
    h.run();
    let scene = h.state().model.scene().clone();
    assert_eq!(scene.curves.len(), 2);
    assert!(scene.curves.iter().all(|c| c.curve.family() == "path"));
    let beside = dir.join("logo.json");
    assert_eq!(h.state().model.editor.path(), Some(beside.as_path()));
    let message = h.state().model.editor.message.clone().unwrap_or_default();
    assert!(
        message.contains("2 path curve(s)") && message.contains("1 <text>"),
        "{message}"
    );
    // Saving writes the scene beside the file, which stays as it was.
    h.state_mut().model.editor.save(None).unwrap();
    assert_eq!(Scene::load(&beside).unwrap().curves.len(), 2);
    assert_eq!(std::fs::read_to_string(&svg).unwrap(), text);
    // With a scene of that name there, it is not the save target.
    h.state_mut().model.open_path(&a);
    h.run();
    h.state_mut().model.open_path(&svg);
    h.run();
    assert_eq!(h.state().model.editor.path(), None);
    // A bad file: a prompt naming the file and the line; the scene stays.
    let bad = dir.join("bad.svg");
    std::fs::write(&bad, "<svg>\n<path d='M 0 0 L'/></svg>").unwrap();
    let before = h.state().model.scene().clone();
    h.state_mut().model.open_path(&bad);
    h.run();
    assert_eq!(h.state().model.scene(), &before);
    match &h.state().model.prompt {
        Some(Prompt::Failed { message }) => {
            assert!(message.contains("bad.svg:2: <path>"), "{message}");
        }
        other => panic!("expected a failure prompt, got {other:?}"),
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Esc in a number field restores the field and changes nothing: no edit, no undo step,
/// no unsaved mark (a point's coordinate and a family's typed parameter alike).
#[test]
fn escape_in_a_number_field_changes_nothing() {
    let mut h = harness(Scene::of_curves([cubic(0.0), modified()]), None);
    h.state_mut().model.editor.selected = Some(0);
    h.state_mut().model.editor.selected_point = Some(1);
    h.run();
    let before = h.state().model.scene().clone();
    // The x field of point 1 reads "x 1.00".
    type_then(&mut h, "x 1.00", "99", egui::Key::Escape);
    assert_eq!(h.state().model.scene(), &before);
    assert_eq!(h.state().model.editor.history_len(), (0, 0));
    assert!(!h.state().model.editor.is_dirty());
    // The field shows the old value again.
    h.get_by_value("x 1.00");

    // A family's number (t*): the same.
    h.state_mut().model.editor.selected = Some(1);
    h.state_mut().model.editor.selected_point = None;
    h.run();
    type_then(&mut h, "0.30", "0.7", egui::Key::Escape);
    assert_eq!(h.state().model.scene(), &before);
    assert_eq!(h.state().model.editor.history_len(), (0, 0));
    h.get_by_value("0.30");
}

/// The shape section: the comb's checkbox turns it on at the scale chosen for the view
/// (a circle's closed form), ×2 and ÷2 scale it, a typed scale that is not a positive
/// number is refused with its value named and changes nothing, and the marker switches
/// show their legend.
#[test]
fn the_shape_section_turns_the_comb_on_scales_it_caps_it_and_refuses_bad_values() {
    use splinescope_core::geom::Nurbs;
    let r = 2.0;
    let mut h = harness(
        Scene::of_curves([Curve::Nurbs(Nurbs::circle(DVec3::ZERO, r).expect("circle"))]),
        None,
    );
    h.get_by_label("curvature comb (K)").click();
    h.run();
    let (height, scale) = {
        let m = &h.state().model;
        (m.camera.view_height(m.viewport), m.shape.comb_scale)
    };
    assert!(h.state().model.shape.comb && h.state().model.shape.comb_auto);
    // κ = 1/r on the whole circle: the automatic hair is the fraction of the view.
    let want = splinescope_core::analysis::comb::AUTO_COMB_FRACTION * height * r;
    assert!((scale - want).abs() <= 1e-9 * want, "{scale} vs {want}");
    h.get_by_label("×2").click();
    h.run();
    assert!((h.state().model.shape.comb_scale - 2.0 * want).abs() <= 1e-9 * want);
    assert!(!h.state().model.shape.comb_auto);
    h.state_mut().model.shape.comb_scale = 0.125;
    h.run();
    type_into(&mut h, "0.125", "-3");
    assert_eq!(h.state().model.shape.comb_scale, 0.125, "refused whole");
    let message = h.state().model.editor.message.clone().unwrap_or_default();
    assert!(
        message.contains("-3") && message.contains("comb scale"),
        "{message}"
    );
    type_into(&mut h, "0.125", "0.5");
    assert_eq!(h.state().model.shape.comb_scale, 0.5);
    h.get_by_label("auto").click();
    h.run();
    assert!((h.state().model.shape.comb_scale - want).abs() <= 1e-9 * want);
    // The cap: typed as a fraction of the view, refused whole when not above 0, off.
    use splinescope_scene::format::shape::CombCap;
    assert_eq!(h.state().model.shape.comb_cap, CombCap::default());
    type_into(&mut h, "0.050", "0");
    assert_eq!(
        h.state().model.shape.comb_cap,
        CombCap::default(),
        "refused"
    );
    let message = h.state().model.editor.message.clone().unwrap_or_default();
    assert!(message.contains("comb cap 0"), "{message}");
    type_into(&mut h, "0.050", "0.2");
    assert_eq!(h.state().model.shape.comb_cap.get(), 0.2);
    h.get_by_label("cap").click();
    h.run();
    assert_eq!(h.state().model.shape.comb_cap, CombCap::NONE);
    h.get_by_label("inflections and cusps").click();
    h.run();
    assert!(h.state().model.shape.inflections);
    h.get_by_label("joints (kinks, curvature jumps)").click();
    h.run();
    assert!(h.state().model.shape.joints);
    assert!(h.state().model.shape.marker_options().joints);
    h.get_by_label("inflection (0)");
    h.get_by_label("cusp (0)");
    h.get_by_label("curvature comb (K)").click();
    h.run();
    assert!(!h.state().model.shape.comb);
}

/// The text shapes a frame drew, with their bounds.
fn drawn_texts(h: &Harness<'static, Viewer>) -> Vec<(String, egui::Rect)> {
    fn collect(shape: &egui::Shape, out: &mut Vec<(String, egui::Rect)>) {
        match shape {
            egui::Shape::Text(t) => {
                out.push((t.galley.text().to_owned(), t.visual_bounding_rect()))
            }
            egui::Shape::Vec(v) => v.iter().for_each(|s| collect(s, out)),
            _ => {}
        }
    }
    let mut out = Vec::new();
    for clipped in &h.output().shapes {
        collect(&clipped.shape, &mut out);
    }
    out
}

/// The window's curve labels as egui draws them (the text shapes of the frame's output, not
/// the placement's own boxes): on the gallery none overlaps another, none reaches into the
/// panel or off the window; and after a small edit of one curve the other labels stay
/// where they were (no jumping while a point is dragged).
#[test]
fn window_labels_never_overlap_and_stay_put() {
    let scene = splinescope_scene::format::gallery::gallery();
    let names: Vec<String> = SceneDigest::of(&scene)
        .summaries
        .iter()
        .map(|s| s.name.clone())
        .collect();
    let mut h = harness(scene, None);
    h.run();
    let labels = |h: &Harness<'static, Viewer>| -> Vec<(String, egui::Rect)> {
        drawn_texts(h)
            .into_iter()
            .filter(|(t, _)| names.contains(t))
            .collect()
    };
    let before = labels(&h);
    assert!(before.len() >= 15, "{} labels drawn", before.len());
    let panel = ui::PANEL_WIDTH_POINTS as f32;
    for (i, (ta, a)) in before.iter().enumerate() {
        assert!(
            a.min.x >= panel && a.max.x <= 1200.0 && a.min.y >= 0.0 && a.max.y <= 800.0,
            "{ta:?} at {a:?} leaves the canvas"
        );
        for (tb, b) in &before[i + 1..] {
            assert!(!a.intersects(*b), "{ta:?} {a:?} overlaps {tb:?} {b:?}");
        }
    }
    // Nudge a control point of the spiral (curve 7) by a hundredth of a unit.
    let p = h.state().model.scene().curves[7].curve.control_points()[3];
    h.state_mut()
        .model
        .editor
        .set_point(7, 3, p + DVec3::new(0.01, 0.0, 0.0))
        .expect("set");
    h.run();
    let after = labels(&h);
    let mut moved = Vec::new();
    for (t, a) in &before {
        if let Some((_, b)) = after.iter().find(|(u, _)| u == t)
            && (a.min - b.min).length() > 0.5
        {
            moved.push(t.clone());
        }
    }
    assert!(
        moved.len() <= 1,
        "labels jumped after a small edit: {moved:?}"
    );
}
