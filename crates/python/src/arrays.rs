//! numpy arrays in and out: contiguous float64 input is read in place (no copy), any
//! other dtype or memory order is converted once by numpy; a wrong shape is refused with
//! a message naming the argument and the shape. Outputs are allocated once, as the
//! vector the work filled, handed to numpy without copying.

use glam::DVec3;
use numpy::{IntoPyArray, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyFloat;
use rayon::prelude::*;

use crate::errors::{CurveError, raise};

/// Past this many values, work runs with the GIL released (other Python threads run).
pub const DETACH_ABOVE: usize = 4096;

/// Parameters evaluated per block (one stack buffer of points, then written out).
pub const BLOCK: usize = 256;

/// Past this many parameters, a single curve's evaluation is spread over every core.
pub const PARALLEL_ABOVE: usize = 32_768;

/// Parameters: one number, or a 1-D array of them.
pub enum Params<'py> {
    /// A scalar: results have shape `(dim,)`.
    Scalar(f64),
    /// An array (read in place when it is contiguous float64): results `(N, dim)`.
    Array(PyReadonlyArrayDyn<'py, f64>),
}

impl Params<'_> {
    /// The parameters as a slice.
    pub fn as_slice(&self) -> PyResult<&[f64]> {
        match self {
            Params::Scalar(t) => Ok(std::slice::from_ref(t)),
            Params::Array(a) => a
                .as_slice()
                .map_err(|e| PyValueError::new_err(format!("parameters: {e}"))),
        }
    }
}

/// `obj` as a float64 array, converted once by `numpy.require` when it is not already a
/// contiguous, aligned float64 array (arrays rebuilt from bytes — by pickle, Dask, shared
/// memory — may be misaligned).
pub fn float_array<'py>(
    obj: &Bound<'py, PyAny>,
    what: &str,
) -> PyResult<PyReadonlyArrayDyn<'py, f64>> {
    if let Ok(a) = obj.cast::<PyArrayDyn<f64>>()
        && a.is_contiguous()
    {
        let read = a.readonly();
        if read.as_slice().is_ok() {
            return Ok(read);
        }
    }
    let py = obj.py();
    let numpy = py.import("numpy")?;
    // Numbers only: numpy would read "0.5" (or an array of strings, or `None` as NaN) as
    // a number; a string where a number goes is a mistake, said as one.
    let as_array = numpy.call_method1("asarray", (obj,)).map_err(|e| {
        PyValueError::new_err(format!(
            "{what} must be numbers (a float64 array or something numpy converts to one): {}",
            e.value(py)
        ))
    })?;
    let kind: String = as_array.getattr("dtype")?.getattr("kind")?.extract()?;
    if !matches!(kind.as_str(), "b" | "i" | "u" | "f") {
        let shown = obj
            .repr()
            .map_or_else(|_| "?".to_owned(), |r| r.to_string());
        let shown: String = if shown.chars().count() > 60 {
            shown.chars().take(57).chain("...".chars()).collect()
        } else {
            shown
        };
        return Err(pyo3::exceptions::PyTypeError::new_err(format!(
            "{what} must be numbers, not {} {shown}",
            obj.get_type()
                .name()
                .map_or_else(|_| "?".to_owned(), |n| n.to_string())
        )));
    }
    let float64 = numpy.getattr("float64")?;
    let converted = numpy
        .call_method1("require", (as_array, float64, "CA"))
        .map_err(|e| {
            PyValueError::new_err(format!(
                "{what} must be numbers (a float64 array or something numpy converts to one): {}",
                e.value(py)
            ))
        })?;
    let a = converted
        .cast_into::<PyArrayDyn<f64>>()
        .map_err(|_| PyValueError::new_err(format!("{what} must be an array of numbers")))?;
    Ok(a.readonly())
}

/// Parameters from a Python number or array-like (`what` names the argument).
pub fn params<'py>(obj: &Bound<'py, PyAny>, what: &str) -> PyResult<Params<'py>> {
    if obj.is_instance_of::<PyFloat>() || obj.is_instance_of::<pyo3::types::PyInt>() {
        // An int past f64's range raises OverflowError in the conversion: refused here
        // naming the argument instead.
        return obj.extract::<f64>().map(Params::Scalar).map_err(|_| {
            PyValueError::new_err(format!(
                "{what} = {}: not a number f64 can hold",
                obj.repr()
                    .map_or_else(|_| "?".to_owned(), |r| r.to_string())
            ))
        });
    }
    let a = float_array(obj, what)?;
    match a.shape() {
        [] => Ok(Params::Scalar(
            a.as_slice()
                .map_err(|e| PyValueError::new_err(e.to_string()))?[0],
        )),
        [_] => Ok(Params::Array(a)),
        shape => Err(PyValueError::new_err(format!(
            "{what} must be a number or a 1-D array of numbers; got an array of shape {}",
            shape_text(shape)
        ))),
    }
}

/// A point's coordinates as text: `(1, NaN)`.
pub fn row_text(row: &[f64]) -> String {
    let parts: Vec<String> = row
        .iter()
        .map(|x| splinescope_core::num::Num(*x).to_string())
        .collect();
    format!("({})", parts.join(", "))
}

/// `(3, 2)` as numpy writes a shape.
pub fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// Points as an `(N, dim)` array (one copy out of the `DVec3`s, none into numpy).
pub fn points_array<'py>(
    py: Python<'py>,
    pts: &[DVec3],
    dim: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let flat = flatten(pts, dim);
    shaped(py, flat, &[pts.len(), dim])
}

/// `pts` as `dim` coordinates each, in one vector.
pub fn flatten(pts: &[DVec3], dim: usize) -> Vec<f64> {
    if dim == 3 {
        return bytemuck::cast_slice::<DVec3, f64>(pts).to_vec();
    }
    let mut out = Vec::with_capacity(pts.len() * dim);
    for p in pts {
        out.extend_from_slice(&p.to_array()[..dim]);
    }
    out
}

/// A vector handed to numpy without copying, with the given shape.
pub fn shaped<'py>(
    py: Python<'py>,
    flat: Vec<f64>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyAny>> {
    // Made in its shape at once (a reshape would make a second array object).
    let a = numpy::ndarray::ArrayD::from_shape_vec(numpy::ndarray::IxDyn(shape), flat)
        .map_err(|e| PyValueError::new_err(format!("array of shape {shape:?}: {e}")))?;
    Ok(a.into_pyarray(py).into_any())
}

/// `out=` (numpy's convention): a C-contiguous, writeable float64 array of exactly
/// `shape`, to be written in place and returned; anything else is refused with a
/// [`crate::errors::CurveError`] naming `out` and what is wrong with it.
///
/// # Errors
/// Not a float64 array, another shape, not C-contiguous.
pub fn out_array<'py>(
    obj: &Bound<'py, PyAny>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let refuse = |why: String| crate::errors::raise::<crate::errors::CurveError>(why, "out");
    let Ok(a) = obj.cast::<PyArrayDyn<f64>>() else {
        let what = match obj.getattr("dtype") {
            Ok(dtype) => format!("an array of dtype {dtype}"),
            Err(_) => format!("{}", obj.get_type().name()?),
        };
        return Err(refuse(format!(
            "out must be a float64 numpy array, not {what}"
        )));
    };
    if a.shape() != shape {
        let tuple = |s: &[usize]| match s {
            [n] => format!("({n},)"),
            _ => format!(
                "({})",
                s.iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        };
        return Err(refuse(format!(
            "out has shape {}, expected {}",
            tuple(a.shape()),
            tuple(shape)
        )));
    }
    if !a.is_c_contiguous() {
        return Err(refuse(
            "out must be C-contiguous (numpy.ascontiguousarray makes one)".to_owned(),
        ));
    }
    Ok(a.clone())
}

/// Runs `write` on `out`'s elements (see [`out_array`]), refusing a read-only array or one
/// whose memory overlaps an argument being read.
///
/// # Errors
/// The array is read-only or overlaps another argument; or `write`'s error.
pub fn write_out<T>(
    out: &Bound<'_, PyArrayDyn<f64>>,
    write: impl FnOnce(&mut [f64]) -> PyResult<T>,
) -> PyResult<T> {
    let refuse = |why: &str| crate::errors::raise::<crate::errors::CurveError>(why, "out");
    let mut rw = out
        .try_readwrite()
        .map_err(|_| refuse("out is read-only, or shares memory with an argument being read"))?;
    let slice = rw
        .as_slice_mut()
        .map_err(|_| refuse("out must be C-contiguous and aligned"))?;
    write(slice)
}

/// `f` applied to the parameters block by block (spread over every core for many), its
/// points written as `dim` coordinates each into one vector; and whether every value
/// written is finite.
pub(crate) fn fill(
    ts: &[f64],
    dim: usize,
    f: &(impl Fn(&[f64], &mut [DVec3]) + Sync),
) -> (Vec<f64>, bool) {
    let mut out = vec![0.0; ts.len() * dim];
    let finite = fill_into(ts, dim, f, &mut out);
    (out, finite)
}

/// [`fill`] into `out` (`ts.len() × dim` values, row-major); whether every value written
/// is finite (checked block by block while the block is in cache, on the same threads).
pub(crate) fn fill_into(
    ts: &[f64],
    dim: usize,
    f: &(impl Fn(&[f64], &mut [DVec3]) + Sync),
    out: &mut [f64],
) -> bool {
    // One scratch block per thread, not one cleared per block.
    let block = |buf: &mut [DVec3; BLOCK], (ts, out): (&[f64], &mut [f64])| {
        let buf = &mut buf[..ts.len()];
        f(ts, buf);
        // Written per dimension, so each point is two or three stores (a copy of a slice
        // of run-time length is a call per point).
        match dim {
            2 => {
                for (o, p) in out.chunks_exact_mut(2).zip(buf.iter()) {
                    o[0] = p.x;
                    o[1] = p.y;
                }
            }
            3 => {
                for (o, p) in out.chunks_exact_mut(3).zip(buf.iter()) {
                    o[0] = p.x;
                    o[1] = p.y;
                    o[2] = p.z;
                }
            }
            _ => {
                for (o, p) in out.chunks_exact_mut(dim).zip(buf.iter()) {
                    o.copy_from_slice(&p.to_array()[..dim]);
                }
            }
        }
        // Branch-free, so it vectorises.
        out.iter().fold(true, |ok, v| ok & v.is_finite())
    };
    if ts.len() > PARALLEL_ABOVE {
        ts.par_chunks(BLOCK)
            .zip(out.par_chunks_mut(BLOCK * dim))
            .map_init(|| [DVec3::ZERO; BLOCK], |buf, pair| block(buf, pair))
            .reduce(|| true, |a, b| a & b)
    } else {
        let mut buf = [DVec3::ZERO; BLOCK];
        ts.chunks(BLOCK)
            .zip(out.chunks_mut(BLOCK * dim))
            .fold(true, |ok, pair| block(&mut buf, pair) & ok)
    }
}

/// Points from an array-like of shape `(N, 2)` or `(N, 3)` (or, with `single`, one point
/// of shape `(2,)` or `(3,)`): the points (`z = 0` for 2 coordinates), their dimension,
/// and whether one point was given. `what` names the argument in the refusal (a
/// `CurveError`).
pub fn point_rows(
    obj: &Bound<'_, PyAny>,
    what: &str,
    single: bool,
) -> PyResult<(Vec<DVec3>, usize, bool)> {
    let a = float_array(obj, what)?;
    let shape = a.shape().to_vec();
    let v = a
        .as_slice()
        .map_err(|e| raise::<CurveError>(format!("{what}: {e}"), what))?;
    let (dim, one) = match shape.as_slice() {
        [d] if single && (*d == 2 || *d == 3) => (*d, true),
        [_, d] if *d == 2 || *d == 3 => (*d, false),
        _ => {
            return Err(raise::<CurveError>(
                format!(
                    "{what} must be {}an array of shape (N, 2) or (N, 3); got shape {}",
                    if single {
                        "a point of 2 or 3 coordinates or "
                    } else {
                        ""
                    },
                    shape_text(&shape)
                ),
                what,
            ));
        }
    };
    let pts = v
        .chunks_exact(dim)
        .map(|r| DVec3::new(r[0], r[1], if dim == 3 { r[2] } else { 0.0 }))
        .collect();
    Ok((pts, dim, one))
}
