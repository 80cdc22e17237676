//! `_Scene`: a scene file's contents, its solve requests, and its picture from the GPU
//! path.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::{Arc, Mutex, PoisonError};

use numpy::{PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;

use splinescope_gpu::{BackendChoice, ContextOptions, GpuContext, Pipelines};
use splinescope_image::RgbaImage;
use splinescope_render::{RenderError, RenderRequest};
use splinescope_scene::format::shape::{CombCap, CombScale, ShapeOptions};
use splinescope_scene::format::{Scene, from_json_str, to_json_string};
use splinescope_scene::request::apply_text;

use crate::arrays;
use crate::curve::PyCurve;
use crate::errors::{GpuError, ImageError, SceneError, SolveError, gpu_error, raise, scene_error};

/// A scene: its curves, view and annotations, and the text it was read from (so that an
/// unedited save keeps the file's bytes and an edited one its form).
#[pyclass(name = "_Scene", module = "splinescope._splinescope", frozen)]
pub struct PyScene {
    scene: Scene,
    /// The text the scene was read from, when it was.
    original: Option<String>,
}

impl PyScene {
    /// A scene made here (read from no text).
    pub(crate) fn of(scene: Scene) -> PyScene {
        PyScene {
            scene,
            original: None,
        }
    }

    /// The scene.
    pub(crate) fn scene(&self) -> &Scene {
        &self.scene
    }
}

#[pymethods]
impl PyScene {
    /// Reads and checks a scene file.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<PyScene> {
        let (scene, text) = py
            .detach(|| Scene::read(&path))
            .map_err(|e| raise::<SceneError>(format!("{}: {e}", path.display()), &e.path))?;
        Ok(PyScene {
            scene,
            original: Some(text),
        })
    }

    /// Reads a file of another format (SVG) as a scene of path curves, with what the
    /// reader left out (one line each).
    #[staticmethod]
    #[pyo3(signature = (path, glyphs=None, text=None, variations=None, index=0))]
    fn import_file(
        py: Python<'_>,
        path: PathBuf,
        glyphs: Option<Vec<String>>,
        text: Option<String>,
        variations: Option<Vec<(String, f64)>>,
        index: u32,
    ) -> PyResult<(PyScene, Vec<String>)> {
        let options = splinescope_import::Options {
            font: splinescope_import::font::FontOptions {
                index,
                glyphs,
                text,
                variations: variations.unwrap_or_default(),
            },
        };
        let imported = py
            .detach(|| splinescope_import::load_with(&path, &options))
            .map_err(|e| raise::<SceneError>(e.to_string(), ""))?;
        Ok((
            PyScene {
                scene: imported.scene,
                original: None,
            },
            imported.warnings,
        ))
    }

    /// Reads and checks a scene from JSON text.
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<PyScene> {
        let scene = from_json_str(text).map_err(|e| scene_error(&e))?;
        Ok(PyScene {
            scene,
            original: Some(text.to_owned()),
        })
    }

    /// A scene of these curves (in order), with the default view and background.
    #[staticmethod]
    #[pyo3(signature = (curves, name=None))]
    fn from_curves(curves: Vec<PyRef<'_, PyCurve>>, name: Option<String>) -> PyResult<PyScene> {
        if let Some(c) = name.as_deref().and_then(|n| {
            n.chars()
                .find(|c| !splinescope_scene::text::displayable(*c))
        }) {
            return Err(raise::<SceneError>(
                format!(
                    "name: the character U+{:04X} is a control character or a noncharacter; names are text to display",
                    u32::from(c)
                ),
                "name",
            ));
        }
        Ok(PyScene {
            scene: Scene {
                name,
                unit: None,
                background: splinescope_encoding::Color::WHITE,
                samples_per_segment: None,
                view: splinescope_scene::format::ViewSpec::Auto,
                curves: curves.iter().map(|c| c.curve.clone()).collect(),
                annotations: Vec::new(),
            },
            original: None,
        })
    }

    /// The scene as JSON text: the text it was read from when unedited, that text's form
    /// (key order, number spelling) kept otherwise.
    fn to_json(&self) -> String {
        match &self.original {
            Some(text) => splinescope_scene::format::to_json_string_keeping(&self.scene, text),
            None => to_json_string(&self.scene),
        }
    }

    /// The scene as JSON text in the canonical form (every number in its shortest
    /// round-trip spelling, keys in the format's order): equal for equal scenes whatever
    /// form their files had.
    fn canonical_json(&self) -> String {
        to_json_string(&self.scene)
    }

    /// Writes the scene to `path` atomically (a temporary file renamed over it: a crash
    /// never leaves half a file), keeping the form of the text it was read from.
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let dxf = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("dxf"));
        let bytes = if dxf {
            splinescope_import::dxf::write(&self.scene)
                .map_err(|e| raise::<SceneError>(format!("{}: {e}", path.display()), ""))?
        } else {
            self.to_json().into_bytes()
        };
        py.detach(|| splinescope_io::files::write_atomic(&path, &bytes))
            .map_err(|e| raise::<SceneError>(format!("cannot write {}: {e}", path.display()), ""))
    }

    /// The scene's name, if it has one.
    #[getter]
    fn name(&self) -> Option<String> {
        self.scene.name.clone()
    }

    /// The unit of length the coordinates are in, when the file named one (STEP).
    #[getter]
    fn unit(&self) -> Option<String> {
        self.scene.unit.clone()
    }

    /// How many curves (without copying them).
    fn __len__(&self) -> usize {
        self.scene.curves.len()
    }

    /// Curve `index` (from 0, in range: the Python layer checks it), alone.
    fn curve_at(&self, index: usize) -> PyResult<PyCurve> {
        let planar = self.scene.curves.iter().all(|c| c.curve.is_planar());
        let dim = if planar { 2 } else { 3 };
        self.scene
            .curves
            .get(index)
            .map(|c| PyCurve::new(c.clone(), Some(dim)))
            .ok_or_else(|| pyo3::exceptions::PyIndexError::new_err(format!("curve index {index}")))
    }

    /// The curves, in order.
    #[getter]
    fn curves(&self) -> Vec<PyCurve> {
        let planar = self.scene.curves.iter().all(|c| c.curve.is_planar());
        let dim = if planar { 2 } else { 3 };
        self.scene
            .curves
            .iter()
            .map(|c| PyCurve::new(c.clone(), Some(dim)))
            .collect()
    }

    /// Applies a solve request (JSON text: one request object or an array of them, as
    /// `splinescope solve` reads, `docs/solve-format.md`): the new scene and the
    /// reports as JSON text. Nothing changes unless every request succeeds.
    fn solve(&self, py: Python<'_>, request: &str) -> PyResult<(PyScene, String)> {
        let outcome = py
            .detach(|| apply_text(&self.scene, request))
            .map_err(|e| raise::<SolveError>(e.to_string(), &e.path))?;
        let reports = serde_json::to_string(&outcome.reports)
            .map_err(|e| raise::<SolveError>(e.to_string(), ""))?;
        Ok((
            PyScene {
                scene: outcome.scene,
                original: self.original.clone(),
            },
            reports,
        ))
    }

    /// The scene drawn on the GPU (`width × height`, its own camera, the tolerance in
    /// pixels) as an `(height, width, 4)` uint8 RGBA array; the same image as
    /// `splinescope render` on the same adapter.
    /// `shape`: `(comb, comb_scale, comb_cap, inflections, curvature_extrema, intersections,
    /// joints)` — the
    /// curvature comb (its scale chosen for the view when `comb_scale` is `None`) and the
    /// markers, as `render --comb …` draws them.
    #[pyo3(signature = (width, height, tolerance_px=0.25, backend="auto", shape=(false, None, None, false, false, false, false)))]
    fn render<'py>(
        &self,
        py: Python<'py>,
        width: u32,
        height: u32,
        tolerance_px: f64,
        backend: &str,
        shape: ShapeArgs,
    ) -> PyResult<Bound<'py, PyAny>> {
        let shape = shape_options(shape)?;
        let image = self.image(py, (width, height), tolerance_px, backend, &shape)?;
        image_array(py, image)
    }

    /// The scene drawn as for `render`, encoded as a PNG file's bytes.
    #[pyo3(signature = (width, height, tolerance_px=0.25, backend="auto", shape=(false, None, None, false, false, false, false)))]
    fn png<'py>(
        &self,
        py: Python<'py>,
        width: u32,
        height: u32,
        tolerance_px: f64,
        backend: &str,
        shape: ShapeArgs,
    ) -> PyResult<Vec<u8>> {
        let shape = shape_options(shape)?;
        let image = self.image(py, (width, height), tolerance_px, backend, &shape)?;
        image
            .png_bytes(std::path::Path::new("(in memory)"))
            .map_err(|e| raise::<ImageError>(e.to_string(), ""))
    }

    /// Writes the scene as a figure, by `path`'s extension: `.svg` or `.pdf` (exact
    /// curves, pieces within `tolerance` points elsewhere) or `.png` (the GPU picture),
    /// with labels, legend, axes and grid as asked; atomically.
    #[pyo3(signature = (path, width=800, height=500, tolerance=0.01, labels=false, legend=false, axes=false, grid=false, backend="auto", shape=(false, None, None, false, false, false, false)))]
    #[allow(clippy::too_many_arguments)]
    fn export(
        &self,
        py: Python<'_>,
        path: PathBuf,
        width: u32,
        height: u32,
        tolerance: f64,
        labels: bool,
        legend: bool,
        axes: bool,
        grid: bool,
        backend: &str,
        shape: ShapeArgs,
    ) -> PyResult<()> {
        let shape = shape_options(shape)?;
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let mut opts = splinescope_figure::FigureOptions::new(width, height).with_text(
            splinescope_figure::TextOptions {
                labels,
                legend,
                axes,
                grid,
            },
        );
        opts.tolerance = tolerance;
        opts.shape = shape;
        let figure = |opts: &splinescope_figure::FigureOptions| {
            splinescope_figure::build(&self.scene, opts).map_err(|e| {
                use splinescope_figure::FigureError as F;
                let path = match &e {
                    F::Tolerance(_) | F::Budget { .. } | F::Precision { .. } => "tolerance",
                    F::Size { .. } => "width",
                    F::AxesIn3d => "axes",
                    _ => "",
                };
                raise::<ImageError>(e.to_string(), path)
            })
        };
        let bytes = match ext.as_deref() {
            Some("svg") => splinescope_figure::svg::write(&figure(&opts)?).into_bytes(),
            Some("pdf") => splinescope_figure::pdf::write(&figure(&opts)?),
            Some("png") => {
                // The guides and text only: the curves are the GPU's picture.
                opts.curves = false;
                let fig = figure(&opts)?;
                let mut image = self.image(py, (width, height), 0.25, backend, &shape)?;
                splinescope_figure::raster::draw_guides(
                    &fig,
                    &mut splinescope_figure::raster::Canvas {
                        data: &mut image.data,
                        width: image.width,
                        height: image.height,
                    },
                );
                image
                    .png_bytes(&path)
                    .map_err(|e| raise::<ImageError>(e.to_string(), ""))?
            }
            other => {
                return Err(raise::<ImageError>(
                    format!(
                        "{}: unknown figure format {} (expected .svg, .pdf or .png)",
                        path.display(),
                        other.map_or_else(|| "(no extension)".to_owned(), |e| format!(".{e}"))
                    ),
                    "path",
                ));
            }
        };
        py.detach(|| splinescope_io::files::write_atomic(&path, &bytes))
            .map_err(|e| {
                raise::<ImageError>(format!("cannot write {}: {e}", path.display()), "path")
            })
    }

    /// The scene as an SVG figure (`splinescope export`'s: exact curves, the scene's own
    /// view), labelled when `labels`: what a notebook shows.
    #[pyo3(signature = (width=640, height=400, labels=true))]
    fn svg(&self, width: u32, height: u32, labels: bool) -> PyResult<String> {
        let mut opts = splinescope_figure::FigureOptions::new(width, height);
        opts.labels = labels;
        let figure = splinescope_figure::build(&self.scene, &opts)
            .map_err(|e| raise::<ImageError>(e.to_string(), ""))?;
        Ok(splinescope_figure::svg::write(&figure))
    }

    fn __repr__(&self) -> String {
        format!(
            "<scene {}with {} curve(s)>",
            self.scene
                .name
                .as_ref()
                .map(|n| format!("{n:?} "))
                .unwrap_or_default(),
            self.scene.curves.len()
        )
    }
}

impl PyScene {
    fn image(
        &self,
        py: Python<'_>,
        (width, height): (u32, u32),
        tolerance_px: f64,
        backend: &str,
        shape: &ShapeOptions,
    ) -> PyResult<RgbaImage> {
        let choice = backend_choice(backend)?;
        let request = RenderRequest::new(width, height)
            .with_tolerance_px(tolerance_px)
            .with_shape(*shape);
        // The request's values first, each named as the Python argument.
        request.check().map_err(|e| {
            let argument = match &e {
                RenderError::Tolerance(_) => "tolerance_px",
                RenderError::EmptySize { name } => name,
                _ => "width",
            };
            raise::<GpuError>(e.to_string(), argument)
        })?;
        render_on(py, choice, &self.scene, &request)
    }
}

/// The backend Python names (`auto`, `vulkan`, `gl`, …), or a [`GpuError`] naming
/// `backend`.
pub(crate) fn backend_choice(backend: &str) -> PyResult<BackendChoice> {
    backend
        .parse()
        .map_err(|e: splinescope_gpu::context::UnknownBackend| {
            raise::<GpuError>(e.to_string(), "backend")
        })
}

/// `scene` drawn as `request` asks on the backend's device (opened once per process),
/// the GPU work without the GIL.
pub(crate) fn render_on(
    py: Python<'_>,
    choice: BackendChoice,
    scene: &Scene,
    request: &RenderRequest,
) -> PyResult<RgbaImage> {
    let gpu = device(py, choice)?;
    py.detach(|| {
        let (ctx, pipelines) = &*gpu;
        splinescope_render::render(ctx, pipelines, scene, request)
    })
    .map_err(|e| match e {
        RenderError::Gpu(e) => gpu_error(&e),
        other => raise::<GpuError>(other.to_string(), ""),
    })
}

/// The shape overlays as Python hands them: the comb on, its scale (`None`: chosen for
/// the view), its cap (a fraction of the view's height; `None`: no cap), and the three
/// marker switches (inflections, curvature extrema, intersections, joints).
type ShapeArgs = (bool, Option<f64>, Option<f64>, bool, bool, bool, bool);

/// The shape options of `ShapeArgs`, the scale and cap checked ([`SceneError`] naming
/// `comb` or `comb_cap`).
fn shape_options(
    (comb, scale, cap, inflections, curvature_extrema, intersections, joints): ShapeArgs,
) -> PyResult<ShapeOptions> {
    let comb_cap = match cap {
        None => CombCap::NONE,
        Some(f) => {
            CombCap::fraction(f).map_err(|e| raise::<SceneError>(e.to_string(), "comb_cap"))?
        }
    };
    let comb = match (comb, scale) {
        (false, _) => None,
        (true, None) => Some(CombScale::Auto),
        (true, Some(s)) => {
            Some(CombScale::fixed(s).map_err(|e| raise::<SceneError>(e.to_string(), "comb"))?)
        }
    };
    Ok(ShapeOptions {
        comb,
        comb_cap,
        inflections,
        curvature_extrema,
        intersections,
        joints,
    })
}

type Device = Arc<(GpuContext, Pipelines)>;

/// The device of each backend, opened on first use and kept for the process.
fn device(py: Python<'_>, choice: BackendChoice) -> PyResult<Device> {
    static DEVICES: Mutex<Option<HashMap<String, Device>>> = Mutex::new(None);
    let key = choice.to_string();
    if let Some(d) = DEVICES
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .as_ref()
        .and_then(|m| m.get(&key))
        && d.0.check_health().is_ok()
    {
        return Ok(Arc::clone(d));
    }
    let opened = py
        .detach(|| GpuContext::new(&ContextOptions::from_env(choice)))
        .map_err(|e| gpu_error(&e))?;
    let d = Arc::new(opened);
    DEVICES
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .get_or_insert_with(HashMap::new)
        .insert(key, Arc::clone(&d));
    Ok(d)
}

/// An image as an `(height, width, 4)` uint8 array (handed to numpy without copying).
pub(crate) fn image_array(py: Python<'_>, image: RgbaImage) -> PyResult<Bound<'_, PyAny>> {
    let (w, h) = (image.width as usize, image.height as usize);
    let a = numpy::IntoPyArray::into_pyarray(image.data, py);
    Ok(a.reshape(vec![h, w, 4])?.into_any())
}

/// An `(H, W, 4)` (or `(H, W, 3)`) uint8 array as an image.
pub(crate) fn array_image(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<RgbaImage> {
    let a = obj.cast::<PyArrayDyn<u8>>().map_err(|_| {
        raise::<ImageError>(
            format!("{what} must be a uint8 numpy array of shape (H, W, 4) or (H, W, 3)"),
            what,
        )
    })?;
    let shape = a.shape().to_vec();
    let ro = a.readonly();
    let data = match ro.as_slice() {
        Ok(s) => s.to_vec(),
        Err(_) => ro.as_array().iter().copied().collect(),
    };
    let (h, w, c) = match shape.as_slice() {
        [h, w, c @ (3 | 4)] if *h > 0 && *w > 0 => (*h, *w, *c),
        _ => {
            return Err(raise::<ImageError>(
                format!(
                    "{what} must have shape (H, W, 4) or (H, W, 3); got shape {}",
                    arrays::shape_text(&shape)
                ),
                what,
            ));
        }
    };
    let rgba = if c == 4 {
        data
    } else {
        data.chunks_exact(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect()
    };
    let too_big = || raise::<ImageError>(format!("{what} is too large"), what);
    Ok(RgbaImage {
        width: u32::try_from(w).map_err(|_| too_big())?,
        height: u32::try_from(h).map_err(|_| too_big())?,
        data: rgba,
    })
}

/// The stress generator's scene (`view --stress`, `bench --families`): `curves` random
/// curves of `family` and `degree`, each in a unit cell of a square grid, from `seed`.
#[pyfunction]
#[pyo3(signature = (curves, family="bezier", degree=3, seed=1))]
pub fn stress_scene(curves: usize, family: &str, degree: usize, seed: u64) -> PyResult<PyScene> {
    use splinescope_scene::format::generate::{StressFamily, StressOptions, random_bezier_scene};
    let family: StressFamily =
        family
            .parse()
            .map_err(|e: splinescope_scene::format::generate::UnknownFamily| {
                raise::<SceneError>(e.to_string(), "family")
            })?;
    if !(1..=31).contains(&degree) {
        return Err(raise::<SceneError>(
            format!("degree {degree}: must be 1 to 31"),
            "degree",
        ));
    }
    splinescope_io::limits::CURVES
        .check(curves as u64)
        .map_err(|e| raise::<SceneError>(e.to_string(), "curves"))?;
    Ok(PyScene {
        scene: random_bezier_scene(StressOptions {
            curves,
            degree,
            seed,
            family,
            ..StressOptions::default()
        }),
        original: None,
    })
}
