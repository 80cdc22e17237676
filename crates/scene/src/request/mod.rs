//! Solve requests (`splinescope solve SCENE REQUEST`): a JSON document naming a curve, a
//! method and its inputs, applied to a scene to give the modified scene and a JSON report.
//! The format is documented in `docs/solve-format.md`; requests are read into the types of
//! [`types`] and reports are written from them (their JSON Schemas are in `docs/schemas/`).

mod error;
mod methods;
pub mod types;

use glam::DVec3;
use serde_json::Value;

use crate::format::{Annotation, AnnotationShape, Scene};
use crate::jsonread::{Node, parse_document};
pub use error::RequestError;
use error::field_path;
use methods::Fields;
use splinescope_encoding::Color;
use types::{MethodReport, Report, Request};

/// One solve method: its name in requests, the fields it reads (beyond `curve` and
/// `method`) and its reader. [`METHOD_TABLE`] is the only list of methods: the names
/// requests may use, the fields each may give and the reader each gets all come from it,
/// and every match on [`Request`] is exhaustive, so a method added to the enum without a
/// row (or a row without a variant) does not compile or fails the table's test.
struct Method {
    name: &'static str,
    fields: &'static [&'static str],
    read: fn(&Fields<'_, '_>) -> Result<Request, RequestError>,
}

/// Every solve method, in the order messages list them.
const METHOD_TABLE: [Method; 7] = [
    Method {
        name: "single_target",
        fields: &["target", "t", "first", "count", "accuracy"],
        read: |f| Ok(Request::SingleTarget(methods::read_single_target(f)?)),
    },
    Method {
        name: "tangent_kept",
        fields: &["target", "t", "accuracy"],
        read: |f| Ok(Request::TangentKept(methods::read_tangent_kept(f)?)),
    },
    Method {
        name: "multi_target",
        fields: &["targets", "params", "accuracy"],
        read: |f| Ok(Request::MultiTarget(methods::read_multi_target(f)?)),
    },
    Method {
        name: "cubic_region",
        fields: &["target", "limited", "reach"],
        read: |f| Ok(Request::CubicRegion(methods::read_cubic_region(f)?)),
    },
    Method {
        name: "nubmp_constrained",
        fields: &["target", "tau", "group", "respect_vd"],
        read: |f| {
            Ok(Request::NubmpConstrained(methods::read_nubmp_constrained(
                f,
            )?))
        },
    },
    Method {
        name: "nubmp_find_tau",
        fields: &["target", "group", "apply", "respect_vd"],
        read: |f| Ok(Request::NubmpFindTau(methods::read_nubmp_find_tau(f)?)),
    },
    Method {
        name: "project",
        fields: &["target", "accuracy"],
        read: |f| Ok(Request::Project(methods::read_project(f)?)),
    },
];

/// The methods a request may name (from `METHOD_TABLE`).
pub const METHODS: [&str; METHOD_TABLE.len()] = {
    let mut names = [""; METHOD_TABLE.len()];
    let mut i = 0;
    while i < names.len() {
        names[i] = METHOD_TABLE[i].name;
        i += 1;
    }
    names
};

/// The outcome of applying requests: the modified scene and one report per request.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The scene after every request.
    pub scene: Scene,
    /// One report per request, in order.
    pub reports: Vec<Report>,
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
        let request = read(&scene, node)?;
        let report = run(&mut scene, node, &request)?;
        check_outputs(&scene, node, &report)?;
        let targets = targets_of(&request);
        if !targets.is_empty() {
            scene.annotations.push(Annotation {
                shape: AnnotationShape::Points(targets),
                color: TARGET_COLOR,
                width: 9.0,
                label: Some(format!(
                    "{} target(s) of curves[{}]",
                    request.method(),
                    report.curve
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
fn check_outputs(scene: &Scene, node: &Node<'_>, report: &Report) -> Result<(), RequestError> {
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
    let value = serde_json::to_value(report).unwrap_or(Value::Null);
    walk(&value, "report", &mut bad);
    if let Some(at) = bad {
        return Err(RequestError {
            path: request_path(node),
            message: format!(
                "the solve produced a value that is not a finite number ({at}): its inputs are too extreme for f64 (a parameter too close to an end, or coordinates too large)"
            ),
        });
    }
    // A solve changes only the curve it names: that one is checked, not the whole scene.
    let Some(c) = scene.curves.get(report.curve) else {
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
                report.curve
            ),
        });
    }
    Ok(())
}

/// The colour of target markers: each request's targets are marked in the scene (red
/// discs), so the result can be checked by eye.
pub const TARGET_COLOR: Color = Color::from_rgba8([217, 26, 26, 255]);

/// Reads one request object into its typed request: the method, only the fields it
/// reads, an existing curve, then the method's own fields.
fn read(scene: &Scene, node: &Node<'_>) -> Result<Request, RequestError> {
    // Every field any method reads.
    let mut known = vec!["curve", "method"];
    for field in METHOD_TABLE.iter().flat_map(|m| m.fields) {
        if !known.contains(field) {
            known.push(field);
        }
    }
    let obj = node.object(&known)?;
    let method_node = obj.req("method")?;
    let name = method_node.string()?;
    let Some(method) = METHOD_TABLE.iter().find(|m| m.name == name) else {
        return Err(method_node
            .invalid(format!(
                "unknown method {name:?} (expected one of: {})",
                METHODS.join(", ")
            ))
            .into());
    };
    for key in obj.map.keys() {
        if key != "curve" && key != "method" && !method.fields.contains(&key.as_str()) {
            return Err(RequestError {
                path: field_path(node, key),
                message: format!(
                    "not used by {name} (it reads: curve, method, {})",
                    method.fields.join(", ")
                ),
            });
        }
    }
    let curve_node = obj.req("curve")?;
    let curve = curve_node.u32_in(0, u32::MAX)? as usize;
    if curve >= scene.curves.len() {
        return Err(curve_node
            .invalid(format!(
                "curve {curve} does not exist (the scene has {} curve(s))",
                scene.curves.len()
            ))
            .into());
    }
    (method.read)(&Fields { node, obj, curve })
}

/// Applies a typed request to `scene`: one function per method.
fn run(scene: &mut Scene, node: &Node<'_>, request: &Request) -> Result<Report, RequestError> {
    let (curve, result) = match request {
        Request::SingleTarget(r) => (
            r.curve,
            MethodReport::SingleTarget(methods::run_single_target(scene, node, r)?),
        ),
        Request::TangentKept(r) => (
            r.curve,
            MethodReport::TangentKept(methods::run_tangent_kept(scene, node, r)?),
        ),
        Request::MultiTarget(r) => (
            r.curve,
            MethodReport::MultiTarget(methods::run_multi_target(scene, node, r)?),
        ),
        Request::CubicRegion(r) => (
            r.curve,
            MethodReport::CubicRegion(methods::run_cubic_region(scene, node, r)?),
        ),
        Request::NubmpConstrained(r) => (
            r.curve,
            MethodReport::NubmpConstrained(methods::run_nubmp_constrained(scene, node, r)?),
        ),
        Request::NubmpFindTau(r) => (
            r.curve,
            MethodReport::NubmpFindTau(methods::run_nubmp_find_tau(scene, node, r)?),
        ),
        Request::Project(r) => (
            r.curve,
            MethodReport::Project(methods::run_project(scene, node, r)?),
        ),
    };
    Ok(Report { curve, result })
}

/// The points a request aims at, marked in the scene.
fn targets_of(request: &Request) -> Vec<DVec3> {
    match request {
        Request::SingleTarget(r) => vec![r.target],
        Request::TangentKept(r) => vec![r.target],
        Request::MultiTarget(r) => r.targets.clone(),
        Request::CubicRegion(r) => r.target.into_iter().collect(),
        Request::NubmpConstrained(r) => vec![r.target],
        Request::NubmpFindTau(r) => vec![r.target],
        Request::Project(r) => vec![r.target],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each method has exactly one row, and the row's reader makes the request of that
    /// method (a row pointing at another method's reader would otherwise go unnoticed).
    #[test]
    fn every_method_has_one_row_whose_reader_makes_its_request() {
        for (i, m) in METHOD_TABLE.iter().enumerate() {
            assert!(
                METHOD_TABLE[..i].iter().all(|o| o.name != m.name),
                "{} has two rows",
                m.name
            );
            assert!(m.fields.contains(&"target") || m.fields.contains(&"targets"));
        }
        let scene = crate::format::Scene::load(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/solve_demo.json"),
        )
        .expect("the demo scene");
        // One request per method, on the demo scene's Bézier curves (0, 1) and NUBMP curve (2).
        let requests = [
            r#"{"curve": 1, "method": "single_target", "target": [9, 3.5]}"#,
            r#"{"curve": 0, "method": "tangent_kept", "target": [2, 2.2]}"#,
            r#"{"curve": 1, "method": "multi_target", "targets": [[7, 3], [9.5, 2.5]]}"#,
            r#"{"curve": 0, "method": "cubic_region", "target": [2, 3], "limited": true}"#,
            r#"{"curve": 2, "method": "nubmp_constrained", "tau": 0.4, "group": 5, "target": [16.45, 1.75]}"#,
            r#"{"curve": 2, "method": "nubmp_find_tau", "group": 5, "target": [16.45, 1.75]}"#,
            r#"{"curve": 2, "method": "project", "target": [17, 3]}"#,
        ];
        let mut seen = Vec::new();
        for text in requests {
            let value = parse_document(text).expect("JSON");
            let request =
                read(&scene, &Node::root(&value)).unwrap_or_else(|e| panic!("{text}: {e}"));
            assert_eq!(
                Some(request.method()),
                value["method"].as_str(),
                "the reader of {text}"
            );
            seen.push(request.method());
        }
        seen.sort_unstable();
        let mut all = METHODS.to_vec();
        all.sort_unstable();
        assert_eq!(seen, all, "one request per method");
    }
}
