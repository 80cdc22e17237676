//! Intersections of planar curves: two curves, a curve with itself, and every pair among
//! many — on their lowered segments, polynomial or rational.
//!
//! **Two segments.** First, coincidence: a segment's end point on the other segment (its
//! closest point by the root finder, within `1e−9` of their size), two such points, and
//! seven points between them on the other curve, make an *overlap* — reported as a pair
//! of parameter intervals, not a cloud of points. Then subdivision: while the control
//! boxes of two sub-segments overlap, the larger is halved (de Casteljau on the
//! homogeneous points, so the convex hull holds for rational segments too), until both
//! are flat to `1e−6` of their size; their chords' crossing starts Newton's method on
//! `C₁(s) − C₂(t) = 0` (damped, Levenberg–Marquardt, where the Jacobian is singular),
//! which converges to full precision for a transversal crossing and to about `√ε` in the
//! parameters at a tangency. A point is kept when `|C₁(s) − C₂(t)| ≤ 64 ε` times the size;
//! it is a *tangent* point where the tangents are parallel within `1e−6` rad (then the
//! neighbouring candidates, which converge to the same point more slowly, are merged
//! into it), a *crossing* otherwise.
//!
//! **A curve with itself.** Its segments are cut where `x′` or `y′` vanishes: the pieces
//! are monotone in both coordinates and cannot cross themselves; every pair of pieces is
//! intersected, leaving out the joint two neighbours share (and, for a closed curve, the
//! start meeting the end).
//!
//! **Many curves.** A sweep over the segments' boxes sorted by `x` pairs the boxes that
//! overlap; the pairs are intersected on every core (rayon).

use glam::{DVec2, DVec3};
use rayon::prelude::*;

mod refine;
mod subdivide;

use refine::{closest, crosses, refine, refine_tangent};
use subdivide::{Sub, Subdivider, boxes_meet, surely_off};

use super::bernstein_roots;
use super::curve::{AnalysisError, CurveAnalysis, HitKind};
use super::piece::Piece;

/// One point where two curves meet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// The first curve's parameter.
    pub s: f64,
    /// The second curve's parameter.
    pub t: f64,
    /// The point (the first curve's, at `s`).
    pub point: DVec3,
    /// Crossing or tangent.
    pub kind: HitKind,
    /// A bound on the error of `s` and `t`: a few ulps for a crossing, about `√ε` of the
    /// parameter range at a tangency.
    pub error: f64,
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

/// The parameter of the point of `p` on `range` closest to `q`, when that point is within
/// `tol` of `q`. A `q` that the piece's control boxes already show to be farther needs no
/// closest point (its root finding is most of an overlap test).
fn within(p: &Piece, range: (f64, f64), q: DVec2, tol: f64) -> Option<f64> {
    if surely_off(p, range, q, tol) {
        return None;
    }
    let (u, d) = closest(p, range, q);
    (d <= tol).then_some(u)
}

/// Coincident stretches of two segments on their ranges: each end of one range whose
/// point lies on the other, confirmed by seven points between two of them. In segment
/// parameters.
fn segment_overlaps(
    a: &Piece,
    ra: (f64, f64),
    b: &Piece,
    rb: (f64, f64),
    tol: f64,
) -> Vec<SpanPair> {
    let on_b = |u: f64| within(b, rb, a.point(u).truncate(), tol).map(|v| (u, v));
    let on_a = |v: f64| within(a, ra, b.point(v).truncate(), tol).map(|u| (u, v));
    let mut ends: Vec<(f64, f64)> = [on_b(ra.0), on_b(ra.1), on_a(rb.0), on_a(rb.1)]
        .into_iter()
        .flatten()
        .collect();
    ends.sort_by(|x, y| x.0.total_cmp(&y.0));
    ends.dedup_by(|x, y| (x.0 - y.0).abs() <= 1e-9 && (x.1 - y.1).abs() <= 1e-9);
    if ends.len() < 2 {
        return Vec::new();
    }
    let (first, last) = (ends[0], ends[ends.len() - 1]);
    if (last.0 - first.0).abs() <= 1e-9 || (last.1 - first.1).abs() <= 1e-9 {
        return Vec::new();
    }
    let coincide = (1..=7).all(|k| {
        let u = first.0 + (last.0 - first.0) * f64::from(k) / 8.0;
        within(b, rb, a.point(u).truncate(), tol).is_some()
    });
    if coincide {
        vec![((first.0, last.0), (first.1, last.1))]
    } else {
        Vec::new()
    }
}

/// The size two pieces are measured by: the diagonal of their control boxes' union.
fn size_of(a: &Piece, b: &Piece) -> f64 {
    let (ba, bb) = (a.bounds(), b.bounds());
    let lo = ba.0.min(bb.0);
    let hi = ba.1.max(bb.1);
    (hi - lo).length().max(f64::MIN_POSITIVE)
}

/// The points and overlaps of two segments, in segment parameters (`u` of `a`, `v` of
/// `b`), on the sub-ranges given.
fn piece_pair(a: &Piece, (a0, a1): (f64, f64), b: &Piece, (b0, b1): (f64, f64)) -> PieceHits {
    let size = size_of(a, b);
    let first = points_of(a, (a0, a1), b, (b0, b1), &[], size);
    // Coincident stretches show as tangent points or as many candidates; only then is the
    // (costlier) coincidence test run, and the points found again outside what coincides.
    if first.iter().all(|h| h.2 == HitKind::Crossing) && first.len() <= 8 {
        return PieceHits {
            hits: first,
            overlaps: Vec::new(),
        };
    }
    let overlaps = segment_overlaps(a, (a0, a1), b, (b0, b1), 1e-9 * size);
    if overlaps.is_empty() {
        return PieceHits {
            hits: first,
            overlaps,
        };
    }
    PieceHits {
        hits: points_of(a, (a0, a1), b, (b0, b1), &overlaps, size),
        overlaps,
    }
}

/// The points where two segments meet on their ranges, outside the given overlaps of `a`
/// (segment parameters).
fn points_of(
    a: &Piece,
    (a0, a1): (f64, f64),
    b: &Piece,
    (b0, b1): (f64, f64),
    overlaps: &[SpanPair],
    size: f64,
) -> Vec<(f64, f64, HitKind)> {
    let tol = 64.0 * f64::EPSILON * size;
    let inside_overlap = |u: f64| {
        overlaps
            .iter()
            .any(|((u0, u1), _)| u >= u0.min(*u1) - 1e-9 && u <= u0.max(*u1) + 1e-9)
    };
    // The parts of `a` outside the overlaps are what the subdivision examines.
    let mut ranges = vec![(a0, a1)];
    for ((u0, u1), _) in overlaps {
        let (lo, hi) = (u0.min(*u1), u0.max(*u1));
        ranges = ranges
            .into_iter()
            .flat_map(|(r0, r1)| {
                let mut parts = Vec::new();
                if lo > r0 {
                    parts.push((r0, lo.min(r1)));
                }
                if hi < r1 {
                    parts.push((hi.max(r0), r1));
                }
                parts
            })
            .filter(|(r0, r1)| r1 > r0)
            .collect();
    }
    let mut sub = Subdivider {
        flat: 1e-6 * size,
        margin: tol,
        candidates: Vec::new(),
    };
    let sb = Sub::of(b, b0, b1);
    for (r0, r1) in ranges {
        sub.run(&Sub::of(a, r0, r1), &sb, 0);
    }
    let mut found: Vec<(f64, f64, HitKind)> = Vec::new();
    // Converged points, to skip candidates of pairs that meet at most once and already
    // hold one (neighbouring leaves share the point on their common edge).
    let mut seen: Vec<(f64, f64)> = Vec::new();
    for &((u, v), single) in &sub.candidates {
        if let Some([u0, u1, v0, v1]) = single
            && seen
                .iter()
                .any(|&(su, sv)| su >= u0 && su <= u1 && sv >= v0 && sv <= v1)
        {
            continue;
        }
        let (u, v, residual) = refine(a, b, u, v);
        if residual <= tol {
            seen.push((u, v));
        }
        if residual > tol || u < a0 || u > a1 || v < b0 || v > b1 || inside_overlap(u) {
            continue;
        }
        let (da, db) = (a.deriv(u).truncate(), b.deriv(v).truncate());
        let sin = da.perp_dot(db).abs() / (da.length() * db.length());
        if (sin.is_finite() && sin > 1e-6) || crosses(a, b, u, v, (a0, a1)) {
            found.push((u, v, HitKind::Crossing));
            continue;
        }
        // A tangency: the touching point itself, where the tangency conditions converge
        // and the curves still meet there.
        let (u, v) = match refine_tangent(a, b, u, v) {
            Some((tu, tv))
                if tu >= a0
                    && tu <= a1
                    && tv >= b0
                    && tv <= b1
                    && (a.point(tu) - b.point(tv)).length() <= tol =>
            {
                (tu, tv)
            }
            _ => (u, v),
        };
        found.push((u, v, HitKind::Tangent));
    }
    found.sort_by(|x, y| x.0.total_cmp(&y.0));
    // One point from candidates that converged to the same place: within a few ulps for
    // crossings, within √ε for tangencies (Newton converges slowly there).
    let mut merged: Vec<(f64, f64, HitKind)> = Vec::new();
    for h in found {
        let same = merged.iter_mut().rev().find(|m| {
            let radius = if m.2 == HitKind::Tangent || h.2 == HitKind::Tangent {
                1e-7
            } else {
                1e-12
            };
            (m.0 - h.0).abs() <= radius && (m.1 - h.1).abs() <= radius
        });
        match same {
            Some(m) => {
                if h.2 == HitKind::Tangent {
                    m.2 = HitKind::Tangent;
                }
            }
            None => merged.push(h),
        }
    }
    merged
}

/// A coincident stretch in two segments' own parameters: `((u0, u1), (v0, v1))`.
type SpanPair = ((f64, f64), (f64, f64));

/// Hits and overlaps of two segments in their own parameters.
#[derive(Debug, Default)]
struct PieceHits {
    hits: Vec<(f64, f64, HitKind)>,
    overlaps: Vec<SpanPair>,
}

/// `u` of a piece as the curve parameter.
fn to_t(p: &Piece, u: f64) -> f64 {
    p.t_of(u)
}

fn hit(a: &Piece, b: &Piece, (u, v, kind): (f64, f64, HitKind)) -> Hit {
    let error = match kind {
        HitKind::Crossing => 8.0 * f64::EPSILON,
        HitKind::Tangent => 1e-7,
    };
    Hit {
        s: to_t(a, u),
        t: to_t(b, v),
        point: a.point(u),
        kind,
        error: error * (a.t1 - a.t0).abs().max(b.t1 - b.t0),
    }
}

/// Sorts hits and overlaps, and merges the copies two neighbouring segments report of a
/// point on their joint, and overlaps that continue across joints.
fn tidy(mut found: Intersections) -> Intersections {
    found
        .hits
        .sort_by(|x, y| x.s.total_cmp(&y.s).then(x.t.total_cmp(&y.t)));
    found.hits.dedup_by(|x, y| {
        (x.s - y.s).abs() <= x.error + y.error && (x.t - y.t).abs() <= x.error + y.error
    });
    found.overlaps.sort_by(|x, y| x.s.0.total_cmp(&y.s.0));
    let mut overlaps: Vec<Overlap> = Vec::new();
    for o in found.overlaps {
        match overlaps.last_mut() {
            Some(last) if (last.s.1 - o.s.0).abs() <= 1e-12 => {
                last.s.1 = o.s.1;
                last.t.1 = o.t.1;
            }
            _ => overlaps.push(o),
        }
    }
    let within = |h: &Hit| {
        overlaps.iter().any(|o| {
            let (lo, hi) = (o.s.0.min(o.s.1), o.s.0.max(o.s.1));
            h.s >= lo - h.error && h.s <= hi + h.error
        })
    };
    found.hits.retain(|h| !within(h));
    found.overlaps = overlaps;
    found
}

impl CurveAnalysis {
    /// The distance from `q` to the curve (2D), by each segment's closest point (segments
    /// whose boxes are farther than the best so far skipped).
    fn distance_to(&self, q: DVec2) -> f64 {
        let mut best = f64::INFINITY;
        for p in self.pieces() {
            let (lo, hi) = piece_box(p);
            let outside = (lo - q).max(q - hi).max(DVec2::ZERO).length();
            if outside < best {
                best = best.min(closest(p, (0.0, 1.0), q).1);
            }
        }
        best
    }

    /// The curve's size: the diagonal of its control box.
    fn size(&self) -> f64 {
        self.control_box().diagonal().max(f64::MIN_POSITIVE)
    }
}

/// Whether `a` stays on `b` (within `tol`) at three points strictly between `s0` and `s1`.
fn coincide_between(a: &CurveAnalysis, b: &CurveAnalysis, s0: f64, s1: f64, tol: f64) -> bool {
    [0.25, 0.5, 0.75].iter().all(|f| {
        let s = s0 + f * (s1 - s0);
        b.distance_to(a.point(s).truncate()) <= tol
    })
}

/// The last cleaning of what two curves have in common, with both curves at hand: a
/// closed curve's start and end are one point; tangent points that the curves join by a
/// stretch along which they stay within `1e−9` of their size (a contact of high order,
/// where Newton's method stops anywhere in a tiny coincident stretch) are one point; and
/// a point joined that way to an overlap's end belongs to the overlap.
fn settle(mut found: Intersections, a: &CurveAnalysis, b: &CurveAnalysis) -> Intersections {
    let close = |c: &CurveAnalysis| c.is_closed().then(|| c.domain());
    if let Some((start, end)) = close(a) {
        let starts: Vec<f64> = found
            .hits
            .iter()
            .filter(|h| h.s == start)
            .map(|h| h.t)
            .collect();
        found
            .hits
            .retain(|h| !(h.s == end && starts.iter().any(|t| (t - h.t).abs() <= 2.0 * h.error)));
    }
    if let Some((start, end)) = close(b) {
        let starts: Vec<f64> = found
            .hits
            .iter()
            .filter(|h| h.t == start)
            .map(|h| h.s)
            .collect();
        found
            .hits
            .retain(|h| !(h.t == end && starts.iter().any(|s| (s - h.s).abs() <= 2.0 * h.error)));
    }
    let tol = 1e-9 * a.size().max(b.size());
    let (da, _) = a.domain();
    let reach = 1e-3 * (a.domain().1 - da).abs();
    // Points joined to an overlap's end by a coincident stretch.
    let overlaps = found.overlaps.clone();
    found.hits.retain(|h| {
        !overlaps.iter().any(|o| {
            [o.s.0, o.s.1].iter().any(|&end| {
                let gap = (h.s - end).abs();
                gap <= reach && (gap == 0.0 || coincide_between(a, b, h.s, end, tol))
            })
        })
    });
    // Tangent points joined by a coincident stretch: one point (the first).
    let mut hits: Vec<Hit> = Vec::with_capacity(found.hits.len());
    for h in std::mem::take(&mut found.hits) {
        if let Some(last) = hits.last()
            && last.kind == HitKind::Tangent
            && h.kind == HitKind::Tangent
            && (h.s - last.s).abs() <= reach
            && coincide_between(a, b, last.s, h.s, tol)
        {
            continue;
        }
        hits.push(h);
    }
    found.hits = hits;
    found
}

/// The control box of a piece, in 2D.
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
        let mut found = Intersections::default();
        let boxes_b: Vec<(DVec2, DVec2)> = other.pieces().iter().map(piece_box).collect();
        for a in self.pieces() {
            let ba = piece_box(a);
            for (b, bb) in other.pieces().iter().zip(&boxes_b) {
                let margin = 1e-9 * size_of(a, b);
                if !boxes_meet(ba, *bb, margin) {
                    continue;
                }
                let ph = piece_pair(a, (0.0, 1.0), b, (0.0, 1.0));
                found.hits.extend(ph.hits.into_iter().map(|h| hit(a, b, h)));
                found
                    .overlaps
                    .extend(ph.overlaps.into_iter().map(|((u0, u1), (v0, v1))| Overlap {
                        s: (to_t(a, u0), to_t(a, u1)),
                        t: (to_t(b, v0), to_t(b, v1)),
                    }));
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
                let size = size_of(&pieces[ka], &pieces[kb]);
                if !boxes_meet(boxes[i], boxes[j], 1e-9 * size) {
                    continue;
                }
                let ph = piece_pair(&pieces[ka], (pi.1, pi.2), &pieces[kb], (pj.1, pj.2));
                let ta = |u: f64| to_t(&pieces[ka], u);
                let tb = |v: f64| to_t(&pieces[kb], v);
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
                for h in ph.hits {
                    let hh = hit(&pieces[ka], &pieces[kb], h);
                    if !shared(hh.s, hh.t) {
                        found.hits.push(hh);
                    }
                }
                for ((u0, u1), (v0, v1)) in ph.overlaps {
                    found.overlaps.push(Overlap {
                        s: (ta(u0), ta(u1)),
                        t: (tb(v0), tb(v1)),
                    });
                }
            }
        }
        Ok(settle(tidy(found), self, self))
    }
}

/// Every intersecting pair among `curves` (2D; 3D curves are refused): a sweep over the
/// segments' boxes finds the pairs of segments whose boxes overlap, and the pairs are
/// intersected on every core. Pairs in `(i, j)` order with `i < j`; self-intersections
/// are not included.
///
/// # Errors
/// [`AnalysisError::NotPlanar`] naming the first 3D curve.
pub fn all_intersections(
    curves: &[CurveAnalysis],
) -> Result<Vec<PairIntersections>, AnalysisError> {
    if curves.iter().any(|c| !c.is_planar()) {
        return Err(AnalysisError::NotPlanar {
            what: "intersections",
        });
    }
    // (min x, max x, min y, max y, curve, piece)
    let mut items: Vec<(DVec2, DVec2, usize, usize)> = Vec::new();
    for (ci, c) in curves.iter().enumerate() {
        for (pi, p) in c.pieces().iter().enumerate() {
            let (lo, hi) = piece_box(p);
            items.push((lo, hi, ci, pi));
        }
    }
    items.sort_by(|x, y| x.0.x.total_cmp(&y.0.x));
    let mut pairs: Vec<(usize, usize, usize, usize)> = Vec::new();
    for (k, a) in items.iter().enumerate() {
        for b in &items[k + 1..] {
            if b.0.x > a.1.x {
                break;
            }
            if a.2 != b.2 && b.0.y <= a.1.y && a.0.y <= b.1.y {
                let (first, second) = if a.2 < b.2 { (a, b) } else { (b, a) };
                pairs.push((first.2, first.3, second.2, second.3));
            }
        }
    }
    // Grouped by pair of curves, then by their segments.
    pairs.sort_unstable_by_key(|&(ci, pi, cj, pj)| (ci, cj, pi, pj));
    let results: Vec<(usize, usize, PieceHits, usize, usize)> = pairs
        .par_iter()
        .map(|&(ci, pi, cj, pj)| {
            let (a, b) = (&curves[ci].pieces()[pi], &curves[cj].pieces()[pj]);
            (ci, cj, piece_pair(a, (0.0, 1.0), b, (0.0, 1.0)), pi, pj)
        })
        .collect();
    let mut out: Vec<PairIntersections> = Vec::new();
    for (ci, cj, ph, pi, pj) in results {
        if ph.hits.is_empty() && ph.overlaps.is_empty() {
            continue;
        }
        let (a, b) = (&curves[ci].pieces()[pi], &curves[cj].pieces()[pj]);
        let entry = match out.last_mut() {
            Some(e) if e.i == ci && e.j == cj => e,
            _ => {
                out.push(PairIntersections {
                    i: ci,
                    j: cj,
                    found: Intersections::default(),
                });
                out.last_mut()
                    .unwrap_or_else(|| unreachable!("just pushed"))
            }
        };
        entry
            .found
            .hits
            .extend(ph.hits.into_iter().map(|h| hit(a, b, h)));
        entry
            .found
            .overlaps
            .extend(ph.overlaps.into_iter().map(|((u0, u1), (v0, v1))| Overlap {
                s: (to_t(a, u0), to_t(a, u1)),
                t: (to_t(b, v0), to_t(b, v1)),
            }));
    }
    Ok(out
        .into_iter()
        .map(|mut p| {
            p.found = settle(tidy(p.found), &curves[p.i], &curves[p.j]);
            p
        })
        .collect())
}
