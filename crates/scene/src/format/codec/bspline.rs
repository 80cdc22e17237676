//! `"bspline"`: a non-uniform B-spline of any order (paper 001, §2).

use schemars::JsonSchema;
use serde::Serialize;
use serde_json::Value;

use super::{Codec, Written, geom_error};
use crate::format::SceneError;
use crate::format::point_doc::PointDoc;
use crate::jsonread::{Node, Obj};
use splinescope_core::geom::exact::{Rational, parse_decimal};
use splinescope_core::geom::{BSpline, Family, KnotVector};

/// A B-spline's fields.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct BSplineDoc {
    /// The control points `P_0 … P_{n−1}`.
    #[schemars(length(min = 2))]
    pub points: Vec<PointDoc>,
    /// The knot vector (`n + k` non-decreasing numbers) or `"clamped_uniform"`.
    pub knots: KnotsDoc,
    /// The order `k` (degree `k − 1`), at least 2.
    #[schemars(range(min = 2))]
    pub order: usize,
}

/// A knot vector: its values, or a named construction.
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[serde(untagged)]
pub enum KnotsDoc {
    /// The knots.
    Values(Vec<f64>),
    /// Clamped with uniform interior knots on `[0, 1]`.
    Named(NamedKnots),
}

/// Named knot vectors.
#[derive(Debug, Clone, Copy, Serialize, JsonSchema)]
pub enum NamedKnots {
    /// `"clamped_uniform"`.
    #[serde(rename = "clamped_uniform")]
    ClampedUniform,
}

impl Codec for BSpline {
    const FIELDS: &'static [&'static str] = &["points", "knots", "order"];

    fn decode(node: &Node<'_>, obj: &Obj<'_>) -> Result<BSpline, SceneError> {
        let (points, knots) = decode_spline_parts(node, obj)?;
        BSpline::from_parts(points, knots).map_err(|e| geom_error(node, "", &e))
    }
}

impl Written for BSpline {
    type Doc = BSplineDoc;

    fn encode(&self) -> BSplineDoc {
        BSplineDoc {
            points: PointDoc::all(self.control_points()),
            knots: KnotsDoc::Values(self.knots().knots().to_vec()),
            order: self.order(),
        }
    }
}

/// Points and validated knots, with the knots' exact decimal values recorded.
pub(super) fn decode_spline_parts(
    node: &Node<'_>,
    obj: &Obj<'_>,
) -> Result<(Vec<glam::DVec3>, KnotVector), SceneError> {
    let points = obj.req("points")?.points(2)?;
    let order_node = obj.req("order")?;
    let order = order_node.u32_in(0, u32::MAX)? as usize;
    splinescope_io::limits::ORDER
        .check(order as u64)
        .map_err(|e| order_node.invalid(e.to_string()))?;
    let knots_node = obj.req("knots")?;
    let knots = match knots_node.value {
        Value::String(s) if s == "clamped_uniform" => {
            KnotVector::clamped_uniform(order, points.len())
                .map_err(|e| geom_error(node, "", &e))?
        }
        Value::String(s) => {
            return Err(knots_node.invalid(format!(
                "unknown knot vector {s:?} (expected an array of numbers or \"clamped_uniform\")"
            )));
        }
        _ => {
            let items = knots_node.array()?;
            let values = items.iter().map(Node::f64).collect::<Result<Vec<_>, _>>()?;
            let exact: Option<Vec<Rational>> = items
                .iter()
                .map(|n| match n.value {
                    Value::Number(x) => parse_decimal(&x.to_string()),
                    _ => None,
                })
                .collect();
            let kv = KnotVector::try_new(values, order, points.len())
                .map_err(|e| geom_error(node, "", &e))?;
            match exact {
                Some(exact) => kv.with_exact(exact),
                None => kv,
            }
        }
    };
    Ok((points, knots))
}
