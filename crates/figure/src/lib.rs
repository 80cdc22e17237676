//! splinescope's figure layer: a scene as a vector figure — SVG and PDF — with exact
//! curves where exact is possible, everything the renderer draws styled as drawn.
//!
//! [`build`] turns a scene seen by a camera at an output size (in points, one per pixel
//! of `render`'s image) into a [`Figure`]: a display list of paths, discs and text in
//! output coordinates (y down). Each curve is one path: its lowered Bézier segments of
//! degree ≤ 3 under the 2D (affine) view keep their exact control points, other segments
//! and every 3D view become cubic pieces within the tolerance by a computed bound
//! ([`fit`]). [`svg::write`] and [`pdf::write`] write it.
//!
//! What it may use: [`splinescope_core`], [`splinescope_scene`] and pdf-writer — no GPU,
//! window or command-line crate: the command line, the viewer and the Python module
//! build on it.

#![forbid(unsafe_code)]

pub mod annotate;
pub mod fit;
pub mod pdf;
pub mod raster;
pub mod svg;
pub mod text;

use glam::{DVec2, DVec3};
use thiserror::Error;

use splinescope_scene::camera::Camera;
use splinescope_scene::scene::draw::{Stroke, Switches};
use splinescope_scene::scene::encoding::Encoding;
use splinescope_scene::scene::{Color, Scene};

use fit::{Piece, Projection, segment_pieces};

/// The default tolerance: a hundredth of an output point.
pub const DEFAULT_TOLERANCE: f64 = 0.01;

/// What to draw and how.
#[derive(Debug, Clone, PartialEq)]
pub struct FigureOptions {
    /// Output width in points (one per pixel of the PNG of the same size).
    pub width: u32,
    /// Output height in points.
    pub height: u32,
    /// The camera; `None`: the scene's own view for this size.
    pub camera: Option<Camera>,
    /// Largest distance, in output points, between a drawn piece and the exact curve.
    pub tolerance: f64,
    /// The curves' overlays (control polygons, points) as the panel's toggles allow.
    pub switches: Switches,
    /// Label each curve at its end (name and live shape parameters).
    pub labels: bool,
    /// A legend in the top right corner.
    pub legend: bool,
    /// Axes with ticks and tick labels in scene units (2D views).
    pub axes: bool,
    /// A grid at the ticks (2D views).
    pub grid: bool,
}

impl FigureOptions {
    /// The scene's own view at `width × height`, the default tolerance, every overlay.
    #[must_use]
    pub fn new(width: u32, height: u32) -> FigureOptions {
        FigureOptions {
            width,
            height,
            camera: None,
            tolerance: DEFAULT_TOLERANCE,
            switches: Switches::ALL,
            labels: false,
            legend: false,
            axes: false,
            grid: false,
        }
    }
}

/// The text a picture carries besides the curves (`render`, `export`, the viewer,
/// Python): what [`FigureOptions`]'s switches of the same names set.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct TextOptions {
    /// Each curve's label at its end.
    pub labels: bool,
    /// A legend.
    pub legend: bool,
    /// Axes with ticks in scene units (2D).
    pub axes: bool,
    /// A grid at the ticks (2D).
    pub grid: bool,
}

impl TextOptions {
    /// Whether any text or guide is asked for.
    #[must_use]
    pub fn any(self) -> bool {
        self.labels || self.legend || self.axes || self.grid
    }
}

impl FigureOptions {
    /// These options with `text`'s labels, legend, axes and grid.
    #[must_use]
    pub fn with_text(mut self, text: TextOptions) -> FigureOptions {
        self.labels = text.labels;
        self.legend = text.legend;
        self.axes = text.axes;
        self.grid = text.grid;
        self
    }
}

/// Why a figure cannot be made.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FigureError {
    /// The tolerance is not a positive finite number.
    #[error("tolerance {0}: must be a finite number greater than 0 (output points)")]
    Tolerance(f64),
    /// Axes or a grid asked of a 3D view.
    #[error(
        "axes and grids are drawn in scene units for 2D views only; this scene has a 3D view (its axis triad shows the directions)"
    )]
    AxesIn3d,
    /// A side of the output is zero or too large.
    #[error("figure size {width}×{height}: each side must be 1..=100000 points")]
    Size {
        /// Width asked for.
        width: u32,
        /// Height asked for.
        height: u32,
    },
}

/// A path of one or more connected runs (`M` starts each run).
#[derive(Debug, Clone, PartialEq)]
pub struct SubPath {
    /// Where the run starts.
    pub start: DVec2,
    /// Its commands, in order.
    pub pieces: Vec<Piece>,
}

/// One thing drawn, in output coordinates.
#[derive(Debug, Clone, PartialEq)]
pub enum Item {
    /// A stroked path (a curve, an overlay polyline).
    Path {
        /// Its runs.
        runs: Vec<SubPath>,
        /// How it is stroked.
        stroke: Stroke,
        /// The scene curve it draws, if it is one.
        curve: Option<usize>,
    },
    /// Text on a baseline.
    Text {
        /// Where the baseline starts, is centred or ends (by `anchor`).
        at: DVec2,
        /// Font size in points.
        size: f64,
        /// The text.
        text: String,
        /// Its colour.
        color: Color,
        /// Which end of the text `at` is.
        anchor: Anchor,
    },
    /// A filled rectangle, optionally outlined (the legend's box).
    Rect {
        /// Top left corner.
        min: DVec2,
        /// Bottom right corner.
        max: DVec2,
        /// Fill colour.
        fill: Color,
        /// Outline.
        stroke: Option<Stroke>,
    },
    /// A filled disc (a control point, an annotation point).
    Disc {
        /// Its centre.
        center: DVec2,
        /// Its radius.
        radius: f64,
        /// Its colour.
        color: Color,
    },
}

/// Which part of a text its position names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Anchor {
    /// The start of the baseline.
    Start,
    /// Its middle.
    Middle,
    /// Its end.
    End,
}

/// A scene as a vector figure (see the crate doc).
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// Width in points.
    pub width: f64,
    /// Height in points.
    pub height: f64,
    /// The background colour.
    pub background: Color,
    /// What is drawn, back to front: the grid ([`Figure::behind`]), overlay polylines,
    /// curves, points, then the axes, labels and legend ([`Figure::front`]).
    pub items: Vec<Item>,
    /// How many of `items` are the grid (drawn behind the scene).
    pub behind: usize,
    /// Where the axes, labels and legend start in `items` (drawn over the scene).
    pub front: usize,
    /// The map from world points to output points.
    pub projection: Projection,
    /// The tolerance the approximated pieces keep.
    pub tolerance: f64,
}

/// The projective map of `camera` for an output of `size` points.
#[must_use]
pub fn projection(camera: &Camera, size: DVec2) -> Projection {
    let m = camera.clip_from_world(size);
    let row = |i: usize| [m.x_axis[i], m.y_axis[i], m.z_axis[i], m.w_axis[i]];
    let (rx, ry, rw) = (row(0), row(1), row(3));
    let mut rows = [[0.0; 4]; 3];
    for k in 0..4 {
        rows[0][k] = 0.5 * size.x * (rx[k] + rw[k]);
        rows[1][k] = 0.5 * size.y * (rw[k] - ry[k]);
        rows[2][k] = rw[k];
    }
    Projection {
        rows,
        affine: matches!(camera, Camera::Ortho2d(_)),
    }
}

/// `scene` as a figure.
///
/// # Errors
/// [`FigureError`] for a tolerance that is not positive or a size out of range.
pub fn build(scene: &Scene, opts: &FigureOptions) -> Result<Figure, FigureError> {
    if !(opts.tolerance.is_finite() && opts.tolerance > 0.0) {
        return Err(FigureError::Tolerance(opts.tolerance));
    }
    if !(1..=100_000).contains(&opts.width) || !(1..=100_000).contains(&opts.height) {
        return Err(FigureError::Size {
            width: opts.width,
            height: opts.height,
        });
    }
    let size = DVec2::new(f64::from(opts.width), f64::from(opts.height));
    let camera = opts.camera.unwrap_or_else(|| scene.camera(size));
    let proj = projection(&camera, size);
    if (opts.axes || opts.grid) && !proj.affine {
        return Err(FigureError::AxesIn3d);
    }
    let encoding = Encoding::with(scene, opts.switches);
    let (mut items, guides) = annotate::axes(&proj, size, opts.axes, opts.grid);
    let behind = items.len();
    for (points, stroke) in &encoding.overlays.lines {
        let runs = polyline_runs(points, &proj);
        if !runs.is_empty() {
            items.push(Item::Path {
                runs,
                stroke: *stroke,
                curve: None,
            });
        }
    }
    for (index, curve) in encoding.curves.iter().enumerate() {
        let mut runs: Vec<SubPath> = Vec::new();
        for seg in &curve.segments {
            let Some(start) = seg.bezier.points().first().and_then(|&p| proj.point(p)) else {
                continue;
            };
            // Half the tolerance for the fit, the rest for rounding the written numbers.
            let Some(pieces) = segment_pieces(
                &seg.bezier,
                seg.weights.as_deref(),
                &proj,
                0.5 * opts.tolerance,
            ) else {
                continue;
            };
            match runs.last_mut() {
                Some(run) if run.pieces.last().map(|p| p.seg.end()) == Some(start) => {
                    run.pieces.extend(pieces);
                }
                _ => runs.push(SubPath { start, pieces }),
            }
        }
        items.push(Item::Path {
            runs,
            stroke: Stroke::solid(curve.color, curve.width),
            curve: Some(index),
        });
    }
    for (points, stroke) in &encoding.overlays.points {
        let radius = 0.5 * f64::from(stroke.width_px);
        let [r, g, b, a] = stroke.color.0;
        // The renderer's darker rim (the colour × 0.45 over the outer pixel and a half),
        // so that points read on top of curves of their own colour.
        let rim = Color([r * 0.45, g * 0.45, b * 0.45, a]);
        for &p in points {
            if let Some(center) = proj.point(p) {
                items.push(Item::Disc {
                    center,
                    radius,
                    color: rim,
                });
                if radius > 1.0 {
                    items.push(Item::Disc {
                        center,
                        radius: radius - 1.0,
                        color: stroke.color,
                    });
                }
            }
        }
    }
    let front = items.len();
    items.extend(guides);
    if opts.labels {
        annotate::labels(scene, &proj, size, &mut items);
    }
    if opts.legend {
        annotate::legend(scene, size, &mut items);
    }
    Ok(Figure {
        width: size.x,
        height: size.y,
        background: encoding.background,
        items,
        behind,
        front,
        projection: proj,
        tolerance: opts.tolerance,
    })
}

/// A polyline's visible runs (points behind the eye break it).
fn polyline_runs(points: &[DVec3], proj: &Projection) -> Vec<SubPath> {
    let mut runs: Vec<SubPath> = Vec::new();
    let mut open = false;
    for &p in points {
        match proj.point(p) {
            Some(q) if open => {
                if let Some(run) = runs.last_mut() {
                    run.pieces.push(Piece {
                        seg: fit::Seg::Line(q),
                        exact: true,
                    });
                }
            }
            Some(q) => {
                runs.push(SubPath {
                    start: q,
                    pieces: Vec::new(),
                });
                open = true;
            }
            None => open = false,
        }
    }
    runs
}

/// The colour as `#rrggbb` and its opacity.
#[must_use]
pub fn hex(color: Color) -> (String, f64) {
    let [r, g, b, a] = color
        .0
        .map(|c| (f64::from(c).clamp(0.0, 1.0) * 255.0).round() as u8);
    (format!("#{r:02x}{g:02x}{b:02x}"), f64::from(a) / 255.0)
}
