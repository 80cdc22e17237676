//! Two segments, on given ranges of their own parameters: every point and every
//! coincident stretch they have in common.
//!
//! 1. **Ends.** Each end of either range is tested against the other segment (its
//!    control boxes, then its closest point): an end that lies on the other segment is a
//!    point they share, whatever the angle — found here, not left to the subdivision.
//! 2. **Coincidence.** Two such ends whose stretch between them lies on the other segment
//!    (at `max(7, n·m)` points, in order — two different curves of degrees `n` and `m`
//!    share at most `n·m` points) bound a coincident stretch. Points on a stretch belong
//!    to it.
//! 3. **Points.** The parts of both ranges outside the stretches are subdivided
//!    ([`super::subdivide`]); each candidate is refined by Newton's method on
//!    `C₁(u) = C₂(v)` and kept when the curves meet there (within the pair's resolution
//!    `δ = 64 ε` times its largest coordinate or size).
//! 4. **Kinds.** A point is a *tangent* when the tangency conditions (the foot of the
//!    perpendicular, parallel tangents) have a solution where the curves still meet,
//!    within eight of the crossing's uncertainty bands of it — a contact of any order, or
//!    a crossing at an angle so small that `f64` cannot tell it from one; otherwise a
//!    *crossing*.
//! 5. **Errors.** A crossing's parameters are known to `2 (e₁ + e₂ + r) / (|C′| sin θ)`:
//!    `e` the evaluations' running error bounds, `r` the residual, `θ` the angle between
//!    the tangents — the crossing's condition number times the noise. A tangent point is
//!    known to the band around it in which the curves stay within `δ` of each other.
//!    Points whose bands overlap are one point.

use glam::DVec2;

use super::refine::{foot, foot_converged, refine_tangent, refine_until};
use super::subdivide::{Leaves, Rest, Sub, Subdivider, max_leaves};
use crate::analysis::curve::HitKind;
use crate::analysis::piece::Piece;

/// A point two segments share, in their own parameters.
#[derive(Debug, Clone, Copy)]
pub(super) struct PairHit {
    pub(super) u: f64,
    pub(super) v: f64,
    pub(super) kind: HitKind,
    /// A bound on the error of `u`.
    pub(super) err_u: f64,
    /// A bound on the error of `v`.
    pub(super) err_v: f64,
}

/// A coincident stretch in two segments' own parameters: `((u0, u1), (v0, v1))`, `v0`
/// meeting `u0`.
pub(super) type SpanPair = ((f64, f64), (f64, f64));

/// Hits and overlaps of two segments in their own parameters.
#[derive(Debug, Default)]
pub(super) struct PieceHits {
    pub(super) hits: Vec<PairHit>,
    pub(super) overlaps: Vec<SpanPair>,
    /// Where the subdivision reached its work bound (`[u0, u1, v0, v1]`): the hits and
    /// overlaps are then not known to be all, and the pair is refused.
    pub(super) crowded: Option<[f64; 4]>,
}

/// A crossing whose parameter's error exceeds this fraction of the range is nearly
/// parallel to the other curve: in a crowded pair its neighbourhood is scanned and
/// skipped as a tangency's is (not before: the ordinary order finds each point by
/// Newton's method, whose answers the stated errors are measured against).
const WIDE: f64 = 1e-10;

/// A tangency's stretch within the flatness is scanned and skipped at once only when it
/// is wider than this fraction of the range (a contact of high order, or curves nearly
/// straight and nearly parallel there); in a crowded pair, always.
const REACH_WORTH: f64 = 1e-3;

/// What classifying a point costs, in leaves' worth (two walks out of its band).
const CLASSIFY_WORK: usize = 8;

/// The subdivision's flatness, in multiples of the resolution `δ`: a pair of pieces this
/// flat is a leaf.
const FLAT: f64 = 64.0;

/// Two ends meeting with tangents parallel to within this sine share their tangent line
/// (a join's tangents computed from exactly collinear control points agree to a few ε).
const JOIN_PARALLEL: f64 = 1e-12;

/// The scale of a pair: its size, and `δ`, the distance within which two of its points
/// are one point (`64 ε` — more for high degrees — times its largest coordinate or its
/// size, whichever is larger: the rounding of an evaluation is relative to the
/// coordinates, not to the size).
#[derive(Debug, Clone, Copy)]
pub(super) struct Scale {
    pub(super) size: f64,
    pub(super) tol: f64,
}

impl Scale {
    pub(super) fn of(a: &Piece, b: &Piece) -> Scale {
        let (ba, bb) = (a.bounds(), b.bounds());
        let (lo, hi) = (ba.0.min(bb.0), ba.1.max(bb.1));
        let size = (hi - lo).length().max(f64::MIN_POSITIVE);
        let magnitude = lo.abs().max(hi.abs()).max_element();
        let factor = 64.0_f64.max(4.0 * (a.degree() + b.degree()) as f64);
        Scale {
            size,
            tol: factor * f64::EPSILON * size.max(magnitude),
        }
    }
}

/// The parameter of a point of `p` on `range` within `tol` of `q` (or of the slack of a
/// fast parametrisation), `None` when there is none: the sub-pieces' control boxes (which
/// hold them, rational ones too) halved while they come within `tol` of `q`, and on a
/// flat sub-piece the foot of the perpendicular by Newton's method from its middle — a
/// flat piece has one foot, so when that is farther the piece is done. No polynomial of
/// twice the degree is solved: with weights far apart its roots lose the digits the
/// curve itself keeps.
pub(super) fn within(p: &Piece, range: (f64, f64), q: DVec2, tol: f64) -> Option<f64> {
    // Most points asked about are far from the whole segment's box.
    let (lo, hi) = p.bounds();
    if (lo - q).max(q - hi).max(DVec2::ZERO).length() > tol {
        return None;
    }
    near(p, &Sub::of(p, range.0, range.1), q, tol, 0)
}

/// [`within`] on a sub-segment (depth first, on the stack).
fn near(p: &Piece, s: &Sub, q: DVec2, tol: f64, depth: u32) -> Option<f64> {
    let (lo, hi) = s.bounds();
    let gap = (lo - q).max(q - hi).max(DVec2::ZERO).length();
    // The rounding of the oriented box's corners (relative to their coordinates) is
    // within twice the resolution.
    if gap > tol || s.oriented_gap(q) > 2.0 * tol {
        return None;
    }
    let small = (hi - lo).max_element() <= tol;
    let flat = s.flatness() <= 1e-2 * s.chord().length() && s.advances();
    if flat || small || depth >= 60 {
        let (s0, s1) = s.range();
        let (u, converged) = foot_converged(p, (s0, s1), q, 0.5 * (s0 + s1));
        let d = (p.point(u).truncate() - q).length();
        if d <= tol || d <= tol + slack(p, u) {
            return Some(u);
        }
        if (flat && converged) || small || depth >= 60 {
            return None;
        }
    }
    let (l, r) = s.halves();
    near(p, &l, q, tol, depth + 1).or_else(|| near(p, &r, q, tol, depth + 1))
}

/// How far the point of `p` moves when `u` moves by a few units in its last place: where
/// a parametrisation runs fast (weights far apart), no `f64` parameter lands closer to a
/// point of the curve than this.
pub(super) fn slack(p: &Piece, u: f64) -> f64 {
    4.0 * f64::EPSILON * u.abs() * p.deriv(u).truncate().length()
}

/// An end of one range lying on the other segment: `(u, v)`, and which of the two is an
/// end (exact).
#[derive(Debug, Clone, Copy)]
struct End {
    u: f64,
    v: f64,
    u_end: bool,
    v_end: bool,
}

/// The ends of both ranges that lie on the other segment, the same point found from both
/// sides (two ends meeting) once.
fn ends_on(a: &Piece, ra: (f64, f64), b: &Piece, rb: (f64, f64), tol: f64) -> Vec<End> {
    let mut out: Vec<End> = Vec::with_capacity(4);
    for u in [ra.0, ra.1] {
        if let Some(v) = within(b, rb, a.point(u).truncate(), tol) {
            out.push(End {
                u,
                v,
                u_end: true,
                v_end: v == rb.0 || v == rb.1,
            });
        }
    }
    for v in [rb.0, rb.1] {
        let q = b.point(v).truncate();
        if let Some(u) = within(a, ra, q, tol) {
            // The same point found from both sides (two ends meeting, or an end where a
            // parametrisation runs so slowly that its parameter is loosely determined).
            let same = out.iter_mut().find(|e| {
                let near = |p: DVec2| (p - q).length() <= 2.0 * tol;
                near(a.point(e.u).truncate())
                    && near(b.point(e.v).truncate())
                    && near(b.point(0.5 * (e.v + v)).truncate())
            });
            match same {
                Some(e) => {
                    e.v = v;
                    e.v_end = true;
                }
                None => out.push(End {
                    u,
                    v,
                    u_end: u == ra.0 || u == ra.1,
                    v_end: true,
                }),
            }
        }
    }
    out.dedup_by(|x, y| x.u == y.u && x.v == y.v);
    out
}

/// Whether `a` on `[u0, u1]` lies on `b` on the range between `v0` and `v1` at `count`
/// points, their parameters on `b` running from `v0` towards `v1`. The points sit at
/// irrational fractions of the range (so that a self-crossing at a simple fraction is not
/// one of them), and each is looked for on `b` between the last one's parameter and `v1`
/// (a self-crossing's other branch lies elsewhere).
fn coincide(a: &Piece, (u0, u1): (f64, f64), b: &Piece, (v0, v1): (f64, f64), tol: f64) -> bool {
    let count = (a.degree() * b.degree()).clamp(7, 64);
    let mut last = v0;
    for k in 0..count {
        let f = (k as f64 + 0.5 + 0.381_966_011_250_105_2 * 0.5) / (count as f64 + 0.5);
        let u = u0 + (u1 - u0) * f;
        // Between the last parameter and the far end, with the closest point's resolution.
        let slack = 1e-9 * (v1 - v0).abs();
        let window = if v1 >= v0 {
            ((last - slack).max(v0.min(v1)), v1)
        } else {
            (v1, (last + slack).min(v0.max(v1)))
        };
        let Some(v) = within(b, window, a.point(u).truncate(), tol) else {
            return false;
        };
        last = v;
    }
    true
}

/// The coincident stretches between pairs of ends, the longest kept where they nest.
fn stretches(a: &Piece, b: &Piece, ends: &[End], tol: f64) -> Vec<SpanPair> {
    let mut found: Vec<SpanPair> = Vec::new();
    for i in 0..ends.len() {
        for j in (i + 1)..ends.len() {
            let (p, q) = (ends[i], ends[j]);
            let (p, q) = if p.u <= q.u { (p, q) } else { (q, p) };
            if q.u - p.u <= 1e-12 || (q.v - p.v).abs() <= 1e-12 {
                continue;
            }
            if coincide(a, (p.u, q.u), b, (p.v, q.v), tol) {
                found.push(((p.u, q.u), (p.v, q.v)));
            }
        }
    }
    // Keep the maximal ones: drop a stretch inside another, join ones that meet.
    found.sort_by(|x, y| x.0.0.total_cmp(&y.0.0).then(y.0.1.total_cmp(&x.0.1)));
    let mut out: Vec<SpanPair> = Vec::new();
    for s in found {
        match out.last_mut() {
            Some(last) if s.0.1 <= last.0.1 => {}
            Some(last) if s.0.0 <= last.0.1 && (s.1.0 - last.1.1).abs() <= 1e-9 => {
                last.0.1 = s.0.1;
                last.1.1 = s.1.1;
            }
            _ => out.push(s),
        }
    }
    out
}

/// `range` without the given intervals.
fn outside(range: (f64, f64), cut: impl Iterator<Item = (f64, f64)>) -> Vec<(f64, f64)> {
    let mut parts = vec![range];
    for (c0, c1) in cut {
        let (lo, hi) = (c0.min(c1), c0.max(c1));
        parts = parts
            .into_iter()
            .flat_map(|(r0, r1)| {
                let mut out = Vec::with_capacity(2);
                if lo > r0 {
                    out.push((r0, lo.min(r1)));
                }
                if hi < r1 {
                    out.push((hi.max(r0), r1));
                }
                out
            })
            .filter(|(r0, r1)| r1 > r0)
            .collect();
    }
    parts
}

/// Whether `x` lies in one of the intervals (ends included, to `1e−9`).
fn in_any(x: f64, spans: impl Iterator<Item = (f64, f64)>) -> bool {
    spans
        .into_iter()
        .any(|(p, q)| x >= p.min(q) - 1e-9 && x <= p.max(q) + 1e-9)
}

/// The point of `p` at `u` and a bound on its rounding error.
fn point_error(p: &Piece, u: f64) -> f64 {
    p.point_error(u)
}

/// The band around a point `(u, v)` where the curves meet, in which `a` stays within the
/// resolution of `b`, and how the distance grows where it leaves it.
#[derive(Debug, Clone, Copy)]
struct Band {
    /// How far `u` may move inside it (the larger side).
    u: f64,
    /// How far `v` moves with it.
    v: f64,
    /// The smallest ratio, over the sides that leave the band inside the ranges (with
    /// perpendicular feet on `b`), of the distance at four times the exit step to the
    /// distance at it: about 4 where the distance grows linearly (a crossing), `4^{k+1}`
    /// at a contact of order `k` (a tangency). `None` when no side does.
    growth: Option<f64>,
    /// The side of `b` (the sign of the distance along `b`'s left normal) on which `a`
    /// lies where it leaves the band, walking backwards and forwards (`0` where it does
    /// not leave it with a perpendicular foot).
    sides: [f64; 2],
}

/// Walks from `(u, v)` along `a` both ways, the step doubling from `start`, each point's
/// foot on `b` followed, until the distance exceeds `tol` (plus the parametrisations'
/// slack). Both curves continue a little past their ranges (by `10⁻³` of them, as the
/// polynomials they are), so that two curves meeting at their ends are measured as the
/// smooth curves they are there: a G1 join grows like a tangency, a corner like a
/// crossing.
fn band(
    a: &Piece,
    ra: (f64, f64),
    b: &Piece,
    rb: (f64, f64),
    (u, v): (f64, f64),
    tol: f64,
    start: f64,
) -> Band {
    let mut out = Band {
        u: 4.0 * f64::EPSILON,
        v: 4.0 * f64::EPSILON,
        growth: None,
        sides: [0.0; 2],
    };
    let grow = |r: (f64, f64)| {
        let e = 1e-3 * (r.1 - r.0);
        (r.0 - e, r.1 + e)
    };
    let (xa, xb) = (grow(ra), grow(rb));
    let distance = |x: f64, fv: f64| -> (f64, f64, f64) {
        let p = a.point(x).truncate();
        let fv = foot(b, xb, p, fv);
        let d = (p - b.point(fv).truncate()).length();
        (fv, d, d - slack(a, x) - slack(b, fv))
    };
    let floor = 4.0 * f64::EPSILON * u.abs().max(1e-300);
    for dir in [-1.0, 1.0] {
        let mut step = start.max(floor);
        // The first step inside the band (so that the exit step is at most twice its edge).
        while step > floor {
            let x = (u + dir * step).max(xa.0).min(xa.1);
            if distance(x, v).2 <= tol {
                break;
            }
            step *= 0.5;
        }
        let mut fv = v;
        loop {
            let x = (u + dir * step).max(xa.0).min(xa.1);
            let at_end = x == xa.0 || x == xa.1;
            let (nv, d, beyond) = distance(x, fv);
            fv = nv;
            out.u = out.u.max((x - u).abs());
            out.v = out.v.max((fv - v).abs());
            if beyond > tol {
                // How the distance grows: at four times the step (inside the range; far
                // enough past the band that the evaluations' rounding, of the order of
                // the band's edge, cannot blur a linear growth into a quadratic one or
                // back). Only where
                // both feet are perpendicular ones, inside `b`: past `b`'s end the distance
                // is to that end point and grows linearly whatever the contact (two curves
                // joined end to start with a common tangent would read as a crossing).
                let x2 = u + dir * 4.0 * step;
                let inside = |f: f64| f > xb.0 && f < xb.1;
                if inside(fv) {
                    let (q, d) = b.point_and_deriv(fv);
                    let gap = a.point(x).truncate() - q.truncate();
                    out.sides[usize::from(dir > 0.0)] = d.truncate().perp_dot(gap).signum();
                }
                if x2 >= xa.0 && x2 <= xa.1 && inside(fv) {
                    let (fv2, d2, _) = distance(x2, fv);
                    if inside(fv2) {
                        let g = d2 / d;
                        out.growth = Some(out.growth.map_or(g, |h: f64| h.min(g)));
                    }
                }
                break;
            }
            if at_end {
                break;
            }
            step *= 2.0;
        }
    }
    out
}

/// The kind and errors of a point where the curves meet (see the module docs).
fn classify(
    a: &Piece,
    ra: (f64, f64),
    b: &Piece,
    rb: (f64, f64),
    (u, v, residual): (f64, f64, f64),
    scale: Scale,
) -> PairHit {
    let tol = scale.tol;
    let ((_, da), (_, db)) = (a.point_and_deriv(u), b.point_and_deriv(v));
    let (da, db) = (da.truncate(), db.truncate());
    let (la, lb) = (da.length(), db.length());
    let sin = da.perp_dot(db).abs() / (la * lb);
    // How far each parameter can move before the curves are `tol` apart, at this angle.
    let (band_u, band_v) = (tol / (la * sin), tol / (lb * sin));
    let noise = point_error(a, u) + point_error(b, v) + residual;
    let crossing = PairHit {
        u,
        v,
        kind: HitKind::Crossing,
        err_u: 2.0 * noise / (la * sin) + f64::EPSILON * u.abs(),
        err_v: 2.0 * noise / (lb * sin) + f64::EPSILON * v.abs(),
    };
    // A tangency can hide near a crossing only within a few bands, where the curves'
    // curvatures bring the tangents parallel: θ² ≲ 8 δ |Δκ|. At an angle over 0.05 rad
    // that needs a radius of curvature under `10⁻⁵ δ / ε`, a cusp to within rounding.
    let could_touch = sin.is_nan()
        || sin <= 1e-3
        || sin <= 0.05 && {
            let (ka, kb) = (curvature(a, u), curvature(b, v));
            let dk = if da.dot(db) >= 0.0 { ka - kb } else { ka + kb };
            sin * sin <= 64.0 * tol * (dk.abs() + 1.0 / scale.size)
        };
    // Where the condition number is not finite (a speed of zero at the point: a cusp, or
    // an end whose control points repeat), the parameters are known to the band in which
    // the curves stay within the resolution of each other, measured.
    let measured = |mut h: PairHit| {
        if !(h.err_u.is_finite() && h.err_v.is_finite()) {
            let found = band(a, ra, b, rb, (u, v), tol, 1e-9 * (ra.1 - ra.0));
            h.err_u = found.u.max(f64::EPSILON * u.abs());
            h.err_v = found.v.max(f64::EPSILON * v.abs());
        }
        h
    };
    if !could_touch {
        return measured(crossing);
    }
    // Where the tangents are parallel nearby and the curves still meet, that is the
    // candidate touching point; else the point itself.
    let (pu, pv) = match refine_tangent(a, b, u, v) {
        Some((tu, tv))
            if tu >= ra.0
                && tu <= ra.1
                && tv >= rb.0
                && tv <= rb.1
                && (a.point(tu) - b.point(tv)).truncate().length()
                    <= tol + slack(a, tu) + slack(b, tv)
                && ((tu - u).abs() <= 8.0 * band_u + 1e-15 || !band_u.is_finite())
                && ((tv - v).abs() <= 8.0 * band_v + 1e-15 || !band_v.is_finite()) =>
        {
            (tu, tv)
        }
        _ => (u, v),
    };
    // The distance grows linearly away from a crossing and at least quadratically away
    // from a tangency: the band's growth tells them apart, whatever the angle.
    let start = if band_u.is_finite() {
        0.25 * band_u
    } else {
        1e-9 * (ra.1 - ra.0)
    };
    let found = band(a, ra, b, rb, (pu, pv), tol, start);
    let touches = match found.growth {
        // Linear growth: 4 over four times the step; quadratic (a tangency): 16. Or `a`
        // leaves the band on one side of `b` both ways — it touches `b` from that side
        // (where it crosses, it leaves on opposite sides), though the growth on one
        // side was slowed by the curves meeting again close by.
        Some(g) => g >= 8.0 || (found.sides[0] != 0.0 && found.sides[0] == found.sides[1]),
        // The band fills both ranges: no way out to measure; parallel tangents decide.
        None => sin.is_nan() || sin <= 1e-7,
    };
    if !touches {
        return measured(crossing);
    }
    PairHit {
        u: pu,
        v: pv,
        kind: HitKind::Tangent,
        err_u: found.u,
        err_v: found.v,
    }
}

/// The signed curvature of a planar piece at `u` (0 where the speed vanishes).
fn curvature(p: &Piece, u: f64) -> f64 {
    let (d1, d2) = (p.deriv(u).truncate(), p.second_deriv(u).truncate());
    let s = d1.length();
    if s == 0.0 {
        return 0.0;
    }
    d1.perp_dot(d2) / (s * s * s)
}

/// Two hits are one point when each lies within the other's error (plus rounding).
fn same(x: &PairHit, y: &PairHit) -> bool {
    (x.u - y.u).abs() <= x.err_u + y.err_u + 4.0 * f64::EPSILON
        && (x.v - y.v).abs() <= x.err_v + y.err_v + 4.0 * f64::EPSILON
}

/// The subdivision's visitor: refines each leaf to a point, classifies it, and keeps it
/// unless it is one already found.
struct Points<'p> {
    a: &'p Piece,
    ra: (f64, f64),
    b: &'p Piece,
    rb: (f64, f64),
    scale: Scale,
    overlaps: &'p [SpanPair],
    hits: Vec<PairHit>,
    /// Converged points, to skip leaves that meet at most once and already hold one
    /// (neighbouring leaves share the point on their common edge).
    seen: Vec<(f64, f64)>,
    /// Around each tangency, the stretch `[u0, u1, v0, v1]` where the curves stay within
    /// the subdivision's flatness of each other (see [`Points::reach_out`]): scanned
    /// once, then skipped.
    reach: Vec<[f64; 4]>,
    /// Work beyond the leaves, in leaves' worth (see [`Leaves::extra_work`]).
    work: usize,
    /// Whether the pair is crowded (see [`Leaves::crowding`]): then ill-conditioned
    /// crossings reach out as tangencies do.
    crowded: bool,
}

impl Points<'_> {
    fn on_stretch(&self, u: f64, v: f64) -> bool {
        in_any(u, self.overlaps.iter().map(|o| o.0)) || in_any(v, self.overlaps.iter().map(|o| o.1))
    }
}

impl Leaves for Points<'_> {
    fn covered(&self, (u0, u1): (f64, f64), (v0, v1): (f64, f64)) -> bool {
        let reached = self
            .reach
            .iter()
            .any(|r| u0 >= r[0] && u1 <= r[1] && v0 >= r[2] && v1 <= r[3]);
        reached
            || self.hits.iter().any(|h| {
                h.kind == HitKind::Tangent
                    && u0 >= h.u - h.err_u
                    && u1 <= h.u + h.err_u
                    && v0 >= h.v - h.err_v
                    && v1 <= h.v + h.err_v
            })
    }

    fn extra_work(&self) -> usize {
        self.work
    }

    fn crowding(&mut self) {
        self.crowded = true;
        let wide: Vec<PairHit> = self
            .hits
            .iter()
            .filter(|h| h.kind == HitKind::Tangent || self.wide(h))
            .copied()
            .collect();
        for h in &wide {
            self.reach_out(h);
        }
    }

    fn leaf(&mut self, (u0, v0): (f64, f64), ranges: [f64; 4], single: bool) -> Rest {
        let (a, b, rb, tol) = (self.a, self.b, self.rb, self.scale.tol);
        let [lo_u, hi_u, lo_v, hi_v] = ranges;
        let inside = |u: f64, v: f64| u >= lo_u && u <= hi_u && v >= lo_v && v <= hi_v;
        if single && self.seen.iter().any(|&(su, sv)| inside(su, sv)) {
            return Rest::Done;
        }
        // Inside a tangent point's band is that point.
        let hits = &self.hits;
        let in_band = |u: f64, v: f64| {
            hits.iter().any(|h| {
                h.kind == HitKind::Tangent
                    && (h.u - u).abs() <= h.err_u
                    && (h.v - v).abs() <= h.err_v
            })
        };
        if in_band(u0, v0) {
            return Rest::Done;
        }
        let meets = |u: f64, v: f64, r: f64| r <= tol || r <= tol + slack(a, u) + slack(b, v);
        let (mut u, mut v, mut residual) = refine_until(a, b, u0, v0, in_band);
        if in_band(u, v) {
            return Rest::Done;
        }
        if !meets(u, v, residual) && !single {
            // Where Newton's method on the points stalls (a contact of high order), the
            // tangency conditions may still lead to the touching point.
            if let Some((tu, tv)) = refine_tangent(a, b, u, v) {
                let r = (a.point(tu) - b.point(tv)).truncate().length();
                if meets(tu, tv, r) {
                    (u, v, residual) = (tu, tv, r);
                }
            }
        }
        if meets(u, v, residual) {
            // A point, wherever it is; a pair meeting at most once whose Newton's method
            // went outside it (to a neighbour's point, or just past its edge) is examined
            // further.
            self.seen.push((u, v));
            let before = self.hits.len();
            let found = self.record(u, v, residual);
            if single {
                return if inside(u, v) {
                    Rest::Done
                } else {
                    Rest::Deeper
                };
            }
            // A flat leaf may hold more points than Newton's method reached (two crossings
            // close together, one at the leaf's end): every sign change of the distance
            // along it too; and a new point inside splits the leaf around it.
            let ext = (
                rb.0.max(lo_v - (hi_v - lo_v)),
                rb.1.min(hi_v + (hi_v - lo_v)),
            );
            self.scan((lo_u, hi_u), ext, v);
            return match found {
                Some(h) if self.hits.len() > before && inside(h.u, h.v) => Rest::Beside(
                    h.u - h.err_u - 4.0 * f64::EPSILON,
                    h.u + h.err_u + 4.0 * f64::EPSILON,
                ),
                _ => Rest::Done,
            };
        }
        // Newton's method went astray (curves nearly parallel, where the linear model's
        // crossing lies far off): the sign changes of the signed distance along `a`.
        let ext = (
            rb.0.max(lo_v - (hi_v - lo_v)),
            rb.1.min(hi_v + (hi_v - lo_v)),
        );
        let found = self.scan((lo_u, hi_u), ext, 0.5 * (lo_v + hi_v));
        if found || !single {
            Rest::Done
        } else {
            Rest::Deeper
        }
    }
}

impl Points<'_> {
    /// The points of a flat leaf, `u` on `range_u`, that Newton's method from one start
    /// does not reach: every sign change of the distance along it, and every touching
    /// point where the distance dips to zero without changing sign (a tangency beside a
    /// crossing, where Newton's method goes to the crossing). Whether any was kept.
    fn scan(&mut self, range_u: (f64, f64), range_v: (f64, f64), v: f64) -> bool {
        let (a, b, tol) = (self.a, self.b, self.scale.tol);
        let meets = |u: f64, v: f64| {
            let r = (a.point(u) - b.point(v)).truncate().length();
            (r <= tol || r <= tol + slack(a, u) + slack(b, v)).then_some(r)
        };
        let gaps = sign_changes(a, range_u, b, range_v, v, tol);
        // Nine feet, and a root closed for each sign change (where the curves run within
        // the resolution of each other, rounding changes the sign often).
        self.work += 1 + 4 * (gaps.crossings.len() + gaps.touches.len());
        let mut found = false;
        for (u, v) in gaps.crossings {
            if let Some(r) = meets(u, v) {
                self.seen.push((u, v));
                self.record(u, v, r);
                found = true;
            }
        }
        for (u, v) in gaps.touches {
            if let Some((tu, tv)) = refine_tangent(a, b, u, v)
                && tu >= range_u.0
                && tu <= range_u.1
                && let Some(r) = meets(tu, tv)
            {
                self.seen.push((tu, tv));
                self.record(tu, tv, r);
                found = true;
            }
        }
        found
    }

    /// Classifies a point where the curves meet and keeps it unless it is one already
    /// found (a tangency replaces a crossing it stands for); the point as kept.
    fn record(&mut self, u: f64, v: f64, residual: f64) -> Option<PairHit> {
        let (a, b, ra, rb) = (self.a, self.b, self.ra, self.rb);
        if u < ra.0 || u > ra.1 || v < rb.0 || v > rb.1 || self.on_stretch(u, v) {
            return None;
        }
        // Inside a tangency's band: that tangency (no need to classify it again).
        if let Some(h) = self.hits.iter().find(|h| {
            h.kind == HitKind::Tangent && (h.u - u).abs() <= h.err_u && (h.v - v).abs() <= h.err_v
        }) {
            return Some(*h);
        }
        self.work += CLASSIFY_WORK;
        let h = classify(a, ra, b, rb, (u, v, residual), self.scale);
        if self.on_stretch(h.u, h.v) {
            return None;
        }
        let kept = match self.hits.iter_mut().find(|x| same(x, &h)) {
            Some(x) => {
                if h.kind == HitKind::Tangent && x.kind == HitKind::Crossing {
                    // The tangency stands for both; an end's exact parameter stays, its
                    // band widened to hold the tangency's.
                    let keep = *x;
                    *x = h;
                    if keep.err_u == 0.0 {
                        x.u = keep.u;
                        x.err_u = (h.u - keep.u).abs() + h.err_u;
                    }
                    if keep.err_v == 0.0 {
                        x.v = keep.v;
                        x.err_v = (h.v - keep.v).abs() + h.err_v;
                    }
                } else if h.kind == HitKind::Tangent {
                    // Two tangencies whose bands meet are one contact (of high order, or
                    // a stretch where the curves stay within the resolution): its band
                    // holds both, so that the subdivision skips all of it.
                    x.err_u = x.err_u.max((h.u - x.u).abs() + h.err_u);
                    x.err_v = x.err_v.max((h.v - x.v).abs() + h.err_v);
                }
                *x
            }
            None => {
                self.hits.push(h);
                h
            }
        };
        // A tangency, or a crossing so ill-conditioned that the curves run within the
        // resolution of each other for a stretch around it (nearly parallel there).
        if kept.kind == HitKind::Tangent || (self.crowded && self.wide(&kept)) {
            self.reach_out(&kept);
        }
        Some(kept)
    }

    /// Whether a hit is a crossing so ill-conditioned that the curves run within the
    /// resolution of each other for a stretch around it.
    fn wide(&self, h: &PairHit) -> bool {
        h.kind == HitKind::Crossing && h.err_u > WIDE * (self.ra.1 - self.ra.0)
    }

    /// Past a tangency's band the curves may stay closer than the subdivision's flatness
    /// for a long way (a contact of high order: two curves sharing their first control
    /// points part like `s^k`), where fat lines cannot separate them and the leaves
    /// would be counted in millions. That stretch, walked out to where the distance
    /// passes the flatness, is scanned instead — the sign changes and dips of the signed
    /// distance, in pieces no longer than a fraction of the stretch — and then skipped.
    fn reach_out(&mut self, h: &PairHit) {
        let (a, b, ra, rb, tol) = (self.a, self.b, self.ra, self.rb, self.scale.tol);
        // Out to where flat pieces (their hulls within twice the flatness of the curve)
        // part by more than the margin.
        let flat = 4.0 * FLAT * tol;
        let inside = |u0: f64, u1: f64, v0: f64, v1: f64| {
            self.reach
                .iter()
                .any(|r| u0 >= r[0] && u1 <= r[1] && v0 >= r[2] && v1 <= r[3])
        };
        if inside(h.u, h.u, h.v, h.v) {
            return;
        }
        let mut ends = [(h.u, h.v); 2];
        for (side, dir) in [-1.0_f64, 1.0].into_iter().enumerate() {
            // (From the rounding of the parameter, not of 0: a walk from a subnormal step
            // would take a thousand doublings.)
            let mut step = h.err_u.max(4.0 * f64::EPSILON * h.u.abs().max(ra.1 - ra.0));
            let (mut last, mut fv) = (h.u, h.v);
            loop {
                let x = (h.u + dir * step).max(ra.0).min(ra.1);
                let p = a.point(x).truncate();
                let nv = foot(b, rb, p, fv);
                let d = (p - b.point(nv).truncate()).length() - slack(a, x) - slack(b, nv);
                if d.is_nan() || d > flat {
                    break;
                }
                (last, fv) = (x, nv);
                if x == ra.0 || x == ra.1 {
                    break;
                }
                step *= 2.0;
            }
            ends[side] = (last, fv);
        }
        const PARTS: usize = 64;
        let [(u0, v0), (u1, v1)] = ends;
        let (v0, v1) = (v0.min(v1), v0.max(v1));
        // Not worth it for a stretch the subdivision crosses in a few leaves (an ordinary
        // tangency or join, whose flat leaves are scanned for touching points anyway) —
        // unless the pair is crowded already.
        let worth = if self.crowded {
            64.0 * h.err_u.max(1e-12 * (ra.1 - ra.0))
        } else {
            REACH_WORTH * (ra.1 - ra.0)
        };
        if u1 - u0 <= worth || inside(u0, u1, v0, v1) {
            return;
        }
        self.work += PARTS;
        // Kept first: a tangency the scan finds inside it reaches no further.
        self.reach.push([u0, u1, v0, v1]);
        let width = (u1 - u0) / PARTS as f64;
        let ext = (rb.0.max(v0 - (v1 - v0)), rb.1.min(v1 + (v1 - v0)));
        for k in 0..PARTS {
            let lo = u0 + width * k as f64;
            let hi = if k + 1 == PARTS { u1 } else { lo + width };
            let v = foot(b, ext, a.point(0.5 * (lo + hi)).truncate(), 0.5 * (v0 + v1));
            self.scan((lo, hi), ext, v);
        }
    }
}

/// The signed distance from `a(u)` to `b` (its foot followed from `v`, on `range`): along
/// `b`'s left normal.
fn signed_gap(a: &Piece, u: f64, b: &Piece, range: (f64, f64), v: f64) -> (f64, f64) {
    let p = a.point(u).truncate();
    let v = foot(b, range, p, v);
    let (q, d) = b.point_and_deriv(v);
    let (q, d) = (q.truncate(), d.truncate());
    let len = d.length();
    let h = if len > 0.0 {
        d.perp_dot(p - q) / len
    } else {
        (p - q).length()
    };
    (h, v)
}

/// What the signed distance from `a` to `b` shows along a leaf: where it changes sign,
/// and where it comes close to zero without changing sign (a touching point may lie
/// there).
#[derive(Debug, Default)]
struct Gaps {
    /// Sign changes, each closed to the last bits: points `(u, v)`.
    crossings: Vec<(f64, f64)>,
    /// Samples `(u, v)` where `|h|` is smallest among its neighbours of the same sign and
    /// the parabola through the three samples reaches within `tol` of zero, or past it.
    touches: Vec<(f64, f64)>,
}

/// Where the signed distance from `a` to `b` changes sign on `(u0, u1)`: sampled at nine
/// points, each change bracketed and closed by the Illinois method to the last bits; and
/// where it dips towards zero between samples of one sign (see [`Gaps`]).
fn sign_changes(
    a: &Piece,
    (u0, u1): (f64, f64),
    b: &Piece,
    range: (f64, f64),
    v_start: f64,
    tol: f64,
) -> Gaps {
    const SAMPLES: usize = 9;
    let mut gaps = Gaps::default();
    let out = &mut gaps.crossings;
    let mut samples = [(0.0, 0.0, 0.0); SAMPLES];
    let mut v = v_start;
    let mut prev: Option<(f64, f64, f64)> = None;
    for (k, sample) in samples.iter_mut().enumerate() {
        let u = u0 + (u1 - u0) * k as f64 / (SAMPLES - 1) as f64;
        let (h, nv) = signed_gap(a, u, b, range, v);
        v = nv;
        *sample = (u, h, v);
        if h == 0.0 {
            out.push((u, v));
        } else if let Some((pu, ph, pv)) = prev
            && ph != 0.0
            && (ph < 0.0) != (h < 0.0)
        {
            // Illinois: regula falsi, the stale end's value halved.
            let (mut lo, mut hlo, mut hi, mut hhi) = (pu, ph, u, h);
            let mut vm = pv;
            let mut side = 0;
            for _ in 0..200 {
                let m = if hhi != hlo {
                    (lo - hlo * (hi - lo) / (hhi - hlo))
                        .max(lo.min(hi))
                        .min(lo.max(hi))
                } else {
                    0.5 * (lo + hi)
                };
                let (hm, nv) = signed_gap(a, m, b, range, vm);
                vm = nv;
                if hm == 0.0 || (hi - lo).abs() <= 4.0 * f64::EPSILON * m.abs().max(1e-300) {
                    lo = m;
                    hi = m;
                    break;
                }
                if (hm < 0.0) == (hlo < 0.0) {
                    lo = m;
                    hlo = hm;
                    if side == -1 {
                        hhi *= 0.5;
                    }
                    side = -1;
                } else {
                    hi = m;
                    hhi = hm;
                    if side == 1 {
                        hlo *= 0.5;
                    }
                    side = 1;
                }
            }
            let m = 0.5 * (lo + hi);
            let (_, nv) = signed_gap(a, m, b, range, vm);
            out.push((m, nv));
        }
        prev = Some((u, h, v));
    }
    for w in samples.windows(3) {
        let [(_, h0, _), (u, h, v), (_, h2, _)] = [w[0], w[1], w[2]];
        let same = (h0 > 0.0 && h > 0.0 && h2 > 0.0) || (h0 < 0.0 && h < 0.0 && h2 < 0.0);
        if !same || h.abs() > h0.abs() || h.abs() > h2.abs() {
            continue;
        }
        // The parabola through the three: its extreme value.
        let curl = h0 - 2.0 * h + h2;
        let lowest = if curl != 0.0 {
            h - (h2 - h0) * (h2 - h0) / (8.0 * curl)
        } else {
            h
        };
        if lowest.abs() <= tol || (lowest > 0.0) != (h > 0.0) {
            gaps.touches.push((u, v));
        }
    }
    gaps
}

/// The subdivision's work bound for a pair of segments.
pub(super) fn max_leaves_of(a: &Piece, b: &Piece) -> usize {
    max_leaves(a.degree(), b.degree())
}

/// The points and overlaps of two segments on the given ranges of their own parameters.
pub(super) fn piece_pair(a: &Piece, ra: (f64, f64), b: &Piece, rb: (f64, f64)) -> PieceHits {
    let scale = Scale::of(a, b);
    let tol = scale.tol;
    // Most pairs whose boxes overlap lie on either side of a line: nothing to find.
    let (sa, sb) = (Sub::of(a, ra.0, ra.1), Sub::of(b, rb.0, rb.1));
    if sa.separated_from(&sb, tol) {
        return PieceHits::default();
    }
    let ends = ends_on(a, ra, b, rb, tol);
    let overlaps = if ends.len() >= 2 {
        stretches(a, b, &ends, tol)
    } else {
        Vec::new()
    };
    let on_stretch = |u: f64, v: f64| {
        in_any(u, overlaps.iter().map(|o| o.0)) || in_any(v, overlaps.iter().map(|o| o.1))
    };
    let mut hits: Vec<PairHit> = Vec::new();
    // The ends first: their parameters are exact on one side.
    for e in &ends {
        if on_stretch(e.u, e.v) {
            continue;
        }
        let residual = (a.point(e.u) - b.point(e.v)).truncate().length();
        // A join (an end of each) whose tangent lines are one, to rounding: the curves
        // share their tangent there — a G1 join, or an S through it — whatever the
        // distance does past it (each curve stops there; how they part is a matter of
        // their higher terms, which the growth test would read through the rounding).
        if e.u_end && e.v_end {
            let (da, db) = (a.deriv(e.u).truncate(), b.deriv(e.v).truncate());
            let sin = da.perp_dot(db).abs() / (da.length() * db.length());
            if sin <= JOIN_PARALLEL {
                let h = PairHit {
                    u: e.u,
                    v: e.v,
                    kind: HitKind::Tangent,
                    err_u: 0.0,
                    err_v: 0.0,
                };
                if !hits.iter().any(|x| same(x, &h)) {
                    hits.push(h);
                }
                continue;
            }
        }
        let mut h = classify(a, ra, b, rb, (e.u, e.v, residual), scale);
        // A crossing keeps the end's exact parameter; a tangency found at the end too.
        if h.kind == HitKind::Crossing || (h.u - e.u).abs() <= h.err_u {
            if e.u_end {
                h.u = e.u;
                if h.kind == HitKind::Crossing {
                    h.err_u = 0.0;
                    let lb = b.deriv(e.v).truncate().length();
                    let noise = point_error(a, e.u) + point_error(b, e.v) + residual;
                    h.err_v = h.err_v.min(2.0 * noise / lb + f64::EPSILON * e.v.abs());
                }
            }
            if e.v_end {
                h.v = e.v;
                if h.kind == HitKind::Crossing {
                    h.err_v = 0.0;
                    if !e.u_end {
                        let la = a.deriv(e.u).truncate().length();
                        let noise = point_error(a, e.u) + point_error(b, e.v) + residual;
                        h.err_u = h.err_u.min(2.0 * noise / la + f64::EPSILON * e.u.abs());
                    }
                }
            }
        }
        if !hits.iter().any(|x| same(x, &h)) {
            hits.push(h);
        }
    }
    // The rest of both ranges, subdivided; each leaf refined as it is found.
    let a_parts = outside(ra, overlaps.iter().map(|o| o.0));
    let b_parts = outside(rb, overlaps.iter().map(|o| o.1));
    let mut points = Points {
        a,
        ra,
        b,
        rb,
        scale,
        overlaps: &overlaps,
        hits,
        seen: Vec::new(),
        reach: Vec::new(),
        work: 0,
        crowded: false,
    };
    // The ends' tangencies reach out before the subdivision starts.
    let tangents: Vec<PairHit> = points
        .hits
        .iter()
        .filter(|h| h.kind == HitKind::Tangent)
        .copied()
        .collect();
    for h in &tangents {
        points.reach_out(h);
    }
    let mut sub = Subdivider {
        flat: FLAT * tol,
        margin: tol,
        visitor: &mut points,
        leaves: 0,
        max_leaves: max_leaves_of(a, b),
        crowded: None,
        crowding: false,
    };
    let whole = |r: (f64, f64), range: (f64, f64)| r == range;
    for &(b0, b1) in &b_parts {
        let part_b = (!whole((b0, b1), rb)).then(|| Sub::of(b, b0, b1));
        for &(a0, a1) in &a_parts {
            let part_a = (!whole((a0, a1), ra)).then(|| Sub::of(a, a0, a1));
            sub.run(
                part_a.as_ref().unwrap_or(&sa),
                part_b.as_ref().unwrap_or(&sb),
                0,
            );
        }
    }
    let crowded = sub.crowded;
    let mut hits = points.hits;
    hits.sort_by(|x, y| x.u.total_cmp(&y.u));
    PieceHits {
        hits,
        overlaps,
        crowded,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Bezier, BezierSegment};
    use crate::rng::Rng;
    use glam::DVec3;

    fn random_piece(rng: &mut Rng, degree: usize, rational: bool) -> Piece {
        let points = (0..=degree)
            .map(|_| DVec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), 0.0))
            .collect();
        let weights = rational.then(|| (0..=degree).map(|_| rng.range(0.1, 10.0)).collect());
        Piece::new(&BezierSegment {
            bezier: Bezier::new(points),
            weights,
            t0: 0.0,
            t1: 1.0,
        })
    }

    #[test]
    fn a_point_near_the_curve_is_within_and_a_far_one_is_not() {
        let mut rng = Rng::new(5);
        for case in 0..400 {
            let p = random_piece(&mut rng, 1 + case % 7, case % 2 == 1);
            let tol = 10f64.powf(rng.range(-12.0, -2.0));
            let (u0, u1) = if case % 3 == 0 {
                (rng.range(0.0, 0.5), rng.range(0.5, 1.0))
            } else {
                (0.0, 1.0)
            };
            // On the curve, then moved by less than the tolerance in any direction.
            let u = rng.range(u0, u1);
            let angle = rng.range(0.0, std::f64::consts::TAU);
            let near = p.point(u).truncate()
                + 0.9 * tol * rng.unit() * DVec2::new(angle.cos(), angle.sin());
            assert!(
                within(&p, (u0, u1), near, tol).is_some(),
                "case {case}: a point within {tol} of the curve at u = {u} called off"
            );
            // Far outside the unit square the points lie in.
            let far = DVec2::new(5.0 * angle.cos(), 5.0 * angle.sin());
            assert!(
                within(&p, (u0, u1), far, tol).is_none(),
                "case {case}: {far}"
            );
        }
    }
}
