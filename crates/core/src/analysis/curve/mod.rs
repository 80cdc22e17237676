//! The questions asked of one curve, answered on its lowered segments ([`Piece`]) and put
//! back in the curve's own parameter.

use glam::DVec3;
use thiserror::Error;

mod length;
mod nearest;

pub use length::bezier_length;
pub use nearest::Nearest;

use super::piece::Piece;
use super::quadrature::integrate;
use crate::geom::{Aabb, BezierSegment, Lower};
use crate::num::Num;
use crate::poly;
use crate::poly::roots::{bernstein_roots, bernstein_roots_with_noise};

/// Why a question cannot be answered.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum AnalysisError {
    /// The accuracy is not a finite number greater than 0.
    #[error("accuracy {}: must be a finite number greater than 0", Num(*.0))]
    Accuracy(f64),
    /// A parameter outside the curve's domain (or not a number).
    #[error("{what} = {}: outside the domain [{}, {}] of the curve", Num(*value), Num(*start), Num(*end))]
    OutsideDomain {
        /// Which argument.
        what: &'static str,
        /// Its value.
        value: f64,
        /// The domain's start.
        start: f64,
        /// The domain's end.
        end: f64,
    },
    /// A question for planar curves asked of a curve with `z ≠ 0`.
    #[error(
        "{what} are defined for planar (2D) curves; this curve leaves the plane z = 0 (a 3D curve has no sign of curvature to change)"
    )]
    NotPlanar {
        /// The question.
        what: &'static str,
    },
    /// An arc length beyond the curve's.
    #[error("arc length {}: outside [0, {}], the curve's length", Num(*s), Num(*length))]
    BeyondLength {
        /// The length asked for.
        s: f64,
        /// The curve's length.
        length: f64,
    },
    /// An arc length the quadrature could not resolve: the speed is not finite somewhere
    /// in the range (weights whose ratio overflows), or the error bound stayed above the
    /// accuracy and the rounding of the value within the work budget.
    #[error(
        "arc length from t = {} to {}: not resolved to the accuracy {} (the estimate {} has an error bound {}; the speed overflows or varies faster than the quadrature can follow)",
        Num(*t0), Num(*t1), Num(*accuracy), Num(*value), Num(*error)
    )]
    Unresolved {
        /// The range's start.
        t0: f64,
        /// The range's end.
        t1: f64,
        /// The accuracy asked for.
        accuracy: f64,
        /// The estimate.
        value: f64,
        /// Its error bound.
        error: f64,
    },
    /// A value beyond the largest double: the curve's coordinates are too large for it.
    #[error(
        "the {what} overflows: the curve's control points span {}, too large for it to be a finite double",
        Num(*size)
    )]
    Overflow {
        /// The quantity.
        what: &'static str,
        /// The diagonal of the control points' box.
        size: f64,
    },
    /// A point asked about that is not finite.
    #[error("the point ({}, {}, {}) is not finite", Num(point.x), Num(point.y), Num(point.z))]
    NotFinitePoint {
        /// The point.
        point: DVec3,
    },
    /// A line given by two equal points.
    #[error("the line's two points are equal ({point}): they give no direction")]
    DegenerateLine {
        /// The point.
        point: DVec3,
    },
    /// Coordinates too large for a question whose squared distances would overflow.
    #[error(
        "{what} are computed for coordinates below 2^400 (about 1e120); this curve reaches {}",
        Num(*magnitude)
    )]
    TooLarge {
        /// The question.
        what: &'static str,
        /// The largest coordinate.
        magnitude: f64,
    },
    /// A line whose two points are so close that positions along it (multiples of
    /// `q − p`) overflow.
    #[error(
        "the line's direction q − p = ({}, {}) is too short: a hit's position along it (λ in p + λ (q − p)) would exceed the largest double",
        Num(direction.x),
        Num(direction.y)
    )]
    ShortLine {
        /// `q − p`.
        direction: DVec3,
    },
    /// Two curves running so close to each other, over a stretch, that the subdivision
    /// cannot tell their points apart within its work bound: closer than its flatness
    /// resolution, yet neither one tangency nor coincident within the point resolution.
    /// What was found is not known to be all, so none of it is returned.
    #[error(
        "intersections: {}the curves run within the resolution of each other near s ∈ [{}, {}], t ∈ [{}, {}] without coinciding; their meeting points there cannot be separated within {leaves} subdivision leaves (nearly coincident curves: move one by more than about 1e-10 of their size, or compare them as overlapping)",
        Pair(*pair), Num(s.0), Num(s.1), Num(t.0), Num(t.1)
    )]
    Crowded {
        /// The two curves' indices, when the question was asked of many curves.
        pair: Option<(usize, usize)>,
        /// The first curve's parameter range where the subdivision stopped.
        s: (f64, f64),
        /// The second curve's.
        t: (f64, f64),
        /// The work bound reached.
        leaves: usize,
    },
}

/// "curves i and j: " where a pair of many is named, else nothing.
struct Pair(Option<(usize, usize)>);

impl std::fmt::Display for Pair {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.0 {
            Some((i, j)) => write!(f, "curves {i} and {j}: "),
            None => Ok(()),
        }
    }
}

/// An arc length and the bound on its error kept by the quadrature.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Length {
    /// The length (negative when `t1 < t0`).
    pub value: f64,
    /// A bound on its error (the requested accuracy unless rounding forbade it).
    pub error: f64,
}

/// A parameter where one coordinate's derivative vanishes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extremum {
    /// The curve parameter.
    pub t: f64,
    /// The coordinate: 0 (x), 1 (y) or 2 (z).
    pub axis: usize,
    /// The point there.
    pub point: DVec3,
}

/// Whether a curvature extremum is a local maximum or minimum of the signed curvature.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExtremumKind {
    /// A local maximum of `κ`.
    Maximum,
    /// A local minimum of `κ`.
    Minimum,
}

/// A local extremum of the signed curvature (a "vertex").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurvatureExtremum {
    /// The curve parameter.
    pub t: f64,
    /// The signed curvature there (2D: positive where the curve turns left); its
    /// magnitude `|κ|` is what [`CurvatureExtremum::kind`] is an extremum of.
    pub curvature: f64,
    /// Maximum or minimum of the curvature's magnitude `|κ|`, as a designer names them:
    /// the sharpest point of a bend is a maximum, whichever way it turns. (The zeros of
    /// `κ`, where it changes sign, are inflections, not minima.)
    pub kind: ExtremumKind,
    /// The point there.
    pub point: DVec3,
}

/// How a curve meets a line or another curve at a point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HitKind {
    /// The curves cross transversally: their tangents differ.
    Crossing,
    /// The curves share a tangent line there: a contact of any order, whether they then
    /// cross (odd order) or touch (even).
    Tangent,
}

/// A curve meeting a line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineHit {
    /// The curve parameter.
    pub t: f64,
    /// The line's parameter: the point is `p + λ (q − p)`.
    pub lambda: f64,
    /// The point.
    pub point: DVec3,
    /// Crossing or tangent.
    pub kind: HitKind,
    /// A bound on the error of `t`.
    pub error: f64,
}

/// Where a curve meets a line.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LineIntersections {
    /// The points, by the curve's parameter.
    pub hits: Vec<LineHit>,
    /// The curve's parameter ranges lying on the line.
    pub overlaps: Vec<(f64, f64)>,
}

/// One curve, lowered, ready to be asked.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveAnalysis {
    pieces: Vec<Piece>,
    domain: (f64, f64),
    planar: bool,
    /// Per piece, the local minima of its speed inside `(0, 1)` with the width `δ` of
    /// the dip (where the arc length's integrand is cut).
    speed_minima: Vec<Vec<(f64, f64)>>,
    /// For a curve whose coordinates lie near the ends of the double range: the exponent
    /// `e` and the curve scaled by `2^e` (built from its control points scaled exactly,
    /// before any product with a weight could overflow or fall into the subnormals), at
    /// which its lengths and box are measured.
    rescaled: Option<(i32, Box<CurveAnalysis>)>,
}

/// The default accuracy of lengths: absolute, in the curve's units.
pub const DEFAULT_ACCURACY: f64 = 1e-12;

/// Refuses a parameter outside `(a, b)` (or NaN), naming it.
fn check_in((a, b): (f64, f64), what: &'static str, t: f64) -> Result<f64, AnalysisError> {
    if t >= a && t <= b {
        Ok(t)
    } else {
        Err(AnalysisError::OutsideDomain {
            what,
            value: t,
            start: a,
            end: b,
        })
    }
}

fn check_accuracy(accuracy: f64) -> Result<f64, AnalysisError> {
    if accuracy.is_finite() && accuracy > 0.0 {
        Ok(accuracy)
    } else {
        Err(AnalysisError::Accuracy(accuracy))
    }
}

impl CurveAnalysis {
    /// The analysis of `curve` (its exact Bézier segments).
    #[must_use]
    pub fn new(curve: &impl Lower) -> CurveAnalysis {
        let segments = curve.lower();
        let mut out = CurveAnalysis::of_segments(&segments, curve.domain());
        // Coordinates near the ends of the double range (beyond 2^±400, where squares
        // overflow or vanish): the same curve at a scale of 1, by a power of two.
        let m = segments
            .iter()
            .flat_map(|s| s.points().iter())
            .fold(0.0_f64, |m, p| m.max(p.abs().max_element()));
        if m.is_finite() && m > 0.0 && (m >= 2f64.powi(400) || m <= 2f64.powi(-400)) {
            let e = -(m.log2().floor() as i32);
            let scaled: Vec<BezierSegment> = segments
                .iter()
                .map(|s| BezierSegment {
                    bezier: crate::geom::Bezier::new(
                        s.points()
                            .iter()
                            .map(|p| {
                                DVec3::new(
                                    crate::num::scale_by_power_of_two(p.x, e),
                                    crate::num::scale_by_power_of_two(p.y, e),
                                    crate::num::scale_by_power_of_two(p.z, e),
                                )
                            })
                            .collect(),
                    ),
                    weights: s.weights.clone(),
                    t0: s.t0,
                    t1: s.t1,
                })
                .collect();
            out.rescaled = Some((
                e,
                Box::new(CurveAnalysis::of_segments(&scaled, curve.domain())),
            ));
        }
        out
    }

    /// The analysis of these segments over `domain`, as they are.
    fn of_segments(segments: &[BezierSegment], domain: (f64, f64)) -> CurveAnalysis {
        let pieces: Vec<Piece> = segments.iter().map(Piece::new).collect();
        let planar = pieces.iter().all(Piece::is_planar);
        // Pieces with an a-priori bound (planar polynomial ones) need no cuts.
        let speed_minima = pieces
            .iter()
            .map(|p| {
                if p.planar_speed().is_some() {
                    Vec::new()
                } else {
                    p.speed_minima()
                }
            })
            .collect();
        CurveAnalysis {
            pieces,
            domain,
            planar,
            speed_minima,
            rescaled: None,
        }
    }

    /// For a curve whose coordinates lie near the ends of the double range, the exponent
    /// `e` and the curve scaled by `2^e` (coordinates about 1); `None` otherwise.
    pub(crate) fn rescaled(&self) -> Option<(i32, &CurveAnalysis)> {
        self.rescaled.as_ref().map(|(e, c)| (*e, c.as_ref()))
    }

    /// Refuses a curve whose coordinates reach beyond `2^400` (about `1e120`) for a
    /// question whose squares of distances would overflow (intersections).
    pub(crate) fn require_moderate(&self, what: &'static str) -> Result<(), AnalysisError> {
        let m = self
            .pieces
            .iter()
            .map(Piece::magnitude)
            .fold(0.0_f64, f64::max);
        if m.is_finite() && m < 2f64.powi(400) {
            Ok(())
        } else {
            Err(AnalysisError::TooLarge { what, magnitude: m })
        }
    }

    /// The segments.
    #[must_use]
    pub fn pieces(&self) -> &[Piece] {
        &self.pieces
    }

    /// The parameter domain.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        self.domain
    }

    /// Whether every point has `z = 0`.
    #[must_use]
    pub fn is_planar(&self) -> bool {
        self.planar
    }

    /// Refuses a parameter outside the domain (or NaN), naming it.
    ///
    /// # Errors
    /// [`AnalysisError::OutsideDomain`].
    pub fn check_t(&self, what: &'static str, t: f64) -> Result<f64, AnalysisError> {
        check_in(self.domain, what, t)
    }

    fn require_planar(&self, what: &'static str) -> Result<(), AnalysisError> {
        if self.planar {
            Ok(())
        } else {
            Err(AnalysisError::NotPlanar { what })
        }
    }

    /// The piece holding `t` and the local parameter (a joint belongs to the later piece,
    /// the domain's end to the last).
    fn locate(&self, t: f64) -> (usize, f64) {
        let k = self
            .pieces
            .partition_point(|p| p.t0 <= t)
            .saturating_sub(1)
            .min(self.pieces.len().saturating_sub(1));
        (k, self.pieces[k].u_of(t))
    }

    /// The point at `t`.
    #[must_use]
    pub fn point(&self, t: f64) -> DVec3 {
        if self.pieces.is_empty() {
            return DVec3::ZERO;
        }
        let (k, u) = self.locate(t);
        self.pieces[k].point(u)
    }

    /// The first derivative with respect to the curve parameter at `t`.
    #[must_use]
    pub fn deriv(&self, t: f64) -> DVec3 {
        if self.pieces.is_empty() {
            return DVec3::ZERO;
        }
        let (k, u) = self.locate(t);
        let p = &self.pieces[k];
        p.deriv(u) / (p.t1 - p.t0)
    }

    /// The second derivative with respect to the curve parameter at `t`.
    #[must_use]
    pub fn second_deriv(&self, t: f64) -> DVec3 {
        if self.pieces.is_empty() {
            return DVec3::ZERO;
        }
        let (k, u) = self.locate(t);
        let p = &self.pieces[k];
        let h = p.t1 - p.t0;
        p.second_deriv(u) / (h * h)
    }

    /// The parameters strictly inside the domain where one coordinate's derivative
    /// vanishes (for a rational segment, the numerator of the quotient rule), by axis
    /// then parameter; 2 axes for a planar curve, 3 otherwise.
    #[must_use]
    pub fn extrema(&self) -> Vec<Extremum> {
        if let Some((e, scaled)) = self.rescaled() {
            let back = |p: DVec3| p.map(|x| crate::num::scale_by_power_of_two(x, -e));
            return scaled
                .extrema()
                .into_iter()
                .map(|x| Extremum {
                    point: back(x.point),
                    ..x
                })
                .collect();
        }
        let dims = if self.planar { 2 } else { 3 };
        let (a, b) = self.domain;
        let mut out: Vec<Extremum> = Vec::new();
        for axis in 0..dims {
            // (t, the point where it is known more closely than at t)
            let mut ts: Vec<(f64, Option<DVec3>)> = Vec::new();
            for p in &self.pieces {
                if p.weights_far_apart() {
                    // In the logistic parameter: its polynomials in u have lost the roots
                    // (and where u is not a double, the point stands at the nearest t).
                    let f: Vec<f64> = (0..=p.degree())
                        .map(|i| p.a(axis)[i] / p.w().map_or(1.0, |w| w[i]))
                        .collect();
                    let mut sigmas: Vec<f64> = p
                        .logistic_roots(&f, true)
                        .into_iter()
                        .map(|r| r.0)
                        .collect();
                    // Extremes where the coordinate levels off (no sign change shows).
                    let (end0, end1) = (f[0], f[f.len() - 1]);
                    let (smin, smax) = p.logistic_extremes(&f);
                    let at = |s: f64| p.point_logistic(s)[axis];
                    if at(smin) < end0.min(end1) {
                        sigmas.push(smin);
                    }
                    if at(smax) > end0.max(end1) {
                        sigmas.push(smax);
                    }
                    for sigma in sigmas {
                        let u = 1.0 / (1.0 + (-sigma).exp());
                        ts.push((p.t_of(u), Some(p.point_logistic(sigma))));
                    }
                    continue;
                }
                let roots = bernstein_roots(&p.deriv_numerator(axis));
                for r in roots.roots {
                    let t = p.t_of(r.t);
                    if t > a && t < b {
                        ts.push((t, None));
                    }
                }
            }
            ts.sort_by(|x, y| x.0.total_cmp(&y.0));
            ts.dedup_by(|x, y| {
                (x.0 - y.0).abs() <= 4.0 * f64::EPSILON * x.0.abs().max(1.0) && x.1 == y.1
            });
            out.extend(ts.into_iter().map(|(t, point)| Extremum {
                t,
                axis,
                point: point.unwrap_or_else(|| self.point(t)),
            }));
        }
        out
    }

    /// The tight axis-aligned box of the curve: its end points, the segments' joints and
    /// the points where a coordinate's derivative vanishes (not the control points' box).
    #[must_use]
    pub fn bounding_box(&self) -> Aabb {
        if let Some((e, scaled)) = self.rescaled() {
            let back = |p: DVec3| p.map(|x| crate::num::scale_by_power_of_two(x, -e));
            let b = scaled.bounding_box();
            return Aabb {
                min: back(b.min),
                max: back(b.max),
            };
        }
        let mut bbox = Aabb::EMPTY;
        let mut rest = false;
        for p in &self.pieces {
            bbox = bbox.including(p.point(0.0)).including(p.point(1.0));
            // Polynomial pieces of degree ≤ 3 in closed form; the others by the roots of
            // their derivatives below.
            match p.box_candidates() {
                Some((us, count)) => {
                    for &u in &us[..count] {
                        bbox = bbox.including(p.point(u));
                    }
                }
                None => rest = true,
            }
        }
        if rest {
            for e in self.extrema() {
                bbox = bbox.including(e.point);
            }
        }
        bbox
    }

    /// Whether the curve ends where it starts (within `1e−12` of its size).
    #[must_use]
    pub fn is_closed(&self) -> bool {
        let (a, b) = self.domain;
        let (p, q) = (self.point(a), self.point(b));
        // Componentwise, in halves: nothing squared or summed can overflow, whatever the
        // coordinates' size.
        let bbox = self.control_box();
        let half_extent = (0.5 * bbox.max - 0.5 * bbox.min).max_element();
        let gap = (0.5 * p - 0.5 * q).abs().max_element();
        gap <= 1e-12 * half_extent.max(f64::MIN_POSITIVE)
    }

    /// The box of every segment's control points (holds the curve).
    #[must_use]
    pub fn control_box(&self) -> Aabb {
        let mut bbox = Aabb::EMPTY;
        for p in &self.pieces {
            for i in 0..p.a(0).len() {
                let w = p.w().map_or(1.0, |w| w[i]);
                bbox = bbox.including(DVec3::new(p.a(0)[i], p.a(1)[i], p.a(2)[i]) / w);
            }
        }
        bbox
    }

    /// The signed area enclosed by the curve and, if it is open, the straight chord from
    /// its end back to its start: `½ ∮ (x dy − y dx)`, positive counter-clockwise. Exact
    /// but for rounding on polynomial segments (Green's theorem on the Bernstein form:
    /// `∫₀¹ (x y′ − y x′) du` is the mean of the product's coefficients); rational segments
    /// by quadrature to `1e−15` of the curve's size squared.
    ///
    /// # Errors
    /// [`AnalysisError::NotPlanar`] for a 3D curve; [`AnalysisError::Overflow`] where the
    /// area is beyond the largest double (coordinates near `10¹⁵⁴` and above).
    pub fn signed_area(&self) -> Result<f64, AnalysisError> {
        self.require_planar("signed areas")?;
        let size = self.control_box().diagonal();
        let mut twice = 0.0;
        for p in &self.pieces {
            match p.area_integrand() {
                Some(c) => twice += poly::integral(&c),
                None => {
                    let q = integrate(
                        |u| {
                            let c = p.point(u);
                            let d = p.deriv(u);
                            c.x * d.y - c.y * d.x
                        },
                        0.0,
                        1.0,
                        1e-15 * size * size,
                    );
                    twice += q.value;
                }
            }
        }
        let (a, b) = self.domain;
        let (start, end) = (self.point(a), self.point(b));
        twice += end.x * start.y - end.y * start.x;
        let area = 0.5 * twice;
        if area.is_finite() {
            Ok(area)
        } else {
            Err(AnalysisError::Overflow {
                what: "signed area",
                size,
            })
        }
    }

    /// The parameters where the velocity vanishes (`C′ = 0`): cusps and stationary points,
    /// strictly inside the domain.
    ///
    /// # Errors
    /// [`AnalysisError::NotPlanar`] for a 3D curve.
    pub fn cusps(&self) -> Result<Vec<f64>, AnalysisError> {
        self.require_planar("cusps")?;
        Ok(self.cusp_parameters())
    }

    fn cusp_parameters(&self) -> Vec<f64> {
        let (a, b) = self.domain;
        let mut out: Vec<f64> = Vec::new();
        for p in &self.pieces {
            let roots = bernstein_roots(&p.speed_squared_numerator(2));
            for r in roots.roots {
                let t = p.t_of(r.t);
                if t > a && t < b {
                    out.push(t);
                }
            }
        }
        out.sort_by(f64::total_cmp);
        out.dedup_by(|x, y| (*x - *y).abs() <= 1e-12 * (b - a));
        out
    }

    /// The inflections: parameters where `C′ × C″` changes sign (an odd-order root inside a
    /// segment, or a sign that differs across a joint), cusps excluded.
    ///
    /// # Errors
    /// [`AnalysisError::NotPlanar`] for a 3D curve.
    pub fn inflections(&self) -> Result<Vec<f64>, AnalysisError> {
        self.require_planar("inflections")?;
        let (a, b) = self.domain;
        let cusps = self.cusp_parameters();
        let near_cusp = |t: f64| cusps.iter().any(|c| (c - t).abs() <= 1e-9 * (b - a));
        let mut out: Vec<f64> = Vec::new();
        // The sign just inside each end of each segment's cross product.
        let mut ends: Vec<(f64, f64)> = Vec::with_capacity(self.pieces.len());
        for p in &self.pieces {
            let (c, noise) = p.cross_numerator();
            // Coefficients within the rounding have no sign (a straight stretch).
            let c: Vec<f64> = c
                .into_iter()
                .map(|v| if v.abs() <= noise { 0.0 } else { v })
                .collect();
            let sign = |v: Option<&f64>| v.map_or(0.0, |v| v.signum());
            ends.push((
                sign(c.iter().find(|v| **v != 0.0)),
                sign(c.iter().rev().find(|v| **v != 0.0)),
            ));
            for r in bernstein_roots_with_noise(&c, noise).roots {
                if r.multiplicity % 2 == 1 && r.t > 0.0 && r.t < 1.0 {
                    let t = p.t_of(r.t);
                    if t > a && t < b && !near_cusp(t) {
                        out.push(t);
                    }
                }
            }
        }
        for k in 1..self.pieces.len() {
            let (left, right) = (ends[k - 1].1, ends[k].0);
            let t = self.pieces[k].t0;
            if left != 0.0 && right != 0.0 && left != right && t > a && t < b && !near_cusp(t) {
                out.push(t);
            }
        }
        out.sort_by(f64::total_cmp);
        out.dedup_by(|x, y| (*x - *y).abs() <= 1e-12 * (b - a));
        Ok(out)
    }

    /// The signed curvature at `t` (2D): `(C′ × C″) / |C′|³`; `None` where `C′ = 0`.
    #[must_use]
    pub fn signed_curvature(&self, t: f64) -> Option<f64> {
        let (d1, d2) = (self.deriv(t), self.second_deriv(t));
        let k = crate::geom::curvature(d1, d2)?;
        Some(if d1.x * d2.y - d1.y * d2.x < 0.0 {
            -k
        } else {
            k
        })
    }

    /// The local extrema of the curvature's magnitude `|κ|` away from its zeros (the
    /// stationary points of `κ`, where `2F′G − 3FG′ = 0` with `κ = F/G^{3/2}`, inside
    /// segments and at joints where `κ` is continuous), cusps excluded, with the signed
    /// `κ` and whether `|κ|` is a maximum or a minimum there: where the curve turns
    /// right (`κ < 0`) a maximum of `κ` is a minimum of `|κ|`. A segment of constant
    /// curvature (a circular arc, a line) has none.
    ///
    /// # Errors
    /// [`AnalysisError::NotPlanar`] for a 3D curve.
    pub fn curvature_extrema(&self) -> Result<Vec<CurvatureExtremum>, AnalysisError> {
        self.require_planar("curvature extrema")?;
        let (a, b) = self.domain;
        let cusps = self.cusp_parameters();
        let mut out = Vec::new();
        // The slope's sign just inside each end of each segment (0: none there).
        let mut ends: Vec<(f64, f64)> = Vec::with_capacity(self.pieces.len());
        for p in &self.pieces {
            let (slope, noise) = p.curvature_slope_numerator();
            // Coefficients within the rounding are no sign at all (a circular arc).
            let slope: Vec<f64> = slope
                .into_iter()
                .map(|v| if v.abs() <= noise { 0.0 } else { v })
                .collect();
            let sign = |v: Option<&f64>| v.map_or(0.0, |v| v.signum());
            ends.push((
                sign(slope.iter().find(|v| **v != 0.0)),
                sign(slope.iter().rev().find(|v| **v != 0.0)),
            ));
            let roots = bernstein_roots_with_noise(&slope, noise);
            if roots.identically_zero {
                continue;
            }
            let rs: Vec<f64> = roots
                .roots
                .iter()
                .filter(|r| r.multiplicity % 2 == 1 && r.t > 0.0 && r.t < 1.0)
                .map(|r| r.t)
                .collect();
            for (i, &u) in rs.iter().enumerate() {
                let t = p.t_of(u);
                if !(t > a && t < b) || cusps.iter().any(|c| (c - t).abs() <= 1e-9 * (b - a)) {
                    continue;
                }
                // Which way κ goes: the sign of the slope numerator (G > 0) on each side,
                // a step short of the neighbouring roots.
                let left_room = if i == 0 { u } else { u - rs[i - 1] };
                let right_room = if i + 1 == rs.len() {
                    1.0 - u
                } else {
                    rs[i + 1] - u
                };
                let h = (0.25 * left_room.min(right_room)).min(1e-3);
                let before = poly::eval(&slope, u - h);
                let after = poly::eval(&slope, u + h);
                let kind = match (before > 0.0, after > 0.0) {
                    (true, false) => ExtremumKind::Maximum,
                    (false, true) => ExtremumKind::Minimum,
                    _ => continue,
                };
                let Some(curvature) = self.signed_curvature(t) else {
                    continue;
                };
                out.push(CurvatureExtremum {
                    t,
                    curvature,
                    kind: of_magnitude(kind, curvature),
                    point: self.point(t),
                });
            }
        }
        // A joint where the slope changes sign and κ is continuous (a joint where κ
        // jumps, as at the knots of a C¹ spline, is not a stationary point).
        for k in 1..self.pieces.len() {
            let t = self.pieces[k].t0;
            let (left, right) = (ends[k - 1].1, ends[k].0);
            let kind = match (left, right) {
                (l, r) if l > 0.0 && r < 0.0 => ExtremumKind::Maximum,
                (l, r) if l < 0.0 && r > 0.0 => ExtremumKind::Minimum,
                _ => continue,
            };
            if !(t > a && t < b) || cusps.iter().any(|c| (c - t).abs() <= 1e-9 * (b - a)) {
                continue;
            }
            let (prev, next) = (&self.pieces[k - 1], &self.pieces[k]);
            let side = |p: &Piece, u: f64| {
                let h = p.t1 - p.t0;
                let (d1, d2) = (p.deriv(u) / h, p.second_deriv(u) / (h * h));
                crate::geom::curvature(d1, d2).map(|k| {
                    if d1.x * d2.y - d1.y * d2.x < 0.0 {
                        -k
                    } else {
                        k
                    }
                })
            };
            let (Some(kl), Some(kr)) = (side(prev, 1.0), side(next, 0.0)) else {
                continue;
            };
            if (kl - kr).abs() > 1e-9 * kl.abs().max(kr.abs()) {
                continue;
            }
            out.push(CurvatureExtremum {
                t,
                curvature: kr,
                kind: of_magnitude(kind, kr),
                point: self.point(t),
            });
        }
        out.sort_by(|x, y| x.t.total_cmp(&y.t));
        Ok(out)
    }

    /// Where the curve meets the line through `p` and `q` (2D): each segment's signed
    /// distance `(A − pW) × (q − p)` in Bernstein form, its roots; a double root is a
    /// tangency. Segments lying on the line are reported as overlaps (their parameter
    /// ranges, joined).
    ///
    /// # Errors
    /// [`AnalysisError`] for a 3D curve or `p = q`.
    pub fn intersect_line(&self, p: DVec3, q: DVec3) -> Result<LineIntersections, AnalysisError> {
        self.require_planar("intersections")?;
        let d = q - p;
        if d.x == 0.0 && d.y == 0.0 {
            return Err(AnalysisError::DegenerateLine { point: p });
        }
        // The direction scaled to a largest component of 1 (exactly enough: the signed
        // distances only need its direction), so that a tiny or huge `q − p` neither
        // vanishes nor overflows in them; positions along the line divide by the scale.
        let m = d.x.abs().max(d.y.abs());
        let dn = DVec3::new(d.x / m, d.y / m, 0.0);
        let lambda = |point: DVec3| -> Result<f64, AnalysisError> {
            let l = (point - p).dot(dn) / dn.length_squared() / m;
            if l.is_finite() {
                Ok(l)
            } else {
                Err(AnalysisError::ShortLine { direction: d })
            }
        };
        let mut hits: Vec<LineHit> = Vec::new();
        let mut overlaps: Vec<(f64, f64)> = Vec::new();
        for piece in &self.pieces {
            let n = piece.a(0).len();
            if piece.weights_far_apart() {
                // In the logistic parameter (its polynomial in u has lost the roots).
                let f: Vec<f64> = (0..n)
                    .map(|i| {
                        let w = piece.w().map_or(1.0, |w| w[i]);
                        let (x, y) = (piece.a(0)[i] / w - p.x, piece.a(1)[i] / w - p.y);
                        x * dn.y - y * dn.x
                    })
                    .collect();
                if f.iter().all(|v| *v == 0.0) {
                    match overlaps.last_mut() {
                        Some(last) if last.1 == piece.t0 => last.1 = piece.t1,
                        _ => overlaps.push((piece.t0, piece.t1)),
                    }
                    continue;
                }
                for (sigma, touches) in piece.logistic_roots(&f, false) {
                    let u = 1.0 / (1.0 + (-sigma).exp());
                    let point = piece.point_logistic(sigma);
                    hits.push(LineHit {
                        t: piece.t_of(u),
                        lambda: lambda(point)?,
                        point,
                        kind: if touches {
                            HitKind::Tangent
                        } else {
                            HitKind::Crossing
                        },
                        error: 4.0 * f64::EPSILON * (piece.t1 - piece.t0).abs(),
                    });
                }
                continue;
            }
            let c: Vec<f64> = (0..n)
                .map(|i| {
                    let w = piece.w().map_or(1.0, |w| w[i]);
                    let x = piece.a(0)[i] - p.x * w;
                    let y = piece.a(1)[i] - p.y * w;
                    x * dn.y - y * dn.x
                })
                .collect();
            let roots = bernstein_roots(&c);
            if roots.identically_zero {
                match overlaps.last_mut() {
                    Some(last) if last.1 == piece.t0 => last.1 = piece.t1,
                    _ => overlaps.push((piece.t0, piece.t1)),
                }
                continue;
            }
            for r in roots.roots {
                let t = piece.t_of(r.t);
                let point = piece.point(r.t);
                hits.push(LineHit {
                    t,
                    lambda: lambda(point)?,
                    point,
                    // A multiple root is a common tangent (a contact of any order).
                    kind: if r.multiplicity >= 2 {
                        HitKind::Tangent
                    } else {
                        HitKind::Crossing
                    },
                    error: r.error * (piece.t1 - piece.t0),
                });
            }
        }
        hits.sort_by(|x, y| x.t.total_cmp(&y.t));
        // A hit at a joint is found by both segments.
        hits.dedup_by(|x, y| (x.t - y.t).abs() <= x.error + y.error + 4.0 * f64::EPSILON);
        hits.retain(|h| !overlaps.iter().any(|(s, e)| h.t >= *s && h.t <= *e));
        Ok(LineIntersections { hits, overlaps })
    }
}

/// An extremum of the signed curvature `κ` as an extremum of `|κ|`: the same where the
/// curve turns left (`κ > 0`), the other where it turns right; where `κ = 0` (a flat
/// point that is no inflection) `|κ|` is at its least.
fn of_magnitude(kind: ExtremumKind, curvature: f64) -> ExtremumKind {
    if curvature > 0.0 {
        kind
    } else if curvature < 0.0 {
        match kind {
            ExtremumKind::Maximum => ExtremumKind::Minimum,
            ExtremumKind::Minimum => ExtremumKind::Maximum,
        }
    } else {
        ExtremumKind::Minimum
    }
}
