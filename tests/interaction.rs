//! The viewer's window-free interaction model driven as a user would drive the window:
//! pointer drags edit control points and pan, the wheel zooms about the cursor, keys
//! toggle, undo, fit, save and quit (Ctrl+Q; Esc never quits). Expected values come from the camera's own
//! pixel↔world maps and from the scene before the input.

use glam::{DVec2, DVec3};
use splinescope_core::geom::{Bezier, Curve};
use splinescope_encoding::Color;
use splinescope_encoding::camera::Camera;
use splinescope_scene::format::{Scene, SceneCurve, Style, ViewSpec};
use splinescope_viewer::edit::Editor;
use splinescope_viewer::interaction::{Button, Input, Interaction, Key};

const VIEWPORT: DVec2 = DVec2::new(1000.0, 700.0);

fn scene(z: f64) -> Scene {
    Scene {
        name: None,
        unit: None,
        background: Color::WHITE,
        samples_per_segment: None,
        view: ViewSpec::Auto,
        curves: vec![SceneCurve {
            name: None,
            curve: Curve::Bezier(Bezier::new(vec![
                DVec3::ZERO,
                DVec3::new(1.0, 2.0, z),
                DVec3::new(3.0, 2.0, 0.0),
                DVec3::new(4.0, 0.0, 0.0),
            ])),
            style: Style::default_for(0),
        }],
        annotations: Vec::new(),
    }
}

fn model(z: f64, path: Option<std::path::PathBuf>) -> Interaction {
    Interaction::new(Editor::new(scene(z), path), VIEWPORT, 1.0, 260.0)
}

fn key(c: char, ctrl: bool) -> Input {
    Input::Key {
        key: Key::Char(c),
        ctrl,
        shift: false,
    }
}

fn pixel_of(m: &Interaction, p: DVec3) -> DVec2 {
    m.camera.pixel_from_world(p, VIEWPORT).expect("on screen")
}

#[test]
fn dragging_a_control_point_moves_it_under_the_pointer_and_undo_restores_it() {
    let mut m = model(0.0, None);
    let before = m.scene().clone();
    let start = pixel_of(&m, DVec3::new(1.0, 2.0, 0.0));
    m.handle(Input::PointerMoved(start + DVec2::new(2.0, -1.0)));
    m.handle(Input::Pressed(Button::Primary));
    assert!(
        m.is_editing(),
        "a press next to a control point starts an edit"
    );
    let to = start + DVec2::new(60.0, 40.0);
    m.handle(Input::PointerMoved(start + DVec2::new(30.0, 10.0)));
    m.handle(Input::PointerMoved(to));
    m.handle(Input::Released);
    let want = m.camera.world_from_pixel(to, VIEWPORT);
    let got = m.scene().curves[0].curve.control_points()[1];
    assert!((got - want).length() < 1e-9, "{got} vs {want}");
    // The others did not move; one drag is one edit.
    assert_eq!(
        m.scene().curves[0].curve.control_points()[2],
        DVec3::new(3.0, 2.0, 0.0)
    );
    assert_eq!(m.editor.history_len(), (1, 0));
    m.handle(key('z', true));
    assert_eq!(m.scene(), &before);
    m.handle(Input::Key {
        key: Key::Char('Z'),
        ctrl: true,
        shift: true,
    });
    assert!((m.scene().curves[0].curve.control_points()[1] - want).length() < 1e-9);
}

#[test]
fn dragging_empty_space_pans_and_f_fits_again() {
    let mut m = model(0.0, None);
    assert!(m.auto_fit);
    let fitted = m.camera;
    let from = DVec2::new(900.0, 650.0);
    let world = m.camera.world_from_pixel(from, VIEWPORT);
    m.handle(Input::PointerMoved(from));
    m.handle(Input::Pressed(Button::Primary));
    assert!(!m.is_editing());
    m.handle(Input::PointerMoved(from + DVec2::new(-50.0, 20.0)));
    m.handle(Input::Released);
    // The world point that was under the pointer is under it still.
    let now = m.camera.pixel_from_world(world, VIEWPORT).unwrap();
    assert!(
        (now - (from + DVec2::new(-50.0, 20.0))).length() < 1e-9,
        "{now}"
    );
    assert!(!m.auto_fit);
    assert_eq!(m.editor.history_len(), (0, 0), "panning edits nothing");
    m.handle(key('f', false));
    assert!(m.auto_fit);
    assert_eq!(m.camera, fitted);
}

#[test]
fn the_wheel_zooms_about_the_cursor() {
    let mut m = model(0.0, None);
    let at = DVec2::new(420.0, 333.0);
    let world = m.camera.world_from_pixel(at, VIEWPORT);
    let Camera::Ortho2d(before) = m.camera else {
        panic!("a planar scene opens in 2D")
    };
    m.handle(Input::PointerMoved(at));
    m.handle(Input::Wheel(2.0));
    let Camera::Ortho2d(after) = m.camera else {
        panic!()
    };
    assert!((after.pixels_per_unit / before.pixels_per_unit - 1.15_f64.powi(2)).abs() < 1e-12);
    let now = m.camera.pixel_from_world(world, VIEWPORT).unwrap();
    assert!((now - at).length() < 1e-9, "{now}");
}

#[test]
fn keys_toggle_the_overlays_and_panel_save_and_quit() {
    let dir = std::env::temp_dir().join(format!("splinescope-interaction-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("saved.json");
    let mut m = model(0.0, Some(path.clone()));
    let t = m.toggles;
    m.handle(key('p', false));
    m.handle(key('C', false));
    m.handle(key('h', false));
    assert_eq!(m.toggles.show_polygons, !t.show_polygons);
    assert_eq!(m.toggles.show_points, !t.show_points);
    assert_eq!(m.toggles.show_panel, !t.show_panel);
    // With control points hidden a press cannot grab one: it pans.
    let p = pixel_of(&m, DVec3::new(3.0, 2.0, 0.0));
    m.handle(Input::PointerMoved(p));
    m.handle(Input::Pressed(Button::Primary));
    m.handle(Input::PointerMoved(p + DVec2::new(10.0, 0.0)));
    m.handle(Input::Released);
    assert_eq!(m.editor.history_len(), (0, 0));
    m.handle(key('s', true));
    let saved = Scene::load(&path).expect("Ctrl+S wrote the scene");
    // Colours are written as 8-bit hex: compare what the file says.
    assert_eq!(
        splinescope_scene::format::to_json_string(&saved),
        splinescope_scene::format::to_json_string(m.scene())
    );
    assert_eq!(saved.curves[0].curve, m.scene().curves[0].curve);
    assert!(!m.handle(key('q', false)).exit);
    assert!(
        !m.handle(Input::Key {
            key: Key::Escape,
            ctrl: false,
            shift: false
        })
        .exit,
        "Esc never quits"
    );
    assert!(m.handle(key('q', true)).exit, "Ctrl+Q quits a saved scene");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_read_only_model_never_edits_and_3d_drags_orbit() {
    let mut m = model(1.5, None);
    assert!(m.camera.is_3d(), "a non-planar scene opens in 3D");
    m.editable = false;
    let before_scene = m.scene().clone();
    let before_camera = m.camera;
    let p = pixel_of(&m, DVec3::new(1.0, 2.0, 1.5));
    m.handle(Input::PointerMoved(p));
    m.handle(Input::Pressed(Button::Primary));
    assert!(!m.is_editing());
    m.handle(Input::PointerMoved(p + DVec2::new(40.0, 15.0)));
    m.handle(Input::Released);
    assert_eq!(m.scene(), &before_scene);
    let (Camera::Orbit3d(a), Camera::Orbit3d(b)) = (&before_camera, &m.camera) else {
        panic!()
    };
    assert_ne!(a.yaw, b.yaw, "a primary drag orbits");
    assert_eq!(a.target, b.target, "orbiting keeps the target");
}

/// Input over the panel is the panel's: a drag that starts there (a slider thumb, a row, a
/// checkbox) leaves the camera and the scene alone, the wheel there does not zoom, and
/// nothing on the canvas is picked; the same over a floating menu. A drag that starts on
/// the canvas still pans when it crosses the panel.
#[test]
fn presses_and_the_wheel_over_the_panel_or_a_menu_do_not_reach_the_canvas() {
    let mut m = model(0.0, None);
    m.auto_fit = false;
    let camera = m.camera;
    let before = m.scene().clone();
    // A slider thumb in the panel (x < 260): press, drag 30 px left, release.
    m.handle(Input::PointerMoved(DVec2::new(120.0, 400.0)));
    assert!(m.pointer_over_ui());
    m.handle(Input::Pressed(Button::Primary));
    m.handle(Input::PointerMoved(DVec2::new(90.0, 400.0)));
    m.handle(Input::Released);
    assert_eq!(m.camera, camera, "a drag on the panel does not pan");
    // The wheel over the panel (the curve list) does not zoom.
    m.handle(Input::Wheel(3.0));
    assert_eq!(m.camera, camera, "the wheel over the panel does not zoom");
    // A menu floating over the canvas: the same, and nothing under it is picked.
    let on_curve = pixel_of(&m, DVec3::new(1.0, 2.0, 0.0));
    m.ui_rects = vec![(on_curve - DVec2::splat(40.0), on_curve + DVec2::splat(40.0))];
    m.handle(Input::PointerMoved(on_curve));
    assert_eq!(m.hovered, None, "nothing is picked under a menu");
    m.handle(Input::Pressed(Button::Primary));
    m.handle(Input::PointerMoved(on_curve + DVec2::new(25.0, 10.0)));
    m.handle(Input::Released);
    m.handle(Input::Wheel(-2.0));
    assert_eq!(m.camera, camera);
    assert_eq!(m.scene(), &before, "the point under the menu did not move");
    assert_eq!(m.editor.history_len(), (0, 0));
    // On the canvas the same gestures act; a pan continues over the panel.
    m.ui_rects.clear();
    m.handle(Input::PointerMoved(DVec2::new(600.0, 650.0)));
    m.handle(Input::Wheel(1.0));
    assert_ne!(m.camera, camera, "the wheel on the canvas zooms");
    let zoomed = m.camera;
    m.handle(Input::Pressed(Button::Secondary));
    m.handle(Input::PointerMoved(DVec2::new(100.0, 650.0)));
    m.handle(Input::Released);
    assert_ne!(
        m.camera, zoomed,
        "a pan begun on the canvas crosses the panel"
    );
}

/// Ctrl+S on a scene that is no file's (the gallery, `--stress`) writes nothing: it opens
/// the save-as dialog proposing `splinescope-scene.json`, and an existing file of that
/// name (someone else's scene) is replaced only when the user confirms a second time.
#[test]
fn saving_the_gallery_asks_where_and_never_replaces_a_file_unasked() {
    use splinescope_viewer::file_dialog::DialogMode;
    use splinescope_viewer::{DEFAULT_SAVE_NAME, ViewOptions, editor_for};
    let gallery = splinescope_scene::format::gallery::gallery();
    let opts = ViewOptions {
        scene: gallery.clone(),
        frames: None,
        backend: splinescope_gpu::BackendChoice::Auto,
        solve: false,
        tolerance_px: 0.25,
        overlays_hidden: false,
        path: None,
        source: None,
        comb: None,
        comb_cap: splinescope_scene::format::shape::CombCap::default(),
        lose_device_after_frames: None,
    };
    let editor = editor_for(&opts, gallery.clone());
    assert_eq!(editor.path(), None, "the gallery is no file's");
    let mut m = Interaction::new(editor, VIEWPORT, 1.0, 260.0);
    // Someone else's scene under the proposed name, in the working directory the dialog
    // starts in — and the same in a directory of our own.
    let in_cwd = std::path::Path::new(DEFAULT_SAVE_NAME);
    let cwd_before = std::fs::read(in_cwd).ok();
    let dir = std::env::temp_dir().join(format!("splinescope-gallery-save-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let theirs = dir.join(DEFAULT_SAVE_NAME);
    std::fs::write(&theirs, b"someone else's scene").unwrap();
    m.editor.set_point(0, 1, DVec3::new(5.0, 5.0, 0.0)).unwrap();
    m.handle(key('s', true));
    let dialog = m.dialog.as_ref().expect("Ctrl+S asks where");
    assert_eq!(dialog.mode, DialogMode::SaveAs);
    assert_eq!(dialog.name, DEFAULT_SAVE_NAME);
    assert_eq!(
        std::fs::read(in_cwd).ok(),
        cwd_before,
        "nothing written in the working directory"
    );
    // In our directory: the first confirmation only warns, the second replaces.
    m.dialog.as_mut().unwrap().enter(&dir.to_string_lossy());
    m.dialog.as_mut().unwrap().name = DEFAULT_SAVE_NAME.into();
    m.confirm_dialog();
    assert_eq!(std::fs::read(&theirs).unwrap(), b"someone else's scene");
    let warning = m
        .dialog
        .as_ref()
        .and_then(|d| d.error.clone())
        .unwrap_or_default();
    assert!(
        warning.contains("exists: save again to replace it"),
        "{warning}"
    );
    m.confirm_dialog();
    assert!(m.dialog.is_none());
    let saved =
        splinescope_scene::format::Scene::load(&theirs).expect("our scene, replaced on request");
    assert_eq!(saved.curves.len(), m.scene().curves.len());
    assert_eq!(
        saved.curves[0].curve.control_points()[1],
        DVec3::new(5.0, 5.0, 0.0)
    );
    assert_eq!(m.editor.path(), Some(theirs.as_path()));
    std::fs::remove_dir_all(&dir).ok();
}

/// `L` hides and shows the curves' labels on the canvas (shown by default).
#[test]
fn l_toggles_the_curve_labels() {
    let mut m = model(0.0, None);
    assert!(m.toggles.show_labels);
    m.handle(key('l', false));
    assert!(!m.toggles.show_labels);
    m.handle(key('l', false));
    assert!(m.toggles.show_labels);
}
