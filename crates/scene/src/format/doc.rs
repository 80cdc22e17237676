//! The scene file as Rust types: what [`crate::format::to_json_string`] writes (through
//! `Serialize`) and what `docs/schemas/scene.schema.json` is generated from (through
//! `JsonSchema`). The reader ([`crate::format::from_json_str`]) walks the parsed JSON by
//! hand instead, to name the path of the first offending value; a test checks that every
//! document it accepts validates against the schema.

use schemars::JsonSchema;
use serde::Serialize;

use super::point_doc;

use super::codec::Written;
use splinescope_core::geom::Curve;

/// A scene document (format version 1, `docs/scene-format.md`).
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[schemars(title = "splinescope scene", deny_unknown_fields)]
pub struct SceneDoc {
    /// The format version: 1.
    #[schemars(range(min = 1, max = 1))]
    pub version: u32,
    /// The title (window title, panel).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The unit of length the coordinates are in, when known (`"millimetre"`, `"inch"`:
    /// what an imported STEP file names); absent: unitless.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unit: Option<String>,
    /// The background colour (default white).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub background: Option<ColorDoc>,
    /// Samples per Bézier segment for curves that do not set their own (default `"auto"`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub samples: Option<SamplesDoc>,
    /// The opening view (default `"auto"`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub view: Option<ViewDoc>,
    /// The curves, drawn in order.
    pub curves: Vec<CurveDoc>,
    /// Marks drawn over the curves.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub annotations: Vec<AnnotationDoc>,
}

/// A colour: `"#rrggbb"`, `"#rrggbbaa"`, or `[r, g, b]` / `[r, g, b, a]` in `[0, 1]`.
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[serde(untagged)]
pub enum ColorDoc {
    /// Hexadecimal sRGB.
    Hex(#[schemars(regex(pattern = r"^#([0-9a-fA-F]{6}|[0-9a-fA-F]{8})$"))] String),
    /// Channels in `[0, 1]`.
    Channels(#[schemars(length(min = 3, max = 4), inner(range(min = 0.0, max = 1.0)))] Vec<f64>),
}

/// The word `"auto"`.
#[derive(Debug, Clone, Copy, Serialize, JsonSchema)]
pub enum Auto {
    /// `"auto"`.
    #[serde(rename = "auto")]
    Auto,
}

/// Samples per segment: a count or `"auto"` (Wang's bound in object space).
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[serde(untagged)]
pub enum SamplesDoc {
    /// Chosen per segment.
    Auto(Auto),
    /// A fixed count.
    Count(#[schemars(range(min = 2, max = 4096))] u32),
}

/// The opening view.
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[serde(untagged)]
pub enum ViewDoc {
    /// Fit every control point.
    Auto(Auto),
    /// A given camera.
    Camera(CameraDoc),
}

/// A camera.
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[serde(tag = "kind", deny_unknown_fields)]
pub enum CameraDoc {
    /// A 2D view: the world point at the centre and the visible height.
    #[serde(rename = "2d")]
    TwoD {
        /// The centre `[x, y]`.
        center: [f64; 2],
        /// The visible height (> 0).
        #[schemars(range(min = 0.0))]
        height: f64,
    },
    /// An orbit camera.
    #[serde(rename = "3d")]
    ThreeD {
        /// The point looked at.
        target: point_doc::PointDoc,
        /// The distance from it (> 0).
        #[schemars(range(min = 0.0))]
        distance: f64,
        /// Yaw about the world `y` axis (default 30).
        #[serde(skip_serializing_if = "Option::is_none")]
        yaw_deg: Option<f64>,
        /// Pitch in (−89, 89) (default 20).
        #[serde(skip_serializing_if = "Option::is_none")]
        #[schemars(range(min = -89.0, max = 89.0))]
        pitch_deg: Option<f64>,
        /// Vertical field of view in (1, 179) (default 45).
        #[serde(skip_serializing_if = "Option::is_none")]
        #[schemars(range(min = 1.0, max = 179.0))]
        fov_deg: Option<f64>,
    },
}

/// One curve: its family's fields (tagged by `type`), a name and a style. Fields of other
/// families are refused (`unevaluatedProperties`).
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[schemars(extend("unevaluatedProperties" = false))]
pub struct CurveDoc {
    /// The family and its fields.
    #[serde(flatten)]
    pub family: FamilyDoc,
    /// The curve's name.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// How it is drawn.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub style: Option<StyleDoc>,
}

macro_rules! family_docs {
    ($( $(#[$doc:meta])* $variant:ident($ty:ty) = $name:literal ),* $(,)?) => {
        /// A curve's family and its own fields; one variant per row of the core's family
        /// table, each defined with the family's codec (`crates/scene/src/format/codec/`).
        #[derive(Debug, Clone, Serialize, JsonSchema)]
        #[serde(tag = "type")]
        pub enum FamilyDoc {
            $(
                #[doc = concat!("`\"", $name, "\"`.")]
                #[serde(rename = $name)]
                $variant(<$ty as Written>::Doc),
            )*
        }

        $(
            impl From<<$ty as Written>::Doc> for FamilyDoc {
                fn from(d: <$ty as Written>::Doc) -> FamilyDoc {
                    FamilyDoc::$variant(d)
                }
            }
        )*
    };
}

splinescope_core::family_table!(family_docs);

/// The written form of a curve's family fields.
pub(crate) fn encode(curve: &Curve) -> FamilyDoc {
    splinescope_core::each_family!(curve, c => c.encode().into())
}

/// How a curve is drawn.
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct StyleDoc {
    /// The colour (default: a palette colour by index).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub color: Option<ColorDoc>,
    /// Line width (default 2.5): in pixels, in (0, 1000]; or in scene units (any
    /// positive number) with `width_units: "scene"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0.0))]
    pub width: Option<f64>,
    /// What `width` is measured in: `"px"` (the default) or `"scene"` (the line zooms
    /// with the view, as an SVG stroke does).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub width_units: Option<WidthUnitsDoc>,
    /// Draw the control polygon and the family's explaining polylines (default true).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub polygon: Option<bool>,
    /// Draw the control points (default true).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub points: Option<bool>,
    /// Samples per Bézier segment (default: the scene's).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 2, max = 4096))]
    pub samples: Option<u32>,
    /// How an open curve's ends are drawn (SVG's `stroke-linecap`; default `"round"`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cap: Option<CapDoc>,
    /// How the stroke turns at corners (SVG's `stroke-linejoin`; default `"round"`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub join: Option<JoinDoc>,
    /// The longest miter, over the width, before a corner is bevelled (SVG's
    /// `stroke-miterlimit`; default 4).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 1.0, max = 1000.0))]
    pub miter_limit: Option<f64>,
}

/// A stroke's ends.
#[derive(Debug, Clone, Copy, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum CapDoc {
    /// Half discs.
    Round,
    /// Cut at the end points.
    Butt,
    /// Cut half the width beyond them.
    Square,
}

/// A stroke's corners.
#[derive(Debug, Clone, Copy, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum JoinDoc {
    /// Discs.
    Round,
    /// The outer edges met, within the miter limit.
    Miter,
    /// The outer corners joined straight.
    Bevel,
}

/// The unit of a style's width.
#[derive(Debug, Clone, Copy, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum WidthUnitsDoc {
    /// Pixels.
    Px,
    /// Scene units.
    Scene,
}

/// A mark drawn over the curves: a polyline or points.
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[schemars(extend("unevaluatedProperties" = false))]
pub struct AnnotationDoc {
    /// The shape.
    #[serde(flatten)]
    pub shape: AnnotationShapeDoc,
    /// The colour.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub color: Option<ColorDoc>,
    /// Line width or point diameter in pixels, in (0, 1000].
    #[serde(skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0.0, max = 1000.0))]
    pub width: Option<f64>,
    /// A label.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub label: Option<String>,
}

/// An annotation's shape.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub enum AnnotationShapeDoc {
    /// At least 2 points joined in order.
    #[serde(rename = "polyline")]
    Polyline(#[schemars(length(min = 2))] Vec<point_doc::PointDoc>),
    /// At least 1 point, drawn as discs.
    #[serde(rename = "points")]
    Points(#[schemars(length(min = 1))] Vec<point_doc::PointDoc>),
}
/// Deprecated: `splinescope_scene::format::point_doc::PointDoc`.
#[deprecated(note = "use splinescope_scene::format::point_doc::PointDoc")]
pub type PointDoc = point_doc::PointDoc;
/// Deprecated: the constructor `splinescope_scene::format::point_doc::PointDoc(coordinates)`.
#[deprecated(note = "use splinescope_scene::format::point_doc::PointDoc")]
#[allow(non_snake_case)] // the tuple struct's constructor, which the type alias does not carry
#[must_use]
pub fn PointDoc(coordinates: Vec<f64>) -> point_doc::PointDoc {
    point_doc::PointDoc(coordinates)
}
