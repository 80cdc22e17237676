// Shared declarations of every splinescope pipeline. Each struct mirrors a #[repr(C)]
// Pod struct in crates/gpu/src/layout.rs (named there with a `Gpu` prefix); a test checks with
// naga that sizes and member offsets agree. This file is prepended to each pipeline's
// shader (WGSL has no includes).

// Twin: MAX_GPU_DEGREE in crates/gpu/src/layout.rs.
const MAX_DEGREE: u32 = 31u;
// Twin: TESSELLATE_WORKGROUP_SIZE in crates/gpu/src/layout.rs.
const TESSELLATE_WORKGROUP_SIZE: u32 = 64u;
// Twins: LAYER_WORKGROUP, LAYER_GROUPS and LAYER_RUN in crates/gpu/src/layout.rs. The layer's
// rasterizers: invocations per workgroup, the most workgroups one dispatches (the rest by
// stride: idle workgroups are not free on a CPU rasterizer, and 16,384 invocations keep a
// GPU busy), and the curve pieces one invocation draws in a row.
const LAYER_WORKGROUP: u32 = 64u;
const LAYER_GROUPS: u32 = 256u;
const LAYER_RUN: u32 = 4u;

// Twin: GpuVertex. A point with a tag (curve index for samples, style index for overlays).
struct Vertex {
    position: vec3<f32>,
    id: u32,
}

// Twin: GpuControlPoint. A control point in homogeneous coordinates: position = w P,
// weight = w (1 for polynomial segments).
struct ControlPoint {
    position: vec3<f32>,
    weight: f32,
}

// Twin: GpuRecord. One workgroup's run of samples (at most 64) of one Bézier segment, and
// where they go.
struct Record {
    first_point: u32,
    degree: u32,
    curve: u32,
    first_sample: u32,
    sample_count: u32,
    u0: f32,
    u1: f32,
    sample_offset: u32,
    // 1: rational (evaluated homogeneous, then divided by the weight).
    rational: u32,
}

// Twin: GpuSegment. A Bézier segment drawn with a per-frame sample count (adaptive.wgsl):
// control points points[first_point ..= first_point + degree], samples tagged `curve`,
// `fixed` samples when the scene sets a count (0: chosen each frame).
struct Segment {
    first_point: u32,
    degree: u32,
    curve: u32,
    fixed: u32,
    rational: u32,
}

// Twin: GpuFrame. What adaptive tessellation needs each frame, per chunk.
struct Frame {
    clip_from_world: mat4x4<f32>,
    viewport_px: vec2<f32>,
    tolerance_px: f32,
    cull_margin_px: f32,
    segment_count: u32,
    capacity: u32,
    max_count: u32,
    // The fewest samples a segment on screen gets (the comb's hairs use their slots).
    min_count: u32,
}

// Twin: GpuTessParams.
struct TessParams {
    record_start: u32,
    record_end: u32,
    groups_x: u32,
    _padding: u32,
}

// Twin: GpuCamera.
struct Camera {
    clip_from_world: mat4x4<f32>,
    viewport_px: vec2<f32>,
    width_scale: f32,
    _padding: f32,
}

// Twin: GpuLineStyle.
struct LineStyle {
    color: vec4<f32>,
    width_px: f32,
    dash_px: f32,
    order: u32,
    flags: u32,
}

// Twin: LINE_WIDTH_IN_SCENE in crates/gpu/src/layout.rs.
const LINE_WIDTH_IN_SCENE: u32 = 1u;
// A curve style's stroke (twins: the LINE_* constants in crates/gpu/src/layout.rs): its
// cap in bits 1–2 (0 round, 1 butt, 2 square), its join in bits 3–4 (0 round, 1 miter,
// 2 bevel), whether the curve's run in this chunk continues one in an earlier chunk
// (its start is no end) or into a later one, whether the curve is closed (its run's
// ends meet where the pack repeated its first segment), and the miter limit times 1024
// in bits 8–31.
const LINE_CAP_SHIFT: u32 = 1u;
const LINE_JOIN_SHIFT: u32 = 3u;
const LINE_SHAPE_MASK: u32 = 30u;
const LINE_CONTINUES_BEFORE: u32 = 32u;
const LINE_CONTINUES_AFTER: u32 = 64u;
const LINE_CLOSED: u32 = 128u;
const LINE_MITER_SHIFT: u32 = 8u;

// Twin: half_width_px in crates/gpu/src/layer_twin.rs. Half a style's line width in
// pixels where the line is at clip-space `w`: its pixels times the display scale, or (a
// width in scene units) its units times the pixels one unit spans there — the length of
// the clip matrix's y row (the projection's scale, the view being rigid) times half the
// viewport's height, over w. At most 16384: wider covers any viewport.
fn half_width_px(style: LineStyle, cam: Camera, w: f32) -> f32 {
    if ((style.flags & LINE_WIDTH_IN_SCENE) != 0u) {
        let m = cam.clip_from_world;
        let s = length(vec3<f32>(m[0][1], m[1][1], m[2][1]));
        return min(0.25 * style.width_px * s * cam.viewport_px.y / max(w, 1e-6), 16384.0);
    }
    return 0.5 * style.width_px * cam.width_scale;
}

// Twin: EYE_W in crates/gpu/src/layer_twin.rs. Clip-space w below which a drawn point counts as
// behind the eye (the line pipelines and the layer; adaptive.wgsl's bound has its own).
const EYE_W: f32 = 1e-6;

// Whether the piece from clip-space ca to cb lies wholly behind the eye.
fn behind_eye(ca: vec4<f32>, cb: vec4<f32>) -> bool {
    return ca.w < EYE_W && cb.w < EYE_W;
}

// The piece from ca to cb cut at the plane w = EYE_W in front of the eye (3D only; w = 1
// in 2D): an end behind it moved onto it. A piece wholly behind is the caller's to drop.
fn clip_to_eye(ca: vec4<f32>, cb: vec4<f32>) -> array<vec4<f32>, 2> {
    if (ca.w < EYE_W) {
        return array<vec4<f32>, 2>(mix(ca, cb, (EYE_W - ca.w) / (cb.w - ca.w)), cb);
    }
    if (cb.w < EYE_W) {
        return array<vec4<f32>, 2>(ca, mix(cb, ca, (EYE_W - cb.w) / (ca.w - cb.w)));
    }
    return array<vec4<f32>, 2>(ca, cb);
}

// A clip-space point's pixel on a viewport of `viewport_px` (y down).
fn pixel_from_clip(c: vec4<f32>, viewport_px: vec2<f32>) -> vec2<f32> {
    return pixel_from_ndc(c.xy / c.w, viewport_px);
}

// A point's pixel from its normalized device coordinates.
fn pixel_from_ndc(ndc: vec2<f32>, viewport_px: vec2<f32>) -> vec2<f32> {
    return vec2<f32>((ndc.x * 0.5 + 0.5) * viewport_px.x, (0.5 - ndc.y * 0.5) * viewport_px.y);
}
