//! [`ModifiedBezier`]'s words: the `t*` and `v` controls, the template, the `inspect`
//! report (paper 002 §4).

use glam::DVec3;
use schemars::JsonSchema;
use serde::Serialize;
use splinescope_core::geom::{Bezier, GeomError, ModifiedBezier, ParamCurve, Xyz};

use splinescope_core::geom::Family;

use crate::Present;
use crate::controls::{
    Control, ControlError, ControlId, ControlKind, ControlValue, unknown_control,
};
use splinescope_encoding::draw::{OverlayKind, OverlayPolyline};

impl Present for ModifiedBezier {
    type Details = ModifiedDetails;

    fn templates(center: DVec3, size: f64) -> Vec<(&'static str, ModifiedBezier)> {
        let base = Bezier::new(crate::template::arch(center, size));
        ModifiedBezier::try_new(base, 0.5, DVec3::new(0.0, 0.2 * size, 0.0))
            .map(|m| vec![("modified Bézier", m)])
            .unwrap_or_default()
    }

    /// The base's control polygon and the bump vector `v` from `Q(t*)` to `R(t*)`.
    fn overlays(&self) -> Vec<OverlayPolyline> {
        let q = self.base().eval(self.t_star());
        vec![
            OverlayPolyline::control_polygon(self.base().points()),
            OverlayPolyline {
                kind: OverlayKind::BumpVector,
                points: vec![q, q + self.v()],
            },
        ]
    }

    fn summary(&self) -> String {
        format!("degree {}, t* = {}", self.base().degree(), self.t_star())
    }

    fn parameter_text(&self) -> Option<String> {
        Some(crate::text::bump_text(self.t_star(), self.v()))
    }

    fn details(&self) -> Result<ModifiedDetails, GeomError> {
        Ok(ModifiedDetails {
            degree: self.base().degree(),
            t_star: self.t_star(),
            v: self.v().to_array(),
            peak: Peak {
                t: self.t_star(),
                q: self.base().eval(self.t_star()).to_array(),
                r: self.eval(self.t_star()).to_array(),
            },
        })
    }

    fn controls(&self) -> Vec<Control> {
        vec![
            Control {
                id: ControlId::new("t_star"),
                label: "t*".into(),
                hint: Some("where the bump peaks, in (0, 1)".into()),
                kind: ControlKind::Number {
                    value: self.t_star(),
                    range: (0.01, 0.99),
                    bands: Vec::new(),
                },
            },
            Control {
                id: ControlId::new("v"),
                label: "v".into(),
                hint: Some("R(t*) = Q(t*) + v".into()),
                kind: ControlKind::Vector { value: self.v() },
            },
        ]
    }

    fn apply_control(
        &self,
        id: ControlId,
        value: ControlValue,
    ) -> Result<ModifiedBezier, ControlError> {
        match (id.key, value) {
            ("t_star", ControlValue::Number(t)) => {
                Ok(ModifiedBezier::try_new(self.base().clone(), t, self.v())?)
            }
            ("v", ControlValue::Vector(v)) => Ok(ModifiedBezier::try_new(
                self.base().clone(),
                self.t_star(),
                v,
            )?),
            _ => Err(unknown_control(Self::NAME, id, value)),
        }
    }
}

/// What `inspect` reports for a modified Bézier curve.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct ModifiedDetails {
    /// The base curve's degree `n`.
    pub degree: usize,
    /// `t*`.
    pub t_star: f64,
    /// `v`.
    pub v: Xyz,
    /// The bump's peak: `Q(t*)` and `R(t*) = Q(t*) + v`.
    pub peak: Peak,
}

/// The peak of a bump.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct Peak {
    /// `t*`.
    pub t: f64,
    /// `Q(t*)`.
    pub q: Xyz,
    /// `R(t*)`.
    pub r: Xyz,
}
