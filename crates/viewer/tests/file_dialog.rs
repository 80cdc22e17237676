//! The viewer's files: the open and save-as dialog (no desktop portal), Ctrl+O / Ctrl+N /
//! Ctrl+Shift+S, dropped files, recent files kept across sessions, and a file that fails
//! to load leaving the scene as it was. Driven through the window-free interaction model
//! as the window drives it (a dropped file is `open_path`); expected scenes are the ones
//! written to disk by the test.

use std::path::{Path, PathBuf};

use glam::{DVec2, DVec3};
use splinescope_core::geom::{Bezier, Curve};
use splinescope_scene::format::{Scene, to_json_string};
use splinescope_viewer::edit::{Editor, recovery_path};
use splinescope_viewer::file_dialog::{DialogMode, Entry, FileDialog, RECENT_KEPT, RecentFiles};
use splinescope_viewer::interaction::{Answer, Button, Input, Interaction, Key, Pending, Prompt};

const VIEWPORT: DVec2 = DVec2::new(1000.0, 700.0);

fn line(y: f64) -> Curve {
    Curve::Bezier(Bezier::new(vec![
        DVec3::new(0.0, y, 0.0),
        DVec3::new(1.0, y + 1.0, 0.0),
        DVec3::new(2.0, y, 0.0),
    ]))
}

/// A fresh directory for one test.
fn fresh_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("splinescope-files-{tag}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A viewer of the scene saved at `path`, keeping its recent files in `dir`.
fn viewer(path: &Path, dir: &Path) -> Interaction {
    let (scene, text) = Scene::read(path).unwrap();
    let mut m = Interaction::new(
        Editor::of_file(scene, path.to_path_buf(), text),
        VIEWPORT,
        1.0,
        260.0,
    );
    m.recent = RecentFiles::load(Some(dir.join("config").join("recent.txt")));
    m
}

fn ctrl(c: char, shift: bool) -> Input {
    Input::Key {
        key: Key::Char(c),
        ctrl: true,
        shift,
    }
}

/// An edit: the first curve's first point dragged 30 px right.
fn edit(m: &mut Interaction) {
    let at = m.scene().curves[0].curve.control_points()[0];
    let p = m.camera.pixel_from_world(at, VIEWPORT).unwrap();
    m.handle(Input::PointerMoved(p));
    m.handle(Input::Pressed(Button::Primary));
    m.handle(Input::PointerMoved(p + DVec2::new(30.0, 0.0)));
    m.handle(Input::Released);
    assert!(m.editor.is_dirty());
}

fn same_file(a: &Scene, b: &Scene) -> bool {
    to_json_string(a) == to_json_string(b)
}

#[test]
fn the_dialog_lists_directories_then_scene_files_and_walks_the_tree() {
    let dir = fresh_dir("dialog");
    std::fs::create_dir_all(dir.join("b-dir").join("inner")).unwrap();
    std::fs::create_dir_all(dir.join(".hidden-dir")).unwrap();
    for name in ["z.json", "a.JSON", "notes.txt", ".hidden.json"] {
        std::fs::write(dir.join(name), "{}").unwrap();
    }
    let mut d = FileDialog::new(DialogMode::Open, &dir, "");
    let listed: Vec<(&str, bool)> = d
        .entries
        .iter()
        .map(|e| (e.name.as_str(), e.is_dir))
        .collect();
    assert_eq!(
        listed,
        [("b-dir", true), ("a.JSON", false), ("z.json", false)]
    );
    // A click on a directory enters it; up comes back.
    d.pick(0);
    assert_eq!(d.dir, dir.join("b-dir").canonicalize().unwrap());
    assert_eq!(
        d.entries,
        [Entry {
            name: "inner".into(),
            is_dir: true
        }]
    );
    d.up();
    assert_eq!(d.dir, dir.canonicalize().unwrap());
    // A click on a file takes its name; nothing typed, or a missing file, is refused
    // with the reason.
    assert_eq!(d.confirm(), None);
    assert!(
        d.error.as_deref().unwrap().contains("file name"),
        "{:?}",
        d.error
    );
    d.name = "missing.json".into();
    assert_eq!(d.confirm(), None);
    assert!(
        d.error.as_deref().unwrap().contains("no such file"),
        "{:?}",
        d.error
    );
    let z = d.entries.iter().position(|e| e.name == "z.json").unwrap();
    d.pick(z);
    assert_eq!(d.name, "z.json");
    assert_eq!(d.confirm(), Some(d.dir.join("z.json")));
    // A typed directory is entered rather than chosen.
    d.name = "b-dir".into();
    assert_eq!(d.confirm(), None);
    assert!(d.dir.ends_with("b-dir"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn save_as_adds_json_refuses_missing_directories_and_replaces_only_when_confirmed_twice() {
    let dir = fresh_dir("save-as");
    std::fs::write(dir.join("taken.json"), "old").unwrap();
    let mut d = FileDialog::new(DialogMode::SaveAs, &dir, "fresh");
    assert_eq!(d.confirm(), Some(dir.join("fresh.json")));
    d.name = "nowhere/x.json".into();
    assert_eq!(d.confirm(), None);
    assert!(
        d.error.as_deref().unwrap().contains("no such directory"),
        "{:?}",
        d.error
    );
    d.name = "taken.json".into();
    assert_eq!(d.confirm(), None, "an existing file asks first");
    assert!(
        d.error.as_deref().unwrap().contains("replace"),
        "{:?}",
        d.error
    );
    assert_eq!(d.confirm(), Some(dir.join("taken.json")));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn ctrl_o_opens_a_file_in_place_of_the_scene_and_remembers_it() {
    let dir = fresh_dir("open");
    let (a, b) = (dir.join("a.json"), dir.join("b.json"));
    Scene::of_curves([line(0.0)]).save(&a).unwrap();
    let other = Scene::of_curves([line(5.0), line(7.0)]);
    other.save(&b).unwrap();
    let mut m = viewer(&a, &dir);
    m.editor.take_changed();
    m.handle(ctrl('o', false));
    let d = m.dialog.as_mut().expect("Ctrl+O shows the dialog");
    assert_eq!(d.mode, DialogMode::Open);
    assert_eq!(d.dir, dir, "it starts in the file's directory");
    d.name = "b.json".into();
    m.confirm_dialog();
    assert_eq!(m.dialog, None);
    assert!(same_file(m.scene(), &other));
    assert_eq!(m.editor.path(), Some(b.as_path()));
    assert!(!m.editor.is_dirty());
    assert_eq!(m.editor.history_len(), (0, 0), "a fresh history");
    assert!(
        m.editor.title().starts_with("b.json — "),
        "{}",
        m.editor.title()
    );
    assert!(
        m.editor.take_changed().list,
        "the window rebuilds everything"
    );
    assert_eq!(m.recent.paths, std::slice::from_ref(&b));
    // Remembered across sessions, newest first, each once.
    m.open_path(&a);
    m.open_path(&b);
    let again = RecentFiles::load(m.recent.store.clone());
    assert_eq!(again.paths, [b.clone(), a.clone()]);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn opening_over_unsaved_changes_asks_and_each_answer_does_what_it_says() {
    let dir = fresh_dir("open-unsaved");
    let (a, b) = (dir.join("a.json"), dir.join("b.json"));
    let first = Scene::of_curves([line(0.0)]);
    first.save(&a).unwrap();
    let other = Scene::of_curves([line(5.0)]);
    other.save(&b).unwrap();

    // Cancel: nothing opened, the edit stays.
    let mut m = viewer(&a, &dir);
    edit(&mut m);
    let edited = m.scene().clone();
    m.open_path(&b);
    assert_eq!(
        m.prompt,
        Some(Prompt::Unsaved {
            then: Pending::Open(b.clone())
        })
    );
    m.answer(Answer::Cancel);
    assert_eq!(m.scene(), &edited);
    assert_eq!(m.editor.path(), Some(a.as_path()));

    // Discard: opened; a.json as it was, its recovery file gone.
    m.open_path(&b);
    m.answer(Answer::Discard);
    assert!(same_file(m.scene(), &other));
    assert!(same_file(&Scene::load(&a).unwrap(), &first));
    assert!(!recovery_path(&a).exists());

    // Save: a.json holds the edit, then b.json is open.
    let mut m = viewer(&a, &dir);
    edit(&mut m);
    let edited = m.scene().clone();
    m.open_path(&b);
    m.answer(Answer::Accept);
    assert!(same_file(&Scene::load(&a).unwrap(), &edited));
    assert!(same_file(m.scene(), &other));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_file_that_fails_to_load_says_why_and_leaves_the_scene_as_it_was() {
    let dir = fresh_dir("broken");
    let a = dir.join("a.json");
    Scene::of_curves([line(0.0)]).save(&a).unwrap();
    let broken = dir.join("broken.json");
    std::fs::write(
        &broken,
        r#"{"curves": [{"type": "bezier", "points": [[0, 0], [1, "x"]]}]}"#,
    )
    .unwrap();
    let mut m = viewer(&a, &dir);
    edit(&mut m);
    let before = m.scene().clone();
    let history = m.editor.history_len();
    m.editor.take_changed();
    // Even after "open without saving", the edit survives a failed open.
    m.open_path(&broken);
    m.answer(Answer::Discard);
    let Some(Prompt::Failed { message }) = &m.prompt else {
        panic!("{:?}", m.prompt)
    };
    assert!(message.contains("broken.json"), "{message}");
    assert!(message.contains("unchanged"), "{message}");
    assert_eq!(m.scene(), &before);
    assert_eq!(m.editor.path(), Some(a.as_path()));
    assert_eq!(m.editor.history_len(), history);
    assert!(m.editor.take_changed().is_empty());
    assert!(m.recent.paths.is_empty(), "a failed open is not remembered");
    // Any answer (Esc here) closes the notice.
    m.handle(Input::Key {
        key: Key::Escape,
        ctrl: false,
        shift: false,
    });
    assert_eq!(m.prompt, None);
    assert!(
        recovery_path(&a).exists(),
        "the edits' recovery file stays while they are shown"
    );
    // A file that does not exist (a stale recent entry, a dropped link) is refused too.
    m.open_path(&dir.join("gone.json"));
    m.answer(Answer::Discard);
    assert!(matches!(m.prompt, Some(Prompt::Failed { .. })));
    assert_eq!(m.scene(), &before);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_new_scene_asks_where_on_first_save_and_a_close_waits_for_that_save() {
    let dir = fresh_dir("new");
    let a = dir.join("a.json");
    Scene::of_curves([line(0.0)]).save(&a).unwrap();
    let mut m = viewer(&a, &dir);
    m.handle(ctrl('n', false));
    assert!(m.scene().curves.is_empty());
    assert_eq!(m.editor.path(), None);
    assert!(
        m.editor.title().starts_with("untitled — "),
        "{}",
        m.editor.title()
    );
    let index = m.add_curve(
        splinescope_viewer::interaction::Template::of_family("bezier").expect("a Bézier template"),
        DVec3::ZERO,
    );
    assert_eq!(index, 0);
    let drawn = m.scene().clone();
    // Ctrl+Q: unsaved; save → where? The dialog; its save writes, then the window closes.
    assert!(!m.handle(ctrl('q', false)).exit);
    assert!(!m.answer(Answer::Accept).exit);
    let d = m
        .dialog
        .as_mut()
        .expect("a scene without a file asks where");
    assert_eq!(d.mode, DialogMode::SaveAs);
    d.name = "drawn".into();
    assert!(m.confirm_dialog().exit);
    let saved = dir.join("drawn.json");
    assert!(same_file(&Scene::load(&saved).unwrap(), &drawn));
    assert_eq!(m.recent.paths[0], saved);

    // Ctrl+Shift+S writes a copy elsewhere and goes on editing that copy.
    let mut m = viewer(&a, &dir);
    edit(&mut m);
    m.handle(ctrl('s', true));
    let d = m.dialog.as_mut().unwrap();
    assert_eq!(d.name, "a.json", "it proposes the file's name");
    d.name = "copy.json".into();
    m.confirm_dialog();
    let copy = dir.join("copy.json");
    assert!(same_file(&Scene::load(&copy).unwrap(), m.scene()));
    assert_eq!(m.editor.path(), Some(copy.as_path()));
    assert!(!m.editor.is_dirty());
    // Esc closes a dialog without doing anything.
    m.handle(ctrl('s', true));
    m.handle(Input::Key {
        key: Key::Escape,
        ctrl: false,
        shift: false,
    });
    assert_eq!(m.dialog, None);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn recent_files_keep_the_newest_ten_and_survive_a_missing_store() {
    let dir = fresh_dir("recent");
    let store = dir.join("deep").join("recent.txt");
    let mut r = RecentFiles::load(Some(store.clone()));
    assert!(r.paths.is_empty());
    for i in 0..(RECENT_KEPT + 3) {
        r.add(&dir.join(format!("{i}.json"))).unwrap();
    }
    r.add(&dir.join("5.json")).unwrap();
    let back = RecentFiles::load(Some(store));
    assert_eq!(back.paths.len(), RECENT_KEPT);
    assert_eq!(back.paths[0], dir.join("5.json"));
    assert_eq!(back.paths[1], dir.join(format!("{}.json", RECENT_KEPT + 2)));
    assert_eq!(
        back.paths.iter().filter(|p| p.ends_with("5.json")).count(),
        1
    );
    // A store that cannot be written is reported, the list kept in memory.
    std::fs::write(dir.join("file"), "").unwrap();
    let mut r = RecentFiles::load(Some(dir.join("file").join("recent.txt")));
    let err = r.add(&dir.join("x.json")).unwrap_err();
    assert!(err.to_string().contains("recent"), "{err}");
    assert_eq!(r.paths, [dir.join("x.json")]);
    std::fs::remove_dir_all(&dir).ok();
}

/// file → export view…: the dialog proposes the scene's name as SVG, refuses other
/// formats, asks before replacing, and writes what is on screen — the model's camera,
/// viewport and toggles — as the figure layer draws it.
#[test]
fn export_view_writes_the_figure_of_the_screen() {
    let dir = fresh_dir("export");
    let a = dir.join("a.json");
    Scene::of_curves([line(0.0), line(3.0)]).save(&a).unwrap();
    let mut m = viewer(&a, &dir);
    m.viewport = DVec2::new(640.0, 400.0);
    m.camera.pan(DVec2::new(37.0, -12.0), m.viewport);
    m.toggles.show_points = false;
    m.export_dialog();
    let d = m.dialog.as_mut().expect("the export dialog");
    assert_eq!(d.mode, DialogMode::Export);
    assert_eq!(d.name, "a.svg");
    d.name = "figure.txt".into();
    m.confirm_dialog();
    let d = m.dialog.as_mut().expect("still open");
    assert!(
        d.error.as_deref().unwrap_or("").contains(".svg or .pdf"),
        "{:?}",
        d.error
    );
    d.name = "figure".into();
    m.confirm_dialog();
    assert_eq!(m.dialog, None);
    let written = std::fs::read_to_string(dir.join("figure.svg")).expect("written as .svg");
    // The canvas right of the 260 px panel: 380 × 400, every world point where the screen
    // shows it, less the panel's strip.
    let (w, h, camera) = m.export_frame();
    assert_eq!((w, h), (380, 400));
    for p in [
        DVec3::new(0.3, 0.7, 0.0),
        DVec3::new(-2.0, 5.0, 0.0),
        DVec3::new(4.0, 1.0, 0.0),
    ] {
        let screen = m.camera.pixel_from_world(p, m.viewport).unwrap();
        let figure = camera
            .pixel_from_world(p, DVec2::new(380.0, 400.0))
            .unwrap();
        assert!(
            (screen - DVec2::new(260.0, 0.0) - figure).length() < 1e-9,
            "{p}: screen {screen}, figure {figure}"
        );
    }
    assert!(
        written.contains(r#"width="380""#),
        "the figure is the canvas's size"
    );
    let mut opts = splinescope_figure::FigureOptions::new(380, 400);
    opts.camera = Some(camera);
    opts.switches = splinescope_encoding::draw::Switches {
        polygons: m.toggles.show_polygons,
        points: false,
    };
    opts.labels = true;
    let want =
        splinescope_figure::svg::write(&splinescope_figure::build(m.scene(), &opts).unwrap());
    assert_eq!(written, want, "the figure of the screen");
    assert!(
        !written.contains("<circle"),
        "points hidden on screen stay hidden"
    );
    // A second export to the same name asks first; a PDF is a PDF.
    m.export_dialog();
    m.dialog.as_mut().unwrap().name = "figure.svg".into();
    m.confirm_dialog();
    assert!(
        m.dialog
            .as_ref()
            .unwrap()
            .error
            .as_deref()
            .unwrap()
            .contains("replace")
    );
    m.cancel_dialog();
    m.export_dialog();
    m.dialog.as_mut().unwrap().name = "figure.pdf".into();
    m.confirm_dialog();
    assert!(
        std::fs::read(dir.join("figure.pdf"))
            .unwrap()
            .starts_with(b"%PDF")
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// The open dialog lists scene files and the files it imports (SVG); save-as lists scene
/// files alone; the export dialog lists figures.
#[test]
fn each_dialog_lists_the_files_it_is_for() {
    let dir = fresh_dir("listing-by-mode");
    for name in ["a.json", "b.svg", "c.PDF", "d.txt"] {
        std::fs::write(dir.join(name), b"x").unwrap();
    }
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    let names = |mode| -> Vec<String> {
        FileDialog::new(mode, &dir, "")
            .entries
            .iter()
            .map(|e| e.name.clone())
            .collect()
    };
    assert_eq!(names(DialogMode::Open), ["sub", "a.json", "b.svg"]);
    assert_eq!(names(DialogMode::SaveAs), ["sub", "a.json"]);
    assert_eq!(names(DialogMode::Export), ["sub", "b.svg", "c.PDF"]);
}
