//! The kernel self-test run when a device is opened: every tessellation entry point
//! evaluates a curve of every degree it serves (the general kernel also rational curves
//! with weights ≠ 1), and
//! the results are compared with the CPU twin. An adapter whose shader compiler gets a kernel wrong (Mesa's GL compiler once
//! returned `P_0` for every sample of the general kernel) is refused with a message that
//! names the kernel, the degree and the values, instead of drawing wrong curves.
//!
//! It costs one small dispatch: 62 curves × 5 samples.

use glam::{DVec3, Vec3};

use super::GpuError;
use super::layout::{GpuVertex, MAX_GPU_DEGREE, TESSELLATE_KERNELS, kernel_class};
use super::tessellator::Tessellator;
use super::twin;
use crate::chunks::{ChunkBuilder, ChunkLimits};
use splinescope_encoding::Color;

/// Samples per test curve: both ends and three interior parameters.
const SAMPLES: u32 = 5;

/// Largest allowed distance between a GPU sample and the twin's, for control points in
/// `[-1, 1]³`: both run the same `f32` operations in the same order, so they differ only
/// where a compiler contracts `a·b + c` into one rounding (a few ulp per level, ~4e-6 at
/// degree 31). A miscompiled kernel is off by the curve's size.
pub const SELF_TEST_TOLERANCE: f32 = 1e-4;

/// Why a kernel failed its self-test.
#[derive(Debug, Clone, PartialEq)]
pub struct KernelFault {
    /// The entry point.
    pub kernel: &'static str,
    /// The degree of the test curve.
    pub degree: u32,
    /// Whether the test curve was rational.
    pub rational: bool,
    /// The sample's parameter.
    pub u: f32,
    /// What the GPU wrote.
    pub got: [f32; 3],
    /// What the twin computes.
    pub want: [f32; 3],
}

impl std::fmt::Display for KernelFault {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "kernel {} evaluated a degree-{} {}Bézier curve at u = {} as {:?} instead of {:?}",
            self.kernel,
            self.degree,
            if self.rational { "rational " } else { "" },
            self.u,
            self.got,
            self.want
        )
    }
}

/// The test curves' control points: a fixed pseudo-random sequence in `[-1, 1]³`.
fn test_points(degree: u32) -> Vec<DVec3> {
    let mut state = 0x9e37_79b9_u32.wrapping_mul(degree + 1);
    let mut next = move || {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        f64::from(state >> 8) / f64::from(1u32 << 23) - 1.0
    };
    (0..=degree)
        .map(|_| DVec3::new(next(), next(), next()))
        .collect()
}

/// The rational test curves' weights: a fixed sequence in `[¼, 4]`.
fn test_weights(degree: u32) -> Vec<f64> {
    (0..=degree)
        .map(|i| [1.0, 4.0, 0.25, 2.0, 0.5][(i as usize + degree as usize) % 5])
        .collect()
}

/// Runs every entry point of `tessellator` on a curve of each degree 1..=[`MAX_GPU_DEGREE`],
/// polynomial and rational, and returns the first sample that disagrees with the twin, if any.
///
/// # Errors
/// [`GpuError`] when the dispatch or the readback itself fails.
pub fn run(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    tessellator: &Tessellator,
) -> Result<Option<KernelFault>, GpuError> {
    let limits = ChunkLimits::for_binding_size(1 << 20);
    let style = super::layout::GpuLineStyle::solid(Color::WHITE, 1.0);
    let mut builder = ChunkBuilder::new(limits);
    let degrees: Vec<u32> = (1..=MAX_GPU_DEGREE as u32).collect();
    let curves: Vec<Vec<DVec3>> = degrees.iter().map(|&d| test_points(d)).collect();
    let weights: Vec<Vec<f64>> = degrees.iter().map(|&d| test_weights(d)).collect();
    let rational = curves.iter().zip(&weights).map(|(p, w)| (p, Some(&w[..])));
    for (slot, (points, weights)) in curves.iter().map(|p| (p, None)).chain(rational).enumerate() {
        builder.begin_segment(slot, style, points, weights)?;
        builder.add_samples(SAMPLES, 0.0, 1.0);
    }
    let chunks = builder.finish();
    let mut got: Vec<GpuVertex> = Vec::new();
    tessellator.tessellate_and_read(device, queue, &chunks, |_, samples| {
        got.extend_from_slice(samples);
    })?;
    // One chunk: the twin over the same records gives the expected samples, in the same
    // places.
    let mut fault = None;
    for chunk in &chunks {
        let mut want = vec![super::tessellator::POISON; chunk.sample_count as usize];
        twin::tessellate(&chunk.points, &chunk.records, &mut want);
        for seg in &chunk.records {
            for j in 0..seg.sample_count {
                let at = (seg.first_sample + j) as usize;
                let g = Vec3::from(got[at].position);
                let w = Vec3::from(want[at].position);
                let off = (g - w).abs().max_element();
                let close = off <= SELF_TEST_TOLERANCE; // false for NaN
                if !close || got[at].id != want[at].id {
                    fault.get_or_insert(KernelFault {
                        kernel: TESSELLATE_KERNELS[kernel_class(seg.degree, seg.rational != 0)].0,
                        degree: seg.degree,
                        rational: seg.rational != 0,
                        u: twin::sample_param(seg, j),
                        got: g.to_array(),
                        want: w.to_array(),
                    });
                }
            }
        }
    }
    Ok(fault)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn test_points_cover_every_degree_and_stay_in_the_unit_cube() {
        for d in 1..=MAX_GPU_DEGREE as u32 {
            let p = test_points(d);
            assert_eq!(p.len(), d as usize + 1);
            assert!(
                p.iter()
                    .all(|q| q.abs().max_element() <= 1.0 && q.is_finite())
            );
        }
        assert_ne!(test_points(3), test_points(4)[..4].to_vec());
    }
}
