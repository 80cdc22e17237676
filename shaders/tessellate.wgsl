// Compute tessellation: every sample of every Bézier segment by de Casteljau.
//
// One workgroup per segment record (2D dispatch: record = record_start + x + y * groups_x);
// lane j of the workgroup evaluates sample sample_offset + j. Records hold at most
// TESSELLATE_WORKGROUP_SIZE samples (packing splits longer runs), so no lane loops over
// samples.
//
// There is one entry point per degree class (cubic, quartic, rational quadratic, rational
// cubic, any other degree — rational segments of other degrees included). Packing sorts each chunk's records by class
// and the tessellator dispatches each class's range with its own pipeline; the evaluation
// itself (the cubic's Bernstein form, the quartic's de Casteljau, Horner's rule for every
// other degree) is bezier.wgsl's, shared with the adaptive kernels. CPU twin:
// crates/gpu/src/twin.rs, with the same operations in the same order.

@group(0) @binding(0) var<uniform> params: TessParams;
@group(0) @binding(1) var<storage, read> points: array<ControlPoint>;
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
    let f = seg.first_point;
    let p = cubic_bernstein(
        control_point(f, 0u), control_point(f, 1u), control_point(f, 2u), control_point(f, 3u),
        u, 1.0 - u,
    );
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
    let f = seg.first_point;
    let p = quartic(
        control_point(f, 0u), control_point(f, 1u), control_point(f, 2u), control_point(f, 3u),
        control_point(f, 4u), u, v,
    );
    samples[seg.first_sample + w.j] = Vertex(p, seg.curve);
}

@compute @workgroup_size(TESSELLATE_WORKGROUP_SIZE)
fn tessellate_rational_quadratic(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let w = work(group, lane);
    if (!w.ok) {
        return;
    }
    let seg = w.seg;
    let u = w.u;
    let f = seg.first_point;
    let p = rational_quadratic(
        control_point4(f, 0u), control_point4(f, 1u), control_point4(f, 2u), u, 1.0 - u,
    );
    samples[seg.first_sample + w.j] = Vertex(p, seg.curve);
}

@compute @workgroup_size(TESSELLATE_WORKGROUP_SIZE)
fn tessellate_rational_cubic(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let w = work(group, lane);
    if (!w.ok) {
        return;
    }
    let seg = w.seg;
    let u = w.u;
    let f = seg.first_point;
    let p = rational_cubic(
        control_point4(f, 0u), control_point4(f, 1u), control_point4(f, 2u),
        control_point4(f, 3u), u, 1.0 - u,
    );
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
    let p = general_point(seg.first_point, n, seg.rational != 0u, u, v);
    samples[seg.first_sample + w.j] = Vertex(p, seg.curve);
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
