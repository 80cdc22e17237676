//! One reader and one solver call per method: each turns its request object into a typed
//! request, applies it to the scene and returns its typed report.

use glam::DVec3;

use super::error::{RequestError, at, field_path};
use super::types::{
    CubicRegionReport, CubicRegionRequest, MultiTargetReport, MultiTargetRequest, NubmpChange,
    NubmpConstrainedReport, NubmpConstrainedRequest, NubmpFindTauReport, NubmpFindTauRequest,
    ProjectReport, ProjectRequest, SingleTargetReport, SingleTargetRequest, TangentKeptReport,
    TangentKeptRequest,
};
use crate::format::{Annotation, AnnotationShape, Scene, SceneError, SceneErrorKind};
use crate::jsonread::{Node, Obj};
use splinescope_core::geom::cubic_region::PolygonType;
use splinescope_core::geom::family::xyz;
use splinescope_core::geom::{Bezier, Curve, Nubmp, Nurbs, ParamCurve, RationalBezier};
use splinescope_core::solve::rational::{self, RationalCurve};
use splinescope_core::solve::region::cubic_region;
use splinescope_core::solve::shape::{
    SingleTargetOptions, multi_target, single_target, tangent_kept,
};
use splinescope_core::solve::{SolveError, nearest, nubmp};
use splinescope_encoding::Color;

/// A request object being read: its node (for error paths) and its fields.
pub(super) struct Fields<'n, 'a> {
    pub node: &'n Node<'a>,
    pub obj: Obj<'a>,
    pub curve: usize,
}

impl Fields<'_, '_> {
    fn f64(&self, key: &str) -> Result<Option<f64>, RequestError> {
        Ok(self.obj.get(key).map(|n| n.f64()).transpose()?)
    }
    fn positive(&self, key: &str) -> Result<Option<f64>, RequestError> {
        Ok(self.obj.get(key).map(|n| n.positive_f64()).transpose()?)
    }
    fn bool(&self, key: &str) -> Result<Option<bool>, RequestError> {
        Ok(self.obj.get(key).map(|n| n.bool()).transpose()?)
    }
    fn index(&self, key: &str) -> Result<usize, RequestError> {
        Ok(self.obj.req(key)?.u32_in(0, u32::MAX)? as usize)
    }
    fn point(&self, key: &str) -> Result<DVec3, RequestError> {
        Ok(self.obj.req(key)?.point()?)
    }
    fn missing(&self, key: &str) -> RequestError {
        SceneError::new(field_path(self.node, key), SceneErrorKind::Missing).into()
    }
}

/// The curve paper 000's methods modify: a Bézier curve, or a rational curve (its weights
/// held fixed).
enum Modifiable<'s> {
    Polynomial(&'s Bezier),
    Rational(&'s RationalBezier),
    Nurbs(&'s Nurbs),
}

fn modifiable<'s>(
    scene: &'s Scene,
    index: usize,
    node: &Node<'_>,
    method: &str,
) -> Result<Modifiable<'s>, RequestError> {
    match &scene.curves[index].curve {
        Curve::Bezier(b) => Ok(Modifiable::Polynomial(b)),
        Curve::RationalBezier(b) => Ok(Modifiable::Rational(b)),
        Curve::Nurbs(b) => Ok(Modifiable::Nurbs(b)),
        other => Err(RequestError {
            path: field_path(node, "curve"),
            message: format!(
                "{method} modifies Bézier curves (paper 000) and rational Bézier and NURBS curves (weights fixed); curves[{index}] is {}",
                other.family()
            ),
        }),
    }
}

/// The field of a request a solver error concerns.
fn single_field(e: &SolveError) -> &'static str {
    match e {
        SolveError::WindowOutOfRange { .. } => "first",
        SolveError::ParameterAtEnd { .. }
        | SolveError::ParameterOutsideDomain { .. }
        | SolveError::NoInfluence { .. }
        | SolveError::MovesOverflow { .. }
        | SolveError::Missed { .. } => "t",
        SolveError::NonFiniteTarget { .. } | SolveError::TargetAtEnd { .. } => "target",
        _ => "",
    }
}

fn multi_field(e: &SolveError) -> String {
    match e {
        SolveError::ParamCount { .. } | SolveError::ParameterOutsideDomain { .. } => {
            "params".to_owned()
        }
        SolveError::ParameterAtEnd { index, .. }
        | SolveError::NoInfluence { index, .. }
        | SolveError::MovesOverflow { index, .. }
        | SolveError::Missed { index, .. } => format!("params[{index}]"),
        SolveError::NonFiniteTarget { index, .. } | SolveError::TargetAtEnd { index, .. } => {
            format!("targets[{index}]")
        }
        _ => String::new(),
    }
}

/// A rational single-target solve and its report; the scene's curve replaced.
fn rational_single<C: RationalCurve + Into<Curve>>(
    scene: &mut Scene,
    node: &Node<'_>,
    r: &SingleTargetRequest,
    c: &C,
) -> Result<SingleTargetReport, RequestError> {
    let s = rational::single_target(c, r.target, r.t, r.first.zip(r.count), r.accuracy)
        .map_err(|e| at(node, single_field(&e), &e))?;
    let t = s.params[0];
    let report = SingleTargetReport {
        target: r.target.to_array(),
        t,
        start: c.eval(t).to_array(),
        moved: s.moved.clone(),
        deltas: xyz(&s.deltas),
        control_points: xyz(s.curve.points()),
        residual: s.residuals[0],
    };
    scene.curves[r.curve].curve = s.curve.into();
    Ok(report)
}

fn rational_tangent<C: RationalCurve + Into<Curve>>(
    scene: &mut Scene,
    node: &Node<'_>,
    r: &TangentKeptRequest,
    c: &C,
) -> Result<TangentKeptReport, RequestError> {
    let s = rational::tangent_kept(c, r.target, r.t, r.accuracy)
        .map_err(|e| at(node, tangent_field(&e), &e))?;
    let report = TangentKeptReport {
        target: r.target.to_array(),
        t: s.solution.params[0],
        mu: s.mu,
        directions: s.directions.map(|d| d.to_array()),
        deltas: xyz(&s.solution.deltas),
        control_points: xyz(s.solution.curve.points()),
        residual: s.solution.residuals[0],
        least_squares: s.solution.least_squares,
    };
    scene.curves[r.curve].curve = s.solution.curve.into();
    Ok(report)
}

fn rational_multi<C: RationalCurve + Into<Curve>>(
    scene: &mut Scene,
    node: &Node<'_>,
    r: &MultiTargetRequest,
    c: &C,
) -> Result<MultiTargetReport, RequestError> {
    let s = rational::multi_target(c, &r.targets, r.params.as_deref(), r.accuracy)
        .map_err(|e| at(node, &multi_field(&e), &e))?;
    let report = MultiTargetReport {
        targets: xyz(&r.targets),
        params: s.params.clone(),
        deltas: xyz(&s.deltas),
        residuals: s.residuals.clone(),
        max_residual: s.residuals.iter().copied().fold(0.0, f64::max),
        rank: s.rank,
        least_squares: s.least_squares,
        control_points: xyz(s.curve.points()),
    };
    scene.curves[r.curve].curve = s.curve.into();
    Ok(report)
}

fn tangent_field(e: &SolveError) -> &'static str {
    match e {
        SolveError::ParameterAtEnd { .. }
        | SolveError::ParameterOutsideDomain { .. }
        | SolveError::NoInfluence { .. }
        | SolveError::MovesOverflow { .. }
        | SolveError::Missed { .. } => "t",
        SolveError::NonFiniteTarget { .. } | SolveError::TargetAtEnd { .. } => "target",
        _ => "curve",
    }
}

fn nubmp_of(
    scene: &Scene,
    index: usize,
    node: &Node<'_>,
    method: &str,
) -> Result<Nubmp, RequestError> {
    match &scene.curves[index].curve {
        Curve::Nubmp(n) => Ok(n.clone()),
        other => Err(RequestError {
            path: field_path(node, "curve"),
            message: format!(
                "{method} modifies NUBMP curves (paper 001); curves[{index}] is {}",
                other.family()
            ),
        }),
    }
}

pub(super) fn read_single_target(f: &Fields<'_, '_>) -> Result<SingleTargetRequest, RequestError> {
    let (first, count) = match (f.obj.get("first"), f.obj.get("count")) {
        (None, None) => (None, None),
        (Some(a), Some(b)) => (
            Some(a.u32_in(0, u32::MAX)? as usize),
            Some(b.u32_in(0, u32::MAX)? as usize),
        ),
        (Some(_), None) => return Err(f.missing("count")),
        (None, Some(_)) => return Err(f.missing("first")),
    };
    Ok(SingleTargetRequest {
        curve: f.curve,
        target: f.point("target")?,
        t: f.f64("t")?,
        first,
        count,
        accuracy: f.positive("accuracy")?,
    })
}

/// Paper 000 §2.1.
pub(super) fn run_single_target(
    scene: &mut Scene,
    node: &Node<'_>,
    r: &SingleTargetRequest,
) -> Result<SingleTargetReport, RequestError> {
    let b = match modifiable(scene, r.curve, node, "single_target")? {
        Modifiable::Polynomial(b) => b,
        Modifiable::Rational(c) => return rational_single(scene, node, r, &c.clone()),
        Modifiable::Nurbs(c) => return rational_single(scene, node, r, &c.clone()),
    };
    let opts = SingleTargetOptions {
        t_s: r.t,
        window: r.first.zip(r.count),
        accuracy: r.accuracy,
    };
    let s = single_target(b, r.target, &opts).map_err(|e| at(node, single_field(&e), &e))?;
    let report = SingleTargetReport {
        target: r.target.to_array(),
        t: s.t_s,
        start: s.start.to_array(),
        moved: (s.first..s.first + s.deltas.len()).collect(),
        deltas: xyz(&s.deltas),
        control_points: xyz(s.curve.points()),
        residual: s.residual,
    };
    scene.curves[r.curve].curve = Curve::Bezier(s.curve);
    Ok(report)
}

pub(super) fn read_tangent_kept(f: &Fields<'_, '_>) -> Result<TangentKeptRequest, RequestError> {
    Ok(TangentKeptRequest {
        curve: f.curve,
        target: f.point("target")?,
        t: f.f64("t")?,
        accuracy: f.positive("accuracy")?,
    })
}

/// Paper 000 §2.2.
pub(super) fn run_tangent_kept(
    scene: &mut Scene,
    node: &Node<'_>,
    r: &TangentKeptRequest,
) -> Result<TangentKeptReport, RequestError> {
    let b = match modifiable(scene, r.curve, node, "tangent_kept")? {
        Modifiable::Polynomial(b) => b,
        Modifiable::Rational(c) => return rational_tangent(scene, node, r, &c.clone()),
        Modifiable::Nurbs(c) => return rational_tangent(scene, node, r, &c.clone()),
    };
    let s =
        tangent_kept(b, r.target, r.t, r.accuracy).map_err(|e| at(node, tangent_field(&e), &e))?;
    let report = TangentKeptReport {
        target: r.target.to_array(),
        t: s.t_s,
        mu: s.mu,
        directions: s.directions.map(|d| d.to_array()),
        deltas: xyz(&s.deltas),
        control_points: xyz(s.curve.points()),
        residual: s.residual,
        least_squares: s.least_squares,
    };
    scene.curves[r.curve].curve = Curve::Bezier(s.curve);
    Ok(report)
}

pub(super) fn read_multi_target(f: &Fields<'_, '_>) -> Result<MultiTargetRequest, RequestError> {
    Ok(MultiTargetRequest {
        curve: f.curve,
        targets: f.obj.req("targets")?.points(1)?,
        params: f.obj.get("params").map(|n| n.numbers()).transpose()?,
        accuracy: f.positive("accuracy")?,
    })
}

/// Paper 000 §3.
pub(super) fn run_multi_target(
    scene: &mut Scene,
    node: &Node<'_>,
    r: &MultiTargetRequest,
) -> Result<MultiTargetReport, RequestError> {
    let b = match modifiable(scene, r.curve, node, "multi_target")? {
        Modifiable::Polynomial(b) => b,
        Modifiable::Rational(c) => return rational_multi(scene, node, r, &c.clone()),
        Modifiable::Nurbs(c) => return rational_multi(scene, node, r, &c.clone()),
    };
    let s = multi_target(b, &r.targets, r.params.as_deref(), r.accuracy)
        .map_err(|e| at(node, &multi_field(&e), &e))?;
    let report = MultiTargetReport {
        targets: xyz(&r.targets),
        params: s.params.clone(),
        deltas: xyz(&s.deltas),
        residuals: s.residuals.clone(),
        max_residual: s.residuals.iter().copied().fold(0.0, f64::max),
        rank: s.rank,
        least_squares: s.least_squares,
        control_points: xyz(s.curve.points()),
    };
    scene.curves[r.curve].curve = Curve::Bezier(s.curve);
    Ok(report)
}

pub(super) fn read_cubic_region(f: &Fields<'_, '_>) -> Result<CubicRegionRequest, RequestError> {
    Ok(CubicRegionRequest {
        curve: f.curve,
        target: f.obj.get("target").map(|n| n.point()).transpose()?,
        limited: f.bool("limited")?,
        reach: f.positive("reach")?,
    })
}

/// Paper 000 §2.3: the outline goes into the scene as annotations, for drawing.
pub(super) fn run_cubic_region(
    scene: &mut Scene,
    node: &Node<'_>,
    r: &CubicRegionRequest,
) -> Result<CubicRegionReport, RequestError> {
    let b = match &scene.curves[r.curve].curve {
        Curve::Bezier(b) => b.clone(),
        other => {
            return Err(RequestError {
                path: field_path(node, "curve"),
                message: format!(
                    "cubic_region classifies Bézier cubics (paper 000); curves[{}] is {}",
                    r.curve,
                    other.family()
                ),
            });
        }
    };
    let region = cubic_region(&b).map_err(|e| at(node, "curve", &e))?;
    let limited = r.limited.unwrap_or(false);
    let reach = r
        .reach
        .unwrap_or_else(|| 3.0 * b.control_box().diagonal().max(1e-9));
    let boundary = region.boundary(limited, reach);
    for line in &boundary {
        scene.annotations.push(Annotation {
            shape: AnnotationShape::Polyline(line.clone()),
            color: Color::from_rgba8([115, 115, 115, 230]),
            width: 1.5,
            label: Some(format!("allowed region of curves[{}]", r.curve)),
        });
    }
    Ok(CubicRegionReport {
        target: r.target.map(|t| t.to_array()),
        kind: region.kind.number(),
        apex: match region.kind {
            PolygonType::Converging { apex } => Some(apex.to_array()),
            _ => None,
        },
        directions: [region.e1.to_array(), region.e2.to_array()],
        reachable: r.target.map(|t| region.contains(t)),
        reachable_limited: r.target.map(|t| region.contains_limited(t)),
        limited,
        boundary: boundary.iter().map(|l| xyz(l)).collect(),
    })
}

pub(super) fn read_nubmp_constrained(
    f: &Fields<'_, '_>,
) -> Result<NubmpConstrainedRequest, RequestError> {
    Ok(NubmpConstrainedRequest {
        curve: f.curve,
        tau: f.obj.req("tau")?.f64()?,
        group: f.index("group")?,
        target: f.point("target")?,
        respect_vd: f.bool("respect_vd")?,
    })
}

fn nubmp_field(e: &SolveError) -> &'static str {
    match e {
        SolveError::ParameterOutsideDomain { .. } => "tau",
        SolveError::GroupInactive { .. } | SolveError::Geom(_) | SolveError::NoTau { .. } => {
            "group"
        }
        _ => "target",
    }
}

/// Moves `P(τ)` to `q` through group `j` and records the change in the scene.
fn nubmp_change(
    scene: &mut Scene,
    node: &Node<'_>,
    index: usize,
    nub: &Nubmp,
    (tau, group, q): (f64, usize, DVec3),
    respect_vd: bool,
) -> Result<NubmpChange, RequestError> {
    let s = nubmp::constrained(nub, tau, group, q, respect_vd)
        .map_err(|e| at(node, nubmp_field(&e), &e))?;
    let change = NubmpChange {
        tau,
        group,
        members: s.curve.groups()[group].members.clone(),
        values: s.values.clone(),
        region: xyz(&s.region),
        dual_points: xyz(s.curve.dual_points()),
        residual: s.residual,
    };
    scene.curves[index].curve = Curve::Nubmp(s.curve);
    Ok(change)
}

/// Paper 001 §5.2.
pub(super) fn run_nubmp_constrained(
    scene: &mut Scene,
    node: &Node<'_>,
    r: &NubmpConstrainedRequest,
) -> Result<NubmpConstrainedReport, RequestError> {
    let nub = nubmp_of(scene, r.curve, node, "nubmp_constrained")?;
    let change = nubmp_change(
        scene,
        node,
        r.curve,
        &nub,
        (r.tau, r.group, r.target),
        r.respect_vd.unwrap_or(false),
    )?;
    Ok(NubmpConstrainedReport {
        target: r.target.to_array(),
        change,
    })
}

pub(super) fn read_nubmp_find_tau(f: &Fields<'_, '_>) -> Result<NubmpFindTauRequest, RequestError> {
    Ok(NubmpFindTauRequest {
        curve: f.curve,
        group: f.index("group")?,
        target: f.point("target")?,
        apply: f.bool("apply")?,
        respect_vd: f.bool("respect_vd")?,
    })
}

/// Paper 001 §5.2, the alternative scenario.
pub(super) fn run_nubmp_find_tau(
    scene: &mut Scene,
    node: &Node<'_>,
    r: &NubmpFindTauRequest,
) -> Result<NubmpFindTauReport, RequestError> {
    let nub = nubmp_of(scene, r.curve, node, "nubmp_find_tau")?;
    let found =
        nubmp::find_tau(&nub, r.group, r.target).map_err(|e| at(node, nubmp_field(&e), &e))?;
    let applied = if r.apply.unwrap_or(false) {
        Some(nubmp_change(
            scene,
            node,
            r.curve,
            &nub,
            (found.best, r.group, r.target),
            r.respect_vd.unwrap_or(false),
        )?)
    } else {
        None
    };
    Ok(NubmpFindTauReport {
        target: r.target.to_array(),
        intervals: found.intervals.iter().map(|&(a, b)| [a, b]).collect(),
        best: found.best,
        applied,
    })
}

pub(super) fn read_project(f: &Fields<'_, '_>) -> Result<ProjectRequest, RequestError> {
    Ok(ProjectRequest {
        curve: f.curve,
        target: f.point("target")?,
        accuracy: f.positive("accuracy")?,
    })
}

/// The closest point of any curve.
pub(super) fn run_project(
    scene: &Scene,
    node: &Node<'_>,
    r: &ProjectRequest,
) -> Result<ProjectReport, RequestError> {
    let q = r.target;
    if let Some(value) = q.to_array().into_iter().find(|c| !c.is_finite()) {
        return Err(at(
            node,
            "target",
            &SolveError::NonFiniteTarget { index: 0, value },
        ));
    }
    let curve = &scene.curves[r.curve].curve;
    let n = nearest(curve, q, r.accuracy);
    Ok(ProjectReport {
        target: q.to_array(),
        t: n.t,
        point: n.point.to_array(),
        distance: n.distance,
        tangent: curve.eval_deriv(n.t).to_array(),
    })
}
