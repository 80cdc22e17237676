//! The old names of drawing a scene offscreen, kept for one release: use
//! [`splinescope_render::render`] with a [`splinescope_render::RenderRequest`], which every caller
//! (the command line, the Python module, the pytest plugin) now goes through
//! (`CHANGELOG.md`).
#![allow(deprecated)]

use glam::DVec2;

use splinescope_encoding::camera::Camera;
use splinescope_gpu::capture::render_with;
use splinescope_gpu::context::GpuContext;
use splinescope_gpu::{GpuError, Pipelines};
use splinescope_image::RgbaImage;
use splinescope_scene::format::Scene;
use splinescope_scene::format::shape::{ShapeOptions, encode_shaped};

pub use splinescope_figure::TextOptions;

/// Draws `scene` into a `width × height` image with `camera` (the scene's own view for
/// that size when `None`), at the default tolerance.
///
/// # Errors
/// The GPU's failure.
#[deprecated(note = "use splinescope_render::render with RenderRequest::new(width, height)")]
pub fn render_scene(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    scene: &Scene,
    camera: Option<Camera>,
    width: u32,
    height: u32,
) -> Result<RgbaImage, GpuError> {
    render_scene_shaped(
        ctx,
        pipelines,
        scene,
        camera,
        (width, height),
        splinescope_gpu::adaptive::DEFAULT_TOLERANCE_PX,
        &ShapeOptions::default(),
    )
}

/// [`render_scene`] for a tolerance of `tolerance_px` pixels.
///
/// # Errors
/// The GPU's failure.
#[deprecated(note = "use splinescope_render::render with RenderRequest::with_tolerance_px")]
pub fn render_scene_with(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    scene: &Scene,
    camera: Option<Camera>,
    (width, height): (u32, u32),
    tolerance_px: f64,
) -> Result<RgbaImage, GpuError> {
    render_scene_shaped(
        ctx,
        pipelines,
        scene,
        camera,
        (width, height),
        tolerance_px,
        &ShapeOptions::default(),
    )
}

/// [`render_scene_with`] with the shape overlays of `shape`.
///
/// # Errors
/// The GPU's failure.
#[deprecated(note = "use splinescope_render::render with RenderRequest::with_shape")]
pub fn render_scene_shaped(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    scene: &Scene,
    camera: Option<Camera>,
    (width, height): (u32, u32),
    tolerance_px: f64,
    shape: &ShapeOptions,
) -> Result<RgbaImage, GpuError> {
    let viewport = DVec2::new(f64::from(width), f64::from(height));
    let camera = camera.unwrap_or_else(|| scene.camera(viewport));
    let encoding = encode_shaped(scene, camera.view_height(viewport), shape);
    render_with(
        ctx,
        pipelines,
        &encoding,
        &camera,
        (width, height),
        tolerance_px,
    )
}

/// Draws `opts`' guides and text over `image`, a render of `scene` with the scene's
/// camera at the image's size.
///
/// # Errors
/// [`splinescope_figure::FigureError`] (axes or a grid asked of a 3D view).
#[deprecated(note = "use splinescope_render::render with RenderRequest::with_text")]
pub fn annotate(
    image: &mut RgbaImage,
    scene: &Scene,
    opts: &TextOptions,
) -> Result<(), splinescope_figure::FigureError> {
    annotate_shaped(image, scene, opts, &ShapeOptions::default())
}

/// [`annotate`] whose legend also lists the markers `shape` shows.
///
/// # Errors
/// As [`annotate`].
#[deprecated(note = "use splinescope_render::render with RenderRequest::with_text and with_shape")]
pub fn annotate_shaped(
    image: &mut RgbaImage,
    scene: &Scene,
    opts: &TextOptions,
    shape: &ShapeOptions,
) -> Result<(), splinescope_figure::FigureError> {
    splinescope_figure::raster::annotate_shaped(
        &mut splinescope_figure::raster::Canvas {
            data: &mut image.data,
            width: image.width,
            height: image.height,
        },
        scene,
        *opts,
        shape,
    )
}
