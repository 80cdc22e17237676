// The curvature comb's kernels (composed after common.wgsl, bezier.wgsl and adaptive.wgsl,
// whose count pass gives each segment its hairs' slots, and whose work ranges, parameters
// and control points these read). CPU twin: comb_point_and_curvature and comb_hair in
// crates/gpu/src/twin.rs, held to these in tests/gpu_comb.rs.
//
// The curvature comb (docs/math.md §8), from the samples just placed: at each sample the
// curve's point P, and a hair to P − scale · K, where K = (P″ − (P″·T) T) / |P′|² is the
// curvature vector (length κ, towards the centre of curvature; in the plane, κ signed, so
// the hairs change side at an inflection). The hair tips joined in order are the comb's
// envelope. Derivatives come from the segment's homogeneous control points H_i = (w P, w):
// H^(k)(u) = n!/(n−k)! Σ Δ^k H_i B_i^{n−k}(u), then P′ = (H′ − w′ P)/w and
// P″ = (H″ − w″ P − 2 w′ P′)/w (cubics written out in Bernstein form). Checked against the
// exact curvature in tests/gpu_comb.rs.

// Twin: GpuComb.
struct Comb {
    // World length of a hair per unit of curvature.
    scale: f32,
    // The longest hair (world units): a longer one is cut to it and drawn as capped.
    cap: f32,
    // Chunk-local curve whose comb is drawn: COMB_ALL for every curve.
    curve: u32,
    _padding: u32,
}

const COMB_ALL: u32 = 0xffffffffu;
// Tags that differ from each neighbour's: the line pipeline skips a piece between them
// (hidden envelope vertices carry COMB_HIDDEN, and COMB_PARITY on every other slot).
const COMB_HIDDEN: u32 = 0x80000000u;
const COMB_PARITY: u32 = 0x40000000u;
// A capped hair's tip: drawn in the envelope's stroke (twin: COMB_CAPPED in layout.rs).
const COMB_CAPPED: u32 = 0x20000000u;

@group(1) @binding(0) var<uniform> comb: Comb;
// Two vertices per sample: the point on the curve, then the hair's tip. The samples'
// order is the tessellation's (per dispatch range, its segments' placed offsets).
@group(1) @binding(1) var<storage, read_write> hairs: array<Vertex>;
// One vertex per sample: the hair's tip.
@group(1) @binding(2) var<storage, read_write> envelope: array<Vertex>;
// The comb's indirect draws (line lists): the hairs' (2 × samples, 1, 0, 0), then the
// envelope's (2 × (samples − 1), 1, 0, 0).
@group(1) @binding(3) var<storage, read_write> comb_args: array<u32>;

// The k-th forward difference of the homogeneous points at i (k ≤ 2).
fn difference(first: u32, i: u32, k: u32) -> vec4<f32> {
    let a = control_point4(first, i);
    if (k == 0u) {
        return a;
    }
    let b = control_point4(first, i + 1u);
    if (k == 1u) {
        return b - a;
    }
    return control_point4(first, i + 2u) - 2.0 * b + a;
}

// Σ Δ^k H_i B_i^m(u), m = n − k, by Horner's rule in u / v (or v / u past the middle),
// scaled by v^m (or u^m): the comb's derivatives, whose bound is the f32 one of §8.
fn difference_sum(first: u32, n: u32, k: u32, u: f32, v: f32) -> vec4<f32> {
    let m = n - k;
    var acc: vec4<f32>;
    var scale = 1.0;
    var binomial = 1.0;
    if (u <= 0.5) {
        let x = u / v;
        acc = difference(first, m, k);
        for (var i = m; i > 0u; i--) {
            binomial = binomial * f32(i) / f32(m - i + 1u);
            acc = acc * x + binomial * difference(first, i - 1u, k);
            scale = scale * v;
        }
    } else {
        let x = v / u;
        acc = difference(first, 0u, k);
        for (var i = 1u; i <= m; i++) {
            binomial = binomial * f32(m - i + 1u) / f32(i);
            acc = acc * x + binomial * difference(first, i, k);
            scale = scale * u;
        }
    }
    return acc * scale;
}

// The point and the curvature vector of a segment of degree n at u.
fn point_and_curvature(first: u32, n: u32, u: f32) -> array<vec3<f32>, 2> {
    let v = 1.0 - u;
    let nf = f32(n);
    let h = difference_sum(first, n, 0u, u, v);
    var h1 = vec4<f32>(0.0);
    var h2 = vec4<f32>(0.0);
    if (n >= 1u) {
        h1 = nf * difference_sum(first, n, 1u, u, v);
    }
    if (n >= 2u) {
        h2 = nf * (nf - 1.0) * difference_sum(first, n, 2u, u, v);
    }
    return curvature_from(h, h1, h2);
}

// The same for a cubic whose homogeneous control points are h: the three sums in
// Bernstein form, written out (v = 1 − u) — H = Σ H_i B_i³, H′ = 3 Σ ΔH_i B_i²,
// H″ = 6 Σ Δ²H_i B_i¹, each a sum of nonnegative weights times differences, as §8's.
fn cubic_point_and_curvature(h: array<vec4<f32>, 4>, u: f32) -> array<vec3<f32>, 2> {
    let v = 1.0 - u;
    let v2 = v * v;
    let u2 = u * u;
    let point = cubic_bernstein4(h[0], h[1], h[2], h[3], u, v);
    let d0 = h[1] - h[0];
    let d1 = h[2] - h[1];
    let d2 = h[3] - h[2];
    let h1 = 3.0 * (d0 * v2 + d1 * (2.0 * u * v) + d2 * u2);
    let h2 = 6.0 * ((d1 - d0) * v + (d2 - d1) * u);
    return curvature_from(point, h1, h2);
}

// The point and the curvature vector from the homogeneous point H and its first two
// derivatives.
fn curvature_from(h: vec4<f32>, h1: vec4<f32>, h2: vec4<f32>) -> array<vec3<f32>, 2> {
    let p = h.xyz / h.w;
    let d1 = (h1.xyz - h1.w * p) / h.w;
    let d2 = (h2.xyz - h2.w * p - 2.0 * h1.w * d1) / h.w;
    let speed2 = dot(d1, d1);
    var k = vec3<f32>(0.0);
    // At a cusp (P′ = 0) the curvature is unbounded: no hair.
    if (speed2 > 0.0) {
        k = (d2 - (dot(d2, d1) / speed2) * d1) / speed2;
    }
    return array<vec3<f32>, 2>(p, k);
}

// The segment of comb invocation `slot`, and (from the range's first invocation) the
// comb's arguments: 2 vertices per hair, then 2 per envelope piece (the layer's
// rasterizer reads both), then the rasterizer's workgroups (one sample's hair and
// envelope piece an invocation, the rest by stride past LAYER_GROUPS).
fn comb_work(slot: u32, first_lane: u32) -> AdaptiveWork {
    if (slot == 0u && first_lane == 0u) {
        let drawn = work[STAT_DRAWN];
        let pieces = max(drawn, 1u) - 1u;
        comb_args[0] = 2u * drawn;
        comb_args[4] = 2u * pieces;
        comb_args[8] = min((drawn + LAYER_WORKGROUP - 1u) / LAYER_WORKGROUP,
                           LAYER_GROUPS);
    }
    return adaptive_work(slot);
}

// The hairs segment `seg` of `count` sample slots gets: comb_hairs_of, fewer only where
// the sample budget cut its count.
fn comb_hairs(seg: Segment, count: u32) -> u32 {
    return min(count, comb_hairs_of(seg));
}

// The tag of a hidden envelope vertex at slot `slot`: never equal to a neighbour's.
fn hidden_tag(curve: u32, slot: u32) -> u32 {
    return curve | COMB_HIDDEN | select(0u, COMB_PARITY, slot % 2u == 1u);
}

// Writes hair j of the segment of `w`, from its point and curvature vector: cut to the
// cap (its tip then marked COMB_CAPPED and its envelope vertex hidden, so the envelope
// breaks there).
fn write_hair(w: AdaptiveWork, j: u32, pk: array<vec3<f32>, 2>) {
    let seg = w.seg;
    let slot = w.first + j;
    let shown = comb.curve == COMB_ALL || comb.curve == seg.curve;
    var hair = -comb.scale * pk[1];
    let length = sqrt(dot(hair, hair));
    let capped = length > comb.cap;
    if (capped) {
        hair = hair * (comb.cap / length);
    }
    let tip = pk[0] + hair;
    var tip_tag = seg.curve | select(0u, COMB_CAPPED, capped);
    var edge_tag = seg.curve;
    if (!shown) {
        tip_tag = seg.curve | COMB_HIDDEN;
    }
    if (!shown || capped) {
        edge_tag = hidden_tag(seg.curve, slot);
    }
    hairs[2u * slot] = Vertex(pk[0], seg.curve);
    hairs[2u * slot + 1u] = Vertex(tip, tip_tag);
    envelope[slot] = Vertex(tip, edge_tag);
}

// Slot j of the segment of `w` past its hairs: nothing drawn from it.
fn write_no_hair(w: AdaptiveWork, j: u32) {
    let slot = w.first + j;
    hairs[2u * slot] = Vertex(vec3<f32>(0.0), w.seg.curve);
    hairs[2u * slot + 1u] = Vertex(vec3<f32>(0.0), w.seg.curve | COMB_HIDDEN);
    envelope[slot] = Vertex(vec3<f32>(0.0), hidden_tag(w.seg.curve, slot));
}

// The hairs of slots j = first_lane, first_lane + stride, … of segment slot `slot` of
// the dispatch's range, any degree.
fn comb_segment(slot: u32, first_lane: u32, stride: u32) {
    let w = comb_work(slot, first_lane);
    if (!w.ok) {
        return;
    }
    let n = min(w.seg.degree, MAX_DEGREE);
    let hairs = comb_hairs(w.seg, w.count);
    for (var j = first_lane; j < w.count; j += stride) {
        if (j < hairs) {
            write_hair(w, j, point_and_curvature(w.seg.first_point, n, adaptive_param(j, hairs)));
        } else {
            write_no_hair(w, j);
        }
    }
}

// The comb of the cubic classes (polynomial and rational): their control points read
// once, the sums written out; SEGMENT_LANES invocations per segment, as their kernels.
@compute @workgroup_size(TESSELLATE_WORKGROUP_SIZE)
fn comb_cubic(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) index: u32,
) {
    let first_lane = index % SEGMENT_LANES;
    let w = comb_work(narrow_slot(group, index), first_lane);
    if (!w.ok) {
        return;
    }
    var h: array<vec4<f32>, 4>;
    for (var i = 0u; i < 4u; i++) {
        h[i] = control_point4(w.seg.first_point, i);
    }
    let hairs = comb_hairs(w.seg, w.count);
    for (var j = first_lane; j < w.count; j += SEGMENT_LANES) {
        if (j < hairs) {
            write_hair(w, j, cubic_point_and_curvature(h, adaptive_param(j, hairs)));
        } else {
            write_no_hair(w, j);
        }
    }
}

// The comb of the other narrow classes (quartics, rational quadratics): SEGMENT_LANES
// invocations per segment, as their tessellation kernels.
@compute @workgroup_size(TESSELLATE_WORKGROUP_SIZE)
fn comb_narrow(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) index: u32,
) {
    comb_segment(narrow_slot(group, index), index % SEGMENT_LANES, SEGMENT_LANES);
}

// The comb of every other segment: one workgroup per segment (see tessellate_any).
@compute @workgroup_size(TESSELLATE_WORKGROUP_SIZE)
fn comb_wide(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    comb_segment(group.x + group.y * range.groups_x, lane, TESSELLATE_WORKGROUP_SIZE);
}
