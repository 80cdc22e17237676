//! `"bezier"`: a Bézier curve of any degree.

use schemars::JsonSchema;
use serde::Serialize;

use super::{Codec, Written, geom_error};
use crate::format::SceneError;
use crate::format::point_doc::PointDoc;
use crate::jsonread::{Node, Obj};
use splinescope_core::geom::{Bezier, Family};

/// A Bézier curve's fields.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct BezierDoc {
    /// The control points `P_0 … P_n` (degree `n` = count − 1).
    #[schemars(length(min = 2))]
    pub points: Vec<PointDoc>,
}

impl Codec for Bezier {
    const FIELDS: &'static [&'static str] = &["points"];

    fn decode(node: &Node<'_>, obj: &Obj<'_>) -> Result<Bezier, SceneError> {
        let points = bezier_points(obj)?;
        Bezier::try_new(points).map_err(|e| geom_error(node, "", &e))
    }
}

impl Written for Bezier {
    type Doc = BezierDoc;

    fn encode(&self) -> BezierDoc {
        BezierDoc {
            points: PointDoc::all(self.control_points()),
        }
    }
}

/// A Bézier curve's points, its degree checked against [`splinescope_io::limits::DEGREE`].
pub(super) fn bezier_points(obj: &Obj<'_>) -> Result<Vec<glam::DVec3>, SceneError> {
    let node = obj.req("points")?;
    let points = node.points(2)?;
    splinescope_io::limits::DEGREE
        .check(points.len() as u64 - 1)
        .map_err(|e| node.invalid(e.to_string()))?;
    Ok(points)
}
