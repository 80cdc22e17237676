//! `"rational_bezier"` and `"nurbs"`: rational curves, their control points with one
//! weight each.

use schemars::JsonSchema;
use serde::Serialize;

use super::bezier::bezier_points;
use super::bspline::{KnotsDoc, decode_spline_parts};
use super::{Codec, Written, geom_error};
use crate::format::SceneError;
use crate::format::point_doc::PointDoc;
use crate::jsonread::{Node, Obj};
use splinescope_core::geom::{Family, Nurbs, RationalBezier};

/// A rational Bézier curve's fields.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct RationalBezierDoc {
    /// The control points `P_0 … P_n` (degree `n` = count − 1).
    #[schemars(length(min = 2))]
    pub points: Vec<PointDoc>,
    /// The weights `w_0 … w_n`, one per point, each a finite number greater than 0.
    #[schemars(length(min = 2))]
    pub weights: Vec<f64>,
}

/// A NURBS curve's fields.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct NurbsDoc {
    /// The control points `P_0 … P_{n−1}`.
    #[schemars(length(min = 2))]
    pub points: Vec<PointDoc>,
    /// The weights, one per point, each a finite number greater than 0.
    #[schemars(length(min = 2))]
    pub weights: Vec<f64>,
    /// The knot vector (`n + k` non-decreasing numbers) or `"clamped_uniform"`.
    pub knots: KnotsDoc,
    /// The order `k` (degree `k − 1`), at least 2.
    #[schemars(range(min = 2))]
    pub order: usize,
}

/// The `weights` array, each entry a number (its path names the entry otherwise).
fn weights(obj: &Obj<'_>) -> Result<Vec<f64>, SceneError> {
    obj.req("weights")?.array()?.iter().map(Node::f64).collect()
}

impl Codec for RationalBezier {
    const FIELDS: &'static [&'static str] = &["points", "weights"];

    fn decode(node: &Node<'_>, obj: &Obj<'_>) -> Result<RationalBezier, SceneError> {
        let points = bezier_points(obj)?;
        RationalBezier::try_new(points, weights(obj)?).map_err(|e| geom_error(node, "", &e))
    }
}

impl Written for RationalBezier {
    type Doc = RationalBezierDoc;

    fn encode(&self) -> RationalBezierDoc {
        RationalBezierDoc {
            points: PointDoc::all(self.control_points()),
            weights: self.weights().to_vec(),
        }
    }
}

impl Codec for Nurbs {
    const FIELDS: &'static [&'static str] = &["points", "weights", "knots", "order"];

    fn decode(node: &Node<'_>, obj: &Obj<'_>) -> Result<Nurbs, SceneError> {
        let (points, knots) = decode_spline_parts(node, obj)?;
        Nurbs::from_knot_vector(points, weights(obj)?, knots).map_err(|e| geom_error(node, "", &e))
    }
}

impl Written for Nurbs {
    type Doc = NurbsDoc;

    fn encode(&self) -> NurbsDoc {
        NurbsDoc {
            points: PointDoc::all(self.control_points()),
            weights: self.weights().to_vec(),
            knots: KnotsDoc::Values(self.knots().knots().to_vec()),
            order: self.order(),
        }
    }
}
