#![doc = include_str!("../README.md")]
#![forbid(unsafe_code)]

use glam::DVec2;
use thiserror::Error;

use splinescope_encoding::camera::Camera;
use splinescope_encoding::draw::Switches;
use splinescope_figure::raster::{Canvas, annotate_with};
use splinescope_figure::{FigureError, FigureOptions, TextOptions};
use splinescope_gpu::adaptive::{DEFAULT_TOLERANCE_PX, ToleranceError, check_tolerance};
use splinescope_gpu::capture::render_with;
use splinescope_gpu::{GpuContext, GpuError, Pipelines};
use splinescope_image::RgbaImage;
use splinescope_io::limits::{IMAGE_PIXELS, LimitError};
use splinescope_scene::format::Scene;
use splinescope_scene::format::shape::{ShapeOptions, encode_shaped_with};

/// What to draw: the image's size, the tolerance, the camera, the shape overlays and the
/// text. [`RenderRequest::new`] gives the defaults every caller shares (the scene's own
/// view, [`DEFAULT_TOLERANCE_PX`], no overlays, no text); the `with_` methods set the rest.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderRequest {
    /// The image's width in pixels.
    pub width: u32,
    /// The image's height in pixels.
    pub height: u32,
    /// How far the drawn polyline may stray from the curve, in pixels (at least
    /// `splinescope_gpu::adaptive::MIN_TOLERANCE_PX`).
    pub tolerance_px: f64,
    /// The camera; `None`: the scene's own view for this size (`Scene::camera`).
    pub camera: Option<Camera>,
    /// Which of the curves' overlays are drawn: control polygons and points as their
    /// styles ask ([`Switches::ALL`], the default), or fewer (the window's `P` and `C`).
    pub switches: Switches,
    /// Curvature combs and markers.
    pub shape: ShapeOptions,
    /// Labels, legend, axes and grid, written over the picture.
    pub text: TextOptions,
}

impl RenderRequest {
    /// A `width × height` picture of the scene as its own view shows it, at the default
    /// tolerance, with no overlays and no text.
    #[must_use]
    pub fn new(width: u32, height: u32) -> RenderRequest {
        RenderRequest {
            width,
            height,
            tolerance_px: DEFAULT_TOLERANCE_PX,
            camera: None,
            switches: Switches::ALL,
            shape: ShapeOptions::default(),
            text: TextOptions::default(),
        }
    }

    /// The request with a tolerance of `tolerance_px` pixels.
    #[must_use]
    pub fn with_tolerance_px(self, tolerance_px: f64) -> RenderRequest {
        RenderRequest {
            tolerance_px,
            ..self
        }
    }

    /// The request seen through `camera` instead of the scene's own view.
    #[must_use]
    pub fn with_camera(self, camera: Camera) -> RenderRequest {
        RenderRequest {
            camera: Some(camera),
            ..self
        }
    }

    /// The request drawing only the overlays `switches` lets through.
    #[must_use]
    pub fn with_switches(self, switches: Switches) -> RenderRequest {
        RenderRequest { switches, ..self }
    }

    /// The request with the shape overlays `shape`.
    #[must_use]
    pub fn with_shape(self, shape: ShapeOptions) -> RenderRequest {
        RenderRequest { shape, ..self }
    }

    /// The request with the text `text`.
    #[must_use]
    pub fn with_text(self, text: TextOptions) -> RenderRequest {
        RenderRequest { text, ..self }
    }

    /// The viewport the camera maps onto.
    #[must_use]
    pub fn viewport(&self) -> DVec2 {
        DVec2::new(f64::from(self.width), f64::from(self.height))
    }

    /// Checks the request before any GPU work: a size of at least one pixel each way and
    /// within the image limit, a tolerance the tessellator takes.
    ///
    /// # Errors
    /// [`RenderError::EmptySize`], [`RenderError::Size`] or [`RenderError::Tolerance`],
    /// each naming the value.
    pub fn check(&self) -> Result<(), RenderError> {
        for (name, value) in [("width", self.width), ("height", self.height)] {
            if value == 0 {
                return Err(RenderError::EmptySize { name });
            }
        }
        IMAGE_PIXELS.check(u64::from(self.width) * u64::from(self.height))?;
        check_tolerance(self.tolerance_px)?;
        Ok(())
    }
}

/// Why a scene could not be drawn.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RenderError {
    /// A width or height of 0.
    #[error("the image's {name} is 0: it must be at least 1 pixel")]
    EmptySize {
        /// `width` or `height`.
        name: &'static str,
    },
    /// More pixels than the image limit.
    #[error("the image's size: {0}")]
    Size(#[from] LimitError),
    /// A tolerance the tessellator does not take.
    #[error(transparent)]
    Tolerance(#[from] ToleranceError),
    /// The GPU's failure: the device, the image size it can hold, the scene's size.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// The text's failure: axes or a grid asked of a 3D view, a view `f64` cannot apply.
    #[error(transparent)]
    Figure(#[from] FigureError),
}

/// Draws `scene` as `request` asks: encoded with its shape overlays resolved for the
/// view, tessellated within the tolerance and drawn by the GPU, then the text written
/// over the pixels by the same camera.
///
/// # Errors
/// [`RenderError`]: the request's values ([`RenderRequest::check`]), the GPU's failure,
/// or the text's.
pub fn render(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    scene: &Scene,
    request: &RenderRequest,
) -> Result<RgbaImage, RenderError> {
    request.check()?;
    let viewport = request.viewport();
    let camera = request.camera.unwrap_or_else(|| scene.camera(viewport));
    let encoding = encode_shaped_with(
        scene,
        camera.view_height(viewport),
        &request.shape,
        request.switches,
    );
    let mut image = render_with(
        ctx,
        pipelines,
        &encoding,
        &camera,
        (request.width, request.height),
        request.tolerance_px,
    )?;
    // The guides and text through the same camera (the legend's marker rows for the
    // markers drawn).
    let mut opts = FigureOptions::new(request.width, request.height).with_text(request.text);
    opts.shape = request.shape;
    opts.camera = Some(camera);
    opts.switches = request.switches;
    annotate_with(
        &mut Canvas {
            data: &mut image.data,
            width: image.width,
            height: image.height,
        },
        scene,
        opts,
    )?;
    Ok(image)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_request_names_what_is_wrong_with_it() {
        assert!(RenderRequest::new(1, 1).check().is_ok());
        assert_eq!(
            RenderRequest::new(10, 0).check(),
            Err(RenderError::EmptySize { name: "height" })
        );
        assert!(matches!(
            RenderRequest::new(100_000, 100_000).check(),
            Err(RenderError::Size(_))
        ));
        for bad in [f64::NAN, f64::INFINITY, 0.0, -0.25] {
            let e = RenderRequest::new(10, 10)
                .with_tolerance_px(bad)
                .check()
                .unwrap_err();
            assert!(matches!(e, RenderError::Tolerance(_)), "{bad}: {e}");
        }
    }
}
