//! The CPU twin of `shaders/tessellate.wgsl`: the same layout, the same loop, in `f32`.
//! Tests compare the GPU's output with it (and both with the exact `f64` curves).

use glam::Vec3;

use super::layout::{
    GpuRecord, GpuTessParams, GpuVertex, MAX_GPU_DEGREE, TESSELLATE_WORKGROUP_SIZE,
};

/// `sample_param` of the shader: `u0 (1 − f) + u1 f`, `f = j / (count − 1)`.
#[must_use]
pub fn sample_param(seg: &GpuRecord, j: u32) -> f32 {
    let f = if seg.sample_count > 1 {
        j as f32 / (seg.sample_count - 1) as f32
    } else {
        0.0
    };
    seg.u0 * (1.0 - f) + seg.u1 * f
}

/// The kernels' de Casteljau: degree `n` from `points[first ..= first + n]` at `u`.
/// `tessellate_any` is this loop; `tessellate_cubic` and `tessellate_quartic` write it out
/// for one degree, with exactly this loop's operations in this order.
#[must_use]
pub fn de_casteljau(points: &[GpuVertex], first: u32, n: u32, u: f32) -> Vec3 {
    let v = 1.0 - u;
    let m = (n as usize).min(MAX_GPU_DEGREE);
    let mut p = [Vec3::ZERO; MAX_GPU_DEGREE + 1];
    for (i, slot) in p.iter_mut().enumerate().take(m + 1) {
        *slot = Vec3::from(points[first as usize + i].position);
    }
    for level in (1..=m).rev() {
        for i in 0..level {
            p[i] = v * p[i] + u * p[i + 1];
        }
    }
    p[0]
}

/// One workgroup's body: every lane of `record` writes its sample (the kernel's `work()`
/// and entry point).
fn run_record(record: &GpuRecord, points: &[GpuVertex], samples: &mut [GpuVertex]) {
    for lane in 0..TESSELLATE_WORKGROUP_SIZE {
        let j = record.sample_offset + lane;
        if j >= record.sample_count {
            break;
        }
        let u = sample_param(record, j);
        samples[(record.first_sample + j) as usize] = GpuVertex {
            position: de_casteljau(points, record.first_point, record.degree, u).to_array(),
            id: record.curve,
        };
    }
}

/// Runs the kernels' body for every lane of every record, writing into `samples`.
///
/// # Panics
/// When a record points outside `points` or `samples` (a packing bug).
pub fn tessellate(points: &[GpuVertex], records: &[GpuRecord], samples: &mut [GpuVertex]) {
    for record in records {
        run_record(record, points, samples);
    }
}

/// One dispatch of the kernel, as the GPU runs it: every workgroup `(x, y)` of the
/// `groups` grid takes record `record_start + x + y · groups_x` when it is below
/// `record_end` (`work()` in the shader), and each of its lanes writes one sample. The
/// twin of [`super::tessellator::plan`]'s dispatches.
///
/// # Panics
/// When a record points outside `points` or `samples` (a packing bug).
pub fn dispatch(
    params: &GpuTessParams,
    groups: (u32, u32),
    points: &[GpuVertex],
    records: &[GpuRecord],
    samples: &mut [GpuVertex],
) {
    for gy in 0..groups.1 {
        for gx in 0..groups.0 {
            let s = params.record_start + gx + gy * params.groups_x;
            if s < params.record_end {
                run_record(&records[s as usize], points, samples);
            }
        }
    }
}
