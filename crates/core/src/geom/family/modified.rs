//! [`ModifiedBezier`]'s [`Family`] side: the `t*` and `v` controls, the bump-vector
//! overlay, the `inspect` report (paper 002 §4).

use glam::DVec3;
#[cfg(feature = "serde")]
use schemars::JsonSchema;
#[cfg(feature = "serde")]
use serde::Serialize;

use super::{
    Control, ControlId, ControlKind, ControlValue, Family, OverlayKind, OverlayPolyline, Xyz,
    lowered_box, unknown_control,
};
use crate::geom::{Aabb, Bezier, GeomError, ModifiedBezier, ParamCurve};

impl Family for ModifiedBezier {
    const NAME: &'static str = "modified_bezier";
    type Details = ModifiedDetails;

    fn with_point_on_polygon(&self, at: DVec3) -> Result<(ModifiedBezier, usize), GeomError> {
        let (points, leg, _) = crate::geom::structure::insert_on_polygon(self.base().points(), at);
        let base = Bezier::try_new(points)?;
        Ok((
            ModifiedBezier::try_new(base, self.t_star(), self.v())?,
            leg + 1,
        ))
    }

    fn with_point_removed(&self, index: usize) -> Result<ModifiedBezier, GeomError> {
        let points = crate::geom::structure::without(self.base().points(), index, 2, Self::NAME)?;
        ModifiedBezier::try_new(Bezier::try_new(points)?, self.t_star(), self.v())
    }

    fn templates(center: DVec3, size: f64) -> Vec<(&'static str, ModifiedBezier)> {
        let base = Bezier::new(crate::geom::template::arch(center, size));
        ModifiedBezier::try_new(base, 0.5, DVec3::new(0.0, 0.2 * size, 0.0))
            .map(|m| vec![("modified Bézier", m)])
            .unwrap_or_default()
    }

    /// The base `Q` of `degree` from `point`, `t* = 1/2`, and `v` a quarter of the
    /// difference of two more points.
    fn generated(
        degree: usize,
        point: &mut dyn FnMut() -> DVec3,
    ) -> Result<ModifiedBezier, GeomError> {
        let base = Bezier::generated(degree, point)?;
        let v = 0.25 * (point() - point());
        ModifiedBezier::try_new(base, 0.5, v)
    }

    fn control_points(&self) -> &[DVec3] {
        self.base.points()
    }

    fn with_control_points(&self, points: Vec<DVec3>) -> Result<ModifiedBezier, GeomError> {
        ModifiedBezier::try_new(Bezier::try_new(points)?, self.t_star, self.v)
    }

    fn overlays(&self) -> Vec<OverlayPolyline> {
        let q = self.base.eval(self.t_star);
        vec![
            OverlayPolyline {
                kind: OverlayKind::ControlPolygon,
                points: self.base.points().to_vec(),
            },
            OverlayPolyline {
                kind: OverlayKind::BumpVector,
                points: vec![q, q + self.v],
            },
        ]
    }

    /// The modified curve leaves its base's hull: it is bounded by its two pieces.
    fn control_box(&self) -> Aabb {
        lowered_box(self)
    }

    fn is_planar(&self) -> bool {
        self.base.points().iter().all(|p| p.z == 0.0) && self.v.z == 0.0
    }

    fn summary(&self) -> String {
        format!("degree {}, t* = {}", self.base.degree(), self.t_star)
    }

    fn parameter_text(&self) -> Option<String> {
        Some(crate::geom::family::bump_text(self.t_star, self.v))
    }

    fn details(&self) -> Result<ModifiedDetails, GeomError> {
        Ok(ModifiedDetails {
            degree: self.base.degree(),
            t_star: self.t_star,
            v: self.v.to_array(),
            peak: Peak {
                t: self.t_star,
                q: self.base.eval(self.t_star).to_array(),
                r: self.eval(self.t_star).to_array(),
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
                    value: self.t_star,
                    range: (0.01, 0.99),
                    bands: Vec::new(),
                },
            },
            Control {
                id: ControlId::new("v"),
                label: "v".into(),
                hint: Some("R(t*) = Q(t*) + v".into()),
                kind: ControlKind::Vector { value: self.v },
            },
        ]
    }

    fn apply_control(
        &self,
        id: ControlId,
        value: ControlValue,
    ) -> Result<ModifiedBezier, GeomError> {
        match (id.key, value) {
            ("t_star", ControlValue::Number(t)) => {
                ModifiedBezier::try_new(self.base.clone(), t, self.v)
            }
            ("v", ControlValue::Vector(v)) => {
                ModifiedBezier::try_new(self.base.clone(), self.t_star, v)
            }
            _ => Err(unknown_control(Self::NAME, id, value)),
        }
    }
}

/// What `inspect` reports for a modified Bézier curve.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
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
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
pub struct Peak {
    /// `t*`.
    pub t: f64,
    /// `Q(t*)`.
    pub q: Xyz,
    /// `R(t*)`.
    pub r: Xyz,
}
