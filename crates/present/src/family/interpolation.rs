//! [`CubicInterpolation`]'s words: the modification controls, the template, the `inspect`
//! report (paper 002 §5).

use glam::DVec3;
use schemars::JsonSchema;
use serde::Serialize;
use splinescope_core::geom::{CubicInterpolation, GeomError, Modification, Reading, Xyz, xyz};

use splinescope_core::geom::Family;

use crate::Present;
use crate::controls::{
    Control, ControlError, ControlId, ControlKind, ControlValue, unknown_control,
};
use splinescope_encoding::draw::{OverlayKind, OverlayPolyline};

impl Present for CubicInterpolation {
    type Details = InterpolationDetails;

    fn templates(center: DVec3, size: f64) -> Vec<(&'static str, CubicInterpolation)> {
        CubicInterpolation::try_new(crate::template::zigzag(center, size, 4), None, None)
            .map(|c| vec![("interpolation", c)])
            .unwrap_or_default()
    }

    /// Each piece's inner Bézier points joined to its ends: the tangent handles.
    fn overlays(&self) -> Vec<OverlayPolyline> {
        self.pieces()
            .iter()
            .map(|p| OverlayPolyline {
                kind: OverlayKind::TangentHandles,
                points: p.points().to_vec(),
            })
            .collect()
    }

    fn summary(&self) -> String {
        let kind = match self.modification() {
            None => "plain".to_owned(),
            Some(m) => format!("modified ({} reading)", m.reading.name()),
        };
        format!("{} points, {kind}", self.points().len())
    }

    fn parameter_text(&self) -> Option<String> {
        self.modification()
            .map(|m| crate::text::bump_text(m.t_star, m.v))
    }

    fn details(&self) -> Result<InterpolationDetails, GeomError> {
        // Paper 002 §5: chord slopes C_i and the parabola weights α_i behind s_i.
        let (p, t) = (self.points(), &self.params());
        let chords: Vec<DVec3> = (0..p.len() - 1)
            .map(|i| (p[i + 1] - p[i]) / (t[i + 1] - t[i]))
            .collect();
        Ok(InterpolationDetails {
            params: self.params().to_vec(),
            chord_slopes: xyz(&chords),
            parabola_weights: (1..p.len() - 1)
                .map(|i| (t[i] - t[i - 1]) / (t[i + 1] - t[i - 1]))
                .collect(),
            tangents: xyz(self.tangents()),
            inner_points: self
                .pieces()
                .iter()
                .map(|b| [b.points()[1].to_array(), b.points()[2].to_array()])
                .collect(),
            modification: self.modification().map(|m| ModificationReport {
                t_star: m.t_star,
                v: m.v.to_array(),
                reading: m.reading.name(),
            }),
        })
    }

    fn controls(&self) -> Vec<Control> {
        let mut out = vec![Control {
            id: ControlId::new("modified"),
            label: "modified (paper 002)".into(),
            hint: Some("a bump of vector v peaking at t* in every piece".into()),
            kind: ControlKind::Toggle {
                value: self.modification().is_some(),
            },
        }];
        if let Some(m) = self.modification() {
            out.push(Control {
                id: ControlId::new("t_star"),
                label: "t*".into(),
                hint: Some("where each piece's bump peaks, in (0, 1)".into()),
                kind: ControlKind::Number {
                    value: m.t_star,
                    range: (0.01, 0.99),
                    bands: Vec::new(),
                },
            });
            out.push(Control {
                id: ControlId::new("v"),
                label: "v".into(),
                hint: None,
                kind: ControlKind::Vector { value: m.v },
            });
            out.push(Control {
                id: ControlId::new("reading"),
                label: "reading".into(),
                hint: Some("docs/math.md §1: the paper's reading or the bump added".into()),
                kind: ControlKind::Choice {
                    options: vec!["paper", "bump added"],
                    selected: usize::from(m.reading == Reading::BumpAdded),
                },
            });
        }
        out
    }

    fn apply_control(
        &self,
        id: ControlId,
        value: ControlValue,
    ) -> Result<CubicInterpolation, ControlError> {
        let current = self.modification();
        let next = match (id.key, value, current) {
            ("modified", ControlValue::Toggle(on), _) => on.then_some(Modification {
                t_star: 0.5,
                v: DVec3::ZERO,
                reading: Reading::Paper,
            }),
            ("t_star", ControlValue::Number(t_star), Some(m)) => Some(Modification { t_star, ..m }),
            ("v", ControlValue::Vector(v), Some(m)) => Some(Modification { v, ..m }),
            ("reading", ControlValue::Choice(i @ 0..=1), Some(m)) => Some(Modification {
                reading: if i == 0 {
                    Reading::Paper
                } else {
                    Reading::BumpAdded
                },
                ..m
            }),
            _ => return Err(unknown_control(Self::NAME, id, value)),
        };
        Ok(CubicInterpolation::try_new(
            self.points().to_vec(),
            Some(self.params().to_vec()),
            next,
        )?)
    }
}

/// What `inspect` reports for an interpolating spline.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct InterpolationDetails {
    /// `t_0..t_k`.
    pub params: Vec<f64>,
    /// `C_i = (P_{i+1} − P_i)/(t_{i+1} − t_i)`.
    pub chord_slopes: Vec<Xyz>,
    /// `α_i = (t_i − t_{i−1})/(t_{i+1} − t_{i−1})`, `i = 1..k−1`.
    pub parabola_weights: Vec<f64>,
    /// `s_0..s_k`.
    pub tangents: Vec<Xyz>,
    /// Each piece's inner points `P_{i−2/3}`, `P_{i−1/3}`.
    pub inner_points: Vec<[Xyz; 2]>,
    /// The modification, when there is one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub modification: Option<ModificationReport>,
}

/// A modification as reports write it.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct ModificationReport {
    /// `t*`.
    pub t_star: f64,
    /// `v`.
    pub v: Xyz,
    /// `"paper"` or `"bump_added"`.
    pub reading: &'static str,
}
