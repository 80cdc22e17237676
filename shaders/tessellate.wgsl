// Compute tessellation: every sample of every Bézier segment by de Casteljau.
//
// One workgroup per segment record (2D dispatch: record = record_start + x + y * groups_x);
// lane j of the workgroup evaluates sample sample_offset + j. Records hold at most
// TESSELLATE_WORKGROUP_SIZE samples (packing splits longer runs), so no lane loops over
// samples.
//
// There is one entry point per degree class. Packing sorts each chunk's records by class
// and the tessellator dispatches each class's range with its own pipeline: the cubic kernel
// sums its Bernstein form, the quartic kernel writes de Casteljau out, the general kernel
// sums the Bernstein form by Horner's rule (bernstein_horner). CPU twin: src/gpu/twin.rs, with the same operations in
// the same order.

@group(0) @binding(0) var<uniform> params: TessParams;
@group(0) @binding(1) var<storage, read> points: array<Vertex>;
@group(0) @binding(2) var<storage, read> records: array<Record>;
@group(0) @binding(3) var<storage, read_write> samples: array<Vertex>;

// The segment parameter of sample j: u0 (1 - f) + u1 f with f = j / (count - 1), so the
// first and last samples land exactly on u0 and u1.
fn sample_param(seg: Record, j: u32) -> f32 {
    var f = 0.0;
    if (seg.sample_count > 1u) {
        f = f32(j) / f32(seg.sample_count - 1u);
    }
    return seg.u0 * (1.0 - f) + seg.u1 * f;
}

// What one invocation evaluates: sample j of record seg, at parameter u; ok is false
// when the invocation has no sample (past the last record, or past the record's samples).
struct Work {
    seg: Record,
    j: u32,
    u: f32,
    ok: bool,
}

fn work(group: vec3<u32>, lane: u32) -> Work {
    var w: Work;
    w.ok = false;
    let s = params.record_start + group.x + group.y * params.groups_x;
    if (s >= params.record_end) {
        return w;
    }
    w.seg = records[s];
    w.j = w.seg.sample_offset + lane;
    if (w.j >= w.seg.sample_count) {
        return w;
    }
    w.u = sample_param(w.seg, w.j);
    w.ok = true;
    return w;
}

fn control_point(seg: Record, i: u32) -> vec3<f32> {
    return points[seg.first_point + i].position;
}

@compute @workgroup_size(TESSELLATE_WORKGROUP_SIZE)
fn tessellate_cubic(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let w = work(group, lane);
    if (!w.ok) {
        return;
    }
    let seg = w.seg;
    let u = w.u;
    let v = 1.0 - u;
    // The Bernstein form, v³P₀ + 3v²uP₁ + 3vu²P₂ + u³P₃: half de Casteljau's operations.
    let v2 = v * v;
    let u2 = u * u;
    let p = (v2 * v) * control_point(seg, 0u)
        + (3.0 * v2 * u) * control_point(seg, 1u)
        + (3.0 * v * u2) * control_point(seg, 2u)
        + (u2 * u) * control_point(seg, 3u);
    samples[seg.first_sample + w.j] = Vertex(p, seg.curve);
}

@compute @workgroup_size(TESSELLATE_WORKGROUP_SIZE)
fn tessellate_quartic(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let w = work(group, lane);
    if (!w.ok) {
        return;
    }
    let seg = w.seg;
    let u = w.u;
    let v = 1.0 - u;
    let p0 = control_point(seg, 0u);
    let p1 = control_point(seg, 1u);
    let p2 = control_point(seg, 2u);
    let p3 = control_point(seg, 3u);
    let p4 = control_point(seg, 4u);
    // One level, then the cubic on the four points it leaves.
    let p = cubic(v * p0 + u * p1, v * p1 + u * p2, v * p2 + u * p3, v * p3 + u * p4, u, v);
    samples[seg.first_sample + w.j] = Vertex(p, seg.curve);
}

@compute @workgroup_size(TESSELLATE_WORKGROUP_SIZE)
fn tessellate_any(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let w = work(group, lane);
    if (!w.ok) {
        return;
    }
    let seg = w.seg;
    let u = w.u;
    let v = 1.0 - u;
    // Packing rejects degrees over MAX_DEGREE; the min keeps the loop bounded.
    let n = min(seg.degree, MAX_DEGREE);
    let p = bernstein_horner(seg, n, u, v);
    samples[seg.first_sample + w.j] = Vertex(p, seg.curve);
}

// The Bernstein sum of degree n by Horner's rule in x = u / v, scaled by v^n (u ≤ 1/2), or
// in x = v / u from the other end, scaled by u^n: O(n) with the binomials built along the
// way and no scratch array (de Casteljau's triangle is O(n²) through a dynamically indexed
// array, which a CPU adapter keeps in memory). The ends are exact: x = 0 there.
fn bernstein_horner(seg: Record, n: u32, u: f32, v: f32) -> vec3<f32> {
    var acc: vec3<f32>;
    var scale = 1.0;
    var binomial = 1.0;
    if (u <= 0.5) {
        let x = u / v;
        acc = control_point(seg, n);
        for (var i = n; i > 0u; i--) {
            // C(n, i − 1) = C(n, i) · i / (n − i + 1)
            binomial = binomial * f32(i) / f32(n - i + 1u);
            acc = acc * x + binomial * control_point(seg, i - 1u);
            scale = scale * v;
        }
    } else {
        let x = v / u;
        acc = control_point(seg, 0u);
        for (var i = 1u; i <= n; i++) {
            // C(n, i) = C(n, i − 1) · (n − i + 1) / i
            binomial = binomial * f32(n - i + 1u) / f32(i);
            acc = acc * x + binomial * control_point(seg, i);
            scale = scale * u;
        }
    }
    return acc * scale;
}

// The bound of the kernels above for their output: the same records, the same invocations
// and the same writes, but no control point read and no arithmetic besides the parameter
// (sample j of a record holds (u, 0, 0) and the record's tag). `splinescope bench` times it
// next to the kernels on the same records.
@compute @workgroup_size(TESSELLATE_WORKGROUP_SIZE)
fn write_only(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let w = work(group, lane);
    if (!w.ok) {
        return;
    }
    samples[w.seg.first_sample + w.j] = Vertex(vec3<f32>(w.u, 0.0, 0.0), w.seg.curve);
}
