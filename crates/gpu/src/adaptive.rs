//! Adaptive tessellation on the GPU, every frame, without readback: the passes of
//! `shaders/adaptive.wgsl` (count by Wang's bound in screen space → prefix sum → place,
//! capping to the buffer → de Casteljau writing exactly those samples) and the buffers
//! they work on. The line pipeline draws the result with one indirect draw per chunk.
//! Twins: [`super::twin::wang_count`], [`super::twin::scan_and_place`].

use super::layout::{
    ADAPTIVE_SEGMENT_LANES, FrameStats, GpuCamera, GpuComb, GpuFrame, GpuLineStyle, GpuTessParams,
    GpuVertex, MAX_SAMPLES_PER_SEGMENT, SCAN_BLOCK, TESSELLATE_KERNELS, TESSELLATE_WORKGROUP_SIZE,
    WORK_HEADER,
};
use super::tessellator::{compute_pipelines, control_points_buffer, dispatch_grid};
use super::{GpuError, shaders};
use crate::chunks::TessChunk;

/// The default tolerance: a drawn polyline stays within this many pixels of its curve.
pub const DEFAULT_TOLERANCE_PX: f64 = 0.25;

/// The smallest tolerance accepted: below it `f32` evaluation noise, not the sampling,
/// decides the distance.
pub const MIN_TOLERANCE_PX: f64 = 0.01;

/// A tolerance that is not a finite number of at least [`MIN_TOLERANCE_PX`].
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error(
    "tolerance {} px: must be a finite number of at least {MIN_TOLERANCE_PX} px",
    splinescope_core::num::Num(*.0)
)]
pub struct ToleranceError(pub f64);

/// Checks a tolerance given by the user.
///
/// # Errors
/// [`ToleranceError`] naming the value when it is not a finite number of at least
/// [`MIN_TOLERANCE_PX`].
pub fn check_tolerance(tolerance_px: f64) -> Result<f64, ToleranceError> {
    if tolerance_px.is_finite() && tolerance_px >= MIN_TOLERANCE_PX {
        Ok(tolerance_px)
    } else {
        Err(ToleranceError(tolerance_px))
    }
}

/// The passes' pipelines.
#[derive(Debug, Clone)]
pub struct AdaptiveTessellator {
    layout: wgpu::BindGroupLayout,
    count: wgpu::ComputePipeline,
    scan_blocks: wgpu::ComputePipeline,
    scan_sums: wgpu::ComputePipeline,
    finalize: wgpu::ComputePipeline,
    kernels: Vec<wgpu::ComputePipeline>,
    /// The comb passes: for the cubic classes, the other narrow ones and the general one.
    comb: [wgpu::ComputePipeline; 3],
    comb_layout: wgpu::BindGroupLayout,
    max_groups_per_dim: u32,
}

/// One chunk's curvature comb: the hairs (two vertices per sample: the curve's point and
/// the hair's tip), the envelope (the tips, one per sample, in the samples' order) and the
/// hairs' indirect draw arguments, written by the comb pass from the chunk's placed
/// samples every frame.
#[derive(Debug)]
pub struct CombChunk {
    /// `2 × capacity` vertices.
    pub hairs: wgpu::Buffer,
    /// `capacity` vertices.
    pub envelope: wgpu::Buffer,
    /// The line-list draws, then the comb layer rasterizer's dispatch (at
    /// [`super::layout::COMB_RASTER_ARGS_OFFSET`]): `[2 × hairs, 1, 0, 0, 2 × envelope
    /// pieces, 1, 0, 0, workgroups, 1, 1, 0]`.
    pub args: wgpu::Buffer,
    uniform: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    /// The samples the buffers hold (the chunk's capacity when they were made).
    pub capacity: u32,
}

/// One chunk's buffers for adaptive tessellation and drawing.
#[derive(Debug)]
pub struct AdaptiveChunk {
    /// The control points (rewritable in place).
    pub points: wgpu::Buffer,
    segments: wgpu::Buffer,
    frame: wgpu::Buffer,
    /// Indirect draw arguments and statistics, then the passes' scratch.
    pub work: wgpu::Buffer,
    /// The samples, in drawing order; `capacity` of them at most.
    pub samples: wgpu::Buffer,
    /// Samples the buffer holds.
    pub capacity: u32,
    segment_count: u32,
    cull_margin_px: f32,
    /// The widest line of the chunk whose width is in scene units (0 when none): its
    /// pixels depend on the view, so the margin is found each frame.
    widest_in_scene: f32,
    /// The pass for counting, scanning and placing (range unused), then one per kernel
    /// class: `(kernel, bind group, grid, range buffer)`.
    base: wgpu::BindGroup,
    dispatches: Vec<(usize, wgpu::BindGroup, (u32, u32), wgpu::Buffer)>,
    ranges: Vec<(usize, GpuTessParams)>,
    base_range: wgpu::Buffer,
}

/// The passes, in order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stage {
    /// Each segment's count.
    Count,
    /// The prefix sum and the placement (offsets, final counts, draw arguments).
    Place,
    /// The samples.
    Tessellate,
}

/// The per-frame settings: camera and tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameSettings {
    /// The camera uniform of the frame.
    pub camera: GpuCamera,
    /// The tolerance in pixels.
    pub tolerance_px: f32,
    /// The fewest samples a segment on screen gets ([`GpuFrame::min_count`]).
    pub min_count: u32,
}

/// Samples a chunk's buffer starts with: room for its segments' object-space automatic
/// counts, twice (zooming in asks for more), and at least 2 per segment (the minimum
/// the cap keeps), within the device's limit.
#[must_use]
pub fn initial_capacity(chunk: &TessChunk, max_samples: u64) -> u32 {
    let want = (2 * u64::from(chunk.sample_count))
        .max(2 * chunk.segments.len() as u64)
        .max(2);
    want.min(max_samples).min(u64::from(u32::MAX)) as u32
}

impl AdaptiveTessellator {
    /// Builds the pipelines of `shaders/adaptive.wgsl` on `device`.
    #[must_use]
    pub fn new(device: &wgpu::Device) -> AdaptiveTessellator {
        let module = shaders::ADAPTIVE.module(device);
        let passes = ["count", "scan_blocks", "scan_sums", "finalize"];
        let entries: Vec<&str> = passes
            .into_iter()
            .chain(TESSELLATE_KERNELS.iter().map(|(e, _, _)| *e))
            .collect();
        let (layout, mut pipelines) = compute_pipelines(
            device,
            "adaptive",
            &module,
            &super::bindings::adaptive()[0],
            &entries,
        );
        let kernels = pipelines.split_off(passes.len());
        let layouts = super::bindings::adaptive();
        let comb_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("comb"),
            entries: &layouts[1],
        });
        let comb_pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("comb"),
            bind_group_layouts: &[Some(&layout), Some(&comb_layout)],
            immediate_size: 0,
        });
        let comb_module = shaders::COMB.module(device);
        let comb = ["comb_cubic", "comb_narrow", "comb_wide"].map(|entry| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&comb_pipeline_layout),
                module: &comb_module,
                entry_point: Some(entry),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                cache: None,
            })
        });
        let [count, scan_blocks, scan_sums, finalize]: [wgpu::ComputePipeline; 4] = pipelines
            .try_into()
            .unwrap_or_else(|_| unreachable!("four passes"));
        AdaptiveTessellator {
            count,
            scan_blocks,
            scan_sums,
            finalize,
            kernels,
            comb,
            comb_layout,
            layout,
            max_groups_per_dim: device.limits().max_compute_workgroups_per_dimension,
        }
    }

    /// Uploads one chunk's control points and segment table, with a sample buffer of
    /// `capacity` samples. `sample_usage` is added to the samples' `STORAGE` usage.
    #[must_use]
    pub fn upload(
        &self,
        device: &wgpu::Device,
        chunk: &TessChunk,
        capacity: u32,
        sample_usage: wgpu::BufferUsages,
    ) -> AdaptiveChunk {
        let points = control_points_buffer(device, chunk);
        let segments = super::init_buffer(
            device,
            "adaptive segments",
            bytemuck::cast_slice(&pad(&chunk.segments)),
            wgpu::BufferUsages::STORAGE,
        );
        let n = chunk.segments.len() as u32;
        let blocks = n.div_ceil(SCAN_BLOCK).max(1);
        let work_words = WORK_HEADER as u64 + 3 * u64::from(n) + 2 * u64::from(blocks);
        let mut header = vec![0u32; work_words as usize];
        header[0] = super::layout::LINE_CORNERS;
        let work = super::init_buffer(
            device,
            "adaptive work",
            bytemuck::cast_slice(&header),
            wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::INDIRECT
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
        );
        let frame = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("adaptive frame"),
            size: size_of::<GpuFrame>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let ranges = ranges(chunk);
        let in_scene = |s: &&GpuLineStyle| s.flags & crate::layout::LINE_WIDTH_IN_SCENE != 0;
        // The widest reach of a line: its width, times how far its ends and corners
        // reach past half of it (a square cap's corner √2, a miter's tip its limit).
        let reach = |s: &GpuLineStyle| s.width_px * crate::layout::stroke_reach(s.flags);
        let widest = chunk
            .styles
            .iter()
            .filter(|s| !in_scene(s))
            .map(reach)
            .fold(0.0_f32, f32::max);
        let widest_in_scene = chunk
            .styles
            .iter()
            .filter(in_scene)
            .map(reach)
            .fold(0.0_f32, f32::max);
        let base_range = super::init_buffer(
            device,
            "adaptive range",
            bytemuck::bytes_of(&GpuTessParams {
                record_start: 0,
                record_end: n,
                groups_x: 0,
                _padding: 0,
            }),
            wgpu::BufferUsages::UNIFORM,
        );
        let samples = sample_buffer(device, capacity, sample_usage);
        let (base, dispatches) = self.bind(
            device,
            [&frame, &points, &segments, &work, &samples],
            &base_range,
            &ranges,
        );
        AdaptiveChunk {
            samples,
            points,
            segments,
            frame,
            work,
            capacity,
            segment_count: n,
            cull_margin_px: 0.5 * widest + 1.0,
            widest_in_scene,
            base,
            dispatches,
            ranges,
            base_range,
        }
    }

    /// The bind groups over a chunk's buffers `[frame, points, segments, work, samples]`:
    /// the counting pass's and one per kernel class range.
    #[allow(clippy::type_complexity)]
    fn bind(
        &self,
        device: &wgpu::Device,
        [frame, points, segments, work, samples]: [&wgpu::Buffer; 5],
        base_range: &wgpu::Buffer,
        ranges: &[(usize, GpuTessParams)],
    ) -> (
        wgpu::BindGroup,
        Vec<(usize, wgpu::BindGroup, (u32, u32), wgpu::Buffer)>,
    ) {
        let group = |range: &wgpu::Buffer| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("adaptive"),
                layout: &self.layout,
                entries: &[
                    entry(0, frame),
                    entry(1, range),
                    entry(2, points),
                    entry(3, segments),
                    entry(4, work),
                    entry(5, samples),
                ],
            })
        };
        let dispatches = ranges
            .iter()
            .map(|&(kernel, params)| {
                let grid = dispatch_grid(
                    adaptive_groups(kernel, params.record_end - params.record_start),
                    self.max_groups_per_dim,
                );
                let params = GpuTessParams {
                    groups_x: grid.0,
                    ..params
                };
                let buffer = super::init_buffer(
                    device,
                    "adaptive range",
                    bytemuck::bytes_of(&params),
                    wgpu::BufferUsages::UNIFORM,
                );
                (kernel, group(&buffer), grid, buffer)
            })
            .collect();
        (group(base_range), dispatches)
    }

    /// Replaces a chunk's sample buffer by one of `capacity` samples (the contents are
    /// rewritten by the next frame).
    pub fn grow(
        &self,
        device: &wgpu::Device,
        chunk: &mut AdaptiveChunk,
        capacity: u32,
        sample_usage: wgpu::BufferUsages,
    ) {
        chunk.samples = sample_buffer(device, capacity, sample_usage);
        chunk.capacity = capacity;
        let (base, dispatches) = self.bind(
            device,
            [
                &chunk.frame,
                &chunk.points,
                &chunk.segments,
                &chunk.work,
                &chunk.samples,
            ],
            &chunk.base_range,
            &chunk.ranges,
        );
        chunk.base = base;
        chunk.dispatches = dispatches;
    }

    /// Writes each chunk's frame uniform for `settings`.
    pub fn prepare<'a>(
        &self,
        queue: &wgpu::Queue,
        chunks: impl IntoIterator<Item = &'a AdaptiveChunk>,
        settings: &FrameSettings,
    ) {
        for c in chunks {
            queue.write_buffer(&c.frame, 0, bytemuck::bytes_of(&c.frame_uniform(settings)));
        }
    }

    /// Records the passes for every chunk in one compute pass.
    pub fn encode<'a>(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        chunks: impl IntoIterator<Item = &'a AdaptiveChunk>,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.encode_until(encoder, chunks, timestamp_writes, Stage::Tessellate);
    }

    /// Records the passes up to and including `last` (tests compare each stage with its
    /// twin).
    pub fn encode_until<'a>(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        chunks: impl IntoIterator<Item = &'a AdaptiveChunk>,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
        last: Stage,
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("adaptive tessellation"),
            timestamp_writes,
        });
        let chunks: Vec<&AdaptiveChunk> = chunks.into_iter().collect();
        self.record_count(&mut pass, &chunks);
        if last != Stage::Count {
            self.record_place(&mut pass, &chunks);
        }
        if last == Stage::Tessellate {
            self.record_tessellate(&mut pass, &chunks);
        }
    }

    /// The count pass of every chunk.
    fn record_count(&self, pass: &mut wgpu::ComputePass<'_>, chunks: &[&AdaptiveChunk]) {
        pass.set_pipeline(&self.count);
        for c in chunks.iter().filter(|c| c.segment_count > 0) {
            pass.set_bind_group(0, &c.base, &[]);
            pass.dispatch_workgroups(c.segment_count.div_ceil(64), 1, 1);
        }
    }

    /// The prefix sum and placement of every chunk.
    fn record_place(&self, pass: &mut wgpu::ComputePass<'_>, chunks: &[&AdaptiveChunk]) {
        for c in chunks.iter().filter(|c| c.segment_count > 0) {
            pass.set_bind_group(0, &c.base, &[]);
            pass.set_pipeline(&self.scan_blocks);
            pass.dispatch_workgroups(c.segment_count.div_ceil(SCAN_BLOCK), 1, 1);
            pass.set_pipeline(&self.scan_sums);
            pass.dispatch_workgroups(1, 1, 1);
            pass.set_pipeline(&self.finalize);
            pass.dispatch_workgroups(c.segment_count.div_ceil(64), 1, 1);
        }
    }

    /// The de Casteljau kernels of every chunk, one dispatch per degree class.
    fn record_tessellate(&self, pass: &mut wgpu::ComputePass<'_>, chunks: &[&AdaptiveChunk]) {
        for c in chunks.iter().filter(|c| c.segment_count > 0) {
            for (kernel, group, grid, _) in &c.dispatches {
                pass.set_pipeline(&self.kernels[*kernel]);
                pass.set_bind_group(0, group, &[]);
                pass.dispatch_workgroups(grid.0, grid.1, 1);
            }
        }
    }
}

impl AdaptiveTessellator {
    /// A comb for `chunk`: buffers for its capacity and the pass's bind group.
    /// `usage` is added to the hairs' and envelope's `STORAGE` usage.
    #[must_use]
    pub fn comb_chunk(
        &self,
        device: &wgpu::Device,
        chunk: &AdaptiveChunk,
        usage: wgpu::BufferUsages,
    ) -> CombChunk {
        let vertices = |label: &str, count: u64| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: count.max(2) * size_of::<GpuVertex>() as u64,
                usage: wgpu::BufferUsages::STORAGE | usage,
                mapped_at_creation: false,
            })
        };
        let capacity = chunk.capacity;
        let hairs = vertices("comb hairs", 2 * u64::from(capacity));
        let envelope = vertices("comb envelope", u64::from(capacity));
        let args = super::init_buffer(
            device,
            "comb draw",
            bytemuck::cast_slice(&[0u32, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0]),
            wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::INDIRECT | usage,
        );
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("comb"),
            size: size_of::<GpuComb>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("comb"),
            layout: &self.comb_layout,
            entries: &[
                entry(0, &uniform),
                entry(1, &hairs),
                entry(2, &envelope),
                entry(3, &args),
            ],
        });
        CombChunk {
            hairs,
            envelope,
            args,
            uniform,
            bind_group,
            capacity,
        }
    }

    /// Sets a comb's scale (world length of a hair per unit of curvature), its cap (the
    /// longest hair, world units) and the curve it is drawn for
    /// ([`super::layout::COMB_ALL`], [`super::layout::COMB_NONE`] or a chunk-local tag).
    pub fn write_comb(
        &self,
        queue: &wgpu::Queue,
        comb: &CombChunk,
        (scale, cap): (f32, f32),
        curve: u32,
    ) {
        let uniform = GpuComb {
            scale,
            cap,
            curve,
            _padding: 0,
        };
        queue.write_buffer(&comb.uniform, 0, bytemuck::bytes_of(&uniform));
    }

    /// Records the comb pass of each `(chunk, comb)` pair, after the chunk's tessellation
    /// (it reads the placed counts and offsets).
    pub fn encode_comb<'a>(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        pairs: impl IntoIterator<Item = (&'a AdaptiveChunk, &'a CombChunk)>,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("curvature comb"),
            timestamp_writes,
        });
        for (chunk, comb) in pairs {
            // Per kernel class range, as the tessellation: the narrow pass where the
            // tessellation shares a workgroup among segments.
            for (kernel, group, grid, _) in &chunk.dispatches {
                let pipeline = match TESSELLATE_KERNELS.get(*kernel) {
                    Some((_, Some(3), _)) => 0,
                    Some((_, Some(_), _)) => 1,
                    _ => 2,
                };
                pass.set_pipeline(&self.comb[pipeline]);
                pass.set_bind_group(0, group, &[]);
                pass.set_bind_group(1, &comb.bind_group, &[]);
                pass.dispatch_workgroups(grid.0, grid.1, 1);
            }
        }
    }
}

impl AdaptiveTessellator {
    /// Records the passes as three compute passes — counting, scanning and placing,
    /// tessellating — each with its own timestamp writes (the viewer's per-stage times).
    pub fn encode_staged(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        chunks: &[&AdaptiveChunk],
        writes: [Option<wgpu::ComputePassTimestampWrites<'_>>; 3],
    ) {
        let labels = ["adaptive count", "adaptive scan", "adaptive tessellate"];
        for (stage, (label, timestamp_writes)) in labels.into_iter().zip(writes).enumerate() {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(label),
                timestamp_writes,
            });
            match stage {
                0 => self.record_count(&mut pass, chunks),
                1 => self.record_place(&mut pass, chunks),
                _ => self.record_tessellate(&mut pass, chunks),
            }
        }
    }
}

impl AdaptiveChunk {
    /// How far outside the viewport, in pixels, a segment may lie and still be drawn: half
    /// the widest line and a pixel. A width in scene units spans a fixed number of pixels
    /// in a 2D view (`w = 1`); in a perspective view it grows without bound near the eye,
    /// so nothing is culled for it there.
    fn cull_margin(&self, camera: &crate::layout::GpuCamera) -> f32 {
        let px = self.cull_margin_px * camera.width_scale;
        if self.widest_in_scene == 0.0 {
            return px;
        }
        let m = camera.clip_from_world;
        let perspective = m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0;
        if perspective {
            return f32::MAX;
        }
        let style = GpuLineStyle {
            color: [0.0; 4],
            width_px: self.widest_in_scene,
            dash_px: 0.0,
            order: 0,
            flags: crate::layout::LINE_WIDTH_IN_SCENE,
        };
        px.max(crate::layer_twin::half_width_px(&style, camera, 1.0) + 1.0)
    }

    /// The frame uniform of this chunk for `settings`.
    #[must_use]
    pub fn frame_uniform(&self, settings: &FrameSettings) -> GpuFrame {
        GpuFrame {
            clip_from_world: settings.camera.clip_from_world,
            viewport_px: settings.camera.viewport_px,
            tolerance_px: settings.tolerance_px,
            cull_margin_px: self.cull_margin(&settings.camera),
            segment_count: self.segment_count,
            capacity: self.capacity,
            max_count: MAX_SAMPLES_PER_SEGMENT,
            min_count: settings.min_count,
        }
    }

    /// Segments in the chunk.
    #[must_use]
    pub fn segment_count(&self) -> u32 {
        self.segment_count
    }
}

/// The dispatch ranges of each non-empty kernel class of `chunk`'s segments.
fn ranges(chunk: &TessChunk) -> Vec<(usize, GpuTessParams)> {
    let mut out = Vec::new();
    let mut start = 0u32;
    for (kernel, &end) in chunk.segment_class_ends.iter().enumerate() {
        if end > start {
            out.push((
                kernel,
                GpuTessParams {
                    record_start: start,
                    record_end: end,
                    groups_x: 0,
                    _padding: 0,
                },
            ));
        }
        start = start.max(end);
    }
    out
}

fn entry(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: buffer.as_entire_binding(),
    }
}

fn sample_buffer(device: &wgpu::Device, capacity: u32, usage: wgpu::BufferUsages) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("adaptive samples"),
        size: u64::from(capacity.max(2)) * size_of::<GpuVertex>() as u64,
        usage: wgpu::BufferUsages::STORAGE | usage,
        mapped_at_creation: false,
    })
}

/// Workgroups the adaptive kernel `kernel` (index in [`TESSELLATE_KERNELS`]) needs for
/// `segments` segments: the single-degree kernels tessellate several segments per
/// workgroup ([`ADAPTIVE_SEGMENT_LANES`] invocations each), the general kernel one.
#[must_use]
pub fn adaptive_groups(kernel: usize, segments: u32) -> u32 {
    match TESSELLATE_KERNELS.get(kernel) {
        Some((_, Some(_), _)) => {
            segments.div_ceil(TESSELLATE_WORKGROUP_SIZE / ADAPTIVE_SEGMENT_LANES)
        }
        _ => segments,
    }
}

/// Storage bindings may not be empty: an empty list becomes one zeroed element.
fn pad<T: bytemuck::Pod + bytemuck::Zeroable>(items: &[T]) -> Vec<T> {
    if items.is_empty() {
        vec![T::zeroed()]
    } else {
        items.to_vec()
    }
}

/// Reads a chunk's whole work buffer: the header ([`FrameStats`]), then each segment's
/// count, then the scan pairs (after [`Stage::Place`]: each segment's offset and the drawn
/// segments before it), then the block pairs.
///
/// # Errors
/// [`GpuError::Readback`] when mapping fails.
pub fn read_work(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    chunk: &AdaptiveChunk,
) -> Result<Vec<u32>, GpuError> {
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("read work"),
    });
    super::tessellator::read_buffer(device, queue, &mut encoder, &chunk.work)
}

/// Reads the statistics the last frame left in `chunk`'s work buffer (waits for the GPU:
/// for tests, offscreen renders and `--stats`, not for the window's frames).
///
/// # Errors
/// [`GpuError::Readback`] when mapping fails.
pub fn read_stats(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    chunk: &AdaptiveChunk,
) -> Result<FrameStats, GpuError> {
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("read stats"),
    });
    let words: Vec<u32> =
        super::tessellator::read_buffer(device, queue, &mut encoder, &chunk.work)?;
    Ok(*bytemuck::from_bytes(bytemuck::cast_slice(
        &words[..WORK_HEADER],
    )))
}
