//! [`RationalBezier`]'s and [`Nurbs`]'s words: the weight controls, the templates, the
//! `inspect` reports (homogeneous points, conic type, knots).

use glam::DVec3;
use schemars::JsonSchema;
use serde::Serialize;
use splinescope_core::geom::{Conic, GeomError, Nurbs, RationalBezier};

use splinescope_core::geom::Family;

use crate::Present;
use crate::controls::{
    Control, ControlError, ControlId, ControlKind, ControlValue, unknown_control,
};
use crate::family::nubmp::SplineDetails;
use splinescope_encoding::draw::OverlayPolyline;

impl Present for RationalBezier {
    type Details = RationalBezierDetails;

    fn overlays(&self) -> Vec<OverlayPolyline> {
        vec![OverlayPolyline::control_polygon(self.points())]
    }

    fn summary(&self) -> String {
        format!("degree {}, rational", self.degree())
    }

    fn parameter_text(&self) -> Option<String> {
        Some(weight_text(self.weights()))
    }

    fn details(&self) -> Result<RationalBezierDetails, GeomError> {
        let conic = match *self.weights() {
            [w0, w1, w2] => {
                let k = w0 * w2 / (w1 * w1);
                Some(if k > 1.0 {
                    Conic::Ellipse
                } else if k < 1.0 {
                    Conic::Hyperbola
                } else {
                    Conic::Parabola
                })
            }
            _ => None,
        };
        Ok(RationalBezierDetails {
            degree: self.degree(),
            weights: self.weights().to_vec(),
            homogeneous: homogeneous_report(self.points(), self.weights()),
            conic,
        })
    }

    fn controls(&self) -> Vec<Control> {
        weight_controls(self.weights())
    }

    fn apply_control(
        &self,
        id: ControlId,
        value: ControlValue,
    ) -> Result<RationalBezier, ControlError> {
        match (id.key, value) {
            ("w", ControlValue::Number(w)) => Ok(RationalBezier::try_new(
                self.points().to_vec(),
                with_weight(self.weights(), id.index[0], w)?,
            )?),
            ("elevate", ControlValue::Press) => Ok(self.elevate()),
            _ => Err(unknown_control(Self::NAME, id, value)),
        }
    }

    fn templates(center: DVec3, size: f64) -> Vec<(&'static str, RationalBezier)> {
        let corner = center - DVec3::new(0.25 * size, 0.2 * size, 0.0);
        vec![(
            "ellipse arc",
            RationalBezier::quarter_ellipse(corner, 0.6 * size, 0.4 * size),
        )]
    }
}

impl Present for Nurbs {
    type Details = NurbsDetails;

    fn overlays(&self) -> Vec<OverlayPolyline> {
        vec![OverlayPolyline::control_polygon(self.points())]
    }

    fn summary(&self) -> String {
        format!(
            "order {}, rational, knots {}",
            self.order(),
            splinescope_core::geom::knots::knots_text(self.knots().knots())
        )
    }

    fn parameter_text(&self) -> Option<String> {
        Some(weight_text(self.weights()))
    }

    fn details(&self) -> Result<NurbsDetails, GeomError> {
        Ok(NurbsDetails {
            spline: SplineDetails::of(self.knots()),
            weights: self.weights().to_vec(),
            homogeneous: homogeneous_report(self.points(), self.weights()),
        })
    }

    fn controls(&self) -> Vec<Control> {
        weight_controls(self.weights())
    }

    fn apply_control(&self, id: ControlId, value: ControlValue) -> Result<Nurbs, ControlError> {
        match (id.key, value) {
            ("w", ControlValue::Number(w)) => Ok(Nurbs::from_knot_vector(
                self.points().to_vec(),
                with_weight(self.weights(), id.index[0], w)?,
                self.knots().clone(),
            )?),
            ("elevate", ControlValue::Press) => Ok(self.elevate()),
            _ => Err(unknown_control(Self::NAME, id, value)),
        }
    }

    fn templates(center: DVec3, size: f64) -> Vec<(&'static str, Nurbs)> {
        let mut out = Vec::new();
        if let Ok(circle) = Nurbs::circle(center, 0.35 * size) {
            out.push(("circle", circle));
        }
        let points = crate::template::zigzag(center, size, 6);
        let weights = vec![1.0, 3.0, 0.5, 3.0, 0.5, 1.0];
        if let Ok(c) = Nurbs::try_new(points, weights, crate::template::clamped_knots(6, 4), 4) {
            out.push(("NURBS curve", c));
        }
        out
    }
}

/// Both families' panel controls: a note, one number control per weight (the family
/// refuses `w ≤ 0`), and the elevate button.
fn weight_controls(weights: &[f64]) -> Vec<Control> {
    let note = Control::note("weights w_i of the points, each greater than 0", false);
    std::iter::once(note)
        .chain(weights.iter().enumerate().map(|(i, &w)| Control {
            id: ControlId {
                key: "w",
                index: [i, 0],
            },
            label: format!("w{i}"),
            hint: None,
            kind: ControlKind::Number {
                value: w,
                range: (0.05, 5.0_f64.max(w)),
                bands: Vec::new(),
            },
        }))
        .chain(std::iter::once(Control::elevate()))
        .collect()
}

/// The weights with weight `index` set to `value` (checked by the curve's constructor).
fn with_weight(weights: &[f64], index: usize, value: f64) -> Result<Vec<f64>, GeomError> {
    if index >= weights.len() {
        return Err(GeomError::NoSuchPoint {
            index,
            count: weights.len(),
        });
    }
    let mut out = weights.to_vec();
    out[index] = value;
    Ok(out)
}

/// The weights written for labels: `w = (1, 0.7071, 1)` up to four weights, their range
/// `w from 0.7071 to 1` beyond.
fn weight_text(weights: &[f64]) -> String {
    if weights.len() > 4 {
        let lo = weights.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = weights.iter().copied().fold(0.0, f64::max);
        return format!("w from {} to {}", round4(lo), round4(hi));
    }
    let items: Vec<String> = weights.iter().map(|w| format!("{}", round4(*w))).collect();
    format!("w = ({})", items.join(", "))
}

/// `x` to four significant decimals after the point, for display.
fn round4(x: f64) -> f64 {
    (x * 1e4).round() / 1e4
}

/// What `inspect` reports for a rational Bézier curve.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct RationalBezierDetails {
    /// `n`.
    pub degree: usize,
    /// The weights `w_i`.
    pub weights: Vec<f64>,
    /// The homogeneous control points `(w_i x_i, w_i y_i, w_i z_i, w_i)`.
    pub homogeneous: Vec<[f64; 4]>,
    /// For a quadratic: the conic it is an arc of.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub conic: Option<Conic>,
}

/// What `inspect` reports for a NURBS curve.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct NurbsDetails {
    /// The knots.
    #[serde(flatten)]
    pub spline: SplineDetails,
    /// The weights `w_i`.
    pub weights: Vec<f64>,
    /// The homogeneous control points `(w_i x_i, w_i y_i, w_i z_i, w_i)`.
    pub homogeneous: Vec<[f64; 4]>,
}

fn homogeneous_report(points: &[DVec3], weights: &[f64]) -> Vec<[f64; 4]> {
    points
        .iter()
        .zip(weights)
        .map(|(p, w)| [p.x * w, p.y * w, p.z * w, *w])
        .collect()
}
