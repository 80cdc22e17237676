//! Continuity at the joints of a piecewise curve: where one lowered segment ends and the
//! next begins (a B-spline's or NURBS curve's interior knots, a NUBMP curve's, a modified
//! Bézier curve's bump ends, an interpolating spline's data points), and a closed curve's
//! seam (its end meeting its start). At each joint: the position gap `|P⁻ − P⁺|`, the
//! angle between the tangents `P′⁻` and `P′⁺` (where a speed vanishes, the direction
//! its first non-vanishing derivative gives), and the relative curvature jump
//! `|K⁻ − K⁺| / max(|K⁻|, |K⁺|)` of the curvature vectors `K = (P″ − (P″·T) T) / |P′|²`
//! (0 where both vanish) — classed as geometric continuity:
//!
//! * **gap**: the ends are more than `10⁻¹²` of the curve's size apart;
//! * **G0**: they meet at an angle over `10⁻⁹` rad (a kink);
//! * **G1**: one tangent, but the curvature jumps by more than `10⁻⁸` of itself;
//! * **G2**: one tangent and one curvature vector.
//!
//! The thresholds are rounding levels: a joint built continuous in exact arithmetic reads
//! as such; anything a designer could see is far above them. `docs/math.md` §9.

use glam::DVec3;

use super::comb::curvature_vector;
use super::curve::{AnalysisError, CurveAnalysis};
use super::piece::Piece;

/// Ends farther apart than this fraction of the curve's half-extent are a gap.
pub const GAP_TOLERANCE: f64 = 1e-12;

/// Tangents at a larger angle than this (radians) are a kink.
pub const ANGLE_TOLERANCE: f64 = 1e-9;

/// A relative curvature jump larger than this breaks G2.
pub const CURVATURE_TOLERANCE: f64 = 1e-8;

/// The continuity class of a joint.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum JointClass {
    /// The ends do not meet.
    Gap,
    /// They meet at an angle.
    G0,
    /// One tangent, a curvature jump.
    G1,
    /// One tangent and one curvature vector.
    G2,
}

impl JointClass {
    /// `gap`, `G0`, `G1` or `G2`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            JointClass::Gap => "gap",
            JointClass::G0 => "G0",
            JointClass::G1 => "G1",
            JointClass::G2 => "G2",
        }
    }
}

/// One joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joint {
    /// The curve parameter (for the seam: the domain's end).
    pub t: f64,
    /// The point (the end of the segment before the joint).
    pub point: DVec3,
    /// `|P⁻ − P⁺|`.
    pub gap: f64,
    /// The angle between the tangents, in radians, from 0 to π.
    pub angle: f64,
    /// `|K⁻ − K⁺| / max(|K⁻|, |K⁺|)`: from 0 to 2 (0 where both vanish).
    pub curvature_jump: f64,
    /// The class.
    pub class: JointClass,
    /// Whether this is a closed curve's seam (the end meeting the start).
    pub seam: bool,
}

/// The tangent direction at the end `u` (0 or 1) of a piece: `P′`, or where it vanishes
/// the first derivative that does not (`P″`, then the control polygon's first leg that is
/// not a point), pointing along the parameter.
fn tangent(p: &Piece, u: f64) -> DVec3 {
    let d1 = p.deriv(u);
    if d1.length_squared() > 0.0 {
        return d1;
    }
    // P′ = 0: near the end P(u) ≈ P(end) + ½ P″ (u − end)², so the curve leaves along
    // +P″ from u = 0 and arrives along −P″ at u = 1.
    let d2 = p.second_deriv(u);
    if d2.length_squared() > 0.0 {
        return if u == 0.0 { d2 } else { -d2 };
    }
    // Higher order: the chord towards the nearest point of the piece that differs.
    let at = p.point(u);
    for k in 1..=64 {
        let h = f64::from(k) / 64.0;
        let q = p.point(if u == 0.0 { h } else { 1.0 - h });
        if q != at {
            return if u == 0.0 { q - at } else { at - q };
        }
    }
    DVec3::ZERO
}

/// `scale` times the curvature vector at the end `u` of a piece (`None` where the speed
/// vanishes): the derivatives divided by `scale` (of their own size) first, so that the
/// product stays representable at coordinates near `1e300` or `1e-300`, where `K` itself
/// would underflow or overflow; a ratio of two with one `scale` is the ratio of the
/// curvatures.
fn curvature_at(p: &Piece, u: f64, scale: f64) -> Option<DVec3> {
    let h = p.t1 - p.t0;
    curvature_vector(
        p.deriv(u) / (h * scale),
        p.second_deriv(u) / (h * h * scale),
    )
}

fn joint(before: &Piece, after: &Piece, t: f64, half_extent: f64, seam: bool) -> Joint {
    let (p, q) = (before.point(1.0), after.point(0.0));
    let gap = (p - q).length();
    // Each tangent scaled by its largest component first: at coordinates near 1e300 a
    // cross product would overflow, near 1e-300 underflow.
    let unit = |v: DVec3| {
        let m = v.abs().max_element();
        if m > 0.0 && m.is_finite() { v / m } else { v }
    };
    let (a, b) = (unit(tangent(before, 1.0)), unit(tangent(after, 0.0)));
    let angle = if a.length_squared() > 0.0 && b.length_squared() > 0.0 {
        a.cross(b).length().atan2(a.dot(b))
    } else {
        0.0
    };
    // One scale for both sides (the jump is a ratio of the two): the larger component of
    // the two first derivatives.
    let scale = {
        let m = before
            .deriv(1.0)
            .abs()
            .max_element()
            .max(after.deriv(0.0).abs().max_element());
        if m > 0.0 && m.is_finite() { m } else { 1.0 }
    };
    let curvature_jump = match (
        curvature_at(before, 1.0, scale),
        curvature_at(after, 0.0, scale),
    ) {
        (Some(k1), Some(k2)) => {
            let m = k1.length().max(k2.length());
            if m > 0.0 { (k1 - k2).length() / m } else { 0.0 }
        }
        // Where a speed vanishes the curvature is unbounded: no claim of G2.
        _ => f64::INFINITY,
    };
    let class = if gap.is_nan() || gap > GAP_TOLERANCE * half_extent.max(f64::MIN_POSITIVE) {
        JointClass::Gap
    } else if angle.is_nan() || angle > ANGLE_TOLERANCE {
        JointClass::G0
    } else if curvature_jump.is_nan() || curvature_jump > CURVATURE_TOLERANCE {
        JointClass::G1
    } else {
        JointClass::G2
    };
    Joint {
        t,
        point: p,
        gap,
        angle,
        curvature_jump,
        class,
        seam,
    }
}

impl CurveAnalysis {
    /// The joints between consecutive lowered segments, in order, then a closed curve's
    /// seam (see the module docs).
    ///
    /// # Errors
    /// [`AnalysisError::TooLarge`] for coordinates beyond `2^400` that are not all of one
    /// scale (curvatures square the derivatives); [`AnalysisError::Overflow`] where a
    /// tangent or a curvature at a joint is not a finite double (weights far apart).
    pub fn joints(&self) -> Result<Vec<Joint>, AnalysisError> {
        // Near the ends of the double range, measured on the curve scaled to about 1 (the
        // angles and jumps do not change with the scale; points and gaps are scaled back).
        if let Some((e, scaled)) = self.rescaled() {
            let back = |x: f64| crate::num::scale_by_power_of_two(x, -e);
            return Ok(scaled
                .joints()?
                .into_iter()
                .map(|j| Joint {
                    point: j.point.map(back),
                    gap: back(j.gap),
                    ..j
                })
                .collect());
        }
        self.require_moderate("joints")?;
        let pieces = self.pieces();
        let bbox = self.control_box();
        let half_extent = (0.5 * bbox.max - 0.5 * bbox.min).max_element();
        let mut out: Vec<Joint> = pieces
            .windows(2)
            .map(|w| joint(&w[0], &w[1], w[0].t1, half_extent, false))
            .collect();
        if self.is_closed()
            && let (Some(last), Some(first)) = (pieces.last(), pieces.first())
        {
            out.push(joint(last, first, self.domain().1, half_extent, true));
        }
        if out.iter().any(|j| {
            !(j.point.is_finite() && j.gap.is_finite() && j.angle.is_finite())
                || j.curvature_jump.is_nan()
        }) {
            return Err(AnalysisError::Overflow {
                what: "joints' tangents or curvatures",
                size: (bbox.max - bbox.min).length(),
            });
        }
        Ok(out)
    }
}
