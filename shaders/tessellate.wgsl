// Compute tessellation: every sample of every Bézier segment by de Casteljau.
// One workgroup per segment (2D dispatch: index = x + y * groups_x); its threads stride
// over the segment's samples. CPU twin: src/gpu/twin.rs (same layout, same loop).

@group(0) @binding(0) var<uniform> params: TessParams;
@group(0) @binding(1) var<storage, read> points: array<Vertex>;
@group(0) @binding(2) var<storage, read> segments: array<Segment>;
@group(0) @binding(3) var<storage, read_write> samples: array<Vertex>;

// The segment parameter of sample j: u0 (1 - f) + u1 f with f = j / (count - 1), so the
// first and last samples land exactly on u0 and u1.
fn sample_param(seg: Segment, j: u32) -> f32 {
    var f = 0.0;
    if (seg.sample_count > 1u) {
        f = f32(j) / f32(seg.sample_count - 1u);
    }
    return seg.u0 * (1.0 - f) + seg.u1 * f;
}

@compute @workgroup_size(TESSELLATE_WORKGROUP_SIZE)
fn tessellate(
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) lane: u32,
) {
    let s = group.x + group.y * params.groups_x;
    if (s >= params.segment_count) {
        return;
    }
    let seg = segments[s];
    // Packing rejects degrees over MAX_DEGREE; the min only keeps p[] in bounds.
    let n = min(seg.degree, MAX_DEGREE);
    for (var j = lane; j < seg.sample_count; j += TESSELLATE_WORKGROUP_SIZE) {
        let u = sample_param(seg, j);
        let v = 1.0 - u;
        var p: array<vec3<f32>, 32>;
        for (var i = 0u; i <= n; i++) {
            p[i] = points[seg.first_point + i].position;
        }
        for (var r = 1u; r <= n; r++) {
            for (var i = 0u; i <= n - r; i++) {
                p[i] = v * p[i] + u * p[i + 1u];
            }
        }
        samples[seg.first_sample + j] = Vertex(p[0], seg.curve);
    }
}
