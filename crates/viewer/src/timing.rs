//! Per-stage GPU times of the viewer's frames (count, scan, tessellate, draw, comb,
//! raster) from
//! timestamp queries, where the adapter has them; read back a few frames late without
//! waiting, like the frame statistics.

use super::readback::Readback;
use splinescope_gpu::GpuContext;

/// The stages timed, in the order of their timestamp pairs (the comb's: its comb pass, or
/// an empty pass when no comb is drawn; the raster's: curves and combs into the layer, or
/// an empty pass where there is none).
pub(crate) const STAGES: [&str; 6] = ["count", "scan", "tessellate", "draw", "comb", "raster"];

/// Milliseconds per stage, in the order of [`STAGES`].
pub(crate) type StageMs = [f64; STAGES.len()];

/// Timestamp queries around each stage's pass.
pub(crate) struct StageTimer {
    set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: Readback,
    period_ns: f64,
    /// The last frame's milliseconds per stage.
    pub last_ms: Option<StageMs>,
    sums: StageMs,
    frames: u32,
}

const QUERIES: u32 = 2 * STAGES.len() as u32;

impl StageTimer {
    /// A timer, when the device has timestamp queries.
    pub fn new(ctx: &GpuContext) -> Option<StageTimer> {
        if !ctx
            .device
            .features()
            .contains(wgpu::Features::TIMESTAMP_QUERY)
        {
            return None;
        }
        let size = u64::from(QUERIES) * 8;
        Some(StageTimer {
            set: ctx.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("stage times"),
                ty: wgpu::QueryType::Timestamp,
                count: QUERIES,
            }),
            resolve: ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("stage times"),
                size,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            readback: Readback::new(&ctx.device, "stage times readback", size),
            period_ns: f64::from(ctx.queue.get_timestamp_period()),
            last_ms: None,
            sums: [0.0; STAGES.len()],
            frames: 0,
        })
    }

    /// Whether this frame is timed (no read in flight).
    pub fn active(&self) -> bool {
        self.readback.idle()
    }

    /// The compute passes' timestamp writes (count, scan, tessellate).
    pub fn compute_writes(&self) -> [Option<wgpu::ComputePassTimestampWrites<'_>>; 3] {
        [0u32, 1, 2].map(|stage| {
            Some(wgpu::ComputePassTimestampWrites {
                query_set: &self.set,
                beginning_of_pass_write_index: Some(2 * stage),
                end_of_pass_write_index: Some(2 * stage + 1),
            })
        })
    }

    /// The render pass's timestamp writes (draw).
    pub fn render_writes(&self) -> wgpu::RenderPassTimestampWrites<'_> {
        wgpu::RenderPassTimestampWrites {
            query_set: &self.set,
            beginning_of_pass_write_index: Some(6),
            end_of_pass_write_index: Some(7),
        }
    }

    /// The comb pass's timestamps.
    pub fn comb_span(&self) -> splinescope_gpu::renderer::PassSpan<'_> {
        splinescope_gpu::renderer::PassSpan {
            query_set: &self.set,
            begin: 8,
            end: 9,
        }
    }

    /// The layer pass's timestamps.
    pub fn raster_span(&self) -> splinescope_gpu::renderer::PassSpan<'_> {
        splinescope_gpu::renderer::PassSpan {
            query_set: &self.set,
            begin: 10,
            end: 11,
        }
    }

    /// After the frame's passes: resolves the queries and copies them for reading.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.set, 0..QUERIES, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(
            &self.resolve,
            0,
            self.readback.staging(),
            0,
            self.resolve.size(),
        );
    }

    /// After submission: asks for the mapping.
    pub fn request(&mut self) {
        self.readback.request();
    }

    /// Takes the times when the mapping completed.
    pub fn poll(&mut self) {
        let Some(ticks) = self.readback.take::<u64>() else {
            return;
        };
        let mut ms = [0.0; STAGES.len()];
        for (i, slot) in ms.iter_mut().enumerate() {
            *slot = ticks[2 * i + 1].saturating_sub(ticks[2 * i]) as f64 * self.period_ns * 1e-6;
        }
        for (sum, m) in self.sums.iter_mut().zip(ms) {
            *sum += m;
        }
        self.frames += 1;
        self.last_ms = Some(ms);
    }

    /// The mean milliseconds per stage over every timed frame.
    pub fn mean_ms(&self) -> Option<StageMs> {
        (self.frames > 0).then(|| self.sums.map(|s| s / f64::from(self.frames)))
    }
}
