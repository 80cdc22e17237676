//! A curve as cubic or quadratic segments within a tolerance, with a **proven** bound.
//!
//! Each lowered segment (any degree, rational or not) is cut into pieces, uniformly into
//! `k = 1, 2, …, 64` first (the fewest that fit), then, if none does, by halving where a
//! piece does not fit. Each piece `S(u)`, `u ∈ [0, 1]` gets an approximant `B(u)` with its
//! end points: a cubic with the piece's end tangents (Hermite: `B₁ = S(0) + S′(0)/3`,
//! `B₂ = S(1) − S′(1)/3`), or a quadratic whose middle point is the average of
//! `S(0) + S′(0)/2` and `S(1) − S′(1)/2` (for a cubic, its degree reduction
//! `(3 (P₁ + P₂) − P₀ − P₃) / 4`, as fontTools' cu2qu builds its splines: it follows the
//! piece's parametrisation, which the bound measures). An exact lower-degree segment is
//! kept (raised exactly to the target degree).
//!
//! **The bound.** For every `u`, `|S(u) − B(u)|` bounds the distance of `S(u)` from the
//! approximant and of `B(u)` from the piece, so its maximum bounds the Hausdorff distance.
//! `S − B = N / W` with `N = A − B·W` (`A`, `W` the piece's homogeneous numerator and
//! weight; `W = 1` for a polynomial piece) a polynomial in Bernstein form. On any interval
//! a Bernstein polynomial lies in the hull of its coefficients and `W` is at least its
//! least coefficient (the weights are positive), so `max |N_i| / min W_i` bounds `|S − B|`
//! there; the interval is halved until that bound is within the tolerance (or a point of
//! it is not, and the piece is refused). The bound reported is the largest over all
//! pieces: every point of the result is within it of the curve and every point of the
//! curve within it of the result.

use glam::DVec3;

use crate::geom::{BezierSegment, GeomError, Path, PathSegment};
use crate::poly;

use super::OpError;

/// The degree of the segments made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// Quadratic segments (what TrueType stores).
    Quadratic,
    /// Cubic segments (what CFF, SVG and PDF store).
    Cubic,
}

impl Target {
    fn degree(self) -> usize {
        match self {
            Target::Quadratic => 2,
            Target::Cubic => 3,
        }
    }
}

/// A path of segments of the target degree, with the proven bound on its Hausdorff
/// distance from the curve it approximates.
#[derive(Debug, Clone, PartialEq)]
pub struct Approximation {
    /// The segments, end to end.
    pub path: Path,
    /// A bound on the Hausdorff distance between the path and the curve (at most the
    /// tolerance asked for).
    pub error: f64,
}

/// The most pieces one lowered segment may be cut into (halving stops here).
pub const MAX_PIECES_PER_SEGMENT: usize = 1 << 14;

/// Uniform cuts tried before halving: the fewest equal pieces that fit, up to this many.
const UNIFORM_MAX: usize = 64;

/// How deep the bound's halving of one piece's difference may go.
const BOUND_DEPTH: u32 = 10;

/// A piece in homogeneous Bernstein form: per coordinate `A_k` and the weight `W`.
#[derive(Debug, Clone)]
struct Piece {
    a: [Vec<f64>; 3],
    w: Option<Vec<f64>>,
}

impl Piece {
    fn of(seg: &BezierSegment) -> Piece {
        let pts = seg.bezier.points();
        let a = [0, 1, 2].map(|k| match &seg.weights {
            Some(w) => pts.iter().zip(w).map(|(p, w)| p[k] * w).collect(),
            None => pts.iter().map(|p| p[k]).collect(),
        });
        Piece {
            a,
            w: seg.weights.clone(),
        }
    }

    fn degree(&self) -> usize {
        self.a[0].len() - 1
    }

    /// The piece on `[u0, u1]`, reparametrised to `[0, 1]`.
    fn restricted(&self, u0: f64, u1: f64) -> Piece {
        Piece {
            a: [0, 1, 2].map(|k| poly::restrict(&self.a[k], u0, u1)),
            w: self.w.as_ref().map(|w| poly::restrict(w, u0, u1)),
        }
    }

    /// The Euclidean control point `i`.
    fn point(&self, i: usize) -> DVec3 {
        let v = DVec3::new(self.a[0][i], self.a[1][i], self.a[2][i]);
        match &self.w {
            Some(w) => v / w[i],
            None => v,
        }
    }

    /// The derivative at the start (`end = false`) or the end.
    fn end_derivative(&self, end: bool) -> DVec3 {
        let n = self.degree();
        let (i, j) = if end { (n - 1, n) } else { (0, 1) };
        let ratio = self
            .w
            .as_ref()
            .map_or(1.0, |w| if end { w[i] / w[j] } else { w[j] / w[i] });
        n as f64 * ratio * (self.point(j) - self.point(i))
    }

    /// Whether it is a polynomial of degree at most `degree` already (its coefficients
    /// are those of one, exactly): then it is kept, raised exactly.
    fn exact_at(&self, degree: usize) -> Option<Vec<DVec3>> {
        if self
            .w
            .as_ref()
            .is_some_and(|w| w.iter().any(|&x| x != w[0]))
        {
            return None;
        }
        let n = self.degree();
        (n <= degree).then(|| {
            let pts: Vec<DVec3> = (0..=n).map(|i| self.point(i)).collect();
            raise(&pts, degree)
        })
    }
}

/// `pts` (a polynomial Bézier curve) raised to `degree` exactly (degree elevation).
fn raise(pts: &[DVec3], degree: usize) -> Vec<DVec3> {
    let coords = [0, 1, 2].map(|k| {
        let c: Vec<f64> = pts.iter().map(|p| p[k]).collect();
        poly::elevate_to(&c, degree)
    });
    (0..=degree)
        .map(|i| DVec3::new(coords[0][i], coords[1][i], coords[2][i]))
        .collect()
}

/// The approximant of a piece: its control points.
fn approximant(piece: &Piece, target: Target) -> Vec<DVec3> {
    let n = piece.degree();
    let (p0, p1) = (piece.point(0), piece.point(n));
    let (d0, d1) = (piece.end_derivative(false), piece.end_derivative(true));
    match target {
        Target::Cubic => vec![p0, p0 + d0 / 3.0, p1 - d1 / 3.0, p1],
        Target::Quadratic => {
            // The average of the two points the end tangents reach in half a parameter
            // step (a cubic's own degree reduction, `(3 (P₁ + P₂) − P₀ − P₃) / 4`): it
            // follows the piece's parametrisation, which the bound measures.
            let q = 0.5 * ((p0 + 0.5 * d0) + (p1 - 0.5 * d1));
            vec![p0, q, p1]
        }
    }
}

/// A proven bound on `max |S(u) − B(u)|` over `[0, 1]`, or `None` when it exceeds
/// `tolerance` (a point of the difference is beyond it, or the halving ran out).
fn difference_bound(piece: &Piece, b: &[DVec3], tolerance: f64) -> Option<f64> {
    let m = b.len() - 1;
    let n = piece.degree();
    // N = A − B W (W = 1: A − B), per coordinate, at one degree.
    let (num, w): ([Vec<f64>; 3], Option<Vec<f64>>) = match &piece.w {
        Some(w) => (
            [0, 1, 2].map(|k| {
                let bk: Vec<f64> = b.iter().map(|p| p[k]).collect();
                let bw = poly::product(&bk, w);
                poly::difference(&poly::elevate_to(&piece.a[k], m + n), &bw)
            }),
            Some(w.clone()),
        ),
        None => {
            let d = n.max(m);
            (
                [0, 1, 2].map(|k| {
                    let bk: Vec<f64> = b.iter().map(|p| p[k]).collect();
                    poly::difference(&poly::elevate_to(&piece.a[k], d), &poly::elevate_to(&bk, d))
                }),
                None,
            )
        }
    };
    bound_rec(&num, w.as_deref(), tolerance, 0)
}

/// A proven bound on `max |N(u)| / W(u)` over `[0, 1]` within `tolerance`, or `None`
/// when it exceeds it (see the module docs); `N` per coordinate, `W` (when given) positive.
pub(super) fn bound_within(num: &[Vec<f64>; 3], w: Option<&[f64]>, tolerance: f64) -> Option<f64> {
    bound_rec(num, w, tolerance, 0)
}

/// A proven bound on `max |N(u)|` over `[0, 1]` with no tolerance to stop at: the largest
/// hull of `N`'s coefficients over `2^depth` equal parts.
pub(super) fn hull_bound(num: &[Vec<f64>; 3], depth: u32) -> f64 {
    let parts = 1usize << depth;
    (0..parts)
        .map(|j| {
            let (lo, hi) = (j as f64 / parts as f64, (j + 1) as f64 / parts as f64);
            let part = [0, 1, 2].map(|k| poly::restrict(&num[k], lo, hi));
            (0..part[0].len())
                .map(|i| DVec3::new(part[0][i], part[1][i], part[2][i]).length())
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

fn bound_rec(num: &[Vec<f64>; 3], w: Option<&[f64]>, tolerance: f64, depth: u32) -> Option<f64> {
    let len = num[0].len();
    let w_min = w.map_or(1.0, |w| w.iter().copied().fold(f64::INFINITY, f64::min));
    let hull = (0..len)
        .map(|i| DVec3::new(num[0][i], num[1][i], num[2][i]).length())
        .fold(0.0, f64::max)
        / w_min;
    if hull <= tolerance {
        return Some(hull);
    }
    // A point beyond the tolerance: the piece does not fit.
    let at = |u: f64| {
        let v = DVec3::new(
            poly::eval(&num[0], u),
            poly::eval(&num[1], u),
            poly::eval(&num[2], u),
        );
        v.length() / w.map_or(1.0, |w| poly::eval(w, u))
    };
    if at(0.5) > tolerance || depth >= BOUND_DEPTH {
        return None;
    }
    let halves = |lo: f64, hi: f64| {
        let part = [0, 1, 2].map(|k| poly::restrict(&num[k], lo, hi));
        let wp = w.map(|w| poly::restrict(w, lo, hi));
        bound_rec(&part, wp.as_deref(), tolerance, depth + 1)
    };
    let left = halves(0.0, 0.5)?;
    let right = halves(0.5, 1.0)?;
    Some(left.max(right))
}

/// The segments for one lowered segment, with their bound.
fn segment_pieces(
    seg: &BezierSegment,
    target: Target,
    tolerance: f64,
) -> Result<(Vec<PathSegment>, f64), OpError> {
    let piece = Piece::of(seg);
    if let Some(pts) = piece.exact_at(target.degree()) {
        return Ok((vec![PathSegment::polynomial(pts)], 0.0));
    }
    // Uniform cuts first: the fewest pieces that all fit.
    'uniform: for k in 1..=UNIFORM_MAX {
        let mut out = Vec::with_capacity(k);
        let mut worst: f64 = 0.0;
        for j in 0..k {
            let part = piece.restricted(j as f64 / k as f64, (j + 1) as f64 / k as f64);
            let b = approximant(&part, target);
            match difference_bound(&part, &b, tolerance) {
                Some(e) => worst = worst.max(e),
                None => continue 'uniform,
            }
            out.push(b);
        }
        return Ok((join_ends(out, &piece), worst));
    }
    // Then halving where a piece does not fit.
    let mut out: Vec<Vec<DVec3>> = Vec::new();
    let mut worst: f64 = 0.0;
    let mut stack = vec![(0.0_f64, 1.0_f64)];
    while let Some((u0, u1)) = stack.pop() {
        let part = piece.restricted(u0, u1);
        let b = approximant(&part, target);
        if let Some(e) = difference_bound(&part, &b, tolerance) {
            worst = worst.max(e);
            out.push(b);
            continue;
        }
        if out.len() + stack.len() + 2 > MAX_PIECES_PER_SEGMENT || u1 - u0 < 1e-12 {
            return Err(OpError::TooManyPieces {
                limit: MAX_PIECES_PER_SEGMENT,
                tolerance,
            });
        }
        let mid = 0.5 * (u0 + u1);
        // Right first: the stack pops the left half next, keeping the order.
        stack.push((mid, u1));
        stack.push((u0, mid));
    }
    Ok((join_ends(out, &piece), worst))
}

/// The pieces as path segments, consecutive ones sharing their end points exactly (each
/// piece's ends are the curve's points, computed once for both neighbours) and the first
/// and last on the segment's own end points.
fn join_ends(mut pieces: Vec<Vec<DVec3>>, piece: &Piece) -> Vec<PathSegment> {
    let n = piece.degree();
    let count = pieces.len();
    if let Some(first) = pieces.first_mut() {
        first[0] = piece.point(0);
    }
    if let Some(last) = pieces.last_mut() {
        let end = last.len() - 1;
        last[end] = piece.point(n);
    }
    for j in 1..count {
        let shared = pieces[j - 1][pieces[j - 1].len() - 1];
        pieces[j][0] = shared;
    }
    pieces.into_iter().map(PathSegment::polynomial).collect()
}

/// The segments of `lowered` (a curve's lowering, end to end) as a path of segments of
/// `target`'s degree within `tolerance` of it (`closed` for a closed curve), with the
/// proven bound.
///
/// # Errors
/// [`OpError::Tolerance`] for a tolerance that is not a finite number greater than 0;
/// [`OpError::TooManyPieces`] when a segment needs more than [`MAX_PIECES_PER_SEGMENT`]
/// pieces; [`OpError::Geom`] when the pieces do not join (a lowering with gaps).
pub fn approximate(
    lowered: &[BezierSegment],
    closed: bool,
    target: Target,
    tolerance: f64,
) -> Result<Approximation, OpError> {
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(OpError::Tolerance(tolerance));
    }
    let mut segments = Vec::new();
    let mut error: f64 = 0.0;
    for seg in lowered {
        let (pieces, e) = segment_pieces(seg, target, tolerance)?;
        segments.extend(pieces);
        error = error.max(e);
    }
    let path = Path::try_new(segments, closed).map_err(|e: GeomError| OpError::Geom(e))?;
    Ok(Approximation { path, error })
}
