//! [`Nubmp`]'s words: the shape-parameter sliders with their variation-diminishing
//! bands, the reset button, the template, and the `inspect` report (the structure of paper
//! 001's curve: coefficients, groups, variation-diminishing ranges).

use glam::DVec3;
use schemars::JsonSchema;
use serde::Serialize;
use splinescope_core::geom::bspline::elevation_coefficients;
use splinescope_core::geom::{GeomError, KnotVector, Nubmp, Xyz, xyz};

use splinescope_core::geom::Family;

use crate::Present;
use crate::controls::{
    Control, ControlError, ControlId, ControlKind, ControlValue, unknown_control,
};
use splinescope_encoding::draw::{OverlayKind, OverlayPolyline};

impl Present for Nubmp {
    type Details = NubmpDetails;

    fn templates(center: DVec3, size: f64) -> Vec<(&'static str, Nubmp)> {
        let points = crate::template::zigzag(center, size, 7);
        Nubmp::try_new(points, crate::template::clamped_knots(7, 4), 4)
            .map(|n| vec![("NUBMP (order 4)", n)])
            .unwrap_or_default()
    }

    /// The parameters that differ from the standard curve's (the first three, then a
    /// count); `None` for the standard curve.
    fn parameter_text(&self) -> Option<String> {
        let changed: Vec<String> = self
            .groups()
            .iter()
            .enumerate()
            .flat_map(|(j, g)| {
                g.members
                    .iter()
                    .zip(g.values.iter().zip(&g.standard))
                    .filter(|(_, (a, c))| a != c)
                    .map(move |(i, (a, _))| {
                        format!("a^{i}_{j} = {}", crate::text::short_number(*a))
                    })
            })
            .collect();
        match changed.len() {
            0 => None,
            n if n <= 3 => Some(changed.join(", ")),
            n => Some(format!("{}, … ({n} changed)", changed[..3].join(", "))),
        }
    }

    /// The control polygon and the dual polygon `P*_j`.
    fn overlays(&self) -> Vec<OverlayPolyline> {
        vec![
            OverlayPolyline::control_polygon(self.points()),
            OverlayPolyline {
                kind: OverlayKind::DualPolygon,
                points: self.dual_points().to_vec(),
            },
        ]
    }

    fn summary(&self) -> String {
        format!(
            "order {}, {} groups, {} free parameters",
            self.order(),
            self.groups().len(),
            self.free_parameter_count()
        )
    }

    fn details(&self) -> Result<NubmpDetails, GeomError> {
        Ok(NubmpDetails {
            spline: SplineDetails::of(self.knots()),
            structure: NubmpStructure::of(self),
        })
    }

    /// A slider per shape parameter of every effective group (the group's last member
    /// absorbs the change), with Theorem 1's value and the permissible ranges for order 4.
    fn controls(&self) -> Vec<Control> {
        // The reset button is always listed (pressing it on the standard curve changes
        // nothing), so that the panel does not gain a row in the middle of a drag.
        let mut out = vec![Control {
            id: ControlId::new("reset"),
            label: "reset to the standard curve".into(),
            hint: Some(if self.is_standard() {
                "already the standard curve".into()
            } else {
                "every a^i_j back to its standard value c^i_j".into()
            }),
            kind: ControlKind::Action,
        }];
        for (j, g) in self.groups().iter().enumerate() {
            if !g.effective || g.members.len() < 2 {
                continue;
            }
            let vd = self.vd_value(j);
            out.push(Control::note(
                match vd {
                    Some(v) if v > 1.0 => format!(
                        "A_{j}: outside the variation-diminishing range (Theorem 1 value {v:.3} > 1)"
                    ),
                    Some(v) => format!(
                        "A_{j}: variation diminishing (Theorem 1 value {v:.3} ≤ 1)"
                    ),
                    None => format!("A_{j}"),
                },
                vd.is_some_and(|v| v > 1.0),
            ));
            let last = g.members[g.members.len() - 1];
            for &i in &g.members[..g.members.len() - 1] {
                let (Some(a), Some(b)) = (g.value(i), g.value(last)) else {
                    continue;
                };
                let bands: Vec<(f64, f64)> = self
                    .vd_bands(j, i, last)
                    .unwrap_or_default()
                    .into_iter()
                    .map(|r| (r.min, r.max))
                    .collect();
                let listed = bands
                    .iter()
                    .map(|(lo, hi)| format!("[{lo:.4}, {hi:.4}]"))
                    .collect::<Vec<_>>()
                    .join(" ∪ ");
                let inside = bands.iter().any(|&(lo, hi)| lo <= a && a <= hi);
                let hint = if bands.is_empty() {
                    format!("a^{last}_{j} absorbs")
                } else if inside {
                    format!("VD range {listed} (a^{last}_{j} absorbs)")
                } else {
                    format!("outside its VD range {listed} (a^{last}_{j} absorbs)")
                };
                out.push(Control {
                    id: ControlId {
                        key: "a",
                        index: [i, j],
                    },
                    label: format!("a^{i}_{j}"),
                    hint: Some(hint),
                    kind: ControlKind::Number {
                        value: a,
                        range: (0.0, a + b),
                        bands,
                    },
                });
            }
        }
        out
    }

    fn apply_control(&self, id: ControlId, value: ControlValue) -> Result<Nubmp, ControlError> {
        match (id.key, value) {
            ("reset", ControlValue::Press) => Ok(Nubmp::standard(
                self.points().to_vec(),
                self.knots().clone(),
            )?),
            ("a", ControlValue::Number(a)) => {
                let [i, j] = id.index;
                let last = *self.group(j)?.members.last().unwrap_or(&i);
                let mut next = self.clone();
                next.set_parameter(j, i, a, last)?;
                Ok(next)
            }
            _ => Err(unknown_control(Self::NAME, id, value)),
        }
    }
}

/// The knot data `inspect` reports for B-splines and NUBMP curves.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct SplineDetails {
    /// `k` (degree `k − 1`).
    pub order: usize,
    /// The knot vector `T`.
    pub knots: Vec<f64>,
    /// Whether the end knots have multiplicity `k`.
    pub clamped: bool,
}

impl SplineDetails {
    /// The data of `knots`.
    #[must_use]
    pub fn of(knots: &KnotVector) -> SplineDetails {
        SplineDetails {
            order: knots.order(),
            knots: knots.knots().to_vec(),
            clamped: knots.is_clamped(),
        }
    }
}

/// What `inspect` reports for a NUBMP curve.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct NubmpDetails {
    /// The knots.
    #[serde(flatten)]
    pub spline: SplineDetails,
    /// The multiple-shape-parameter structure.
    #[serde(flatten)]
    pub structure: NubmpStructure,
}

/// The highest order for which `inspect` reports the elevation coefficients as exact
/// rationals (above it, `exact_omitted` says so; the `f64` values are always there).
pub const EXACT_MAX_ORDER: usize = 16;

/// The most control points for which `inspect` reports exact rational coefficients.
pub const EXACT_MAX_POINTS: usize = 10_000;

/// Paper 001's structure of a NUBMP curve: the refined knots `T*`, the degree-elevation
/// coefficients `c^i_j` (Eq. 6), the groups with their parameters, and the dual points.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct NubmpStructure {
    /// `T*`.
    pub refined_knots: Vec<f64>,
    /// Why exact coefficients are missing, when they are.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exact_omitted: Option<String>,
    /// `"decimal knots"` (exact from the file's decimals) or `"binary f64 knots"`.
    pub exact_from: &'static str,
    /// One row per control point `i`: `c^i_j` for `j = first_group..`.
    pub coefficients: Vec<CoefficientReport>,
    /// The number of free shape parameters.
    pub free_parameters: usize,
    /// `P*_j`.
    pub dual_points: Vec<Xyz>,
    /// The groups `A_j`.
    pub groups: Vec<GroupReport>,
}

/// One row of elevation coefficients.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct CoefficientReport {
    /// The control point `i`.
    pub i: usize,
    /// The first group `j` of the row.
    pub first_group: usize,
    /// `c^i_j` in `f64`.
    pub values: Vec<f64>,
    /// `c^i_j` as exact rationals.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exact: Option<Vec<String>>,
}

/// One group as `inspect` reports it.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct GroupReport {
    /// `j`.
    pub group: usize,
    /// Its members `i`.
    pub members: Vec<usize>,
    /// The standard values `c^i_j`.
    pub standard: Vec<f64>,
    /// The current values `a^i_j`.
    pub values: Vec<f64>,
    /// Whether the group affects the curve on its domain.
    pub effective: bool,
    /// The parameter spans it affects.
    pub affected_spans: Vec<[f64; 2]>,
    /// Order 4: Theorem 1's value (`null` when the group has no such condition).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vd: Option<Option<f64>>,
    /// Order 4: the permissible range of each member with each absorber.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub permissible_ranges: Option<Vec<RangeReport>>,
}

/// A permissible range (`null` ends: the current value violates a condition).
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct RangeReport {
    /// The changed member.
    pub member: usize,
    /// The absorbing member.
    pub absorber: usize,
    /// The least permissible value.
    pub min: Option<f64>,
    /// The greatest.
    pub max: Option<f64>,
}

impl NubmpStructure {
    /// The structure of `n`. Exact rationals cost about order⁴ big-number operations per
    /// coefficient: they are computed up to [`EXACT_MAX_ORDER`], the `f64` values always.
    #[must_use]
    pub fn of(n: &Nubmp) -> NubmpStructure {
        use splinescope_core::geom::exact::format_rational;
        let exact = (n.order() <= EXACT_MAX_ORDER && n.points().len() <= EXACT_MAX_POINTS)
            .then(|| n.exact_coefficients());
        let exact_omitted = exact.is_none().then(|| {
            format!(
                "exact rational coefficients are computed up to order {EXACT_MAX_ORDER} and {EXACT_MAX_POINTS} points; this curve has order {} and {} points",
                n.order(),
                n.points().len()
            )
        });
        let rows = elevation_coefficients(n.knots().knots(), n.order()).rows;
        let coefficients = rows
            .into_iter()
            .enumerate()
            .map(|(i, row)| CoefficientReport {
                i,
                first_group: row.first,
                values: row.values,
                exact: exact
                    .as_ref()
                    .map(|e| e.rows[i].values.iter().map(format_rational).collect()),
            })
            .collect();
        NubmpStructure {
            refined_knots: n.refined_knots().knots().to_vec(),
            exact_omitted,
            exact_from: if n.knots().has_exact() {
                "decimal knots"
            } else {
                "binary f64 knots"
            },
            coefficients,
            free_parameters: n.free_parameter_count(),
            dual_points: xyz(n.dual_points()),
            groups: (0..n.groups().len()).map(|j| group_report(n, j)).collect(),
        }
    }
}

/// One group's report.
fn group_report(n: &Nubmp, j: usize) -> GroupReport {
    let g = &n.groups()[j];
    let order4 = n.order() == 4;
    let ranges = order4.then(|| {
        let mut ranges = Vec::new();
        for &i in &g.members {
            for &l in &g.members {
                if i == l {
                    continue;
                }
                if let Ok(r) = n.permissible_range(j, i, l) {
                    ranges.push(RangeReport {
                        member: i,
                        absorber: l,
                        min: r.map(|r| r.min),
                        max: r.map(|r| r.max),
                    });
                }
            }
        }
        ranges
    });
    GroupReport {
        group: j,
        members: g.members.clone(),
        standard: g.standard.clone(),
        values: g.values.clone(),
        effective: g.effective,
        affected_spans: n
            .affected_spans(j)
            .into_iter()
            .map(|(a, b)| [a, b])
            .collect(),
        vd: order4.then(|| n.vd_value(j)),
        permissible_ranges: ranges,
    }
}
