//! `"path"`: Bézier segments of any degree (each may be rational) joined end to end, open
//! or closed.

use schemars::JsonSchema;
use serde::Serialize;

use super::{Codec, Written, geom_error};
use crate::format::SceneError;
use crate::format::point_doc::PointDoc;
use crate::jsonread::{Node, Obj};
use splinescope_core::geom::{Path, PathSegment};

/// A path's fields.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct PathDoc {
    /// The segments in order; each starts where the one before ends (segment `k` covers
    /// the parameters `[k, k + 1]`).
    #[schemars(length(min = 1))]
    pub segments: Vec<PathSegmentDoc>,
    /// Whether the last segment ends where the first starts (default `false`).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub closed: bool,
}

/// One segment of a path.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct PathSegmentDoc {
    /// The control points `P_0 … P_n` (degree `n` = count − 1).
    #[schemars(length(min = 2))]
    pub points: Vec<PointDoc>,
    /// For a rational segment, one weight per point, each a finite number greater than 0.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub weights: Option<Vec<f64>>,
}

/// One segment object, its degree checked against [`splinescope_io::limits::DEGREE`].
fn segment(node: &Node<'_>) -> Result<PathSegment, SceneError> {
    let obj = node.object(&["points", "weights"])?;
    let points_node = obj.req("points")?;
    let points = points_node.points(2)?;
    splinescope_io::limits::DEGREE
        .check(points.len() as u64 - 1)
        .map_err(|e| points_node.invalid(e.to_string()))?;
    let weights = match obj.get("weights") {
        None => None,
        Some(w) => Some(w.numbers()?),
    };
    Ok(PathSegment {
        points: points.into(),
        weights,
    })
}

impl Codec for Path {
    const FIELDS: &'static [&'static str] = &["segments", "closed"];

    fn decode(node: &Node<'_>, obj: &Obj<'_>) -> Result<Path, SceneError> {
        let list = obj.req("segments")?;
        let items = list.array()?;
        if items.is_empty() {
            return Err(list.invalid("needs at least 1 segment, found 0"));
        }
        // Every segment has a point of its own besides the one it shares.
        splinescope_io::limits::POINTS
            .check(items.len() as u64)
            .map_err(|e| list.invalid(e.to_string()))?;
        let segments = items.iter().map(segment).collect::<Result<Vec<_>, _>>()?;
        let total: usize = segments.iter().map(|s| s.points.len()).sum();
        splinescope_io::limits::POINTS
            .check(total as u64)
            .map_err(|e| list.invalid(e.to_string()))?;
        let closed = match obj.get("closed") {
            None => false,
            Some(c) => c.bool()?,
        };
        Path::try_new(segments, closed).map_err(|e| geom_error(node, "", &e))
    }
}

impl Written for Path {
    type Doc = PathDoc;

    fn encode(&self) -> PathDoc {
        PathDoc {
            segments: self
                .segments()
                .iter()
                .map(|s| PathSegmentDoc {
                    points: PointDoc::all(&s.points),
                    weights: s.weights.clone(),
                })
                .collect(),
            closed: self.is_closed(),
        }
    }
}
