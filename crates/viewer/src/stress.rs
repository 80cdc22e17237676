//! The viewer's stress mode with solving: every frame each curve's target circles around
//! its original midpoint, the batch solver (paper 000, Eq. 8 at `t_s = 1/2`) re-solves every
//! curve from its original control points, and the new points are written in place into
//! the GPU chunks (the tessellation and drawing then run as every frame).

use std::time::Instant;

use glam::DVec3;

use splinescope_core::geom::Curve;
use splinescope_core::solve::batch::{BatchResult, BatchSingleTarget};
use splinescope_gpu::chunks::Placement;
use splinescope_gpu::layout::GpuControlPoint;
use splinescope_gpu::renderer::GpuScene;
use splinescope_scene::format::Scene;

/// Re-solves a stress scene every frame.
pub(crate) struct StressSolver {
    batch: BatchSingleTarget,
    stride: usize,
    original: Vec<DVec3>,
    anchors: Vec<DVec3>,
    phases: Vec<f64>,
    targets: Vec<DVec3>,
    ts: Vec<f64>,
    out: Vec<DVec3>,
    results: Vec<BatchResult>,
    staging: Vec<Vec<GpuControlPoint>>,
    placements: Vec<Placement>,
    radius: f64,
    /// Milliseconds the last batch took.
    pub last_solve_ms: f64,
    /// Curves solved per frame.
    pub curves: usize,
}

impl StressSolver {
    /// A solver for `scene` if every curve is a Bézier curve of one degree ≥ 2 lowered to
    /// one segment (the stress scenes), with the placements of its packing.
    pub(crate) fn new(
        scene: &Scene,
        placements: &[Vec<Placement>],
        chunk_points: &[usize],
    ) -> Option<StressSolver> {
        let degree = match scene.curves.first().map(|c| &c.curve) {
            Some(Curve::Bezier(b)) => b.degree(),
            _ => return None,
        };
        let batch = BatchSingleTarget::new(degree).ok()?;
        let stride = degree + 1;
        let mut original = Vec::with_capacity(scene.curves.len() * stride);
        let mut anchors = Vec::with_capacity(scene.curves.len());
        let mut flat_placements = Vec::with_capacity(scene.curves.len());
        for (c, sc) in scene.curves.iter().enumerate() {
            let Curve::Bezier(b) = &sc.curve else {
                return None;
            };
            let [p] = placements.get(c)?.as_slice() else {
                return None;
            };
            if b.degree() != degree {
                return None;
            }
            original.extend_from_slice(b.points());
            anchors.push(b.eval(0.5));
            flat_placements.push(*p);
        }
        let n = anchors.len();
        let scale = scene.bounds().diagonal() / (n as f64).sqrt().max(1.0);
        Some(StressSolver {
            batch,
            stride,
            targets: anchors.clone(),
            phases: (0..n)
                .map(|c| c as f64 * 0.618_033_988_75 * std::f64::consts::TAU)
                .collect(),
            ts: vec![0.5; n],
            out: original.clone(),
            results: vec![BatchResult::default(); n],
            staging: chunk_points
                .iter()
                .map(|&len| {
                    vec![
                        GpuControlPoint {
                            position: [0.0; 3],
                            weight: 1.0
                        };
                        len
                    ]
                })
                .collect(),
            placements: flat_placements,
            radius: 0.12 * scale,
            original,
            anchors,
            last_solve_ms: 0.0,
            curves: n,
        })
    }

    /// Moves the targets to time `seconds`, re-solves every curve and writes the new
    /// control points into `gpu`.
    pub(crate) fn step(&mut self, seconds: f64, queue: &wgpu::Queue, gpu: &GpuScene) {
        for ((t, a), phase) in self.targets.iter_mut().zip(&self.anchors).zip(&self.phases) {
            let angle = 2.0 * seconds + phase;
            *t = *a + self.radius * DVec3::new(angle.cos(), angle.sin(), 0.0);
        }
        let started = Instant::now();
        self.batch.solve(
            &self.original,
            &self.targets,
            Some(&self.ts),
            &mut self.out,
            &mut self.results,
        );
        self.last_solve_ms = started.elapsed().as_secs_f64() * 1e3;
        for (c, p) in self.placements.iter().enumerate() {
            let dst = &mut self.staging[p.chunk][p.first_point as usize..][..self.stride];
            for (v, q) in dst
                .iter_mut()
                .zip(&self.out[c * self.stride..(c + 1) * self.stride])
            {
                v.position = q.as_vec3().to_array();
            }
        }
        for (chunk, points) in self.staging.iter().enumerate() {
            gpu.write_points(queue, chunk, 0, points);
        }
    }
}
