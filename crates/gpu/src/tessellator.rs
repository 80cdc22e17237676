//! The compute tessellator: uploads [`TessChunk`]s and dispatches
//! `shaders/tessellate.wgsl` over them.

use super::GpuError;
use super::layout::{GpuTessParams, GpuVertex, TESSELLATE_KERNELS};
use super::shaders;
use crate::chunks::TessChunk;

/// The tessellation compute pipelines, one per kernel of [`TESSELLATE_KERNELS`].
#[derive(Debug, Clone)]
pub struct Tessellator {
    layout: wgpu::BindGroupLayout,
    pipelines: Vec<wgpu::ComputePipeline>,
    /// The module the kernels come from, for the write-only kernel.
    module: wgpu::ShaderModule,
    /// The write-only kernel, built the first time a benchmark asks for it (a device that
    /// only draws never compiles it).
    write_only: std::sync::Arc<std::sync::OnceLock<wgpu::ComputePipeline>>,
    max_groups_per_dim: u32,
}

/// One dispatch: a kernel over a range of a chunk's records.
#[derive(Debug)]
struct Dispatch {
    kernel: usize,
    bind_group: wgpu::BindGroup,
    groups: (u32, u32),
    _params: wgpu::Buffer,
}

/// One chunk's buffers on the GPU, ready to dispatch.
#[derive(Debug)]
pub struct ChunkBuffers {
    /// The samples the kernels write (`GpuVertex` each); also read by the line renderer.
    pub samples: wgpu::Buffer,
    /// How many samples.
    pub sample_count: u32,
    /// The control points the kernels read; rewritable in place when curves change
    /// without changing their structure.
    pub points: wgpu::Buffer,
    dispatches: Vec<Dispatch>,
    // Kept alive for the bind groups.
    _segments: wgpu::Buffer,
}

/// The 2D workgroup grid covering `segments` workgroups: `x ≤ max_per_dim`.
#[must_use]
pub fn dispatch_grid(segments: u32, max_per_dim: u32) -> (u32, u32) {
    if segments == 0 {
        return (0, 0);
    }
    let x = segments.min(max_per_dim);
    (x, segments.div_ceil(x))
}

/// One dispatch as the tessellator issues it: the kernel (index in
/// [`TESSELLATE_KERNELS`]), its parameters and its workgroup grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlannedDispatch {
    /// Index in [`TESSELLATE_KERNELS`].
    pub kernel: usize,
    /// The uniform the kernel reads.
    pub params: GpuTessParams,
    /// Workgroups in x and y.
    pub groups: (u32, u32),
}

/// The dispatches that tessellate `chunk`: one per non-empty kernel class, over its range
/// of records, on a grid of at most `max_groups_per_dim` workgroups per dimension. The
/// CPU twin runs the same plan ([`super::twin::dispatch`]).
#[must_use]
pub fn plan(chunk: &TessChunk, max_groups_per_dim: u32) -> Vec<PlannedDispatch> {
    let mut out = Vec::new();
    let mut start = 0u32;
    for (kernel, &end) in chunk.class_ends.iter().enumerate() {
        if end > start {
            let groups = dispatch_grid(end - start, max_groups_per_dim);
            out.push(PlannedDispatch {
                kernel,
                params: GpuTessParams {
                    record_start: start,
                    record_end: end,
                    groups_x: groups.0,
                    _padding: 0,
                },
                groups,
            });
        }
        start = start.max(end);
    }
    out
}

/// The entry point of the write-only kernel in `shaders/tessellate.wgsl`.
pub const WRITE_ONLY: &str = "write_only";

impl Tessellator {
    /// Builds the pipelines of `shaders/tessellate.wgsl` on `device`.
    #[must_use]
    pub fn new(device: &wgpu::Device) -> Tessellator {
        Self::with_module(device, &shaders::TESSELLATE.module(device))
    }

    /// Builds the pipelines from another module with the same entry points and bindings
    /// (the kernel self-test's own tests hand it a deliberately wrong kernel).
    #[must_use]
    pub fn with_module(device: &wgpu::Device, module: &wgpu::ShaderModule) -> Tessellator {
        let entries: Vec<&str> = TESSELLATE_KERNELS.iter().map(|(e, _, _)| *e).collect();
        let (layout, pipelines) = compute_pipelines(
            device,
            "tessellate",
            module,
            &super::bindings::tessellate()[0],
            &entries,
        );
        Tessellator {
            layout,
            pipelines,
            module: module.clone(),
            write_only: std::sync::Arc::default(),
            max_groups_per_dim: device.limits().max_compute_workgroups_per_dimension,
        }
    }

    /// Whether the write-only kernel has been built (only a benchmark's first
    /// [`Tessellator::encode_write_only`] builds it).
    #[must_use]
    pub fn write_only_built(&self) -> bool {
        self.write_only.get().is_some()
    }

    /// The write-only kernel's pipeline, built on the first call with the kernels' own
    /// bind group layout.
    fn write_only(&self, device: &wgpu::Device) -> &wgpu::ComputePipeline {
        self.write_only.get_or_init(|| {
            let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(WRITE_ONLY),
                bind_group_layouts: &[Some(&self.layout)],
                immediate_size: 0,
            });
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(WRITE_ONLY),
                layout: Some(&layout),
                module: &self.module,
                entry_point: Some(WRITE_ONLY),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                cache: None,
            })
        })
    }

    /// Uploads one chunk. `sample_usage` is added to the samples buffer's `STORAGE` usage
    /// (`COPY_SRC` to read it back).
    #[must_use]
    pub fn upload(
        &self,
        device: &wgpu::Device,
        chunk: &TessChunk,
        sample_usage: wgpu::BufferUsages,
    ) -> ChunkBuffers {
        let points = control_points_buffer(device, chunk);
        let segments = super::init_buffer(
            device,
            "segments",
            bytemuck::cast_slice(&chunk.records),
            wgpu::BufferUsages::STORAGE,
        );
        let samples = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("samples"),
            size: (u64::from(chunk.sample_count.max(1)) * size_of::<GpuVertex>() as u64),
            usage: wgpu::BufferUsages::STORAGE | sample_usage,
            mapped_at_creation: false,
        });
        let mut dispatches = Vec::new();
        for planned in plan(chunk, self.max_groups_per_dim) {
            let PlannedDispatch {
                kernel,
                params: tess_params,
                groups,
            } = planned;
            {
                let params = super::init_buffer(
                    device,
                    "tessellate params",
                    bytemuck::bytes_of(&tess_params),
                    wgpu::BufferUsages::UNIFORM,
                );
                let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(TESSELLATE_KERNELS[kernel].0),
                    layout: &self.layout,
                    entries: &[
                        wgpu::BindGroupEntry {
                            binding: 0,
                            resource: params.as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 1,
                            resource: points.as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 2,
                            resource: segments.as_entire_binding(),
                        },
                        wgpu::BindGroupEntry {
                            binding: 3,
                            resource: samples.as_entire_binding(),
                        },
                    ],
                });
                dispatches.push(Dispatch {
                    kernel,
                    bind_group,
                    groups,
                    _params: params,
                });
            }
        }
        ChunkBuffers {
            samples,
            sample_count: chunk.sample_count,
            points,
            dispatches,
            _segments: segments,
        }
    }

    /// Records one compute pass dispatching each chunk's kernel classes.
    pub fn encode<'a>(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        chunks: impl IntoIterator<Item = &'a ChunkBuffers>,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.record(encoder, chunks, timestamp_writes, None);
    }

    /// Records one compute pass dispatching the write-only kernel (`write_only` in
    /// `shaders/tessellate.wgsl`) over exactly the records and invocations
    /// [`Tessellator::encode`] dispatches: the adapter's bound for this output, against
    /// which the kernels are measured. Sample `j` of a record gets `(u_j, 0, 0)`.
    pub fn encode_write_only<'a>(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        chunks: impl IntoIterator<Item = &'a ChunkBuffers>,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.record(
            encoder,
            chunks,
            timestamp_writes,
            Some(self.write_only(device)),
        );
    }

    /// One pass over every dispatch of `chunks`, each with its class's kernel or with
    /// `instead`.
    fn record<'a>(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        chunks: impl IntoIterator<Item = &'a ChunkBuffers>,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
        instead: Option<&wgpu::ComputePipeline>,
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(if instead.is_some() {
                "write only"
            } else {
                "tessellate"
            }),
            timestamp_writes,
        });
        for chunk in chunks {
            for d in &chunk.dispatches {
                pass.set_pipeline(instead.unwrap_or(&self.pipelines[d.kernel]));
                pass.set_bind_group(0, &d.bind_group, &[]);
                pass.dispatch_workgroups(d.groups.0, d.groups.1, 1);
            }
        }
    }

    /// Tessellates each chunk in turn and reads its samples back (one chunk's buffers
    /// alive at a time, so memory stays bounded however many chunks there are). Every
    /// sample buffer is first filled with a poison value, so a sample the kernel fails to
    /// write shows up as `NaN` with tag `u32::MAX`.
    ///
    /// # Errors
    /// [`GpuError::Readback`] when mapping fails.
    pub fn tessellate_and_read(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        chunks: &[TessChunk],
        mut sink: impl FnMut(usize, &[GpuVertex]),
    ) -> Result<(), GpuError> {
        for (index, chunk) in chunks.iter().enumerate() {
            let buffers = self.upload(
                device,
                chunk,
                wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
            );
            let poison = vec![POISON; chunk.sample_count as usize];
            queue.write_buffer(&buffers.samples, 0, bytemuck::cast_slice(&poison));
            let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("tessellate and read"),
            });
            self.encode(&mut encoder, [&buffers], None);
            let samples: Vec<GpuVertex> =
                read_buffer(device, queue, &mut encoder, &buffers.samples)?;
            let _ = encoder;
            sink(index, &samples[..chunk.sample_count as usize]);
        }
        Ok(())
    }
}

/// A chunk's control points on the GPU, rewritable in place (at least one element:
/// storage bindings may not be empty).
#[must_use]
pub(crate) fn control_points_buffer(device: &wgpu::Device, chunk: &TessChunk) -> wgpu::Buffer {
    let empty = [super::layout::GpuControlPoint {
        position: [0.0; 3],
        weight: 1.0,
    }];
    let points = if chunk.points.is_empty() {
        &empty[..]
    } else {
        &chunk.points[..]
    };
    super::init_buffer(
        device,
        "control points",
        bytemuck::cast_slice(points),
        wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
    )
}

/// A bind-group layout from `entries` and one compute pipeline per entry point of
/// `module`, all sharing that layout.
#[must_use]
pub(crate) fn compute_pipelines(
    device: &wgpu::Device,
    label: &str,
    module: &wgpu::ShaderModule,
    layout_entries: &[wgpu::BindGroupLayoutEntry],
    entry_points: &[&str],
) -> (wgpu::BindGroupLayout, Vec<wgpu::ComputePipeline>) {
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: layout_entries,
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let pipelines = entry_points
        .iter()
        .map(|entry| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&pipeline_layout),
                module,
                entry_point: Some(entry),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                cache: None,
            })
        })
        .collect();
    (layout, pipelines)
}

/// What sample buffers hold before the kernel writes them (NaN, tag `u32::MAX`).
pub const POISON: GpuVertex = GpuVertex {
    position: [f32::NAN, f32::NAN, f32::NAN],
    id: u32::MAX,
};

/// Copies `buffer` into a mappable one after the commands in `encoder`, submits, waits and
/// returns its contents. The encoder is replaced by a fresh one.
///
/// # Errors
/// [`GpuError::Readback`] when the wait or the mapping fails.
pub fn read_buffer<T: bytemuck::Pod>(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    encoder: &mut wgpu::CommandEncoder,
    buffer: &wgpu::Buffer,
) -> Result<Vec<T>, GpuError> {
    let size = buffer.size();
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
    let done = std::mem::replace(
        encoder,
        device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None }),
    );
    queue.submit([done.finish()]);
    let slice = staging.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| GpuError::Readback(e.to_string()))?;
    rx.recv()
        .map_err(|e| GpuError::Readback(e.to_string()))?
        .map_err(|e| GpuError::Readback(e.to_string()))?;
    let data = slice
        .get_mapped_range()
        .map_err(|e| GpuError::Readback(e.to_string()))?;
    let out = bytemuck::pod_collect_to_vec::<u8, T>(&data);
    drop(data);
    staging.unmap();
    Ok(out)
}
