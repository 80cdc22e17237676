#![doc = include_str!("../README.md")]
#![forbid(unsafe_code)]

pub mod annotate;
pub mod fit;
pub mod pdf;
pub mod raster;
pub mod svg;
pub mod text;

use glam::{DVec2, DVec3};
use thiserror::Error;

use splinescope_encoding::camera::Camera;
use splinescope_encoding::draw::{COMB_WIDTH_PX, Stroke, Switches, comb_strokes};
use splinescope_encoding::{Color, Encoding, StrokeShape};
use splinescope_scene::format::Scene;
use splinescope_scene::format::encoding::encode_with;
use splinescope_scene::format::labels::Ink;
use splinescope_scene::format::shape::{ShapeOptions, marker_points, markers};

use fit::{Budget, FitError, Page, Piece, Projection, segment_pieces};

/// The default tolerance: a hundredth of an output point.
pub const DEFAULT_TOLERANCE: f64 = 0.01;

/// The finest tolerance: a millionth of an output point. Output coordinates reach 10⁵
/// points, where `f64` keeps about 10⁻¹¹, and the written decimals need room below the
/// tolerance; finer than this, rounding rather than shape would decide the pieces.
pub const MIN_TOLERANCE: f64 = 1e-6;

/// Checks a tolerance: a finite number of at least [`MIN_TOLERANCE`] output points.
///
/// # Errors
/// [`FigureError::Tolerance`] naming the value.
pub fn check_tolerance(tolerance: f64) -> Result<f64, FigureError> {
    if tolerance.is_finite() && tolerance >= MIN_TOLERANCE {
        Ok(tolerance)
    } else {
        Err(FigureError::Tolerance(tolerance))
    }
}

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
    /// The curves and overlays themselves; `false` makes only the guides and text (what
    /// [`raster::annotate`] draws over a picture the GPU made).
    pub curves: bool,
    /// The curvature combs and shape markers (drawn with the curves).
    pub shape: ShapeOptions,
    /// The comb of this curve alone (the viewer's "selected curve only"); `None`: every
    /// curve's.
    pub comb_only: Option<usize>,
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
            curves: true,
            shape: ShapeOptions::default(),
            comb_only: None,
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

    /// The text and guides these options ask for.
    #[must_use]
    pub fn text(&self) -> TextOptions {
        TextOptions {
            labels: self.labels,
            legend: self.legend,
            axes: self.axes,
            grid: self.grid,
        }
    }
}

/// Why a figure cannot be made.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FigureError {
    /// The tolerance is not a finite number of at least [`MIN_TOLERANCE`].
    #[error(
        "tolerance {}: must be a finite number of at least 1e-6 (output points; finer, f64 output coordinates cannot keep it)",
        splinescope_core::num::Num(*.0)
    )]
    Tolerance(f64),
    /// The view maps the scene to output coordinates `f64` cannot hold.
    #[error("the view {view} cannot be drawn at {width}×{height}: {why}")]
    View {
        /// The view, described.
        view: String,
        /// Width asked for.
        width: u32,
        /// Height asked for.
        height: u32,
        /// What overflows.
        why: String,
    },
    /// The fit needs more pieces than the limit allows.
    #[error(
        "keeping the tolerance {} needs more than {limit} path pieces (the figure's budget; a larger tolerance needs fewer, or raise it with the environment variable {var}=N)",
        splinescope_core::num::Num(*tolerance)
    )]
    Budget {
        /// The tolerance asked for.
        tolerance: f64,
        /// The budget in force.
        limit: u64,
        /// The variable that raises it.
        var: &'static str,
    },
    /// Halving stops helping: the tolerance is as fine as the rounding of the curve's
    /// output coordinates.
    #[error(
        "curves[{curve}]: the tolerance {} is finer than f64 keeps the curve's output coordinates in this view (they reach {magnitude:e} points); choose a larger tolerance or a wider view",
        splinescope_core::num::Num(*tolerance)
    )]
    Precision {
        /// The curve.
        curve: usize,
        /// The tolerance asked for.
        tolerance: f64,
        /// The largest output coordinate of the piece.
        magnitude: f64,
    },
    /// A number of the figure is not finite (the scene's coordinates or weights under
    /// this view leave `f64`).
    #[error(
        "{what}: its output coordinates are not finite numbers in this view (the scene's coordinates or weights are too large for it)"
    )]
    NotFinite {
        /// What holds it: `curves[3]`, `the control polygons`, `the labels`.
        what: String,
    },
    /// A limit's environment variable is malformed.
    #[error("{0}")]
    Limit(String),
    /// Axes or a grid asked of a 3D view.
    #[error(
        "axes and grids are drawn in scene units for 2D views only; this scene has a 3D view (its axis triad shows the directions)"
    )]
    AxesIn3d,
    /// A side of the output is zero or too large.
    #[error("figure size {width}×{height}: each side must be between 1 and 100000 points")]
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
        /// Its ends and corners (a curve's, as its style says; round for the overlays).
        shape: StrokeShape,
        /// Whether its one run ends where it starts as a closed curve (written closed:
        /// where it closes is a join, not two caps).
        closed: bool,
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

/// `camera`, described for messages.
fn describe_view(camera: &Camera) -> String {
    use splinescope_core::num::Num;
    match camera {
        Camera::Ortho2d(c) => format!(
            "(centre [{}, {}], {} output points per scene unit at this size)",
            Num(c.center.x),
            Num(c.center.y),
            Num(c.pixels_per_unit)
        ),
        Camera::Orbit3d(c) => format!(
            "(target [{}, {}, {}], distance {})",
            Num(c.target.x),
            Num(c.target.y),
            Num(c.target.z),
            Num(c.distance)
        ),
    }
}

/// Checks that `proj` is a map `f64` can apply: finite rows, and in 2D a scale that is
/// neither 0 nor infinite.
fn check_projection(
    proj: &Projection,
    camera: &Camera,
    opts: &FigureOptions,
) -> Result<(), FigureError> {
    let why = if !proj.rows.iter().flatten().all(|v| v.is_finite()) {
        Some("its map to output points overflows f64 (a centre too far out, or a scale too large)")
    } else if proj.affine && (proj.rows[0][0] == 0.0 || proj.rows[1][1] == 0.0) {
        Some("its scale underflows f64 (one scene unit is 0 output points)")
    } else {
        None
    };
    match why {
        None => Ok(()),
        Some(why) => Err(FigureError::View {
            view: describe_view(camera),
            width: opts.width,
            height: opts.height,
            why: why.to_owned(),
        }),
    }
}

/// The budget of path pieces per figure, from the limit in force.
fn budget() -> Result<Budget, FigureError> {
    let limit = splinescope_io::limits::FIGURE_PIECES
        .value()
        .map_err(|e| FigureError::Limit(e.to_string()))?;
    Ok(Budget::new(usize::try_from(limit).unwrap_or(usize::MAX)))
}

/// `scene` as a figure.
///
/// # Errors
/// [`FigureError`] for a tolerance out of range, a size out of range, axes in 3D, a view
/// `f64` cannot apply, a fit over the budget or below the coordinates' rounding, and any
/// output number that is not finite.
pub fn build(scene: &Scene, opts: &FigureOptions) -> Result<Figure, FigureError> {
    check_tolerance(opts.tolerance)?;
    if !(1..=100_000).contains(&opts.width) || !(1..=100_000).contains(&opts.height) {
        return Err(FigureError::Size {
            width: opts.width,
            height: opts.height,
        });
    }
    let size = DVec2::new(f64::from(opts.width), f64::from(opts.height));
    let camera = opts.camera.unwrap_or_else(|| scene.camera(size));
    let proj = projection(&camera, size);
    check_projection(&proj, &camera, opts)?;
    if (opts.axes || opts.grid) && !proj.affine {
        return Err(FigureError::AxesIn3d);
    }
    // What the curves draw — also where only the text is asked for (over a GPU picture
    // of the curves): labels and the legend keep clear of it.
    let draw_curves = opts.curves || opts.labels || opts.legend;
    let mut encoding = encode_with(scene, opts.switches);
    if draw_curves && opts.shape.any_marker() {
        let found = markers(scene, &opts.shape);
        encoding
            .overlays
            .points
            .extend(marker_points(scene, &found));
    }
    let (mut items, guides) = annotate::axes(&proj, size, opts.axes, opts.grid);
    let behind = items.len();
    let mut drawn = Vec::new();
    if draw_curves {
        if let Some(scale) = opts.shape.comb {
            let view_height = camera.view_height(size);
            let scale = scale.resolve(scene, view_height);
            let cap = opts.shape.comb_cap.world(view_height);
            comb_items(scene, (scale, cap, opts.comb_only), &proj, size, &mut drawn);
        }
        curve_items(&encoding, &proj, size, opts.tolerance, &mut drawn)?;
    }
    // Clear of everything drawn over the guides: curves, polygons, points, combs,
    // markers, the axes.
    let mut ink = Ink::new(size);
    if opts.labels || opts.legend {
        annotate::add_ink(&mut ink, &drawn);
        annotate::add_ink(&mut ink, &guides);
    }
    if opts.curves {
        items.append(&mut drawn);
    }
    let front = items.len();
    items.extend(guides);
    if opts.labels || opts.legend {
        let legend = if opts.legend {
            annotate::legend_layout(scene, size, &opts.shape.marker_kinds(), &ink, opts.labels)
        } else {
            None
        };
        // The legend and the text already placed (tick labels).
        let blocked: Vec<(DVec2, DVec2)> = legend
            .iter()
            .map(annotate::Legend::area)
            .chain(items.iter().filter_map(annotate::text_box))
            .collect();
        let hidden = if opts.labels {
            annotate::labels(scene, &proj, size, &ink, &blocked, &mut items)
        } else {
            0
        };
        if let Some(legend) = legend {
            annotate::legend(legend, hidden, &mut items);
        }
    }
    let fig = Figure {
        width: size.x,
        height: size.y,
        background: encoding.background,
        items,
        behind,
        front,
        projection: proj,
        tolerance: opts.tolerance,
    };
    fig.check_finite()?;
    Ok(fig)
}

/// The most hairs of a comb on one lowered segment (the GPU's; fewer on a short one).
use splinescope_core::analysis::comb::COMB_HAIRS_PER_SEGMENT;

/// Each curve's curvature comb ([`splinescope_core::analysis::comb::comb`]): its hairs as
/// one path of straight runs, then its envelope, in the curve's colour
/// ([`comb_strokes`]), at exact positions. A hair cut to the cap is drawn in the
/// envelope's stroke and the envelope is broken there, as the GPU draws them.
fn comb_items(
    scene: &Scene,
    (scale, cap, only): (f64, f64, Option<usize>),
    proj: &Projection,
    size: DVec2,
    items: &mut Vec<Item>,
) {
    let margin = DVec2::splat(2.0 + f64::from(COMB_WIDTH_PX));
    let page = Page {
        min: -margin,
        max: size + margin,
    };
    for (index, sc) in scene.curves.iter().enumerate() {
        if only.is_some_and(|o| o != index) {
            continue;
        }
        let analysis = splinescope_core::analysis::CurveAnalysis::new(&sc.curve);
        // The GPU's density: one hair every few pixels of each segment's projected control
        // polygon.
        let segments = splinescope_core::geom::Lower::lower(&sc.curve);
        let hairs_of = |k: usize| {
            segments.get(k).map_or(COMB_HAIRS_PER_SEGMENT, |seg| {
                let pts: Vec<DVec2> = seg
                    .bezier
                    .points()
                    .iter()
                    .filter_map(|p| proj.point(*p))
                    .collect();
                if pts.len() != seg.bezier.points().len() {
                    return COMB_HAIRS_PER_SEGMENT;
                }
                splinescope_core::analysis::comb::hairs_for(
                    pts.windows(2).map(|w| (w[1] - w[0]).length()).sum(),
                )
            })
        };
        let hairs = splinescope_core::analysis::comb::comb(&analysis, &hairs_of, scale, cap);
        let (hair_stroke, envelope_stroke) = comb_strokes(sc.style.color);
        for (capped, stroke) in [(false, hair_stroke), (true, envelope_stroke)] {
            let runs: Vec<SubPath> = hairs
                .iter()
                .filter(|h| h.tip != h.point && h.capped == capped)
                .flat_map(|h| polyline_runs(&[h.point, h.tip], proj, &page))
                .collect();
            if !runs.is_empty() {
                items.push(Item::Path {
                    runs,
                    stroke,
                    shape: StrokeShape::default(),
                    closed: false,
                    curve: None,
                });
            }
        }
        // The envelope: the tips between capped hairs, each stretch its own polyline.
        let runs: Vec<SubPath> = hairs
            .split(|h| h.capped)
            .filter(|stretch| stretch.len() >= 2)
            .flat_map(|stretch| {
                let tips: Vec<DVec3> = stretch.iter().map(|h| h.tip).collect();
                polyline_runs(&tips, proj, &page)
            })
            .collect();
        if !runs.is_empty() {
            items.push(Item::Path {
                runs,
                stroke: envelope_stroke,
                shape: StrokeShape::default(),
                closed: false,
                curve: None,
            });
        }
    }
}

/// The overlay polylines, the curves and the points of `encoding`, in drawing order.
fn curve_items(
    encoding: &Encoding,
    proj: &Projection,
    size: DVec2,
    tolerance: f64,
    items: &mut Vec<Item>,
) -> Result<(), FigureError> {
    let mut budget = budget()?;
    for (points, stroke) in &encoding.overlays.lines {
        // Legs beyond the page by more than the stroke cannot be seen.
        let margin = DVec2::splat(f64::from(stroke.width_px) + 2.0);
        let page = Page {
            min: -margin,
            max: size + margin,
        };
        let runs = polyline_runs(points, proj, &page);
        if !runs.is_empty() {
            items.push(Item::Path {
                runs,
                stroke: *stroke,
                shape: StrokeShape::default(),
                closed: false,
                curve: None,
            });
        }
    }
    for (index, curve) in encoding.curves.iter().enumerate() {
        let width = stroke_width(curve, proj);
        // Pieces beyond the page by more than the stroke cannot be seen.
        let margin = DVec2::splat(f64::from(width) + 2.0);
        let page = Page {
            min: -margin,
            max: size + margin,
        };
        let mut runs: Vec<SubPath> = Vec::new();
        for seg in &curve.segments {
            let Some(start) = seg.bezier.points().first().and_then(|&p| proj.point(p)) else {
                continue;
            };
            // Half the tolerance for the fit, the rest for rounding the written numbers.
            let pieces = segment_pieces(
                &seg.bezier,
                seg.weights.as_deref(),
                proj,
                0.5 * tolerance,
                Some(&page),
                &mut budget,
            )
            .map_err(|e| match e {
                FitError::Budget { limit } => FigureError::Budget {
                    tolerance,
                    limit: limit as u64,
                    var: splinescope_io::limits::FIGURE_PIECES.var,
                },
                FitError::Precision { magnitude } => FigureError::Precision {
                    curve: index,
                    tolerance,
                    magnitude,
                },
                FitError::NotFinite => FigureError::NotFinite {
                    what: format!("curves[{index}]"),
                },
            })?;
            let Some(pieces) = pieces else {
                continue;
            };
            match runs.last_mut() {
                Some(run) if run.pieces.last().map(|p| p.seg.end()) == Some(start) => {
                    run.pieces.extend(pieces);
                }
                _ => runs.push(SubPath { start, pieces }),
            }
        }
        let closed = curve.closed
            && runs.len() == 1
            && runs[0].pieces.last().map(|p| p.seg.end()) == Some(runs[0].start);
        items.push(Item::Path {
            runs,
            stroke: Stroke::solid(curve.color, width),
            shape: curve.stroke,
            closed,
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
    Ok(())
}

impl Item {
    /// Whether every number of the item is finite.
    fn is_finite(&self) -> bool {
        match self {
            Item::Path { runs, .. } => runs.iter().all(|r| {
                r.start.is_finite()
                    && r.pieces.iter().all(|p| match p.seg {
                        fit::Seg::Line(a) => a.is_finite(),
                        fit::Seg::Quad(a, b) => a.is_finite() && b.is_finite(),
                        fit::Seg::Cubic(a, b, c) => a.is_finite() && b.is_finite() && c.is_finite(),
                    })
            }),
            Item::Text { at, size, .. } => at.is_finite() && size.is_finite(),
            Item::Rect { min, max, .. } => min.is_finite() && max.is_finite(),
            Item::Disc { center, radius, .. } => center.is_finite() && radius.is_finite(),
        }
    }
}

impl Figure {
    /// Every number the figure would write is finite, or an error naming what holds one.
    ///
    /// # Errors
    /// [`FigureError::NotFinite`].
    pub fn check_finite(&self) -> Result<(), FigureError> {
        let Some(k) = self.items.iter().position(|i| !i.is_finite()) else {
            return Ok(());
        };
        let what = match &self.items[k] {
            Item::Path { curve: Some(c), .. } => format!("curves[{c}]"),
            Item::Path { .. } if k < self.behind => "the grid".to_owned(),
            Item::Path { .. } if k < self.front => "the control polygons".to_owned(),
            Item::Disc { .. } => "the control points".to_owned(),
            Item::Text { text, .. } => format!("the text {text:?}"),
            _ => "the axes and legend".to_owned(),
        };
        Err(FigureError::NotFinite { what })
    }
}

/// A curve's stroke width in output points: its pixels as they are, or its width in
/// scene units times the points one unit spans (the length of the projection's y row,
/// over `W` at the curve's first point in a perspective view: a figure's stroke has one
/// width).
fn stroke_width(curve: &splinescope_encoding::EncodedCurve, proj: &Projection) -> f32 {
    if !curve.width_in_scene {
        return curve.width;
    }
    let r = proj.rows[1];
    let scale = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
    let w = if proj.affine {
        1.0
    } else {
        curve
            .segments
            .first()
            .and_then(|s| s.bezier.points().first())
            .map_or(1.0, |&p| proj.homogeneous(p)[2])
    };
    let width = f64::from(curve.width) * scale / w.max(1e-12);
    // At most the page's own size in any sensible figure; an f32 holds it.
    width.min(1e7) as f32
}

/// A polyline's visible runs: points behind the eye break it, and so does the page —
/// each leg is clipped to `page` (Liang–Barsky), so that a polyline far off the page
/// writes nothing there (a dashed leg 10¹⁵ points long would otherwise be 10¹⁴ dashes to
/// a reader). Legs inside the page keep their exact end points.
fn polyline_runs(points: &[DVec3], proj: &Projection, page: &Page) -> Vec<SubPath> {
    let mut runs: Vec<SubPath> = Vec::new();
    let mut previous: Option<DVec2> = None;
    // Where the last run ends, when the next leg may continue it.
    let mut open_end: Option<DVec2> = None;
    for &p in points {
        let Some(q) = proj.point(p) else {
            previous = None;
            open_end = None;
            continue;
        };
        if let Some(a) = previous {
            match clip_leg(a, q, page) {
                Some((from, to)) => {
                    let continues = open_end == Some(from);
                    match runs.last_mut() {
                        Some(run) if continues => run.pieces.push(Piece {
                            seg: fit::Seg::Line(to),
                            exact: true,
                        }),
                        _ => runs.push(SubPath {
                            start: from,
                            pieces: vec![Piece {
                                seg: fit::Seg::Line(to),
                                exact: true,
                            }],
                        }),
                    }
                    open_end = (to == q).then_some(to);
                }
                None => open_end = None,
            }
        } else if page.contains(q) {
            // A lone first point starts a run even before its first leg.
            runs.push(SubPath {
                start: q,
                pieces: Vec::new(),
            });
            open_end = Some(q);
        }
        previous = Some(q);
    }
    runs.retain(|r| !r.pieces.is_empty());
    runs
}

/// The part of the leg `a → b` inside `page` (Liang–Barsky), its ends unchanged where
/// they lie inside.
fn clip_leg(a: DVec2, b: DVec2, page: &Page) -> Option<(DVec2, DVec2)> {
    if page.contains(a) && page.contains(b) {
        return Some((a, b));
    }
    let d = b - a;
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    for (p, q) in [
        (-d.x, a.x - page.min.x),
        (d.x, page.max.x - a.x),
        (-d.y, a.y - page.min.y),
        (d.y, page.max.y - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                lo = lo.max(r);
            } else {
                hi = hi.min(r);
            }
        }
    }
    if lo.is_nan() || hi.is_nan() || lo > hi {
        return None;
    }
    let from = if lo > 0.0 { a + d * lo } else { a };
    let to = if hi < 1.0 { a + d * hi } else { b };
    Some((from, to))
}

/// The colour as `#rrggbb` and its opacity.
#[must_use]
pub fn hex(color: Color) -> (String, f64) {
    let [r, g, b, a] = color
        .0
        .map(|c| (f64::from(c).clamp(0.0, 1.0) * 255.0).round() as u8);
    (format!("#{r:02x}{g:02x}{b:02x}"), f64::from(a) / 255.0)
}
