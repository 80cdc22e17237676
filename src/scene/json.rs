//! Reading and writing the JSON scene format with path-naming errors (the reader walks the
//! parsed value with [`crate::jsonread`]).

use glam::{DVec2, DVec3};
use serde_json::{Map, Value};

use crate::jsonread::{Node, Obj, describe, parse_document};

use super::{
    Annotation, AnnotationShape, Color, FORMAT_VERSION, MAX_SAMPLES_PER_SEGMENT, Scene, SceneCurve,
    SceneError, SceneErrorKind, Style, ViewSpec,
};
use crate::geom::exact::{Rational, parse_decimal};
use crate::geom::{
    BSpline, Bezier, CubicInterpolation, Curve, GeomError, KnotVector, Modification,
    ModifiedBezier, Nubmp, Reading,
};

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
        .map(|n| n.string().map(str::to_owned))
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
        crate::limits::CURVES
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
        background: background.unwrap_or(Color::WHITE),
        samples_per_segment: samples,
        view: view.unwrap_or(ViewSpec::Auto),
        curves,
        annotations,
    })
}

/// The default colour of annotations.
const ANNOTATION_COLOR: Color = Color([0.35, 0.35, 0.35, 0.9]);

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
        .map(|n| n.string().map(str::to_owned))
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
                fov_deg: angle("fov_deg", crate::camera::DEFAULT_FOV_DEG, 1.0, 179.0)?,
            })
        }
        other => Err(kind.invalid(format!(
            "unknown view kind {other:?} (expected \"2d\" or \"3d\")"
        ))),
    }
}

/// The fields every curve object may have, whatever its family.
const COMMON_CURVE_FIELDS: [&str; 3] = ["type", "name", "style"];

fn decode_curve(node: &Node<'_>, index: usize) -> Result<SceneCurve, SceneError> {
    let Value::Object(map) = node.value else {
        return Err(node.wrong_type("a curve object"));
    };
    let probe = Obj {
        map,
        path: node.path.clone(),
    };
    let ty = probe.req("type")?;
    let family = ty.string()?;
    let (curve, obj) = match family {
        "bezier" => {
            let obj = node.object(&with_common(&["points"]))?;
            let points = bezier_points(&obj)?;
            let curve = Bezier::try_new(points).map_err(|e| geom_error(node, "", &e))?;
            (Curve::Bezier(curve), obj)
        }
        "modified_bezier" => {
            let obj = node.object(&with_common(&["points", "t_star", "v"]))?;
            let points = bezier_points(&obj)?;
            let t_star = obj.req("t_star")?.f64()?;
            let v = obj.req("v")?.point()?;
            let base = Bezier::try_new(points).map_err(|e| geom_error(node, "", &e))?;
            let curve =
                ModifiedBezier::try_new(base, t_star, v).map_err(|e| geom_error(node, "", &e))?;
            (Curve::Modified(curve), obj)
        }
        "interpolation" => {
            let obj = node.object(&with_common(&["points", "params", "modification"]))?;
            let points = obj.req("points")?.points(2)?;
            let params = obj.get("params").map(|n| n.numbers()).transpose()?;
            let modification = obj
                .get("modification")
                .map(|n| decode_modification(&n))
                .transpose()?;
            let curve = CubicInterpolation::try_new(points, params, modification).map_err(|e| {
                let prefix = match e {
                    GeomError::TStarOutside { .. }
                    | GeomError::NonFiniteVector { .. }
                    | GeomError::DerivedNotFinite {
                        field: "t_star", ..
                    } => "modification.",
                    _ => "",
                };
                geom_error(node, prefix, &e)
            })?;
            (Curve::Interpolation(curve), obj)
        }
        "bspline" => {
            let obj = node.object(&with_common(&["points", "knots", "order"]))?;
            let (points, knots) = decode_spline_parts(node, &obj)?;
            let curve = BSpline::from_parts(points, knots).map_err(|e| geom_error(node, "", &e))?;
            (Curve::BSpline(curve), obj)
        }
        "nubmp" => {
            let obj = node.object(&with_common(&["points", "knots", "order", "shape"]))?;
            let (points, knots) = decode_spline_parts(node, &obj)?;
            let mut curve = Nubmp::standard(points, knots).map_err(|e| geom_error(node, "", &e))?;
            if let Some(shape) = obj.get("shape") {
                for setting in shape.array()? {
                    apply_shape_setting(&mut curve, &setting)?;
                }
            }
            (Curve::Nubmp(curve), obj)
        }
        other => {
            return Err(ty.invalid(format!(
                "unknown curve type {other:?} (expected one of: {})",
                FAMILIES.join(", ")
            )));
        }
    };
    curve
        .check_derived()
        .map_err(|e| geom_error(node, "", &e))?;
    let name = obj
        .get("name")
        .map(|n| n.string().map(str::to_owned))
        .transpose()?;
    let style = match obj.get("style") {
        None => Style::default_for(index),
        Some(n) => decode_style(&n, index)?,
    };
    Ok(SceneCurve { name, curve, style })
}

/// A Bézier curve's points, its degree checked against [`crate::limits::DEGREE`].
fn bezier_points(obj: &Obj<'_>) -> Result<Vec<glam::DVec3>, SceneError> {
    let node = obj.req("points")?;
    let points = node.points(2)?;
    crate::limits::DEGREE
        .check(points.len() as u64 - 1)
        .map_err(|e| node.invalid(e.to_string()))?;
    Ok(points)
}

/// The curve types the format knows.
const FAMILIES: [&str; 5] = [
    "bezier",
    "modified_bezier",
    "interpolation",
    "bspline",
    "nubmp",
];

fn decode_modification(node: &Node<'_>) -> Result<Modification, SceneError> {
    let obj = node.object(&["t_star", "v", "reading"])?;
    let reading = match obj.get("reading") {
        None => Reading::Paper,
        Some(n) => match n.string()? {
            "paper" => Reading::Paper,
            "bump_added" => Reading::BumpAdded,
            other => {
                return Err(n.invalid(format!(
                    "unknown reading {other:?} (expected \"paper\" or \"bump_added\")"
                )));
            }
        },
    };
    Ok(Modification {
        t_star: obj.req("t_star")?.f64()?,
        v: obj.req("v")?.point()?,
        reading,
    })
}

/// Points and validated knots, with the knots' exact decimal values recorded.
fn decode_spline_parts(
    node: &Node<'_>,
    obj: &Obj<'_>,
) -> Result<(Vec<glam::DVec3>, KnotVector), SceneError> {
    let points = obj.req("points")?.points(2)?;
    let order_node = obj.req("order")?;
    let order = order_node.u32_in(0, u32::MAX)? as usize;
    crate::limits::ORDER
        .check(order as u64)
        .map_err(|e| order_node.invalid(e.to_string()))?;
    let knots_node = obj.req("knots")?;
    let knots = match knots_node.value {
        Value::String(s) if s == "clamped_uniform" => {
            KnotVector::clamped_uniform(order, points.len())
                .map_err(|e| geom_error(node, "", &e))?
        }
        Value::String(s) => {
            return Err(knots_node.invalid(format!(
                "unknown knot vector {s:?} (expected an array of numbers or \"clamped_uniform\")"
            )));
        }
        _ => {
            let items = knots_node.array()?;
            let values = items.iter().map(Node::f64).collect::<Result<Vec<_>, _>>()?;
            let exact: Option<Vec<Rational>> = items
                .iter()
                .map(|n| match n.value {
                    Value::Number(x) => parse_decimal(&x.to_string()),
                    _ => None,
                })
                .collect();
            let kv = KnotVector::try_new(values, order, points.len())
                .map_err(|e| geom_error(node, "", &e))?;
            match exact {
                Some(exact) => kv.with_exact(exact),
                None => kv,
            }
        }
    };
    Ok((points, knots))
}

/// Applies one entry of a NUBMP `shape` list: `{"group": j, "values": [...]}` or
/// `{"group": j, "member": i, "value": x, "absorber": l}`.
fn apply_shape_setting(curve: &mut Nubmp, node: &Node<'_>) -> Result<(), SceneError> {
    let obj = node.object(&["group", "values", "member", "value", "absorber"])?;
    let group = obj.req("group")?.u32_in(0, u32::MAX)? as usize;
    let at =
        |field: &str| SceneError::new(format!("{}.{field}", node.path), SceneErrorKind::Missing);
    let err = |field: String, e: &GeomError| {
        SceneError::new(
            format!("{}.{field}", node.path),
            SceneErrorKind::Invalid(e.to_string()),
        )
    };
    if let Some(values_node) = obj.get("values") {
        for extra in ["member", "value", "absorber"] {
            if obj.get(extra).is_some() {
                return Err(SceneError::new(
                    format!("{}.{extra}", node.path),
                    SceneErrorKind::Invalid(
                        "give either \"values\" (the whole group) or \"member\", \"value\" and \"absorber\"".into(),
                    ),
                ));
            }
        }
        let values = values_node.numbers()?;
        return curve.set_group(group, &values).map_err(|e| {
            let field = match &e {
                GeomError::NoSuchGroup { .. } | GeomError::GroupOutsideDomain { .. } => {
                    "group".into()
                }
                GeomError::NegativeParameter { member, .. } => curve.groups()[group]
                    .position(*member)
                    .map_or("values".into(), |p| format!("values[{p}]")),
                _ => "values".into(),
            };
            err(field, &e)
        });
    }
    let member_node = obj.get("member").ok_or_else(|| at("member"))?;
    let member = member_node.u32_in(0, u32::MAX)? as usize;
    let value = obj.get("value").ok_or_else(|| at("value"))?.f64()?;
    let absorber = obj
        .get("absorber")
        .ok_or_else(|| at("absorber"))?
        .u32_in(0, u32::MAX)? as usize;
    curve
        .set_parameter(group, member, value, absorber)
        .map_err(|e| {
            let field = match &e {
                GeomError::NoSuchGroup { .. } | GeomError::GroupOutsideDomain { .. } => "group",
                GeomError::NotInGroup { member: m, .. } if *m == member => "member",
                GeomError::NotInGroup { .. } | GeomError::SameAbsorber { .. } => "absorber",
                // A negative result (for either member) comes from the value asked for.
                _ => "value",
            };
            err(field.into(), &e)
        })
}

fn with_common(fields: &[&'static str]) -> Vec<&'static str> {
    COMMON_CURVE_FIELDS.iter().chain(fields).copied().collect()
}

fn geom_error(curve: &Node<'_>, prefix: &str, e: &GeomError) -> SceneError {
    let field = e.field();
    let path = if field.is_empty() {
        curve.path.to_string()
    } else {
        format!("{}.{prefix}{field}", curve.path)
    };
    SceneError::new(path, SceneErrorKind::Invalid(e.to_string()))
}

fn decode_style(node: &Node<'_>, index: usize) -> Result<Style, SceneError> {
    let obj = node.object(&["color", "width", "polygon", "points", "samples"])?;
    let mut style = Style::default_for(index);
    if let Some(n) = obj.get("color") {
        style.color = n.color()?;
    }
    if let Some(n) = obj.get("width") {
        let w = n.positive_f64()?;
        if w > 1000.0 {
            return Err(n.invalid(format!("width {w} px is over the maximum of 1000")));
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

fn point_json(p: DVec3) -> Value {
    if p.z == 0.0 {
        serde_json::json!([p.x, p.y])
    } else {
        serde_json::json!([p.x, p.y, p.z])
    }
}

fn points_json(points: &[DVec3]) -> Value {
    Value::Array(points.iter().copied().map(point_json).collect())
}

fn curve_json(c: &SceneCurve) -> Value {
    let mut obj = Map::new();
    obj.insert("type".into(), c.curve.family().into());
    if let Some(name) = &c.name {
        obj.insert("name".into(), name.clone().into());
    }
    match &c.curve {
        Curve::Bezier(b) => {
            obj.insert("points".into(), points_json(b.points()));
        }
        Curve::Modified(m) => {
            obj.insert("points".into(), points_json(m.base().points()));
            obj.insert("t_star".into(), m.t_star().into());
            obj.insert("v".into(), point_json(m.v()));
        }
        Curve::Interpolation(ip) => {
            obj.insert("points".into(), points_json(ip.points()));
            obj.insert("params".into(), ip.params().to_vec().into());
            if let Some(m) = ip.modification() {
                obj.insert(
                    "modification".into(),
                    serde_json::json!({
                        "t_star": m.t_star, "v": point_json(m.v), "reading": m.reading.name()
                    }),
                );
            }
        }
        Curve::BSpline(b) => {
            obj.insert("points".into(), points_json(b.points()));
            obj.insert("knots".into(), b.knots().knots().to_vec().into());
            obj.insert("order".into(), b.order().into());
        }
        Curve::Nubmp(n) => {
            obj.insert("points".into(), points_json(n.points()));
            obj.insert("knots".into(), n.knots().knots().to_vec().into());
            obj.insert("order".into(), n.order().into());
            let shape: Vec<Value> = n
                .groups()
                .iter()
                .enumerate()
                .filter(|(_, g)| g.values != g.standard)
                .map(|(j, g)| serde_json::json!({"group": j, "values": g.values}))
                .collect();
            if !shape.is_empty() {
                obj.insert("shape".into(), Value::Array(shape));
            }
        }
    }
    let s = &c.style;
    let mut style = Map::new();
    style.insert("color".into(), s.color.to_hex().into());
    style.insert("width".into(), f64::from(s.width).into());
    style.insert("polygon".into(), s.show_polygon.into());
    style.insert("points".into(), s.show_points.into());
    if let Some(n) = s.samples {
        style.insert("samples".into(), n.into());
    }
    obj.insert("style".into(), Value::Object(style));
    Value::Object(obj)
}

/// Writes a scene as pretty JSON in the current format version.
#[must_use]
pub fn to_json_string(scene: &Scene) -> String {
    let mut obj = Map::new();
    obj.insert("version".into(), FORMAT_VERSION.into());
    if let Some(name) = &scene.name {
        obj.insert("name".into(), name.clone().into());
    }
    obj.insert("background".into(), scene.background.to_hex().into());
    obj.insert(
        "samples".into(),
        scene
            .samples_per_segment
            .map_or_else(|| Value::from("auto"), Value::from),
    );
    let view = match scene.view {
        ViewSpec::Auto => Value::from("auto"),
        ViewSpec::TwoD { center, height } => serde_json::json!({
            "kind": "2d", "center": [center.x, center.y], "height": height
        }),
        ViewSpec::ThreeD {
            target,
            distance,
            yaw_deg,
            pitch_deg,
            fov_deg,
        } => serde_json::json!({
            "kind": "3d", "target": [target.x, target.y, target.z], "distance": distance,
            "yaw_deg": yaw_deg, "pitch_deg": pitch_deg, "fov_deg": fov_deg
        }),
    };
    obj.insert("view".into(), view);
    obj.insert(
        "curves".into(),
        Value::Array(scene.curves.iter().map(curve_json).collect()),
    );
    if !scene.annotations.is_empty() {
        let annotations = scene
            .annotations
            .iter()
            .map(|a| {
                let mut m = Map::new();
                match &a.shape {
                    AnnotationShape::Polyline(p) => m.insert("polyline".into(), points_json(p)),
                    AnnotationShape::Points(p) => m.insert("points".into(), points_json(p)),
                };
                m.insert("color".into(), a.color.to_hex().into());
                m.insert("width".into(), f64::from(a.width).into());
                if let Some(l) = &a.label {
                    m.insert("label".into(), l.clone().into());
                }
                Value::Object(m)
            })
            .collect();
        obj.insert("annotations".into(), Value::Array(annotations));
    }
    let mut text = String::new();
    write_pretty(&Value::Object(obj), 0, &mut text);
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
                out.push_str(&item.to_string());
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
        other => out.push_str(&other.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
