//! Reading and writing the JSON scene format with path-naming errors (the reader walks the
//! parsed value with [`crate::jsonread`]).

use glam::DVec2;
use serde_json::Value;

use crate::jsonread::{Node, Obj, describe, parse_document};

use super::codec::{self, geom_error};
use super::doc::{
    AnnotationDoc, AnnotationShapeDoc, Auto, CameraDoc, CapDoc, ColorDoc, CurveDoc, JoinDoc,
    SamplesDoc, SceneDoc, StyleDoc, ViewDoc, WidthUnitsDoc,
};
use super::point_doc::PointDoc;
use super::{
    Annotation, AnnotationShape, FORMAT_VERSION, Scene, SceneCurve, SceneError, SceneErrorKind,
    Style, ViewSpec,
};
use splinescope_core::ops::{Cap, Join};
use splinescope_encoding::{Color, MAX_MITER_LIMIT, MAX_SAMPLES_PER_SEGMENT, StrokeShape};

/// Parses and validates a scene from JSON text.
///
/// # Errors
/// The first problem found, as a [`SceneError`] naming its path.
pub fn from_json_str(text: &str) -> Result<Scene, SceneError> {
    let value = parse_document(text)?;
    decode_scene(&Node::root(&value))
}

fn decode_scene(root: &Node<'_>) -> Result<Scene, SceneError> {
    let obj = root.object(&[
        "version",
        "name",
        "unit",
        "background",
        "samples",
        "view",
        "curves",
        "annotations",
    ])?;
    let version = obj.req("version")?;
    match version.value.as_u64() {
        Some(v) if v == u64::from(FORMAT_VERSION) => {}
        _ => {
            return Err(version.err(SceneErrorKind::Version {
                found: describe(version.value),
                supported: FORMAT_VERSION,
            }));
        }
    }
    let name = obj
        .get("name")
        .map(|n| n.text().map(str::to_owned))
        .transpose()?;
    let unit = obj
        .get("unit")
        .map(|n| n.text().map(str::to_owned))
        .transpose()?;
    let background = obj.get("background").map(|n| n.color()).transpose()?;
    let samples = match obj.get("samples") {
        None => None,
        Some(n) if n.value.as_str() == Some("auto") => None,
        Some(n) => Some(n.u32_in(2, MAX_SAMPLES_PER_SEGMENT)?),
    };
    let view = obj.get("view").map(|n| decode_view(&n)).transpose()?;
    let curves_node = obj.req("curves")?;
    if let Value::Array(a) = curves_node.value {
        splinescope_io::limits::CURVES
            .check(a.len() as u64)
            .map_err(|e| curves_node.invalid(e.to_string()))?;
    }
    let curves = curves_node
        .array()?
        .iter()
        .enumerate()
        .map(|(i, n)| decode_curve(n, i))
        .collect::<Result<Vec<_>, _>>()?;
    let annotations = match obj.get("annotations") {
        None => Vec::new(),
        Some(n) => n
            .array()?
            .iter()
            .map(decode_annotation)
            .collect::<Result<Vec<_>, _>>()?,
    };
    Ok(Scene {
        name,
        unit,
        background: background.unwrap_or(Color::WHITE),
        samples_per_segment: samples,
        view: view.unwrap_or(ViewSpec::Auto),
        curves,
        annotations,
    })
}

/// The default colour of annotations.
const ANNOTATION_COLOR: Color = Color::from_rgba8([89, 89, 89, 230]);

fn decode_annotation(node: &Node<'_>) -> Result<Annotation, SceneError> {
    let obj = node.object(&["polyline", "points", "color", "width", "label"])?;
    let shape = match (obj.get("polyline"), obj.get("points")) {
        (Some(p), None) => AnnotationShape::Polyline(p.points(2)?),
        (None, Some(p)) => AnnotationShape::Points(p.points(1)?),
        (Some(_), Some(p)) => {
            return Err(p.invalid("an annotation is either a \"polyline\" or \"points\", not both"));
        }
        (None, None) => {
            return Err(node.invalid("an annotation needs \"polyline\" or \"points\""));
        }
    };
    let color = obj
        .get("color")
        .map(|n| n.color())
        .transpose()?
        .unwrap_or(ANNOTATION_COLOR);
    let width = match obj.get("width") {
        Some(n) => {
            let w = n.positive_f64()?;
            if w > 1000.0 {
                return Err(n.invalid(format!("width {w} px is over the maximum of 1000")));
            }
            w as f32
        }
        None => match shape {
            AnnotationShape::Polyline(_) => 1.5,
            AnnotationShape::Points(_) => 9.0,
        },
    };
    let label = obj
        .get("label")
        .map(|n| n.text().map(str::to_owned))
        .transpose()?;
    Ok(Annotation {
        shape,
        color,
        width,
        label,
    })
}

fn decode_view(node: &Node<'_>) -> Result<ViewSpec, SceneError> {
    if let Value::String(s) = node.value {
        return if s == "auto" {
            Ok(ViewSpec::Auto)
        } else {
            Err(node.invalid(format!(
                "unknown view {s:?} (expected \"auto\" or an object)"
            )))
        };
    }
    let Value::Object(map) = node.value else {
        return Err(node.wrong_type("\"auto\" or a view object"));
    };
    // Read the kind first: the fields allowed depend on it.
    let probe = Obj {
        map,
        path: node.path.clone(),
    };
    let kind = probe.req("kind")?;
    match kind.string()? {
        "2d" => {
            let obj = node.object(&["kind", "center", "height"])?;
            let c = obj.req("center")?;
            let center = c.point()?;
            if center.z != 0.0 {
                return Err(c.invalid("a 2D view centre has 2 coordinates"));
            }
            Ok(ViewSpec::TwoD {
                center: DVec2::new(center.x, center.y),
                height: obj.req("height")?.positive_f64()?,
            })
        }
        "3d" => {
            let obj = node.object(&[
                "kind",
                "target",
                "distance",
                "yaw_deg",
                "pitch_deg",
                "fov_deg",
            ])?;
            let angle = |key: &str, default: f64, lo: f64, hi: f64| -> Result<f64, SceneError> {
                match obj.get(key) {
                    None => Ok(default),
                    Some(n) => {
                        let v = n.f64()?;
                        if v > lo && v < hi {
                            Ok(v)
                        } else {
                            Err(n.invalid(format!("{v} is outside ({lo}, {hi})")))
                        }
                    }
                }
            };
            Ok(ViewSpec::ThreeD {
                target: obj.req("target")?.point()?,
                distance: obj.req("distance")?.positive_f64()?,
                yaw_deg: angle("yaw_deg", 30.0, -1e6, 1e6)?,
                pitch_deg: angle("pitch_deg", 20.0, -89.0, 89.0)?,
                fov_deg: angle(
                    "fov_deg",
                    splinescope_encoding::camera::DEFAULT_FOV_DEG,
                    1.0,
                    179.0,
                )?,
            })
        }
        other => Err(kind.invalid(format!(
            "unknown view kind {other:?} (expected \"2d\" or \"3d\")"
        ))),
    }
}

/// Reads one curve object of the scene format (what `curves[index]` of a scene file
/// holds: `type`, the family's fields, `name`, `style`), checked as a scene's curve is;
/// errors name the path inside the object (`points[2][0]`). `index` picks the default
/// style's palette colour.
///
/// # Errors
/// The first problem found, as a [`SceneError`].
pub fn curve_from_value(value: &Value, index: usize) -> Result<SceneCurve, SceneError> {
    decode_curve(&Node::root(value), index)
}

/// The written form of one curve (as [`curve_from_value`] reads it): the scene
/// writer's own curve object.
#[must_use]
pub fn curve_to_value(curve: &SceneCurve) -> Value {
    serde_json::to_value(curve_doc(curve))
        .unwrap_or_else(|e| unreachable!("a curve document always serialises: {e}"))
}

pub(super) fn decode_curve(node: &Node<'_>, index: usize) -> Result<SceneCurve, SceneError> {
    let Value::Object(map) = node.value else {
        return Err(node.wrong_type("a curve object"));
    };
    let probe = Obj {
        map,
        path: node.path.clone(),
    };
    let ty = probe.req("type")?;
    let family = ty.string()?;
    let Some(decoded) = codec::decode(family, node) else {
        return Err(ty.invalid(format!(
            "unknown curve type {family:?} (expected one of: {})",
            codec::family_names().join(", ")
        )));
    };
    let (curve, obj) = decoded?;
    curve
        .check_derived()
        .map_err(|e| geom_error(node, "", &e))?;
    let name = obj
        .get("name")
        .map(|n| n.text().map(str::to_owned))
        .transpose()?;
    let style = match obj.get("style") {
        None => Style::default_for(index),
        Some(n) => decode_style(&n, index)?,
    };
    Ok(SceneCurve { name, curve, style })
}

fn decode_style(node: &Node<'_>, index: usize) -> Result<Style, SceneError> {
    let obj = node.object(&[
        "color",
        "width",
        "width_units",
        "polygon",
        "points",
        "samples",
        "cap",
        "join",
        "miter_limit",
    ])?;
    let mut style = Style::default_for(index);
    if let Some(n) = obj.get("cap") {
        style.stroke.cap = match n.value.as_str() {
            Some("round") => Cap::Round,
            Some("butt") => Cap::Butt,
            Some("square") => Cap::Square,
            _ => {
                return Err(n.invalid(format!(
                    "cap {}: \"round\", \"butt\" or \"square\"",
                    n.value
                )));
            }
        };
    }
    if let Some(n) = obj.get("join") {
        style.stroke.join = match n.value.as_str() {
            Some("round") => Join::Round,
            Some("miter") => Join::Miter,
            Some("bevel") => Join::Bevel,
            _ => {
                return Err(n.invalid(format!(
                    "join {}: \"round\", \"miter\" or \"bevel\"",
                    n.value
                )));
            }
        };
    }
    if let Some(n) = obj.get("miter_limit") {
        let m = n.positive_f64()?;
        if !(1.0..=MAX_MITER_LIMIT).contains(&m) {
            return Err(n.invalid(format!(
                "miter_limit {m}: from 1 to {MAX_MITER_LIMIT} (a miter's length over the width)"
            )));
        }
        style.stroke.miter_limit = m;
    }
    if let Some(n) = obj.get("color") {
        style.color = n.color()?;
    }
    if let Some(n) = obj.get("width_units") {
        style.width_in_scene = match n.value.as_str() {
            Some("px") => false,
            Some("scene") => true,
            _ => {
                return Err(n.invalid(format!("width_units {}: \"px\" or \"scene\"", n.value)));
            }
        };
    }
    if let Some(n) = obj.get("width") {
        let w = n.positive_f64()?;
        if !style.width_in_scene && w > 1000.0 {
            return Err(n.invalid(format!("width {w} px is over the maximum of 1000")));
        }
        // In scene units any positive width an f32 holds (the line is drawn at most
        // the view's size).
        if style.width_in_scene && !((w as f32).is_finite() && w as f32 > 0.0) {
            return Err(n.invalid(format!(
                "width {w} scene units: a positive number an f32 holds"
            )));
        }
        style.width = w as f32;
    }
    if let Some(n) = obj.get("polygon") {
        style.show_polygon = n.bool()?;
    }
    if let Some(n) = obj.get("points") {
        style.show_points = n.bool()?;
    }
    if let Some(n) = obj.get("samples") {
        style.samples = Some(n.u32_in(2, MAX_SAMPLES_PER_SEGMENT)?);
    }
    Ok(style)
}

/// The typed document of `scene` (what is written, and what the schema describes).
#[must_use]
pub fn to_doc(scene: &Scene) -> SceneDoc {
    SceneDoc {
        version: FORMAT_VERSION,
        name: scene.name.clone(),
        unit: scene.unit.clone(),
        background: Some(ColorDoc::Hex(scene.background.to_hex())),
        samples: Some(
            scene
                .samples_per_segment
                .map_or(SamplesDoc::Auto(Auto::Auto), SamplesDoc::Count),
        ),
        view: Some(match scene.view {
            ViewSpec::Auto => ViewDoc::Auto(Auto::Auto),
            ViewSpec::TwoD { center, height } => ViewDoc::Camera(CameraDoc::TwoD {
                center: center.to_array(),
                height,
            }),
            ViewSpec::ThreeD {
                target,
                distance,
                yaw_deg,
                pitch_deg,
                fov_deg,
            } => ViewDoc::Camera(CameraDoc::ThreeD {
                target: PointDoc(target.to_array().to_vec()),
                distance,
                yaw_deg: Some(yaw_deg),
                pitch_deg: Some(pitch_deg),
                fov_deg: Some(fov_deg),
            }),
        }),
        curves: scene.curves.iter().map(curve_doc).collect(),
        annotations: scene
            .annotations
            .iter()
            .map(|a| AnnotationDoc {
                shape: match &a.shape {
                    AnnotationShape::Polyline(p) => AnnotationShapeDoc::Polyline(PointDoc::all(p)),
                    AnnotationShape::Points(p) => AnnotationShapeDoc::Points(PointDoc::all(p)),
                },
                color: Some(ColorDoc::Hex(a.color.to_hex())),
                width: Some(f64::from(a.width)),
                label: a.label.clone(),
            })
            .collect(),
    }
}

pub(super) fn curve_doc(c: &SceneCurve) -> CurveDoc {
    let s = &c.style;
    CurveDoc {
        family: super::doc::encode(&c.curve),
        name: c.name.clone(),
        style: Some(StyleDoc {
            color: Some(ColorDoc::Hex(s.color.to_hex())),
            width: Some(f64::from(s.width)),
            width_units: s.width_in_scene.then_some(WidthUnitsDoc::Scene),
            polygon: Some(s.show_polygon),
            points: Some(s.show_points),
            samples: s.samples,
            cap: match s.stroke.cap {
                Cap::Round => None,
                Cap::Butt => Some(CapDoc::Butt),
                Cap::Square => Some(CapDoc::Square),
            },
            join: match s.stroke.join {
                Join::Round => None,
                Join::Miter => Some(JoinDoc::Miter),
                Join::Bevel => Some(JoinDoc::Bevel),
            },
            miter_limit: (s.stroke.miter_limit != StrokeShape::default().miter_limit)
                .then_some(s.stroke.miter_limit),
        }),
    }
}

/// Writes a scene as pretty JSON in the current format version.
#[must_use]
pub fn to_json_string(scene: &Scene) -> String {
    let value = serde_json::to_value(to_doc(scene))
        .unwrap_or_else(|e| unreachable!("a scene document always serialises: {e}"));
    let mut text = String::new();
    write_pretty(&value, 0, &mut text);
    text.push('\n');
    text
}

/// Pretty JSON with two-space indents, except that arrays holding only numbers (points,
/// colours, knots) stay on one line.
#[must_use]
pub fn pretty_json(value: &Value) -> String {
    let mut out = String::new();
    write_pretty(value, 0, &mut out);
    out
}

/// Writes `v` as [`pretty_json`] does, at `indent`.
pub(crate) fn write_pretty(v: &Value, indent: usize, out: &mut String) {
    let pad = |n: usize, out: &mut String| out.extend(std::iter::repeat_n(' ', n));
    match v {
        Value::Array(items) if items.iter().all(Value::is_number) => {
            out.push('[');
            for (i, item) in items.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                write_scalar(item, out);
            }
            out.push(']');
        }
        Value::Array(items) if !items.is_empty() => {
            out.push_str("[\n");
            for (i, item) in items.iter().enumerate() {
                pad(indent + 2, out);
                write_pretty(item, indent + 2, out);
                out.push_str(if i + 1 < items.len() { ",\n" } else { "\n" });
            }
            pad(indent, out);
            out.push(']');
        }
        Value::Object(map) if !map.is_empty() => {
            out.push_str("{\n");
            for (i, (key, item)) in map.iter().enumerate() {
                pad(indent + 2, out);
                out.push_str(&Value::from(key.as_str()).to_string());
                out.push_str(": ");
                write_pretty(item, indent + 2, out);
                out.push_str(if i + 1 < map.len() { ",\n" } else { "\n" });
            }
            pad(indent, out);
            out.push('}');
        }
        other => write_scalar(other, out),
    }
}

/// A scalar as JSON; numbers in their shortest round-trip form, whole numbers without a
/// fraction (`1`, not `1.0`), so that a written file reads as people write it.
fn write_scalar(v: &Value, out: &mut String) {
    match v.as_f64() {
        // Whole numbers up to 2^53 are exact as integers.
        Some(x) if v.is_f64() && x.fract() == 0.0 && x.abs() < 9_007_199_254_740_992.0 => {
            if x == 0.0 && x.is_sign_negative() {
                out.push_str("-0");
            } else {
                out.push_str(&format!("{x:.0}"));
            }
        }
        _ => out.push_str(&v.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_width_in_scene_units_reads_writes_back_and_bad_units_are_named() {
        let doc = |style: &str| {
            format!(
                r#"{{"version":1,"curves":[{{"type":"bezier","points":[[0,0],[1,1]],"style":{style}}}]}}"#
            )
        };
        let s = from_json_str(&doc(r#"{"width": 2000, "width_units": "scene"}"#)).unwrap();
        assert!(s.curves[0].style.width_in_scene);
        assert_eq!(s.curves[0].style.width, 2000.0);
        let back = from_json_str(&to_json_string(&s)).unwrap();
        assert_eq!(back.curves[0].style, s.curves[0].style);
        let e = from_json_str(&doc(r#"{"width_units": "mm"}"#)).unwrap_err();
        assert!(
            e.to_string().contains("width_units") && e.to_string().contains("mm"),
            "{e}"
        );
        let e = from_json_str(&doc(r#"{"width": 2000}"#)).unwrap_err();
        assert!(e.to_string().contains("2000 px"), "{e}");
        let e = from_json_str(&doc(r#"{"width": 1e300, "width_units": "scene"}"#)).unwrap_err();
        assert!(e.to_string().contains("scene units"), "{e}");
        let px = from_json_str(&doc(r#"{"width": 3, "width_units": "px"}"#)).unwrap();
        assert!(!px.curves[0].style.width_in_scene);
    }

    #[test]
    fn caps_joins_and_miter_limits_read_write_back_and_bad_ones_are_named() {
        let doc = |style: &str| {
            format!(
                r#"{{"version":1,"curves":[{{"type":"bezier","points":[[0,0],[1,1]],"style":{style}}}]}}"#
            )
        };
        let s = from_json_str(&doc(
            r#"{"cap": "square", "join": "bevel", "miter_limit": 7.5}"#,
        ))
        .unwrap();
        let st = s.curves[0].style.stroke;
        assert_eq!(
            (st.cap, st.join, st.miter_limit),
            (Cap::Square, Join::Bevel, 7.5)
        );
        let text = to_json_string(&s);
        assert!(text.contains(r#""cap": "square""#) && text.contains(r#""miter_limit": 7.5"#));
        assert_eq!(
            from_json_str(&text).unwrap().curves[0].style,
            s.curves[0].style
        );
        // The defaults are not written.
        let plain = from_json_str(&doc("{}")).unwrap();
        assert!(!to_json_string(&plain).contains("cap"));
        assert_eq!(plain.curves[0].style.stroke, StrokeShape::default());
        for (bad, words) in [
            (r#"{"cap": "flat"}"#, ["cap", "flat"]),
            (r#"{"join": "arcs"}"#, ["join", "arcs"]),
            (r#"{"miter_limit": 0.5}"#, ["miter_limit", "0.5"]),
            (r#"{"miter_limit": 5000}"#, ["miter_limit", "5000"]),
        ] {
            let e = from_json_str(&doc(bad)).unwrap_err().to_string();
            assert!(words.iter().all(|w| e.contains(w)), "{bad}: {e}");
        }
    }
    use glam::DVec3;

    fn err(text: &str) -> SceneError {
        from_json_str(text).expect_err("should be rejected")
    }

    #[test]
    fn minimal_scene_reads_with_defaults() {
        let s =
            from_json_str(r#"{"version":1,"curves":[{"type":"bezier","points":[[0,0],[1,2,3]]}]}"#)
                .unwrap();
        assert_eq!(s.curves.len(), 1);
        assert_eq!(
            s.curves[0].curve.control_points()[1],
            DVec3::new(1.0, 2.0, 3.0)
        );
        assert_eq!(s.curves[0].style, Style::default_for(0));
        assert_eq!(s.view, ViewSpec::Auto);
    }

    #[test]
    fn nan_literal_is_reported_at_its_path() {
        let e = err(r#"{"version":1,"curves":[{"type":"bezier","points":[[0,0],[1,NaN]]}]}"#);
        assert_eq!(e.path, "curves[0].points[1][1]");
        assert_eq!(e.kind, SceneErrorKind::NotFinite("NaN".into()));
        let e = err(r#"{"version":1,"curves":[{"type":"bezier","points":[[0,0],[1,1e999]]}]}"#);
        assert_eq!(e.path, "curves[0].points[1][1]");
        assert!(matches!(e.kind, SceneErrorKind::NotFinite(_)));
    }

    #[test]
    fn nan_inside_a_string_is_left_alone() {
        let e = err(
            r#"{"version":1,"name":"NaN","curves":[{"type":"bezier","points":[[0,0],[1,x]]}]}"#,
        );
        assert!(
            matches!(e.kind, SceneErrorKind::Syntax { line: 1, .. }),
            "{e}"
        );
    }

    #[test]
    fn whole_numbers_are_written_without_a_fraction_and_others_round_trip() {
        let v = serde_json::json!([1.0, -2.0, 0.5, 0.1, 1e300, 3, -0.0, 9007199254740992.0]);
        let text = pretty_json(&v);
        assert_eq!(text, "[1, -2, 0.5, 0.1, 1e+300, 3, -0, 9007199254740992.0]");
        let back: Vec<f64> = serde_json::from_str(&text).unwrap();
        let want: [f64; 8] = [1.0, -2.0, 0.5, 0.1, 1e300, 3.0, -0.0, 9007199254740992.0];
        for (a, b) in back.iter().zip(want) {
            assert_eq!(a.to_bits(), b.to_bits(), "{a} vs {b}");
        }
    }

    #[test]
    fn written_scene_reads_back_identically() {
        let scene = super::super::gallery::gallery();
        let text = to_json_string(&scene);
        let back = from_json_str(&text).unwrap();
        assert_eq!(back.curves.len(), scene.curves.len());
        for (a, b) in back.curves.iter().zip(&scene.curves) {
            assert_eq!(a.curve, b.curve);
            assert_eq!(a.name, b.name);
            assert_eq!(a.style.width, b.style.width);
            assert_eq!(a.style.color.to_hex(), b.style.color.to_hex());
        }
        assert_eq!(back.view, scene.view);
    }
}
