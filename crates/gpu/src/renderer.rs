//! The render pipelines (`shaders/lines.wgsl`, `shaders/points.wgsl`, the layer's of
//! `shaders/layer.wgsl`) and a scene as it lives on the GPU. Curves are drawn straight from
//! the tessellator's sample buffers — rasterized into the layer by a compute pass, or as
//! quads where no layer fits — and no sample comes back to the CPU in a frame.

use bytemuck::Zeroable;
use glam::DVec2;

use super::adaptive::{
    AdaptiveChunk, AdaptiveTessellator, CombChunk, FrameSettings, initial_capacity,
};
use super::context::GpuContext;
use super::layout::{
    COMB_ALL, COMB_NONE, COMB_RASTER_ARGS_OFFSET, FrameStats, GpuCamera, GpuControlPoint,
    GpuLineStyle, GpuVertex, LAYER_GROUPS, LAYER_RUN, LAYER_WORKGROUP,
};
use super::pack::PreparedScene;
use super::pipelines::Pipelines;
use super::shaders;
use crate::chunks::LineBatch;
use splinescope_encoding::camera::Camera;
use splinescope_encoding::draw::{COMB_ENVELOPE_ALPHA, COMB_HAIR_ALPHA, COMB_WIDTH_PX};

use super::layout;

/// Line and point pipelines for one colour target format, the camera uniform, and a
/// handle to the adaptive tessellation passes it runs before drawing.
#[derive(Debug)]
pub struct Renderer {
    adaptive: AdaptiveTessellator,
    camera_buffer: wgpu::Buffer,
    camera_bind_group: wgpu::BindGroup,
    batch_layout: wgpu::BindGroupLayout,
    line_pipeline: wgpu::RenderPipeline,
    /// The comb as line lists, where the layer does not fit in one binding.
    hair_pipeline: wgpu::RenderPipeline,
    envelope_pipeline: wgpu::RenderPipeline,
    point_pipeline: wgpu::RenderPipeline,
    /// The layer: its comb and curve rasterizers and the full-screen pass blending it.
    comb_raster: wgpu::ComputePipeline,
    comb_raster_layout: wgpu::BindGroupLayout,
    curve_raster: wgpu::ComputePipeline,
    curve_raster_layout: wgpu::BindGroupLayout,
    layer_pipeline: wgpu::RenderPipeline,
    layer_layout: wgpu::BindGroupLayout,
    format: wgpu::TextureFormat,
}

/// The layer: one `u32` per pixel of the target (`shaders/layer.wgsl`), cleared and
/// rasterized into each frame (the curves and their combs), then blended over the target
/// in the draw pass.
#[derive(Debug)]
struct Layer {
    buffer: wgpu::Buffer,
    /// Width and height in pixels.
    size: [u32; 2],
    bind_group: wgpu::BindGroup,
}

/// Curve styles the layer's pixels can name (23 bits of order).
const LAYER_ORDERS: usize = 1 << 23;

/// A drawable set of tagged vertices with their styles.
#[derive(Debug)]
pub struct DrawBatch {
    bind_group: wgpu::BindGroup,
    vertex_count: u32,
    /// The vertices, then the styles.
    buffers: Vec<wgpu::Buffer>,
}

/// A curve chunk on the GPU: the adaptive tessellation's buffers plus the draw bind
/// group over its samples.
#[derive(Debug)]
pub struct GpuChunk {
    /// The tessellation buffers (samples and the indirect draw arguments among them).
    pub adaptive: AdaptiveChunk,
    draw: DrawBatch,
    styles: Vec<GpuLineStyle>,
    comb: Option<CombDraw>,
    /// The curve rasterizer's bind group over the samples, styles and work buffer and the
    /// scene's layer (made when the layer is, and again when the chunk grows).
    raster: Option<wgpu::BindGroup>,
    /// The capacity the chunk started with: it never shrinks below it.
    floor: u32,
}

/// A chunk's curvature comb on the GPU: the comb pass's buffers and the draws over them.
#[derive(Debug)]
struct CombDraw {
    buffers: CombChunk,
    hairs: DrawBatch,
    envelope: DrawBatch,
    /// The rasterizer's bind group over these buffers and the scene's layer (made when
    /// the layer is).
    raster: Option<wgpu::BindGroup>,
    /// The curve tag the pass draws for ([`COMB_ALL`], [`COMB_NONE`] or one tag).
    curve: u32,
}

impl GpuChunk {
    /// The chunk's curve styles, by tag, with their places in the scene
    /// ([`GpuLineStyle::order`]).
    #[must_use]
    pub fn styles(&self) -> &[GpuLineStyle] {
        &self.styles
    }
}

impl CombDraw {
    /// Whether the comb pass draws any curve's comb.
    fn shown(&self) -> bool {
        self.curve != COMB_NONE
    }
}

/// Timestamp queries around a stage of several passes: `begin` written at the start of
/// the first, `end` at the end of the last.
#[derive(Debug, Clone, Copy)]
pub struct PassSpan<'a> {
    /// The query set.
    pub query_set: &'a wgpu::QuerySet,
    /// The query written first.
    pub begin: u32,
    /// The query written last.
    pub end: u32,
}

/// Which curvature combs are drawn, and how long their hairs are.
#[derive(Debug, Clone, PartialEq)]
pub struct CombRequest {
    /// World length of a hair per unit of curvature.
    pub scale: f32,
    /// The longest hair, in world units (`f32::MAX`: no cap).
    pub cap: f32,
    /// `None`: every curve's comb; `Some(tags)`: only the curve with these
    /// `(chunk, tag)` pairs ([`super::pack::curve_tags`]).
    pub only: Option<Vec<(usize, u32)>>,
}

/// The style of a comb's hairs and envelope over a curve of style `curve`
/// ([`splinescope_encoding::draw::comb_strokes`]): one pixel, the curve's colour, the hairs
/// fainter.
#[must_use]
pub fn comb_styles(curve: &[GpuLineStyle]) -> (Vec<GpuLineStyle>, Vec<GpuLineStyle>) {
    let with = |alpha: f32| {
        curve
            .iter()
            .map(|s| GpuLineStyle {
                color: [s.color[0], s.color[1], s.color[2], s.color[3] * alpha],
                width_px: COMB_WIDTH_PX,
                dash_px: 0.0,
                ..*s
            })
            .collect()
    };
    (with(COMB_HAIR_ALPHA), with(COMB_ENVELOPE_ALPHA))
}

/// A scene uploaded to the GPU.
#[derive(Debug)]
pub struct GpuScene {
    /// The curve chunks: tessellated every frame, then drawn.
    pub chunks: Vec<GpuChunk>,
    lines: Vec<DrawBatch>,
    points: Vec<DrawBatch>,
    /// The clear colour.
    pub background: wgpu::Color,
    /// The comb's scale and cap ([`CombRequest`]).
    comb_scale: (f32, f32),
    /// The most samples the chunks may grow to hold together ([`SAMPLE_BUDGET`] unless
    /// set).
    sample_budget: u64,
    /// The layer, where it fits in one binding and is allowed.
    layer: Option<Layer>,
    /// Whether curves and combs may be drawn through the layer (else as quads and line
    /// lists).
    layer_allowed: bool,
    /// The curve styles in scene order (the colours the layer's pixels name); `None` for a
    /// scene with more than the layer can name (it is then drawn without one).
    layer_styles: Option<wgpu::Buffer>,
    markers: Vec<DrawBatch>,
}

impl GpuScene {
    /// Overwrites overlay vertices in place: `lines` and `points` as
    /// [`super::pack::OverlayMap::rewrite`] gives them.
    ///
    /// # Panics
    /// If a write falls outside its batch (a bug in the caller).
    pub fn write_overlays(
        &self,
        queue: &wgpu::Queue,
        lines: &[(usize, usize, Vec<GpuVertex>)],
        points: &[(usize, usize, Vec<GpuVertex>)],
    ) {
        for (batches, writes) in [(&self.lines, lines), (&self.points, points)] {
            for (batch, first, verts) in writes {
                let b = &batches[*batch];
                assert!(
                    first + verts.len() <= b.vertex_count as usize,
                    "overlay write outside its batch"
                );
                queue.write_buffer(
                    &b.buffers[0],
                    (*first * size_of::<GpuVertex>()) as u64,
                    bytemuck::cast_slice(verts),
                );
            }
        }
    }

    /// Overwrites control points of chunk `chunk` from `first_point` on (a curve whose
    /// lowering kept its structure: see [`super::pack::repack_points`]).
    ///
    /// # Panics
    /// If the range is outside the chunk (a bug in the caller).
    pub fn write_points(
        &self,
        queue: &wgpu::Queue,
        chunk: usize,
        first_point: u32,
        points: &[GpuControlPoint],
    ) {
        let offset = u64::from(first_point) * size_of::<GpuControlPoint>() as u64;
        let buffer = &self.chunks[chunk].adaptive.points;
        assert!(
            offset + size_of_val(points) as u64 <= buffer.size(),
            "points outside the chunk"
        );
        queue.write_buffer(buffer, offset, bytemuck::cast_slice(points));
    }

    /// Sets the most samples the chunks may grow to hold together (see
    /// [`GpuScene::grow`]); buffers already larger are kept until they shrink.
    pub fn set_sample_budget(&mut self, samples: u64) {
        self.sample_budget = samples;
    }

    /// Samples the chunks' buffers hold together.
    #[must_use]
    pub fn capacity(&self) -> u64 {
        self.chunks
            .iter()
            .map(|c| u64::from(c.adaptive.capacity))
            .sum()
    }

    /// Writes every chunk's frame uniform (camera and tolerance) for the next frame, and
    /// sizes the layer to the frame's viewport.
    pub fn prepare_frame(
        &mut self,
        ctx: &GpuContext,
        renderer: &Renderer,
        settings: &FrameSettings,
    ) {
        renderer.adaptive.prepare(
            &ctx.queue,
            self.chunks.iter().map(|c| &c.adaptive),
            settings,
        );
        let Some(styles) = self.layer_styles.as_ref().filter(|_| self.layer_allowed) else {
            self.layer = None;
            return;
        };
        let [w, h] = settings.camera.viewport_px;
        // Viewports are whole pixels; at least one, so that the buffer is never empty.
        let size = [w.round().max(1.0) as u32, h.round().max(1.0) as u32];
        if self.layer.as_ref().is_none_or(|l| l.size != size) {
            self.layer = renderer.layer(ctx, size, styles);
            for chunk in &mut self.chunks {
                chunk.raster = None;
                if let Some(comb) = &mut chunk.comb {
                    comb.raster = None;
                }
            }
        }
        if let Some(layer) = &self.layer {
            for chunk in &mut self.chunks {
                if chunk.raster.is_none() {
                    chunk.raster = Some(renderer.curve_raster_group(&ctx.device, chunk, layer));
                }
                if let Some(comb) = chunk.comb.as_mut().filter(|c| c.raster.is_none()) {
                    comb.raster = Some(renderer.comb_raster_group(&ctx.device, comb, layer));
                }
            }
        }
    }

    /// Records the adaptive tessellation of every chunk.
    pub fn encode_tessellation(
        &self,
        renderer: &Renderer,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        renderer.adaptive.encode(
            encoder,
            self.chunks.iter().map(|c| &c.adaptive),
            timestamp_writes,
        );
        self.encode_comb(renderer, encoder);
        self.encode_layer(renderer, encoder, None);
    }

    /// Records the layer's frame (after the tessellation and the comb pass): cleared, then
    /// every shown comb and every chunk's curves rasterized into it, with timestamps at
    /// the start and end of its pass (an empty pass where there is no layer, so the pair
    /// is always written).
    pub fn encode_layer(
        &self,
        renderer: &Renderer,
        encoder: &mut wgpu::CommandEncoder,
        span: Option<PassSpan<'_>>,
    ) {
        let timestamp_writes = span.as_ref().map(|s| wgpu::ComputePassTimestampWrites {
            query_set: s.query_set,
            beginning_of_pass_write_index: Some(s.begin),
            end_of_pass_write_index: Some(s.end),
        });
        let Some(layer) = &self.layer else {
            if timestamp_writes.is_some() {
                encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("no layer"),
                    timestamp_writes,
                });
            }
            return;
        };
        encoder.clear_buffer(&layer.buffer, 0, None);
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("layer"),
            timestamp_writes,
        });
        pass.set_bind_group(0, &renderer.camera_bind_group, &[]);
        pass.set_pipeline(&renderer.comb_raster);
        for comb in self.chunks.iter().filter_map(|c| c.comb.as_ref()) {
            if let (true, Some(group)) = (comb.shown(), &comb.raster) {
                pass.set_bind_group(1, group, &[]);
                pass.dispatch_workgroups_indirect(&comb.buffers.args, COMB_RASTER_ARGS_OFFSET);
            }
        }
        pass.set_pipeline(&renderer.curve_raster);
        for chunk in &self.chunks {
            if let Some(group) = &chunk.raster {
                // Runs of LAYER_RUN pieces by stride over at most LAYER_GROUPS
                // workgroups (the pieces drawn are known only on the GPU).
                let groups = chunk
                    .adaptive
                    .capacity
                    .div_ceil(LAYER_RUN * LAYER_WORKGROUP)
                    .clamp(1, LAYER_GROUPS);
                pass.set_bind_group(1, group, &[]);
                pass.dispatch_workgroups(groups, 1, 1);
            }
        }
    }

    /// Records the comb pass of every chunk with a comb (after its tessellation).
    pub fn encode_comb(&self, renderer: &Renderer, encoder: &mut wgpu::CommandEncoder) {
        self.encode_comb_timed(renderer, encoder, None);
    }

    /// [`GpuScene::encode_comb`] with timestamps at the start and end of its pass (an
    /// empty pass where no comb is drawn, so the pair is always written).
    pub fn encode_comb_timed(
        &self,
        renderer: &Renderer,
        encoder: &mut wgpu::CommandEncoder,
        span: Option<PassSpan<'_>>,
    ) {
        let writes = |begin: bool, end: bool| {
            span.as_ref().map(|s| wgpu::ComputePassTimestampWrites {
                query_set: s.query_set,
                beginning_of_pass_write_index: begin.then_some(s.begin),
                end_of_pass_write_index: end.then_some(s.end),
            })
        };
        let pairs: Vec<(&AdaptiveChunk, &CombChunk)> = self
            .chunks
            .iter()
            .filter_map(|c| {
                c.comb
                    .as_ref()
                    .filter(|comb| comb.shown())
                    .map(|comb| (&c.adaptive, &comb.buffers))
            })
            .collect();
        if pairs.is_empty() {
            if span.is_some() {
                encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("no comb"),
                    timestamp_writes: writes(true, true),
                });
            }
            return;
        }
        renderer
            .adaptive
            .encode_comb(encoder, pairs, writes(true, true));
    }

    /// Turns the curvature combs on (`Some`: every curve's, or one curve's, with hairs of
    /// `scale` world units per unit of curvature) or off (`None`, freeing their buffers).
    pub fn set_comb(&mut self, ctx: &GpuContext, renderer: &Renderer, comb: Option<&CombRequest>) {
        let Some(request) = comb else {
            for chunk in &mut self.chunks {
                chunk.comb = None;
            }
            return;
        };
        self.comb_scale = (request.scale, request.cap);
        for (index, chunk) in self.chunks.iter_mut().enumerate() {
            let curve = match &request.only {
                None => COMB_ALL,
                Some(tags) => tags
                    .iter()
                    .find(|(c, _)| *c == index)
                    .map_or(COMB_NONE, |&(_, tag)| tag),
            };
            let fits = chunk
                .comb
                .as_ref()
                .is_some_and(|c| c.buffers.capacity == chunk.adaptive.capacity);
            if !fits {
                chunk.comb = Some(renderer.comb_draw(ctx, &chunk.adaptive, &chunk.styles, curve));
            }
            if let Some(comb) = &mut chunk.comb {
                comb.curve = curve;
                renderer.adaptive.write_comb(
                    &ctx.queue,
                    &comb.buffers,
                    (request.scale, request.cap),
                    curve,
                );
            }
        }
    }

    /// Whether any chunk draws a comb.
    #[must_use]
    pub fn has_comb(&self) -> bool {
        self.chunks.iter().any(|c| c.comb.is_some())
    }

    /// The fewest samples a segment on screen gets this frame
    /// ([`crate::adaptive::FrameSettings::min_count`]): room for the comb's hairs while a
    /// comb is drawn.
    #[must_use]
    pub fn min_count(&self) -> u32 {
        if self.has_comb() {
            crate::layout::COMB_HAIRS
        } else {
            0
        }
    }

    /// Whether curves and combs are drawn through the layer (`true`, the default: a
    /// compute pass rasterizes them, one full-screen triangle blends them) or as quads and
    /// line lists (`false`, also what happens where the layer would not fit in one storage
    /// binding). Takes effect at the next [`GpuScene::prepare_frame`].
    pub fn set_layer(&mut self, allowed: bool) {
        self.layer_allowed = allowed;
    }

    /// The layer (`shaders/layer.wgsl`: one `u32` per pixel, row by row) and its width and
    /// height, where it is allowed and fits in one binding (after a
    /// [`GpuScene::prepare_frame`]).
    #[must_use]
    pub fn layer(&self) -> Option<(&wgpu::Buffer, [u32; 2])> {
        self.layer.as_ref().map(|l| (&l.buffer, l.size))
    }

    /// Chunk `chunk`'s comb buffers (hairs, envelope, draw arguments), when it has them.
    #[must_use]
    pub fn comb_buffers(&self, chunk: usize) -> Option<&CombChunk> {
        self.chunks.get(chunk)?.comb.as_ref().map(|c| &c.buffers)
    }

    /// Fits every chunk's sample buffer to what its last frame asked for: a chunk that asked
    /// for more than its buffer holds gets room for half as much again, within the
    /// device's binding limit and within the scene's budget ([`SAMPLE_BUDGET`] unless set) for all its chunks (past it the
    /// frame's counts are scaled down to fit, and the frame says it was capped); a chunk
    /// that asked for under a quarter of a buffer larger than its first one is given back
    /// the excess. Returns whether any chunk grew. `stats` are the chunks' statistics of
    /// that frame, in order.
    pub fn grow(&mut self, ctx: &GpuContext, renderer: &Renderer, stats: &[FrameStats]) -> bool {
        let limit = (ctx.max_binding_bytes() / size_of::<GpuVertex>() as u64)
            .min(u64::from(u32::MAX)) as u32;
        // Shrink first, so that the room given back is there for the chunks that grow.
        for (chunk, s) in self.chunks.iter_mut().zip(stats) {
            let capacity = chunk.adaptive.capacity;
            if capacity > chunk.floor && u64::from(s.requested) * 4 < u64::from(capacity) {
                let fit = (u64::from(s.requested) * 3 / 2).max(u64::from(chunk.floor)) as u32;
                chunk.resize(ctx, renderer, fit, self.comb_scale);
            }
        }
        let mut total: u64 = self
            .chunks
            .iter()
            .map(|c| u64::from(c.adaptive.capacity))
            .sum();
        let mut grew = false;
        for (chunk, s) in self.chunks.iter_mut().zip(stats) {
            let capacity = chunk.adaptive.capacity;
            let others = total - u64::from(capacity);
            let room = self
                .sample_budget
                .saturating_sub(others)
                .min(u64::from(limit))
                .max(u64::from(capacity));
            if u64::from(s.requested) <= u64::from(capacity) || u64::from(capacity) >= room {
                continue;
            }
            // Headroom, so that zooming in does not reallocate every frame.
            let fit = (u64::from(s.requested) * 3 / 2).min(room) as u32;
            chunk.resize(ctx, renderer, fit, self.comb_scale);
            total = others + u64::from(fit);
            grew = true;
        }
        grew
    }
}

/// The most samples a scene's chunks hold together once grown (16 bytes each; a comb adds
/// three more per sample): 2²³, some eight million — a sample for every pixel of a 4K
/// screen. A scene whose first buffers (twice its object-space counts) are larger keeps
/// them but never grows.
pub const SAMPLE_BUDGET: u64 = 1 << 23;

impl GpuChunk {
    /// Replaces the chunk's sample buffer with one of `capacity` samples, and what is
    /// bound over it (its draw, its comb, its raster bind group).
    fn resize(
        &mut self,
        ctx: &GpuContext,
        renderer: &Renderer,
        capacity: u32,
        comb_scale: (f32, f32),
    ) {
        renderer.adaptive.grow(
            &ctx.device,
            &mut self.adaptive,
            capacity,
            wgpu::BufferUsages::COPY_SRC,
        );
        self.draw = renderer.batch(
            &ctx.device,
            self.adaptive.samples.clone(),
            self.adaptive.capacity,
            &self.styles,
        );
        // Over the old samples: made again at the next frame.
        self.raster = None;
        if let Some(old) = self.comb.take() {
            let comb = renderer.comb_draw(ctx, &self.adaptive, &self.styles, old.curve);
            renderer
                .adaptive
                .write_comb(&ctx.queue, &comb.buffers, comb_scale, comb.curve);
            self.comb = Some(comb);
        }
    }
}

/// The camera uniform for `camera` on a `viewport` in physical pixels, with line widths
/// scaled by `width_scale` (the window's scale factor; 1 offscreen).
#[must_use]
pub fn camera_uniform(camera: &Camera, viewport: DVec2, width_scale: f32) -> GpuCamera {
    GpuCamera {
        clip_from_world: camera
            .clip_from_world(viewport)
            .as_mat4()
            .to_cols_array_2d(),
        viewport_px: viewport.as_vec2().to_array(),
        width_scale,
        _padding: 0.0,
    }
}

impl Renderer {
    /// Builds the pipelines for targets of `format`, running `pipelines`' adaptive passes
    /// to tessellate.
    #[must_use]
    pub fn new(
        device: &wgpu::Device,
        pipelines: &Pipelines,
        format: wgpu::TextureFormat,
    ) -> Renderer {
        let layouts = super::bindings::draw();
        let camera_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("camera"),
            entries: &layouts[0],
        });
        let batch_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("vertices and styles"),
            entries: &layouts[1],
        });
        let camera_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("camera"),
            size: size_of::<GpuCamera>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let camera_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("camera"),
            layout: &camera_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: camera_buffer.as_entire_binding(),
            }],
        });
        // Every draw and layer pipeline: the camera, then its own group 1.
        let layout_with = |label: &str, group: &wgpu::BindGroupLayout| {
            device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(label),
                bind_group_layouts: &[Some(&camera_layout), Some(group)],
                immediate_size: 0,
            })
        };
        let group_layout = |label: &str, entries: &[wgpu::BindGroupLayoutEntry]| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(label),
                entries,
            })
        };
        let layout = layout_with("draw", &batch_layout);
        let pipeline = |layout: &wgpu::PipelineLayout,
                        module: &wgpu::ShaderModule,
                        (vs, fs): (&str, &str),
                        topology: wgpu::PrimitiveTopology| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(vs),
                layout: Some(layout),
                vertex: wgpu::VertexState {
                    module,
                    entry_point: Some(vs),
                    compilation_options: wgpu::PipelineCompilationOptions::default(),
                    buffers: &[],
                },
                primitive: wgpu::PrimitiveState {
                    topology,
                    ..wgpu::PrimitiveState::default()
                },
                depth_stencil: None,
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module,
                    entry_point: Some(fs),
                    compilation_options: wgpu::PipelineCompilationOptions::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format,
                        blend: Some(wgpu::BlendState::PREMULTIPLIED_ALPHA_BLENDING),
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let lines = shaders::LINES.module(device);
        let points = shaders::POINTS.module(device);
        let layer_module = shaders::LAYER.module(device);
        use wgpu::PrimitiveTopology::{LineList, TriangleList, TriangleStrip};
        let line_pipeline = pipeline(&layout, &lines, ("vs_line", "fs_line"), TriangleStrip);
        let hair_pipeline = pipeline(&layout, &lines, ("vs_hair_line", "fs_flat"), LineList);
        let envelope_pipeline =
            pipeline(&layout, &lines, ("vs_envelope_line", "fs_flat"), LineList);
        let point_pipeline = pipeline(&layout, &points, ("vs_point", "fs_point"), TriangleList);
        let layer_layout = group_layout("layer", &super::bindings::layer_blend());
        let layer_pipeline = pipeline(
            &layout_with("layer", &layer_layout),
            &layer_module,
            ("vs_layer", "fs_layer"),
            TriangleList,
        );
        let raster = |entry: &str, group: &wgpu::BindGroupLayout| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&layout_with(entry, group)),
                module: &layer_module,
                entry_point: Some(entry),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                cache: None,
            })
        };
        let comb_raster_layout = group_layout("comb raster", &super::bindings::comb_raster());
        let curve_raster_layout = group_layout("curve raster", &super::bindings::curve_raster());
        let comb_raster = raster("raster_comb", &comb_raster_layout);
        let curve_raster = raster("raster_curves", &curve_raster_layout);
        Renderer {
            adaptive: pipelines.adaptive.clone(),
            camera_buffer,
            camera_bind_group,
            batch_layout,
            line_pipeline,
            hair_pipeline,
            envelope_pipeline,
            point_pipeline,
            comb_raster,
            comb_raster_layout,
            curve_raster,
            curve_raster_layout,
            layer_pipeline,
            layer_layout,
            format,
        }
    }

    /// A chunk's comb: its buffers and the draws of its hairs and envelope.
    fn comb_draw(
        &self,
        ctx: &GpuContext,
        chunk: &AdaptiveChunk,
        styles: &[GpuLineStyle],
        curve: u32,
    ) -> CombDraw {
        let buffers = self
            .adaptive
            .comb_chunk(&ctx.device, chunk, wgpu::BufferUsages::COPY_SRC);
        let (hair_styles, envelope_styles) = comb_styles(styles);
        let hairs = self.batch(
            &ctx.device,
            buffers.hairs.clone(),
            2 * buffers.capacity,
            &hair_styles,
        );
        let envelope = self.batch(
            &ctx.device,
            buffers.envelope.clone(),
            buffers.capacity,
            &envelope_styles,
        );
        CombDraw {
            buffers,
            hairs,
            envelope,
            raster: None,
            curve,
        }
    }

    /// A layer of `size` pixels, or `None` where it would not fit in one storage binding
    /// (curves and combs are then drawn as quads and line lists).
    fn layer(&self, ctx: &GpuContext, size: [u32; 2], styles: &wgpu::Buffer) -> Option<Layer> {
        let bytes = u64::from(size[0]) * u64::from(size[1]) * 4;
        if bytes > ctx.max_binding_bytes() {
            return None;
        }
        let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("layer"),
            size: bytes,
            // COPY_SRC: read back by tests.
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_DST
                | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("comb layer"),
            layout: &self.layer_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 6,
                    resource: buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 10,
                    resource: styles.as_entire_binding(),
                },
            ],
        });
        Some(Layer {
            buffer,
            size,
            bind_group,
        })
    }

    /// The curve rasterizer's bind group for `chunk` into `layer`.
    fn curve_raster_group(
        &self,
        device: &wgpu::Device,
        chunk: &GpuChunk,
        layer: &Layer,
    ) -> wgpu::BindGroup {
        let buffers = [
            (5, &layer.buffer),
            (7, &chunk.draw.buffers[0]),
            (8, &chunk.draw.buffers[1]),
            (9, &chunk.adaptive.work),
        ];
        let entries: Vec<wgpu::BindGroupEntry<'_>> = buffers
            .into_iter()
            .map(|(binding, buffer)| wgpu::BindGroupEntry {
                binding,
                resource: buffer.as_entire_binding(),
            })
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("curve raster"),
            layout: &self.curve_raster_layout,
            entries: &entries,
        })
    }

    /// The rasterizer's bind group for `comb` into `layer`.
    fn comb_raster_group(
        &self,
        device: &wgpu::Device,
        comb: &CombDraw,
        layer: &Layer,
    ) -> wgpu::BindGroup {
        let buffers = [
            &comb.buffers.hairs,
            &comb.buffers.envelope,
            &comb.hairs.buffers[1],
            &comb.envelope.buffers[1],
            &comb.buffers.args,
            &layer.buffer,
        ];
        let entries: Vec<wgpu::BindGroupEntry<'_>> = (0u32..)
            .zip(buffers)
            .map(|(binding, buffer)| wgpu::BindGroupEntry {
                binding,
                resource: buffer.as_entire_binding(),
            })
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("comb raster"),
            layout: &self.comb_raster_layout,
            entries: &entries,
        })
    }

    /// The colour format the pipelines draw to.
    #[must_use]
    pub fn format(&self) -> wgpu::TextureFormat {
        self.format
    }

    pub(crate) fn batch(
        &self,
        device: &wgpu::Device,
        vertices: wgpu::Buffer,
        vertex_count: u32,
        styles: &[GpuLineStyle],
    ) -> DrawBatch {
        let styles = super::init_buffer(
            device,
            "styles",
            bytemuck::cast_slice(styles),
            wgpu::BufferUsages::STORAGE,
        );
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("vertices and styles"),
            layout: &self.batch_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: vertices.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: styles.as_entire_binding(),
                },
            ],
        });
        DrawBatch {
            bind_group,
            vertex_count,
            buffers: vec![vertices, styles],
        }
    }

    fn overlay_batch(&self, device: &wgpu::Device, batch: &LineBatch) -> DrawBatch {
        let vertices = super::init_buffer(
            device,
            "overlay vertices",
            bytemuck::cast_slice::<GpuVertex, u8>(&batch.vertices),
            // Written in place when an edit keeps the overlays' shape.
            wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        );
        self.batch(device, vertices, batch.vertices.len() as u32, &batch.styles)
    }

    /// Uploads a prepared scene.
    #[must_use]
    pub fn upload(&self, ctx: &GpuContext, prepared: &PreparedScene) -> GpuScene {
        let device = &ctx.device;
        let limit = ctx.max_binding_bytes() / size_of::<GpuVertex>() as u64;
        // Each curve style's place in the scene (chunks hold the curves in order): the
        // layer's pixels name it, and the scene's table of them gives their colours.
        let mut ordered: Vec<GpuLineStyle> = Vec::new();
        let chunk_styles: Vec<Vec<GpuLineStyle>> = prepared
            .chunks
            .iter()
            .map(|chunk| {
                chunk
                    .styles
                    .iter()
                    .map(|s| {
                        let style = GpuLineStyle {
                            order: ordered.len() as u32,
                            ..*s
                        };
                        ordered.push(style);
                        style
                    })
                    .collect()
            })
            .collect();
        if ordered.is_empty() {
            // A binding is never empty.
            ordered.push(GpuLineStyle::zeroed());
        }
        let layer_styles = (ordered.len() <= LAYER_ORDERS).then(|| {
            super::init_buffer(
                device,
                "layer styles",
                bytemuck::cast_slice(&ordered),
                wgpu::BufferUsages::STORAGE,
            )
        });
        let chunks = prepared
            .chunks
            .iter()
            .zip(chunk_styles)
            // Every chunk, even one without segments of its own: placements index them.
            .map(|(chunk, styles)| {
                let adaptive = self.adaptive.upload(
                    device,
                    chunk,
                    initial_capacity(chunk, limit),
                    wgpu::BufferUsages::COPY_SRC,
                );
                let draw = self.batch(device, adaptive.samples.clone(), adaptive.capacity, &styles);
                let floor = adaptive.capacity;
                GpuChunk {
                    adaptive,
                    draw,
                    styles,
                    comb: None,
                    raster: None,
                    floor,
                }
            })
            .collect();
        let [r, g, b, a] = prepared.background.0.map(f64::from);
        GpuScene {
            chunks,
            lines: prepared
                .lines
                .iter()
                .map(|b| self.overlay_batch(device, b))
                .collect(),
            points: prepared
                .points
                .iter()
                .map(|b| self.overlay_batch(device, b))
                .collect(),
            background: wgpu::Color { r, g, b, a },
            comb_scale: (0.0, f32::MAX),
            sample_budget: SAMPLE_BUDGET,
            layer: None,
            layer_allowed: true,
            layer_styles,
            markers: Vec::new(),
        }
    }

    /// Replaces the scene's overlay batches (after curves were edited in place).
    pub fn replace_overlays(
        &self,
        device: &wgpu::Device,
        scene: &mut GpuScene,
        lines: &[LineBatch],
        points: &[LineBatch],
    ) {
        scene.lines = lines
            .iter()
            .map(|b| self.overlay_batch(device, b))
            .collect();
        scene.points = points
            .iter()
            .map(|b| self.overlay_batch(device, b))
            .collect();
    }

    /// Replaces the scene's shape markers (point sets drawn over everything, each a ring
    /// then a core: `splinescope_scene::format::shape::marker_points`).
    pub fn set_markers(
        &self,
        ctx: &GpuContext,
        scene: &mut GpuScene,
        points: &[(Vec<glam::DVec3>, splinescope_encoding::draw::Stroke)],
    ) {
        let limits = crate::chunks::ChunkLimits::for_binding_size(ctx.max_binding_bytes());
        scene.markers = super::overlays::prepare_points(points, limits)
            .iter()
            .map(|b| self.overlay_batch(&ctx.device, b))
            .collect();
    }

    /// The adaptive tessellation passes this renderer runs (for callers that record them
    /// themselves, e.g. with per-stage timestamps).
    #[must_use]
    pub fn adaptive(&self) -> &AdaptiveTessellator {
        &self.adaptive
    }

    /// Sets the camera for the next frames.
    pub fn set_camera(&self, queue: &wgpu::Queue, camera: &GpuCamera) {
        queue.write_buffer(&self.camera_buffer, 0, bytemuck::bytes_of(camera));
    }

    /// Records the whole frame: the compute pass tessellating every chunk, then one render
    /// pass clearing `target` and drawing overlays' polylines, the curves, and points on
    /// top. The frame's camera and tolerance must have been set ([`Renderer::set_camera`],
    /// [`GpuScene::prepare_frame`]).
    pub fn encode_frame(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &GpuScene,
        target: &wgpu::TextureView,
    ) {
        scene.encode_tessellation(self, encoder, None);
        let mut pass = self.begin_pass(encoder, target, wgpu::LoadOp::Clear(scene.background));
        self.draw(&mut pass, scene);
    }

    /// Starts a render pass on `target` with the given load operation.
    #[must_use]
    pub fn begin_pass<'e>(
        &self,
        encoder: &'e mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        load: wgpu::LoadOp<wgpu::Color>,
    ) -> wgpu::RenderPass<'e> {
        self.begin_timed_pass(encoder, target, load, None)
    }

    /// [`Renderer::begin_pass`] with timestamp writes at its start and end.
    #[must_use]
    pub fn begin_timed_pass<'e>(
        &self,
        encoder: &'e mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        load: wgpu::LoadOp<wgpu::Color>,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) -> wgpu::RenderPass<'e> {
        encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("draw"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load,
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes,
            occlusion_query_set: None,
            multiview_mask: None,
        })
    }

    /// Draws an uploaded (and tessellated) scene into an open pass.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>, scene: &GpuScene) {
        pass.set_bind_group(0, &self.camera_bind_group, &[]);
        pass.set_pipeline(&self.line_pipeline);
        for batch in &scene.lines {
            draw_lines(pass, batch);
        }
        // The curves over their combs: the layer the compute pass rasterized them into,
        // blended in one full-screen triangle; where no layer fits, the combs as line
        // lists (hairs, then the envelope joining their tips) and the curves as quads.
        if let Some(layer) = &scene.layer {
            pass.set_pipeline(&self.layer_pipeline);
            pass.set_bind_group(1, &layer.bind_group, &[]);
            pass.draw(0..3, 0..1);
        } else {
            let shown = scene
                .chunks
                .iter()
                .filter_map(|c| c.comb.as_ref().filter(|comb| comb.shown()));
            for comb in shown {
                pass.set_pipeline(&self.hair_pipeline);
                pass.set_bind_group(1, &comb.hairs.bind_group, &[]);
                pass.draw_indirect(&comb.buffers.args, 0);
                pass.set_pipeline(&self.envelope_pipeline);
                pass.set_bind_group(1, &comb.envelope.bind_group, &[]);
                pass.draw_indirect(&comb.buffers.args, 16);
            }
            pass.set_pipeline(&self.line_pipeline);
            for chunk in &scene.chunks {
                // As many pieces as the adaptive passes wrote samples, less one.
                pass.set_bind_group(1, &chunk.draw.bind_group, &[]);
                pass.draw_indirect(&chunk.adaptive.work, 0);
            }
        }
        pass.set_pipeline(&self.point_pipeline);
        for batch in scene.points.iter().chain(&scene.markers) {
            pass.set_bind_group(1, &batch.bind_group, &[]);
            pass.draw(0..6, 0..batch.vertex_count);
        }
    }
}

fn draw_lines(pass: &mut wgpu::RenderPass<'_>, batch: &DrawBatch) {
    if batch.vertex_count < 2 {
        return;
    }
    pass.set_bind_group(1, &batch.bind_group, &[]);
    pass.draw(0..layout::LINE_CORNERS, 0..batch.vertex_count - 1);
}

/// Deprecated: `splinescope_gpu::layout::LINE_CORNERS`.
#[deprecated(note = "use splinescope_gpu::layout::LINE_CORNERS")]
pub const LINE_CORNERS: u32 = layout::LINE_CORNERS;
