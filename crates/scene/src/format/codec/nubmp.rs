//! `"nubmp"`: a B-spline with multiple shape parameters (paper 001, §3–5).

use schemars::JsonSchema;
use serde::Serialize;

use super::bspline::{KnotsDoc, decode_spline_parts};
use super::{Codec, Written, geom_error};
use crate::format::point_doc::PointDoc;
use crate::format::{SceneError, SceneErrorKind};
use crate::jsonread::{Node, Obj};
use splinescope_core::geom::{Family, GeomError, Nubmp};

/// A NUBMP curve's fields.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct NubmpDoc {
    /// The control points.
    #[schemars(length(min = 2))]
    pub points: Vec<PointDoc>,
    /// The knot vector or `"clamped_uniform"`.
    pub knots: KnotsDoc,
    /// The order `k`, at least 2.
    #[schemars(range(min = 2))]
    pub order: usize,
    /// Shape parameters that differ from the standard values, applied in order.
    #[serde(skip_serializing_if = "Vec::is_empty", default)]
    pub shape: Vec<ShapeSettingDoc>,
}

/// One entry of a NUBMP `shape` list.
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[serde(untagged)]
pub enum ShapeSettingDoc {
    /// Every parameter of a group (summing to 1, each ≥ 0).
    Group {
        /// The group `j`.
        group: usize,
        /// `a^i_j` in member order.
        values: Vec<f64>,
    },
    /// One parameter, another member of the group absorbing the difference.
    Member {
        /// The group `j`.
        group: usize,
        /// The member `i`.
        member: usize,
        /// The new `a^i_j`.
        value: f64,
        /// The member `l` whose `a^l_j` absorbs the change.
        absorber: usize,
    },
}

impl Codec for Nubmp {
    const FIELDS: &'static [&'static str] = &["points", "knots", "order", "shape"];

    fn decode(node: &Node<'_>, obj: &Obj<'_>) -> Result<Nubmp, SceneError> {
        let (points, knots) = decode_spline_parts(node, obj)?;
        let mut curve = Nubmp::standard(points, knots).map_err(|e| geom_error(node, "", &e))?;
        if let Some(shape) = obj.get("shape") {
            for setting in shape.array()? {
                apply_shape_setting(&mut curve, &setting)?;
            }
        }
        Ok(curve)
    }
}

impl Written for Nubmp {
    type Doc = NubmpDoc;

    fn encode(&self) -> NubmpDoc {
        NubmpDoc {
            points: PointDoc::all(self.control_points()),
            knots: KnotsDoc::Values(self.knots().knots().to_vec()),
            order: self.order(),
            shape: self
                .groups()
                .iter()
                .enumerate()
                .filter(|(_, g)| g.values != g.standard)
                .map(|(j, g)| ShapeSettingDoc::Group {
                    group: j,
                    values: g.values.clone(),
                })
                .collect(),
        }
    }
}

/// Applies one entry of a NUBMP `shape` list: `{"group": j, "values": [...]}` or
/// `{"group": j, "member": i, "value": x, "absorber": l}`.
fn apply_shape_setting(curve: &mut Nubmp, node: &Node<'_>) -> Result<(), SceneError> {
    let obj = node.object(&["group", "values", "member", "value", "absorber"])?;
    let group = obj.req("group")?.u32_in(0, u32::MAX)? as usize;
    let at =
        |field: &str| SceneError::new(format!("{}.{field}", node.path), SceneErrorKind::Missing);
    let err = |field: String, e: &GeomError| {
        SceneError::new(
            format!("{}.{field}", node.path),
            SceneErrorKind::Invalid(e.to_string()),
        )
    };
    if let Some(values_node) = obj.get("values") {
        for extra in ["member", "value", "absorber"] {
            if obj.get(extra).is_some() {
                return Err(SceneError::new(
                    format!("{}.{extra}", node.path),
                    SceneErrorKind::Invalid(
                        "give either \"values\" (the whole group) or \"member\", \"value\" and \"absorber\"".into(),
                    ),
                ));
            }
        }
        let values = values_node.numbers()?;
        return curve.set_group(group, &values).map_err(|e| {
            let field = match &e {
                GeomError::NoSuchGroup { .. } | GeomError::GroupOutsideDomain { .. } => {
                    "group".into()
                }
                GeomError::NegativeParameter { member, .. } => curve.groups()[group]
                    .position(*member)
                    .map_or("values".into(), |p| format!("values[{p}]")),
                _ => "values".into(),
            };
            err(field, &e)
        });
    }
    let member_node = obj.get("member").ok_or_else(|| at("member"))?;
    let member = member_node.u32_in(0, u32::MAX)? as usize;
    let value = obj.get("value").ok_or_else(|| at("value"))?.f64()?;
    let absorber = obj
        .get("absorber")
        .ok_or_else(|| at("absorber"))?
        .u32_in(0, u32::MAX)? as usize;
    curve
        .set_parameter(group, member, value, absorber)
        .map_err(|e| {
            let field = match &e {
                GeomError::NoSuchGroup { .. } | GeomError::GroupOutsideDomain { .. } => "group",
                GeomError::NotInGroup { member: m, .. } if *m == member => "member",
                GeomError::NotInGroup { .. } | GeomError::SameAbsorber { .. } => "absorber",
                // A negative result (for either member) comes from the value asked for.
                _ => "value",
            };
            err(field.into(), &e)
        })
}
