//! What image regression needs from Python (the pytest plugin, `splinescope.pytest_plugin`):
//! PNGs read within the limits and written atomically, a comparison with its diff and FLIP
//! pictures, and the same report page as `splinescope regress --report`.

use std::path::PathBuf;

use pyo3::prelude::*;
use splinescope_image::RgbaImage;
use splinescope_image::compare::{
    Comparison, ComparisonImages, Tolerance, compare_images as compare,
};
use splinescope_image::report::{ReportRow, write_report as write_page};

use crate::errors::{ImageError, raise};
use crate::scene::{array_image, image_array};

/// A PNG file as a `(H, W, 4)` uint8 array, read within the image limit.
#[pyfunction]
pub fn read_png(py: Python<'_>, path: PathBuf) -> PyResult<Bound<'_, PyAny>> {
    let image = py
        .detach(|| RgbaImage::read_png(&path))
        .map_err(|e| raise::<ImageError>(format!("{}: {e}", path.display()), "path"))?;
    image_array(py, image)
}

/// Writes a `(H, W, 4)` or `(H, W, 3)` uint8 array as a PNG file, atomically.
#[pyfunction]
pub fn write_png(py: Python<'_>, path: PathBuf, image: &Bound<'_, PyAny>) -> PyResult<()> {
    let image = array_image(image, "image")?;
    py.detach(|| image.write_png(&path))
        .map_err(|e| raise::<ImageError>(format!("{}: {e}", path.display()), "path"))
}

/// A `(H, W, 4)` or `(H, W, 3)` uint8 array encoded as a PNG file's bytes.
#[pyfunction]
pub fn png_bytes(py: Python<'_>, image: &Bound<'_, PyAny>) -> PyResult<Vec<u8>> {
    let image = array_image(image, "image")?;
    py.detach(|| image.png_bytes(std::path::Path::new("(in memory)")))
        .map_err(|e| raise::<ImageError>(e.to_string(), "image"))
}

/// Compares `actual` with `reference` as `splinescope diff` does: the figures (JSON), the
/// diff picture (differing pixels red on a grey reference) and FLIP's error map.
#[pyfunction]
#[pyo3(signature = (actual, reference, tolerance="channel=24,pixels=0.1%"))]
pub fn compare_pictures<'py>(
    py: Python<'py>,
    actual: &Bound<'py, PyAny>,
    reference: &Bound<'py, PyAny>,
    tolerance: &str,
) -> PyResult<(String, Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let (figures, pictures) = compare_arrays(py, actual, reference, tolerance)?;
    let json =
        serde_json::to_string(&figures).map_err(|e| raise::<ImageError>(e.to_string(), ""))?;
    Ok((
        json,
        image_array(py, pictures.diff)?,
        image_array(py, pictures.flip)?,
    ))
}

/// `actual` and `reference` (uint8 arrays) compared within `tolerance` (its text, refused
/// naming `tolerance`): the figures and the pictures, as `splinescope diff` makes them.
///
/// # Errors
/// A tolerance that does not parse, an array that is not an image, sizes that differ.
pub(crate) fn compare_arrays(
    py: Python<'_>,
    actual: &Bound<'_, PyAny>,
    reference: &Bound<'_, PyAny>,
    tolerance: &str,
) -> PyResult<(Comparison, ComparisonImages)> {
    let tolerance: Tolerance =
        tolerance
            .parse()
            .map_err(|e: splinescope_image::compare::ToleranceError| {
                raise::<ImageError>(e.to_string(), "tolerance")
            })?;
    let a = array_image(actual, "actual")?;
    let r = array_image(reference, "reference")?;
    py.detach(|| compare(&a, &r, &tolerance))
        .map_err(|e| raise::<ImageError>(e.to_string(), ""))
}

/// One report row as Python hands it: name, status, figures, message, and the reference,
/// actual, diff and FLIP images (each `None` or a uint8 array).
type Row<'py> = (
    String,
    String,
    String,
    String,
    [Option<Bound<'py, PyAny>>; 4],
);

/// Writes the regression report page (`splinescope regress --report`'s) into the existing
/// directory `dir`: the rows' images and `index.html`, headed by `summary`.
#[pyfunction]
pub fn write_report(
    py: Python<'_>,
    dir: PathBuf,
    summary: &str,
    rows: Vec<Row<'_>>,
) -> PyResult<()> {
    let mut images: Vec<[Option<RgbaImage>; 4]> = Vec::with_capacity(rows.len());
    for (name, _, _, _, pictures) in &rows {
        let mut four: [Option<RgbaImage>; 4] = Default::default();
        for (slot, picture) in four.iter_mut().zip(pictures) {
            if let Some(p) = picture {
                *slot = Some(array_image(p, name)?);
            }
        }
        images.push(four);
    }
    let report: Vec<ReportRow<'_>> = rows
        .iter()
        .zip(&images)
        .map(|((name, status, figures, message, _), four)| ReportRow {
            name: name.clone(),
            status: status.clone(),
            figures: figures.clone(),
            message: message.clone(),
            images: [
                four[0].as_ref(),
                four[1].as_ref(),
                four[2].as_ref(),
                four[3].as_ref(),
            ],
        })
        .collect();
    py.detach(|| write_page(&dir, summary, &report))
        .map_err(|e| raise::<ImageError>(format!("{}: {e}", dir.display()), "dir"))
}

/// Compares two images (`(H, W, 4)` or `(H, W, 3)` uint8 arrays, `actual` against
/// `reference`) per channel and by NVIDIA FLIP, as `splinescope diff` does: the figures
/// as JSON text (`matches`, `max_channel_diff`, `differing_pixels`, `differing_fraction`,
/// `flip_mean`, `flip_max`, `width`, `height`).
#[pyfunction]
#[pyo3(signature = (actual, reference, tolerance="channel=24,pixels=0.1%"))]
pub fn compare_images(
    py: Python<'_>,
    actual: &Bound<'_, PyAny>,
    reference: &Bound<'_, PyAny>,
    tolerance: &str,
) -> PyResult<String> {
    let (figures, _) = compare_arrays(py, actual, reference, tolerance)?;
    serde_json::to_string(&figures).map_err(|e| raise::<ImageError>(e.to_string(), ""))
}
