//! A scene drawn offscreen: its encoding ([`crate::scene::encoding::Encoding`]) handed to
//! the GPU layer, seen by the scene's own camera for the image size (or the one given) —
//! the GPU layer neither reads scenes nor chooses cameras.

use glam::DVec2;

use crate::camera::Camera;
use crate::gpu::capture::render_with;
use crate::gpu::context::GpuContext;
use crate::gpu::{GpuError, Pipelines};
use crate::image::RgbaImage;
use crate::scene::Scene;
use crate::scene::encoding::encode;
use crate::scene::shape::{ShapeOptions, encode_shaped};

/// Draws `scene` into a `width × height` image with `camera` (the scene's own view for
/// that size when `None`), at the default tolerance.
///
/// # Errors
/// As [`crate::gpu::capture::render`].
pub fn render_scene(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    scene: &Scene,
    camera: Option<Camera>,
    width: u32,
    height: u32,
) -> Result<RgbaImage, GpuError> {
    render_scene_with(
        ctx,
        pipelines,
        scene,
        camera,
        (width, height),
        crate::gpu::adaptive::DEFAULT_TOLERANCE_PX,
    )
}

/// [`render_scene`] for a tolerance of `tolerance_px` pixels.
///
/// # Errors
/// As [`crate::gpu::capture::render`].
pub fn render_scene_with(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    scene: &Scene,
    camera: Option<Camera>,
    (width, height): (u32, u32),
    tolerance_px: f64,
) -> Result<RgbaImage, GpuError> {
    let camera =
        camera.unwrap_or_else(|| scene.camera(DVec2::new(f64::from(width), f64::from(height))));
    render_with(
        ctx,
        pipelines,
        &encode(scene),
        &camera,
        (width, height),
        tolerance_px,
    )
}

/// [`render_scene_with`] with the shape overlays of `shape`: the curvature comb (its
/// scale resolved for the view when automatic) drawn by the GPU, and the markers as
/// points over the curves.
///
/// # Errors
/// As [`crate::gpu::capture::render`].
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

/// Draws `opts`' guides and text (labels, legend, axes, grid) over `image`, a render of
/// `scene` with the scene's camera at the image's size ([`splinescope_figure::raster::annotate`]).
///
/// # Errors
/// [`splinescope_figure::FigureError`] (axes or a grid asked of a 3D view).
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

pub use splinescope_figure::TextOptions;
