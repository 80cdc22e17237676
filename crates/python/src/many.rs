//! Functions over many curves at once: `eval_many` (every curve at its own parameters, on
//! every core), `intersections` (every intersecting pair) and the timing hook the peer
//! benchmark reads.

use glam::DVec3;
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PySlice};

use splinescope_core::analysis::CurveAnalysis;
use splinescope_core::geom::batch::{CurveSampler, sample_many};

use crate::arrays;
use crate::arrays::fill;
use crate::curve::{PyCurve, analysis_error, check_sample_count};
use crate::errors::{CurveError, raise};

/// Every intersecting pair among `curves` (2D), on every core, and the groups of copies:
/// a list of dicts — `{"i", "j", "params": (K, 2) array of (s, t), "kinds", "overlaps"}`
/// (and `"errors"`, `(K, 2)` bounds on the parameters' errors, when `errors` is true) for
/// each pair that meets, `i < j`, then `{"copies": [indices], "interval": (t0, t1)}` for
/// each group of curves that coincide entirely (the same segments over the same domain),
/// reported once rather than as pairs.
#[pyfunction]
#[pyo3(signature = (curves, errors = false))]
pub fn intersections<'py>(
    py: Python<'py>,
    curves: Vec<PyRef<'py, PyCurve>>,
    errors: bool,
) -> PyResult<Bound<'py, PyList>> {
    let analyses: Vec<&CurveAnalysis> = curves.iter().map(|c| c.analysis()).collect();
    if let Some(k) = analyses.iter().position(|c| !c.is_planar()) {
        return Err(raise::<CurveError>(
            format!(
                "curves[{k}] is not planar (it leaves z = 0); intersections are computed for planar curves"
            ),
            &format!("curves[{k}]"),
        ));
    }
    let all = py
        .detach(|| splinescope_core::analysis::all_intersections(&analyses))
        .map_err(|e| analysis_error(&e))?;
    let out = PyList::empty(py);
    let (i, j, params, kinds, overlaps) = (
        intern!(py, "i"),
        intern!(py, "j"),
        intern!(py, "params"),
        intern!(py, "kinds"),
        intern!(py, "overlaps"),
    );
    let (crossing, tangent) = (intern!(py, "crossing"), intern!(py, "tangent"));
    // Every pair's (s, t) in one (H, 2) array; each pair's params a view of its rows.
    let flat: Vec<f64> = all
        .pairs
        .iter()
        .flat_map(|p| p.found.hits.iter().flat_map(|h| [h.s, h.t]))
        .collect();
    let total = flat.len() / 2;
    let big = arrays::shaped(py, flat, &[total, 2])?;
    let big_errors = if errors {
        let flat: Vec<f64> = all
            .pairs
            .iter()
            .flat_map(|p| p.found.hits.iter().flat_map(|h| [h.error_s, h.error_t]))
            .collect();
        Some(arrays::shaped(py, flat, &[total, 2])?)
    } else {
        None
    };
    let mut row = 0;
    for p in &all.pairs {
        let k = p.found.hits.len();
        let rows = PySlice::new(py, row as isize, (row + k) as isize, 1);
        row += k;
        let d = PyDict::new(py);
        d.set_item(i, p.i)?;
        d.set_item(j, p.j)?;
        if let Some(e) = &big_errors {
            d.set_item(intern!(py, "errors"), e.get_item(&rows)?)?;
        }
        d.set_item(params, big.get_item(rows)?)?;
        let names = PyList::empty(py);
        for h in &p.found.hits {
            names.append(if h.kind == splinescope_core::analysis::HitKind::Crossing {
                crossing
            } else {
                tangent
            })?;
        }
        d.set_item(kinds, names)?;
        let o: Vec<((f64, f64), (f64, f64))> =
            p.found.overlaps.iter().map(|o| (o.s, o.t)).collect();
        d.set_item(overlaps, o)?;
        out.append(d)?;
    }
    for g in &all.copies {
        let d = PyDict::new(py);
        d.set_item(intern!(py, "copies"), &g.curves)?;
        d.set_item(intern!(py, "interval"), g.domain)?;
        out.append(d)?;
    }
    Ok(out)
}

/// `curves` joined end to end into one path of their exact segments.
#[pyfunction]
#[pyo3(signature = (curves, closed=false))]
pub fn join<'py>(curves: Vec<PyRef<'py, PyCurve>>, closed: bool) -> PyResult<PyCurve> {
    let all: Vec<splinescope_core::geom::Curve> =
        curves.iter().map(|c| c.curve.curve.clone()).collect();
    let path = splinescope_core::ops::join(&all, closed)
        .map_err(|e| raise::<CurveError>(format!("join: {e}"), "curves"))?;
    let dim = curves.iter().map(|c| c.dim).max().unwrap_or(2);
    Ok(PyCurve::new(
        splinescope_scene::format::SceneCurve {
            name: None,
            curve: splinescope_core::geom::Curve::Path(path),
            style: curves.first().map_or_else(
                || splinescope_scene::format::Style::default_for(0),
                |c| c.curve.style.clone(),
            ),
        },
        Some(dim),
    ))
}

/// `n ≥ 2` uniform samples of every curve, `(C, n, dim)`, spread over every core.
#[pyfunction]
pub fn eval_many<'py>(
    py: Python<'py>,
    curves: Vec<PyRef<'py, PyCurve>>,
    n: usize,
) -> PyResult<Bound<'py, PyAny>> {
    check_sample_count(n, curves.len())?;
    let dim = curves.first().map_or(2, |c| c.dim);
    if let Some(i) = curves.iter().position(|c| c.dim != dim) {
        return Err(raise::<CurveError>(
            format!(
                "curves[{i}] has {} coordinates per point and curves[0] has {dim}: eval_many needs one dimension",
                curves[i].dim
            ),
            &format!("curves[{i}]"),
        ));
    }
    let samplers: Vec<CurveSampler> = curves.iter().map(|c| c.sampler.clone()).collect();
    let count = curves.len();
    let total = count * n;
    let out = py.detach(|| {
        let mut pts = vec![DVec3::ZERO; total];
        sample_many(&samplers, n, &mut pts);
        arrays::flatten(&pts, dim)
    });
    if let Some(k) = out.iter().position(|v| !v.is_finite()) {
        let (i, j) = (k / dim / n, k / dim % n);
        return Err(raise::<CurveError>(
            format!(
                "curves[{i}]: sample {j} of {n} is not a finite number (its coordinates or weights are too large for this computation in f64)"
            ),
            &format!("curves[{i}]"),
        ));
    }
    arrays::shaped(py, out, &[count, n, dim])
}

/// Seconds per call of the same evaluation made in Rust, without Python: `t` (a 1-D
/// float64 array) evaluated `repeats` times into a fresh vector of `dim` coordinates
/// per point, on the threads the module uses. The benchmark compares the binding with
/// it to measure its overhead.
#[pyfunction]
pub fn rust_eval_seconds(
    py: Python<'_>,
    curve: PyRef<'_, PyCurve>,
    t: &Bound<'_, PyAny>,
    repeats: u32,
) -> PyResult<f64> {
    let params = arrays::params(t, "t")?;
    let ts = params.as_slice()?;
    let sampler = &curve.sampler;
    let dim = curve.dim;
    Ok(py.detach(|| {
        let started = std::time::Instant::now();
        for _ in 0..repeats.max(1) {
            std::hint::black_box(fill(ts, dim, &|ts, out| sampler.eval_into(ts, out)));
        }
        started.elapsed().as_secs_f64() / f64::from(repeats.max(1))
    }))
}
