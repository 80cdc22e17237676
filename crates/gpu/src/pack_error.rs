//! Why curves cannot be packed for the GPU, and the coordinate range the `f32` path takes.
//! Its own file so that the chunk builders and the packer both name it without naming
//! each other.

use thiserror::Error;

/// The largest coordinate magnitude the GPU path takes: half of `f32::MAX` (≈ 1.7e38)
/// rounded down, so that a de Casteljau step `v·a + u·b` of two such coordinates cannot
/// overflow (`|v·a| + |u·b| ≤ max(|a|, |b|)` in exact arithmetic, and rounding stays far
/// below the other half).
pub const GPU_COORDINATE_LIMIT: f64 = 1e38;

/// The smallest ratio of a rational segment's weight to its largest weight the GPU path
/// takes (`2⁻¹⁰⁰`): the weights are scaled so that the largest is in `[½, 1)`, and every
/// other must stay a normal `f32` (down to `2⁻¹²⁶`) with room for the Bernstein factors.
pub const GPU_WEIGHT_RATIO: f64 = 7.888_609_052_210_118e-31;

/// Why a scene cannot be packed for the GPU.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PackError {
    /// A lowered segment's degree is over [`MAX_GPU_DEGREE`](crate::layout::MAX_GPU_DEGREE).
    #[error(
        "curves[{curve}]: Bézier segment {segment} has degree {degree}, over the GPU maximum of {max} (the CPU path, e.g. `eval --backend cpu`, takes any degree)"
    )]
    DegreeTooHigh {
        /// The curve's index in the scene.
        curve: usize,
        /// The segment's index in the curve's lowering.
        segment: usize,
        /// Its degree.
        degree: usize,
        /// [`MAX_GPU_DEGREE`](crate::layout::MAX_GPU_DEGREE).
        max: usize,
    },
    /// A lowered control point has a coordinate the kernel cannot work with in `f32`: its
    /// `f32` form, or a de Casteljau intermediate (a sum of two products), would overflow.
    #[error(
        "curves[{curve}]: Bézier segment {segment}, control point {point} has coordinate {value:e}, beyond the GPU's f32 range of ±{limit:e} (the CPU path, e.g. `eval --backend cpu`, takes it)"
    )]
    CoordinateTooLarge {
        /// The curve's index in the scene.
        curve: usize,
        /// The segment's index in the curve's lowering.
        segment: usize,
        /// The point's index in the segment.
        point: usize,
        /// The offending coordinate.
        value: f64,
        /// [`GPU_COORDINATE_LIMIT`].
        limit: f64,
    },
    /// A rational segment's weight is too small beside its largest for `f32`.
    #[error(
        "curves[{curve}]: Bézier segment {segment}, weight {point} is {ratio:e} times the segment's largest weight, below the GPU's f32 range of {limit:e} (the CPU path, e.g. `eval --backend cpu`, takes it)"
    )]
    WeightRange {
        /// The curve's index in the scene.
        curve: usize,
        /// The segment's index in the curve's lowering.
        segment: usize,
        /// The point's index in the segment.
        point: usize,
        /// The weight divided by the segment's largest.
        ratio: f64,
        /// [`GPU_WEIGHT_RATIO`].
        limit: f64,
    },
    /// An annotation point has a coordinate beyond [`GPU_COORDINATE_LIMIT`].
    #[error(
        "annotations[{annotation}].points[{point}] has coordinate {value:e}, beyond the GPU's f32 range of ±{limit:e}"
    )]
    AnnotationTooLarge {
        /// The annotation's index in the scene.
        annotation: usize,
        /// The point's index.
        point: usize,
        /// The offending coordinate.
        value: f64,
        /// [`GPU_COORDINATE_LIMIT`].
        limit: f64,
    },
    /// The scene needs more samples than [`splinescope_io::limits::SAMPLES`] allows.
    #[error("the scene's curves need {0}")]
    TooManySamples(String),
    /// The chunk limits are too small to hold even one segment.
    #[error("GPU buffer limits too small: one chunk holds {what}")]
    LimitsTooSmall {
        /// What did not fit.
        what: String,
    },
}
