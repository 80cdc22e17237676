//! The scene on the GPU for the viewer: uploaded once, then kept in step with edits and
//! the panel's switches (curves rewritten in place when their structure is unchanged),
//! tessellated and drawn every frame.

use super::AppError;
use super::interaction::Toggles;
use super::ui;
use crate::geom::Lower;
use crate::gpu::pack::{
    ChunkLimits, PreparedScene, prepare_overlays, prepare_scene, repack_points,
};
use crate::gpu::renderer::{GpuScene, Renderer};
use crate::gpu::{GpuContext, GpuError};
use crate::scene::Scene;

/// What the GPU holds of the scene, and the panel's per-curve summaries.
pub(crate) struct SceneView {
    pub renderer: Renderer,
    pub gpu: GpuScene,
    pub prepared: PreparedScene,
    uploaded_toggles: Toggles,
    pub summaries: Vec<ui::CurveSummary>,
}

impl SceneView {
    pub fn new(
        ctx: &GpuContext,
        format: wgpu::TextureFormat,
        scene: &Scene,
        toggles: Toggles,
    ) -> Result<SceneView, AppError> {
        let renderer = Renderer::new(&ctx.device, format);
        let (gpu, prepared) = upload(ctx, &renderer, scene, toggles)?;
        Ok(SceneView {
            renderer,
            gpu,
            prepared,
            uploaded_toggles: toggles,
            summaries: ui::summarize(scene),
        })
    }

    /// Brings the GPU up to date with the `changed` curves of `scene` and the panel's
    /// switches: curves whose lowering kept its structure are rewritten in place;
    /// otherwise the scene is packed again. Overlays are rebuilt when anything changed.
    pub fn sync(
        &mut self,
        ctx: &GpuContext,
        scene: &Scene,
        changed: &[usize],
        toggles: Toggles,
    ) -> Result<(), AppError> {
        if changed.is_empty() && toggles == self.uploaded_toggles {
            return Ok(());
        }
        let shown = shown_scene(scene, toggles);
        let in_place = toggles == self.uploaded_toggles
            && changed
                .iter()
                .all(|&c| self.rewrite_in_place(ctx, &shown, c));
        if in_place {
            let limits = ChunkLimits::for_binding_size(ctx.max_binding_bytes());
            let (lines, points) = prepare_overlays(&shown, limits);
            self.renderer
                .replace_overlays(&ctx.device, &mut self.gpu, &lines, &points);
        } else {
            let (gpu, prepared) = upload(ctx, &self.renderer, scene, toggles)?;
            self.gpu = gpu;
            self.prepared = prepared;
            self.uploaded_toggles = toggles;
        }
        ui::refresh(&mut self.summaries, scene, changed);
        Ok(())
    }

    /// Writes curve `c`'s new points where its samples already are; `false` when its
    /// structure changed (segment count, degree or samples).
    fn rewrite_in_place(&mut self, ctx: &GpuContext, shown: &Scene, c: usize) -> bool {
        let segments = shown.curves[c].curve.lower();
        let writes = self
            .prepared
            .placements
            .get(c)
            .zip(self.prepared.sample_counts.get(c))
            .and_then(|(p, n)| repack_points(p, n, &segments, shown.samples_for(c)));
        let Some(writes) = writes else {
            return false;
        };
        for (chunk, first, verts) in writes {
            self.gpu.write_points(&ctx.queue, chunk, first, &verts);
        }
        true
    }

    /// Records the frame's tessellation (every chunk) into `encoder`.
    pub fn encode_tessellation(&self, ctx: &GpuContext, encoder: &mut wgpu::CommandEncoder) {
        ctx.tessellator
            .encode(encoder, self.gpu.chunks.iter().map(|c| &c.buffers), None);
    }
}

/// The scene with the panel's overlay switches applied.
fn shown_scene(scene: &Scene, toggles: Toggles) -> Scene {
    let mut shown = scene.clone();
    for c in &mut shown.curves {
        c.style.show_polygon &= toggles.show_polygons;
        c.style.show_points &= toggles.show_points;
    }
    shown
}

/// Prepares and uploads the scene with the panel's overlay switches applied.
fn upload(
    ctx: &GpuContext,
    renderer: &Renderer,
    scene: &Scene,
    toggles: Toggles,
) -> Result<(GpuScene, PreparedScene), AppError> {
    let shown = shown_scene(scene, toggles);
    let prepared = prepare_scene(
        &shown,
        ChunkLimits::for_binding_size(ctx.max_binding_bytes()),
    )
    .map_err(GpuError::from)?;
    Ok((
        renderer.upload(&ctx.device, &ctx.tessellator, &prepared),
        prepared,
    ))
}
