//! `"interpolation"`: cubic Bézier interpolation, plain or modified (paper 002, §5).

use schemars::JsonSchema;
use serde::Serialize;

use super::{Codec, Written, geom_error};
use crate::format::SceneError;
use crate::format::point_doc::PointDoc;
use crate::jsonread::{Node, Obj};
use splinescope_core::geom::{CubicInterpolation, GeomError, Modification, Reading};

/// An interpolating spline's fields.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct InterpolationDoc {
    /// The points passed through.
    #[schemars(length(min = 2))]
    pub points: Vec<PointDoc>,
    /// Their strictly increasing parameters (default `0, 1, 2, …`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub params: Option<Vec<f64>>,
    /// The modification of paper 002, when there is one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub modification: Option<ModificationDoc>,
}

/// A modification: `t*`, `v` and the reading (docs/math.md §1).
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct ModificationDoc {
    /// `t*`, in the open interval (0, 1).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub t_star: f64,
    /// The vector `v`.
    pub v: PointDoc,
    /// `"paper"` (default) or `"bump_added"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reading: Option<ReadingDoc>,
}

/// How a modification is read.
#[derive(Debug, Clone, Copy, Serialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ReadingDoc {
    /// The paper's reading.
    Paper,
    /// The bump added to plain pieces.
    BumpAdded,
}

impl Codec for CubicInterpolation {
    const FIELDS: &'static [&'static str] = &["points", "params", "modification"];

    fn decode(node: &Node<'_>, obj: &Obj<'_>) -> Result<CubicInterpolation, SceneError> {
        let points = obj.req("points")?.points(2)?;
        let params = obj.get("params").map(|n| n.numbers()).transpose()?;
        let modification = obj
            .get("modification")
            .map(|n| decode_modification(&n))
            .transpose()?;
        CubicInterpolation::try_new(points, params, modification).map_err(|e| {
            let prefix = match e {
                GeomError::TStarOutside { .. }
                | GeomError::NonFiniteVector { .. }
                | GeomError::DerivedNotFinite {
                    field: "t_star" | "v",
                    ..
                } => "modification.",
                _ => "",
            };
            geom_error(node, prefix, &e)
        })
    }
}

impl Written for CubicInterpolation {
    type Doc = InterpolationDoc;

    fn encode(&self) -> InterpolationDoc {
        InterpolationDoc {
            points: PointDoc::all(self.points()),
            params: Some(self.params().to_vec()),
            modification: self.modification().map(|m| ModificationDoc {
                t_star: m.t_star,
                v: PointDoc::of(m.v),
                reading: Some(match m.reading {
                    Reading::Paper => ReadingDoc::Paper,
                    Reading::BumpAdded => ReadingDoc::BumpAdded,
                }),
            }),
        }
    }
}

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
