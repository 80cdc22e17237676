//! Solve requests and their reports as Rust types. Requests are read by hand (to name the
//! path of the first offending value) into these types; reports are written from them
//! through `Serialize`. `docs/schemas/request.schema.json` and
//! `docs/schemas/report.schema.json` are generated from them.

use glam::DVec3;
use schemars::JsonSchema;
use serde::Serialize;

use crate::format::point_doc::PointDoc;
use splinescope_core::geom::family::Xyz;

/// A request document: one request, or an array applied in order.
#[derive(Debug, Clone, JsonSchema)]
#[schemars(title = "splinescope solve request")]
#[serde(untagged)]
pub enum RequestDocument {
    /// One request.
    One(Request),
    /// Several, applied in order (each sees the previous one's result).
    Many(Vec<Request>),
}

/// One request: a method and its inputs (`docs/solve-format.md`).
#[derive(Debug, Clone, JsonSchema)]
#[serde(tag = "method", rename_all = "snake_case")]
pub enum Request {
    /// Paper 000 §2.1.
    SingleTarget(SingleTargetRequest),
    /// Paper 000 §2.2.
    TangentKept(TangentKeptRequest),
    /// Paper 000 §3.
    MultiTarget(MultiTargetRequest),
    /// Paper 000 §2.3.
    CubicRegion(CubicRegionRequest),
    /// Paper 001 §5.2.
    NubmpConstrained(NubmpConstrainedRequest),
    /// Paper 001 §5.2, the alternative scenario.
    NubmpFindTau(NubmpFindTauRequest),
    /// The closest point of any curve.
    Project(ProjectRequest),
}

impl Request {
    /// The method's name as written in requests and reports.
    #[must_use]
    pub fn method(&self) -> &'static str {
        match self {
            Request::SingleTarget(_) => "single_target",
            Request::TangentKept(_) => "tangent_kept",
            Request::MultiTarget(_) => "multi_target",
            Request::CubicRegion(_) => "cubic_region",
            Request::NubmpConstrained(_) => "nubmp_constrained",
            Request::NubmpFindTau(_) => "nubmp_find_tau",
            Request::Project(_) => "project",
        }
    }
}

/// `single_target`: move `P_l..P_{l+m−1}` so the curve passes through `target`.
#[derive(Debug, Clone, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct SingleTargetRequest {
    /// The curve's index in the scene.
    pub curve: usize,
    /// `T`.
    #[schemars(with = "PointDoc")]
    pub target: DVec3,
    /// `t_s ∈ (0, 1)` (default: `T` projected onto the curve).
    pub t: Option<f64>,
    /// `l` (with `count`).
    pub first: Option<usize>,
    /// `m` (with `first`).
    pub count: Option<usize>,
    /// Projection accuracy (> 0).
    pub accuracy: Option<f64>,
}

/// `tangent_kept`: keep the end points and tangent lines.
#[derive(Debug, Clone, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct TangentKeptRequest {
    /// The curve's index in the scene.
    pub curve: usize,
    /// `T`.
    #[schemars(with = "PointDoc")]
    pub target: DVec3,
    /// `t_s ∈ (0, 1)`.
    pub t: Option<f64>,
    /// Projection accuracy (> 0).
    pub accuracy: Option<f64>,
}

/// `multi_target`: pass through every target.
#[derive(Debug, Clone, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct MultiTargetRequest {
    /// The curve's index in the scene.
    pub curve: usize,
    /// `T_0, T_1, …`.
    #[schemars(with = "Vec<PointDoc>", length(min = 1))]
    pub targets: Vec<DVec3>,
    /// One parameter per target, in `(0, 1)`.
    pub params: Option<Vec<f64>>,
    /// Projection accuracy (> 0).
    pub accuracy: Option<f64>,
}

/// `cubic_region`: classify a cubic's polygon and outline what it can reach.
#[derive(Debug, Clone, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct CubicRegionRequest {
    /// The curve's index in the scene.
    pub curve: usize,
    /// A point to test.
    #[schemars(with = "Option<PointDoc>")]
    pub target: Option<DVec3>,
    /// Outline the limited type-2 region (default false).
    pub limited: Option<bool>,
    /// How far the unbounded region is drawn (> 0).
    pub reach: Option<f64>,
}

/// `nubmp_constrained`: move `P(τ)` by changing one group.
#[derive(Debug, Clone, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct NubmpConstrainedRequest {
    /// The curve's index in the scene.
    pub curve: usize,
    /// `τ` in the curve's domain.
    pub tau: f64,
    /// The group `j`.
    pub group: usize,
    /// `q`.
    #[schemars(with = "PointDoc")]
    pub target: DVec3,
    /// (Order 4) refuse parameters that break a Theorem 1 condition.
    pub respect_vd: Option<bool>,
}

/// `nubmp_find_tau`: find where a group can move the curve to `target`.
#[derive(Debug, Clone, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct NubmpFindTauRequest {
    /// The curve's index in the scene.
    pub curve: usize,
    /// The group `j`.
    pub group: usize,
    /// `q`.
    #[schemars(with = "PointDoc")]
    pub target: DVec3,
    /// Then solve at the best `τ`.
    pub apply: Option<bool>,
    /// (Order 4, with `apply`) respect Theorem 1.
    pub respect_vd: Option<bool>,
}

/// `project`: the closest point of the curve.
#[derive(Debug, Clone, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct ProjectRequest {
    /// The curve's index in the scene.
    pub curve: usize,
    /// The point projected.
    #[schemars(with = "PointDoc")]
    pub target: DVec3,
    /// Accuracy (> 0).
    pub accuracy: Option<f64>,
}

/// What `splinescope solve` prints: one report per request.
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[schemars(title = "splinescope solve report")]
pub struct SolveOutput {
    /// In request order.
    pub reports: Vec<Report>,
}

/// The report of one request.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct Report {
    /// The curve's index.
    pub curve: usize,
    /// The method and what it found.
    #[serde(flatten)]
    pub result: MethodReport,
}

/// What each method reports.
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[serde(tag = "method", rename_all = "snake_case")]
pub enum MethodReport {
    /// `single_target`.
    SingleTarget(SingleTargetReport),
    /// `tangent_kept`.
    TangentKept(TangentKeptReport),
    /// `multi_target`.
    MultiTarget(MultiTargetReport),
    /// `cubic_region`.
    CubicRegion(CubicRegionReport),
    /// `nubmp_constrained`.
    NubmpConstrained(NubmpConstrainedReport),
    /// `nubmp_find_tau`.
    NubmpFindTau(NubmpFindTauReport),
    /// `project`.
    Project(ProjectReport),
}

/// `single_target`'s report.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct SingleTargetReport {
    /// `T`.
    pub target: Xyz,
    /// `t_s`.
    pub t: f64,
    /// `S = P(t_s)`.
    pub start: Xyz,
    /// The indices of the moved control points.
    pub moved: Vec<usize>,
    /// Their displacements `ε_i`.
    pub deltas: Vec<Xyz>,
    /// The new control points.
    pub control_points: Vec<Xyz>,
    /// `|P̃(t_s) − T|`.
    pub residual: f64,
}

/// `tangent_kept`'s report.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct TangentKeptReport {
    /// `T`.
    pub target: Xyz,
    /// `t_s`.
    pub t: f64,
    /// `μ_1, μ_2`.
    pub mu: [f64; 2],
    /// `e_1, e_2`.
    pub directions: [Xyz; 2],
    /// `ε_2..ε_{n−2}`.
    pub deltas: Vec<Xyz>,
    /// The new control points.
    pub control_points: Vec<Xyz>,
    /// `|P̃(t_s) − T|`.
    pub residual: f64,
    /// Whether the system was solved in least squares.
    pub least_squares: bool,
}

/// `multi_target`'s report.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct MultiTargetReport {
    /// `T_k`.
    pub targets: Vec<Xyz>,
    /// Their parameters.
    pub params: Vec<f64>,
    /// `ε_1..ε_{n−1}`.
    pub deltas: Vec<Xyz>,
    /// `|P̃(t_k) − T_k|`.
    pub residuals: Vec<f64>,
    /// The largest residual.
    pub max_residual: f64,
    /// The rank of the system.
    pub rank: usize,
    /// Whether it was solved in least squares.
    pub least_squares: bool,
    /// The new control points.
    pub control_points: Vec<Xyz>,
}

/// `cubic_region`'s report.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct CubicRegionReport {
    /// The point tested, if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target: Option<Xyz>,
    /// 1, 2 or 3.
    #[serde(rename = "type")]
    pub kind: u8,
    /// Type 2: where the legs' lines meet.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub apex: Option<Xyz>,
    /// `e_1, e_2`.
    pub directions: [Xyz; 2],
    /// With a target: whether it is reachable.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reachable: Option<bool>,
    /// With a target: whether the limited type-2 region holds it (`null` when not type 2).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reachable_limited: Option<Option<bool>>,
    /// Whether the limited region was outlined.
    pub limited: bool,
    /// The outline's polylines.
    pub boundary: Vec<Vec<Xyz>>,
}

/// The change a NUBMP solve made.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct NubmpChange {
    /// `τ`.
    pub tau: f64,
    /// The group `j`.
    pub group: usize,
    /// Its members.
    pub members: Vec<usize>,
    /// Its new parameters (on the simplex).
    pub values: Vec<f64>,
    /// The vertices `P(τ)` could reach.
    pub region: Vec<Xyz>,
    /// The new dual points.
    pub dual_points: Vec<Xyz>,
    /// `|P̃(τ) − q|`.
    pub residual: f64,
}

/// `nubmp_constrained`'s report.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct NubmpConstrainedReport {
    /// `q`.
    pub target: Xyz,
    /// The change.
    #[serde(flatten)]
    pub change: NubmpChange,
}

/// `nubmp_find_tau`'s report.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct NubmpFindTauReport {
    /// `q`.
    pub target: Xyz,
    /// The `τ` intervals where the group reaches `q`.
    pub intervals: Vec<[f64; 2]>,
    /// The middle of the longest.
    pub best: f64,
    /// With `apply`: the change made at `best`.
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub applied: Option<NubmpChange>,
}

/// `project`'s report.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct ProjectReport {
    /// The point projected.
    pub target: Xyz,
    /// The closest parameter.
    pub t: f64,
    /// `P(t)`.
    pub point: Xyz,
    /// The distance.
    pub distance: f64,
    /// `P′(t)`.
    pub tangent: Xyz,
}
