//! Intersections of planar curves: two curves, a curve with itself, and every pair among
//! many — on their lowered segments, polynomial or rational.
//!
//! **Two segments** (`pair`): the ends of each tested against the other explicitly;
//! coincident stretches between such ends; the rest subdivided to candidates refined by
//! Newton's method; each point classified as a crossing or a tangency (parallel tangents,
//! a contact of any order), with a bound on its parameters' error.
//!
//! **A curve with itself.** Its segments are cut where `x′` or `y′` vanishes: the pieces
//! are monotone in both coordinates and cannot cross themselves; every pair of pieces is
//! intersected, leaving out the joint two neighbours share (and, for a closed curve, the
//! start meeting the end).
//!
//! **Many curves** ([`many`]): copies (curves with identical segments) grouped first, a
//! grid over the segments' boxes pairs the boxes that overlap, and the pairs are
//! intersected on every core (rayon).

use glam::{DVec2, DVec3};

pub mod many;
mod pair;
mod refine;
mod subdivide;

use super::curve::{AnalysisError, CurveAnalysis, HitKind};
use super::piece::Piece;
use crate::poly::roots::bernstein_roots;
use pair::{PairHit, PieceHits, Scale, SpanPair, piece_pair};
use subdivide::{Sub, boxes_meet};

/// One point where two curves meet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// The first curve's parameter.
    pub s: f64,
    /// The second curve's parameter.
    pub t: f64,
    /// The point (the first curve's, at `s`).
    pub point: DVec3,
    /// Crossing (the tangents differ) or tangent (a common tangent: a contact of any
    /// order).
    pub kind: HitKind,
    /// A bound on the error of `s`: for a crossing `2 (e₁ + e₂ + r) / (|C₁′| sin θ)` —
    /// the evaluations' rounding bounds `e` and the residual `r` over the speed and the
    /// sine of the angle between the tangents (the crossing's condition number); for a
    /// tangency, the band around it where the curves stay within the resolution of each
    /// other.
    pub error_s: f64,
    /// A bound on the error of `t`, likewise.
    pub error_t: f64,
}

/// A stretch where two curves coincide.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Overlap {
    /// The first curve's parameter interval.
    pub s: (f64, f64),
    /// The second curve's parameter interval (in the order matching `s`: `t.0` meets
    /// `s.0`).
    pub t: (f64, f64),
}

/// Everything two curves (or a curve and itself) have in common.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Intersections {
    /// The points, by `s`.
    pub hits: Vec<Hit>,
    /// The coincident stretches, by `s`.
    pub overlaps: Vec<Overlap>,
}

/// The intersections of one pair among many curves.
#[derive(Debug, Clone, PartialEq)]
pub struct PairIntersections {
    /// The first curve's index.
    pub i: usize,
    /// The second curve's index (`i < j`).
    pub j: usize,
    /// What they have in common.
    pub found: Intersections,
}

/// A segment's hit in curve parameters.
fn hit(a: &Piece, b: &Piece, h: &PairHit) -> Hit {
    let (s, t) = (a.t_of(h.u), b.t_of(h.v));
    Hit {
        s,
        t,
        point: a.point(h.u),
        kind: h.kind,
        error_s: h.err_u * (a.t1 - a.t0).abs() + f64::EPSILON * s.abs(),
        error_t: h.err_v * (b.t1 - b.t0).abs() + f64::EPSILON * t.abs(),
    }
}

/// A segment's overlap in curve parameters.
fn overlap(a: &Piece, b: &Piece, ((u0, u1), (v0, v1)): SpanPair) -> Overlap {
    Overlap {
        s: (a.t_of(u0), a.t_of(u1)),
        t: (b.t_of(v0), b.t_of(v1)),
    }
}

/// Sorts hits and overlaps, merges the copies two neighbouring segments report of one
/// point (on their joint, or a tangency whose band reaches it) and overlaps that continue
/// across joints, and drops the points on an overlap (they belong to it).
fn tidy(mut found: Intersections) -> Intersections {
    found
        .hits
        .sort_by(|x, y| x.s.total_cmp(&y.s).then(x.t.total_cmp(&y.t)));
    let mut hits: Vec<Hit> = Vec::with_capacity(found.hits.len());
    for h in found.hits {
        let same = hits.iter_mut().rev().take(4).find(|m| {
            (m.s - h.s).abs() <= m.error_s + h.error_s + 4.0 * f64::EPSILON * h.s.abs()
                && (m.t - h.t).abs() <= m.error_t + h.error_t + 4.0 * f64::EPSILON * h.t.abs()
        });
        match same {
            Some(m) => {
                if h.kind == HitKind::Tangent && m.kind == HitKind::Crossing {
                    *m = h;
                }
            }
            None => hits.push(h),
        }
    }
    found.overlaps.sort_by(|x, y| x.s.0.total_cmp(&y.s.0));
    let mut overlaps: Vec<Overlap> = Vec::new();
    for o in found.overlaps {
        match overlaps.last_mut() {
            Some(last)
                if (last.s.1 - o.s.0).abs() <= 1e-12 && (last.t.1 - o.t.0).abs() <= 1e-12 =>
            {
                last.s.1 = o.s.1;
                last.t.1 = o.t.1;
            }
            _ => overlaps.push(o),
        }
    }
    let on_overlap = |h: &Hit| {
        overlaps.iter().any(|o| {
            let within = |x: f64, e: f64, (p, q): (f64, f64)| {
                x >= p.min(q) - e - 1e-12 && x <= p.max(q) + e + 1e-12
            };
            within(h.s, h.error_s, o.s) || within(h.t, h.error_t, o.t)
        })
    };
    hits.retain(|h| !on_overlap(h));
    found.hits = hits;
    found.overlaps = overlaps;
    found
}

/// A closed curve's start and end are one point: a hit found at both is kept once.
fn settle(mut found: Intersections, a: &CurveAnalysis, b: &CurveAnalysis) -> Intersections {
    // Only hits at a curve's end can be doubled.
    let at_end = |x: f64, e: f64, (lo, hi): (f64, f64)| (x - lo).abs() <= e || (x - hi).abs() <= e;
    if !found
        .hits
        .iter()
        .any(|h| at_end(h.s, h.error_s, a.domain()) || at_end(h.t, h.error_t, b.domain()))
    {
        return found;
    }
    let close = |c: &CurveAnalysis| c.is_closed().then(|| c.domain());
    if let Some((start, end)) = close(a) {
        let starts: Vec<(f64, f64)> = found
            .hits
            .iter()
            .filter(|h| (h.s - start).abs() <= h.error_s)
            .map(|h| (h.t, h.error_t))
            .collect();
        found.hits.retain(|h| {
            !((h.s - end).abs() <= h.error_s
                && starts
                    .iter()
                    .any(|(t, e)| (t - h.t).abs() <= e + h.error_t + 4.0 * f64::EPSILON))
        });
    }
    if let Some((start, end)) = close(b) {
        let starts: Vec<(f64, f64)> = found
            .hits
            .iter()
            .filter(|h| (h.t - start).abs() <= h.error_t)
            .map(|h| (h.s, h.error_s))
            .collect();
        found.hits.retain(|h| {
            !((h.t - end).abs() <= h.error_t
                && starts
                    .iter()
                    .any(|(s, e)| (s - h.s).abs() <= e + h.error_s + 4.0 * f64::EPSILON))
        });
    }
    found
}

/// The control box of a piece, in 2D.
/// [`AnalysisError::Crowded`] where the pair's subdivision reached its work bound, in
/// the curves' parameters.
fn refuse_crowded(a: &Piece, b: &Piece, ph: &PieceHits) -> Result<(), AnalysisError> {
    match ph.crowded {
        None => Ok(()),
        Some([u0, u1, v0, v1]) => Err(AnalysisError::Crowded {
            pair: None,
            s: (a.t_of(u0), a.t_of(u1)),
            t: (b.t_of(v0), b.t_of(v1)),
            leaves: pair::max_leaves_of(a, b),
        }),
    }
}

fn piece_box(p: &Piece) -> (DVec2, DVec2) {
    p.bounds()
}

impl CurveAnalysis {
    /// Where this curve and `other` meet (2D): points with both parameters and their kind,
    /// and coincident stretches as parameter intervals.
    ///
    /// # Errors
    /// [`AnalysisError::NotPlanar`] when either curve is 3D.
    pub fn intersect(&self, other: &CurveAnalysis) -> Result<Intersections, AnalysisError> {
        if !self.is_planar() || !other.is_planar() {
            return Err(AnalysisError::NotPlanar {
                what: "intersections",
            });
        }
        self.require_moderate("intersections")?;
        other.require_moderate("intersections")?;
        let mut found = Intersections::default();
        let boxes_b: Vec<(DVec2, DVec2)> = other.pieces().iter().map(piece_box).collect();
        for a in self.pieces() {
            let ba = piece_box(a);
            for (b, bb) in other.pieces().iter().zip(&boxes_b) {
                if !boxes_meet(ba, *bb, Scale::of(a, b).tol) {
                    continue;
                }
                let ph = piece_pair(a, (0.0, 1.0), b, (0.0, 1.0));
                refuse_crowded(a, b, &ph)?;
                found.hits.extend(ph.hits.iter().map(|h| hit(a, b, h)));
                found
                    .overlaps
                    .extend(ph.overlaps.into_iter().map(|o| overlap(a, b, o)));
            }
        }
        Ok(settle(tidy(found), self, other))
    }

    /// Where the curve crosses or touches itself (2D), `s < t`: its segments cut into
    /// pieces monotone in `x` and `y`, every pair of pieces intersected, the joints that
    /// neighbouring pieces share (and a closed curve's start meeting its end) left out.
    ///
    /// # Errors
    /// [`AnalysisError::NotPlanar`] for a 3D curve.
    pub fn self_intersections(&self) -> Result<Intersections, AnalysisError> {
        if !self.is_planar() {
            return Err(AnalysisError::NotPlanar {
                what: "self-intersections",
            });
        }
        self.require_moderate("self-intersections")?;
        // Monotone pieces: (segment index, u0, u1).
        let mut parts: Vec<(usize, f64, f64)> = Vec::new();
        for (k, p) in self.pieces().iter().enumerate() {
            let mut cuts: Vec<f64> = (0..2)
                .flat_map(|axis| {
                    bernstein_roots(&p.deriv_numerator(axis))
                        .roots
                        .into_iter()
                        .map(|r| r.t)
                        // An extremum at a joint needs no cut (it would leave a sliver).
                        .filter(|u| *u > 1e-9 && *u < 1.0 - 1e-9)
                })
                .collect();
            cuts.sort_by(f64::total_cmp);
            cuts.dedup_by(|x, y| (*x - *y).abs() <= 1e-12);
            let mut prev = 0.0;
            for c in cuts.into_iter().chain(std::iter::once(1.0)) {
                if c > prev {
                    parts.push((k, prev, c));
                }
                prev = c;
            }
        }
        let (a, b) = self.domain();
        let closed = self.is_closed();
        let pieces = self.pieces();
        let boxes: Vec<(DVec2, DVec2)> = parts
            .iter()
            .map(|&(k, u0, u1)| Sub::of(&pieces[k], u0, u1).bounds())
            .collect();
        let mut found = Intersections::default();
        for i in 0..parts.len() {
            for j in (i + 1)..parts.len() {
                let (pi, pj) = (parts[i], parts[j]);
                let (ka, kb) = (pi.0, pj.0);
                let tol = Scale::of(&pieces[ka], &pieces[kb]).tol;
                if !boxes_meet(boxes[i], boxes[j], tol) {
                    continue;
                }
                let ph = piece_pair(&pieces[ka], (pi.1, pi.2), &pieces[kb], (pj.1, pj.2));
                refuse_crowded(&pieces[ka], &pieces[kb], &ph)?;
                let ta = |u: f64| pieces[ka].t_of(u);
                let tb = |v: f64| pieces[kb].t_of(v);
                let shared = |s: f64, t: f64| {
                    let eps = 1e-9 * (b - a);
                    // One parameter is one point of the curve, not a crossing with itself.
                    if (t - s).abs() <= eps {
                        return true;
                    }
                    // Neighbouring pieces meet at their joint; a closed curve at its ends.
                    (j == i + 1 && (s - ta(pi.2)).abs() <= eps && (t - tb(pj.1)).abs() <= eps)
                        || (closed && (s - a).abs() <= eps && (t - b).abs() <= eps)
                };
                for h in &ph.hits {
                    let hh = hit(&pieces[ka], &pieces[kb], h);
                    if !shared(hh.s, hh.t) {
                        found.hits.push(hh);
                    }
                }
                for o in ph.overlaps {
                    found.overlaps.push(overlap(&pieces[ka], &pieces[kb], o));
                }
            }
        }
        Ok(settle(tidy(found), self, self))
    }
}

pub use many::{AllIntersections, Copies, all_intersections};
