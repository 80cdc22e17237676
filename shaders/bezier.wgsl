// Bézier evaluation shared by both tessellators: composed after common.wgsl into
// tessellate.wgsl and adaptive.wgsl, each of which declares its control points as
// `points: array<ControlPoint>`. A segment's point at u by degree class — the cubic's
// Bernstein form, the quartic's de Casteljau written out, Bernstein–Horner for every other
// degree, and for rational segments Bernstein–Horner on the homogeneous points (w P, w)
// divided by the weight.
// CPU twin: fixed_kernel in crates/gpu/src/twin.rs, with the same operations in the same
// order.

fn control_point(first: u32, i: u32) -> vec3<f32> {
    return points[first + i].position;
}

// The homogeneous control point (w P, w).
fn control_point4(first: u32, i: u32) -> vec4<f32> {
    let c = points[first + i];
    return vec4<f32>(c.position, c.weight);
}

// The cubic Bernstein weights (v³, 3v²u, 3vu², u³), v = 1 − u.
fn cubic_weights(u: f32, v: f32) -> vec4<f32> {
    let v2 = v * v;
    let u2 = u * u;
    return vec4<f32>(v2 * v, 3.0 * v2 * u, 3.0 * v * u2, u2 * u);
}

// The cubic's Bernstein form, v³P₀ + 3v²uP₁ + 3vu²P₂ + u³P₃: half de Casteljau's
// operations. v = 1 − u.
fn cubic_bernstein(p0: vec3<f32>, p1: vec3<f32>, p2: vec3<f32>, p3: vec3<f32>, u: f32, v: f32) -> vec3<f32> {
    let b = cubic_weights(u, v);
    return b.x * p0 + b.y * p1 + b.z * p2 + b.w * p3;
}

// The same sum of homogeneous points (w P, w).
fn cubic_bernstein4(h0: vec4<f32>, h1: vec4<f32>, h2: vec4<f32>, h3: vec4<f32>, u: f32, v: f32) -> vec4<f32> {
    let b = cubic_weights(u, v);
    return b.x * h0 + b.y * h1 + b.z * h2 + b.w * h3;
}

// De Casteljau of a cubic, written out (its three levels): the quartic's last three.
// v = 1 − u.
fn cubic(p0: vec3<f32>, p1: vec3<f32>, p2: vec3<f32>, p3: vec3<f32>, u: f32, v: f32) -> vec3<f32> {
    let q0 = v * p0 + u * p1;
    let q1 = v * p1 + u * p2;
    let q2 = v * p2 + u * p3;
    let r0 = v * q0 + u * q1;
    let r1 = v * q1 + u * q2;
    return v * r0 + u * r1;
}

// A rational quadratic's point, written out: the homogeneous Bernstein sum
// v²H₀ + 2vuH₁ + u²H₂ divided by its weight lane.
fn rational_quadratic(h0: vec4<f32>, h1: vec4<f32>, h2: vec4<f32>, u: f32, v: f32) -> vec3<f32> {
    let h = (v * v) * h0 + (2.0 * v * u) * h1 + (u * u) * h2;
    return h.xyz / h.w;
}

// A rational cubic's point, written out: the cubic's Bernstein form on the homogeneous
// points, divided by its weight lane.
fn rational_cubic(h0: vec4<f32>, h1: vec4<f32>, h2: vec4<f32>, h3: vec4<f32>, u: f32, v: f32) -> vec3<f32> {
    let h = cubic_bernstein4(h0, h1, h2, h3, u, v);
    return h.xyz / h.w;
}

// One de Casteljau level, then the cubic on the four points it leaves.
fn quartic(p0: vec3<f32>, p1: vec3<f32>, p2: vec3<f32>, p3: vec3<f32>, p4: vec3<f32>, u: f32, v: f32) -> vec3<f32> {
    return cubic(v * p0 + u * p1, v * p1 + u * p2, v * p2 + u * p3, v * p3 + u * p4, u, v);
}

// The Bernstein sum of degree n of the homogeneous points from `first` on, O(n) by
// Horner's rule in 1 − u with the powers of u and the binomials built along the way:
// q ← C(n, k) u^k H_k + q (1 − u) for k = 1..n from q = H_0, with q (1 − u) as q − q u
// (fused, one rounding; unfused, within two of it) where u < 1/2, else as q v with v = 1 − u
// exact. Each term passes at most 3n roundings (2n where fma fuses), so the sum is within
// γ_{3n} Σ|H_i| B_i(u) in f32 (docs/math.md §4); the binomials are exact up to n = 24. No
// division and no scratch array (de Casteljau's triangle is O(n²) through a dynamically
// indexed array, which a CPU adapter keeps in memory). The ends are exact: at u = 0 every
// weight is 0; at u = 1 every step but the last multiplies by v = 0 and the last adds H_n.
fn bernstein_horner4(first: u32, n: u32, u: f32, v: f32) -> vec4<f32> {
    var q = control_point4(first, 0u);
    var power = 1.0;
    var binomial = 1.0;
    let below = u < 0.5;
    for (var k = 1u; k <= n; k++) {
        // C(n, k) = C(n, k − 1) · (n − k + 1) / k
        binomial = binomial * f32(n - k + 1u) / f32(k);
        power = power * u;
        let kept = select(q * v, fma(-q, vec4<f32>(u), q), below);
        q = fma(vec4<f32>(binomial * power), control_point4(first, k), kept);
    }
    return q;
}

// A polynomial segment's point: the homogeneous sum's first three lanes (its weights are
// all 1, and the lanes are computed independently).
fn bernstein_horner(first: u32, n: u32, u: f32, v: f32) -> vec3<f32> {
    return bernstein_horner4(first, n, u, v).xyz;
}

// A rational segment's point: the homogeneous sum divided by its weight lane. The ends
// are exact up to the division (x = 0 there).
fn rational_point(first: u32, n: u32, u: f32, v: f32) -> vec3<f32> {
    let h = bernstein_horner4(first, n, u, v);
    return h.xyz / h.w;
}

// What the general kernels compute for a segment of any degree: the rational point when
// it has weights, else the polynomial sum.
fn general_point(first: u32, n: u32, rational: bool, u: f32, v: f32) -> vec3<f32> {
    if (rational) {
        return rational_point(first, n, u, v);
    }
    return bernstein_horner(first, n, u, v);
}
