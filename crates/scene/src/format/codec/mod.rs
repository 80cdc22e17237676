//! One codec per curve family: how its object in a scene file is read (with the path of
//! the first offending value) and written. Each family's file implements [`Written`] and
//! `Codec`; the reader's table `CODECS` and the written forms' enum
//! ([`super::doc::FamilyDoc`]) are generated from the core's family table
//! (`splinescope_core::family_table!`), so a family without a codec does not compile.

mod bezier;
mod bspline;
mod interpolation;
mod modified;
mod nubmp;
mod path;
mod rational;

pub use bezier::BezierDoc;
pub use bspline::BSplineDoc;
pub use interpolation::{InterpolationDoc, ModificationDoc};
pub use modified::ModifiedBezierDoc;
pub use nubmp::{NubmpDoc, ShapeSettingDoc};
pub use path::{PathDoc, PathSegmentDoc};
pub use rational::{NurbsDoc, RationalBezierDoc};

use crate::jsonread::{Node, Obj};
use splinescope_core::geom::{Curve, Family, GeomError};

use super::SceneError;

/// How one family's curve object is written: its fields' form in scene files and the
/// schema.
pub trait Written: Family {
    /// The written form of the family's fields.
    type Doc: serde::Serialize + schemars::JsonSchema;

    /// The family's fields as they are written.
    fn encode(&self) -> Self::Doc;
}

/// How one family reads its curve object.
pub(crate) trait Codec: Written + Into<Curve> {
    /// The family's own fields (beyond `type`, `name` and `style`).
    const FIELDS: &'static [&'static str];

    /// Reads the family's fields of the curve object `obj` (at `node`).
    fn decode(node: &Node<'_>, obj: &Obj<'_>) -> Result<Self, SceneError>;
}

/// The fields every curve object may have, whatever its family.
const COMMON_CURVE_FIELDS: [&str; 3] = ["type", "name", "style"];

type Decoder = for<'a> fn(&Node<'a>) -> Result<(Curve, Obj<'a>), SceneError>;

fn decode_as<'a, F: Codec>(node: &Node<'a>) -> Result<(Curve, Obj<'a>), SceneError> {
    let fields: Vec<&str> = COMMON_CURVE_FIELDS
        .iter()
        .chain(F::FIELDS)
        .copied()
        .collect();
    let obj = node.object(&fields)?;
    let curve = F::decode(node, &obj)?;
    Ok((curve.into(), obj))
}

macro_rules! codec_table {
    ($( $(#[$doc:meta])* $variant:ident($ty:ty) = $name:literal ),* $(,)?) => {
        /// Every family's name and reader, in the core's family table's order (the order
        /// error messages list them in).
        const CODECS: &[(&str, Decoder)] = &[$( ($name, decode_as::<$ty>), )*];
    };
}

splinescope_core::family_table!(codec_table);

/// Reads the curve object at `node` as family `family`; `None` for an unknown family.
pub(crate) fn decode<'a>(
    family: &str,
    node: &Node<'a>,
) -> Option<Result<(Curve, Obj<'a>), SceneError>> {
    CODECS
        .iter()
        .find(|(name, _)| *name == family)
        .map(|(_, decode)| decode(node))
}

/// The families' names, for error messages.
pub(crate) fn family_names() -> Vec<&'static str> {
    CODECS.iter().map(|(name, _)| *name).collect()
}

/// A [`GeomError`] at its field of the curve at `curve` (`prefix` before the field, e.g.
/// `modification.`).
pub(crate) fn geom_error(curve: &Node<'_>, prefix: &str, e: &GeomError) -> SceneError {
    let field = e.field();
    let path = if field.is_empty() {
        curve.path.to_string()
    } else if curve.path.is_empty() {
        format!("{prefix}{field}")
    } else {
        format!("{}.{prefix}{field}", curve.path)
    };
    SceneError::new(path, super::SceneErrorKind::Invalid(e.to_string()))
}
