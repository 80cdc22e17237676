//! Fitting curves to points from Python: `fit_bezier`, `fit_bspline`.

use glam::DVec3;
use pyo3::prelude::*;

use splinescope_core::geom::Curve;
use splinescope_core::ops::{
    Fit, Params, fit_bezier as core_bezier, fit_bspline as core_bspline, fit_path as core_path,
};
use splinescope_scene::format::{SceneCurve, Style};

use crate::arrays;
use crate::curve::PyCurve;
use crate::errors::{CurveError, raise};

/// `(N, dim)` points from an array-like (dim 2 or 3).
fn points_of(obj: &Bound<'_, PyAny>) -> PyResult<(Vec<DVec3>, usize)> {
    let (pts, dim, _) = arrays::point_rows(obj, "points", false)?;
    Ok((pts, dim))
}

/// The parametrisation: `"chord"`, `"centripetal"` or an array of one parameter per point.
fn params_of(obj: &Bound<'_, PyAny>) -> PyResult<Params> {
    if let Ok(s) = obj.extract::<String>() {
        return match s.as_str() {
            "chord" => Ok(Params::Chord),
            "centripetal" => Ok(Params::Centripetal),
            other => Err(raise::<CurveError>(
                format!("params {other:?}: \"chord\", \"centripetal\" or an array of parameters"),
                "params",
            )),
        };
    }
    let a = arrays::float_array(obj, "params")?;
    let v = a
        .as_slice()
        .map_err(|e| raise::<CurveError>(format!("params: {e}"), "params"))?;
    Ok(Params::Given(v.to_vec()))
}

fn out<'py, C>(
    py: Python<'py>,
    fit: Fit<C>,
    curve: Curve,
    dim: usize,
) -> PyResult<(PyCurve, Bound<'py, PyAny>)> {
    let n = fit.residuals.len();
    let residuals = arrays::shaped(py, fit.residuals, &[n])?;
    Ok((
        PyCurve::new(
            SceneCurve {
                name: None,
                curve,
                style: Style::default_for(0),
            },
            Some(dim),
        ),
        residuals,
    ))
}

/// The least-squares Bézier curve of `degree` through `points`, and the residuals.
#[pyfunction]
#[pyo3(signature = (points, degree, params, weights=None))]
pub fn fit_bezier<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    degree: usize,
    params: &Bound<'py, PyAny>,
    weights: Option<Vec<f64>>,
) -> PyResult<(PyCurve, Bound<'py, PyAny>)> {
    let (pts, dim) = points_of(points)?;
    let params = params_of(params)?;
    let fit = py
        .detach(|| core_bezier(&pts, degree, &params, weights.as_deref()))
        .map_err(|e| raise::<CurveError>(e.to_string(), "points"))?;
    let curve = Curve::Bezier(fit.curve.clone());
    out(py, fit, curve, dim)
}

/// A B-spline fitted to `points` on `knots`, or with `smoothing`, and the residuals.
#[pyfunction]
#[pyo3(signature = (points, degree, knots, smoothing, params, weights=None))]
pub fn fit_bspline<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    degree: usize,
    knots: Option<Vec<f64>>,
    smoothing: Option<f64>,
    params: &Bound<'py, PyAny>,
    weights: Option<Vec<f64>>,
) -> PyResult<(PyCurve, Bound<'py, PyAny>)> {
    let (pts, dim) = points_of(points)?;
    let params = params_of(params)?;
    let fit = py
        .detach(|| {
            core_bspline(
                &pts,
                degree,
                knots.as_deref(),
                smoothing,
                &params,
                weights.as_deref(),
            )
        })
        .map_err(|e| raise::<CurveError>(e.to_string(), "points"))?;
    let curve = Curve::BSpline(fit.curve.clone());
    out(py, fit, curve, dim)
}

/// A cubic path through `points` within `tolerance`, corners sharper than `corner_angle`
/// degrees kept, and the residuals.
#[pyfunction]
#[pyo3(signature = (points, tolerance, corner_angle=30.0))]
pub fn fit_path<'py>(
    py: Python<'py>,
    points: &Bound<'py, PyAny>,
    tolerance: f64,
    corner_angle: f64,
) -> PyResult<(PyCurve, Bound<'py, PyAny>)> {
    let (pts, dim) = points_of(points)?;
    let fit = py
        .detach(|| core_path(&pts, tolerance, corner_angle))
        .map_err(|e| raise::<CurveError>(e.to_string(), "points"))?;
    let curve = Curve::Path(fit.curve.clone());
    out(py, fit, curve, dim)
}
