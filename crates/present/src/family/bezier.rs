//! [`Bezier`]'s words: the elevate button, the template, the `inspect` report (power
//! basis, paper 000 §2.3's polygon type of a cubic).

use glam::DVec3;
use schemars::JsonSchema;
use serde::Serialize;
use splinescope_core::geom::cubic_region::CubicRegion;
use splinescope_core::geom::{Bezier, GeomError, Xyz};

use splinescope_core::geom::Family;

use crate::Present;
use crate::controls::{Control, ControlError, ControlId, ControlValue, unknown_control};
use splinescope_encoding::draw::OverlayPolyline;

impl Present for Bezier {
    type Details = BezierDetails;

    fn templates(center: DVec3, size: f64) -> Vec<(&'static str, Bezier)> {
        vec![(
            "Bézier (cubic)",
            Bezier::new(crate::template::arch(center, size)),
        )]
    }

    fn overlays(&self) -> Vec<OverlayPolyline> {
        vec![OverlayPolyline::control_polygon(self.points())]
    }

    fn summary(&self) -> String {
        format!("degree {}", self.degree())
    }

    fn details(&self) -> Result<BezierDetails, GeomError> {
        let (cubic_region, cubic_region_unavailable) = if self.degree() == 3 {
            // Paper 000 §2.3's classification of the control polygon.
            match self.end_directions() {
                Some(directions) => {
                    let region = CubicRegion::from_cubic(self.points(), directions);
                    let (subtype, meets) = region.subtype();
                    (
                        Some(CubicRegionReport {
                            kind: region.kind.number(),
                            subtype,
                            lines_meet_at: meets.map(|p| p.to_array()),
                        }),
                        None,
                    )
                }
                None => (
                    None,
                    Some(
                        "an end point coincides with its neighbour: the end tangent direction is undefined"
                            .to_owned(),
                    ),
                ),
            }
        } else {
            (None, None)
        };
        Ok(BezierDetails {
            degree: self.degree(),
            power_basis: (self.degree() <= POWER_BASIS_MAX_DEGREE)
                .then(|| power_basis(self.points())),
            cubic_region,
            cubic_region_unavailable,
        })
    }

    fn controls(&self) -> Vec<Control> {
        vec![Control::elevate()]
    }

    fn apply_control(&self, id: ControlId, value: ControlValue) -> Result<Bezier, ControlError> {
        match (id.key, value) {
            ("elevate", ControlValue::Press) => Ok(self.elevate()),
            _ => Err(unknown_control(Self::NAME, id, value)),
        }
    }
}

/// What `inspect` reports for a Bézier curve.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct BezierDetails {
    /// `n`.
    pub degree: usize,
    /// The power-basis coefficients, up to degree [`POWER_BASIS_MAX_DEGREE`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub power_basis: Option<PowerBasis>,
    /// For a cubic: paper 000 §2.3's polygon type.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cubic_region: Option<CubicRegionReport>,
    /// For a cubic without end tangents: why there is no type.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cubic_region_unavailable: Option<String>,
}

/// A cubic's polygon type (paper 000 §2.3) as `inspect` reports it.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct CubicRegionReport {
    /// 1, 2 or 3.
    #[serde(rename = "type")]
    pub kind: u8,
    /// The finer classification ([`CubicRegion::subtype`]).
    pub subtype: &'static str,
    /// Where the legs' lines meet, when they do.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lines_meet_at: Option<Xyz>,
}

/// The highest degree for which `inspect` reports a Bézier curve's power-basis
/// coefficients (their binomial factors grow as 2ⁿ).
pub const POWER_BASIS_MAX_DEGREE: usize = 64;

/// The power-basis coefficients `a_k` of `P(t) = Σ_k a_k t^k`.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct PowerBasis {
    /// Each `a_k` as exact rationals (`"p/q"`) per coordinate.
    pub exact: Vec<[String; 3]>,
    /// Each `a_k` rounded to `f64`; absent when some coefficient is beyond `f64`'s range
    /// (the binomial factors multiply coordinates near ±1.8e308 past it), and then
    /// `values_unavailable` names it and `exact` alone holds the coefficients.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub values: Option<Vec<Xyz>>,
    /// Why `values` is absent: the first coefficient beyond `f64`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub values_unavailable: Option<String>,
}

/// `a_k = C(n,k) Σ_{i≤k} (−1)^{k−i} C(k,i) P_i`, as exact rationals of each coordinate's
/// shortest decimal form (the decimal written in the scene file, for inputs of up to 15
/// significant digits) and, when every one is within its range, as `f64`.
fn power_basis(pts: &[DVec3]) -> PowerBasis {
    use splinescope_core::geom::exact::{Rational, Scalar, format_rational, parse_decimal};
    let n = pts.len() - 1;
    let exact: Vec<[Rational; 3]> = pts
        .iter()
        .map(|p| {
            p.to_array().map(|c| {
                parse_decimal(&splinescope_core::num::Num(c).to_string())
                    .unwrap_or_else(|| unreachable!("a finite coordinate's decimal parses"))
            })
        })
        .collect();
    let binomial = |n: usize, k: usize| -> Rational {
        let mut b = Rational::one();
        for j in 0..k {
            b = b * Rational::from_integer((n - j).into()) / Rational::from_integer((j + 1).into());
        }
        b
    };
    let coefficients: Vec<[Rational; 3]> = (0..=n)
        .map(|k| {
            let mut sum = [Rational::zero(), Rational::zero(), Rational::zero()];
            for (i, p) in exact.iter().enumerate().take(k + 1) {
                let sign = if (k - i) % 2 == 0 {
                    Rational::one()
                } else {
                    -Rational::one()
                };
                let w = binomial(k, i) * sign;
                for (s, c) in sum.iter_mut().zip(p) {
                    *s = s.clone() + w.clone() * c.clone();
                }
            }
            let ck = binomial(n, k);
            sum.map(|s| s * ck.clone())
        })
        .collect();
    let values: Vec<Xyz> = coefficients
        .iter()
        .map(|c| c.clone().map(|r| r.to_f64()))
        .collect();
    let beyond = values.iter().enumerate().find_map(|(k, a)| {
        let axis = a.iter().position(|v| !v.is_finite())?;
        Some(format!(
            "a_{k}.{} is beyond the range of f64 (±1.8e308); `exact` holds every coefficient",
            ["x", "y", "z"][axis]
        ))
    });
    PowerBasis {
        exact: coefficients
            .iter()
            .map(|c| c.clone().map(|r| format_rational(&r)))
            .collect(),
        values: beyond.is_none().then_some(values),
        values_unavailable: beyond,
    }
}
