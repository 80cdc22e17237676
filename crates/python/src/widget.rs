//! `_Interaction`: the viewer's window-free model (`splinescope_viewer::interaction`)
//! for the notebook widget (`splinescope.Widget`): the same picking, dragging, paper 000's
//! pull, zoom, pan, orbit, keys and undo as the window, fed the page's pointer and key
//! events, and its picture drawn by the one render entry point with the model's camera.

use std::sync::{Mutex, MutexGuard, PoisonError};

use glam::{DVec2, DVec3};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use splinescope_core::analysis::CurveAnalysis;
use splinescope_core::geom::Curve;
use splinescope_encoding::camera::Camera;
use splinescope_encoding::draw::Switches;
use splinescope_figure::TextOptions;
use splinescope_render::RenderRequest;
use splinescope_scene::format::shape::{CombScale, ShapeOptions};
use splinescope_viewer::edit::Editor;
use splinescope_viewer::interaction::{Button, Input, Interaction, Key};
use splinescope_viewer::shape::Readouts;

use crate::errors::{SceneError, raise};
use crate::scene::{PyScene, backend_choice, image_array, render_on};

/// The widest and tallest picture, in physical pixels (the texture side every device
/// takes).
const MAX_SIDE_PX: f64 = 8192.0;

/// The farthest from the picture a pointer position is taken, in logical pixels.
const MAX_POINTER_PX: f64 = 1e6;

/// What the picture depends on besides the curves: when none of it changes and no curve
/// does, an event needs no new frame.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Look {
    camera: Camera,
    polygons: bool,
    points: bool,
    labels: bool,
    shape: ShapeOptions,
}

/// The viewer's interaction model behind a notebook widget. Sizes and positions are in
/// the page's logical pixels; the model and the picture work in physical pixels (times
/// the pixel ratio).
#[pyclass(name = "_Interaction", module = "splinescope._splinescope")]
pub struct PyInteraction(Mutex<Inner>);

/// The model and what the widget keeps beside it (behind the lock: the kernel may hand
/// the widget's messages to another thread).
struct Inner {
    model: Interaction,
    /// The logical size and the pixel ratio.
    size: (f64, f64, f64),
    /// Edits not yet handed to Python: (curve or `None` for the whole list, the point
    /// being dragged).
    edits: Vec<(Option<usize>, Option<usize>)>,
    /// Whether the picture changed since the last frame.
    stale: bool,
    /// The selected curve's readouts and the curve they were computed for: a pointer move
    /// asks only for the nearest point, not for the length and the box again.
    readouts: Option<(usize, Curve, Readouts)>,
}

fn check_size(width: f64, height: f64, ratio: f64) -> PyResult<()> {
    for (name, v) in [("width", width), ("height", height), ("pixel_ratio", ratio)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(raise::<SceneError>(
                format!("{name} {v}: must be a finite number above 0"),
                name,
            ));
        }
    }
    let (w, h) = ((width * ratio).round(), (height * ratio).round());
    if w > MAX_SIDE_PX || h > MAX_SIDE_PX {
        return Err(raise::<SceneError>(
            format!(
                "{width} x {height} at pixel ratio {ratio}: {w} x {h} pixels, more than {MAX_SIDE_PX} a side"
            ),
            "width",
        ));
    }
    RenderRequest::new(w.max(1.0) as u32, h.max(1.0) as u32)
        .check()
        .map_err(|e| raise::<SceneError>(e.to_string(), "width"))
}

impl Inner {
    fn viewport(&self) -> DVec2 {
        let (w, h, r) = self.size;
        DVec2::new((w * r).round().max(1.0), (h * r).round().max(1.0))
    }

    fn look(&self) -> Look {
        let m = &self.model;
        let mut shape = m.shape.marker_options();
        if m.shape.comb {
            shape.comb = Some(CombScale::Fixed(m.shape.comb_scale));
        }
        Look {
            camera: m.camera,
            polygons: m.toggles.show_polygons,
            points: m.toggles.show_points,
            labels: m.toggles.show_labels,
            shape,
        }
    }

    /// Feeds one input; whether the picture changed. Edits are queued for Python.
    fn feed(&mut self, input: Input) -> bool {
        let before = self.look();
        self.model.handle(input);
        let changes = self.model.editor.take_changed();
        let dragged = self
            .model
            .is_editing()
            .then_some(self.model.editor.selected_point)
            .flatten();
        if changes.list {
            self.edits.push((None, dragged));
        }
        for curve in &changes.curves {
            self.edits.push((Some(*curve), dragged));
        }
        let changed = !changes.is_empty() || self.look() != before;
        self.stale |= changed;
        changed
    }
}

impl PyInteraction {
    fn lock(&self) -> MutexGuard<'_, Inner> {
        self.0.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

#[pymethods]
impl PyInteraction {
    /// The model of `scene` shown `width × height` logical pixels at `pixel_ratio`.
    #[new]
    #[pyo3(signature = (scene, width, height, pixel_ratio=1.0))]
    fn new(scene: &PyScene, width: f64, height: f64, pixel_ratio: f64) -> PyResult<Self> {
        check_size(width, height, pixel_ratio)?;
        let viewport = DVec2::new(
            (width * pixel_ratio).round().max(1.0),
            (height * pixel_ratio).round().max(1.0),
        );
        // The scene's own view, fitted when it is "auto" (no panel takes room here).
        let mut model = Interaction::new(
            Editor::new(scene.scene().clone(), None),
            viewport,
            pixel_ratio,
            0.0,
        );
        // The notebook has no panel and writes no labels unless asked (`L`).
        model.toggles.show_panel = false;
        model.toggles.show_labels = false;
        let out = PyInteraction(Mutex::new(Inner {
            model,
            size: (width, height, pixel_ratio),
            edits: Vec::new(),
            stale: true,
            readouts: None,
        }));
        Ok(out)
    }

    /// A new size (the page's resize event): the view keeps its centre and scale, or is
    /// fitted again while it follows the scene.
    fn resize(&self, width: f64, height: f64, pixel_ratio: f64) -> PyResult<bool> {
        let mut this = self.lock();
        check_size(width, height, pixel_ratio)?;
        if (width, height, pixel_ratio) == this.size {
            return Ok(false);
        }
        let old = this.model.camera;
        let old_ratio = this.size.2;
        this.size = (width, height, pixel_ratio);
        this.model.viewport = this.viewport();
        this.model.scale_factor = pixel_ratio;
        if this.model.auto_fit {
            this.model.fit();
        } else if let Camera::Ortho2d(mut c) = old {
            // The same world size per logical pixel.
            c.pixels_per_unit *= pixel_ratio / old_ratio;
            this.model.camera = Camera::Ortho2d(c);
        }
        this.stale = true;
        Ok(true)
    }

    /// The pointer moved to (`x`, `y`) logical pixels; whether the picture changed.
    fn pointer_move(&self, x: f64, y: f64) -> bool {
        let mut this = self.lock();
        // A page sends positions on or near the picture; anything else (not finite, or a
        // million pixels away) is no pointer and is ignored.
        if !(x.is_finite() && y.is_finite()) || x.abs() > MAX_POINTER_PX || y.abs() > MAX_POINTER_PX
        {
            return false;
        }
        let r = this.size.2;
        this.feed(Input::PointerMoved(DVec2::new(x * r, y * r)))
    }

    /// A button went down: `1` primary, `2` secondary, `3` middle (the page's numbering);
    /// other buttons do nothing.
    fn pointer_down(&self, button: u32) -> bool {
        let mut this = self.lock();
        let button = match button {
            1 => Button::Primary,
            2 => Button::Secondary,
            3 => Button::Middle,
            _ => return false,
        };
        this.feed(Input::Pressed(button))
    }

    /// The button went up.
    fn pointer_up(&self) -> bool {
        let mut this = self.lock();
        this.feed(Input::Released)
    }

    /// The wheel turned `lines` lines (positive: zoom in) at the pointer.
    fn wheel(&self, lines: f64) -> bool {
        let mut this = self.lock();
        // A page's wheel turns a few notches at a time; more than 100 lines is no wheel.
        if !lines.is_finite() || lines.abs() > 100.0 {
            return false;
        }
        this.feed(Input::Wheel(lines))
    }

    /// A key went down: a character, `Escape`, `Delete`/`Backspace` or `F1`; whether the
    /// picture changed. Other keys do nothing, nor do the window's file and window
    /// commands (`Ctrl+S`, `Ctrl+O`, `Ctrl+N`, `Ctrl+Q`).
    fn key(&self, key: &str, ctrl: bool, shift: bool) -> bool {
        let mut this = self.lock();
        let key = match key {
            "Escape" => Key::Escape,
            "Delete" | "Backspace" => Key::Delete,
            "F1" => Key::Help,
            k => {
                let mut chars = k.chars();
                match (chars.next(), chars.next()) {
                    // The window's file and window commands (save, open, new, quit) have
                    // no place in a notebook: their dialogs and prompts would stop the
                    // widget, unseen, until Esc.
                    (Some(c), None) if ctrl && "sonqSONQ".contains(c) => return false,
                    (Some(c), None) => Key::Char(c),
                    _ => return false,
                }
            }
        };
        this.feed(Input::Key { key, ctrl, shift })
    }

    /// The edited scene (a new value).
    fn scene(&self) -> PyScene {
        let this = self.lock();
        PyScene::of(this.model.scene().clone())
    }

    /// Replaces the scene (its curves as one undoable edit; during a drag of a point the
    /// new curves still have, the drag goes on over them). Not reported as an edit.
    fn set_scene(&self, scene: &PyScene) {
        let mut this = self.lock();
        this.model.editor.replace_scene(scene.scene().clone());
        this.model.editor.take_changed();
        if this.model.auto_fit {
            this.model.fit();
        }
        this.stale = true;
    }

    /// The edits since the last call: `(curve or None for the whole list, the dragged
    /// point or None)`, in order.
    fn take_edits(&self) -> Vec<(Option<usize>, Option<usize>)> {
        let mut this = self.lock();
        std::mem::take(&mut this.edits)
    }

    /// Whether the picture changed since the last frame (and forgets it).
    fn take_stale(&self) -> bool {
        let mut this = self.lock();
        std::mem::take(&mut this.stale)
    }

    /// Whether a drag edits the scene now.
    #[getter]
    fn editing(&self) -> bool {
        let this = self.lock();
        this.model.is_editing()
    }

    /// The picture's size in logical pixels and the pixel ratio: `(width, height,
    /// ratio)`, as the page last said.
    #[getter]
    fn size(&self) -> (f64, f64, f64) {
        self.lock().size
    }

    /// The selected curve, if any.
    #[getter]
    fn selected(&self) -> Option<usize> {
        let this = self.lock();
        this.model.editor.selected
    }

    /// Whether the combs are drawn.
    #[getter]
    fn comb(&self) -> bool {
        let this = self.lock();
        this.model.shape.comb
    }

    /// Turns the combs on or off (a scale chosen for the view when turned on).
    #[setter]
    fn set_comb(&self, on: bool) {
        let mut this = self.lock();
        if this.model.shape.comb != on {
            this.model.toggle_comb();
            this.stale = true;
        }
    }

    /// The comb's scale: the world length of a hair per unit of curvature.
    #[getter]
    fn comb_scale(&self) -> f64 {
        let this = self.lock();
        this.model.shape.comb_scale
    }

    /// Turns the markers on or off: `inflections`, `curvature_extrema`,
    /// `intersections`, `joints`.
    fn set_marker(&self, name: &str, on: bool) -> PyResult<()> {
        let mut this = self.lock();
        let s = &mut this.model.shape;
        let slot = match name {
            "inflections" => &mut s.inflections,
            "curvature_extrema" => &mut s.curvature_extrema,
            "intersections" => &mut s.intersections,
            "joints" => &mut s.joints,
            other => {
                return Err(raise::<SceneError>(
                    format!(
                        "marker {other:?}: not one of inflections, curvature_extrema, intersections, joints"
                    ),
                    "markers",
                ));
            }
        };
        if *slot != on {
            *slot = on;
            this.stale = true;
        }
        Ok(())
    }

    /// The message the viewer would show (a refused drag, an edit cancelled), if any.
    #[getter]
    fn message(&self) -> Option<String> {
        let this = self.lock();
        this.model.editor.message.clone()
    }

    /// How many edits can be undone and redone.
    fn history_len(&self) -> (usize, usize) {
        let this = self.lock();
        this.model.editor.history_len()
    }

    /// The view as the scene format writes it (`{"kind": "2d", "center": [x, y],
    /// "height": h}` or the 3D orbit), so that a scene given this view renders as the
    /// widget shows it.
    fn view<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let this = self.lock();
        let d = PyDict::new(py);
        match this.model.camera {
            Camera::Ortho2d(c) => {
                d.set_item("kind", "2d")?;
                d.set_item("center", vec![c.center.x, c.center.y])?;
                d.set_item("height", this.viewport().y / c.pixels_per_unit)?;
            }
            Camera::Orbit3d(c) => {
                d.set_item("kind", "3d")?;
                d.set_item("target", vec![c.target.x, c.target.y, c.target.z])?;
                d.set_item("distance", c.distance)?;
                d.set_item("yaw_deg", c.yaw.to_degrees())?;
                d.set_item("pitch_deg", c.pitch.to_degrees())?;
                d.set_item("fov_deg", c.fov_y.to_degrees())?;
            }
        }
        Ok(d)
    }

    /// Where (`x`, `y`) logical pixels of the picture is in the scene (2D views; in 3D on
    /// the plane through the view's target).
    fn world_at(&self, x: f64, y: f64) -> (f64, f64, f64) {
        let this = self.lock();
        let r = this.size.2;
        let p = this
            .model
            .camera
            .world_from_pixel(DVec2::new(x * r, y * r), this.viewport());
        (p.x, p.y, p.z)
    }

    /// Where the scene point `p` is drawn, in logical pixels (`None` behind a 3D camera).
    fn pixel_of(&self, p: (f64, f64, f64)) -> Option<(f64, f64)> {
        let this = self.lock();
        let r = this.size.2;
        this.model
            .camera
            .pixel_from_world(DVec3::new(p.0, p.1, p.2), this.viewport())
            .map(|q| (q.x / r, q.y / r))
    }

    /// The selected curve's readouts: its name, family, length, tight box, area when
    /// closed and planar, and at the point of the curve nearest the pointer its
    /// parameter, distance and signed curvature. `None` with no selection.
    fn readout<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let mut this = self.lock();
        let this = &mut *this;
        let Some(index) = this.model.editor.selected else {
            return Ok(None);
        };
        let scene = this.model.scene();
        let Some(sc) = scene.curves.get(index) else {
            return Ok(None);
        };
        let fresh = matches!(&this.readouts, Some((i, c, _)) if *i == index && *c == sc.curve);
        if !fresh {
            this.readouts = Readouts::of(scene, index, None).map(|r| (index, sc.curve.clone(), r));
        }
        let Some((_, _, r)) = &this.readouts else {
            return Ok(None);
        };
        let d = PyDict::new(py);
        d.set_item("curve", index)?;
        d.set_item("name", sc.label())?;
        d.set_item("family", sc.curve.family())?;
        d.set_item("length", r.length)?;
        d.set_item(
            "box",
            (
                vec![r.bbox.min.x, r.bbox.min.y, r.bbox.min.z],
                vec![r.bbox.max.x, r.bbox.max.y, r.bbox.max.z],
            ),
        )?;
        d.set_item("area", r.area)?;
        let a = CurveAnalysis::new(&sc.curve);
        let cursor = this.model.cursor_world();
        if let Ok(n) = a.nearest(cursor) {
            d.set_item("t", n.t)?;
            d.set_item("distance", n.distance)?;
            d.set_item("curvature", a.signed_curvature(n.t))?;
        }
        Ok(Some(d))
    }

    /// The picture as the widget shows it: an `(H, W, 4)` uint8 array, `H × W` the
    /// logical size times the pixel ratio.
    #[pyo3(signature = (backend="auto"))]
    fn render<'py>(&self, py: Python<'py>, backend: &str) -> PyResult<Bound<'py, PyAny>> {
        let choice = backend_choice(backend)?;
        // What to draw, taken under the lock and drawn without it: the GPU work runs
        // without the GIL, and another thread holding the GIL may be waiting for the lock.
        let (scene, request) = {
            let mut this = self.lock();
            let look = this.look();
            let viewport = this.viewport();
            let request = RenderRequest::new(viewport.x as u32, viewport.y as u32)
                .with_tolerance_px(this.model.tolerance_px)
                .with_camera(look.camera)
                .with_switches(Switches {
                    polygons: look.polygons,
                    points: look.points,
                })
                .with_shape(look.shape)
                .with_text(TextOptions {
                    labels: look.labels,
                    ..TextOptions::default()
                });
            this.stale = false;
            (this.model.scene().clone(), request)
        };
        let image = render_on(py, choice, &scene, &request)?;
        image_array(py, image)
    }
}
