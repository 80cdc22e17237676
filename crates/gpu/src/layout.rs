//! The data layout shared by Rust and WGSL.
//!
//! Every struct here is `#[repr(C)]`, `Pod`, with named `_padding` fields, and has a twin
//! of the same name (less the `Gpu` prefix) in `shaders/common.wgsl`. A test parses the
//! WGSL with naga and checks that sizes and member offsets agree.

use bytemuck::{Pod, Zeroable};

/// The highest Bézier degree the GPU kernel evaluates (its de Casteljau scratch holds
/// `MAX_GPU_DEGREE + 1` points). Twin: `MAX_DEGREE` in `shaders/common.wgsl`. A scene
/// whose lowered segments go over it is an error ([`super::PackError::DegreeTooHigh`]),
/// never a silent clamp; the CPU evaluates any degree.
pub const MAX_GPU_DEGREE: usize = 31;

/// Threads per workgroup of the tessellation kernel. Twin:
/// `TESSELLATE_WORKGROUP_SIZE` in `shaders/common.wgsl`.
pub const TESSELLATE_WORKGROUP_SIZE: u32 = 64;

/// A point with a 32-bit tag: tessellated samples (tag = the chunk-local curve index),
/// overlay vertices (tag = index into the batch's style table).
/// Consecutive vertices with different tags are not joined by a line.
///
/// Twin: `Vertex` in `shaders/common.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuVertex {
    /// World position.
    pub position: [f32; 3],
    /// The tag (see the type's doc).
    pub id: u32,
}

/// A control point in homogeneous coordinates: `position = w·P`, `weight = w`. Polynomial
/// segments have `w = 1` (`position = P`); a rational segment's weights are scaled by a
/// power of two so that the largest is in `[½, 1)` (the same curve: a rational curve does
/// not change when every weight is scaled alike), which keeps `w·P` within the
/// coordinate limit.
///
/// Twin: `ControlPoint` in `shaders/common.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuControlPoint {
    /// `w·P`.
    pub position: [f32; 3],
    /// `w`.
    pub weight: f32,
}

/// One record of tessellation work on a Bézier segment: its control points are
/// `points[first_point ..= first_point + degree]` (homogeneous, divided after evaluation
/// when `rational` is 1); of the run of `sample_count` samples
/// at the segment parameters `u = u0 (1 − f) + u1 f`, `f = j / (sample_count − 1)`
/// (`f = 0` for a single sample), this record evaluates
/// `j = sample_offset .. min(sample_offset + TESSELLATE_WORKGROUP_SIZE, sample_count)`,
/// writing sample `j` to `samples[first_sample + j]`. A run longer than one workgroup is
/// several records differing only in `sample_offset`.
///
/// Twin: `Record` in `shaders/common.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuRecord {
    /// Index of the first control point.
    pub first_point: u32,
    /// Degree `n` (`n + 1` control points), at most [`MAX_GPU_DEGREE`].
    pub degree: u32,
    /// Tag written with every sample (chunk-local curve index).
    pub curve: u32,
    /// Index of the first output sample.
    pub first_sample: u32,
    /// Number of samples in the whole run.
    pub sample_count: u32,
    /// Segment parameter of the first sample of the run.
    pub u0: f32,
    /// Segment parameter of the last sample of the run.
    pub u1: f32,
    /// The first `j` of the run this record evaluates (a multiple of the workgroup size).
    pub sample_offset: u32,
    /// 1 for a rational segment (evaluated in homogeneous coordinates, then divided by
    /// the weight), 0 for a polynomial one.
    pub rational: u32,
}

/// The uniform of one tessellation dispatch. Twin: `TessParams` in
/// `shaders/common.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuTessParams {
    /// The first record this dispatch evaluates.
    pub record_start: u32,
    /// One past the last record this dispatch evaluates.
    pub record_end: u32,
    /// Workgroups along x of the 2D dispatch (record = `record_start + x + y · groups_x`).
    pub groups_x: u32,
    /// Uniform structs are 16-byte aligned.
    pub _padding: u32,
}

/// A Bézier segment drawn with a per-frame sample count (`shaders/adaptive.wgsl`): control
/// points `points[first_point ..= first_point + degree]`, samples tagged `curve`.
///
/// Twin: `Segment` in `shaders/common.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Pod, Zeroable)]
pub struct GpuSegment {
    /// Index of the first control point.
    pub first_point: u32,
    /// Degree `n`, at most [`MAX_GPU_DEGREE`].
    pub degree: u32,
    /// Tag written with every sample (chunk-local curve index).
    pub curve: u32,
    /// The scene's or curve's fixed sample count; 0: chosen every frame for the tolerance.
    pub fixed: u32,
    /// 1 for a rational segment, 0 for a polynomial one (see [`GpuRecord::rational`]).
    pub rational: u32,
}

/// The curvature comb's uniform, one per chunk (`Comb` and `comb` in `shaders/comb.wgsl`).
/// Twin: `Comb` in `shaders/comb.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuComb {
    /// World length of a hair per unit of curvature.
    pub scale: f32,
    /// The longest hair, in world units: a longer one is cut to it and drawn as capped
    /// (`f32::MAX`: no cap).
    pub cap: f32,
    /// The chunk-local curve whose comb is drawn, or [`COMB_ALL`].
    pub curve: u32,
    /// Uniform structs are 16-byte aligned.
    pub _padding: u32,
}

/// [`GpuComb::curve`] for a comb on every curve. Twin: `COMB_ALL` in
/// `shaders/comb.wgsl`.
pub const COMB_ALL: u32 = u32::MAX;

/// [`GpuComb::curve`] for no comb in the chunk (no curve has this tag).
pub const COMB_NONE: u32 = u32::MAX - 1;

/// The bit a hidden comb vertex's tag carries, so that it differs from its neighbours'
/// and the line pipeline skips the pieces around it. Twin: `COMB_HIDDEN` in
/// `shaders/adaptive.wgsl`.
pub const COMB_HIDDEN: u32 = 0x8000_0000;

/// The bit a capped hair's tip carries (the hair drawn in the envelope's stroke, its
/// envelope vertex hidden). Twin: `COMB_CAPPED` in `shaders/comb.wgsl`.
pub const COMB_CAPPED: u32 = 0x2000_0000;

/// The bit that alternates along hidden envelope vertices so that no two neighbours'
/// tags agree. Twin: `COMB_PARITY` in `shaders/comb.wgsl`.
pub const COMB_PARITY: u32 = 0x4000_0000;

/// The most hairs per segment. Twin: `COMB_HAIRS` in `shaders/adaptive.wgsl`.
pub const COMB_HAIRS: u32 = splinescope_core::analysis::comb::COMB_HAIRS_PER_SEGMENT as u32;

/// The hairs' spacing along a segment's projected control polygon, in pixels. Twin:
/// `COMB_SPACING_PX` in `shaders/adaptive.wgsl`.
pub const COMB_SPACING_PX: f32 = splinescope_core::analysis::comb::COMB_SPACING_PX as f32;

/// Invocations per workgroup of the layer's rasterizers. Twin:
/// `LAYER_WORKGROUP` in `shaders/common.wgsl`.
pub const LAYER_WORKGROUP: u32 = 64;

/// Byte offset of the comb layer rasterizer's indirect dispatch arguments in a comb's
/// argument buffer ([`crate::adaptive::CombChunk::args`]).
pub const COMB_RASTER_ARGS_OFFSET: u64 = 32;

/// The most workgroups one of the layer's rasterizers dispatches (each invocation then
/// takes every line or piece a stride apart: idle workgroups are not free on a CPU
/// rasterizer). Twin: `LAYER_GROUPS` in `shaders/common.wgsl`.
pub const LAYER_GROUPS: u32 = 256;

/// The curve pieces one invocation of the layer's curve rasterizer draws in a row (their
/// shared ends projected once). Twin: `LAYER_RUN` in `shaders/common.wgsl`.
pub const LAYER_RUN: u32 = 4;

/// The per-frame uniform of adaptive tessellation, one per chunk. Twin: `Frame` in
/// `shaders/common.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuFrame {
    /// World to clip space, column-major (the camera's).
    pub clip_from_world: [[f32; 4]; 4],
    /// Viewport size in physical pixels.
    pub viewport_px: [f32; 2],
    /// The largest distance, in pixels, between a drawn polyline and its curve.
    pub tolerance_px: f32,
    /// How far outside the viewport a segment may reach and still be drawn (half the
    /// chunk's widest line, plus a pixel).
    pub cull_margin_px: f32,
    /// Segments in the chunk.
    pub segment_count: u32,
    /// Samples the chunk's sample buffer holds.
    pub capacity: u32,
    /// The most samples one segment may get ([`MAX_SAMPLES_PER_SEGMENT`]).
    pub max_count: u32,
    /// While a comb is drawn, the most hairs a segment gets ([`COMB_HAIRS`]): a segment on
    /// screen then gets at least as many samples as its hairs (their slots hold them);
    /// 0 without a comb.
    pub min_count: u32,
}

/// The most samples adaptive tessellation gives one segment (a scene's fixed counts have
/// the same maximum).
pub const MAX_SAMPLES_PER_SEGMENT: u32 = splinescope_encoding::MAX_SAMPLES_PER_SEGMENT;

/// The most segments of one chunk in adaptive tessellation: the prefix sum scans blocks of
/// [`SCAN_BLOCK`] and then at most [`SCAN_BLOCK`] block totals in one workgroup.
pub const MAX_ADAPTIVE_SEGMENTS: usize = (SCAN_BLOCK * SCAN_BLOCK) as usize;

/// Invocations that share one segment in the adaptive cubic and quartic kernels: a
/// workgroup of [`TESSELLATE_WORKGROUP_SIZE`] invocations tessellates that many segments
/// divided by this, each segment's samples strided over its lanes. On screen most segments
/// need a few samples, so a whole workgroup per segment left most invocations idle (and a
/// CPU adapter still runs them). The general kernel keeps one segment per workgroup (see
/// `shaders/adaptive.wgsl`). Twin: `SEGMENT_LANES` in `shaders/adaptive.wgsl`.
pub const ADAPTIVE_SEGMENT_LANES: u32 = 8;

/// Segments per block of the prefix sum. Twin: `SCAN_BLOCK` in `shaders/adaptive.wgsl`.
pub const SCAN_BLOCK: u32 = 256;

/// The `u32` words at the start of the adaptive work buffer: the indirect draw arguments
/// (`[4, pieces, 0, 0]`) and the frame's statistics ([`FrameStats`]); the segments'
/// counts, scan pairs and block pairs follow. Twin: `WORK_COUNTS` in
/// `shaders/adaptive.wgsl`.
pub const WORK_HEADER: usize = 8;

/// The frame's figures as the adaptive passes leave them in the work buffer's header.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Pod, Zeroable)]
pub struct FrameStats {
    /// Vertices per line piece (4, a triangle strip), for the indirect draw.
    pub vertex_count: u32,
    /// Line pieces drawn (samples − 1).
    pub instance_count: u32,
    /// 0, for the indirect draw.
    pub first_vertex: u32,
    /// 0, for the indirect draw.
    pub first_instance: u32,
    /// Samples the tolerance asked for.
    pub requested: u32,
    /// Samples written (fewer when the buffer capped them).
    pub drawn: u32,
    /// Segments with samples (not wholly off screen).
    pub segments_drawn: u32,
    /// 1 when the counts were scaled down to fit the buffer.
    pub capped: u32,
}

/// The kernels of `shaders/tessellate.wgsl` (and of `shaders/adaptive.wgsl`), one per
/// degree class: `(entry point, the one degree it evaluates or None for any degree,
/// whether that one degree is rational)`. Polynomial cubics and quartics and rational
/// quadratics and cubics are written out; every other segment goes to the general kernel,
/// which evaluates rational ones in homogeneous coordinates (a branch on the record's
/// `rational`, the same for a whole workgroup). Each chunk's records are sorted in this
/// order and each class is dispatched with its own pipeline.
pub const TESSELLATE_KERNELS: [(&str, Option<u32>, bool); 5] = [
    ("tessellate_cubic", Some(3), false),
    ("tessellate_quartic", Some(4), false),
    ("tessellate_rational_quadratic", Some(2), true),
    ("tessellate_rational_cubic", Some(3), true),
    ("tessellate_any", None, false),
];

/// The index in [`TESSELLATE_KERNELS`] of the kernel that evaluates a segment of `degree`
/// (`rational`: with weights).
#[must_use]
pub fn kernel_class(degree: u32, rational: bool) -> usize {
    let general = TESSELLATE_KERNELS.len() - 1;
    TESSELLATE_KERNELS
        .iter()
        .position(|&(_, d, r)| d.is_none_or(|d| d == degree && r == rational))
        .unwrap_or(general)
}

/// The camera uniform. Twin: `Camera` in `shaders/common.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuCamera {
    /// World to clip space, column-major.
    pub clip_from_world: [[f32; 4]; 4],
    /// Viewport size in physical pixels.
    pub viewport_px: [f32; 2],
    /// Physical pixels per logical pixel: style widths are multiplied by it.
    pub width_scale: f32,
    /// Uniform structs are 16-byte aligned.
    pub _padding: f32,
}

/// How a tagged polyline or point is drawn. Twin: `LineStyle` in `shaders/common.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GpuLineStyle {
    /// Straight-alpha sRGB colour.
    pub color: [f32; 4],
    /// Line width, or point diameter, in physical pixels.
    pub width_px: f32,
    /// Dash period in pixels along each line piece (0 = solid).
    pub dash_px: f32,
    /// A curve's place in the scene (its style's index in the scene's table of curve
    /// styles, which the layer's pixels name: a later curve over an earlier one); 0 for
    /// overlays.
    pub order: u32,
    /// Bits: [`LINE_WIDTH_IN_SCENE`] (the width is in scene units).
    pub flags: u32,
}

/// [`GpuLineStyle::flags`] bit: `width_px` holds a width in scene units (the line zooms
/// with the view); pixels where the line is are `half_width_px` of the layer twin. Twin:
/// `LINE_WIDTH_IN_SCENE` in `shaders/common.wgsl`.
pub const LINE_WIDTH_IN_SCENE: u32 = 1;

/// [`GpuLineStyle::flags`]: a curve's cap in bits 1–2 (0 round, 1 butt, 2 square). Twins:
/// the `LINE_*` constants in `shaders/common.wgsl`, drawn by `shaders/layer.wgsl` (and
/// `layer_twin`).
pub const LINE_CAP_SHIFT: u32 = 1;
/// A curve's join in bits 3–4 (0 round, 1 miter, 2 bevel).
pub const LINE_JOIN_SHIFT: u32 = 3;
/// The cap and join bits: 0 for the all-round stroke.
pub const LINE_SHAPE_MASK: u32 = 0b11110;
/// The curve's run in this chunk continues one in an earlier chunk (its start is drawn
/// round, as a join).
pub const LINE_CONTINUES_BEFORE: u32 = 1 << 5;
/// The curve's run in this chunk continues in a later chunk.
pub const LINE_CONTINUES_AFTER: u32 = 1 << 6;
/// The curve is closed: its run's ends are cut hard (the pack repeats its first segment
/// after its last, so the seam is a join like any other).
pub const LINE_CLOSED: u32 = 1 << 7;
/// The miter limit times 1024 (rounded) in bits 8–31.
pub const LINE_MITER_SHIFT: u32 = 8;

/// How far a style's ends and corners reach from the curve, in half widths: 1 for round
/// ones and bevels, `√2` at a square cap's corners, the miter limit at a miter's tip.
#[must_use]
pub fn stroke_reach(flags: u32) -> f32 {
    let cap = (flags >> LINE_CAP_SHIFT) & 3;
    let join = (flags >> LINE_JOIN_SHIFT) & 3;
    let mut reach: f32 = if cap == 2 {
        std::f32::consts::SQRT_2
    } else {
        1.0
    };
    if join == 1 {
        reach = reach.max((flags >> LINE_MITER_SHIFT) as f32 / 1024.0);
    }
    reach
}

/// The stroke bits of a curve style: cap, join, miter limit and closedness (the
/// continuation bits are the chunk builder's).
#[must_use]
pub fn stroke_flags(shape: &splinescope_encoding::StrokeShape, closed: bool) -> u32 {
    use splinescope_core::ops::{Cap, Join};
    let cap = match shape.cap {
        Cap::Round => 0,
        Cap::Butt => 1,
        Cap::Square => 2,
    };
    let join = match shape.join {
        Join::Round => 0,
        Join::Miter => 1,
        Join::Bevel => 2,
    };
    // At most 1000 × 1024 < 2²⁴: the limit fits its 24 bits.
    let limit = (shape
        .miter_limit
        .clamp(1.0, splinescope_encoding::MAX_MITER_LIMIT)
        * 1024.0)
        .round() as u32;
    (cap << LINE_CAP_SHIFT)
        | (join << LINE_JOIN_SHIFT)
        | if closed { LINE_CLOSED } else { 0 }
        | (limit << LINE_MITER_SHIFT)
}

/// Vertices per line piece: a triangle strip around the piece's capsule
/// (`shaders/lines.wgsl`); the adaptive kernel writes it into the draw arguments.
pub const LINE_CORNERS: u32 = 4;
