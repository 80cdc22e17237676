//! Two segments subdivided down to candidate intersections: the sub-segments' homogeneous
//! control points (de Casteljau halves and restrictions, so the convex hull holds for
//! rational segments too), their boxes, tangent cones and flatness, Bézier clipping by the
//! other's fat line, and the chord crossings that start the refinement.

use glam::DVec2;

use crate::analysis::piece::Piece;
use crate::poly;

/// Homogeneous control points, on the stack up to degree 7 (large on purpose: the
/// subdivision makes thousands of them and must not allocate each).
#[derive(Debug, Clone)]
#[allow(clippy::large_enum_variant)]
pub(super) enum Points {
    Stack([[f64; 3]; 8], usize),
    Heap(Vec<[f64; 3]>),
}

impl Points {
    pub(super) fn with_len(n: usize) -> Points {
        if n <= 8 {
            Points::Stack([[0.0; 3]; 8], n)
        } else {
            Points::Heap(vec![[0.0; 3]; n])
        }
    }

    pub(super) fn as_slice(&self) -> &[[f64; 3]] {
        match self {
            Points::Stack(a, n) => &a[..*n],
            Points::Heap(v) => v,
        }
    }

    pub(super) fn as_mut_slice(&mut self) -> &mut [[f64; 3]] {
        match self {
            Points::Stack(a, n) => &mut a[..*n],
            Points::Heap(v) => v,
        }
    }
}

/// A sub-segment: homogeneous control points `(w x, w y, w)` and its range of the
/// segment's own parameter.
#[derive(Debug, Clone)]
pub(super) struct Sub {
    pub(super) h: Points,
    u0: f64,
    u1: f64,
    /// Whether the weights differ from 1 (else the points are Cartesian already).
    pub(super) rational: bool,
}

impl Sub {
    pub(super) fn of(p: &Piece, u0: f64, u1: f64) -> Sub {
        let n = p.a(0).len();
        let mut h = Points::with_len(n);
        let slots = h.as_mut_slice();
        if u0 > 0.0 || u1 < 1.0 {
            // Each coordinate restricted into one scratch row (a polynomial's weights as
            // ones, restricted too), then laid into the points.
            poly::in_two_buffers(n, |row, ones| {
                ones.fill(1.0);
                let w = p.w().unwrap_or(ones);
                for (k, c) in [p.a(0), p.a(1), w].into_iter().enumerate() {
                    poly::restrict_into(c, u0, u1, row);
                    for (slot, v) in slots.iter_mut().zip(row.iter()) {
                        slot[k] = *v;
                    }
                }
            });
        } else {
            for (i, slot) in slots.iter_mut().enumerate() {
                let w = p.w().map_or(1.0, |w| w[i]);
                *slot = [p.a(0)[i], p.a(1)[i], w];
            }
        }
        Sub {
            h,
            u0,
            u1,
            rational: p.w().is_some(),
        }
    }

    /// The box of the control points aligned with the chord: the chord's start and unit
    /// direction, and the points' extents along it and across it (`[a0, a1, n0, n1]`,
    /// from the start); `None` for a closed or non-finite chord. The sub-segment lies in
    /// it, which hugs it more closely than the axis-aligned box.
    fn chord_box(&self) -> Option<(DVec2, DVec2, [f64; 4])> {
        let n = self.len();
        let origin = self.point(0);
        let c = self.point(n - 1) - origin;
        let len = c.length();
        if len == 0.0 || !len.is_finite() {
            return None;
        }
        let along = c / len;
        let mut ext = [0.0_f64; 4];
        for i in 1..n {
            let p = self.point(i) - origin;
            let (x, y) = (p.dot(along), along.perp_dot(p));
            ext = [ext[0].min(x), ext[1].max(x), ext[2].min(y), ext[3].max(y)];
        }
        Some((origin, along, ext))
    }

    /// How far `q` lies outside [`Sub::chord_box`] (outside the axis-aligned box where the
    /// chord is closed).
    pub(super) fn oriented_gap(&self, q: DVec2) -> f64 {
        let Some((origin, along, [a0, a1, n0, n1])) = self.chord_box() else {
            let (lo, hi) = self.bounds();
            return (lo - q).max(q - hi).max(DVec2::ZERO).length();
        };
        let p = q - origin;
        let (x, y) = (p.dot(along), along.perp_dot(p));
        let gx = (a0 - x).max(x - a1).max(0.0);
        let gy = (n0 - y).max(y - n1).max(0.0);
        gx.hypot(gy)
    }

    /// Whether a line separates the two (by more than `margin`): the sides of either's
    /// [`Sub::chord_box`] (the hull of its control points lies within them) that leave
    /// every control point of the other outside.
    pub(super) fn separated_from(&self, other: &Sub, margin: f64) -> bool {
        let outside = |s: &Sub, o: &Sub| -> bool {
            let Some((origin, along, [a0, a1, n0, n1])) = s.chord_box() else {
                return false;
            };
            let (mut b0, mut b1, mut m0, mut m1) = (
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            );
            for i in 0..o.len() {
                let p = o.point(i) - origin;
                let (x, y) = (p.dot(along), along.perp_dot(p));
                b0 = b0.min(x);
                b1 = b1.max(x);
                m0 = m0.min(y);
                m1 = m1.max(y);
            }
            let m = 2.0 * margin;
            b0 > a1 + m || b1 < a0 - m || m0 > n1 + m || m1 < n0 - m
        };
        outside(self, other) || outside(other, self)
    }

    /// Whether the convex hulls of the two control polygons (which hold the pieces,
    /// rational ones with positive weights too) lie more than `margin` apart: a side of
    /// either hull with every point of the other beyond it. Two convex polygons that do
    /// not meet always have such a side, so this separates what the boxes and fat lines
    /// cannot — neighbouring pieces of two nearly coincident curves, one just past the
    /// other's end, whose thin hulls bend past each other's lines.
    pub(super) fn hulls_apart(&self, other: &Sub, margin: f64) -> bool {
        let (Some(ha), Some(hb)) = (Hull::of(self), Hull::of(other)) else {
            return false;
        };
        ha.has_side_beyond(&hb, margin) || hb.has_side_beyond(&ha, margin)
    }

    /// The range of the segment's own parameter this sub-segment covers.
    pub(super) fn range(&self) -> (f64, f64) {
        (self.u0, self.u1)
    }

    pub(super) fn len(&self) -> usize {
        self.h.as_slice().len()
    }

    pub(super) fn point(&self, i: usize) -> DVec2 {
        let v = self.h.as_slice()[i];
        if self.rational {
            DVec2::new(v[0] / v[2], v[1] / v[2])
        } else {
            DVec2::new(v[0], v[1])
        }
    }

    pub(super) fn bounds(&self) -> (DVec2, DVec2) {
        let mut lo = DVec2::INFINITY;
        let mut hi = DVec2::NEG_INFINITY;
        for i in 0..self.len() {
            let p = self.point(i);
            lo = lo.min(p);
            hi = hi.max(p);
        }
        (lo, hi)
    }

    /// The directions of the control polygon's legs as an interval `[θ₀, θ₁]` of
    /// [`pseudo_angle`]s (narrower than a quarter turn), or `None` when they spread wider.
    /// The curve's tangent — for positive weights a rational one's too — is a positive
    /// combination of the legs, so it stays inside.
    pub(super) fn cone(&self) -> Option<(f64, f64)> {
        let n = self.len() - 1;
        let mut first: Option<f64> = None;
        let (mut lo, mut hi) = (0.0_f64, 0.0_f64);
        for i in 0..n {
            let e = self.point(i + 1) - self.point(i);
            if e.x == 0.0 && e.y == 0.0 {
                continue;
            }
            let angle = pseudo_angle(e);
            match first {
                None => first = Some(angle),
                Some(f) => {
                    // Relative to the first leg, within half a turn either way.
                    let mut d = angle - f;
                    if d > HALF_TURN {
                        d -= 2.0 * HALF_TURN;
                    } else if d <= -HALF_TURN {
                        d += 2.0 * HALF_TURN;
                    }
                    lo = lo.min(d);
                    hi = hi.max(d);
                    if hi - lo >= QUARTER_TURN {
                        return None;
                    }
                }
            }
        }
        first.map(|f| (f + lo, f + hi))
    }

    /// The range, in this piece's own parameter `[0, 1]`, of the part that can lie in the
    /// fat line of `other`: the strip parallel to `other`'s chord between the extreme
    /// signed distances of `other`'s control points (so it holds `other`). For a rational
    /// piece the distances are weighed: `Σ w_i (d_i − d_min) B_i ≥ 0` and
    /// `Σ w_i (d_max − d_i) B_i ≥ 0`, with `W > 0`. `None` when no part can.
    pub(super) fn clip_range(&self, other: &Sub, margin: f64) -> Option<(f64, f64)> {
        let m = other.len() - 1;
        let origin = other.point(0);
        let mut dir = other.point(m) - origin;
        if dir.length_squared() == 0.0 {
            // A closed chord: the direction to the farthest control point.
            dir = (1..m)
                .map(|i| other.point(i) - origin)
                .max_by(|p, q| p.length_squared().total_cmp(&q.length_squared()))?;
            if dir.length_squared() == 0.0 {
                return None;
            }
        }
        let normal = dir.perp().normalize();
        let (mut dmin, mut dmax) = (0.0_f64, 0.0_f64);
        for i in 0..=m {
            let d = (other.point(i) - origin).dot(normal);
            dmin = dmin.min(d);
            dmax = dmax.max(d);
        }
        // Widened by the resolution: the points' own rounding is relative to their
        // coordinates, not to the strip.
        let slack = (1e-12 * (dmax - dmin).max(dir.length())).max(margin);
        let (dmin, dmax) = (dmin - slack, dmax + slack);
        let h = self.h.as_slice();
        let n = h.len();
        // On the stack up to degree 31 (the GPU's maximum), else on the heap.
        let (mut below_s, mut above_s) = ([0.0; 32], [0.0; 32]);
        let (mut below_h, mut above_h) = (Vec::new(), Vec::new());
        let (below, above): (&mut [f64], &mut [f64]) = if n <= 32 {
            (&mut below_s[..n], &mut above_s[..n])
        } else {
            below_h.resize(n, 0.0);
            above_h.resize(n, 0.0);
            (&mut below_h, &mut above_h)
        };
        for (i, v) in h.iter().enumerate() {
            let w = v[2];
            let d = (DVec2::new(v[0], v[1]) - origin * w).dot(normal);
            below[i] = d - dmin * w;
            above[i] = dmax * w - d;
        }
        let (l1, h1) = nonnegative_range(below)?;
        let (l2, h2) = nonnegative_range(above)?;
        let (lo, hi) = (l1.max(l2), h1.min(h2));
        if lo > hi {
            return None;
        }
        Some((lo, hi))
    }

    /// The piece on its own parameter range `[lo, hi] ⊆ [0, 1]`.
    pub(super) fn restricted(&self, lo: f64, hi: f64) -> Sub {
        if lo <= 0.0 && hi >= 1.0 {
            return self.clone();
        }
        let mut h = self.h.clone();
        let pts = h.as_mut_slice();
        let n = pts.len() - 1;
        // Right part at `lo`, then the left part of that at the rescaled `hi`.
        // (A polynomial piece's weights stay 1: only `x` and `y` are interpolated.)
        let rational = self.rational;
        let split_right = |pts: &mut [[f64; 3]], t: f64| {
            let s = 1.0 - t;
            for k in 1..=n {
                for i in 0..=(n - k) {
                    let (p, q) = (pts[i], pts[i + 1]);
                    pts[i][0] = s * p[0] + t * q[0];
                    pts[i][1] = s * p[1] + t * q[1];
                    if rational {
                        pts[i][2] = s * p[2] + t * q[2];
                    }
                }
            }
        };
        // After the triangle, `pts[j]` holds the point of level n − j at index j: the right
        // part's control points.
        if lo > 0.0 {
            split_right(pts, lo);
        }
        if hi < 1.0 {
            let t = if lo > 0.0 { (hi - lo) / (1.0 - lo) } else { hi };
            // The left part at `t`: the same triangle on the reversed points.
            pts.reverse();
            split_right(pts, 1.0 - t);
            pts.reverse();
        }
        let span = self.u1 - self.u0;
        Sub {
            h,
            u0: self.u0 + lo * span,
            u1: self.u0 + hi * span,
            rational: self.rational,
        }
    }

    /// The chord from the first control point to the last.
    pub(super) fn chord(&self) -> DVec2 {
        self.point(self.len() - 1) - self.point(0)
    }

    /// The largest distance of a control point from the chord.
    pub(super) fn flatness(&self) -> f64 {
        let n = self.len() - 1;
        let (a, b) = (self.point(0), self.point(n));
        let d = b - a;
        let len = d.length();
        (1..n)
            .map(|i| {
                let p = self.point(i) - a;
                if len > 0.0 {
                    (p.perp_dot(d) / len).abs()
                } else {
                    p.length()
                }
            })
            .fold(0.0, f64::max)
    }

    /// The sub-segment's own parameter where its point lies at `alpha` of the way along
    /// its chord: the fraction is `Σ wᵢ αᵢ Bᵢ / Σ wᵢ Bᵢ` (`αᵢ` the control points'
    /// fractions), solved by bisection where the control points advance along the chord,
    /// else `alpha` itself. (A parametrisation that runs unevenly — weights far apart,
    /// points bunched — puts the chord's fraction far from the parameter, and Newton's
    /// method far from its point.)
    pub(super) fn parameter_of_fraction(&self, alpha: f64) -> f64 {
        let c = self.chord();
        let len2 = c.length_squared();
        let h = self.h.as_slice();
        let n = h.len();
        if len2 == 0.0 || n > 16 {
            return alpha;
        }
        let origin = self.point(0);
        let mut num = [0.0; 16];
        let mut den = [0.0; 16];
        // Points spread evenly along the chord (and no weights) make the fraction the
        // parameter, to within what Newton's method needs.
        let mut even = !self.rational;
        let mut last = f64::NEG_INFINITY;
        for (i, v) in h.iter().enumerate() {
            let w = if self.rational { v[2] } else { 1.0 };
            let f = (self.point(i) - origin).dot(c) / len2;
            if f < last {
                return alpha;
            }
            last = f;
            even &= (f - i as f64 / (n - 1) as f64).abs() <= 0.05;
            num[i] = w * f;
            den[i] = w;
        }
        if even {
            return alpha;
        }
        let fraction = |t: f64| poly::eval(&num[..n], t) / poly::eval(&den[..n], t);
        if !(fraction(0.0).is_finite() && fraction(1.0).is_finite()) {
            return alpha;
        }
        // Regula falsi (Illinois) on the monotone fraction, to 1e−9: a start, not a root.
        let (mut lo, mut flo, mut hi, mut fhi) =
            (0.0, fraction(0.0) - alpha, 1.0, fraction(1.0) - alpha);
        if flo >= 0.0 {
            return 0.0;
        }
        if fhi <= 0.0 {
            return 1.0;
        }
        let mut side = 0;
        for _ in 0..60 {
            let m = (lo - flo * (hi - lo) / (fhi - flo)).max(lo).min(hi);
            let fm = fraction(m) - alpha;
            if fm == 0.0 || hi - lo <= 1e-9 {
                return m;
            }
            if fm < 0.0 {
                lo = m;
                flo = fm;
                if side == -1 {
                    fhi *= 0.5;
                }
                side = -1;
            } else {
                hi = m;
                fhi = fm;
                if side == 1 {
                    flo *= 0.5;
                }
                side = 1;
            }
        }
        0.5 * (lo + hi)
    }

    /// Whether the control points advance along the chord (their projections on it in
    /// order): then so does the curve, and a point near it has one foot there.
    pub(super) fn advances(&self) -> bool {
        let c = self.chord();
        let origin = self.point(0);
        let mut last = 0.0;
        for i in 1..self.len() {
            let t = (self.point(i) - origin).dot(c);
            if t < last {
                return false;
            }
            last = t;
        }
        true
    }

    pub(super) fn halves(&self) -> (Sub, Sub) {
        let n = self.len() - 1;
        let mut left = Points::with_len(n + 1);
        let mut right = Points::with_len(n + 1);
        {
            // The right half's points are the triangle's last column: work in `right`.
            let (l, r) = (left.as_mut_slice(), right.as_mut_slice());
            r.copy_from_slice(self.h.as_slice());
            l[0] = r[0];
            for (k, slot) in l.iter_mut().enumerate().skip(1) {
                for i in 0..=(n - k) {
                    let (p, q) = (r[i], r[i + 1]);
                    r[i] = [
                        0.5 * (p[0] + q[0]),
                        0.5 * (p[1] + q[1]),
                        0.5 * (p[2] + q[2]),
                    ];
                }
                *slot = r[0];
            }
        }
        let mid = 0.5 * (self.u0 + self.u1);
        (
            Sub {
                h: left,
                u0: self.u0,
                u1: mid,
                rational: self.rational,
            },
            Sub {
                h: right,
                u0: mid,
                u1: self.u1,
                rational: self.rational,
            },
        )
    }
}

/// `x` held to `[0, 1]`; a NaN becomes ½ (never left to the optimiser's choice of
/// `min`/`max`, which treat NaN differently).
#[allow(clippy::manual_clamp)]
pub(super) fn to_unit(x: f64) -> f64 {
    if x.is_nan() {
        0.5
    } else if x < 0.0 {
        0.0
    } else if x > 1.0 {
        1.0
    } else {
        x
    }
}

pub(super) fn boxes_meet(a: (DVec2, DVec2), b: (DVec2, DVec2), margin: f64) -> bool {
    a.0.x <= b.1.x + margin
        && b.0.x <= a.1.x + margin
        && a.0.y <= b.1.y + margin
        && b.0.y <= a.1.y + margin
}

/// What the subdivision hands its leaves to: each leaf's start for Newton's method, and
/// whether a pair of sub-ranges is already accounted for (inside a tangency's band).
pub(super) trait Leaves {
    /// A start `(u, v)` for Newton's method, the leaf's sub-ranges `[u0, u1, v0, v1]`, and
    /// whether the pair meets at most once. Returns what is left to do there.
    fn leaf(&mut self, start: (f64, f64), ranges: [f64; 4], single: bool) -> Rest;
    /// Whether nothing is left to find where `u ∈ a` and `v ∈ b`.
    fn covered(&self, a: (f64, f64), b: (f64, f64)) -> bool;
    /// The work done so far beyond the leaves themselves, in leaves' worth (classifying
    /// a point walks the curves out of its band: several leaves' worth).
    fn extra_work(&self) -> usize;
    /// Called once, when the work passes a quarter of the bound: the pair is crowded
    /// (curves running within the resolution of each other), and the visitor may trade
    /// the usual order of its work for cover.
    fn crowding(&mut self);
}

/// What is left of a leaf once the visitor has seen it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Rest {
    /// Nothing.
    Done,
    /// The leaf, subdivided further: a pair that meets at most once whose point was not
    /// found inside it (its point may be far from the chords' crossing when the curves run
    /// nearly parallel).
    Deeper,
    /// The leaf with `u` in `(lo, hi)` taken out (around the point found there): another
    /// point may lie beside it in a leaf flat to the resolution.
    Beside(f64, f64),
}

/// Two segments subdivided down to leaves: pairs of sub-segments flat to `flat` (then the
/// crossing of their chords starts Newton's method), or that meet at most once (flat to
/// 5 % of their chords, their tangent cones disjoint). Leaves go to the visitor as they
/// are found, so that what it finds prunes the rest.
pub(super) struct Subdivider<'v, V: Leaves> {
    pub(super) flat: f64,
    pub(super) margin: f64,
    pub(super) visitor: &'v mut V,
    /// Leaves handed over so far.
    pub(super) leaves: usize,
    /// The most leaves this pair may take (see [`max_leaves`]).
    pub(super) max_leaves: usize,
    /// Where the subdivision stopped at its limit: the sub-ranges `[u0, u1, v0, v1]` it
    /// was examining then (nothing found there, or after it, is certain).
    pub(super) crowded: Option<[f64; 4]>,
    /// Whether the visitor was told that the work passed a quarter of the bound.
    pub(super) crowding: bool,
}

/// The most leaves for a pair of segments of degrees `m` and `n`: a work bound (a leaf
/// costs about `(m + 1)(n + 1)` evaluations' worth) that still leaves room for every
/// point the pair can have (`m n`, sixteen leaves each). More means stretches closer than
/// the flatness resolution that are neither one tangency nor coincident: the
/// subdivision stops, and the caller refuses the pair rather than return what it found
/// so far as if it were all.
pub(super) fn max_leaves(m: usize, n: usize) -> usize {
    let work = (1usize << 20) / ((m + 1) * (n + 1)).max(1);
    work.max(4096 + 16 * m * n)
}

impl<V: Leaves> Subdivider<'_, V> {
    pub(super) fn run(&mut self, a: &Sub, b: &Sub, depth: u32) {
        let (ba, bb) = (a.bounds(), b.bounds());
        if !boxes_meet(ba, bb, self.margin) {
            return;
        }
        if self.visitor.covered(a.range(), b.range()) {
            return;
        }
        let work = self.leaves + self.visitor.extra_work();
        if !self.crowding && 4 * work >= self.max_leaves {
            self.crowding = true;
            self.visitor.crowding();
        }
        if work >= self.max_leaves {
            self.crowded.get_or_insert([a.u0, a.u1, b.u0, b.u1]);
            return;
        }
        let (fa, fb) = (a.flatness(), b.flatness());
        if (fa <= self.flat && fb <= self.flat) || depth >= 96 {
            // Flat pieces farther apart than their flatness (each outside the other's
            // fat line) do not meet: no leaf.
            if (fa > 0.0 || fb > 0.0)
                && (b.clip_range(a, self.margin).is_none()
                    || a.clip_range(b, self.margin).is_none()
                    || a.hulls_apart(b, self.margin))
            {
                return;
            }
            self.leaves += 1;
            // Disjoint tangent cones: the two meet at most once (a chord between two
            // common points would lie in both cones), so one point found is all of them.
            let single =
                matches!((a.cone(), b.cone()), (Some(ka), Some(kb)) if cones_disjoint(ka, kb));
            if let Rest::Beside(lo, hi) =
                self.visitor
                    .leaf(chord_crossing(a, b), [a.u0, a.u1, b.u0, b.u1], single)
                && depth < 96
            {
                let span = a.u1 - a.u0;
                for (x0, x1) in [(a.u0, lo), (hi, a.u1)] {
                    if x1 > x0 && (x1 - x0) > 1e-9 * span {
                        let part = a.restricted((x0 - a.u0) / span, (x1 - a.u0) / span);
                        self.run(&part, b, depth + 1);
                    }
                }
            }
            return;
        }
        // Two pieces each within 5 % of its chord's length of the chord, whose tangent
        // cones (as lines, directions modulo π) are disjoint, meet at most once; Newton's
        // method from the chords' crossing finds that point.
        // Deep down, pairs the boxes keep are mostly neighbours along two nearly
        // coincident stretches: their hulls part where the boxes do not.
        if depth >= 8 && a.hulls_apart(b, self.margin) {
            return;
        }
        let (ca, cb) = (a.chord(), b.chord());
        if fa <= 0.05 * ca.length()
            && fb <= 0.05 * cb.length()
            && let (Some(ka), Some(kb)) = (a.cone(), b.cone())
            && cones_disjoint(ka, kb)
        {
            self.leaves += 1;
            if self
                .visitor
                .leaf(chord_crossing(a, b), [a.u0, a.u1, b.u0, b.u1], true)
                != Rest::Deeper
            {
                return;
            }
        }
        // Fat-line clipping (Sederberg–Nishita): the part of `b` inside the strip around
        // `a`'s chord that holds `a`, then the part of `a` inside the strip around the
        // clipped `b`'s chord. Each clip keeps every point the two have in common.
        if fa > 0.0 || fb > 0.0 {
            // (Restricted only where the clip cut something: most clips of pieces with
            // several points in common keep all of both.)
            let Some((lo, hi)) = b.clip_range(a, self.margin) else {
                return;
            };
            let b_cut;
            let b2 = if lo <= 0.0 && hi >= 1.0 {
                b
            } else {
                b_cut = b.restricted(lo, hi);
                &b_cut
            };
            let Some((lo, hi)) = a.clip_range(b2, self.margin) else {
                return;
            };
            let a_cut;
            let a2 = if lo <= 0.0 && hi >= 1.0 {
                a
            } else {
                a_cut = a.restricted(lo, hi);
                &a_cut
            };
            let shrink = ((a2.u1 - a2.u0) * (b2.u1 - b2.u0)) / ((a.u1 - a.u0) * (b.u1 - b.u0));
            if shrink <= 0.5 {
                self.run(a2, b2, depth + 1);
                return;
            }
            self.split(a2, b2, depth);
            return;
        }
        self.split(a, b, depth);
    }

    /// Halves the larger of two pieces that clipping did not shrink enough (several points
    /// in common, or a tangency) and examines both halves. (The larger, flat or not: a
    /// line's box holds much of the plane, and only halving it separates a curve that
    /// passes near it.)
    pub(super) fn split(&mut self, a: &Sub, b: &Sub, depth: u32) {
        let (ba, bb) = (a.bounds(), b.bounds());
        let size_a = (ba.1 - ba.0).length();
        let size_b = (bb.1 - bb.0).length();
        if size_a >= size_b {
            let (l, r) = a.halves();
            self.run(&l, b, depth + 1);
            self.run(&r, b, depth + 1);
        } else {
            let (l, r) = b.halves();
            self.run(a, &l, depth + 1);
            self.run(a, &r, depth + 1);
        }
    }
}

/// Control points a [`Hull`] holds: up to degree 31 (the GPU's maximum); pieces of higher
/// degree are not tested (the test only prunes: nothing depends on it).
const HULL_POINTS: usize = 32;

/// The convex hull of a sub-segment's control points, counter-clockwise (Andrew's
/// monotone chain), on the stack.
struct Hull {
    points: [DVec2; 2 * HULL_POINTS + 1],
    len: usize,
}

impl Hull {
    /// The hull of `s`'s control points; `None` past [`HULL_POINTS`] points.
    fn of(s: &Sub) -> Option<Hull> {
        let n = s.len();
        if n > HULL_POINTS {
            return None;
        }
        let mut pts = [DVec2::ZERO; HULL_POINTS];
        for (i, p) in pts.iter_mut().enumerate().take(n) {
            *p = s.point(i);
        }
        let pts = &mut pts[..n];
        pts.sort_unstable_by(|p, q| p.x.total_cmp(&q.x).then(p.y.total_cmp(&q.y)));
        let mut out = Hull {
            points: [DVec2::ZERO; 2 * HULL_POINTS + 1],
            len: 0,
        };
        let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
        let (h, len) = (&mut out.points, &mut out.len);
        if n < 3 {
            h[..n].copy_from_slice(pts);
            *len = n;
            return Some(out);
        }
        for &p in pts.iter() {
            while *len >= 2 && cross(h[*len - 2], h[*len - 1], p) <= 0.0 {
                *len -= 1;
            }
            h[*len] = p;
            *len += 1;
        }
        let lower = *len + 1;
        for &p in pts.iter().rev().skip(1) {
            while *len >= lower && cross(h[*len - 2], h[*len - 1], p) <= 0.0 {
                *len -= 1;
            }
            h[*len] = p;
            *len += 1;
        }
        *len -= 1;
        Some(out)
    }

    fn points(&self) -> &[DVec2] {
        &self.points[..self.len]
    }

    /// Whether a side of this hull has every point of `other` more than `margin` beyond
    /// it (on its outer side).
    fn has_side_beyond(&self, other: &Hull, margin: f64) -> bool {
        let h = self.points();
        let n = h.len();
        if n < 2 || other.len == 0 {
            return false;
        }
        // A segment (two points) has both its sides as candidate lines.
        let sides = if n == 2 { 2 } else { n };
        (0..sides).any(|i| {
            let (p, q) = if n == 2 && i == 1 {
                (h[1], h[0])
            } else {
                (h[i], h[(i + 1) % n])
            };
            let e = q - p;
            let len = e.length();
            if len == 0.0 || !len.is_finite() {
                return false;
            }
            // The outer normal of a counter-clockwise polygon's side points right.
            let out = DVec2::new(e.y, -e.x) / len;
            other.points().iter().all(|&r| (r - p).dot(out) > margin)
        })
    }
}

/// The parameter interval `[lo, hi] ⊆ [0, 1]` where a polynomial with Bernstein
/// coefficients `y` can be ≥ 0: where the convex hull of the points `(i/n, y_i)` reaches
/// `y ≥ 0`. `None` when it cannot anywhere.
pub(super) fn nonnegative_range(y: &[f64]) -> Option<(f64, f64)> {
    // The hull reaches `y ≥ 0` only if a point does; between the first and the last such
    // point it does throughout. Beyond them, the hull's edges from the negative points
    // outside to the nonnegative ones cross zero: the extreme crossings are the ends.
    // (Edges between two points inside `[first, last]` cross there, and two negative
    // points make no crossing.)
    let first = y.iter().position(|&v| v >= 0.0)?;
    let last = y.iter().rposition(|&v| v >= 0.0).unwrap_or(first);
    let n = (y.len() - 1) as f64;
    let x = |i: usize| i as f64 / n;
    let crossing = |i: usize, j: usize| x(i) + (x(j) - x(i)) * y[i] / (y[i] - y[j]);
    let (mut lo, mut hi) = (x(first), x(last));
    let inside = || (first..=last).filter(|&k| y[k] >= 0.0);
    for i in 0..first {
        for j in inside() {
            lo = lo.min(crossing(i, j));
        }
    }
    for j in (last + 1)..y.len() {
        for i in inside() {
            hi = hi.max(crossing(i, j));
        }
    }
    Some((lo.max(0.0), hi.min(1.0)))
}

/// A quarter turn in [`pseudo_angle`]'s units.
const QUARTER_TURN: f64 = 1.0;

/// Half a turn in [`pseudo_angle`]'s units.
const HALF_TURN: f64 = 2.0;

/// The direction of `e ≠ 0` as a number in `[0, 4)` that grows with its angle from the
/// `+x` axis and grows by exactly 1 for each quarter turn (the "diamond angle": in each
/// quadrant the share of the second coordinate in the sum of the two): every comparison of
/// angles, and every shift by quarter and half turns, holds for it as for the angle,
/// without a trigonometric function.
fn pseudo_angle(e: DVec2) -> f64 {
    let (x, y) = (e.x, e.y);
    if y >= 0.0 {
        if x >= 0.0 {
            y / (x + y)
        } else {
            1.0 - x / (y - x)
        }
    } else if x < 0.0 {
        2.0 - y / (-x - y)
    } else {
        3.0 + x / (x - y)
    }
}

/// Whether two intervals of line directions (`[θ₀, θ₁]` in [`pseudo_angle`]'s units,
/// modulo half a turn, each narrower than a quarter turn) have no direction in common.
pub(super) fn cones_disjoint((a0, a1): (f64, f64), (b0, b1): (f64, f64)) -> bool {
    let shift = ((a0 - b0) / HALF_TURN).floor() * HALF_TURN;
    [
        shift - HALF_TURN,
        shift,
        shift + HALF_TURN,
        shift + 2.0 * HALF_TURN,
    ]
    .iter()
    .all(|k| b1 + k < a0 || b0 + k > a1)
}

/// Where the chords of two flat sub-segments cross, as segment parameters (clamped to the
/// sub-segments; the midpoints for parallel chords).
pub(super) fn chord_crossing(a: &Sub, b: &Sub) -> (f64, f64) {
    let (p0, p1) = (a.point(0), a.point(a.len() - 1));
    let (q0, q1) = (b.point(0), b.point(b.len() - 1));
    let (d, e) = (p1 - p0, q1 - q0);
    let det = d.perp_dot(e);
    let (alpha, beta) = if det.abs() > 1e-300 {
        let r = q0 - p0;
        (to_unit(r.perp_dot(e) / det), to_unit(r.perp_dot(d) / det))
    } else {
        (0.5, 0.5)
    };
    let (alpha, beta) = (
        a.parameter_of_fraction(alpha),
        b.parameter_of_fraction(beta),
    );
    (a.u0 + alpha * (a.u1 - a.u0), b.u0 + beta * (b.u1 - b.u0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    #[test]
    fn the_nonnegative_range_is_where_the_hull_reaches_zero() {
        // Against the hull taken whole: every nonnegative point and every zero crossing of
        // every edge between two points of opposite signs — on coefficients with zeros,
        // ties and every sign pattern.
        let brute = |y: &[f64]| -> Option<(f64, f64)> {
            let n = (y.len() - 1) as f64;
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for (i, &yi) in y.iter().enumerate() {
                let xi = i as f64 / n;
                if yi >= 0.0 {
                    lo = lo.min(xi);
                    hi = hi.max(xi);
                }
                for (j, &yj) in y.iter().enumerate().skip(i + 1) {
                    if (yi < 0.0) != (yj < 0.0) {
                        let x = xi + (j as f64 / n - xi) * yi / (yi - yj);
                        lo = lo.min(x);
                        hi = hi.max(x);
                    }
                }
            }
            (lo <= hi).then_some((lo.max(0.0), hi.min(1.0)))
        };
        let mut rng = Rng::new(11);
        let values = [-2.0, -1.0, -1e-300, 0.0, 1e-300, 0.5, 1.0, 3.0];
        for _ in 0..20_000 {
            let len = 2 + (rng.range(0.0, 15.0) as usize);
            let y: Vec<f64> = (0..len)
                .map(|_| {
                    if rng.range(0.0, 1.0) < 0.3 {
                        values[rng.range(0.0, values.len() as f64) as usize % values.len()]
                    } else {
                        rng.range(-1.0, 1.0)
                    }
                })
                .collect();
            // The same to rounding (an edge's crossing computed from the far side may land
            // an ulp beyond the point it meets).
            match (nonnegative_range(&y), brute(&y)) {
                (None, None) => {}
                (Some(a), Some(b)) => assert!(
                    (a.0 - b.0).abs() <= 4.0 * f64::EPSILON
                        && (a.1 - b.1).abs() <= 4.0 * f64::EPSILON,
                    "{y:?}: {a:?} vs {b:?}"
                ),
                (a, b) => panic!("{y:?}: {a:?} vs {b:?}"),
            }
        }
    }

    #[test]
    fn pseudo_angles_order_directions_as_angles_and_turn_by_one_a_quarter() {
        let mut rng = Rng::new(6);
        let turn = |e: DVec2| {
            let a = e.y.atan2(e.x);
            if a < 0.0 {
                a + std::f64::consts::TAU
            } else {
                a
            }
        };
        for _ in 0..2000 {
            let e = DVec2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
            let f = DVec2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
            let (pe, pf) = (pseudo_angle(e), pseudo_angle(f));
            assert!((0.0..4.0).contains(&pe), "{e}: {pe}");
            // Order as the angles in [0, 2π), unless the two are within rounding.
            if (turn(e) - turn(f)).abs() > 1e-12 {
                assert_eq!(pe < pf, turn(e) < turn(f), "{e} {f}: {pe} {pf}");
            }
            // A quarter turn adds exactly one (modulo four).
            let quarter = pseudo_angle(e.perp());
            let want = (pe + QUARTER_TURN) % 4.0;
            assert!(
                (quarter - want).abs() <= 4.0 * f64::EPSILON
                    || (quarter - want).abs() >= 4.0 - 1e-15,
                "{e}: {pe} then {quarter}"
            );
        }
        // The axes and diagonals exactly.
        for (e, want) in [
            (DVec2::X, 0.0),
            (DVec2::new(1.0, 1.0), 0.5),
            (DVec2::Y, 1.0),
            (DVec2::new(-1.0, 1.0), 1.5),
            (-DVec2::X, 2.0),
            (DVec2::new(-1.0, -1.0), 2.5),
            (-DVec2::Y, 3.0),
            (DVec2::new(1.0, -1.0), 3.5),
        ] {
            assert_eq!(pseudo_angle(e), want, "{e}");
        }
    }
}
