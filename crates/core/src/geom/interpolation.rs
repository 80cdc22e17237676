//! Cubic Bézier interpolation, plain and modified (paper 002, §5).

use glam::DVec3;

use super::Aabb;
use super::bezier::check_finite;
use super::family::{Family, lowered_box};
use super::modified::{
    ModifiedBezier, bump, bump_deriv, bump_second_deriv, check_t_star, check_vector,
};
use super::{Bezier, BezierSegment, GeomError, Lower, ParamCurve};

/// Which reading of paper 002's modified interpolation to use (docs/math.md §1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Reading {
    /// The paper's reading (default; reproduces its Example 2 exactly): plain cubic pieces
    /// with inner points `P̃_{i−2/3} = P_{i−1} + (h/3)(s_{i−1} − (2/t*) v)` and
    /// `P̃_{i−1/3} = P_i − (h/3)(s_i − (2/t*) v)`; C¹ with tangent `s_i − (2/t*) v` at
    /// every point.
    #[default]
    Paper,
    /// "Bump added": piece `i` is `Q̃_i(u) + h S(u) v` with
    /// `P̃_{i−2/3} = P_{i−1} + (h/3)(s_{i−1} − (2/t*) v)` and
    /// `P̃_{i−1/3} = P_i − (h/3)(s_i + (2/(1 − t*)) v)`; C¹ with tangent `s_i` at every
    /// point, for any `t*`. Each piece is a [`ModifiedBezier`] with vector `h v`.
    BumpAdded,
}

impl Reading {
    /// The name used in scene files: `"paper"` or `"bump_added"`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Reading::Paper => "paper",
            Reading::BumpAdded => "bump_added",
        }
    }
}

/// The modification of an interpolating curve: `t*`, `v` and the reading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Modification {
    /// `t* ∈ (0, 1)`.
    pub t_star: f64,
    /// The vector `v`.
    pub v: DVec3,
    /// How the modification is read.
    pub reading: Reading,
}

/// The interpolating cubic Bézier spline of paper 002, §5, optionally modified.
///
/// Points `P_0..P_k` at strictly increasing parameters `t_0 < … < t_k`;
/// `C_i = (P_{i+1} − P_i)/(t_{i+1} − t_i)`, `α_i = (t_i − t_{i−1})/(t_{i+1} − t_{i−1})`,
/// tangents `s_i = (1 − α_i) C_{i−1} + α_i C_i` (the parabola through three points),
/// `s_0 = 2C_0 − s_1`, `s_k = 2C_{k−1} − s_{k−1}` (with two points, `s_0 = s_1 = C_0`: a
/// straight cubic). Piece `i` (from `P_{i−1}` to `P_i`, `h = t_i − t_{i−1}`) is the cubic
/// with inner points `P_{i−2/3} = P_{i−1} + (h/3) s_{i−1}` and `P_{i−1/3} = P_i − (h/3) s_i`,
/// parametrised by `u = (t − t_{i−1})/h`. The modified forms are described by [`Reading`].
#[derive(Debug, Clone, PartialEq)]
pub struct CubicInterpolation {
    pub(crate) points: Vec<DVec3>,
    pub(crate) params: Vec<f64>,
    pub(crate) modification: Option<Modification>,
    pub(crate) tangents: Vec<DVec3>,
    pub(crate) pieces: Vec<Bezier>,
}

impl CubicInterpolation {
    /// Interpolates `points` at `params` (`None`: `t_i = i`).
    ///
    /// # Errors
    /// [`GeomError`] for fewer than 2 points, a parameter count mismatch, parameters not
    /// strictly increasing or not finite, non-finite points, `t*` outside `(0, 1)`.
    pub fn try_new(
        points: Vec<DVec3>,
        params: Option<Vec<f64>>,
        modification: Option<Modification>,
    ) -> Result<CubicInterpolation, GeomError> {
        if points.len() < 2 {
            return Err(GeomError::TooFewPoints {
                min: 2,
                found: points.len(),
            });
        }
        check_finite(&points)?;
        let params = params.unwrap_or_else(|| (0..points.len()).map(|i| i as f64).collect());
        if params.len() != points.len() {
            return Err(GeomError::ParamCount {
                expected: points.len(),
                found: params.len(),
            });
        }
        for (index, &value) in params.iter().enumerate() {
            if !value.is_finite() {
                return Err(GeomError::NonFiniteParam { index, value });
            }
            if index > 0 && value <= params[index - 1] {
                return Err(GeomError::ParamsNotIncreasing {
                    index,
                    value,
                    previous: params[index - 1],
                });
            }
        }
        if let Some(m) = &modification {
            check_t_star(m.t_star)?;
            check_vector(m.v)?;
        }
        // In the bump-added reading each piece is a modified Bézier curve with the vector
        // `h v`: one that leaves f64 is an error here rather than in the lowering (which
        // builds those curves and can then not fail).
        if let Some(m) = modification.filter(|m| m.reading == Reading::BumpAdded) {
            for (i, pair) in params.windows(2).enumerate() {
                let hv = (pair[1] - pair[0]) * m.v;
                if let Some(value) = hv.to_array().into_iter().find(|c| !c.is_finite()) {
                    return Err(GeomError::DerivedNotFinite {
                        field: "v",
                        what: format!("the bump vector h·v of piece {i}"),
                        value,
                    });
                }
            }
        }
        let tangents = tangents(&points, &params);
        let pieces = (1..points.len())
            .map(|i| {
                let h = params[i] - params[i - 1];
                let (s0, s1) = (tangents[i - 1], tangents[i]);
                let (d0, d1) = match modification {
                    None => (DVec3::ZERO, DVec3::ZERO),
                    Some(m) => {
                        let a = (2.0 / m.t_star) * m.v;
                        match m.reading {
                            Reading::Paper => (a, a),
                            Reading::BumpAdded => (a, -(2.0 / (1.0 - m.t_star)) * m.v),
                        }
                    }
                };
                Bezier::new(vec![
                    points[i - 1],
                    points[i - 1] + (h / 3.0) * (s0 - d0),
                    points[i] - (h / 3.0) * (s1 - d1),
                    points[i],
                ])
            })
            .collect();
        Ok(CubicInterpolation {
            points,
            params,
            modification,
            tangents,
            pieces,
        })
    }

    /// The interpolated points.
    #[must_use]
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }

    /// Their parameters.
    #[must_use]
    pub fn params(&self) -> &[f64] {
        &self.params
    }

    /// The modification, if any.
    #[must_use]
    pub fn modification(&self) -> Option<Modification> {
        self.modification
    }

    /// The tangents `s_0..s_k` of the plain construction.
    #[must_use]
    pub fn tangents(&self) -> &[DVec3] {
        &self.tangents
    }

    /// The cubic pieces `Q_i` (`Q̃_i` when modified), each over its own `u ∈ [0, 1]`: their
    /// inner control points are the paper's `P_{i−2/3}`, `P_{i−1/3}`. In the "bump added"
    /// reading the curve is each piece plus `h S(u) v`.
    #[must_use]
    pub fn pieces(&self) -> &[Bezier] {
        &self.pieces
    }

    /// The piece index and its `u` for curve parameter `t` (ends extrapolate).
    fn locate(&self, t: f64) -> (usize, f64, f64) {
        let k = self.pieces.len();
        let i = self.params[1..k].partition_point(|&p| p <= t);
        let h = self.params[i + 1] - self.params[i];
        (i, (t - self.params[i]) / h, h)
    }

    /// The bump term's `(t*, v)` when the reading adds one.
    fn bump(&self) -> Option<(f64, DVec3)> {
        self.modification
            .filter(|m| m.reading == Reading::BumpAdded)
            .map(|m| (m.t_star, m.v))
    }
}

/// The tangents `s_i` of paper 002, §5.
fn tangents(points: &[DVec3], params: &[f64]) -> Vec<DVec3> {
    let k = points.len() - 1;
    let c: Vec<DVec3> = (0..k)
        .map(|i| (points[i + 1] - points[i]) / (params[i + 1] - params[i]))
        .collect();
    if k == 1 {
        return vec![c[0], c[0]];
    }
    let mut s = vec![DVec3::ZERO; k + 1];
    for i in 1..k {
        let alpha = (params[i] - params[i - 1]) / (params[i + 1] - params[i - 1]);
        s[i] = (1.0 - alpha) * c[i - 1] + alpha * c[i];
    }
    s[0] = 2.0 * c[0] - s[1];
    s[k] = 2.0 * c[k - 1] - s[k - 1];
    s
}

impl ParamCurve for CubicInterpolation {
    fn domain(&self) -> (f64, f64) {
        (self.params[0], self.params[self.params.len() - 1])
    }
    fn eval(&self, t: f64) -> DVec3 {
        let (i, u, h) = self.locate(t);
        let base = self.pieces[i].eval(u);
        match self.bump() {
            Some((ts, v)) => base + h * bump(u, ts) * v,
            None => base,
        }
    }
    fn eval_deriv(&self, t: f64) -> DVec3 {
        let (i, u, h) = self.locate(t);
        let d = self.pieces[i].eval_deriv(u)
            + self
                .bump()
                .map_or(DVec3::ZERO, |(ts, v)| h * bump_deriv(u, ts) * v);
        d / h
    }
    fn eval_second_deriv(&self, t: f64) -> DVec3 {
        let (i, u, h) = self.locate(t);
        let d = self.pieces[i].eval_second_deriv(u)
            + self
                .bump()
                .map_or(DVec3::ZERO, |(ts, v)| h * bump_second_deriv(u, ts) * v);
        d / (h * h)
    }
}

impl Lower for CubicInterpolation {
    fn lower(&self) -> Vec<BezierSegment> {
        let mut out = Vec::new();
        for (i, piece) in self.pieces.iter().enumerate() {
            let (t0, t1) = (self.params[i], self.params[i + 1]);
            let h = t1 - t0;
            match self.bump() {
                None => out.push(BezierSegment::polynomial(piece.clone(), t0, t1)),
                Some((ts, v)) => {
                    let m = ModifiedBezier::try_new(piece.clone(), ts, h * v)
                        .unwrap_or_else(|e| unreachable!("t* was checked: {e}"));
                    for s in m.lower() {
                        out.push(BezierSegment::polynomial(
                            s.bezier,
                            t0 + h * s.t0,
                            if s.t1 == 1.0 { t1 } else { t0 + h * s.t1 },
                        ));
                    }
                }
            }
        }
        out
    }
}

// The family: what the editor, the reports and the drawing need of every curve family.

impl Family for CubicInterpolation {
    const NAME: &'static str = "interpolation";

    /// The new point's parameter lies between its neighbours' in proportion to where
    /// `at` projects on the leg.
    fn with_point_on_polygon(&self, at: DVec3) -> Result<(CubicInterpolation, usize), GeomError> {
        let (points, leg, s) = crate::geom::structure::insert_on_polygon(self.points(), at);
        let mut params = self.params().to_vec();
        let t = params[leg] + s.clamp(0.05, 0.95) * (params[leg + 1] - params[leg]);
        params.insert(leg + 1, t);
        Ok((
            CubicInterpolation::try_new(points, Some(params), self.modification())?,
            leg + 1,
        ))
    }

    fn with_point_removed(&self, index: usize) -> Result<CubicInterpolation, GeomError> {
        let points = crate::geom::structure::without(self.points(), index, 2, Self::NAME)?;
        let mut params = self.params().to_vec();
        params.remove(index);
        CubicInterpolation::try_new(points, Some(params), self.modification())
    }

    /// `degree + 1` points (at least 2) interpolated by the plain cubic spline: always
    /// cubic, `degree` pieces.
    fn generated(
        degree: usize,
        point: &mut dyn FnMut() -> DVec3,
    ) -> Result<CubicInterpolation, GeomError> {
        let points = (0..=degree.max(1)).map(|_| point()).collect();
        CubicInterpolation::try_new(points, None, None)
    }

    fn control_points(&self) -> &[DVec3] {
        self.points()
    }

    fn with_control_points(&self, points: Vec<DVec3>) -> Result<CubicInterpolation, GeomError> {
        CubicInterpolation::try_new(points, Some(self.params.clone()), self.modification)
    }

    /// The curve leaves the hull of the interpolated points: it is bounded by its pieces.
    fn control_box(&self) -> Aabb {
        lowered_box(self)
    }

    fn is_planar(&self) -> bool {
        self.points.iter().all(|p| p.z == 0.0) && self.modification.is_none_or(|m| m.v.z == 0.0)
    }

    /// Tangents depend on points and parameters alike: the curve itself is named.
    fn derived_field(&self) -> &'static str {
        ""
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn example_points() -> Vec<DVec3> {
        [(0., 0.), (0., 6.), (6., 6.), (6., 0.)]
            .map(|(x, y)| DVec3::new(x, y, 0.0))
            .to_vec()
    }

    fn inner(c: &CubicInterpolation) -> Vec<(f64, f64)> {
        c.pieces()
            .iter()
            .flat_map(|p| [p.points()[1], p.points()[2]])
            .map(|p| (p.x, p.y))
            .collect()
    }

    #[test]
    fn paper_example_1_inner_points() {
        let c = CubicInterpolation::try_new(example_points(), Some(vec![0., 1., 2., 3.]), None)
            .unwrap();
        assert_eq!(
            inner(&c),
            vec![(-1., 3.), (-1., 5.), (1., 7.), (5., 7.), (7., 5.), (7., 3.)]
        );
    }

    #[test]
    fn paper_example_2_inner_points() {
        let m = Modification {
            t_star: 0.5,
            v: DVec3::new(0.0, 0.75, 0.0),
            reading: Reading::Paper,
        };
        let c = CubicInterpolation::try_new(example_points(), Some(vec![0., 1., 2., 3.]), Some(m))
            .unwrap();
        assert_eq!(
            inner(&c),
            vec![(-1., 2.), (-1., 6.), (1., 6.), (5., 8.), (7., 4.), (7., 4.)]
        );
    }

    #[test]
    fn bad_parameters_are_errors_naming_the_index() {
        let e = CubicInterpolation::try_new(example_points(), Some(vec![0., 1., 1., 3.]), None)
            .unwrap_err();
        assert_eq!(e.field(), "params[2]");
        let e = CubicInterpolation::try_new(vec![DVec3::ZERO], None, None).unwrap_err();
        assert_eq!(e, GeomError::TooFewPoints { min: 2, found: 1 });
        let e =
            CubicInterpolation::try_new(example_points(), Some(vec![0., 1.]), None).unwrap_err();
        assert_eq!(e.field(), "params");
    }
}
