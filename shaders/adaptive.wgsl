// Adaptive tessellation, every frame, on the GPU (no readback):
//
//   count       one invocation per Bézier segment: its sample count from Wang's bound on
//               its control points projected to the screen, for a tolerance in pixels
//               (0 for a segment wholly off screen; a fixed count when the scene sets one)
//   scan_blocks exclusive prefix sums of (count, drawn) within blocks of 256 segments
//   scan_sums   the same over the block totals (one workgroup; at most 256 blocks)
//   finalize    each segment's offset in the sample buffer; when the counts exceed the
//               buffer they are scaled down in proportion (never below 2 for a drawn
//               segment, never past the buffer); the indirect draw's instance count
//   tessellate_{cubic,quartic,rational_quadratic,rational_cubic,any}
//               one workgroup per segment writes exactly its samples there
//
// The line pipeline then draws `instance_count` pieces with one indirect draw. The CPU
// twins are `wang_count`, `scan_and_place` and `tessellate_adaptive` in crates/gpu/src/twin.rs.
// The bound (docs/math.md §5): with H_i = (x, y, w) the control points in homogeneous
// pixel coordinates (a rational segment's weights multiply its points' w), M_xy and M_w
// their largest second differences (x and y taken about the centre of the projected
// control points' box), R the largest distance of a projected control point from that
// centre and W the smallest w,
// N uniform intervals keep every screen chord within
// n (n − 1) (M_xy + R M_w) / (8 N² W) pixels of the curve (orthographic: w = 1, M_w = 0,
// Wang's own bound).

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> range: TessParams;
@group(0) @binding(2) var<storage, read> points: array<ControlPoint>;
@group(0) @binding(3) var<storage, read> segments: array<Segment>;
// Twin: the WORK_* constants in crates/gpu/src/layout.rs. [0, 8): the indirect draw arguments and
// the frame's statistics (FrameStats); then counts[S], scan pairs[2 S], block pairs[2 B].
@group(0) @binding(4) var<storage, read_write> work: array<u32>;
@group(0) @binding(5) var<storage, read_write> samples: array<Vertex>;

const SCAN_BLOCK: u32 = 256u;
const STAT_INSTANCES: u32 = 1u;
const STAT_REQUESTED: u32 = 4u;
const STAT_DRAWN: u32 = 5u;
const STAT_SEGMENTS_DRAWN: u32 = 6u;
const STAT_CAPPED: u32 = 7u;
const WORK_COUNTS: u32 = 8u;
// w below this (relative to the largest |w|) counts as at or behind the eye.
const NEAR_W: f32 = 1e-5;

fn scan_base() -> u32 {
    return WORK_COUNTS + frame.segment_count;
}

fn block_base() -> u32 {
    return WORK_COUNTS + 3u * frame.segment_count;
}

// The samples a segment needs this frame.
fn wang_count(seg: Segment) -> u32 {
    if (seg.fixed > 0u) {
        return seg.fixed;
    }
    let n = min(seg.degree, MAX_DEGREE);
    let half = 0.5 * frame.viewport_px;
    var h: array<vec3<f32>, 32>;
    var w_min = 3.4e38;
    var w_max = 0.0;
    var lo = vec2<f32>(3.4e38);
    var hi = vec2<f32>(-3.4e38);
    var r = 0.0;
    for (var i = 0u; i <= n; i++) {
        // The homogeneous control point (w P, w) in clip space: w times the projection of
        // P, so the bound below covers the weights and the perspective alike.
        let q = points[seg.first_point + i];
        let c = frame.clip_from_world * vec4<f32>(q.position, q.weight);
        h[i] = vec3<f32>(c.x * half.x, -c.y * half.y, c.w);
        w_min = min(w_min, c.w);
        w_max = max(w_max, abs(c.w));
    }
    if (!(w_min > NEAR_W * w_max)) {
        // At or behind the eye: no bound holds; the most samples (the line pipeline clips).
        return frame.max_count;
    }
    for (var i = 0u; i <= n; i++) {
        let p = h[i].xy / h[i].z;
        lo = min(lo, p);
        hi = max(hi, p);
    }
    // The bound holds with pixel coordinates taken about any point (the chords do not
    // move with the origin): about the middle of the projected control points, R is the
    // segment's own size rather than its distance from the viewport's centre.
    let centre = 0.5 * (lo + hi);
    for (var i = 0u; i <= n; i++) {
        r = max(r, length(h[i].xy / h[i].z - centre));
    }
    // The curve lies in the hull of its projected control points: wholly off screen
    // (with a margin for the line's width), it needs no samples.
    let m = frame.cull_margin_px;
    if (hi.x < -half.x - m || lo.x > half.x + m || hi.y < -half.y - m || lo.y > half.y + m) {
        return 0u;
    }
    var m_xy = 0.0;
    var m_w = 0.0;
    for (var i = 0u; i + 2u <= n; i++) {
        let d = h[i] - 2.0 * h[i + 1u] + h[i + 2u];
        m_xy = max(m_xy, length(d.xy - centre * d.z));
        m_w = max(m_w, abs(d.z));
    }
    // A lower bound of H_w on [0, 1], at least W = min w_i (docs/math.md §5): the smallest
    // Bernstein coefficient of H_w's two halves split at ½ (each half lies in the hull of
    // its coefficients), the k-th of each half 2⁻ᵏ Σ_j C(k, j) w_j (from its own end), less
    // WEIGHT_ROUNDING of itself for the rounding. (Written as sums, not as de Casteljau's
    // averages in place: GL on llvmpipe lost those writes to a local array in the nested
    // loop.) Twin: w_floor in crates/gpu/src/twin.rs.
    // Equal weights (a polynomial segment seen orthographically) are their own floor.
    var low = min(h[0].z, h[n].z);
    var half_k = 1.0;
    for (var k = 1u; k <= n && w_max > w_min; k++) {
        half_k = 0.5 * half_k;
        var binomial = 1.0;
        var left = 0.0;
        var right = 0.0;
        for (var j = 0u; j <= k; j++) {
            left += binomial * h[j].z;
            right += binomial * h[n - k + j].z;
            binomial = binomial * f32(k - j) / f32(j + 1u);
        }
        low = min(low, min(left, right) * half_k);
    }
    let w_floor = max(w_min, low * (1.0 - WEIGHT_ROUNDING));
    let nn = f32(n * (n - min(n, 1u)));
    let intervals = ceil(sqrt(nn * (m_xy + r * m_w) / (8.0 * frame.tolerance_px * w_floor)));
    // NaN or overflow (a degenerate camera) asks for the most samples, not garbage.
    if (!(intervals < f32(frame.max_count))) {
        return frame.max_count;
    }
    return clamp(max(u32(intervals) + 1u, comb_floor(seg)), 2u, frame.max_count);
}

// While a comb is drawn (frame.min_count > 0), a segment on screen gets at least as many
// samples as its hairs: their slots hold them.
fn comb_floor(seg: Segment) -> u32 {
    if (frame.min_count == 0u) {
        return 0u;
    }
    return min(comb_hairs_of(seg), frame.min_count);
}

// The hairs of a segment: one every COMB_SPACING_PX pixels of its projected control
// polygon and one more, from 2 to COMB_HAIRS (the most when a point is at or behind the
// eye, or the length is not finite). Twin: hairs_for in the core's comb module (figures)
// and comb_hairs_of in crates/gpu/src/twin.rs.
fn comb_hairs_of(seg: Segment) -> u32 {
    let n = min(seg.degree, MAX_DEGREE);
    let half = 0.5 * frame.viewport_px;
    var length = 0.0;
    var previous = vec2<f32>(0.0);
    for (var i = 0u; i <= n; i++) {
        let q = points[seg.first_point + i];
        let c = frame.clip_from_world * vec4<f32>(q.position, q.weight);
        if (!(c.w > 0.0)) {
            return COMB_HAIRS;
        }
        let p = vec2<f32>(c.x * half.x, -c.y * half.y) / c.w;
        if (i > 0u) {
            length += distance(p, previous);
        }
        previous = p;
    }
    if (!(length < 1e9)) {
        return COMB_HAIRS;
    }
    return clamp(u32(ceil(length / COMB_SPACING_PX)) + 1u, 2u, COMB_HAIRS);
}

// Twin: WEIGHT_ROUNDING in crates/gpu/src/twin.rs. Above (n + 3) · 2⁻²⁴ for every degree up to
// 31: the relative rounding of a sum of n + 1 positive terms whose binomials are rounded.
const WEIGHT_ROUNDING: f32 = 4e-6;

@compute @workgroup_size(64)
fn count(@builtin(global_invocation_id) id: vec3<u32>) {
    let s = id.x;
    if (s >= frame.segment_count) {
        return;
    }
    work[WORK_COUNTS + s] = wang_count(segments[s]);
}

var<workgroup> scan_scratch: array<vec2<u32>, 256>;

// Inclusive scan of scan_scratch (Hillis–Steele); every lane calls it.
fn scan_workgroup(lane: u32) {
    for (var step = 1u; step < SCAN_BLOCK; step = step * 2u) {
        workgroupBarrier();
        var add = vec2<u32>(0u);
        if (lane >= step) {
            add = scan_scratch[lane - step];
        }
        workgroupBarrier();
        scan_scratch[lane] = scan_scratch[lane] + add;
    }
    workgroupBarrier();
}

@compute @workgroup_size(256)
fn scan_blocks(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let s = group.x * SCAN_BLOCK + lane;
    var v = vec2<u32>(0u);
    if (s < frame.segment_count) {
        let c = work[WORK_COUNTS + s];
        v = vec2<u32>(c, select(0u, 1u, c > 0u));
    }
    scan_scratch[lane] = v;
    scan_workgroup(lane);
    if (s < frame.segment_count) {
        let exclusive = scan_scratch[lane] - v;
        work[scan_base() + 2u * s] = exclusive.x;
        work[scan_base() + 2u * s + 1u] = exclusive.y;
    }
    if (lane == SCAN_BLOCK - 1u) {
        work[block_base() + 2u * group.x] = scan_scratch[lane].x;
        work[block_base() + 2u * group.x + 1u] = scan_scratch[lane].y;
    }
}

@compute @workgroup_size(256)
fn scan_sums(@builtin(local_invocation_index) lane: u32) {
    let blocks = (frame.segment_count + SCAN_BLOCK - 1u) / SCAN_BLOCK;
    var v = vec2<u32>(0u);
    if (lane < blocks) {
        v = vec2<u32>(work[block_base() + 2u * lane], work[block_base() + 2u * lane + 1u]);
    }
    scan_scratch[lane] = v;
    scan_workgroup(lane);
    if (lane < blocks) {
        let exclusive = scan_scratch[lane] - v;
        work[block_base() + 2u * lane] = exclusive.x;
        work[block_base() + 2u * lane + 1u] = exclusive.y;
    }
    if (lane == SCAN_BLOCK - 1u) {
        work[STAT_REQUESTED] = scan_scratch[lane].x;
        work[STAT_SEGMENTS_DRAWN] = scan_scratch[lane].y;
    }
}

// Where a prefix (offset, drawn segments before) lands once the counts are scaled to fit
// the buffer: drawn segments keep 2 samples each, the rest shrink by `ratio`.
fn placed(offset: u32, drawn: u32, ratio: f32) -> u32 {
    if (ratio >= 1.0) {
        return offset;
    }
    let base = 2u * drawn;
    return min(base + u32(floor(f32(offset - base) * ratio)), frame.capacity);
}

@compute @workgroup_size(64)
fn finalize(@builtin(global_invocation_id) id: vec3<u32>) {
    let s = id.x;
    if (s >= frame.segment_count) {
        return;
    }
    let total = work[STAT_REQUESTED];
    let drawn_total = work[STAT_SEGMENTS_DRAWN];
    var ratio = 1.0;
    if (total > frame.capacity) {
        ratio = f32(frame.capacity - 2u * drawn_total) / f32(total - 2u * drawn_total);
    }
    let block = s / SCAN_BLOCK;
    let c = work[WORK_COUNTS + s];
    let offset = work[scan_base() + 2u * s] + work[block_base() + 2u * block];
    let drawn = work[scan_base() + 2u * s + 1u] + work[block_base() + 2u * block + 1u];
    let start = placed(offset, drawn, ratio);
    let end = placed(offset + c, drawn + select(0u, 1u, c > 0u), ratio);
    work[scan_base() + 2u * s] = start;
    work[WORK_COUNTS + s] = end - start;
    if (s + 1u == frame.segment_count) {
        work[STAT_DRAWN] = end;
        work[STAT_INSTANCES] = max(end, 1u) - 1u;
        work[STAT_CAPPED] = select(0u, 1u, ratio < 1.0);
    }
}

// What one workgroup tessellates: its segment, the count placed for it and where its
// samples start; ok is false past the dispatch's range.
struct AdaptiveWork {
    seg: Segment,
    count: u32,
    first: u32,
    ok: bool,
}

// Twin: ADAPTIVE_SEGMENT_LANES in crates/gpu/src/layout.rs. The invocations that share one
// segment in the cubic and quartic kernels, whose workgroups tessellate
// TESSELLATE_WORKGROUP_SIZE / SEGMENT_LANES segments each. The general kernel keeps a
// whole workgroup per segment: its loops over the degree are long, and llvmpipe ends every
// loop of an invocation once all its loops together ran 65,535 iterations
// (LP_MAX_TGSI_LOOP_ITERATIONS; a stride of 8 reached it for degree 13 at 4,096 samples,
// while a stride of 64 stays under it up to degree 31).
const SEGMENT_LANES: u32 = 8u;
const SEGMENTS_PER_GROUP: u32 = TESSELLATE_WORKGROUP_SIZE / SEGMENT_LANES;

// The segment slot of invocation `index` of workgroup `group` in the kernels that share a
// workgroup among SEGMENTS_PER_GROUP segments, SEGMENT_LANES invocations each.
fn narrow_slot(group: vec3<u32>, index: u32) -> u32 {
    return (group.x + group.y * range.groups_x) * SEGMENTS_PER_GROUP + index / SEGMENT_LANES;
}

// Segment `slot` of the dispatch's range.
fn adaptive_work(slot: u32) -> AdaptiveWork {
    var w: AdaptiveWork;
    w.ok = false;
    let s = range.record_start + slot;
    if (s >= range.record_end) {
        return w;
    }
    w.seg = segments[s];
    w.count = work[WORK_COUNTS + s];
    w.first = work[scan_base() + 2u * s];
    w.ok = true;
    return w;
}

// The parameter of sample j of count: j / (count − 1), exactly 0 and 1 at the ends (a
// segment the cap left one sample gets its start).
fn adaptive_param(j: u32, count: u32) -> f32 {
    if (count < 2u) {
        return 0.0;
    }
    return f32(j) / f32(count - 1u);
}

@compute @workgroup_size(TESSELLATE_WORKGROUP_SIZE)
fn tessellate_cubic(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) index: u32,
) {
    let w = adaptive_work(narrow_slot(group, index));
    let lane = index % SEGMENT_LANES;
    if (!w.ok) {
        return;
    }
    let seg = w.seg;
    let count = w.count;
    let first = w.first;
    let p0 = control_point(seg.first_point, 0u);
    let p1 = control_point(seg.first_point, 1u);
    let p2 = control_point(seg.first_point, 2u);
    let p3 = control_point(seg.first_point, 3u);
    for (var j = lane; j < count; j += SEGMENT_LANES) {
        let u = adaptive_param(j, count);
        samples[first + j] = Vertex(cubic_bernstein(p0, p1, p2, p3, u, 1.0 - u), seg.curve);
    }
}

@compute @workgroup_size(TESSELLATE_WORKGROUP_SIZE)
fn tessellate_quartic(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) index: u32,
) {
    let w = adaptive_work(narrow_slot(group, index));
    let lane = index % SEGMENT_LANES;
    if (!w.ok) {
        return;
    }
    let seg = w.seg;
    let count = w.count;
    let first = w.first;
    let p0 = control_point(seg.first_point, 0u);
    let p1 = control_point(seg.first_point, 1u);
    let p2 = control_point(seg.first_point, 2u);
    let p3 = control_point(seg.first_point, 3u);
    let p4 = control_point(seg.first_point, 4u);
    for (var j = lane; j < count; j += SEGMENT_LANES) {
        let u = adaptive_param(j, count);
        samples[first + j] = Vertex(quartic(p0, p1, p2, p3, p4, u, 1.0 - u), seg.curve);
    }
}

@compute @workgroup_size(TESSELLATE_WORKGROUP_SIZE)
fn tessellate_rational_quadratic(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) index: u32,
) {
    let w = adaptive_work(narrow_slot(group, index));
    let lane = index % SEGMENT_LANES;
    if (!w.ok) {
        return;
    }
    let seg = w.seg;
    let count = w.count;
    let first = w.first;
    let h0 = control_point4(seg.first_point, 0u);
    let h1 = control_point4(seg.first_point, 1u);
    let h2 = control_point4(seg.first_point, 2u);
    for (var j = lane; j < count; j += SEGMENT_LANES) {
        let u = adaptive_param(j, count);
        samples[first + j] = Vertex(rational_quadratic(h0, h1, h2, u, 1.0 - u), seg.curve);
    }
}

@compute @workgroup_size(TESSELLATE_WORKGROUP_SIZE)
fn tessellate_rational_cubic(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) index: u32,
) {
    let w = adaptive_work(narrow_slot(group, index));
    let lane = index % SEGMENT_LANES;
    if (!w.ok) {
        return;
    }
    let seg = w.seg;
    let count = w.count;
    let first = w.first;
    let h0 = control_point4(seg.first_point, 0u);
    let h1 = control_point4(seg.first_point, 1u);
    let h2 = control_point4(seg.first_point, 2u);
    let h3 = control_point4(seg.first_point, 3u);
    for (var j = lane; j < count; j += SEGMENT_LANES) {
        let u = adaptive_param(j, count);
        samples[first + j] = Vertex(rational_cubic(h0, h1, h2, h3, u, 1.0 - u), seg.curve);
    }
}

@compute @workgroup_size(TESSELLATE_WORKGROUP_SIZE)
fn tessellate_any(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let w = adaptive_work(group.x + group.y * range.groups_x);
    if (!w.ok) {
        return;
    }
    let seg = w.seg;
    let count = w.count;
    let first = w.first;
    let n = min(seg.degree, MAX_DEGREE);
    for (var j = lane; j < count; j += TESSELLATE_WORKGROUP_SIZE) {
        let u = adaptive_param(j, count);
        samples[first + j] = Vertex(
            general_point(seg.first_point, n, seg.rational != 0u, u, 1.0 - u),
            seg.curve,
        );
    }
}

// The most hairs per segment, uniform in its parameter, ends included; the segment's
// samples' slots hold them (the count kernel gives each segment on screen at least as
// many samples as hairs while a comb is drawn). Twin: COMB_HAIRS_PER_SEGMENT in the
// core's comb module.
const COMB_HAIRS: u32 = 32u;
// The hairs' spacing along a segment's projected control polygon, in pixels. Twin:
// COMB_SPACING_PX in the core's comb module.
const COMB_SPACING_PX: f32 = 4.0;
