//! `_Curve`: one curve of any family, read from the scene format's curve object (so the
//! checks and messages are the command line's), evaluated on numpy arrays.

use glam::DVec3;
use numpy::PyUntypedArrayMethods;
use pyo3::prelude::*;
use rayon::prelude::*;
use serde_json::Value;

use splinescope_core::analysis::{AnalysisError, CurveAnalysis, Intersections};
use splinescope_core::geom::batch::CurveSampler;
use splinescope_core::geom::{Curve, Lower, ParamCurve, curvature};
use splinescope_scene::format::{SceneCurve, curve_from_value, curve_to_value};

use crate::arrays::{self, BLOCK, DETACH_ABOVE, PARALLEL_ABOVE, Params, fill, fill_into};
use crate::errors::{CurveError, SceneError, geom_error, raise, scene_error};

/// The name of parameter `k` of argument `what` in a message: `what` for a number,
/// `what[k]` for an array.
fn param_name(what: &str, scalar: bool, k: usize) -> String {
    if scalar {
        what.to_owned()
    } else {
        format!("{what}[{k}]")
    }
}

/// One curve: its family, fields, name and style, and its lowering (computed once).
#[pyclass(name = "_Curve", module = "splinescope._splinescope", frozen)]
pub struct PyCurve {
    pub(crate) curve: SceneCurve,
    pub(crate) sampler: CurveSampler,
    /// The first and second derivatives' samplers, made on first use.
    derivatives: std::sync::OnceLock<[CurveSampler; 2]>,
    /// The analysis (lowered segments in Bernstein form), made on first use.
    analysis: std::sync::OnceLock<CurveAnalysis>,
    /// Coordinates per point in results: 2 (planar input) or 3.
    pub(crate) dim: usize,
}

impl PyCurve {
    /// Wraps a checked curve.
    pub fn new(curve: SceneCurve, dim: Option<usize>) -> PyCurve {
        let dim = dim.unwrap_or(if curve.curve.is_planar() { 2 } else { 3 });
        PyCurve {
            sampler: CurveSampler::new(&curve.curve),
            derivatives: std::sync::OnceLock::new(),
            analysis: std::sync::OnceLock::new(),
            curve,
            dim,
        }
    }

    /// The curve's analysis.
    pub(crate) fn analysis(&self) -> &CurveAnalysis {
        self.analysis
            .get_or_init(|| CurveAnalysis::new(&self.curve.curve))
    }

    /// A parameter pair list `(s, t)` as a `(K, 2)` array.
    fn pairs<'py>(py: Python<'py>, found: &Intersections) -> PyResult<Bound<'py, PyAny>> {
        let flat: Vec<f64> = found.hits.iter().flat_map(|h| [h.s, h.t]).collect();
        arrays::shaped(py, flat, &[found.hits.len(), 2])
    }

    /// The sampler of the `order`-th derivative (1 or 2).
    fn derivative_sampler(&self, order: u32) -> &CurveSampler {
        let [d1, d2] = self
            .derivatives
            .get_or_init(|| [self.sampler.derivative(1), self.sampler.derivative(2)]);
        if order == 1 { d1 } else { d2 }
    }

    fn with_curve(&self, curve: Curve) -> PyCurve {
        PyCurve::new(
            SceneCurve {
                name: self.curve.name.clone(),
                curve,
                style: self.curve.style.clone(),
            },
            Some(self.dim),
        )
    }

    /// [`splinescope_core::ops::approx::approximate`] of this curve.
    fn approximate(
        &self,
        py: Python<'_>,
        tolerance: f64,
        target: splinescope_core::ops::Target,
    ) -> PyResult<(PyCurve, f64)> {
        let curve = &self.curve.curve;
        let closed = matches!(curve, Curve::Path(p) if p.is_closed());
        let made = py
            .detach(|| {
                splinescope_core::ops::approx::approximate(
                    &curve.lower(),
                    closed,
                    target,
                    tolerance,
                )
            })
            .map_err(|e| {
                let what = match e {
                    splinescope_core::ops::OpError::Geom(_) => "",
                    _ => "tolerance",
                };
                raise::<CurveError>(e.to_string(), what)
            })?;
        Ok((self.with_curve(Curve::Path(made.path)), made.error))
    }

    /// Refuses parameters outside the domain (or not numbers), naming the first.
    fn check_domain(&self, ts: &[f64], what: &str, scalar: bool) -> PyResult<()> {
        let (a, b) = self.curve.curve.domain();
        // A branch-free pass first (it vectorises); the position only on failure.
        let inside = |t: &f64| *t >= a && *t <= b;
        let all_inside = ts
            .chunks(1024)
            .all(|c| c.iter().fold(true, |ok, t| ok & inside(t)));
        let bad = if all_inside {
            None
        } else {
            ts.iter().position(|t| !inside(t))
        };
        match bad {
            None => Ok(()),
            Some(k) => {
                let name = param_name(what, scalar, k);
                Err(raise::<CurveError>(
                    format!(
                        "{name} = {} is outside the domain [{}, {}] of this {} curve",
                        ts[k],
                        a,
                        b,
                        self.curve.curve.family()
                    ),
                    &name,
                ))
            }
        }
    }

    /// Refuses a result that is not finite for parameters inside the domain (a rational
    /// curve whose weights or coordinates leave `f64` there), naming the first, as
    /// `splinescope eval` does.
    fn check_finite(
        &self,
        ts: &[f64],
        out: &[f64],
        per: usize,
        what: &str,
        scalar: bool,
    ) -> PyResult<()> {
        // Called once the evaluation found a value that is not finite (`fill` checks as
        // it writes): only its position is sought here.
        let Some(k) = out
            .iter()
            .position(|v| !v.is_finite())
            .map(|i| i / per.max(1))
        else {
            return Ok(());
        };
        let name = param_name("t", scalar, k);
        Err(raise::<CurveError>(
            format!(
                "{name} = {}: the {what} of this {} curve is not a finite number there (its coordinates or weights are too large for this computation in f64)",
                ts.get(k).copied().unwrap_or(f64::NAN),
                self.curve.curve.family()
            ),
            &name,
        ))
    }

    /// Refuses curvatures that left `f64` (infinite), naming the first parameter.
    fn check_curvature(&self, ts: &[f64], out: &[f64], scalar: bool) -> PyResult<()> {
        let Some(k) = out.iter().position(|k| k.is_infinite()) else {
            return Ok(());
        };
        let name = param_name("t", scalar, k);
        Err(raise::<CurveError>(
            format!(
                "{name} = {}: the curvature of this {} curve is not a finite number there (its derivatives or their ratio leave f64)",
                ts[k],
                self.curve.curve.family()
            ),
            &name,
        ))
    }

    /// `f(t)` for every parameter, as `(N, dim)` (or `(dim,)` for a scalar).
    fn map_params<'py>(
        &self,
        py: Python<'py>,
        (t, out): (&Bound<'py, PyAny>, Option<&Bound<'py, PyAny>>),
        what: &str,
        f: impl Fn(&[f64], &mut [DVec3]) + Sync,
    ) -> PyResult<Bound<'py, PyAny>> {
        let params = arrays::params(t, "t")?;
        let ts = params.as_slice()?;
        let scalar = matches!(params, Params::Scalar(_));
        self.check_domain(ts, "t", scalar)?;
        let dim = self.dim;
        let n = ts.len();
        if let Some(out) = out {
            let shape = match &params {
                Params::Scalar(_) => vec![dim],
                Params::Array(a) => vec![a.shape()[0], dim],
            };
            let array = arrays::out_array(out, &shape)?;
            arrays::write_out(&array, |values| {
                let finite = if n > DETACH_ABOVE {
                    py.detach(|| fill_into(ts, dim, &f, values))
                } else {
                    fill_into(ts, dim, &f, values)
                };
                if finite {
                    return Ok(());
                }
                self.check_finite(ts, values, dim, what, scalar)
            })?;
            return Ok(array.into_any());
        }
        let run = || fill(ts, dim, &f);
        let (out, finite) = if n > DETACH_ABOVE {
            py.detach(run)
        } else {
            run()
        };
        if !finite {
            self.check_finite(ts, &out, dim, what, scalar)?;
        }
        match params {
            Params::Scalar(_) => arrays::shaped(py, out, &[dim]),
            Params::Array(a) => {
                let shape = [a.shape()[0], dim];
                arrays::shaped(py, out, &shape)
            }
        }
    }
}

#[pymethods]
impl PyCurve {
    /// Reads a curve object of the scene format (`{"type": "bezier", "points": …}`) from
    /// JSON text; `dim` (2 or 3) fixes the coordinates of results (default: 2 for a
    /// planar curve).
    #[staticmethod]
    #[pyo3(signature = (text, dim=None))]
    fn from_json(text: &str, dim: Option<usize>) -> PyResult<PyCurve> {
        if let Some(d) = dim
            && d != 2
            && d != 3
        {
            return Err(raise::<CurveError>(
                format!("dim must be 2 or 3, not {d}"),
                "dim",
            ));
        }
        let value: Value = serde_json::from_str(text)
            .map_err(|e| raise::<SceneError>(format!("not JSON: {e}"), ""))?;
        let curve = curve_from_value(&value, 0).map_err(|e| scene_error(&e))?;
        Ok(PyCurve::new(curve, dim))
    }

    /// The curve object of the scene format, as JSON text.
    fn to_json(&self) -> String {
        curve_to_value(&self.curve).to_string()
    }

    /// The family's name in scene files (`"bezier"`, …).
    #[getter]
    fn family(&self) -> &'static str {
        self.curve.curve.family()
    }

    /// Coordinates per point in results (2 or 3).
    #[getter]
    fn dim(&self) -> usize {
        self.dim
    }

    /// The curve's name, if it has one.
    #[getter]
    fn name(&self) -> Option<String> {
        self.curve.name.clone()
    }

    /// The parameter domain `(a, b)`.
    fn domain(&self) -> (f64, f64) {
        self.curve.curve.domain()
    }

    /// One line describing the curve's structure ("degree 3", …).
    fn summary(&self) -> String {
        splinescope_present::Present::summary(&self.curve.curve)
    }

    /// The points the user places (control points, or the interpolated points), `(N, dim)`.
    fn control_points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        arrays::points_array(py, self.curve.curve.control_points(), self.dim)
    }

    /// `P(t)`: a number gives `(dim,)`, a 1-D array `(N, dim)`; with `out`, written into
    /// that array (C-contiguous float64 of that shape) and returned.
    #[pyo3(signature = (t, out=None))]
    fn eval<'py>(
        &self,
        py: Python<'py>,
        t: &Bound<'py, PyAny>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let sampler = &self.sampler;
        self.map_params(py, (t, out), "point", |ts, o| sampler.eval_into(ts, o))
    }

    /// The first or second derivative with respect to `t`.
    #[pyo3(signature = (t, order=1, out=None))]
    fn derivative<'py>(
        &self,
        py: Python<'py>,
        t: &Bound<'py, PyAny>,
        order: u32,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        match order {
            1 | 2 => {
                let d = self.derivative_sampler(order);
                let what = if order == 1 {
                    "first derivative"
                } else {
                    "second derivative"
                };
                self.map_params(py, (t, out), what, |ts, o| d.eval_into(ts, o))
            }
            _ => Err(raise::<CurveError>(
                format!("order must be 1 or 2, not {order}"),
                "order",
            )),
        }
    }

    /// The curvature `κ = |P′ × P″| / |P′|³` (NaN where `P′ = 0`): a number for a number,
    /// `(N,)` for an array. With `signed` (planar curves), negative where the curve turns
    /// right (`P′ × P″ < 0`).
    #[pyo3(signature = (t, out=None, signed=false))]
    fn curvature<'py>(
        &self,
        py: Python<'py>,
        t: &Bound<'py, PyAny>,
        out: Option<&Bound<'py, PyAny>>,
        signed: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        if signed && self.dim != 2 {
            return Err(raise::<CurveError>(
                "a signed curvature is defined for planar (2D) curves; this one is 3D".to_string(),
                "signed",
            ));
        }
        let params = arrays::params(t, "t")?;
        let ts = params.as_slice()?;
        let scalar = matches!(params, Params::Scalar(_));
        self.check_domain(ts, "t", scalar)?;
        let (d1, d2) = (self.derivative_sampler(1), self.derivative_sampler(2));
        let run = |out: &mut [f64]| {
            let block = |(ts, out): (&[f64], &mut [f64])| {
                let mut p1 = [DVec3::ZERO; BLOCK];
                let mut p2 = [DVec3::ZERO; BLOCK];
                d1.eval_into(ts, &mut p1[..ts.len()]);
                d2.eval_into(ts, &mut p2[..ts.len()]);
                for ((o, a), b) in out.iter_mut().zip(&p1).zip(&p2) {
                    // Derivatives that leave f64 give an infinite value, refused below;
                    // NaN only where P′ = 0 (the curvature is not defined there).
                    *o = if a.is_finite() && b.is_finite() {
                        let k = curvature(*a, *b).unwrap_or(f64::NAN);
                        if signed && a.x * b.y - a.y * b.x < 0.0 {
                            -k
                        } else {
                            k
                        }
                    } else {
                        f64::INFINITY
                    };
                }
            };
            if ts.len() > PARALLEL_ABOVE {
                ts.par_chunks(BLOCK)
                    .zip(out.par_chunks_mut(BLOCK))
                    .for_each(block);
            } else {
                ts.chunks(BLOCK).zip(out.chunks_mut(BLOCK)).for_each(block);
            }
        };
        let compute = |out: &mut [f64]| -> PyResult<()> {
            if ts.len() > DETACH_ABOVE {
                py.detach(|| run(out));
            } else {
                run(out);
            }
            self.check_curvature(ts, out, scalar)
        };
        if let Some(out) = out {
            // A number's curvature goes into a 0-d array, an array's into `(N,)`.
            let shape: Vec<usize> = if scalar { Vec::new() } else { vec![ts.len()] };
            let array = arrays::out_array(out, &shape)?;
            arrays::write_out(&array, compute)?;
            return Ok(array.into_any());
        }
        let mut values = vec![0.0; ts.len()];
        compute(&mut values)?;
        match params {
            Params::Scalar(_) => Ok(pyo3::types::PyFloat::new(py, values[0]).into_any()),
            Params::Array(_) => {
                let n = values.len();
                arrays::shaped(py, values, &[n])
            }
        }
    }

    /// `n ≥ 2` points at uniform parameters over the domain, ends included: `(n, dim)`.
    fn sample<'py>(&self, py: Python<'py>, n: usize) -> PyResult<Bound<'py, PyAny>> {
        check_sample_count(n, 1)?;
        let (a, b) = self.curve.curve.domain();
        let ts: Vec<f64> = (0..n)
            .map(|j| splinescope_core::geom::batch::uniform(a, b, j, n))
            .collect();
        let arr = numpy::IntoPyArray::into_pyarray(ts, py);
        self.eval(py, arr.as_any(), None)
    }

    /// The exact Bézier segments: a list of `(t0, t1, points (degree + 1, dim))`, and for
    /// a rational segment `(t0, t1, points, weights (degree + 1,))`.
    fn segments<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyAny>>> {
        self.curve
            .curve
            .lower()
            .iter()
            .map(|s| {
                let points = arrays::points_array(py, s.bezier.points(), self.dim)?;
                match &s.weights {
                    None => (s.t0, s.t1, points).into_pyobject(py).map(Bound::into_any),
                    Some(w) => {
                        let w = numpy::IntoPyArray::into_pyarray(w.clone(), py);
                        (s.t0, s.t1, points, w)
                            .into_pyobject(py)
                            .map(Bound::into_any)
                    }
                }
            })
            .collect()
    }

    /// The same data as `splinescope inspect` for this curve, as JSON text.
    fn inspect_json(&self) -> PyResult<String> {
        let report = splinescope_present::inspect::curve_report(
            0,
            self.curve.name.as_deref(),
            &self.curve.curve,
        )
        .map_err(|e| geom_error(&e))?;
        serde_json::to_string(&report).map_err(|e| raise::<CurveError>(e.to_string(), ""))
    }

    /// The curve with the knot `t` inserted (B-splines, standard NUBMP curves): the same
    /// curve with one more control point.
    fn insert_knot(&self, t: f64) -> PyResult<PyCurve> {
        let c = self
            .curve
            .curve
            .with_knot_inserted(t)
            .map_err(|e| geom_error(&e))?;
        Ok(self.with_curve(c))
    }

    /// The curve with a control point `at` inserted on the control polygon's nearest leg
    /// (Bézier families, interpolation), and the new point's index.
    fn insert_point(&self, at: &Bound<'_, PyAny>) -> PyResult<(PyCurve, usize)> {
        let p = point(at, "at", self.dim)?;
        let (c, i) = self
            .curve
            .curve
            .with_point_on_polygon(p)
            .map_err(|e| geom_error(&e))?;
        Ok((self.with_curve(c), i))
    }

    /// The curve with control point `index` moved to `to` (every other property kept;
    /// a point a path's segments share moves in both).
    fn move_point(&self, index: usize, to: &Bound<'_, PyAny>) -> PyResult<PyCurve> {
        let p = point(to, "to", self.dim)?;
        let c = self
            .curve
            .curve
            .with_control_point(index, p)
            .map_err(|e| geom_error(&e))?;
        Ok(self.with_curve(c))
    }

    /// The curve without control point `index`.
    fn remove_point(&self, index: usize) -> PyResult<PyCurve> {
        let c = self
            .curve
            .curve
            .with_point_removed(index)
            .map_err(|e| geom_error(&e))?;
        Ok(self.with_curve(c))
    }

    /// The same curve with its degree raised by `times` (Bézier curves and B-splines:
    /// the curve does not move).
    #[pyo3(signature = (times=1))]
    fn elevate(&self, times: usize) -> PyResult<PyCurve> {
        // The limit is checked on the degree asked for, before any work.
        let (limit, now) = match &self.curve.curve {
            Curve::Bezier(b) => (splinescope_io::limits::DEGREE, b.degree()),
            Curve::RationalBezier(b) => (splinescope_io::limits::DEGREE, b.degree()),
            Curve::BSpline(b) => (splinescope_io::limits::ORDER, b.order()),
            Curve::Nurbs(b) => (splinescope_io::limits::ORDER, b.order()),
            _ => (splinescope_io::limits::DEGREE, 0),
        };
        limit
            .check((now as u64).saturating_add(times as u64))
            .map_err(|e| {
                raise::<CurveError>(
                    format!("elevate(times={times}): the result would have {e}"),
                    "times",
                )
            })?;
        let mut c = self.curve.curve.clone();
        for _ in 0..times {
            c = match c {
                Curve::Bezier(b) => Curve::Bezier(b.elevate()),
                Curve::BSpline(b) => Curve::BSpline(b.elevate()),
                Curve::RationalBezier(b) => Curve::RationalBezier(b.elevate()),
                Curve::Nurbs(b) => Curve::Nurbs(b.elevate()),
                other => {
                    return Err(raise::<CurveError>(
                        format!(
                            "{} curves have no degree elevation here (Bézier, B-spline, rational Bézier and NURBS curves do)",
                            other.family()
                        ),
                        "",
                    ));
                }
            };
        }
        splinescope_io::limits::DEGREE
            .check(
                c.lower()
                    .iter()
                    .map(|s| s.bezier.degree() as u64)
                    .max()
                    .unwrap_or(0),
            )
            .map_err(|e| raise::<CurveError>(e.to_string(), "times"))?;
        Ok(self.with_curve(c))
    }

    /// The arc length from `t0` to `t1` (default: the domain's ends), within `accuracy`
    /// (absolute).
    #[pyo3(signature = (t0=None, t1=None, accuracy=splinescope_core::analysis::DEFAULT_ACCURACY))]
    fn length(
        &self,
        py: Python<'_>,
        t0: Option<f64>,
        t1: Option<f64>,
        accuracy: f64,
    ) -> PyResult<f64> {
        let c = self.analysis();
        let (a, b) = c.domain();
        py.detach(|| c.length(t0.unwrap_or(a), t1.unwrap_or(b), accuracy))
            .map(|l| l.value)
            .map_err(|e| analysis_error(&e))
    }

    /// The parameter at arc length `s` from the domain's start.
    #[pyo3(signature = (s, accuracy=splinescope_core::analysis::DEFAULT_ACCURACY))]
    fn parameter_at_length(&self, py: Python<'_>, s: f64, accuracy: f64) -> PyResult<f64> {
        let c = self.analysis();
        py.detach(|| c.parameter_at_length(s, accuracy))
            .map_err(|e| analysis_error(&e))
    }

    /// The point of the curve nearest to `p` — the global minimum of the distance, never
    /// a local one — as `(t, distance)`; for `(N, dim)` points, `(N,)` parameters and
    /// `(N,)` distances, computed on every core.
    fn nearest<'py>(&self, py: Python<'py>, p: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let (points, dim, single) = arrays::point_rows(p, "p", true)?;
        let rows = points.len();
        if let Some(i) = points.iter().position(|q| !q.is_finite()) {
            let what = if single {
                "p".to_owned()
            } else {
                format!("p[{i}]")
            };
            return Err(raise::<CurveError>(
                format!(
                    "{what} = {}: not a finite point",
                    arrays::row_text(&points[i].to_array()[..dim])
                ),
                "p",
            ));
        }
        let c = self.analysis();
        let found = py.detach(|| c.nearest_many(&points));
        let mut ts = Vec::with_capacity(rows);
        let mut ds = Vec::with_capacity(rows);
        for n in found {
            let n = n.map_err(|e| analysis_error(&e))?;
            ts.push(n.t);
            ds.push(n.distance);
        }
        if single {
            return Ok((ts[0], ds[0]).into_pyobject(py)?.into_any());
        }
        let t = arrays::shaped(py, ts, &[rows])?;
        let d = arrays::shaped(py, ds, &[rows])?;
        Ok((t, d).into_pyobject(py)?.into_any())
    }

    /// The curve as a path of cubic segments within `tolerance` (Hausdorff, a proven
    /// bound), with that bound.
    fn to_cubics(&self, py: Python<'_>, tolerance: f64) -> PyResult<(PyCurve, f64)> {
        self.approximate(py, tolerance, splinescope_core::ops::Target::Cubic)
    }

    /// The curve as a path of quadratic segments within `tolerance`, with the bound.
    fn to_quadratics(&self, py: Python<'_>, tolerance: f64) -> PyResult<(PyCurve, f64)> {
        self.approximate(py, tolerance, splinescope_core::ops::Target::Quadratic)
    }

    /// The curve split at `t` into the curves before and after it (a Bézier or rational
    /// Bézier curve into two of its family; others into two paths of their exact
    /// segments).
    fn split(&self, t: f64) -> PyResult<(PyCurve, PyCurve)> {
        let (l, r) = splinescope_core::ops::split(&self.curve.curve, t).map_err(|e| {
            raise::<CurveError>(
                format!("split at t = {}: {e}", splinescope_core::num::Num(t)),
                "t",
            )
        })?;
        Ok((self.with_curve(l), self.with_curve(r)))
    }

    /// The curve (B-spline or NURBS) with the knot `u` removed `times` times when it
    /// moves by at most `tolerance` (a proven bound), with that bound.
    fn remove_knot(&self, u: f64, times: usize, tolerance: f64) -> PyResult<(PyCurve, f64)> {
        let r = splinescope_core::ops::remove_knot(&self.curve.curve, u, times, tolerance)
            .map_err(|e| {
                let what = match e {
                    splinescope_core::ops::OpError::Tolerance(_)
                    | splinescope_core::ops::OpError::WouldMove { .. } => "tolerance",
                    splinescope_core::ops::OpError::NotAKnot { .. } => "u",
                    _ => "",
                };
                raise::<CurveError>(e.to_string(), what)
            })?;
        Ok((self.with_curve(r.curve), r.error))
    }

    /// The Bézier curve at the lowest degree within `tolerance` (a proven bound), its
    /// ends kept, with that bound.
    fn reduce_degree(&self, tolerance: f64) -> PyResult<(PyCurve, f64)> {
        let Curve::Bezier(b) = &self.curve.curve else {
            return Err(raise::<CurveError>(
                format!(
                    "reduce_degree is for Bézier curves, not {} curves (to_cubics approximates any curve)",
                    self.curve.curve.family()
                ),
                "",
            ));
        };
        let r = splinescope_core::ops::reduce_degree(b, tolerance)
            .map_err(|e| raise::<CurveError>(e.to_string(), "tolerance"))?;
        Ok((self.with_curve(Curve::Bezier(r.curve)), r.error))
    }

    /// The curve's offset by `d` (a list of paths of cubic segments) within `tolerance`
    /// of the true offset (a proven bound), with that bound and the number of cusps.
    /// `join` is "round", "miter" or "bevel"; `caps` None (an offset) or "butt",
    /// "round", "square" (a stroke outline).
    #[pyo3(signature = (d, tolerance, join, miter_limit, caps, trim))]
    #[allow(clippy::too_many_arguments)]
    fn offset(
        &self,
        py: Python<'_>,
        d: f64,
        tolerance: f64,
        join: &str,
        miter_limit: f64,
        caps: Option<&str>,
        trim: bool,
    ) -> PyResult<(Vec<PyCurve>, f64, usize)> {
        use splinescope_core::ops::{Cap, Join, OffsetOptions, OpError};
        let join = match join {
            "round" => Join::Round,
            "miter" => Join::Miter,
            "bevel" => Join::Bevel,
            other => {
                return Err(raise::<CurveError>(
                    format!("offset: join = {other:?}: one of \"round\", \"miter\", \"bevel\""),
                    "join",
                ));
            }
        };
        let caps = match caps {
            None => None,
            Some("butt") => Some(Cap::Butt),
            Some("round") => Some(Cap::Round),
            Some("square") => Some(Cap::Square),
            Some(other) => {
                return Err(raise::<CurveError>(
                    format!(
                        "offset: caps = {other:?}: one of \"butt\", \"round\", \"square\" (or None)"
                    ),
                    "caps",
                ));
            }
        };
        let options = OffsetOptions {
            join,
            miter_limit,
            caps,
            trim,
        };
        let curve = &self.curve.curve;
        let o = py
            .detach(|| splinescope_core::ops::offset(curve, d, tolerance, &options))
            .map_err(|e| {
                let what = match e {
                    OpError::Tolerance(_) | OpError::TooManyPieces { .. } => "tolerance",
                    OpError::Distance(_) => "d",
                    OpError::MiterLimit(_) => "miter_limit",
                    OpError::TrimWithCaps => "trim",
                    _ => "",
                };
                raise::<CurveError>(format!("offset: {e}"), what)
            })?;
        let paths = o
            .paths
            .into_iter()
            .map(|p| self.with_curve(Curve::Path(p)))
            .collect();
        Ok((paths, o.error, o.cusps))
    }

    /// The curve traced the other way.
    fn reverse(&self) -> PyResult<PyCurve> {
        let r = splinescope_core::ops::reverse(&self.curve.curve)
            .map_err(|e| raise::<CurveError>(e.to_string(), ""))?;
        Ok(self.with_curve(r))
    }

    /// The tight bounding box as `(2, dim)`: the smallest corner, then the largest.
    fn bbox<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let b = self.analysis().bounding_box();
        arrays::points_array(py, &[b.min, b.max], self.dim)
    }

    /// Where a coordinate's derivative vanishes, sorted: every axis, or `axis` alone.
    #[pyo3(signature = (axis=None))]
    fn extrema<'py>(&self, py: Python<'py>, axis: Option<usize>) -> PyResult<Bound<'py, PyAny>> {
        if let Some(k) = axis
            && k >= self.dim
        {
            return Err(raise::<CurveError>(
                format!("extrema: axis = {k} is not between 0 and {}", self.dim - 1),
                "axis",
            ));
        }
        let mut ts: Vec<f64> = self
            .analysis()
            .extrema()
            .into_iter()
            .filter(|e| axis.is_none_or(|k| e.axis == k))
            .map(|e| e.t)
            .collect();
        ts.sort_by(f64::total_cmp);
        ts.dedup();
        let n = ts.len();
        arrays::shaped(py, ts, &[n])
    }

    /// The inflections (2D).
    fn inflections<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let ts = self
            .analysis()
            .inflections()
            .map_err(|e| analysis_error(&e))?;
        let n = ts.len();
        arrays::shaped(py, ts, &[n])
    }

    /// The cusps (2D): where the velocity vanishes.
    fn cusps<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let ts = self.analysis().cusps().map_err(|e| analysis_error(&e))?;
        let n = ts.len();
        arrays::shaped(py, ts, &[n])
    }

    /// The local extrema of the curvature's magnitude (2D) as `(K, 4)`: `t`, `|κ|`, the
    /// signed `κ`, and `+1` for a maximum or `−1` for a minimum of `|κ|`.
    fn curvature_extrema<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let ex = self
            .analysis()
            .curvature_extrema()
            .map_err(|e| analysis_error(&e))?;
        let n = ex.len();
        let flat: Vec<f64> = ex
            .iter()
            .flat_map(|e| {
                let kind = match e.kind {
                    splinescope_core::analysis::ExtremumKind::Maximum => 1.0,
                    splinescope_core::analysis::ExtremumKind::Minimum => -1.0,
                };
                [e.t, e.curvature.abs(), e.curvature, kind]
            })
            .collect();
        arrays::shaped(py, flat, &[n, 4])
    }

    /// Continuity at every joint between lowered segments, then a closed curve's seam, as
    /// `(K, 4)`: `t`, the position gap, the angle between the tangents (radians) and the
    /// relative curvature jump (`inf` where a speed vanishes).
    fn joints<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let joints = self.analysis().joints().map_err(|e| analysis_error(&e))?;
        let n = joints.len();
        let flat: Vec<f64> = joints
            .iter()
            .flat_map(|j| [j.t, j.gap, j.angle, j.curvature_jump])
            .collect();
        arrays::shaped(py, flat, &[n, 4])
    }

    /// The signed area enclosed (2D; an open curve closed by its chord).
    fn signed_area(&self) -> PyResult<f64> {
        self.analysis()
            .signed_area()
            .map_err(|e| analysis_error(&e))
    }

    /// Whether the curve ends where it starts.
    fn is_closed(&self) -> bool {
        self.analysis().is_closed()
    }

    /// Where this curve and `other` meet (2D): the points' `(s, t)` as `(K, 2)`, sorted by
    /// `s`, their kinds (`"crossing"`/`"tangent"`), the overlaps `((s0, s1), (t0, t1))`,
    /// and the bounds on each point's parameter errors `(error_s, error_t)` as `(K, 2)`.
    /// The kinds and the errors are made only when asked for (`None` otherwise).
    #[pyo3(signature = (other, kinds = false, errors = false))]
    fn intersect<'py>(
        &self,
        py: Python<'py>,
        other: PyRef<'py, PyCurve>,
        kinds: bool,
        errors: bool,
    ) -> PyResult<Hits<'py>> {
        let (a, b) = (self.analysis(), other.analysis());
        let found = py
            .detach(|| a.intersect(b))
            .map_err(|e| analysis_error(&e))?;
        hits_out(py, &found, kinds, errors)
    }

    /// Where the curve meets itself (2D), as [`PyCurve::intersect`], `s < t`.
    #[pyo3(signature = (kinds = false, errors = false))]
    fn self_intersections<'py>(
        &self,
        py: Python<'py>,
        kinds: bool,
        errors: bool,
    ) -> PyResult<Hits<'py>> {
        let a = self.analysis();
        let found = py
            .detach(|| a.self_intersections())
            .map_err(|e| analysis_error(&e))?;
        hits_out(py, &found, kinds, errors)
    }

    /// Where the curve meets the line through `p` and `q` (2D): `(t, λ)` as `(K, 2)` (the
    /// point is `p + λ (q − p)`), the kinds, and the parameter ranges lying on the line.
    #[allow(clippy::type_complexity)]
    fn intersect_line<'py>(
        &self,
        py: Python<'py>,
        p: &Bound<'py, PyAny>,
        q: &Bound<'py, PyAny>,
    ) -> PyResult<(Bound<'py, PyAny>, Vec<&'static str>, Vec<(f64, f64)>)> {
        let (p, q) = (point(p, "p", self.dim)?, point(q, "q", self.dim)?);
        let found = self
            .analysis()
            .intersect_line(p, q)
            .map_err(|e| analysis_error(&e))?;
        let flat: Vec<f64> = found.hits.iter().flat_map(|h| [h.t, h.lambda]).collect();
        let kinds = found
            .hits
            .iter()
            .map(|h| splinescope_core::analysis::report::kind_name(h.kind))
            .collect();
        Ok((
            arrays::shaped(py, flat, &[found.hits.len(), 2])?,
            kinds,
            found.overlaps,
        ))
    }

    /// `splinescope analyze`'s report of this curve, as JSON text.
    #[pyo3(signature = (accuracy=splinescope_core::analysis::DEFAULT_ACCURACY, intersections=false))]
    fn analyze_json(&self, py: Python<'_>, accuracy: f64, intersections: bool) -> PyResult<String> {
        let c = self.analysis();
        let report = py
            .detach(|| {
                splinescope_core::analysis::report::curve_analysis_report(
                    0,
                    self.curve.curve.family(),
                    self.curve.name.as_deref(),
                    c,
                    accuracy,
                    intersections && c.is_planar(),
                )
            })
            .map_err(|e| analysis_error(&e))?;
        serde_json::to_string(&report).map_err(|e| raise::<CurveError>(e.to_string(), ""))
    }

    fn __repr__(&self) -> String {
        format!(
            "<{} curve, {}>",
            self.curve.curve.family(),
            splinescope_present::Present::summary(&self.curve.curve)
        )
    }
}

/// An analysis error as the module's `CurveError`, naming the argument.
pub(crate) fn analysis_error(e: &AnalysisError) -> PyErr {
    let path = match e {
        AnalysisError::Accuracy(_) => "accuracy",
        AnalysisError::OutsideDomain { what, .. } => what,
        AnalysisError::BeyondLength { .. } => "s",
        AnalysisError::Unresolved { .. } => "accuracy",
        AnalysisError::Overflow { .. } => "",
        AnalysisError::DegenerateLine { .. } | AnalysisError::ShortLine { .. } => "q",
        AnalysisError::NotPlanar { .. } | AnalysisError::TooLarge { .. } => "",
        AnalysisError::Crowded { .. } => "other",
        AnalysisError::NotFinitePoint { .. } => "p",
    };
    raise::<CurveError>(e.to_string(), path)
}

/// What `intersect` and `self_intersections` return: the `(K, 2)` parameter pairs, their
/// kinds (when asked for), the overlaps, and the `(K, 2)` error bounds (when asked for).
pub(crate) type Hits<'py> = (
    Bound<'py, PyAny>,
    Option<Vec<&'static str>>,
    Vec<((f64, f64), (f64, f64))>,
    Option<Bound<'py, PyAny>>,
);

/// [`Hits`] of `found`.
pub(crate) fn hits_out<'py>(
    py: Python<'py>,
    found: &Intersections,
    kinds: bool,
    errors: bool,
) -> PyResult<Hits<'py>> {
    let kinds = kinds.then(|| {
        found
            .hits
            .iter()
            .map(|h| splinescope_core::analysis::report::kind_name(h.kind))
            .collect()
    });
    let overlaps = found.overlaps.iter().map(|o| (o.s, o.t)).collect();
    let errors = if errors {
        let flat: Vec<f64> = found
            .hits
            .iter()
            .flat_map(|h| [h.error_s, h.error_t])
            .collect();
        Some(arrays::shaped(py, flat, &[found.hits.len(), 2])?)
    } else {
        None
    };
    Ok((PyCurve::pairs(py, found)?, kinds, overlaps, errors))
}

/// One point of `dim` coordinates.
pub(crate) fn point(obj: &Bound<'_, PyAny>, what: &str, dim: usize) -> PyResult<DVec3> {
    let a = arrays::float_array(obj, what)?;
    let v = a
        .as_slice()
        .map_err(|e| raise::<CurveError>(format!("{what}: {e}"), what))?;
    if a.shape() != [dim] {
        return Err(raise::<CurveError>(
            format!(
                "{what} must be a point of {dim} coordinates; got shape {}",
                arrays::shape_text(a.shape())
            ),
            what,
        ));
    }
    Ok(DVec3::new(v[0], v[1], if dim == 3 { v[2] } else { 0.0 }))
}

/// Checks a sample count `n` (at least 2) for `curves` curves against the command line's
/// sample limit, before anything is allocated.
pub(crate) fn check_sample_count(n: usize, curves: usize) -> PyResult<()> {
    if n < 2 {
        return Err(raise::<CurveError>(
            format!("n must be at least 2, not {n}"),
            "n",
        ));
    }
    let total = (n as u64).saturating_mul(curves.max(1) as u64);
    splinescope_io::limits::SAMPLES.check(total).map_err(|e| {
        let what = if curves > 1 {
            format!("{curves} curves × {n} samples")
        } else {
            format!("n = {n}")
        };
        raise::<CurveError>(format!("{what}: {e}"), "n")
    })
}
