//! The window's surface: creation with the device, configuration, resizing and frame
//! acquisition (minimised, outdated and lost surfaces handled here).

use std::sync::Arc;

use winit::dpi::PhysicalSize;
use winit::event_loop::ActiveEventLoop;
use winit::window::Window;

use crate::app_error::AppError;
use splinescope_gpu::{ContextOptions, GpuContext, Pipelines};

/// A window with its configured surface.
pub(crate) struct WindowSurface {
    pub window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    pub config: wgpu::SurfaceConfiguration,
}

impl WindowSurface {
    /// Opens a window titled `title` and creates the GPU context able to present to it,
    /// with the compute pipelines built on its device.
    pub fn open(
        event_loop: &ActiveEventLoop,
        title: &str,
        options: &ContextOptions,
    ) -> Result<(WindowSurface, GpuContext, Pipelines), AppError> {
        let window = Arc::new(
            event_loop
                .create_window(
                    Window::default_attributes()
                        .with_title(title)
                        .with_inner_size(PhysicalSize::new(1280, 800)),
                )
                .map_err(|e| AppError::Window(e.to_string()))?,
        );
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends: options.backend.backends(),
            ..wgpu::InstanceDescriptor::new_with_display_handle_from_env(Box::new(
                event_loop.owned_display_handle(),
            ))
        });
        let surface = instance
            .create_surface(window.clone())
            .map_err(|e| AppError::Surface(e.to_string()))?;
        let (ctx, pipelines) = GpuContext::with_instance(instance, options, Some(&surface))?;
        let size = window.inner_size();
        let caps = surface.get_capabilities(&ctx.adapter);
        // Colours are sRGB values blended as such (like the offscreen images), so a
        // non-sRGB format is preferred; egui prefers it too.
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| !f.is_srgb())
            .or_else(|| caps.formats.first().copied())
            .ok_or_else(|| AppError::Surface("the surface offers no format".into()))?;
        let mut config = surface
            .get_default_config(&ctx.adapter, size.width.max(1), size.height.max(1))
            .ok_or_else(|| AppError::Surface("the adapter cannot present to this window".into()))?;
        config.format = format;
        config.present_mode = wgpu::PresentMode::AutoVsync;
        surface.configure(&ctx.device, &config);
        Ok((
            WindowSurface {
                window,
                surface,
                config,
            },
            ctx,
            pipelines,
        ))
    }

    /// The surface's pixel format.
    pub fn format(&self) -> wgpu::TextureFormat {
        self.config.format
    }

    /// The configured size in physical pixels.
    pub fn viewport(&self) -> glam::DVec2 {
        glam::DVec2::new(f64::from(self.config.width), f64::from(self.config.height))
    }

    /// Reconfigures for the window's current size (a minimised window keeps the old one).
    pub fn resize(&mut self, ctx: &GpuContext) {
        let size = self.window.inner_size();
        if size.width == 0 || size.height == 0 {
            return;
        }
        self.config.width = size.width;
        self.config.height = size.height;
        self.surface.configure(&ctx.device, &self.config);
    }

    /// The next frame to draw into; `None` when there is nothing to draw this time
    /// (minimised, occluded, or the surface had to be reconfigured).
    pub fn acquire(&mut self, ctx: &GpuContext) -> Result<Option<wgpu::SurfaceTexture>, AppError> {
        let size = self.window.inner_size();
        if size.width == 0 || size.height == 0 {
            return Ok(None);
        }
        match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f)
            | wgpu::CurrentSurfaceTexture::Suboptimal(f) => Ok(Some(f)),
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => {
                Ok(None)
            }
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.resize(ctx);
                Ok(None)
            }
            wgpu::CurrentSurfaceTexture::Validation => {
                // A failed device is the likelier cause: say so when it is.
                ctx.check_health()?;
                Err(AppError::Surface(
                    "validation error acquiring the frame".into(),
                ))
            }
        }
    }
}
