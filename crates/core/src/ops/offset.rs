//! Offset (parallel) curves of planar curves as cubic paths within a tolerance, with a
//! **proven** bound on the Hausdorff distance from the true offset; cusps, joins at
//! kinks, the outline of a stroke with caps, and loops trimmed.
//!
//! The offset of `C` by `d` is `O(t) = C(t) + d n(t)`, `n = J C′ / |C′|` the left unit
//! normal (`J (x, y) = (−y, x)`: `d > 0` offsets to the left of the direction of travel,
//! in y-up coordinates). `O′ = (1 − d κ) C′` (`κ` the signed curvature), so the offset has
//! a **cusp** where `d κ = 1`; the segments are cut there, at the roots of
//! `Q³ − d² W⁴ K²` with `d K > 0` (`H = A′W − AW′` the direction of `C′` for the
//! homogeneous `A/W`, `Q = |H|²`, `K = H × H′`, so that `κ = K W² / Q^{3/2}`), and each
//! part runs with `s = sign(1 − dκ)` fixed: forward, or backward in a loop.
//!
//! **The pieces.** Each part is covered greedily by the longest pieces that fit (the
//! longest whose error at a few points is within the tolerance, found by bisection, then
//! shortened until its bound is proven): a cubic `B` with the offset's end points and end
//! tangent directions (`s C′/|C′|`), its two handle lengths (at least 0) fitted to 20
//! samples of the offset — first at the samples' orthogonal feet on `B` (a geometric fit:
//! parameters Newton-corrected each round, the weights then reweighted by Lawson's rule
//! toward the least largest distance rather than the least squares), else at the
//! offset's own parameters (a parametric fit, by least squares).
//!
//! **The bound of a geometric fit** (every point of `B` and of the offset within `ε` of
//! the other). Let `G(u, t) = s (W(t) B(u) − A(t)) · H(t)`, zero exactly where `B(u)`
//! lies on the normal of `C` at `t`. `B`'s parameter is cut into intervals `U_i`; on each,
//! with `ψ` the chord between the feet (numerical roots of `G`) at its ends, a strip
//! `|t − ψ(u)| ≤ r` is checked in Bernstein form: `G > 0` along its lower edge and `G < 0`
//! along its upper edge (polynomials in `u` once `t` is the edge's line; where an edge
//! leaves `[0, 1]` it runs along `t = 0` or `t = 1` instead, and at the piece's own end
//! `G`'s zero there is left out), and `∂G/∂t < 0` on the box holding the strip (the
//! tensor-product Bernstein coefficients). So for each `u` there is exactly one root
//! `t = φ(u)`, within `r` of `ψ(u)`; neighbouring strips overlap around their shared root,
//! so `φ` is continuous on `[0, 1]` with `φ(0) = 0`, `φ(1) = 1`: it reaches every `t`. At a
//! root `B(u) − C(t) = λ n(t)` and `|B(u) − O(t)| = |λ − d|`; with `X = H × (W B − A)`
//! (so `λ = X / (W |H|)`) and `V = W² Q`, `λ² − d² = Z / V`, `Z = X² − d² V`. Along `ψ`,
//! `Z` is a polynomial in `u` (its hull bounds it), and within the strip it moves by at
//! most `r max |∂Z/∂t|` (the tensor hull of `2 X ∂X/∂t − d² V′` on the box); with `e` that
//! sum over `min V` and `e < d²`, `λ` is never 0 and starts at `d`, so keeps `d`'s sign,
//! and `|λ − d| = |λ² − d²| / (|λ| + |d|) ≤ e / (|d| + √(d² − e))`. Each `u` is then within
//! that of `O(φ(u))` and each `t` within it of `B(φ⁻¹(t))`.
//!
//! **Next to a cusp** the normals of `C` cross (`∂G/∂t` is 0 at the cusp), so the end box
//! is covered by a ball instead: `B` on it lies within `ρ_B` (its control points' hull) of
//! the cusp point `P = B(end) = O(end)`, and `O` between the cusp and `τ` (twice as far as
//! the box's other foot) within `ρ_O ≤ |τ − end| max |1 − dκ| max |C′|` of it (`O′ =
//! (1 − dκ) C′`; `|1 − dκ| ≤ max |Q³ − d²K²W⁴| / min Q³` from the hulls), and the strip
//! beside must hold its root on the near side of `τ`. The end box is halved until the ball
//! is small enough; the corner coefficient of `∂G/∂t` at the cusp (0 there, up to
//! rounding) is not asked to be negative.
//!
//! **The bound of a parametric fit** (used where the normals of `C` crowd, next to a
//! cusp): `|B(u) − O(u)|` with `B(u) − O(u) = E_T T + E_n n`, `E_T = N · H / (W |H|)`
//! (`N = W B − A`) and `|E_n| = |λ − d|` as above with `X = H × N` at the same parameter;
//! each bounded from the hulls of the polynomials `N · H`, `Z` and `V` on intervals
//! halved until the bound holds.
//!
//! **The rest.** A segment's end with (nearly) zero speed is moved by at most `δ =
//! tolerance / 1000` so that its normal is defined (the curve moves by at most `δ`: its
//! points are convex combinations of its control points); a segment with a stationary
//! point inside is cut there (a kink). Kinks get a join on their outer side — a round
//! join of cubic arcs (their radial error bounded from the hull of `|B − c|² − r²`), a
//! miter (bevel past the limit) or a bevel — and a line on the inner side. The error
//! reported is the largest piece bound plus `δ` where an end moved plus the largest gap
//! closed between pieces computed separately.

use glam::DVec3;

use crate::analysis::curve::CurveAnalysis;
use crate::geom::{BezierSegment, Curve, Lower, ParamCurve, Path, PathSegment};
use crate::poly::{self, roots};

use super::OpError;
use super::approx;
use super::fit::handle_lengths;
use crate::geom::bezier::{de_casteljau, deriv_at, second_deriv_at};

/// How a stroke turns where its direction changes (SVG's `stroke-linejoin`), and how an
/// offset's outer side is joined at a kink: what the renderer draws and what
/// [`offset`] makes are the same join.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Join {
    /// A circular arc (a disc of the stroke's width) around the corner (the default).
    #[default]
    Round,
    /// The outer edges extended until they meet, unless the spike would be longer than
    /// the miter limit times the width (`|d|` for an offset): then [`Join::Bevel`].
    Miter,
    /// The outer corners joined by a straight line.
    Bevel,
}

/// How an open stroke's two ends are drawn (SVG's `stroke-linecap`), and how a stroke
/// outline closes them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Cap {
    /// A half disc of the stroke's width beyond each end (the default).
    #[default]
    Round,
    /// Cut square at the end point.
    Butt,
    /// Cut square half the width beyond the end point.
    Square,
}

/// The choices of an offset.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OffsetOptions {
    /// The join at kinks.
    pub join: Join,
    /// The most a miter may reach out, as a multiple of `|d|` (SVG's `stroke-miterlimit`:
    /// `1 / cos(φ/2)` for a turn by `φ`); at least 1.
    pub miter_limit: f64,
    /// `Some(cap)`: the outline of a stroke of half width `|d|` (both sides, joined by the
    /// caps at an open curve's ends; a closed curve's outline is its two offsets).
    pub caps: Option<Cap>,
    /// Remove the loops the offset makes where `|d|` passes the radius of curvature (and
    /// at the inner side of kinks): the parts of the raw offset closer to the curve than
    /// `|d|`.
    pub trim: bool,
}

impl Default for OffsetOptions {
    fn default() -> Self {
        OffsetOptions {
            join: Join::Round,
            miter_limit: 4.0,
            caps: None,
            trim: false,
        }
    }
}

/// An offset: its paths of cubic segments and the proven bound on their Hausdorff
/// distance from the true offset (or stroke outline).
#[derive(Debug, Clone, PartialEq)]
pub struct Offset {
    /// The paths: one for an offset (more where trimming cuts it apart), the outline's
    /// one (open curve) or two (closed curve) with caps.
    pub paths: Vec<Path>,
    /// The bound on the Hausdorff distance (at most the tolerance).
    pub error: f64,
    /// How many cusps the raw offset has (where `d κ = 1`).
    pub cusps: usize,
}

/// The most pieces one offset may have (the work is refused past it).
pub const MAX_OFFSET_PIECES: usize = 1 << 14;

/// The finest tolerance an offset is proven to, relative to the curve's size plus `|d|`
/// (the bounds' own rounding is far below it; finer asks would only cost time).
pub const RELATIVE_FLOOR: f64 = 1e-9;

/// Samples of the offset each fit uses.
const SAMPLES: usize = 20;
/// Rounds of a geometric fit (parameters corrected, then reweighted toward minimax).
const FIT_ROUNDS: usize = 24;
/// How deep a piece's bound may cut its parameter.
const VERIFY_DEPTH: u32 = 9;
/// How deep at an end next to a cusp (the ball there shrinks with the box).
const CUSP_DEPTH: u32 = 30;
/// The share of the tolerance the search's estimate aims at (the proof then has room).
const ESTIMATE_SHARE: f64 = 0.97;
/// How much shorter the next try is when a piece's bound is not shown.
const SHRINK: f64 = 0.9;
/// Bisections of the longest piece that fits before settling.
const SEARCH_STEPS: usize = 10;

fn cross(a: DVec3, b: DVec3) -> f64 {
    a.x * b.y - a.y * b.x
}

fn perp(v: DVec3) -> DVec3 {
    DVec3::new(-v.y, v.x, 0.0)
}

/// Binomial coefficients `C(n, k)`, `k = 0..=n`.
fn binomials(n: usize) -> Vec<f64> {
    let mut c = vec![1.0; n + 1];
    for k in 1..=n {
        c[k] = c[k - 1] * (n + 1 - k) as f64 / k as f64;
    }
    c
}

/// The coefficients of `p` on `[a, b]` (`a < 1`), which may reach a little outside
/// `[0, 1]` (de Casteljau's steps extrapolate there).
fn restrict_any(c: &[f64], a: f64, b: f64) -> Vec<f64> {
    if a >= 0.0 && b <= 1.0 {
        return poly::restrict(c, a, b);
    }
    let right = poly::split(c, a).1;
    poly::split(&right, (b - a) / (1.0 - a)).0
}

/// Largest and least coefficient.
fn hull(c: &[f64]) -> (f64, f64) {
    c.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        })
}

/// A segment in homogeneous Bernstein form, planar: `A = (A_x, A_y)` and `W` (`[1]` for a
/// polynomial one).
#[derive(Debug, Clone)]
struct Seg {
    a: [Vec<f64>; 2],
    w: Vec<f64>,
}

impl Seg {
    fn of_points(points: &[DVec3], weights: Option<&[f64]>) -> Seg {
        match weights {
            Some(w) => Seg {
                a: [0, 1].map(|k| points.iter().zip(w).map(|(p, w)| p[k] * w).collect()),
                w: w.to_vec(),
            },
            None => Seg {
                a: [0, 1].map(|k| points.iter().map(|p| p[k]).collect()),
                w: vec![1.0],
            },
        }
    }

    fn restricted(&self, t0: f64, t1: f64) -> Seg {
        Seg {
            a: [0, 1].map(|k| poly::restrict(&self.a[k], t0, t1)),
            w: if self.w.len() == 1 {
                self.w.clone()
            } else {
                poly::restrict(&self.w, t0, t1)
            },
        }
    }

    fn euclidean(&self) -> (Vec<DVec3>, Option<Vec<f64>>) {
        let n = self.a[0].len();
        let rational = self.w.len() > 1;
        let pts = (0..n)
            .map(|i| {
                let w = if rational { self.w[i] } else { self.w[0] };
                DVec3::new(self.a[0][i] / w, self.a[1][i] / w, 0.0)
            })
            .collect();
        (pts, rational.then(|| self.w.clone()))
    }
}

/// A segment's derived polynomials: `A′`, `W′`, `H = A′W − AW′`, `H′`.
#[derive(Debug, Clone)]
struct Geo {
    seg: Seg,
    da: [Vec<f64>; 2],
    dw: Vec<f64>,
    h: [Vec<f64>; 2],
    dh: [Vec<f64>; 2],
}

impl Geo {
    fn new(seg: Seg) -> Geo {
        let da = [0, 1].map(|k| poly::derivative(&seg.a[k]));
        let (dw, h) = if seg.w.len() == 1 {
            (vec![0.0], [0, 1].map(|k| poly::scaled(&da[k], seg.w[0])))
        } else {
            let dw = poly::derivative(&seg.w);
            let h = [0, 1].map(|k| {
                poly::difference(
                    &poly::product(&da[k], &seg.w),
                    &poly::product(&seg.a[k], &dw),
                )
            });
            (dw, h)
        };
        let dh = [0, 1].map(|k| poly::derivative(&h[k]));
        Geo { seg, da, dw, h, dh }
    }

    fn w_at(&self, t: f64) -> f64 {
        poly::eval(&self.seg.w, t)
    }

    fn a_at(&self, t: f64) -> DVec3 {
        DVec3::new(
            poly::eval(&self.seg.a[0], t),
            poly::eval(&self.seg.a[1], t),
            0.0,
        )
    }

    fn h_at(&self, t: f64) -> DVec3 {
        DVec3::new(poly::eval(&self.h[0], t), poly::eval(&self.h[1], t), 0.0)
    }

    fn point(&self, t: f64) -> DVec3 {
        self.a_at(t) / self.w_at(t)
    }

    fn tangent(&self, t: f64) -> DVec3 {
        self.h_at(t).normalize_or_zero()
    }

    fn offset_at(&self, t: f64, d: f64) -> DVec3 {
        self.point(t) + d * perp(self.tangent(t))
    }

    /// `Q = |H|²`.
    fn q(&self) -> Vec<f64> {
        poly::sum(
            &poly::product(&self.h[0], &self.h[0]),
            &poly::product(&self.h[1], &self.h[1]),
        )
    }

    /// `V = W² Q`.
    fn v(&self) -> Vec<f64> {
        let q = self.q();
        if self.seg.w.len() == 1 {
            poly::scaled(&q, self.seg.w[0] * self.seg.w[0])
        } else {
            poly::product(&poly::product(&self.seg.w, &self.seg.w), &q)
        }
    }

    /// `K = H × H′`.
    fn k(&self) -> Vec<f64> {
        poly::difference(
            &poly::product(&self.h[0], &self.dh[1]),
            &poly::product(&self.h[1], &self.dh[0]),
        )
    }
}

/// The polynomials in `t` the geometric bound needs, at common degrees.
struct Tensors {
    /// `∂G/∂t = s (B_x P_x + B_y P_y − R₀)`: `[P_x, P_y, R₀]`.
    gt: [Vec<f64>; 3],
    /// `X = B_x M_x + B_y M_y − R₁`: `[M_x, M_y, R₁]`.
    x: [Vec<f64>; 3],
    /// `V = W² Q` at twice `X`'s degree.
    v: Vec<f64>,
}

impl Tensors {
    fn new(g: &Geo) -> Tensors {
        let w = &g.seg.w;
        let a = &g.seg.a;
        let prod = |p: &[f64], q: &[f64]| poly::product(p, q);
        let px = poly::sum(&prod(&g.dw, &g.h[0]), &prod(w, &g.dh[0]));
        let py = poly::sum(&prod(&g.dw, &g.h[1]), &prod(w, &g.dh[1]));
        let r0 = poly::sum(
            &poly::sum(&prod(&g.da[0], &g.h[0]), &prod(&g.da[1], &g.h[1])),
            &poly::sum(&prod(&a[0], &g.dh[0]), &prod(&a[1], &g.dh[1])),
        );
        let mx = poly::scaled(&prod(&g.h[1], w), -1.0);
        let my = prod(&g.h[0], w);
        let r1 = poly::difference(&prod(&g.h[0], &a[1]), &prod(&g.h[1], &a[0]));
        let common = |v: [Vec<f64>; 3]| {
            let deg = v.iter().map(|c| c.len() - 1).max().unwrap_or(0);
            v.map(|c| poly::elevate_to(&c, deg))
        };
        let x = common([mx, my, r1]);
        let m = x[0].len() - 1;
        let v = poly::elevate_to(&g.v(), 2 * m);
        Tensors {
            gt: common([px, py, r0]),
            x,
            v,
        }
    }
}

/// The cubic's control points restricted to `[u0, u1]`.
fn cubic_restricted(b: &[DVec3; 4], u0: f64, u1: f64) -> [DVec3; 4] {
    let c = [0, 1].map(|k| poly::restrict(&b.iter().map(|p| p[k]).collect::<Vec<_>>(), u0, u1));
    std::array::from_fn(|i| DVec3::new(c[0][i], c[1][i], 0.0))
}

/// `|λ − d|` from `e ≥ |λ² − d²|`, or `None` when `e ≥ d²` (λ could vanish).
fn normal_error(e: f64, d: f64) -> Option<f64> {
    (e < d * d).then(|| e / (d.abs() + (d * d - e).sqrt()))
}

/// What a geometric check found.
enum Check {
    Fits(f64),
    /// A point of `B` is farther than the tolerance from the offset.
    TooFar,
    /// Not shown either way (the normals crowd): try the parametric fit.
    Undecided,
}

/// What the boxes of one geometric check pass on, left to right: after a cusp's ball at
/// the start, where the next box starts and the `τ` its root must stay below; the last
/// strip's end and the least `t` of its root there.
#[derive(Debug, Default)]
struct Chain {
    start: Option<(f64, f64)>,
    end: Option<(f64, f64)>,
}

/// One piece of a part: the segment restricted, and the quantities the fits need.
struct Piece {
    g: Geo,
    d: f64,
    s: f64,
    /// Whether the piece starts (ends) at a cusp of the offset, where `∂G/∂t` is 0 at the
    /// corner `(0, 0)` (`(1, 1)`).
    cusp: (bool, bool),
}

impl Piece {
    /// The foot `t` of `p` on the curve's normals near `guess` (Newton on `G`).
    fn foot(&self, p: DVec3, guess: f64) -> f64 {
        let g = &self.g;
        let mut t = guess;
        for _ in 0..12 {
            let (w, a, h) = (g.w_at(t), g.a_at(t), g.h_at(t));
            let dw = poly::eval(&g.dw, t);
            let da = DVec3::new(poly::eval(&g.da[0], t), poly::eval(&g.da[1], t), 0.0);
            let dh = DVec3::new(poly::eval(&g.dh[0], t), poly::eval(&g.dh[1], t), 0.0);
            let f = (w * p - a).dot(h);
            let df = (dw * p - da).dot(h) + (w * p - a).dot(dh);
            if df == 0.0 || !df.is_finite() {
                break;
            }
            let next = (t - f / df).clamp(0.0, 1.0);
            if (next - t).abs() < 1e-15 {
                t = next;
                break;
            }
            t = next;
        }
        t
    }

    /// The geometric bound of `b` over `[0, 1]` (see the module docs).
    fn check_geometric(&self, b: &[DVec3; 4], tensors: &Tensors, tol: f64) -> Check {
        let mut chain = Chain::default();
        self.check_box(
            b,
            tensors,
            (0.0, 1.0),
            (0.0, 1.0),
            tol,
            (0, VERIFY_DEPTH),
            &mut chain,
        )
    }

    #[allow(clippy::too_many_arguments)]
    fn check_box(
        &self,
        b: &[DVec3; 4],
        tensors: &Tensors,
        (ua, ub): (f64, f64),
        (fa, fb): (f64, f64),
        tol: f64,
        depth: (u32, u32),
        chain: &mut Chain,
    ) -> Check {
        let cusp_start = ua == 0.0 && self.cusp.0;
        let cusp_end = ub == 1.0 && self.cusp.1;
        let um = 0.5 * (ua + ub);
        let pm = de_casteljau(b, um);
        let fm = self.foot(pm, 0.5 * (fa + fb));
        let foot_ok = fm > fa && fm < fb;
        if foot_ok && (pm - self.g.offset_at(fm, self.d)).length() > tol {
            return Check::TooFar;
        }
        if foot_ok {
            // The strip around the chord ψ of the feet: twice the middle's distance from it.
            let r = 2.0 * (fm - 0.5 * (fa + fb)).abs() + 1e-9 * (fb - fa) + 1e-15;
            let linked = chain.start.is_none_or(|(h, tau)| ua != h || fa + r <= tau);
            if linked
                && let Some(e) = self.strip_bound(b, tensors, (ua, ub), (fa, fb), r)
                && e <= tol
            {
                chain.end = Some((ub, fb - r));
                return Check::Fits(e);
            }
        }
        // Next to a cusp the normals cross: the ends are covered by a ball instead.
        if (cusp_start || cusp_end)
            && let Some(e) = self.cusp_ball(b, (ua, ub), (fa, fb), cusp_start, chain)
            && e <= tol
        {
            return Check::Fits(e);
        }
        // Each box may be cut VERIFY_DEPTH times; one at a cusp's end again and again (its
        // neighbours then get a fresh allowance), down to CUSP_DEPTH.
        let (depth, budget) = depth;
        let next = if budget > 0 {
            budget - 1
        } else if (cusp_start || cusp_end) && depth < CUSP_DEPTH {
            VERIFY_DEPTH / 2
        } else {
            return Check::Undecided;
        };
        if !foot_ok {
            return Check::Undecided;
        }
        let left = match self.check_box(
            b,
            tensors,
            (ua, um),
            (fa, fm),
            tol,
            (depth + 1, next),
            chain,
        ) {
            Check::Fits(e) => e,
            other => return other,
        };
        match self.check_box(
            b,
            tensors,
            (um, ub),
            (fm, fb),
            tol,
            (depth + 1, next),
            chain,
        ) {
            Check::Fits(e) => Check::Fits(left.max(e)),
            other => other,
        }
    }

    /// The bound on the end box `U` at a cusp (at `u = 0` when `start`, else `u = 1`):
    /// `B(U)` lies within `ρ_B` of the cusp point `P = B(end) = O(end)`, and `O` on the
    /// parameters between the end and `τ` (twice as far from it as the box's other foot)
    /// within `ρ_O` of it; the strip beside must then hold its root on that side of `τ`
    /// (checked through `chain`), so every point of either side is within `max(ρ_B, ρ_O)`
    /// of the other.
    fn cusp_ball(
        &self,
        b: &[DVec3; 4],
        (ua, ub): (f64, f64),
        (fa, fb): (f64, f64),
        start: bool,
        chain: &mut Chain,
    ) -> Option<f64> {
        let bu = cubic_restricted(b, ua, ub);
        let p = if start { b[0] } else { b[3] };
        let rho_b = bu.iter().map(|q| (*q - p).length()).fold(0.0, f64::max);
        let (t0, t1) = if start {
            (0.0, (2.0 * fb).min(1.0))
        } else {
            ((1.0 - 2.0 * (1.0 - fa)).max(0.0), 1.0)
        };
        if !start {
            // The strip before must end with its root above τ.
            if !chain.end.is_some_and(|(u, lower)| u == ua && lower >= t0) {
                return None;
            }
        }
        let rho_o = self.offset_radius(t0, t1);
        let rho_o = rho_o?;
        if start {
            chain.start = Some((ub, t1));
        }
        Some(rho_b.max(rho_o))
    }

    /// A bound on `|O(t) − O(end)|` over `[t0, t1]` (`end` the start when `start`):
    /// `O′ = (1 − dκ) C′`, so it is at most `(t1 − t0) max |1 − dκ| max |C′|`, with
    /// `|1 − dκ| = |Q³ − d²K²W⁴| / (Q^{3/2} (Q^{3/2} + dKW²)) ≤ max |Q³ − d²K²W⁴| / min Q³`
    /// (`dK ≥ 0` there, checked) and `|C′| = √Q / W²`, each from its Bernstein hull.
    fn offset_radius(&self, t0: f64, t1: f64) -> Option<f64> {
        let g = &self.g;
        let q = poly::restrict(&g.q(), t0, t1);
        let kw = poly::restrict(
            &poly::product(&g.k(), &poly::product(&g.seg.w, &g.seg.w)),
            t0,
            t1,
        );
        let (q_min, q_max) = hull(&q);
        let (kw_lo, kw_hi) = hull(&kw);
        if q_min <= 0.0 || (self.d > 0.0 && kw_lo < 0.0) || (self.d < 0.0 && kw_hi > 0.0) {
            return None;
        }
        let q3 = poly::product(&poly::product(&q, &q), &q);
        let n3 = poly::difference(
            &q3,
            &poly::scaled(&poly::product(&kw, &kw), self.d * self.d),
        );
        let (nlo, nhi) = hull(&n3);
        let w_min = if g.seg.w.len() == 1 {
            g.seg.w[0]
        } else {
            hull(&poly::restrict(&g.seg.w, t0, t1)).0
        };
        if w_min <= 0.0 {
            return None;
        }
        let factor = nlo.abs().max(nhi.abs()) / (q_min * q_min * q_min);
        Some((t1 - t0) * factor * q_max.sqrt() / (w_min * w_min))
    }

    /// Whether `G(u, t)` at `t = 0` (`> 0`) or `t = 1` (`< 0`) has its sign for every `u`
    /// of the restricted cubic `bu`; `at_end`: `bu` starts (ends) at the piece's end, where
    /// `G` is 0, its coefficients taken relative to that end.
    fn end_sign(&self, bu: &[DVec3; 4], t: f64, at_end: bool) -> bool {
        let (w, a, h) = (self.g.w_at(t), self.g.a_at(t), self.g.h_at(t));
        let (sign, end) = if t == 0.0 { (1.0, 0) } else { (-1.0, 3) };
        (0..4).filter(|&i| !(at_end && i == end)).all(|i| {
            let g = if at_end {
                w * (bu[i] - bu[end]).dot(h)
            } else {
                (w * bu[i] - a).dot(h)
            };
            sign * self.s * g > 0.0
        })
    }

    /// Whether `G` has its sign (`> 0` below the strip, `bound = 0`; `< 0` above it,
    /// `bound = 1`) along the edge line `t(σ) = e0 + σ (e1 − e0)` over the restricted cubic
    /// `bu`, the line cut where it leaves `[0, 1]` and continued along `t = bound`.
    fn edge_holds(&self, bu: &[DVec3; 4], (e0, e1): (f64, f64), bound: f64, at_end: bool) -> bool {
        let sign = if bound == 0.0 { 1.0 } else { -1.0 };
        let line_ok = |part: &[DVec3; 4], t0: f64, t1: f64| {
            self.along(part, t0, t1).iter().all(|&x| sign * x > 0.0)
        };
        let outside = |t: f64| if bound == 0.0 { t < 0.0 } else { t > 1.0 };
        match (outside(e0), outside(e1)) {
            (false, false) => line_ok(bu, e0, e1),
            (true, true) => self.end_sign(bu, bound, at_end),
            (o0, _) => {
                let cross = (bound - e0) / (e1 - e0);
                let head = cubic_restricted(bu, 0.0, cross);
                let tail = cubic_restricted(bu, cross, 1.0);
                if o0 {
                    // Outside first (the lower edge at the piece's start).
                    self.end_sign(&head, bound, at_end && bound == 0.0) && line_ok(&tail, bound, e1)
                } else {
                    line_ok(&head, e0, bound) && self.end_sign(&tail, bound, at_end && bound == 1.0)
                }
            }
        }
    }

    /// `G(u, t(σ))` along the line `t(σ) = t0 + σ (t1 − t0)` as `u` runs over the
    /// restricted cubic `bu` (`σ` its local parameter): a polynomial in `σ`.
    fn along(&self, bu: &[DVec3; 4], t0: f64, t1: f64) -> Vec<f64> {
        let g = &self.g;
        let w = restrict_any(&g.seg.w, t0, t1);
        let a = [0, 1].map(|k| restrict_any(&g.seg.a[k], t0, t1));
        let h = [0, 1].map(|k| restrict_any(&g.h[k], t0, t1));
        let bc = [0, 1].map(|k| bu.iter().map(|p| p[k]).collect::<Vec<f64>>());
        let n = [0, 1].map(|k| poly::difference(&poly::product(&w, &bc[k]), &a[k]));
        poly::scaled(
            &poly::sum(&poly::product(&n[0], &h[0]), &poly::product(&n[1], &h[1])),
            self.s,
        )
    }

    /// The bound on the strip `|t − ψ(u)| ≤ r` over `U` (`ψ` the chord from `(ua, fa)` to
    /// `(ub, fb)`), or `None` when a condition is not shown.
    fn strip_bound(
        &self,
        b: &[DVec3; 4],
        tensors: &Tensors,
        (ua, ub): (f64, f64),
        (fa, fb): (f64, f64),
        r: f64,
    ) -> Option<f64> {
        let bu = cubic_restricted(b, ua, ub);
        // The strip's edges: G > 0 below, G < 0 above, for every u in U.
        let (lo0, lo1) = (fa - r, fb - r);
        let (hi0, hi1) = (fa + r, fb + r);
        // Where an edge leaves [0, 1] it is cut there and runs along t = 0 (t = 1), where
        // G > 0 (G < 0) is asked instead: the roots stay inside, and still within r of ψ
        // (ψ is within r of the end there).
        if !self.edge_holds(&bu, (lo0, lo1), 0.0, ua == 0.0) {
            return None;
        }
        if !self.edge_holds(&bu, (hi0, hi1), 1.0, ub == 1.0) {
            return None;
        }
        let (ta, tb) = (lo0.max(0.0), hi1.min(1.0));
        // ∂G/∂t < 0 on the box holding the strip.
        // At a cusp's corner it is 0 (up to rounding): that one coefficient may be, and G
        // is still strictly decreasing in t for every u.
        let gt = tensors.gt.each_ref().map(|c| restrict_any(c, ta, tb));
        let last = gt[0].len() - 1;
        let coef =
            |i: usize, j: usize| self.s * (bu[i].x * gt[0][j] + bu[i].y * gt[1][j] - gt[2][j]);
        let scale = (0..4)
            .flat_map(|i| (0..=last).map(move |j| (i, j)))
            .fold(0.0_f64, |m, (i, j)| m.max(coef(i, j).abs()));
        let corner = |i: usize, j: usize| {
            let at_cusp = (i == 0 && j == 0 && self.cusp.0 && ua == 0.0 && ta == 0.0)
                || (i == 3 && j == last && self.cusp.1 && ub == 1.0 && tb == 1.0);
            at_cusp && coef(i, j).abs() <= 1e-9 * scale
        };
        for i in 0..4 {
            for j in 0..=last {
                if coef(i, j) >= 0.0 && !corner(i, j) {
                    return None;
                }
            }
        }
        let v = restrict_any(&tensors.v, ta, tb);
        let (v_min, _) = hull(&v);
        if v_min <= 0.0 {
            return None;
        }
        // Z along ψ (a polynomial in σ) …
        let xs = tensors.x.each_ref().map(|c| poly::restrict(c, fa, fb));
        let bc = [0, 1].map(|k| bu.iter().map(|p| p[k]).collect::<Vec<f64>>());
        let x = poly::difference(
            &poly::sum(
                &poly::product(&bc[0], &xs[0]),
                &poly::product(&bc[1], &xs[1]),
            ),
            &xs[2],
        );
        let vpsi = poly::restrict(&tensors.v, fa, fb);
        let z = poly::difference(
            &poly::product(&x, &x),
            &poly::scaled(&vpsi, self.d * self.d),
        );
        let (zlo, zhi) = hull(&z);
        // … and how far it can change within the strip: r max |∂Z/∂t| over the box.
        let xt = tensors.x.each_ref().map(|c| restrict_any(c, ta, tb));
        let dxt = tensors.x.each_ref().map(|c| {
            let d = poly::derivative(c);
            poly::elevate_to(&restrict_any(&d, ta, tb), c.len() - 1)
        });
        let m = xt[0].len() - 1;
        let tensor = |p: &[Vec<f64>; 3], scale: f64| -> Vec<f64> {
            bu.iter()
                .flat_map(|bi| (0..=m).map(move |j| (bi, j)))
                .map(|(bi, j)| scale * (bi.x * p[0][j] + bi.y * p[1][j] - p[2][j]))
                .collect()
        };
        let xtens = tensor(&xt, 1.0);
        // dX/dt in the box's local t is (tb − ta) times the derivative in t.
        let dxtens = tensor(&dxt, 1.0);
        let dv = poly::elevate_to(&restrict_any(&poly::derivative(&tensors.v), ta, tb), 2 * m);
        let zt = tensor_product_minus(&xtens, &dxtens, 3, m, &dv, 0.5 * self.d * self.d);
        let e = (zlo.abs().max(zhi.abs()) + r * 2.0 * zt) / v_min;
        normal_error(e, self.d)
    }

    /// The parametric bound of `b`: `max |B(u) − O(u)|` over `[0, 1]`.
    fn check_parametric(&self, b: &[DVec3; 4], tol: f64) -> Option<f64> {
        let g = &self.g;
        let bc = [0, 1].map(|k| b.iter().map(|p| p[k]).collect::<Vec<f64>>());
        let n = [0, 1].map(|k| {
            let wb = if g.seg.w.len() == 1 {
                poly::scaled(&bc[k], g.seg.w[0])
            } else {
                poly::product(&g.seg.w, &bc[k])
            };
            poly::difference(&wb, &g.seg.a[k])
        });
        let tn = poly::sum(
            &poly::product(&n[0], &g.h[0]),
            &poly::product(&n[1], &g.h[1]),
        );
        let x = poly::difference(
            &poly::product(&g.h[0], &n[1]),
            &poly::product(&g.h[1], &n[0]),
        );
        let v = g.v();
        let z = poly::difference(&poly::product(&x, &x), &poly::scaled(&v, self.d * self.d));
        self.parametric_rec(&tn, &z, &v, (0.0, 1.0), tol, 0)
    }

    fn parametric_rec(
        &self,
        tn: &[f64],
        z: &[f64],
        v: &[f64],
        (a, b): (f64, f64),
        tol: f64,
        depth: u32,
    ) -> Option<f64> {
        let (tnr, zr, vr) = (
            poly::restrict(tn, a, b),
            poly::restrict(z, a, b),
            poly::restrict(v, a, b),
        );
        let (v_min, _) = hull(&vr);
        if v_min > 0.0 {
            let (tlo, thi) = hull(&tnr);
            let (zlo, zhi) = hull(&zr);
            let et = tlo.abs().max(thi.abs()) / v_min.sqrt();
            if let Some(en) = normal_error(zlo.abs().max(zhi.abs()) / v_min, self.d) {
                let e = et.hypot(en);
                if e <= tol {
                    return Some(e);
                }
            }
        }
        if depth >= VERIFY_DEPTH + 2 {
            return None;
        }
        let m = 0.5 * (a + b);
        let l = self.parametric_rec(tn, z, v, (a, m), tol, depth + 1)?;
        let r = self.parametric_rec(tn, z, v, (m, b), tol, depth + 1)?;
        Some(l.max(r))
    }

    /// The fitted cubic: `geometric` with the samples' parameters corrected toward their
    /// feet on it, else at the offset's own parameters.
    fn fit(&self, geometric: bool) -> [DVec3; 4] {
        let us: Vec<f64> = (0..SAMPLES)
            .map(|j| j as f64 / (SAMPLES - 1) as f64)
            .collect();
        let pts: Vec<DVec3> = us.iter().map(|&u| self.g.offset_at(u, self.d)).collect();
        let t0 = self.s * self.g.tangent(0.0);
        let t1 = -self.s * self.g.tangent(1.0);
        let mut u = us.clone();
        let mut w = vec![1.0; SAMPLES];
        let mut c = handles(&pts, &u, &w, t0, t1);
        if geometric {
            for round in 0..FIT_ROUNDS {
                for j in 1..SAMPLES - 1 {
                    let v = u[j];
                    let (q, d1, d2) =
                        (de_casteljau(&c, v), deriv_at(&c, v), second_deriv_at(&c, v));
                    let f = (q - pts[j]).dot(d1);
                    let df = d1.dot(d1) + (q - pts[j]).dot(d2);
                    if df.abs() > 1e-300 {
                        u[j] = (v - f / df).clamp(0.0, 1.0);
                    }
                }
                // After a few plain rounds, Lawson's reweighting toward the least largest
                // distance (minimax) rather than the least squares.
                if round >= 2 {
                    let r: Vec<f64> = (0..SAMPLES)
                        .map(|j| (de_casteljau(&c, u[j]) - pts[j]).length())
                        .collect();
                    let total: f64 = w.iter().zip(&r).map(|(a, b)| a * b).sum();
                    if total > 0.0 {
                        for j in 0..SAMPLES {
                            w[j] = (w[j] * r[j] / total).max(1e-12);
                        }
                    }
                }
                c = handles(&pts, &u, &w, t0, t1);
            }
        }
        c[0] = pts[0];
        c[3] = pts[SAMPLES - 1];
        c
    }

    /// The geometric fit's largest distance from the offset at a few of its points (their
    /// feet): an estimate, to search with before proving.
    fn estimate(&self) -> f64 {
        let b = self.fit(true);
        (1..16)
            .map(|j| {
                let u = j as f64 / 16.0;
                let p = de_casteljau(&b, u);
                (p - self.g.offset_at(self.foot(p, u), self.d)).length()
            })
            .fold(0.0, f64::max)
    }

    /// The best fit of this piece within `tol`, with its bound, if one is shown.
    fn fitted(&self, tol: f64) -> Option<([DVec3; 4], f64)> {
        let b = self.fit(true);
        let tensors = Tensors::new(&self.g);
        match self.check_geometric(&b, &tensors, tol) {
            Check::Fits(e) => return Some((b, e)),
            Check::TooFar => return None,
            Check::Undecided => {}
        }
        let b = self.fit(false);
        self.check_parametric(&b, tol).map(|e| (b, e))
    }
}

/// The cubic from `pts[0]` to the last point with inner points along `t0`, `t1`, its two
/// handle lengths by weighted least squares ([`handle_lengths`]), each at least a
/// billionth of the chord (a vanishing handle suits an end at a cusp; a negative one would
/// loop); a singular system gives a third of the chord.
fn handles(pts: &[DVec3], u: &[f64], w: &[f64], t0: DVec3, t1: DVec3) -> [DVec3; 4] {
    let (p0, p3) = (pts[0], pts[pts.len() - 1]);
    let chord = (p3 - p0).length();
    let floor = 1e-9 * chord;
    let (l0, l1) = handle_lengths(pts, u, Some(w), t0, t1)
        .map_or((chord / 3.0, chord / 3.0), |(l0, l1)| {
            (l0.max(floor), l1.max(floor))
        });
    [p0, p0 + t0 * l0, p3 + t1 * l1, p3]
}

/// `max |X Y − k V|` over the tensor coefficients (`X`, `Y` of degrees `(nu, nt)`,
/// row-major by `u`; `V` a polynomial in `t` of degree `2 nt`).
fn tensor_product_minus(x: &[f64], y: &[f64], nu: usize, nt: usize, v: &[f64], k: f64) -> f64 {
    let (cu, ct) = (binomials(nu), binomials(nt));
    let (cu2, ct2) = (binomials(2 * nu), binomials(2 * nt));
    let w = nt + 1;
    let scale = |p: &[f64]| -> Vec<f64> {
        p.iter()
            .enumerate()
            .map(|(i, &pv)| pv * cu[i / w] * ct[i % w])
            .collect()
    };
    let (xs, ys) = (scale(x), scale(y));
    let w2 = 2 * nt + 1;
    let mut out = vec![0.0; (2 * nu + 1) * w2];
    for (k1, &a) in xs.iter().enumerate() {
        if a == 0.0 {
            continue;
        }
        let (i1, j1) = (k1 / w, k1 % w);
        for (k2, &b) in ys.iter().enumerate() {
            let (i2, j2) = (k2 / w, k2 % w);
            out[(i1 + i2) * w2 + j1 + j2] += a * b;
        }
    }
    let mut worst: f64 = 0.0;
    for (idx, s) in out.iter().enumerate() {
        let (i, j) = (idx / w2, idx % w2);
        worst = worst.max((s / (cu2[i] * ct2[j]) - k * v[j]).abs());
    }
    worst
}

/// A cubic arc of `center`, radius `r`, from angle `a0` sweeping `sweep` (`|sweep| ≤
/// π/2`), with its bound: the radial error from the hull of `|B − c|² − r²`, the angle
/// shown monotone by the hull of `(B − c) × B′`.
fn arc_piece(center: DVec3, r: f64, a0: f64, sweep: f64) -> ([DVec3; 4], f64) {
    let a1 = a0 + sweep;
    let k = 4.0 / 3.0 * (sweep / 4.0).tan();
    let (p0, p3) = (
        center + r * DVec3::new(a0.cos(), a0.sin(), 0.0),
        center + r * DVec3::new(a1.cos(), a1.sin(), 0.0),
    );
    let b = [
        p0,
        p0 + k * r * DVec3::new(-a0.sin(), a0.cos(), 0.0),
        p3 - k * r * DVec3::new(-a1.sin(), a1.cos(), 0.0),
        p3,
    ];
    let c = [0, 1].map(|i| b.iter().map(|p| p[i] - center[i]).collect::<Vec<f64>>());
    let z = poly::difference(
        &poly::sum(&poly::product(&c[0], &c[0]), &poly::product(&c[1], &c[1])),
        &[r * r],
    );
    let zeros = vec![0.0; z.len()];
    let e = approx::hull_bound(&[z, zeros.clone(), zeros], 4);
    let err = normal_error(e, r).unwrap_or(r);
    (b, err)
}

/// Cubic arcs from `from` (on the circle) sweeping `sweep`, each within `tol` (more pieces
/// until they are), appended to `out`; returns the bound.
fn arc(out: &mut Vec<[DVec3; 4]>, center: DVec3, from: DVec3, sweep: f64, tol: f64) -> f64 {
    let r = (from - center).length();
    if r == 0.0 || sweep == 0.0 {
        return 0.0;
    }
    let a0 = (from.y - center.y).atan2(from.x - center.x);
    let mut count = (sweep.abs() / std::f64::consts::FRAC_PI_2).ceil().max(1.0) as usize;
    loop {
        let step = sweep / count as f64;
        let pieces: Vec<([DVec3; 4], f64)> = (0..count)
            .map(|i| arc_piece(center, r, a0 + step * i as f64, step))
            .collect();
        let worst = pieces.iter().map(|p| p.1).fold(0.0, f64::max);
        if worst <= tol || count >= 4096 {
            let start = out.len();
            out.extend(pieces.into_iter().map(|p| p.0));
            out[start][0] = from;
            return worst;
        }
        count *= 2;
    }
}

fn line(a: DVec3, b: DVec3) -> [DVec3; 4] {
    [a, a + (b - a) / 3.0, a + (b - a) * (2.0 / 3.0), b]
}

/// The segments ready to offset: lowered, planar, stationary points inside cut out as
/// kinks, ends with (nearly) zero speed moved by at most `delta`.
fn prepare(lowered: &[BezierSegment], delta: f64) -> Vec<Geo> {
    let mut out = Vec::new();
    for s in lowered {
        let seg = Seg::of_points(s.bezier.points(), s.weights.as_deref());
        let (pts, _) = seg.euclidean();
        let size = pts
            .iter()
            .map(|p| (*p - pts[0]).length())
            .fold(0.0, f64::max);
        if size <= delta {
            continue; // a point: nothing to offset
        }
        // Stationary points inside: where Q is (nearly) zero at a minimum.
        let g = Geo::new(seg.clone());
        let q = g.q();
        let floor = (1e-9 * size * pts.len() as f64).powi(2)
            * seg.w.iter().fold(0.0_f64, |m, w| m.max(w * w * w * w));
        let mut cuts: Vec<f64> = roots::bernstein_roots(&poly::derivative(&q))
            .roots
            .iter()
            .map(|r| r.t)
            .filter(|&t| t > 1e-9 && t < 1.0 - 1e-9 && poly::eval(&q, t) <= floor)
            .collect();
        cuts.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
        let mut bounds = vec![0.0];
        bounds.extend(cuts);
        bounds.push(1.0);
        for w in bounds.windows(2) {
            let part = if w == [0.0, 1.0] {
                seg.clone()
            } else {
                seg.restricted(w[0], w[1])
            };
            out.push(Geo::new(regularized(&part, delta)));
        }
    }
    out
}

/// `seg` with its first (last) inner point moved off its end point when it is within
/// `delta` of it, so that the end has a direction.
fn regularized(seg: &Seg, delta: f64) -> Seg {
    let (mut pts, w) = seg.euclidean();
    let n = pts.len() - 1;
    if n >= 2 {
        for (end, inner, step) in [(0usize, 1usize, 1isize), (n, n - 1, -1)] {
            if (pts[inner] - pts[end]).length() <= delta {
                let mut k = inner as isize;
                while k >= 0 && (k as usize) <= n && (pts[k as usize] - pts[end]).length() <= delta
                {
                    k += step;
                }
                if k >= 0 && (k as usize) <= n {
                    let dir = (pts[k as usize] - pts[end]).normalize_or_zero();
                    pts[inner] = pts[end] + dir * delta;
                }
            }
        }
    }
    Seg::of_points(&pts, w.as_deref())
}

/// The parameters in `(0, 1)` where the offset of `g` by `d` has a cusp (`d κ = 1`).
fn cusps(g: &Geo, d: f64) -> Vec<f64> {
    let q = g.q();
    let k = g.k();
    let q3 = poly::product(&poly::product(&q, &q), &q);
    let w2 = poly::product(&g.seg.w, &g.seg.w);
    let kw = poly::product(&k, &w2);
    let rhs = poly::scaled(&poly::product(&kw, &kw), d * d);
    let z = poly::difference(&q3, &rhs);
    let noise = 1e-13 * z.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
    roots::bernstein_roots_with_noise(&z, noise)
        .roots
        .iter()
        .filter(|r| r.t > 1e-12 && r.t < 1.0 - 1e-12 && d * poly::eval(&kw, r.t) > 0.0)
        .map(|r| r.t)
        .collect()
}

/// `sign(1 − d κ)` at `t`.
fn direction(g: &Geo, d: f64, t: f64) -> f64 {
    let q = poly::eval(&g.q(), t);
    let kw = poly::eval(&g.k(), t) * g.w_at(t).powi(2);
    if q.powf(1.5) - d * kw >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// The offset of one prepared segment by `d`: its cubic pieces, the bound, the cusps.
fn offset_segment(
    g: &Geo,
    d: f64,
    tol: f64,
    out: &mut Vec<[DVec3; 4]>,
) -> Result<(f64, usize), OpError> {
    let cuts = cusps(g, d);
    let mut bounds = vec![0.0];
    bounds.extend(cuts.iter().copied());
    bounds.push(1.0);
    let mut worst: f64 = 0.0;
    let piece_at = |t0: f64, t1: f64, s: f64| Piece {
        g: Geo::new(g.seg.restricted(t0, t1)),
        d,
        s,
        cusp: (cuts.contains(&t0), cuts.contains(&t1)),
    };
    let too_many = || OpError::TooManyPieces {
        limit: MAX_OFFSET_PIECES,
        tolerance: tol,
    };
    for w in bounds.windows(2) {
        let (c0, c1) = (w[0], w[1]);
        let s = direction(g, d, 0.5 * (c0 + c1));
        let mut t0 = c0;
        while t0 < c1 {
            if out.len() >= MAX_OFFSET_PIECES {
                return Err(too_many());
            }
            // The longest piece whose estimate is within the tolerance …
            let mut t1 = c1;
            if piece_at(t0, c1, s).estimate() > ESTIMATE_SHARE * tol {
                let (mut lo, mut hi) = (t0, c1);
                for _ in 0..SEARCH_STEPS {
                    let mid = 0.5 * (lo + hi);
                    if piece_at(t0, mid, s).estimate() <= ESTIMATE_SHARE * tol {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                t1 = if lo > t0 { lo } else { hi };
            }
            // … then the longest, from there down, whose bound is proven.
            let mut guard = 0;
            loop {
                if let Some((b, e)) = piece_at(t0, t1, s).fitted(tol) {
                    out.push(b);
                    worst = worst.max(e);
                    break;
                }
                guard += 1;
                if t1 - t0 < 1e-13 || guard > 80 {
                    return Err(too_many());
                }
                t1 = t0 + SHRINK * (t1 - t0);
            }
            t0 = if t1 >= c1 { c1 } else { t1 };
        }
    }
    Ok((worst, cuts.len()))
}

/// One side's cubic pieces: each segment's offset, kinks joined. Returns the pieces, the
/// bound, the cusps and the largest gap closed.
struct Side {
    pieces: Vec<[DVec3; 4]>,
    error: f64,
    cusps: usize,
}

fn side(
    geos: &[Geo],
    closed: bool,
    d: f64,
    tol: f64,
    options: &OffsetOptions,
    stroke: bool,
) -> Result<Side, OpError> {
    let mut pieces: Vec<[DVec3; 4]> = Vec::new();
    let mut error: f64 = 0.0;
    let mut cusps = 0;
    let count = geos.len();
    for (i, g) in geos.iter().enumerate() {
        let start = pieces.len();
        let (e, c) = offset_segment(g, d, tol, &mut pieces)?;
        error = error.max(e);
        cusps += c;
        // Consecutive pieces share their ends exactly.
        error = error.max(stitch(&mut pieces, start));
        let next = if i + 1 < count {
            Some(&geos[i + 1])
        } else if closed {
            Some(&geos[0])
        } else {
            None
        };
        if let Some(next) = next {
            let e = join(&mut pieces, g, next, d, tol, options, stroke);
            error = error.max(e);
        }
    }
    if closed && let (Some(first), Some(last)) = (pieces.first().copied(), pieces.last_mut()) {
        error = error.max((last[3] - first[0]).length());
        last[3] = first[0];
    }
    Ok(Side {
        pieces,
        error,
        cusps,
    })
}

/// Pieces from `start` on made to start where the one before ends; returns the largest
/// gap closed.
fn stitch(pieces: &mut [[DVec3; 4]], start: usize) -> f64 {
    let mut gap: f64 = 0.0;
    for k in start.max(1)..pieces.len() {
        let end = pieces[k - 1][3];
        gap = gap.max((pieces[k][0] - end).length());
        pieces[k][0] = end;
    }
    gap
}

/// The join after `prev` (whose offset ends the pieces) to `next`; returns its bound.
fn join(
    pieces: &mut Vec<[DVec3; 4]>,
    prev: &Geo,
    next: &Geo,
    d: f64,
    tol: f64,
    options: &OffsetOptions,
    stroke: bool,
) -> f64 {
    let (t_in, t_out) = (prev.tangent(1.0), next.tangent(0.0));
    let pivot = 0.5 * (prev.point(1.0) + next.point(0.0));
    let from = pieces.last().map_or(prev.offset_at(1.0, d), |p| p[3]);
    let to = next.offset_at(0.0, d);
    let turn = cross(t_in, t_out);
    let dot = t_in.dot(t_out);
    if (to - from).length() <= 1e-12 * (1.0 + d.abs()) || (turn.abs() < 1e-12 && dot > 0.0) {
        // Smooth: the next segment's offset starts here (the gap counts in the bound).
        return (to - from).length();
    }
    let angle = turn.atan2(dot);
    let outer = d * angle < 0.0 || (turn == 0.0 && dot < 0.0);
    if !outer {
        if stroke {
            pieces.push(line(from, pivot));
            pieces.push(line(pivot, to));
        } else {
            pieces.push(line(from, to));
        }
        return 0.0;
    }
    match options.join {
        Join::Bevel => {
            pieces.push(line(from, to));
            0.0
        }
        Join::Miter => {
            let half = 0.5 * angle.abs();
            if half.cos() > 0.0 && 1.0 / half.cos() <= options.miter_limit {
                let tip = from + t_in * (d.abs() * half.tan());
                pieces.push(line(from, tip));
                pieces.push(line(tip, to));
            } else {
                pieces.push(line(from, to));
            }
            0.0
        }
        Join::Round => {
            let sweep = if turn == 0.0 {
                -d.signum() * std::f64::consts::PI
            } else {
                angle
            };
            let e = arc(pieces, pivot, from, sweep, tol);
            if let Some(last) = pieces.last_mut() {
                last[3] = to;
            }
            e
        }
    }
}

fn path_of(pieces: Vec<[DVec3; 4]>, closed: bool) -> Result<Path, OpError> {
    let segments = pieces
        .into_iter()
        .map(|p| PathSegment::polynomial(p.to_vec()))
        .collect();
    Path::try_new(segments, closed).map_err(OpError::Geom)
}

#[allow(clippy::too_many_arguments)]
/// The cap at an end: from `from` (the left side's end) to `to` (the right side's),
/// around `center` with the outward direction `out`.
fn cap(
    pieces: &mut Vec<[DVec3; 4]>,
    kind: Cap,
    center: DVec3,
    from: DVec3,
    to: DVec3,
    out: DVec3,
    half: f64,
    tol: f64,
) -> f64 {
    match kind {
        Cap::Butt => {
            pieces.push(line(from, to));
            0.0
        }
        Cap::Square => {
            let (a, b) = (from + out * half, to + out * half);
            pieces.push(line(from, a));
            pieces.push(line(a, b));
            pieces.push(line(b, to));
            0.0
        }
        Cap::Round => {
            let e = arc(pieces, center, from, -std::f64::consts::PI, tol);
            if let Some(last) = pieces.last_mut() {
                last[3] = to;
            }
            e
        }
    }
}

/// A path of cubic segments as their control points.
fn cubics_of(path: &Path) -> Vec<[DVec3; 4]> {
    path.segments()
        .iter()
        .map(|s| std::array::from_fn(|i| s.points[i]))
        .collect()
}

/// A path of cubic segments traced the other way.
fn reverse_path(path: &Path) -> Result<Path, OpError> {
    path_of(reversed(cubics_of(path)), path.is_closed())
}

/// The pieces reversed (each cubic's points in reverse order).
fn reversed(pieces: Vec<[DVec3; 4]>) -> Vec<[DVec3; 4]> {
    pieces
        .into_iter()
        .rev()
        .map(|[a, b, c, d]| [d, c, b, a])
        .collect()
}

/// The offset of `curve` by `d` within `tolerance` (Hausdorff, proven; see the module
/// docs), with `options`' joins, caps and trimming.
///
/// # Errors
/// [`OpError::Tolerance`] for a tolerance that is not a finite number greater than 0;
/// [`OpError::Distance`] for a `d` that is not finite, or 0 with caps; [`OpError::MiterLimit`]
/// for a limit below 1 or not finite; [`OpError::NotPlanar`] for a curve that leaves the
/// plane `z = 0`; [`OpError::Degenerate`] for a curve that is a single point;
/// [`OpError::TrimWithCaps`] for both at once; [`OpError::BelowPrecision`] for a
/// tolerance below [`RELATIVE_FLOOR`] times the curve's size plus `|d|`;
/// [`OpError::TooManyPieces`] past [`MAX_OFFSET_PIECES`].
pub fn offset(
    curve: &Curve,
    d: f64,
    tolerance: f64,
    options: &OffsetOptions,
) -> Result<Offset, OpError> {
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(OpError::Tolerance(tolerance));
    }
    if !d.is_finite() || (d == 0.0 && options.caps.is_some()) {
        return Err(OpError::Distance(d));
    }
    if !(options.miter_limit.is_finite() && options.miter_limit >= 1.0) {
        return Err(OpError::MiterLimit(options.miter_limit));
    }
    if options.trim && options.caps.is_some() {
        return Err(OpError::TrimWithCaps);
    }
    if !curve.is_planar() {
        return Err(OpError::NotPlanar {
            operation: "offset",
        });
    }
    // Closed: a closed path, or a curve that ends where it starts (a closed NURBS curve).
    let (ta, tb) = curve.domain();
    let (start, end) = (curve.eval(ta), curve.eval(tb));
    let closed = matches!(curve, Curve::Path(p) if p.is_closed())
        || (start - end).length() <= 1e-12 * (1.0 + start.length().max(end.length()));
    // Within half the tolerance of the curve: every point of the offset (joins included)
    // is |d| from one of the curve's and back, so the curve's own cubics within the rest of
    // the tolerance are within it of the offset (a stroke outline of such a width: the
    // curve there and back).
    if d.abs() <= 0.5 * tolerance {
        let a = approx::approximate(
            &curve.lower(),
            closed,
            approx::Target::Cubic,
            tolerance - d.abs(),
        )?;
        let error = a.error + d.abs();
        let own = if closed {
            let mut c = cubics_of(&a.path);
            let start = c[0][0];
            if let Some(last) = c.last_mut() {
                last[3] = start;
            }
            path_of(c, true)?
        } else {
            a.path
        };
        let paths = match options.caps {
            None => vec![own],
            Some(_) if closed => vec![own.clone(), reverse_path(&own)?],
            Some(_) => {
                let there: Vec<[DVec3; 4]> = cubics_of(&own);
                let back = reversed(there.clone());
                let mut all = there;
                all.extend(back);
                vec![path_of(all, true)?]
            }
        };
        return Ok(Offset {
            paths,
            error,
            cusps: 0,
        });
    }
    let lowered = curve.lower();
    let size = lowered.iter().flat_map(|s| s.bezier.points().iter()).fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let floor = RELATIVE_FLOOR * ((size.1 - size.0).length() + d.abs());
    if tolerance < floor || !floor.is_finite() {
        return Err(OpError::BelowPrecision {
            tolerance,
            relative: RELATIVE_FLOOR,
            floor,
        });
    }
    let delta = tolerance * 1e-3;
    let geos = prepare(&lowered, delta);
    if geos.is_empty() {
        return Err(OpError::Degenerate(
            "the curve is a single point: it has no normal to offset along",
        ));
    }
    let moved = delta;
    // The pieces' own bounds get what is left after the ends' moves and the seams.
    let tol = 0.99 * tolerance - moved;
    let stroke = options.caps.is_some();
    let asked = |e: OpError| match e {
        OpError::TooManyPieces { limit, .. } => OpError::TooManyPieces { limit, tolerance },
        other => other,
    };
    let (paths, error, cusps) = match options.caps {
        None => {
            let s = side(&geos, closed, d, tol, options, false).map_err(asked)?;
            let error = s.error;
            let paths = if options.trim {
                trim(curve, s.pieces, closed, d, tolerance)?
            } else {
                vec![path_of(s.pieces, closed)?]
            };
            (paths, error, s.cusps)
        }
        Some(kind) => {
            let half = d.abs();
            let left = side(&geos, closed, half, tol, options, stroke).map_err(asked)?;
            let right = side(&geos, closed, -half, tol, options, stroke).map_err(asked)?;
            let error = left.error.max(right.error);
            let cusps = left.cusps + right.cusps;
            if closed {
                (
                    vec![
                        path_of(left.pieces, true)?,
                        path_of(reversed(right.pieces), true)?,
                    ],
                    error,
                    cusps,
                )
            } else {
                let (first, last) = (&geos[0], &geos[geos.len() - 1]);
                let mut pieces = left.pieces;
                let end_from = pieces.last().map_or(DVec3::ZERO, |p| p[3]);
                let mut back = reversed(right.pieces);
                let end_to = back.first().map_or(DVec3::ZERO, |p| p[0]);
                let e1 = cap(
                    &mut pieces,
                    kind,
                    last.point(1.0),
                    end_from,
                    end_to,
                    last.tangent(1.0),
                    half,
                    tol,
                );
                let start_from = back.last().map_or(DVec3::ZERO, |p| p[3]);
                let start_to = pieces.first().map_or(DVec3::ZERO, |p| p[0]);
                pieces.append(&mut back);
                let e2 = cap(
                    &mut pieces,
                    kind,
                    first.point(0.0),
                    start_from,
                    start_to,
                    -first.tangent(0.0),
                    half,
                    tol,
                );
                let start = pieces[0][0];
                if let Some(l) = pieces.last_mut() {
                    l[3] = start;
                }
                (vec![path_of(pieces, true)?], error.max(e1).max(e2), cusps)
            }
        }
    };
    Ok(Offset {
        paths,
        error: error + moved,
        cusps,
    })
}

/// The raw offset's pieces with its loops removed: cut at its self-intersections, the
/// parts whose middle is closer to the curve than `|d|` (less the tolerance) dropped, the
/// rest chained into paths where they meet.
fn trim(
    curve: &Curve,
    pieces: Vec<[DVec3; 4]>,
    closed: bool,
    d: f64,
    tolerance: f64,
) -> Result<Vec<Path>, OpError> {
    let raw = path_of(pieces, closed)?;
    let raw_curve = Curve::Path(raw.clone());
    let analysis = CurveAnalysis::new(&raw_curve);
    let found = analysis
        .self_intersections()
        .map_err(|e| OpError::Analysis(e.to_string()))?;
    let end = raw.segments().len() as f64;
    let mut cuts: Vec<f64> = found
        .hits
        .iter()
        .flat_map(|p| [p.t, p.s])
        .filter(|&t| t > 1e-9 && t < end - 1e-9)
        .collect();
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let base = CurveAnalysis::new(curve);
    let mut bounds = vec![0.0];
    bounds.extend(cuts);
    bounds.push(end);
    let keep_from = d.abs() - 2.0 * tolerance;
    let mut kept: Vec<Path> = Vec::new();
    for w in bounds.windows(2) {
        let mid = 0.5 * (w[0] + w[1]);
        let p = raw_curve.eval(mid);
        let near = base
            .nearest(p)
            .map_err(|e| OpError::Analysis(e.to_string()))?;
        if near.distance >= keep_from {
            kept.push(raw.between(w[0], w[1]).map_err(OpError::Geom)?);
        }
    }
    // Chain the kept parts where one ends at the next's start.
    let mut chained: Vec<Vec<PathSegment>> = Vec::new();
    for part in kept {
        let segs = part.segments().to_vec();
        let joins = chained.last().and_then(|c| c.last()).is_some_and(|last| {
            let a = last.points[last.points.len() - 1];
            (a - segs[0].points[0]).length() <= tolerance
        });
        if joins {
            let chain = chained
                .last_mut()
                .unwrap_or_else(|| unreachable!("checked"));
            let a = chain
                .last()
                .map(|l| l.points[l.points.len() - 1])
                .unwrap_or_default();
            let mut segs = segs;
            segs[0].points[0] = a;
            chain.extend(segs);
        } else {
            chained.push(segs);
        }
    }
    // A closed offset's first and last parts meet at the seam.
    if closed && chained.len() > 1 {
        let first_start = chained[0][0].points[0];
        let last = chained
            .last()
            .and_then(|c| c.last())
            .map(|l| l.points[l.points.len() - 1]);
        if last.is_some_and(|a| (a - first_start).length() <= tolerance) {
            let mut tail = chained.pop().unwrap_or_default();
            let first = std::mem::take(&mut chained[0]);
            if let Some(l) = tail.last_mut() {
                let k = l.points.len() - 1;
                l.points[k] = first[0].points[0];
            }
            tail.extend(first);
            chained[0] = tail;
        }
    }
    chained
        .into_iter()
        .map(|segs| {
            let a = segs[0].points[0];
            let z = segs
                .last()
                .map(|l| l.points[l.points.len() - 1])
                .unwrap_or_default();
            let closed = segs.len() > 1 && (a - z).length() <= tolerance;
            let mut segs = segs;
            if closed && let Some(l) = segs.last_mut() {
                let k = l.points.len() - 1;
                l.points[k] = a;
            }
            Path::try_new(segs, closed).map_err(OpError::Geom)
        })
        .collect()
}
