//! Solve requests (`splinescope solve SCENE REQUEST`): a JSON document naming a curve, a
//! method and its inputs, applied to a scene to give the modified scene and a JSON report.
//! The format is documented in `docs/solve-format.md`.

use glam::DVec3;
use serde_json::{Map, Value, json};
use thiserror::Error;

use crate::geom::{Bezier, Curve, ParamCurve};
use crate::inspect::{point, points};
use crate::jsonread::{Node, parse_document};
use crate::scene::{Annotation, AnnotationShape, Color, Scene, SceneError};
use crate::solve::shape::{
    PolygonType, SingleTargetOptions, cubic_region, multi_target, single_target, tangent_kept,
};
use crate::solve::{SolveError, nearest, nubmp};

/// The methods a request may name.
pub const METHODS: [&str; 7] = [
    "single_target",
    "tangent_kept",
    "multi_target",
    "cubic_region",
    "nubmp_constrained",
    "nubmp_find_tau",
    "project",
];

/// Why a request could not be applied: the path of the offending value in the request
/// document (`[1].target`, `first`) and what is wrong.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{path}: {message}")]
pub struct RequestError {
    /// Where, as a JSON path in the request document, or `(root)`.
    pub path: String,
    /// What.
    pub message: String,
}

impl From<SceneError> for RequestError {
    fn from(e: SceneError) -> RequestError {
        RequestError {
            path: e.path,
            message: e.kind.to_string(),
        }
    }
}

fn at(node: &Node<'_>, field: &str, e: &SolveError) -> RequestError {
    let base = node.display_path();
    RequestError {
        path: if field.is_empty() {
            base
        } else if node.path.is_empty() {
            field.to_owned()
        } else {
            format!("{base}.{field}")
        },
        message: e.to_string(),
    }
}

/// The outcome of applying requests: the modified scene and one report per request.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The scene after every request.
    pub scene: Scene,
    /// One report per request, in order.
    pub reports: Vec<Value>,
}

/// Parses a request document (one request object, or an array of them) and applies each,
/// in order, to `scene`. Nothing is changed unless every request succeeds.
///
/// # Errors
/// [`RequestError`] naming the offending value of the request.
pub fn apply_text(scene: &Scene, text: &str) -> Result<Outcome, RequestError> {
    let value = parse_document(text)?;
    let root = Node::root(&value);
    let nodes = match &value {
        Value::Array(_) => root.array()?,
        _ => vec![Node::root(&value)],
    };
    let mut scene = scene.clone();
    let mut reports = Vec::new();
    for node in &nodes {
        let mut targets = Vec::new();
        let report = apply_one(&mut scene, node, &mut targets)?;
        check_outputs(&scene, node, &report)?;
        if !targets.is_empty() {
            scene.annotations.push(Annotation {
                shape: AnnotationShape::Points(targets),
                color: TARGET_COLOR,
                width: 9.0,
                label: Some(format!(
                    "{} target(s) of curves[{}]",
                    report["method"].as_str().unwrap_or_default(),
                    report["curve"]
                )),
            });
        }
        reports.push(report);
    }
    Ok(Outcome { scene, reports })
}

/// The request's own path: `[2]` in an array, `request` for a single one.
fn request_path(node: &Node<'_>) -> String {
    let p = node.path.to_string();
    if p.is_empty() { "request".into() } else { p }
}

/// Every number a request produced is finite: the report (where `null` only ever stands
/// for "not applicable" under `reachable_limited`) and the curve it changed, with its
/// lowering. Otherwise the request is refused, named, and nothing is written.
fn check_outputs(scene: &Scene, node: &Node<'_>, report: &Value) -> Result<(), RequestError> {
    fn walk(v: &Value, at: &str, bad: &mut Option<String>) {
        match v {
            Value::Null if !at.ends_with("reachable_limited") => {
                bad.get_or_insert_with(|| at.to_owned());
            }
            Value::Number(n) if n.as_f64().is_none_or(|x| !x.is_finite()) => {
                bad.get_or_insert_with(|| at.to_owned());
            }
            Value::Array(items) => {
                for (i, item) in items.iter().enumerate() {
                    walk(item, &format!("{at}[{i}]"), bad);
                }
            }
            Value::Object(map) => {
                for (k, item) in map {
                    walk(item, &format!("{at}.{k}"), bad);
                }
            }
            _ => {}
        }
    }
    let mut bad = None;
    walk(report, "report", &mut bad);
    if let Some(at) = bad {
        return Err(RequestError {
            path: request_path(node),
            message: format!(
                "the solve produced a value that is not a finite number ({at}): its inputs are too extreme for f64 (a parameter too close to an end, or coordinates too large)"
            ),
        });
    }
    // A solve changes only the curve it names: that one is checked, not the whole scene.
    let Some(c) = report["curve"]
        .as_u64()
        .and_then(|i| scene.curves.get(i as usize))
    else {
        return Ok(());
    };
    let control = c
        .curve
        .control_points()
        .iter()
        .position(|p| !p.is_finite())
        .map(|j| format!("control point {j} is not a finite number"));
    if let Some(why) = control.or_else(|| c.curve.check_derived().err().map(|e| e.to_string())) {
        return Err(RequestError {
            path: request_path(node),
            message: format!(
                "the solve left curves[{}] with a value that is not finite ({why}); nothing was changed",
                report["curve"]
            ),
        });
    }
    Ok(())
}

/// The colour of target markers: each request's targets are marked in the scene (red
/// discs), so the result can be checked by eye.
pub const TARGET_COLOR: Color = Color([0.85, 0.1, 0.1, 1.0]);

const FIELDS: [&str; 15] = [
    "curve",
    "method",
    "target",
    "targets",
    "t",
    "params",
    "first",
    "count",
    "accuracy",
    "limited",
    "tau",
    "group",
    "respect_vd",
    "apply",
    "reach",
];

/// The fields each method reads (beyond `curve` and `method`).
fn method_fields(method: &str) -> &'static [&'static str] {
    match method {
        "single_target" => &["target", "t", "first", "count", "accuracy"],
        "tangent_kept" => &["target", "t", "accuracy"],
        "multi_target" => &["targets", "params", "accuracy"],
        "cubic_region" => &["target", "limited", "reach"],
        "nubmp_constrained" => &["target", "tau", "group", "respect_vd"],
        "nubmp_find_tau" => &["target", "group", "apply", "respect_vd"],
        "project" => &["target", "accuracy"],
        _ => &[],
    }
}

fn bezier_of<'s>(
    scene: &'s Scene,
    index: usize,
    node: &Node<'_>,
    method: &str,
) -> Result<&'s Bezier, RequestError> {
    match &scene.curves[index].curve {
        Curve::Bezier(b) => Ok(b),
        other => Err(RequestError {
            path: field_path(node, "curve"),
            message: format!(
                "{method} modifies Bézier curves (paper 000); curves[{index}] is {}",
                other.family()
            ),
        }),
    }
}

fn field_path(node: &Node<'_>, field: &str) -> String {
    if node.path.is_empty() {
        field.to_owned()
    } else {
        format!("{}.{field}", node.path)
    }
}

/// Applies one request to `scene` and returns its report; `targets` receives the points
/// the request aimed at, for marking.
fn apply_one(
    scene: &mut Scene,
    node: &Node<'_>,
    targets: &mut Vec<DVec3>,
) -> Result<Value, RequestError> {
    let obj = node.object(&FIELDS)?;
    let method_node = obj.req("method")?;
    let method = method_node.string()?;
    if !METHODS.contains(&method) {
        return Err(method_node
            .invalid(format!(
                "unknown method {method:?} (expected one of: {})",
                METHODS.join(", ")
            ))
            .into());
    }
    for key in obj.map.keys() {
        if key != "curve" && key != "method" && !method_fields(method).contains(&key.as_str()) {
            return Err(RequestError {
                path: field_path(node, key),
                message: format!(
                    "not used by {method} (it reads: curve, method, {})",
                    method_fields(method).join(", ")
                ),
            });
        }
    }
    let curve_node = obj.req("curve")?;
    let index = curve_node.u32_in(0, u32::MAX)? as usize;
    if index >= scene.curves.len() {
        return Err(curve_node
            .invalid(format!(
                "curve {index} does not exist (the scene has {} curve(s))",
                scene.curves.len()
            ))
            .into());
    }
    let opt_f64 = |key: &str| obj.get(key).map(|n| n.f64()).transpose();
    let mut report_target: Option<DVec3> = None;
    let accuracy = match obj.get("accuracy") {
        Some(n) => Some(n.positive_f64()?),
        None => None,
    };
    let target = || -> Result<DVec3, RequestError> { Ok(obj.req("target")?.point()?) };
    if let Some(t) = obj.get("target") {
        report_target = Some(t.point()?);
    }
    let mut report = Map::new();
    report.insert("curve".into(), index.into());
    report.insert("method".into(), method.into());
    if let Some(t) = report_target {
        report.insert("target".into(), point(t));
        targets.push(t);
    }
    match method {
        "single_target" => {
            let b = bezier_of(scene, index, node, method)?;
            let window = match (obj.get("first"), obj.get("count")) {
                (None, None) => None,
                (Some(f), Some(c)) => Some((
                    f.u32_in(0, u32::MAX)? as usize,
                    c.u32_in(0, u32::MAX)? as usize,
                )),
                (Some(_), None) => {
                    return Err(SceneError::new(
                        field_path(node, "count"),
                        crate::scene::SceneErrorKind::Missing,
                    )
                    .into());
                }
                (None, Some(_)) => {
                    return Err(SceneError::new(
                        field_path(node, "first"),
                        crate::scene::SceneErrorKind::Missing,
                    )
                    .into());
                }
            };
            let opts = SingleTargetOptions {
                t_s: opt_f64("t")?,
                window,
                accuracy,
            };
            let s = single_target(b, target()?, &opts).map_err(|e| {
                let field = match e {
                    SolveError::WindowOutOfRange { .. } => "first",
                    SolveError::ParameterAtEnd { .. }
                    | SolveError::ParameterOutsideDomain { .. } => "t",
                    SolveError::NonFiniteTarget { .. } | SolveError::TargetAtEnd { .. } => "target",
                    _ => "",
                };
                at(node, field, &e)
            })?;
            report.insert("t".into(), s.t_s.into());
            report.insert("start".into(), point(s.start));
            report.insert(
                "moved".into(),
                (s.first..s.first + s.deltas.len())
                    .collect::<Vec<_>>()
                    .into(),
            );
            report.insert("deltas".into(), points(&s.deltas));
            report.insert("control_points".into(), points(s.curve.points()));
            report.insert("residual".into(), s.residual.into());
            scene.curves[index].curve = Curve::Bezier(s.curve);
        }
        "tangent_kept" => {
            let b = bezier_of(scene, index, node, method)?;
            let s = tangent_kept(b, target()?, opt_f64("t")?, accuracy).map_err(|e| {
                let field = match e {
                    SolveError::ParameterAtEnd { .. }
                    | SolveError::ParameterOutsideDomain { .. } => "t",
                    SolveError::NonFiniteTarget { .. } | SolveError::TargetAtEnd { .. } => "target",
                    _ => "curve",
                };
                at(node, field, &e)
            })?;
            report.insert("t".into(), s.t_s.into());
            report.insert("mu".into(), s.mu.to_vec().into());
            report.insert("directions".into(), points(&s.directions));
            report.insert("deltas".into(), points(&s.deltas));
            report.insert("control_points".into(), points(s.curve.points()));
            report.insert("residual".into(), s.residual.into());
            report.insert("least_squares".into(), s.least_squares.into());
            scene.curves[index].curve = Curve::Bezier(s.curve);
        }
        "multi_target" => {
            let b = bezier_of(scene, index, node, method)?;
            *targets = obj.req("targets")?.points(1)?;
            let params = obj.get("params").map(|n| n.numbers()).transpose()?;
            let s = multi_target(b, targets, params.as_deref(), accuracy).map_err(|e| {
                let field = match e {
                    SolveError::ParamCount { .. } | SolveError::ParameterOutsideDomain { .. } => {
                        "params".to_owned()
                    }
                    SolveError::ParameterAtEnd { index, .. } => format!("params[{index}]"),
                    SolveError::NonFiniteTarget { index, .. }
                    | SolveError::TargetAtEnd { index, .. } => {
                        format!("targets[{index}]")
                    }
                    _ => String::new(),
                };
                at(node, &field, &e)
            })?;
            report.insert("targets".into(), points(targets));
            report.insert("params".into(), s.params.clone().into());
            report.insert("deltas".into(), points(&s.deltas));
            report.insert("residuals".into(), s.residuals.clone().into());
            report.insert(
                "max_residual".into(),
                s.residuals.iter().copied().fold(0.0, f64::max).into(),
            );
            report.insert("rank".into(), s.rank.into());
            report.insert("least_squares".into(), s.least_squares.into());
            report.insert("control_points".into(), points(s.curve.points()));
            scene.curves[index].curve = Curve::Bezier(s.curve);
        }
        "cubic_region" => {
            let b = bezier_of(scene, index, node, method)?.clone();
            let region = cubic_region(&b).map_err(|e| at(node, "curve", &e))?;
            let limited = obj
                .get("limited")
                .map(|n| n.bool())
                .transpose()?
                .unwrap_or(false);
            let reach = match obj.get("reach") {
                Some(n) => n.positive_f64()?,
                None => 3.0 * b.control_box().diagonal().max(1e-9),
            };
            report.insert("type".into(), region.kind.number().into());
            if let PolygonType::Converging { apex } = region.kind {
                report.insert("apex".into(), point(apex));
            }
            report.insert("directions".into(), points(&[region.e1, region.e2]));
            if let Some(t) = report_target {
                report.insert("reachable".into(), region.contains(t).into());
                report.insert(
                    "reachable_limited".into(),
                    region.contains_limited(t).map_or(Value::Null, Value::from),
                );
            }
            let boundary = region.boundary(limited, reach);
            report.insert("limited".into(), limited.into());
            report.insert(
                "boundary".into(),
                Value::Array(boundary.iter().map(|l| points(l)).collect()),
            );
            // The outline goes into the scene as an annotation, for drawing.
            for line in boundary {
                scene.annotations.push(Annotation {
                    shape: AnnotationShape::Polyline(line),
                    color: Color([0.45, 0.45, 0.45, 0.9]),
                    width: 1.5,
                    label: Some(format!("allowed region of curves[{index}]")),
                });
            }
        }
        "nubmp_constrained" | "nubmp_find_tau" => {
            let Curve::Nubmp(nub) = &scene.curves[index].curve else {
                return Err(RequestError {
                    path: field_path(node, "curve"),
                    message: format!(
                        "{method} modifies NUBMP curves (paper 001); curves[{index}] is {}",
                        scene.curves[index].curve.family()
                    ),
                });
            };
            let nub = nub.clone();
            let group = obj.req("group")?.u32_in(0, u32::MAX)? as usize;
            let q = target()?;
            let respect_vd = obj
                .get("respect_vd")
                .map(|n| n.bool())
                .transpose()?
                .unwrap_or(false);
            let field_of = |e: &SolveError| match e {
                SolveError::ParameterOutsideDomain { .. } => "tau",
                SolveError::GroupInactive { .. }
                | SolveError::Geom(_)
                | SolveError::NoTau { .. } => "group",
                _ => "target",
            };
            let tau = if method == "nubmp_find_tau" {
                let found =
                    nubmp::find_tau(&nub, group, q).map_err(|e| at(node, field_of(&e), &e))?;
                report.insert(
                    "intervals".into(),
                    Value::Array(found.intervals.iter().map(|(a, b)| json!([a, b])).collect()),
                );
                report.insert("best".into(), found.best.into());
                if !obj
                    .get("apply")
                    .map(|n| n.bool())
                    .transpose()?
                    .unwrap_or(false)
                {
                    return Ok(Value::Object(report));
                }
                found.best
            } else {
                obj.req("tau")?.f64()?
            };
            let s = nubmp::constrained(&nub, tau, group, q, respect_vd)
                .map_err(|e| at(node, field_of(&e), &e))?;
            report.insert("tau".into(), tau.into());
            report.insert("group".into(), group.into());
            report.insert(
                "members".into(),
                s.curve.groups()[group].members.clone().into(),
            );
            report.insert("values".into(), s.values.clone().into());
            report.insert("region".into(), points(&s.region));
            report.insert("dual_points".into(), points(s.curve.dual_points()));
            report.insert("residual".into(), s.residual.into());
            scene.curves[index].curve = Curve::Nubmp(s.curve);
        }
        "project" => {
            let q = target()?;
            if let Some(value) = q.to_array().into_iter().find(|c| !c.is_finite()) {
                return Err(at(
                    node,
                    "target",
                    &SolveError::NonFiniteTarget { index: 0, value },
                ));
            }
            let n = nearest(&scene.curves[index].curve, q, accuracy);
            report.insert("t".into(), n.t.into());
            report.insert("point".into(), point(n.point));
            report.insert("distance".into(), n.distance.into());
            let d = scene.curves[index].curve.eval_deriv(n.t);
            report.insert("tangent".into(), point(d));
        }
        _ => unreachable!("methods were checked"),
    }
    Ok(Value::Object(report))
}
