//! The CPU twin of `shaders/tessellate.wgsl`: the same layout, the same loop, in `f32`.
//! Tests compare the GPU's output with it (and both with the exact `f64` curves).

use glam::Vec3;

use super::layout::{GpuSegment, GpuVertex, MAX_GPU_DEGREE};

/// `sample_param` of the shader: `u0 (1 − f) + u1 f`, `f = j / (count − 1)`.
#[must_use]
pub fn sample_param(seg: &GpuSegment, j: u32) -> f32 {
    let f = if seg.sample_count > 1 {
        j as f32 / (seg.sample_count - 1) as f32
    } else {
        0.0
    };
    seg.u0 * (1.0 - f) + seg.u1 * f
}

/// Evaluates every sample of every segment into `samples`, exactly as the kernel does.
///
/// # Panics
/// When a record points outside `points` or `samples` (a packing bug).
pub fn tessellate(points: &[GpuVertex], segments: &[GpuSegment], samples: &mut [GpuVertex]) {
    for seg in segments {
        let n = (seg.degree as usize).min(MAX_GPU_DEGREE);
        for j in 0..seg.sample_count {
            let u = sample_param(seg, j);
            let v = 1.0 - u;
            let mut p = [Vec3::ZERO; MAX_GPU_DEGREE + 1];
            for (i, slot) in p.iter_mut().enumerate().take(n + 1) {
                *slot = Vec3::from(points[seg.first_point as usize + i].position);
            }
            for r in 1..=n {
                for i in 0..=(n - r) {
                    p[i] = v * p[i] + u * p[i + 1];
                }
            }
            samples[(seg.first_sample + j) as usize] = GpuVertex {
                position: p[0].to_array(),
                id: seg.curve,
            };
        }
    }
}
