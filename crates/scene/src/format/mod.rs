//! The scene model: a versioned JSON document listing curves with their styles, plus the
//! view. Reading validates everything and reports the first problem as a [`SceneError`]
//! naming the path of the offending value (`curves[3].points[2][1]: not a finite number`).
//!
//! The format is documented in `docs/scene-format.md`.

pub mod codec;
pub mod doc;
pub mod draw;
pub mod encoding;
pub mod gallery;
pub mod generate;
mod json;
pub mod labels;
pub mod point_doc;
mod preserve;
pub mod shape;

use std::path::Path;

use glam::{DVec2, DVec3};
use thiserror::Error;

use splinescope_core::geom::{Aabb, Curve};
use splinescope_encoding::camera::{Camera, Camera2d, Camera3d};

pub use json::{
    curve_from_value, curve_to_value, from_json_str, pretty_json, to_doc, to_json_string,
};
pub use preserve::to_json_string_keeping;

// The colour, the stroke's shape and the sample counts are the encoding's.
use splinescope_encoding as enc;

/// Deprecated: `splinescope_encoding::Color`.
#[deprecated(note = "use splinescope_encoding::Color")]
pub type Color = enc::Color;
/// Deprecated: the constructor `splinescope_encoding::Color(rgba)`.
#[deprecated(note = "use splinescope_encoding::Color")]
#[allow(non_snake_case)] // the tuple struct's constructor, which the type alias does not carry
#[must_use]
pub const fn Color(rgba: [f32; 4]) -> enc::Color {
    enc::Color(rgba)
}
/// Deprecated: `splinescope_encoding::Cap` (the core's `splinescope_core::ops::Cap`).
#[deprecated(note = "use splinescope_core::ops::Cap")]
pub type Cap = splinescope_core::ops::Cap;
/// Deprecated: `splinescope_core::ops::Join`.
#[deprecated(note = "use splinescope_core::ops::Join")]
pub type Join = splinescope_core::ops::Join;
/// Deprecated: `splinescope_encoding::StrokeShape`.
#[deprecated(note = "use splinescope_encoding::StrokeShape")]
pub type StrokeShape = enc::StrokeShape;
/// Deprecated: `splinescope_encoding::AUTO_SAMPLES_TOLERANCE`.
#[deprecated(note = "use splinescope_encoding::AUTO_SAMPLES_TOLERANCE")]
pub const AUTO_SAMPLES_TOLERANCE: f64 = enc::AUTO_SAMPLES_TOLERANCE;
/// Deprecated: `splinescope_encoding::MAX_MITER_LIMIT`.
#[deprecated(note = "use splinescope_encoding::MAX_MITER_LIMIT")]
pub const MAX_MITER_LIMIT: f64 = enc::MAX_MITER_LIMIT;
/// Deprecated: `splinescope_encoding::auto_samples`.
#[deprecated(note = "use splinescope_encoding::auto_samples")]
#[must_use]
pub fn auto_samples(points: &[DVec3]) -> u32 {
    enc::auto_samples(points)
}
/// Deprecated: `splinescope_encoding::MAX_SAMPLES_PER_SEGMENT`.
#[deprecated(note = "use splinescope_encoding::MAX_SAMPLES_PER_SEGMENT")]
pub const MAX_SAMPLES_PER_SEGMENT: u32 = enc::MAX_SAMPLES_PER_SEGMENT;

/// The scene format version this build reads and writes.
pub const FORMAT_VERSION: u32 = 1;
/// Samples per Bézier segment of the stress scenes and benchmarks.
pub const DEFAULT_SAMPLES_PER_SEGMENT: u32 = 64;

/// The palette curves take their colour from, by index, when the scene gives none
/// (tab10's first eight), on the 8-bit grid scene files write: a scene saved and read
/// back (or pickled) keeps its colours exactly.
pub const PALETTE: [enc::Color; 8] = [
    enc::Color::from_rgba8([31, 119, 180, 255]),
    enc::Color::from_rgba8([214, 39, 40, 255]),
    enc::Color::from_rgba8([44, 160, 44, 255]),
    enc::Color::from_rgba8([255, 127, 14, 255]),
    enc::Color::from_rgba8([148, 103, 189, 255]),
    enc::Color::from_rgba8([140, 86, 75, 255]),
    enc::Color::from_rgba8([227, 119, 194, 255]),
    enc::Color::from_rgba8([23, 190, 207, 255]),
];

/// How one curve is drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct Style {
    /// The curve's colour.
    pub color: enc::Color,
    /// The curve's width (> 0): pixels, or scene units when `width_in_scene`.
    pub width: f32,
    /// Whether `width` is in scene units — the line then zooms with the view, as an SVG
    /// stroke does — rather than pixels.
    pub width_in_scene: bool,
    /// Whether to draw the control polygon (and, per family, the other explaining
    /// polylines).
    pub show_polygon: bool,
    /// Whether to draw the control points.
    pub show_points: bool,
    /// Samples per Bézier segment; `None` takes the scene's.
    pub samples: Option<u32>,
    /// The stroke's ends and corners (round, unless a scene or an SVG says otherwise).
    pub stroke: enc::StrokeShape,
}

impl Style {
    /// The default style of the curve at `index`: a palette colour, 2.5 px, with its
    /// control polygon and points.
    #[must_use]
    pub fn default_for(index: usize) -> Style {
        Style {
            color: PALETTE[index % PALETTE.len()],
            width: 2.5,
            width_in_scene: false,
            show_polygon: true,
            show_points: true,
            samples: None,
            stroke: enc::StrokeShape::default(),
        }
    }
}

/// One curve of a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneCurve {
    /// An optional label.
    pub name: Option<String>,
    /// The curve itself.
    pub curve: Curve,
    /// How it is drawn.
    pub style: Style,
}

impl SceneCurve {
    /// The curve's name (or its family) with its shape parameters as they are now
    /// (`name · t* = 0.3, v = (1, 2)`): what the viewer and figures label it with.
    #[must_use]
    pub fn label(&self) -> String {
        let name = self.name.as_deref().unwrap_or(self.curve.family());
        match splinescope_present::Present::parameter_text(&self.curve) {
            Some(p) => format!("{name} · {p}"),
            None => name.to_owned(),
        }
    }
}

/// The view a scene opens with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ViewSpec {
    /// Fit everything: 2D when every point has `z = 0`, else 3D.
    Auto,
    /// A 2D view centred on `center` showing `height` world units vertically.
    TwoD {
        /// The centre of the view.
        center: DVec2,
        /// The visible height in world units (> 0).
        height: f64,
    },
    /// A 3D orbit view.
    ThreeD {
        /// The point looked at.
        target: DVec3,
        /// Eye distance (> 0).
        distance: f64,
        /// Yaw in degrees.
        yaw_deg: f64,
        /// Pitch in degrees, inside (−89, 89).
        pitch_deg: f64,
        /// Vertical field of view in degrees, inside (1, 179).
        fov_deg: f64,
    },
}

/// A whole scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// An optional title.
    pub name: Option<String>,
    /// The unit of length its coordinates are in, when the file it came from names one
    /// (a STEP file's `millimetre`); `None`: unitless.
    pub unit: Option<String>,
    /// The background colour.
    pub background: enc::Color,
    /// Samples per Bézier segment for curves that do not say; `None`: automatic (see
    /// [`auto_samples`]).
    pub samples_per_segment: Option<u32>,
    /// The opening view.
    pub view: ViewSpec,
    /// The curves, drawn in order.
    pub curves: Vec<SceneCurve>,
    /// Marks drawn over the curves (targets, reachable regions, notes).
    pub annotations: Vec<Annotation>,
}

/// What an annotation draws.
#[derive(Debug, Clone, PartialEq)]
pub enum AnnotationShape {
    /// A polyline through the points.
    Polyline(Vec<DVec3>),
    /// Separate points (drawn as discs).
    Points(Vec<DVec3>),
}

/// A mark drawn over the curves: a polyline or a set of points, with a colour and a width
/// (line width or disc diameter, in pixels).
#[derive(Debug, Clone, PartialEq)]
pub struct Annotation {
    /// What to draw.
    pub shape: AnnotationShape,
    /// Its colour.
    pub color: enc::Color,
    /// Line width or disc diameter in pixels (> 0).
    pub width: f32,
    /// An optional label.
    pub label: Option<String>,
}

/// Why a scene could not be read: the path of the offending value and what is wrong.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{}{kind}", at(path))]
pub struct SceneError {
    /// Where, as a JSON path from the document root (`curves[3].points[2]`); empty for the
    /// document as a whole (the message then names no path).
    pub path: String,
    /// What.
    pub kind: SceneErrorKind,
}

/// `path: ` before a message, nothing for the whole document (an empty path).
pub(crate) fn at(path: &str) -> String {
    if path.is_empty() {
        String::new()
    } else {
        format!("{path}: ")
    }
}

/// What is wrong with a scene value.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SceneErrorKind {
    /// The file could not be read.
    #[error("cannot read the file: {0}")]
    Io(String),
    /// The text is not JSON.
    #[error("invalid JSON at line {line}, column {column}: {message}")]
    Syntax {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// A required field is absent.
    #[error("missing (required)")]
    Missing,
    /// A field the format does not define.
    #[error("unknown field (expected one of: {expected})")]
    UnknownField {
        /// The fields allowed here.
        expected: String,
    },
    /// A value of the wrong JSON type.
    #[error("expected {expected}, found {found}")]
    WrongType {
        /// What the format wants.
        expected: String,
        /// What the file has.
        found: String,
    },
    /// NaN, an infinity or a number too large for `f64`.
    #[error("not a finite number ({0})")]
    NotFinite(String),
    /// A value outside what the format allows.
    #[error("{0}")]
    Invalid(String),
    /// A version this build does not read.
    #[error("unsupported version {found} (this build reads version {supported})")]
    Version {
        /// The file's version.
        found: String,
        /// [`FORMAT_VERSION`].
        supported: u32,
    },
}

impl SceneError {
    /// An error at `path`.
    #[must_use]
    pub fn new(path: impl Into<String>, kind: SceneErrorKind) -> SceneError {
        SceneError {
            path: path.into(),
            kind,
        }
    }
}

impl Scene {
    /// A scene of `curves` with the defaults of a file that gives nothing else: white
    /// background, automatic samples and view, each curve in its palette style.
    #[must_use]
    pub fn of_curves(curves: impl IntoIterator<Item = splinescope_core::geom::Curve>) -> Scene {
        Scene {
            name: None,
            unit: None,
            background: enc::Color::WHITE,
            samples_per_segment: None,
            view: ViewSpec::Auto,
            curves: curves
                .into_iter()
                .enumerate()
                .map(|(i, curve)| SceneCurve {
                    name: None,
                    curve,
                    style: Style::default_for(i),
                })
                .collect(),
            annotations: Vec::new(),
        }
    }

    /// Reads and validates a scene file.
    ///
    /// ```
    /// use splinescope_scene::format::Scene;
    ///
    /// let dir = std::env::temp_dir().join(format!("splinescope-load-doc-{}", std::process::id()));
    /// std::fs::create_dir_all(&dir).unwrap();
    /// let path = dir.join("arch.json");
    /// std::fs::write(&path, r#"{"version": 1, "curves": [
    ///     {"type": "bezier", "name": "arch", "points": [[0, 0], [1, 2], [3, 2], [4, 0]]}
    /// ]}"#).unwrap();
    /// let scene = Scene::load(&path).unwrap();
    /// assert_eq!(scene.curves[0].name.as_deref(), Some("arch"));
    /// // A bad value is refused, its path in the file named.
    /// std::fs::write(&path, r#"{"version": 1, "curves": [{"type": "bezier", "points": [[0, 0], [1]]}]}"#).unwrap();
    /// let e = Scene::load(&path).unwrap_err();
    /// assert!(e.to_string().contains("curves[0].points[1]"), "{e}");
    /// std::fs::remove_dir_all(&dir).unwrap();
    /// ```
    ///
    /// # Errors
    /// A [`SceneError`] naming the offending value (or the I/O problem).
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        Scene::read(path).map(|(scene, _)| scene)
    }

    /// Reads and validates a scene file, keeping the text it was read from (for saving
    /// in the same form, [`to_json_string_keeping`]).
    ///
    /// # Errors
    /// A [`SceneError`] naming the offending value (or the I/O problem).
    pub fn read(path: &Path) -> Result<(Scene, String), SceneError> {
        let text = splinescope_io::limits::read_bounded(path)
            .map_err(|e| SceneError::new("", SceneErrorKind::Io(e.to_string())))?;
        let scene = from_json_str(&text)?;
        Ok((scene, text))
    }

    /// Writes the scene as JSON, atomically (temporary file, then rename).
    ///
    /// # Errors
    /// The I/O error.
    pub fn save(&self, path: &Path) -> std::io::Result<()> {
        splinescope_io::files::write_atomic(path, to_json_string(self).as_bytes())
    }

    /// Samples per segment for curve `index` (its own, else the scene's); `None`:
    /// automatic, per segment.
    #[must_use]
    pub fn samples_for(&self, index: usize) -> Option<u32> {
        self.curves[index]
            .style
            .samples
            .or(self.samples_per_segment)
    }

    /// The box of every control point (holds every curve) and every annotation.
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        let curves = self
            .curves
            .iter()
            .fold(Aabb::EMPTY, |b, c| b.union(c.curve.control_box()));
        self.annotations.iter().fold(curves, |b, a| match &a.shape {
            AnnotationShape::Polyline(p) | AnnotationShape::Points(p) => {
                b.union(Aabb::from_points(p))
            }
        })
    }

    /// Whether every curve is planar (`z = 0`).
    #[must_use]
    pub fn is_planar(&self) -> bool {
        self.curves.iter().all(|c| c.curve.is_planar())
    }

    /// The camera the scene opens with for a viewport in pixels.
    #[must_use]
    pub fn camera(&self, viewport: DVec2) -> Camera {
        match self.view {
            ViewSpec::Auto => Camera::fit(self.bounds(), viewport, !self.is_planar()),
            ViewSpec::TwoD { center, height } => Camera::Ortho2d(Camera2d {
                center,
                pixels_per_unit: viewport.y / height,
            }),
            ViewSpec::ThreeD {
                target,
                distance,
                yaw_deg,
                pitch_deg,
                fov_deg,
            } => Camera::Orbit3d(Camera3d {
                target,
                distance,
                yaw: yaw_deg.to_radians(),
                pitch: pitch_deg.to_radians(),
                fov_y: fov_deg.to_radians(),
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use splinescope_core::geom::Bezier;
    use splinescope_core::rng::Rng;

    /// The largest distance from dense points of the curve to the polyline of `samples`
    /// uniform samples.
    fn polyline_error(b: &Bezier, samples: u32) -> f64 {
        let poly: Vec<DVec3> = (0..samples)
            .map(|j| b.eval(f64::from(j) / f64::from(samples - 1)))
            .collect();
        let mut worst = 0.0_f64;
        for k in 0..=4000 {
            let p = b.eval(f64::from(k) / 4000.0);
            let d = poly
                .windows(2)
                .map(|w| {
                    let ab = w[1] - w[0];
                    let t = if ab.length_squared() > 0.0 {
                        ((p - w[0]).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    (w[0] + t * ab - p).length()
                })
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(d);
        }
        worst
    }

    #[test]
    fn automatic_samples_keep_the_polyline_within_tolerance() {
        let mut rng = Rng::new(12);
        for n in [2usize, 3, 5, 8, 12, 20, 31] {
            for _ in 0..5 {
                let b = Bezier::new(
                    (0..=n)
                        .map(|_| {
                            DVec3::new(rng.range(-1., 1.), rng.range(-1., 1.), rng.range(-1., 1.))
                        })
                        .collect(),
                );
                let samples = enc::auto_samples(b.points());
                let size = b.control_box().diagonal();
                let err = polyline_error(&b, samples);
                if samples < enc::MAX_SAMPLES_PER_SEGMENT {
                    assert!(
                        err <= enc::AUTO_SAMPLES_TOLERANCE * size,
                        "n={n}: {samples} samples, error {err:e}"
                    );
                }
            }
        }
        // The ladder.
        let mut seen = std::collections::BTreeSet::new();
        for n in 2..40 {
            let b = Bezier::new(
                (0..=n)
                    .map(|i| DVec3::new(i as f64, ((i * i) % 7) as f64, 0.0))
                    .collect(),
            );
            seen.insert(enc::auto_samples(b.points()));
        }
        for s in &seen {
            let on_ladder = s.is_power_of_two()
                || (s % 3 == 0 && (s / 3).is_power_of_two())
                || *s == enc::MAX_SAMPLES_PER_SEGMENT;
            assert!(on_ladder, "{s}");
        }
        let line = Bezier::new(vec![DVec3::ZERO, DVec3::X, DVec3::X * 2.0]);
        assert_eq!(enc::auto_samples(line.points()), 2);
        assert_eq!(enc::auto_samples(&[DVec3::ZERO, DVec3::ONE]), 2);
    }
}
