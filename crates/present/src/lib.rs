#![doc = include_str!("../README.md")]
#![forbid(unsafe_code)]

pub mod controls;
pub mod family;
pub mod inspect;
pub mod template;
pub mod text;

use glam::DVec3;
use schemars::JsonSchema;
use serde::Serialize;
use splinescope_core::geom::{Curve, GeomError};
/// Deprecated: the overlay kinds are the encoding's, `splinescope_encoding::draw::OverlayKind`.
#[deprecated(note = "use splinescope_encoding::draw::OverlayKind")]
pub type OverlayKind = splinescope_encoding::draw::OverlayKind;

/// Deprecated: `splinescope_encoding::draw::OverlayPolyline`.
#[deprecated(note = "use splinescope_encoding::draw::OverlayPolyline")]
pub type OverlayPolyline = splinescope_encoding::draw::OverlayPolyline;

pub use controls::{Control, ControlError, ControlId, ControlKind, ControlValue};

/// What a family says to a person: its summary and parameters as labels write them, its
/// panel controls (and how a change through one is applied), the templates the editor
/// offers, and its part of the `inspect` report. One implementation per family, in its own
/// file of [`family`]; [`Curve`] implements it by dispatching to its family.
pub trait Present: Sized {
    /// What `splinescope inspect` reports for this family beyond the common fields
    /// (`docs/inspect-format.md`).
    type Details: Serialize + JsonSchema;

    /// One line describing the curve's structure for the panel ("degree 3", …).
    fn summary(&self) -> String;

    /// The polylines that explain the curve, drawn over it when control polygons are
    /// shown: its control polygon, and the family's own (a NUBMP curve's dual polygon, an
    /// interpolation's tangent handles, a modified curve's bump vector).
    fn overlays(&self) -> Vec<splinescope_encoding::draw::OverlayPolyline>;

    /// The curve's shape parameters as they are now, for labels that must not go stale
    /// when they are edited (`t* = 0.3, v = (1, 2)`; a NUBMP curve's parameters that
    /// differ from the standard curve's). `None` for families without parameters.
    fn parameter_text(&self) -> Option<String> {
        None
    }

    /// The family's derived data, as `inspect` reports it.
    ///
    /// # Errors
    /// [`GeomError::DerivedNotFinite`] when a derived structure overflows `f64`.
    fn details(&self) -> Result<Self::Details, GeomError>;

    /// The panel's controls for this curve's own parameters, as data: the viewer draws
    /// them and applies changes through [`Present::apply_control`]; tests drive them the
    /// same way.
    fn controls(&self) -> Vec<Control> {
        Vec::new()
    }

    /// The curve with control `id` set to `value`.
    ///
    /// # Errors
    /// [`ControlError::Unknown`] for a control the curve does not have or a value of the
    /// wrong kind; otherwise the family's error for a value it refuses
    /// ([`ControlError::Geom`]; nothing is clamped).
    fn apply_control(&self, id: ControlId, value: ControlValue) -> Result<Self, ControlError>;

    /// The starting curves the editor offers (label and curve), centred on `center`,
    /// about `size` wide, in the plane `z = center.z`.
    fn templates(center: DVec3, size: f64) -> Vec<(&'static str, Self)>;
}

macro_rules! define_details {
    ($( $(#[$doc:meta])* $variant:ident($ty:ty) = $name:literal ),* $(,)?) => {
        /// The per-family part of an `inspect` report (flattened into the curve's
        /// object): each family's [`Present::Details`], generated from core's
        /// [`family_table!`](splinescope_core::family_table).
        #[derive(Debug, Clone, Serialize, JsonSchema)]
        #[serde(untagged)]
        pub enum FamilyDetails {
            $( $(#[$doc])* $variant(<$ty as Present>::Details), )*
        }

        impl Present for Curve {
            type Details = FamilyDetails;

            fn summary(&self) -> String {
                splinescope_core::each_family!(self, c => c.summary())
            }

            fn overlays(&self) -> Vec<splinescope_encoding::draw::OverlayPolyline> {
                splinescope_core::each_family!(self, c => c.overlays())
            }

            fn parameter_text(&self) -> Option<String> {
                splinescope_core::each_family!(self, c => c.parameter_text())
            }

            fn details(&self) -> Result<FamilyDetails, GeomError> {
                match self {
                    $( Curve::$variant(c) => c.details().map(FamilyDetails::$variant), )*
                }
            }

            fn controls(&self) -> Vec<Control> {
                splinescope_core::each_family!(self, c => c.controls())
            }

            fn apply_control(&self, id: ControlId, value: ControlValue) -> Result<Curve, ControlError> {
                splinescope_core::each_family!(self, c => c.apply_control(id, value).map(Into::into))
            }

            /// Every family's templates in the family table's order: what the editor
            /// offers to add.
            fn templates(center: DVec3, size: f64) -> Vec<(&'static str, Curve)> {
                let mut out = Vec::new();
                $(
                    out.extend(
                        <$ty as Present>::templates(center, size)
                            .into_iter()
                            .map(|(label, c)| (label, Curve::from(c))),
                    );
                )*
                out
            }
        }
    };
}

splinescope_core::family_table!(define_details);
