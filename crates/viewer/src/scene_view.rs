//! The scene on the GPU for the viewer: uploaded once, then kept in step with edits and
//! the panel's switches (curves rewritten in place when their structure is unchanged),
//! tessellated and drawn every frame.

use super::edit::Changes;
use super::interaction::Toggles;
use super::readback::Readback;
use crate::app_error::AppError;
use crate::digest;
use crate::shape::{MarkerWorker, ShapeView};
use splinescope_core::geom::{BezierSegment, Lower};
use splinescope_encoding::draw::{Switches, axis_polylines};
use splinescope_gpu::adaptive::FrameSettings;
use splinescope_gpu::chunks::ChunkLimits;
use splinescope_gpu::layout::{FrameStats, WORK_HEADER};
use splinescope_gpu::overlays::{OverlayEdit, prepare_overlays_mapped};
use splinescope_gpu::pack::curve_tags;
use splinescope_gpu::pack::{PreparedScene, prepare, repack_points};
use splinescope_gpu::renderer::{CombRequest, GpuScene, Renderer};
use splinescope_gpu::{GpuContext, GpuError, Pipelines};
use splinescope_scene::format::Scene;
use splinescope_scene::format::draw::{curve_overlays, draw_list_with};
use splinescope_scene::format::encoding::encode_with;
use splinescope_scene::format::shape::marker_points;
use std::time::Instant;

/// What the GPU holds of the scene, and the panel's per-curve summaries.
pub(crate) struct SceneView {
    pub renderer: Renderer,
    pub gpu: GpuScene,
    pub prepared: PreparedScene,
    /// The overlay switches the GPU's overlays were built with.
    uploaded: Switches,
    /// What the panel and canvas overlay show of the scene, derived on each change.
    pub digest: digest::SceneDigest,
    stats: StatsReader,
    /// The chunks' statistics of a recent frame (read back without waiting).
    pub last_stats: Vec<FrameStats>,
    /// What the GPU scene's comb was set from — on, selected only, scale, the selected
    /// curve — (`None`: not yet set on this upload), so that the request (and the selected
    /// curve's tags) is made again only when one of them changes, not every frame.
    comb_applied: Option<(bool, bool, u64, u64, Option<usize>)>,
    /// The shape markers, computed off the frame thread.
    pub markers: MarkerWorker,
    /// Whether the GPU scene holds the current markers.
    markers_uploaded: bool,
}

/// Reads the chunks' frame statistics back a few frames late, never waiting for the GPU.
struct StatsReader {
    readback: Option<Readback>,
}

const STATS_BYTES: u64 = (WORK_HEADER * 4) as u64;

impl StatsReader {
    fn new() -> StatsReader {
        StatsReader { readback: None }
    }

    /// Records copies of every chunk's statistics when no read is in flight; whether it did.
    fn record(
        &mut self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        gpu: &GpuScene,
    ) -> bool {
        if gpu.chunks.is_empty() || self.readback.as_ref().is_some_and(|r| !r.idle()) {
            return false;
        }
        let size = STATS_BYTES * gpu.chunks.len() as u64;
        let readback = match &mut self.readback {
            Some(r) if r.staging().size() == size => r,
            slot => slot.insert(Readback::new(&ctx.device, "frame statistics", size)),
        };
        for (i, c) in gpu.chunks.iter().enumerate() {
            encoder.copy_buffer_to_buffer(
                &c.adaptive.work,
                0,
                readback.staging(),
                i as u64 * STATS_BYTES,
                STATS_BYTES,
            );
        }
        true
    }

    /// After the recorded copies were submitted: asks for the mapping.
    fn request(&mut self) {
        if let Some(r) = &mut self.readback {
            r.request();
        }
    }

    /// The statistics, once the mapping completed.
    fn take(&mut self) -> Option<Vec<FrameStats>> {
        self.readback.as_mut()?.take()
    }
}

impl SceneView {
    pub fn new(
        ctx: &GpuContext,
        pipelines: &Pipelines,
        format: wgpu::TextureFormat,
        scene: &Scene,
        toggles: Toggles,
    ) -> Result<SceneView, AppError> {
        let renderer = Renderer::new(&ctx.device, pipelines, format);
        let switches = switches(toggles);
        let (gpu, prepared) = upload(ctx, &renderer, scene, switches)?;
        Ok(SceneView {
            renderer,
            gpu,
            prepared,
            uploaded: switches,
            digest: digest::SceneDigest::of(scene),
            stats: StatsReader::new(),
            last_stats: Vec::new(),
            comb_applied: None,
            markers: MarkerWorker::default(),
            markers_uploaded: true,
        })
    }

    /// Brings the comb and the markers up to date with the panel's shape switches
    /// (`selected` for a comb on the selected curve alone, its cap a fraction of a view
    /// `view_height` world units tall); `changed` says the scene was
    /// edited this frame (the markers are then recomputed, throttled, off this thread).
    pub fn sync_shape(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        changed: bool,
        (shape, view_height): (&ShapeView, f64),
        selected: Option<usize>,
    ) {
        // The cap follows the view (a fraction of its height).
        let cap = (shape.comb_cap.world(view_height) as f32).min(f32::MAX);
        let key = (
            shape.comb,
            shape.comb_selected_only,
            shape.comb_scale.to_bits(),
            u64::from(cap.to_bits()),
            selected.filter(|_| shape.comb_selected_only),
        );
        if self.comb_applied != Some(key) {
            let request = shape.comb.then(|| CombRequest {
                scale: shape.comb_scale as f32,
                cap,
                only: shape.comb_selected_only.then(|| {
                    selected
                        .map(|s| curve_tags(&self.prepared, s))
                        .unwrap_or_default()
                }),
            });
            self.gpu.set_comb(ctx, &self.renderer, request.as_ref());
            self.comb_applied = Some(key);
        }
        self.markers
            .poll(scene, changed, shape.marker_options(), Instant::now());
        let fresh = self.markers.take_fresh().is_some();
        if fresh || !self.markers_uploaded {
            let points = marker_points(scene, &self.markers.markers);
            self.renderer.set_markers(ctx, &mut self.gpu, &points);
            self.markers_uploaded = true;
        }
    }

    /// Brings the GPU up to date with the `changes` of `scene` and the panel's switches:
    /// curves whose lowering kept its structure are rewritten in place (each lowered
    /// once, for the GPU and the panel alike); otherwise (or when curves were added or
    /// removed, or an overlay switch changed) the scene is packed again. The scene is never
    /// copied: the switches are applied as the overlays are built.
    pub fn sync(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        changes: &Changes,
        toggles: Toggles,
    ) -> Result<(), AppError> {
        let switches = switches(toggles);
        if changes.is_empty() && switches == self.uploaded {
            return Ok(());
        }
        let mut lowered = Vec::with_capacity(changes.curves.len());
        let in_place = switches == self.uploaded
            && !changes.list
            && changes.curves.iter().all(|&c| {
                let segments = scene.curves[c].curve.lower();
                let ok = self.rewrite_in_place(ctx, scene, c, &segments);
                lowered.push((c, segments));
                ok
            });
        // The panel's digest first: its facts hold the 3D axis triad the overlays need, so
        // the scene's bounds are walked once per edit.
        self.digest.update(scene, changes, &lowered);
        if in_place {
            self.sync_overlays(ctx, scene, &changes.curves, switches);
        } else {
            let (gpu, prepared) = upload(ctx, &self.renderer, scene, switches)?;
            self.gpu = gpu;
            self.prepared = prepared;
            self.uploaded = switches;
            // A new GPU scene has no comb and no markers yet.
            self.comb_applied = None;
            self.markers_uploaded = false;
            // Statistics of the old chunks no longer apply.
            self.stats = StatsReader::new();
            self.last_stats.clear();
        }
        Ok(())
    }

    /// Brings the overlays up to date after in-place edits of `curves`: their polylines
    /// and points (and the 3D axis triad) are written over the old ones when they keep
    /// their shape; otherwise every overlay is packed again.
    fn sync_overlays(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        curves: &[usize],
        switches: Switches,
    ) {
        let edit = OverlayEdit {
            switches,
            curve_count: scene.curves.len(),
            curves: curves
                .iter()
                .map(|&c| (c, curve_overlays(&scene.curves[c], switches)))
                .collect(),
            axes: axis_polylines(&self.digest.facts.axes),
        };
        if let Some((lines, points)) = self.prepared.overlay_map.rewrite(&edit) {
            self.gpu.write_overlays(&ctx.queue, &lines, &points);
            return;
        }
        let limits = ChunkLimits::for_binding_size(ctx.max_binding_bytes());
        let (lines, points, map) =
            prepare_overlays_mapped(&draw_list_with(scene, switches), switches, limits);
        self.renderer
            .replace_overlays(&ctx.device, &mut self.gpu, &lines, &points);
        self.prepared.lines = lines;
        self.prepared.points = points;
        self.prepared.overlay_map = map;
    }

    /// Writes curve `c`'s new points (its lowering, `segments`) where its samples already
    /// are; `false` when its structure changed (segment count, degree or samples).
    fn rewrite_in_place(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        c: usize,
        segments: &[BezierSegment],
    ) -> bool {
        let writes = self
            .prepared
            .placements
            .get(c)
            .zip(self.prepared.sample_counts.get(c))
            .and_then(|(p, n)| repack_points(p, n, segments, scene.samples_for(c)));
        let Some(writes) = writes else {
            return false;
        };
        for (chunk, first, verts) in writes {
            self.gpu.write_points(&ctx.queue, chunk, first, &verts);
        }
        true
    }

    /// Takes the statistics of an earlier frame if they arrived, growing the chunks whose
    /// samples did not fit.
    pub fn poll_stats(&mut self, ctx: &GpuContext) {
        if let Some(stats) = self.stats.take() {
            if stats.len() == self.gpu.chunks.len() {
                self.gpu.grow(ctx, &self.renderer, &stats);
            }
            self.last_stats = stats;
        }
    }

    /// Records the frame's adaptive tessellation (every chunk, for the camera and
    /// tolerance of `settings`) into `encoder`, and a copy of its statistics when none is
    /// in flight; returns whether it copied them ([`SceneView::after_submit`] then).
    pub fn encode_tessellation(
        &mut self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        settings: &FrameSettings,
        timestamps: Option<(
            [Option<wgpu::ComputePassTimestampWrites<'_>>; 3],
            splinescope_gpu::renderer::PassSpan<'_>,
            splinescope_gpu::renderer::PassSpan<'_>,
        )>,
    ) -> bool {
        self.gpu.prepare_frame(ctx, &self.renderer, settings);
        match timestamps {
            Some((writes, comb, raster)) => {
                let chunks: Vec<_> = self.gpu.chunks.iter().map(|c| &c.adaptive).collect();
                self.renderer
                    .adaptive()
                    .encode_staged(encoder, &chunks, writes);
                self.gpu
                    .encode_comb_timed(&self.renderer, encoder, Some(comb));
                self.gpu.encode_layer(&self.renderer, encoder, Some(raster));
            }
            None => self.gpu.encode_tessellation(&self.renderer, encoder, None),
        }
        self.stats.record(ctx, encoder, &self.gpu)
    }

    /// After the frame was submitted: maps the statistics copied this frame.
    pub fn after_submit(&mut self) {
        self.stats.request();
    }

    /// The fewest samples a segment on screen gets this frame (room for the comb's hairs).
    pub fn gpu_min_count(&self) -> u32 {
        self.gpu.min_count()
    }

    /// Samples drawn per frame (recent statistics; the buffers' capacity before any).
    pub fn samples_per_frame(&self) -> u64 {
        if self.last_stats.is_empty() {
            return self.gpu.capacity();
        }
        self.last_stats.iter().map(|s| u64::from(s.drawn)).sum()
    }

    /// Line pieces drawn for the curves in a recent frame.
    pub fn pieces_per_frame(&self) -> u64 {
        self.last_stats
            .iter()
            .map(|s| u64::from(s.instance_count))
            .sum()
    }

    /// Whether a recent frame's samples were scaled down to fit the buffers.
    pub fn capped(&self) -> bool {
        self.last_stats.iter().any(|s| s.capped != 0)
    }
}

/// The overlay switches of the panel's toggles.
fn switches(toggles: Toggles) -> Switches {
    Switches {
        polygons: toggles.show_polygons,
        points: toggles.show_points,
    }
}

/// Prepares and uploads the scene with the panel's overlay switches applied.
fn upload(
    ctx: &GpuContext,
    renderer: &Renderer,
    scene: &Scene,
    switches: Switches,
) -> Result<(GpuScene, PreparedScene), AppError> {
    let prepared = prepare(
        &encode_with(scene, switches),
        ChunkLimits::for_binding_size(ctx.max_binding_bytes()),
    )
    .map_err(GpuError::from)?;
    Ok((renderer.upload(ctx, &prepared), prepared))
}
