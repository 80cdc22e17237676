//! The module's exceptions. Every error of the library crates becomes one of them,
//! carrying the command line's message and, where the error has one, the path of the
//! offending value (`points[2][0]`, `curves[1].knots`) as the attribute `path`.

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    splinescope,
    SplinescopeError,
    PyValueError,
    "Base class of the module's errors about values: a subclass of ValueError."
);
pyo3::create_exception!(
    splinescope,
    SceneError,
    SplinescopeError,
    "A scene or curve description that does not read: wrong type, missing field, a value the family refuses. `path` names the value."
);
pyo3::create_exception!(
    splinescope,
    CurveError,
    SplinescopeError,
    "An operation a curve refuses: a parameter outside its domain, a shape parameter out of range, a structural edit its family does not allow."
);
pyo3::create_exception!(
    splinescope,
    SolveError,
    SplinescopeError,
    "A solve request that cannot be applied (docs/solve-format.md). `path` names the value in the request."
);
pyo3::create_exception!(
    splinescope,
    ImageError,
    SplinescopeError,
    "An image that cannot be compared or read: sizes differ, a bad tolerance, a damaged PNG."
);
pyo3::create_exception!(
    splinescope,
    GpuError,
    PyRuntimeError,
    "The GPU path failed: no adapter (the message says how to install one), a device lost, an image size the device cannot hold."
);

/// An exception of type `E` with `message`, and `path` set (empty when there is none).
pub fn raise<E: pyo3::PyTypeInfo>(message: impl Into<String>, path: &str) -> PyErr {
    let message = message.into();
    let path = path.to_owned();
    Python::attach(|py| {
        let err = PyErr::from_type(py.get_type::<E>(), message);
        // Setting an attribute on a fresh exception object cannot fail in practice; if it
        // did, the exception still carries the message.
        let _ = err.value(py).setattr("path", path);
        err
    })
}

/// A scene or curve description error.
pub fn scene_error(e: &splinescope_scene::format::SceneError) -> PyErr {
    raise::<SceneError>(e.to_string(), &e.path)
}

/// A curve operation refused by the family.
pub fn geom_error(e: &splinescope_core::geom::GeomError) -> PyErr {
    raise::<CurveError>(e.to_string(), &e.field())
}

/// A GPU failure.
pub fn gpu_error(e: &splinescope_gpu::GpuError) -> PyErr {
    raise::<GpuError>(e.to_string(), "")
}

/// Registers the exceptions in the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("SplinescopeError", py.get_type::<SplinescopeError>())?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("CurveError", py.get_type::<CurveError>())?;
    m.add("SolveError", py.get_type::<SolveError>())?;
    m.add("ImageError", py.get_type::<ImageError>())?;
    m.add("GpuError", py.get_type::<GpuError>())?;
    Ok(())
}
