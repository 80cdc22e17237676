//! Exact arithmetic on polynomials with rational coefficients, and the exact answer to
//! "where do two planar curves meet": the resultant of one curve's implicit equation and
//! the other's parametrisation, its real roots isolated by Sturm sequences, the roots of
//! the two directions paired by exact point equality, kinds from the exact sign of the
//! tangents' cross product (or, where that sign is 0, the roots' multiplicities), and
//! coincident stretches decided by exact point membership.
//!
//! Nothing here uses floating point except to read the curves' control points (every
//! `f64` is a dyadic rational, so the curve the float code sees is this curve exactly).

#![allow(dead_code)]

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// An exact rational.
pub type Q = BigRational;

/// `n` as a rational.
pub fn q(n: i64) -> Q {
    Q::from_integer(BigInt::from(n))
}

/// The exact value of a finite `f64`.
pub fn qf(x: f64) -> Q {
    Q::from_float(x).expect("finite")
}

/// `C(n, k)`.
pub fn binomial(n: usize, k: usize) -> BigInt {
    let mut r = BigInt::one();
    for i in 0..k {
        r = r * BigInt::from(n - i) / BigInt::from(i + 1);
    }
    r
}

/// A polynomial with rational coefficients, ascending, without trailing zeros.
#[derive(Clone, Debug, PartialEq)]
pub struct Poly(pub Vec<Q>);

impl Poly {
    pub fn new(mut c: Vec<Q>) -> Poly {
        while c.last().is_some_and(Zero::is_zero) {
            c.pop();
        }
        Poly(c)
    }

    pub fn zero() -> Poly {
        Poly(Vec::new())
    }

    pub fn constant(c: Q) -> Poly {
        Poly::new(vec![c])
    }

    /// `x − r`.
    pub fn linear_root(r: &Q) -> Poly {
        Poly::new(vec![-r.clone(), Q::one()])
    }

    pub fn is_zero(&self) -> bool {
        self.0.is_empty()
    }

    /// The degree (`None` for the zero polynomial).
    pub fn degree(&self) -> Option<usize> {
        self.0.len().checked_sub(1)
    }

    pub fn eval(&self, x: &Q) -> Q {
        let mut acc = Q::zero();
        for c in self.0.iter().rev() {
            acc = acc * x + c;
        }
        acc
    }

    /// The sign at `x`: −1, 0 or 1.
    pub fn sign_at(&self, x: &Q) -> i32 {
        let v = self.eval(x);
        if v.is_zero() {
            0
        } else if v.is_positive() {
            1
        } else {
            -1
        }
    }

    pub fn add(&self, o: &Poly) -> Poly {
        let n = self.0.len().max(o.0.len());
        Poly::new(
            (0..n)
                .map(|i| {
                    self.0.get(i).cloned().unwrap_or_else(Q::zero)
                        + o.0.get(i).cloned().unwrap_or_else(Q::zero)
                })
                .collect(),
        )
    }

    pub fn sub(&self, o: &Poly) -> Poly {
        self.add(&o.scale(&q(-1)))
    }

    pub fn scale(&self, k: &Q) -> Poly {
        Poly::new(self.0.iter().map(|c| c * k).collect())
    }

    pub fn mul(&self, o: &Poly) -> Poly {
        if self.is_zero() || o.is_zero() {
            return Poly::zero();
        }
        let mut out = vec![Q::zero(); self.0.len() + o.0.len() - 1];
        for (i, a) in self.0.iter().enumerate() {
            if a.is_zero() {
                continue;
            }
            for (j, b) in o.0.iter().enumerate() {
                out[i + j] += a * b;
            }
        }
        Poly::new(out)
    }

    pub fn pow(&self, k: usize) -> Poly {
        (0..k).fold(Poly::constant(Q::one()), |acc, _| acc.mul(self))
    }

    pub fn deriv(&self) -> Poly {
        Poly::new(
            self.0
                .iter()
                .enumerate()
                .skip(1)
                .map(|(i, c)| c * q(i as i64))
                .collect(),
        )
    }

    /// Quotient and remainder by `d ≠ 0`.
    pub fn divrem(&self, d: &Poly) -> (Poly, Poly) {
        let dd = d.degree().expect("division by the zero polynomial");
        let lead = d.0[dd].clone();
        let mut r = self.0.clone();
        if r.len() <= dd {
            return (Poly::zero(), self.clone());
        }
        let mut quo = vec![Q::zero(); r.len() - dd];
        for k in (0..quo.len()).rev() {
            let c = &r[k + dd] / &lead;
            if !c.is_zero() {
                for (i, di) in d.0.iter().enumerate() {
                    r[k + i] -= &c * di;
                }
            }
            quo[k] = c;
        }
        r.truncate(dd);
        (Poly::new(quo), Poly::new(r))
    }

    pub fn monic(&self) -> Poly {
        match self.0.last() {
            Some(lead) => {
                let inv = Q::one() / lead;
                self.scale(&inv)
            }
            None => Poly::zero(),
        }
    }

    /// The monic greatest common divisor (zero when both are zero).
    pub fn gcd(&self, o: &Poly) -> Poly {
        let (mut a, mut b) = (self.clone(), o.clone());
        while !b.is_zero() {
            let r = a.divrem(&b).1;
            a = b;
            b = r.monic();
        }
        a.monic()
    }

    /// The square-free part `p / gcd(p, p′)`.
    pub fn squarefree(&self) -> Poly {
        let g = self.gcd(&self.deriv());
        if g.degree() == Some(0) {
            return self.monic();
        }
        self.divrem(&g).0.monic()
    }

    /// `|p(x)| ≤ Σ |c_k|` for `x ∈ [−1, 1]`.
    pub fn norm1(&self) -> Q {
        self.0.iter().map(Signed::abs).fold(Q::zero(), |a, b| a + b)
    }
}

/// A real root, isolated: `lo == hi` when it is exactly that rational.
#[derive(Clone, Debug)]
pub struct RootIv {
    pub lo: Q,
    pub hi: Q,
}

impl RootIv {
    pub fn exact(x: Q) -> RootIv {
        RootIv {
            lo: x.clone(),
            hi: x,
        }
    }

    pub fn is_exact(&self) -> bool {
        self.lo == self.hi
    }

    pub fn mid(&self) -> Q {
        (&self.lo + &self.hi) / q(2)
    }

    pub fn width(&self) -> Q {
        &self.hi - &self.lo
    }

    pub fn to_f64(&self) -> f64 {
        self.mid().to_f64().expect("finite")
    }

    /// Whether `x` is in the interval widened by `margin`.
    pub fn holds(&self, x: f64, margin: f64) -> bool {
        let (lo, hi) = (
            self.lo.to_f64().expect("finite"),
            self.hi.to_f64().expect("finite"),
        );
        x >= lo - margin && x <= hi + margin
    }
}

/// The Sturm sequence of a square-free `p`.
fn sturm(p: &Poly) -> Vec<Poly> {
    let mut seq = vec![p.clone(), p.deriv()];
    loop {
        let n = seq.len();
        if seq[n - 1].is_zero() {
            seq.pop();
            break;
        }
        let r = seq[n - 2].divrem(&seq[n - 1]).1;
        if r.is_zero() {
            break;
        }
        seq.push(r.scale(&q(-1)));
    }
    seq
}

fn variations(seq: &[Poly], x: &Q) -> usize {
    let mut last = 0;
    let mut count = 0;
    for p in seq {
        let s = p.sign_at(x);
        if s != 0 {
            if last != 0 && s != last {
                count += 1;
            }
            last = s;
        }
    }
    count
}

/// The distinct real roots of `p ≠ 0` in `[lo, hi]`, isolated (exact where a bisection
/// point is one), by `x`.
pub fn real_roots(p: &Poly, lo: &Q, hi: &Q) -> Vec<RootIv> {
    isolated(p, lo, hi).0
}

/// [`real_roots`], and the square-free part without the roots at the ends (whose signs
/// at the ends of every isolating interval differ).
fn isolated(p: &Poly, lo: &Q, hi: &Q) -> (Vec<RootIv>, Poly) {
    assert!(!p.is_zero(), "the zero polynomial has every root");
    let mut sf = p.squarefree();
    let mut out = Vec::new();
    // Roots at the ends exactly, deflated so that the Sturm counts see none there.
    for end in [lo, hi] {
        if sf.sign_at(end) == 0 {
            out.push(RootIv::exact(end.clone()));
            sf = sf.divrem(&Poly::linear_root(end)).0;
        }
    }
    if sf.degree().unwrap_or(0) > 0 {
        let seq = sturm(&sf);
        isolate(&sf, &seq, lo.clone(), hi.clone(), &mut out);
    }
    out.sort_by(|a, b| a.lo.cmp(&b.lo));
    if lo == hi {
        out.truncate(1);
    }
    (out, sf)
}

/// Roots of `sf` in the open `(a, b)`, `sf(a), sf(b) ≠ 0`.
fn isolate(sf: &Poly, seq: &[Poly], a: Q, b: Q, out: &mut Vec<RootIv>) {
    let count = variations(seq, &a) - variations(seq, &b);
    if count == 0 {
        return;
    }
    if count == 1 {
        out.push(RootIv { lo: a, hi: b });
        return;
    }
    // Split in the middle, or beside it where the middle is a root (that root then lies
    // inside one half and is isolated there).
    let mut m = (&a + &b) / q(2);
    let mut step = (&b - &a) / q(1024);
    while sf.sign_at(&m) == 0 {
        m += &step;
        step /= q(2);
    }
    isolate(sf, seq, a, m.clone(), out);
    isolate(sf, seq, m, b, out);
}

/// Refines an isolated root of the square-free `sf` to a width of at most `width`.
pub fn refine(sf: &Poly, r: &mut RootIv, width: &Q) {
    if r.is_exact() {
        return;
    }
    let mut slo = sf.sign_at(&r.lo);
    assert!(slo != 0, "an isolating interval's end is a root");
    while r.width() > *width {
        let m = r.mid();
        let sm = sf.sign_at(&m);
        if sm == 0 {
            *r = RootIv::exact(m);
            return;
        }
        if sm == slo {
            r.lo = m;
            slo = sm;
        } else {
            r.hi = m;
        }
    }
}

/// The isolated roots in `[lo, hi]` refined to `width`, and the square-free part used.
pub fn roots_refined(p: &Poly, lo: &Q, hi: &Q, width: &Q) -> Vec<RootIv> {
    let (mut roots, sf) = isolated(p, lo, hi);
    for r in &mut roots {
        refine(&sf, r, width);
    }
    roots
}

/// Whether the root isolated by `r` (a root of `p`'s square-free part) is a multiple root
/// of `p`: a root of `gcd(p, p′)` in the interval.
pub fn is_multiple(p: &Poly, r: &RootIv) -> bool {
    let g = p.gcd(&p.deriv());
    if g.degree().unwrap_or(0) == 0 {
        return false;
    }
    if r.is_exact() {
        return g.sign_at(&r.lo) == 0;
    }
    !real_roots(&g, &r.lo, &r.hi).is_empty()
}

/// The determinant of a square rational matrix (Gaussian elimination).
pub fn determinant(mut m: Vec<Vec<Q>>) -> Q {
    let n = m.len();
    let mut det = Q::one();
    for col in 0..n {
        let Some(pivot) = (col..n).find(|&r| !m[r][col].is_zero()) else {
            return Q::zero();
        };
        if pivot != col {
            m.swap(pivot, col);
            det = -det;
        }
        let p = m[col][col].clone();
        det *= &p;
        for r in (col + 1)..n {
            if m[r][col].is_zero() {
                continue;
            }
            let f = &m[r][col] / &p;
            let pivot_row = m[col].clone();
            for (x, y) in m[r].iter_mut().zip(&pivot_row).skip(col) {
                *x -= &f * y;
            }
        }
    }
    det
}

/// The Sylvester resultant of `p(y) = Σ p_k yᵏ` and `q(y)` with the formal degrees given
/// by their lengths (numbers).
fn sylvester(p: &[Q], q_: &[Q]) -> Q {
    let (m, n) = (p.len() - 1, q_.len() - 1);
    let size = m + n;
    if size == 0 {
        return Q::one();
    }
    let mut rows = vec![vec![Q::zero(); size]; size];
    for r in 0..n {
        for (k, c) in p.iter().enumerate() {
            // Descending powers along the row.
            rows[r][r + (m - k)] = c.clone();
        }
    }
    for r in 0..m {
        for (k, c) in q_.iter().enumerate() {
            rows[n + r][r + (n - k)] = c.clone();
        }
    }
    determinant(rows)
}

/// `Res_y(p, q)` for `p(x, y) = Σ_k p[k](x) yᵏ` and `q` likewise, as a polynomial in `x`:
/// the Sylvester determinant at `deg + 1` integers, interpolated.
pub fn resultant(p: &[Poly], q_: &[Poly]) -> Poly {
    let trim = |v: &[Poly]| -> Vec<Poly> {
        let mut v = v.to_vec();
        while v.last().is_some_and(Poly::is_zero) {
            v.pop();
        }
        v
    };
    let (p, q_) = (trim(p), trim(q_));
    if p.is_empty() || q_.is_empty() {
        return Poly::zero();
    }
    let (m, n) = (p.len() - 1, q_.len() - 1);
    let dp = p.iter().filter_map(Poly::degree).max().unwrap_or(0);
    let dq = q_.iter().filter_map(Poly::degree).max().unwrap_or(0);
    let deg = n * dp + m * dq;
    let xs: Vec<Q> = (0..=deg as i64).map(q).collect();
    let ys: Vec<Q> = xs
        .iter()
        .map(|x| {
            let pv: Vec<Q> = p.iter().map(|c| c.eval(x)).collect();
            let qv: Vec<Q> = q_.iter().map(|c| c.eval(x)).collect();
            sylvester(&pv, &qv)
        })
        .collect();
    interpolate(&xs, &ys)
}

/// The polynomial through `(xs[i], ys[i])` (Newton's divided differences).
pub fn interpolate(xs: &[Q], ys: &[Q]) -> Poly {
    let n = xs.len();
    let mut coef = ys.to_vec();
    for j in 1..n {
        for i in (j..n).rev() {
            coef[i] = (&coef[i] - &coef[i - 1]) / (&xs[i] - &xs[i - j]);
        }
    }
    let mut out = Poly::constant(coef[n - 1].clone());
    for i in (0..n - 1).rev() {
        out = out
            .mul(&Poly::linear_root(&xs[i]))
            .add(&Poly::constant(coef[i].clone()));
    }
    out
}

/// A planar rational curve on `[0, 1]` exactly: `(X(t), Y(t)) / W(t)`, power basis.
#[derive(Clone, Debug)]
pub struct Curve {
    pub x: Poly,
    pub y: Poly,
    pub w: Poly,
    /// The smallest weight (a lower bound of `W` on `[0, 1]`), positive.
    pub wmin: Q,
}

/// `Σ c_i B_{i,n}(t)` in the power basis.
pub fn bernstein_to_power(c: &[Q]) -> Poly {
    let n = c.len() - 1;
    let mut out = vec![Q::zero(); n + 1];
    for (i, ci) in c.iter().enumerate() {
        if ci.is_zero() {
            continue;
        }
        let b = Q::from_integer(binomial(n, i));
        for (k, slot) in out.iter_mut().enumerate().skip(i) {
            let sign = if (k - i) % 2 == 0 { 1 } else { -1 };
            let coef = Q::from_integer(binomial(n - i, k - i) * BigInt::from(sign));
            *slot += ci * &b * coef;
        }
    }
    Poly::new(out)
}

impl Curve {
    /// From control points and (optional) positive weights, read exactly.
    pub fn new(points: &[(f64, f64)], weights: Option<&[f64]>) -> Curve {
        let exact: Vec<(Q, Q, Q)> = points
            .iter()
            .enumerate()
            .map(|(i, &(x, y))| {
                let w = weights.map_or_else(Q::one, |w| qf(w[i]));
                (qf(x) * &w, qf(y) * &w, w)
            })
            .collect();
        Curve::from_homogeneous(&exact)
    }

    /// From exact homogeneous Bernstein coefficients `(w x, w y, w)`.
    pub fn from_homogeneous(h: &[(Q, Q, Q)]) -> Curve {
        let xs: Vec<Q> = h.iter().map(|p| p.0.clone()).collect();
        let ys: Vec<Q> = h.iter().map(|p| p.1.clone()).collect();
        let ws: Vec<Q> = h.iter().map(|p| p.2.clone()).collect();
        let wmin = ws.iter().cloned().min().expect("points");
        assert!(wmin.is_positive(), "weights must be positive");
        Curve {
            x: bernstein_to_power(&xs),
            y: bernstein_to_power(&ys),
            w: bernstein_to_power(&ws),
            wmin,
        }
    }

    pub fn point(&self, t: &Q) -> (Q, Q) {
        let w = self.w.eval(t);
        (self.x.eval(t) / &w, self.y.eval(t) / &w)
    }

    /// The numerators of the velocity: `X′W − XW′`, `Y′W − YW′` (over `W²`).
    pub fn velocity_numerators(&self) -> (Poly, Poly) {
        let dw = self.w.deriv();
        (
            self.x.deriv().mul(&self.w).sub(&self.x.mul(&dw)),
            self.y.deriv().mul(&self.w).sub(&self.y.mul(&dw)),
        )
    }

    /// `C′(t)` and `C″(t)`, computed exactly and rounded.
    pub fn derivatives(&self, t: &Q) -> ((f64, f64), (f64, f64)) {
        let w = self.w.eval(t);
        let (w1, w2) = (self.w.deriv().eval(t), self.w.deriv().deriv().eval(t));
        let one = |p: &Poly| -> (f64, f64) {
            let (x, x1, x2) = (p.eval(t), p.deriv().eval(t), p.deriv().deriv().eval(t));
            let n1 = &x1 * &w - &x * &w1;
            let d1 = &n1 / (&w * &w);
            let d2 = ((&x2 * &w - &x * &w2) * &w - q(2) * &w1 * &n1) / (&w * &w * &w);
            (d1.to_f64().expect("finite"), d2.to_f64().expect("finite"))
        };
        let ((dx, ddx), (dy, ddy)) = (one(&self.x), one(&self.y));
        ((dx, dy), (ddx, ddy))
    }

    /// A Lipschitz constant on `[0, 1]`.
    pub fn lipschitz(&self) -> Q {
        let (nx, ny) = self.velocity_numerators();
        (nx.norm1() + ny.norm1()) / (&self.wmin * &self.wmin)
    }

    /// Whether the curve is polynomial (`W` constant).
    pub fn is_polynomial(&self) -> bool {
        self.w.degree().unwrap_or(0) == 0
    }
}

/// Coefficients (in `s`) of `X_P(s) W_Q(t) − X_Q(t) W_P(s)`, each a polynomial in `t`:
/// the points of `P` equal to `Q(t)` are the common roots of this and its `y` twin.
fn incidence(p: &Curve, q_: &Curve, y: bool) -> Vec<Poly> {
    let (pc, qc) = if y { (&p.y, &q_.y) } else { (&p.x, &q_.x) };
    let n = pc.0.len().max(p.w.0.len());
    (0..n)
        .map(|k| {
            let xk = pc.0.get(k).cloned().unwrap_or_else(Q::zero);
            let wk = p.w.0.get(k).cloned().unwrap_or_else(Q::zero);
            q_.w.scale(&xk).sub(&qc.scale(&wk))
        })
        .collect()
}

/// `Res_s` of the incidence equations: a polynomial in `t` that vanishes where `Q(t)` lies
/// on `P`'s implicit curve (and possibly at `W_Q(t) = 0`, never in `[0, 1]`).
pub fn implicit_resultant(p: &Curve, q_: &Curve) -> Poly {
    resultant(&incidence(p, q_, false), &incidence(p, q_, true))
}

/// The parameters in `[0, 1]` where `c` passes through the rational point `(x, y)`.
pub fn parameters_of_point(c: &Curve, x: &Q, y: &Q) -> Vec<RootIv> {
    let ex = c.x.sub(&c.w.scale(x));
    let ey = c.y.sub(&c.w.scale(y));
    let g = match (ex.is_zero(), ey.is_zero()) {
        (true, true) => panic!("a constant curve"),
        (true, false) => ey,
        (false, true) => ex,
        (false, false) => ex.gcd(&ey),
    };
    if g.degree().unwrap_or(0) == 0 {
        return Vec::new();
    }
    roots_refined(&g, &Q::zero(), &Q::one(), &width())
}

/// The width every root is refined to: `2⁻¹²⁰`.
pub fn width() -> Q {
    Q::new(BigInt::one(), BigInt::one() << 120)
}

/// The bivariate divided differences `(F(σ)W(τ) − F(τ)W(σ)) / (σ − τ)` for `F` = `X` or
/// `Y`, as coefficients in `τ` that are polynomials in `σ`.
fn divided(c: &Curve, y: bool) -> Vec<Poly> {
    let f = if y { &c.y } else { &c.x };
    let n = f.0.len().max(c.w.0.len());
    let get = |p: &Poly, i: usize| p.0.get(i).cloned().unwrap_or_else(Q::zero);
    // f[i][j] = f_i w_j − f_j w_i; (σ^i τ^j − σ^j τ^i) / (σ − τ) for i > j is
    // σ^j τ^j Σ_{k<i−j} σ^{i−j−1−k} τ^k.
    let mut coef = vec![vec![Q::zero(); n]; n]; // coef[a][b]: σ^a τ^b
    for i in 0..n {
        for j in 0..i {
            let fij = get(f, i) * get(&c.w, j) - get(f, j) * get(&c.w, i);
            if fij.is_zero() {
                continue;
            }
            for k in 0..(i - j) {
                coef[j + i - j - 1 - k][j + k] += &fij;
            }
        }
    }
    (0..n)
        .map(|b| Poly::new((0..n).map(|a| coef[a][b].clone()).collect()))
        .collect()
}

/// The node polynomial of a curve: its roots (over all real `σ`) hold the parameters
/// where the curve passes twice through one point (and its cusps).
pub fn node_polynomial(c: &Curve) -> Poly {
    let (dx, dy) = (divided(c, false), divided(c, true));
    let zero = |d: &[Poly]| d.iter().all(Poly::is_zero);
    let constant = |d: &[Poly]| d.iter().skip(1).all(Poly::is_zero) && d[0].degree() == Some(0);
    match (zero(&dx), zero(&dy)) {
        // A line, horizontal or vertical: no nodes.
        (true, false) if constant(&dy) => Poly::constant(q(1)),
        (false, true) if constant(&dx) => Poly::constant(q(1)),
        (false, false) => {
            let r = resultant(&dx, &dy);
            assert!(
                !r.is_zero(),
                "oracle: an improper parametrisation (it runs over itself)"
            );
            r
        }
        _ => panic!("oracle: an improper parametrisation (it runs over itself)"),
    }
}

/// The kind of an exact meeting point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Crossing,
    Tangent,
}

/// One exact meeting point: both parameters isolated, and its kind.
#[derive(Clone, Debug)]
pub struct Point {
    pub s: RootIv,
    pub t: RootIv,
    pub kind: Kind,
}

/// One exact coincident stretch: `s` and `t` intervals (ends isolated), `t.0` meeting
/// `s.0`.
#[derive(Clone, Debug)]
pub struct Stretch {
    pub s: (RootIv, RootIv),
    pub t: (RootIv, RootIv),
}

/// Everything two curves have in common, exactly.
#[derive(Clone, Debug, Default)]
pub struct Truth {
    pub points: Vec<Point>,
    pub overlaps: Vec<Stretch>,
}

/// Whether `P(s) = Q(t)` for the isolated roots given (exactly when both are exact; by an
/// interval bound at the midpoints otherwise — the intervals are `2⁻¹²⁰` wide, so points
/// that are not equal are told apart unless they are closer than about `2⁻¹⁰⁰`).
fn same_point(p: &Curve, s: &RootIv, q_: &Curve, t: &RootIv) -> bool {
    let (a, b) = (p.point(&s.mid()), q_.point(&t.mid()));
    let bound = p.lipschitz() * s.width() / q(2) + q_.lipschitz() * t.width() / q(2);
    (&a.0 - &b.0).abs() <= bound && (&a.1 - &b.1).abs() <= bound
}

/// The sign of `P′(s) × Q′(t)` where the box of the two intervals decides it, else `None`.
fn cross_sign(p: &Curve, s: &RootIv, q_: &Curve, t: &RootIv) -> Option<i32> {
    let (px, py) = p.velocity_numerators();
    let (qx, qy) = q_.velocity_numerators();
    let (sm, tm) = (s.mid(), t.mid());
    let c = px.eval(&sm) * qy.eval(&tm) - py.eval(&sm) * qx.eval(&tm);
    // |∂c/∂s| ≤ |px′||qy| + |py′||qx|, and likewise in t (norms on [−1, 1] ⊇ [0, 1]).
    let ds = px.deriv().norm1() * qy.norm1() + py.deriv().norm1() * qx.norm1();
    let dt = px.norm1() * qy.deriv().norm1() + py.norm1() * qx.deriv().norm1();
    let var = ds * s.width() / q(2) + dt * t.width() / q(2);
    if c.abs() > var {
        Some(if c.is_positive() { 1 } else { -1 })
    } else if s.is_exact() && t.is_exact() && c.is_zero() {
        Some(0)
    } else {
        None
    }
}

/// The exact intersections of two planar curves on `[0, 1]²`.
pub fn intersect(p: &Curve, q_: &Curve) -> Truth {
    let g = implicit_resultant(p, q_);
    if g.is_zero() {
        return coincident(p, q_);
    }
    let h = implicit_resultant(q_, p);
    assert!(
        !h.is_zero(),
        "one resultant vanishes and the other does not"
    );
    let (zero, one, w) = (Q::zero(), Q::one(), width());
    let ts = roots_refined(&g, &zero, &one, &w);
    let ss = roots_refined(&h, &zero, &one, &w);
    let mut points = Vec::new();
    for s in &ss {
        for t in &ts {
            if !same_point(p, s, q_, t) {
                continue;
            }
            let kind = match cross_sign(p, s, q_, t) {
                Some(0) => Kind::Tangent,
                Some(_) => Kind::Crossing,
                None => {
                    // The sign could not be told: a tangency has a multiple root in both
                    // directions; a crossing has a simple one in at least one.
                    match (is_multiple(&h, s), is_multiple(&g, t)) {
                        (true, true) => Kind::Tangent,
                        (false, _) | (_, false) => {
                            panic!(
                                "oracle: undecided kind at s ≈ {}, t ≈ {}",
                                s.to_f64(),
                                t.to_f64()
                            )
                        }
                    }
                }
            };
            points.push(Point {
                s: s.clone(),
                t: t.clone(),
                kind,
            });
        }
    }
    Truth {
        points,
        overlaps: Vec::new(),
    }
}

/// Two curves on one algebraic curve: the stretches where both cover it, and the points
/// they share outside those (ends that meet, and the curve's self-crossings).
fn coincident(p: &Curve, q_: &Curve) -> Truth {
    let (zero, one) = (Q::zero(), Q::one());
    // Where Q passes through P's ends, and 0 and 1: between consecutive breaks, Q is on P
    // throughout or nowhere (apart from single points).
    let mut breaks: Vec<(RootIv, Option<Q>)> = vec![
        (RootIv::exact(zero.clone()), None),
        (RootIv::exact(one.clone()), None),
    ];
    for s_end in [&zero, &one] {
        let (x, y) = p.point(s_end);
        for t in parameters_of_point(q_, &x, &y) {
            breaks.push((t, Some(s_end.clone())));
        }
    }
    breaks.sort_by(|a, b| a.0.lo.cmp(&b.0.lo));
    let mut merged: Vec<(RootIv, Vec<Option<Q>>)> = Vec::new();
    for (t, s) in breaks {
        match merged.last_mut() {
            Some(last) if last.0.lo <= t.hi && t.lo <= last.0.hi => last.1.push(s),
            _ => merged.push((t, vec![s])),
        }
    }
    let on_p = |t: &Q| -> Vec<RootIv> {
        let (x, y) = q_.point(t);
        parameters_of_point(p, &x, &y)
    };
    let mut overlaps: Vec<Stretch> = Vec::new();
    for k in 0..merged.len().saturating_sub(1) {
        let (a, b) = (&merged[k], &merged[k + 1]);
        // Two points a third and two thirds of the way (not where a dyadic self-crossing
        // could sit), both on P when the stretch lies on it.
        let third = (&b.0.lo - &a.0.hi) / q(3);
        let (m1, mid) = (&a.0.hi + &third, &b.0.lo - &third);
        let inner = on_p(&mid);
        if inner.is_empty() || on_p(&m1).is_empty() {
            continue;
        }
        assert!(
            inner.len() == 1,
            "oracle: a coincident stretch through a self-crossing"
        );
        let sm = inner[0].clone();
        // The s at each end: P's end when the break is one, else Q's end's preimage
        // nearest the inside.
        let s_at = |brk: &(RootIv, Vec<Option<Q>>)| -> RootIv {
            let mut best: Option<RootIv> = None;
            let cands: Vec<RootIv> = if brk.1.iter().any(Option::is_some) {
                brk.1
                    .iter()
                    .flatten()
                    .map(|s| RootIv::exact(s.clone()))
                    .collect()
            } else {
                on_p(&brk.0.lo)
            };
            for c in cands {
                let d = (c.mid() - sm.mid()).abs();
                if best.as_ref().is_none_or(|b| (b.mid() - sm.mid()).abs() > d) {
                    best = Some(c);
                }
            }
            best.expect("an end of a coincident stretch has a parameter on P")
        };
        let (s0, s1) = (s_at(a), s_at(b));
        match overlaps.last_mut() {
            Some(last) if last.t.1.lo == a.0.lo => {
                last.t.1 = b.0.clone();
                last.s.1 = s1;
            }
            _ => overlaps.push(Stretch {
                s: (s0, s1),
                t: (a.0.clone(), b.0.clone()),
            }),
        }
    }
    // Orient every stretch by s.
    for o in &mut overlaps {
        if o.s.0.lo > o.s.1.lo {
            std::mem::swap(&mut o.s.0, &mut o.s.1);
            std::mem::swap(&mut o.t.0, &mut o.t.1);
        }
    }
    overlaps.sort_by(|a, b| a.s.0.lo.cmp(&b.s.0.lo));
    let inside = |x: &RootIv, lo: &RootIv, hi: &RootIv| -> bool {
        let (l, h) = if lo.lo <= hi.lo { (lo, hi) } else { (hi, lo) };
        x.hi >= l.lo && x.lo <= h.hi
    };
    let on_stretch = |s: &RootIv, t: &RootIv| {
        overlaps
            .iter()
            .any(|o| inside(s, &o.s.0, &o.s.1) || inside(t, &o.t.0, &o.t.1))
    };
    // Shared points off the stretches: ends of one on the other, and self-crossings.
    let mut points: Vec<Point> = Vec::new();
    let push = |s: RootIv, t: RootIv, points: &mut Vec<Point>| {
        if on_stretch(&s, &t)
            || points
                .iter()
                .any(|x| x.s.lo <= s.hi && s.lo <= x.s.hi && x.t.lo <= t.hi && t.lo <= x.t.hi)
        {
            return;
        }
        let kind = match cross_sign(p, &s, q_, &t) {
            Some(0) | None => Kind::Tangent,
            Some(_) => Kind::Crossing,
        };
        points.push(Point { s, t, kind });
    };
    for s_end in [&zero, &one] {
        let (x, y) = p.point(s_end);
        for t in parameters_of_point(q_, &x, &y) {
            push(RootIv::exact(s_end.clone()), t, &mut points);
        }
    }
    for t_end in [&zero, &one] {
        for s in on_p(t_end) {
            push(s, RootIv::exact(t_end.clone()), &mut points);
        }
    }
    let w = width();
    let np = roots_refined(&node_polynomial(p), &zero, &one, &w);
    let nq = roots_refined(&node_polynomial(q_), &zero, &one, &w);
    for s in &np {
        for t in &nq {
            if same_point(p, s, q_, t) {
                push(s.clone(), t.clone(), &mut points);
            }
        }
    }
    points.sort_by(|a, b| a.s.lo.cmp(&b.s.lo));
    Truth { points, overlaps }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resultant_of_two_lines_in_a_parameter() {
        // p = y − x, q = y − 1: Res_y = (1 − x)·(sign) — vanishes at x = 1.
        let p = vec![Poly::new(vec![q(0), q(-1)]), Poly::constant(q(1))];
        let qq = vec![Poly::constant(q(-1)), Poly::constant(q(1))];
        let r = resultant(&p, &qq);
        assert_eq!(r.degree(), Some(1));
        assert!(r.eval(&q(1)).is_zero());
    }
}
