//! The JSON that `splinescope eval` and `splinescope check --json` print, as Rust types
//! (their JSON Schemas are generated from them into `docs/schemas/`).

use schemars::JsonSchema;
use serde::Serialize;

use splinescope_core::geom::family::Xyz;
use splinescope_core::geom::{Lower, ParamCurve};
use splinescope_scene::format::Scene;

/// What `eval` prints: `{"curves": [...]}` (streamed curve by curve).
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[schemars(title = "splinescope eval output")]
pub struct EvalOutput {
    /// One entry per evaluated curve.
    pub curves: Vec<EvalCurve>,
}

/// One curve's values at the requested parameters.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct EvalCurve {
    /// The curve's index in the scene.
    pub index: usize,
    /// `P(t)` at each parameter.
    pub samples: Vec<Xyz>,
    /// `P′(t)`, with `--derivatives 1` or 2.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub d1: Option<Vec<Xyz>>,
    /// `P″(t)`, with `--derivatives 2`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub d2: Option<Vec<Xyz>>,
    /// `κ = |P′ × P″| / |P′|³` with `--derivatives 2`; `null` where `P′ = 0`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub curvature: Option<Vec<Option<f64>>>,
}

/// What `check --json` prints.
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[schemars(title = "splinescope check output")]
pub struct CheckOutput {
    /// The file checked.
    pub file: String,
    /// The scene's name.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The unit of length of its coordinates, when the file names one (STEP).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unit: Option<String>,
    /// Each curve's structure.
    pub curves: Vec<CheckCurve>,
    /// Why the scene cannot be drawn on the GPU (empty: it can).
    pub gpu_problems: Vec<String>,
}

/// One curve as `check` describes it.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct CheckCurve {
    /// Its index.
    pub index: usize,
    /// Its family.
    pub family: &'static str,
    /// Its name.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The parameter domain.
    pub domain: [f64; 2],
    /// How many Bézier segments it lowers to.
    pub segments: usize,
    /// Their highest degree.
    pub max_degree: usize,
}

impl CheckOutput {
    /// The description of a loaded scene (`file` as given on the command line).
    #[must_use]
    pub fn of(file: &str, scene: &Scene) -> CheckOutput {
        let mut gpu_problems = Vec::new();
        let curves = scene
            .curves
            .iter()
            .enumerate()
            .map(|(index, c)| {
                let segments = c.curve.lower();
                if let Err(e) = splinescope_gpu::pack::check_gpu_fit(index, &segments) {
                    gpu_problems.push(e.to_string());
                }
                let (a, b) = c.curve.domain();
                CheckCurve {
                    index,
                    family: c.curve.family(),
                    name: c.name.clone(),
                    domain: [a, b],
                    segments: segments.len(),
                    max_degree: splinescope_core::geom::max_degree(&segments),
                }
            })
            .collect();
        if let Err(e) = splinescope_gpu::pack::check_annotations(
            &splinescope_scene::format::encoding::annotation_points(scene),
        ) {
            gpu_problems.push(e.to_string());
        }
        CheckOutput {
            unit: scene.unit.clone(),
            file: file.to_owned(),
            name: scene.name.clone(),
            curves,
            gpu_problems,
        }
    }
}
