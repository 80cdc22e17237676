#![doc = include_str!("../README.md")]

mod arrays;
mod curve;
mod errors;
mod fit;
mod many;
mod regression;
mod scene;
mod widget;

use pyo3::prelude::*;

/// The native part of the `splinescope` package.
#[pymodule]
fn _splinescope(m: &Bound<'_, PyModule>) -> PyResult<()> {
    errors::register(m)?;
    m.add_class::<curve::PyCurve>()?;
    m.add_class::<scene::PyScene>()?;
    m.add_class::<widget::PyInteraction>()?;
    m.add_function(wrap_pyfunction!(many::eval_many, m)?)?;
    m.add_function(wrap_pyfunction!(many::join, m)?)?;
    m.add_function(wrap_pyfunction!(fit::fit_bezier, m)?)?;
    m.add_function(wrap_pyfunction!(fit::fit_bspline, m)?)?;
    m.add_function(wrap_pyfunction!(fit::fit_path, m)?)?;
    m.add_function(wrap_pyfunction!(many::intersections, m)?)?;
    m.add_function(wrap_pyfunction!(regression::compare_images, m)?)?;
    m.add_function(wrap_pyfunction!(many::rust_eval_seconds, m)?)?;
    m.add_function(wrap_pyfunction!(scene::stress_scene, m)?)?;
    m.add_function(wrap_pyfunction!(regression::read_png, m)?)?;
    m.add_function(wrap_pyfunction!(regression::write_png, m)?)?;
    m.add_function(wrap_pyfunction!(regression::png_bytes, m)?)?;
    m.add_function(wrap_pyfunction!(regression::compare_pictures, m)?)?;
    m.add_function(wrap_pyfunction!(regression::write_report, m)?)?;
    m.add(
        "FAMILY_NAMES",
        splinescope_core::geom::Curve::FAMILY_NAMES.to_vec(),
    )?;
    m.add(
        "SOLVE_METHODS",
        splinescope_scene::request::METHODS.to_vec(),
    )?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
