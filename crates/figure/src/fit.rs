//! Curves as path commands in output coordinates. The view maps world points to output
//! points projectively (`(X, Y, W)`, homogeneous); a Bézier segment of degree `n` becomes
//! the polynomials `X(u)`, `Y(u)`, `W(u)` of degree `n` whose Bernstein coefficients are
//! the mapped control points.
//!
//! * Affine views (the 2D camera, `W ≡ 1`) and `n ≤ 3`: one command with the mapped
//!   control points — exact.
//! * Otherwise: cubic Hermite pieces (end points and end tangents of the exact curve),
//!   each within the tolerance `T` of it by a computed bound, halving a piece until the
//!   bound holds. The error of a piece is `(X − H_x W, Y − H_y W) / W`; its numerator is
//!   a polynomial of degree `n + 3` whose Bernstein coefficients bound it (convex hull),
//!   and `W ≥ min_j W_j > 0` on the piece. So `|error| ≤ ‖(max|N_x|, max|N_y|)‖ / min W`.

use glam::{DVec2, DVec3};

use splinescope_core::geom::Bezier;
use splinescope_core::poly::{elevate_to, product};

/// One path command after the current point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Seg {
    /// A straight line to the point.
    Line(DVec2),
    /// A quadratic Bézier: control point, end point.
    Quad(DVec2, DVec2),
    /// A cubic Bézier: two control points, end point.
    Cubic(DVec2, DVec2, DVec2),
}

impl Seg {
    /// The end point.
    #[must_use]
    pub fn end(&self) -> DVec2 {
        match *self {
            Seg::Line(p) | Seg::Quad(_, p) | Seg::Cubic(_, _, p) => p,
        }
    }
}

/// A path command and whether it carries the exact control points of the curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    /// The command.
    pub seg: Seg,
    /// `true`: the exact curve (degree ≤ 3 under an affine view); `false`: a cubic within
    /// the tolerance of it.
    pub exact: bool,
}

/// The projective map from world points to output points (y down), as the rows of
/// `(X, Y, W)` over `(x, y, z, 1)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// Rows for `X`, `Y` and `W`.
    pub rows: [[f64; 4]; 3],
    /// Whether `W ≡ 1` (an orthographic view): curves keep their degree.
    pub affine: bool,
}

impl Projection {
    /// The homogeneous image `(X, Y, W)` of `p`.
    #[must_use]
    pub fn homogeneous(&self, p: DVec3) -> [f64; 3] {
        let v = [p.x, p.y, p.z, 1.0];
        self.rows
            .map(|r| r[0] * v[0] + r[1] * v[1] + r[2] * v[2] + r[3] * v[3])
    }

    /// The output point of `p`, or `None` at or behind the eye.
    #[must_use]
    pub fn point(&self, p: DVec3) -> Option<DVec2> {
        let [x, y, w] = self.homogeneous(p);
        if self.affine {
            return Some(DVec2::new(x, y));
        }
        (w > 0.0).then(|| DVec2::new(x / w, y / w))
    }
}

/// How many times a piece may be halved: a piece is then 2⁻⁴⁰ of its segment, where the
/// parameters of its ends carry about 12 significant digits; a bound still over the
/// tolerance there is rounding, not shape (see [`FitError::Precision`]).
const MAX_DEPTH: u32 = 40;

/// Why a segment cannot be written within the tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FitError {
    /// The figure needs more pieces than its budget allows.
    Budget {
        /// The budget, in pieces.
        limit: usize,
    },
    /// Halving stops meeting the tolerance: the rounding of the curve's coordinates in
    /// this view (their largest magnitude given) is as large as the tolerance.
    Precision {
        /// The largest coordinate of the piece, in output points.
        magnitude: f64,
    },
    /// The curve's homogeneous weight `W` is not positive and finite on a piece in an
    /// affine view (its weights span more than `f64` holds), or a coordinate is not finite.
    NotFinite,
}

/// How many pieces a figure may still write (one count for all its curves).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Budget {
    /// Pieces left.
    pub left: usize,
    /// The budget it started with.
    pub limit: usize,
}

impl Budget {
    /// A budget of `limit` pieces.
    #[must_use]
    pub fn new(limit: usize) -> Budget {
        Budget { left: limit, limit }
    }

    fn take(&mut self) -> Result<(), FitError> {
        if self.left == 0 {
            return Err(FitError::Budget { limit: self.limit });
        }
        self.left -= 1;
        Ok(())
    }
}

/// Where the fit need not keep the tolerance: pieces whose control points all lie outside
/// the rectangle `min..max` (the page grown by the stroke) cannot be seen, so they are
/// written as the chord to their end point, which lies in their convex hull and so outside
/// the page too.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Page {
    /// The rectangle's top left corner.
    pub min: DVec2,
    /// Its bottom right corner.
    pub max: DVec2,
}

impl Page {
    /// Whether `p` lies on the page (its edges included).
    #[must_use]
    pub fn contains(&self, p: DVec2) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }

    /// Whether the points' bounding box misses the page.
    fn misses(&self, pts: impl Iterator<Item = DVec2>) -> bool {
        let (mut lo, mut hi) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
        for p in pts {
            lo = lo.min(p);
            hi = hi.max(p);
        }
        hi.x < self.min.x || lo.x > self.max.x || hi.y < self.min.y || lo.y > self.max.y
    }
}

/// The path commands of one Bézier segment (world control points, with their weights for
/// a rational segment) under `proj`, each within `tolerance` output points of the exact
/// curve where it can be seen on `page` (everywhere when `page` is `None`); `Ok(None)`
/// when part of the segment lies at or behind the eye of a perspective view (it is not
/// drawn). Each piece written is taken from `budget`.
///
/// # Errors
/// [`FitError`]: the budget runs out, the tolerance is finer than the coordinates' rounding,
/// or the segment's weights leave `f64`.
pub fn segment_pieces(
    bezier: &Bezier,
    weights: Option<&[f64]>,
    proj: &Projection,
    tolerance: f64,
    page: Option<&Page>,
    budget: &mut Budget,
) -> Result<Option<Vec<Piece>>, FitError> {
    let pts = bezier.points();
    if proj.affine && pts.len() <= 4 && weights.is_none() {
        let p: Vec<DVec2> = pts.iter().filter_map(|&p| proj.point(p)).collect();
        let seg = match p.as_slice() {
            [_, b] => Seg::Line(*b),
            [_, b, c] => Seg::Quad(*b, *c),
            [_, b, c, d] => Seg::Cubic(*b, *c, *d),
            _ => return Ok(Some(Vec::new())),
        };
        budget.take()?;
        return Ok(Some(vec![Piece { seg, exact: true }]));
    }
    // The segment in homogeneous output coordinates (X, Y, W) as one polynomial Bézier
    // curve: the projection of (w·P, w) is w times the projection of P.
    let homogeneous = Bezier::new(
        pts.iter()
            .enumerate()
            .map(|(i, &p)| DVec3::from(proj.homogeneous(p)) * weights.map_or(1.0, |w| w[i]))
            .collect(),
    );
    let mut out = Vec::new();
    let fitter = Fitter {
        homogeneous: &homogeneous,
        tolerance,
        page,
        affine: proj.affine,
    };
    match fitter.fit(0.0, 1.0, 0, &mut out, budget)? {
        true => Ok(Some(out)),
        false => Ok(None),
    }
}

/// One segment's fit: the homogeneous curve and what its pieces must keep.
struct Fitter<'a> {
    homogeneous: &'a Bezier,
    tolerance: f64,
    page: Option<&'a Page>,
    affine: bool,
}

impl Fitter<'_> {
    /// The Hermite cubic of the homogeneous curve `(X, Y, W)` on `[a, b]` if within the
    /// tolerance, else its halves; `false` when the piece reaches the eye.
    fn fit(
        &self,
        a: f64,
        b: f64,
        depth: u32,
        out: &mut Vec<Piece>,
        budget: &mut Budget,
    ) -> Result<bool, FitError> {
        let piece = self.homogeneous.subsegment(a, b);
        let h: Vec<[f64; 3]> = piece.points().iter().map(|p| p.to_array()).collect();
        let w: Vec<f64> = h.iter().map(|v| v[2]).collect();
        let min_w = w.iter().copied().fold(f64::INFINITY, f64::min);
        if !h.iter().flatten().all(|v| v.is_finite()) {
            return Err(FitError::NotFinite);
        }
        if min_w <= 0.0 {
            // Behind the eye in perspective; in an affine view the weights underflowed.
            return if self.affine {
                Err(FitError::NotFinite)
            } else {
                Ok(false)
            };
        }
        let n = h.len() - 1;
        let at = |i: usize| DVec2::new(h[i][0] / h[i][2], h[i][1] / h[i][2]);
        let (p0, p3) = (at(0), at(n));
        if let Some(page) = self.page
            && page.misses((0..=n).map(at))
        {
            budget.take()?;
            out.push(Piece {
                seg: Seg::Line(p3),
                exact: false,
            });
            return Ok(true);
        }
        // d/du (X/W) at the ends: n (X₁W₀ − X₀W₁) / W₀², and the same at u = 1.
        let d0 = DVec2::new(
            h[1][0] * h[0][2] - h[0][0] * h[1][2],
            h[1][1] * h[0][2] - h[0][1] * h[1][2],
        ) * (n as f64 / (h[0][2] * h[0][2]));
        let d1 = DVec2::new(
            h[n][0] * h[n - 1][2] - h[n - 1][0] * h[n][2],
            h[n][1] * h[n - 1][2] - h[n - 1][1] * h[n][2],
        ) * (n as f64 / (h[n][2] * h[n][2]));
        let (c1, c2) = (p0 + d0 / 3.0, p3 - d1 / 3.0);
        let hermite = [p0, c1, c2, p3];
        let bound = {
            let mut m = DVec2::ZERO;
            for axis in 0..2 {
                let num = elevate_to(&h.iter().map(|v| v[axis]).collect::<Vec<_>>(), n + 3);
                let hw = product(&hermite.map(|p| p[axis]), &w);
                let worst = num
                    .iter()
                    .zip(&hw)
                    .map(|(x, y)| (x - y).abs())
                    .fold(0.0, f64::max);
                m[axis] = worst;
            }
            m.length() / min_w
        };
        if !bound.is_finite() {
            return Err(FitError::NotFinite);
        }
        if bound <= self.tolerance {
            budget.take()?;
            out.push(Piece {
                seg: Seg::Cubic(c1, c2, p3),
                exact: false,
            });
            return Ok(true);
        }
        if depth >= MAX_DEPTH {
            let magnitude = hermite
                .iter()
                .map(|p| p.abs().max_element())
                .fold(0.0, f64::max);
            return Err(FitError::Precision { magnitude });
        }
        let mid = 0.5 * (a + b);
        Ok(
            self.fit(a, mid, depth + 1, out, budget)?
                && self.fit(mid, b, depth + 1, out, budget)?,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use splinescope_core::geom::bernstein::binomial;

    #[test]
    fn product_and_elevation_keep_the_polynomial() {
        // (1 − u + 2u)·(3(1 − u)² + …) evaluated against the product's coefficients.
        let a = [1.0, 2.0];
        let b = [3.0, -1.0, 4.0];
        let eval = |c: &[f64], u: f64| {
            let n = c.len() - 1;
            c.iter()
                .enumerate()
                .map(|(i, ci)| {
                    binomial(n, i) * u.powi(i as i32) * (1.0 - u).powi((n - i) as i32) * ci
                })
                .sum::<f64>()
        };
        let p = product(&a, &b);
        let e = elevate_to(&b, 6);
        for k in 0..=10 {
            let u = f64::from(k) / 10.0;
            assert!((eval(&p, u) - eval(&a, u) * eval(&b, u)).abs() < 1e-13);
            assert!((eval(&e, u) - eval(&b, u)).abs() < 1e-13);
        }
    }
}
