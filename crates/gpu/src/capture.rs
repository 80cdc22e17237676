//! Rendering into a texture and reading it back as an image (for `render`, image tests
//! and the headless gallery).

use glam::DVec2;

use super::GpuError;
use super::adaptive::{DEFAULT_TOLERANCE_PX, FrameSettings, read_stats};
use super::context::GpuContext;
use super::pack::prepare;
use super::pipelines::Pipelines;
use super::renderer::{GpuScene, Renderer, camera_uniform};
use super::tessellator::read_buffer;
use crate::chunks::ChunkLimits;
use splinescope_encoding::Encoding;
use splinescope_encoding::camera::Camera;
use splinescope_image::RgbaImage;

/// The texture format offscreen images are drawn in: 8-bit RGBA, colours stored as given
/// (sRGB values, blended as such, like the window's non-sRGB surface).
pub const OFFSCREEN_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;

/// Draws `encoding` seen by `camera` into a `width × height` image, tessellated as the
/// window does for the default tolerance ([`DEFAULT_TOLERANCE_PX`]). The camera is the
/// caller's (a scene's own is `Scene::camera` for the viewport).
///
/// # Errors
/// [`GpuError::ImageSize`] for a size the device cannot hold, [`GpuError::Pack`] for a
/// scene over the GPU limits, [`GpuError::Readback`] when reading fails.
#[deprecated(
    note = "a scene is drawn by splinescope_render::render; an encoding by capture::render_with"
)]
pub fn render(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    encoding: &Encoding,
    camera: &Camera,
    (width, height): (u32, u32),
) -> Result<RgbaImage, GpuError> {
    render_with(
        ctx,
        pipelines,
        encoding,
        camera,
        (width, height),
        DEFAULT_TOLERANCE_PX,
    )
}

/// Draws `encoding` seen by `camera` into a `width × height` image, tessellated as the
/// window does for a tolerance of `tolerance_px` pixels: what `splinescope_render::render`
/// draws a scene's encoding with. The camera is the caller's.
///
/// # Errors
/// [`GpuError::ImageSize`] for a size the device cannot hold, [`GpuError::Pack`] for a
/// scene over the GPU limits, [`GpuError::Readback`] when reading fails.
pub fn render_with(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    encoding: &Encoding,
    camera: &Camera,
    (width, height): (u32, u32),
    tolerance_px: f64,
) -> Result<RgbaImage, GpuError> {
    check_size(ctx, width, height)?;
    let prepared = prepare(
        encoding,
        ChunkLimits::for_binding_size(ctx.max_binding_bytes()),
    )?;
    let renderer = Renderer::new(&ctx.device, pipelines, OFFSCREEN_FORMAT);
    let mut gpu_scene = renderer.upload(ctx, &prepared);
    if let Some(scale) = encoding.comb {
        gpu_scene.set_comb(
            ctx,
            &renderer,
            Some(&super::renderer::CombRequest {
                scale: scale as f32,
                cap: (encoding.comb_cap as f32).min(f32::MAX),
                only: None,
            }),
        );
    }
    render_uploaded(
        ctx,
        &renderer,
        &mut gpu_scene,
        camera,
        (width, height),
        tolerance_px,
    )
}

fn check_size(ctx: &GpuContext, width: u32, height: u32) -> Result<(), GpuError> {
    let max = ctx.device.limits().max_texture_dimension_2d;
    if width == 0 || height == 0 || width > max || height > max {
        return Err(GpuError::ImageSize { width, height, max });
    }
    Ok(())
}

/// Draws an already uploaded scene (tessellating it first, for `tolerance_px`) into a
/// `width × height` image; `renderer` must draw to [`OFFSCREEN_FORMAT`]. When the view
/// asks for more samples than a chunk's buffer holds, the buffer grows and the frame is
/// drawn again, so an image is never coarsened by the buffer (only by the device's
/// limit).
///
/// # Errors
/// [`GpuError::ImageSize`], or [`GpuError::Readback`] when reading fails.
pub fn render_uploaded(
    ctx: &GpuContext,
    renderer: &Renderer,
    gpu_scene: &mut GpuScene,
    camera: &Camera,
    (width, height): (u32, u32),
    tolerance_px: f64,
) -> Result<RgbaImage, GpuError> {
    let image = render_once(
        ctx,
        renderer,
        gpu_scene,
        camera,
        (width, height),
        tolerance_px,
    )?;
    let stats = gpu_scene
        .chunks
        .iter()
        .map(|c| read_stats(&ctx.device, &ctx.queue, &c.adaptive))
        .collect::<Result<Vec<_>, _>>()?;
    if gpu_scene.grow(ctx, renderer, &stats) {
        return render_once(
            ctx,
            renderer,
            gpu_scene,
            camera,
            (width, height),
            tolerance_px,
        );
    }
    Ok(image)
}

fn render_once(
    ctx: &GpuContext,
    renderer: &Renderer,
    gpu_scene: &mut GpuScene,
    camera: &Camera,
    (width, height): (u32, u32),
    tolerance_px: f64,
) -> Result<RgbaImage, GpuError> {
    check_size(ctx, width, height)?;
    ctx.check_health()?;
    let viewport = DVec2::new(f64::from(width), f64::from(height));
    let camera = camera_uniform(camera, viewport, 1.0);
    renderer.set_camera(&ctx.queue, &camera);
    gpu_scene.prepare_frame(
        ctx,
        renderer,
        &FrameSettings {
            camera,
            tolerance_px: tolerance_px as f32,
            min_count: gpu_scene.min_count(),
        },
    );

    let texture = ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("offscreen"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: OFFSCREEN_FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("offscreen"),
        });
    renderer.encode_frame(&mut encoder, gpu_scene, &view);

    // Rows of a texture copy are padded to 256 bytes.
    let row = width * 4;
    let padded =
        row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("offscreen pixels"),
        size: u64::from(padded) * u64::from(height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture: &texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    let read = read_buffer(&ctx.device, &ctx.queue, &mut encoder, &buffer);
    // A device error during the frame makes the pixels untrustworthy, whatever was read.
    ctx.check_health()?;
    let bytes: Vec<u8> = read?;
    let mut data = Vec::with_capacity((row * height) as usize);
    for y in 0..height as usize {
        let start = y * padded as usize;
        data.extend_from_slice(&bytes[start..start + row as usize]);
    }
    Ok(RgbaImage {
        width,
        height,
        data,
    })
}
