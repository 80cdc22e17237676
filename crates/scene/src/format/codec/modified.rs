//! `"modified_bezier"`: `R(t) = Q(t) + S(t) v` (paper 002, §4).

use schemars::JsonSchema;
use serde::Serialize;

use super::bezier::bezier_points;
use super::{Codec, Written, geom_error};
use crate::format::SceneError;
use crate::format::point_doc::PointDoc;
use crate::jsonread::{Node, Obj};
use splinescope_core::geom::{Bezier, ModifiedBezier};

/// A modified Bézier curve's fields.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct ModifiedBezierDoc {
    /// The control points of `Q`.
    #[schemars(length(min = 2))]
    pub points: Vec<PointDoc>,
    /// `t*`, in the open interval (0, 1).
    #[schemars(range(min = 0.0, max = 1.0))]
    pub t_star: f64,
    /// The vector `v`.
    pub v: PointDoc,
}

impl Codec for ModifiedBezier {
    const FIELDS: &'static [&'static str] = &["points", "t_star", "v"];

    fn decode(node: &Node<'_>, obj: &Obj<'_>) -> Result<ModifiedBezier, SceneError> {
        let points = bezier_points(obj)?;
        let t_star = obj.req("t_star")?.f64()?;
        let v = obj.req("v")?.point()?;
        let base = Bezier::try_new(points).map_err(|e| geom_error(node, "", &e))?;
        ModifiedBezier::try_new(base, t_star, v).map_err(|e| geom_error(node, "", &e))
    }
}

impl Written for ModifiedBezier {
    type Doc = ModifiedBezierDoc;

    fn encode(&self) -> ModifiedBezierDoc {
        ModifiedBezierDoc {
            points: PointDoc::all(self.base().points()),
            t_star: self.t_star(),
            v: PointDoc::of(self.v()),
        }
    }
}
