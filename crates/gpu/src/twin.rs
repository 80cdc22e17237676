//! The CPU twins of `shaders/tessellate.wgsl` and `shaders/adaptive.wgsl`: the same
//! layout, the same loops, in `f32`.
//! Tests compare the GPU's output with it (and both with the exact `f64` curves).

use glam::{Mat4, Vec2, Vec3, Vec4};

use super::layout::{
    FrameStats, GpuControlPoint, GpuFrame, GpuRecord, GpuSegment, GpuTessParams, GpuVertex,
    MAX_GPU_DEGREE, TESSELLATE_WORKGROUP_SIZE,
};

/// `sample_param` of the shader: `u0 (1 − f) + u1 f`, `f = j / (count − 1)`.
#[must_use]
pub fn sample_param(seg: &GpuRecord, j: u32) -> f32 {
    let f = if seg.sample_count > 1 {
        j as f32 / (seg.sample_count - 1) as f32
    } else {
        0.0
    };
    seg.u0 * (1.0 - f) + seg.u1 * f
}

/// The homogeneous control point `(w·P, w)` at `first + i`: `control_point4` of
/// `shaders/bezier.wgsl`.
fn control_point4(points: &[GpuControlPoint], first: u32, i: u32) -> Vec4 {
    let c = points[(first + i) as usize];
    Vec3::from(c.position).extend(c.weight)
}

/// De Casteljau of degree `n` from `points[first ..= first + n]` at `u`: what the
/// quartic kernels (`quartic` of `shaders/bezier.wgsl`) write out, with exactly this loop's
/// operations in this order.
#[must_use]
pub fn de_casteljau(points: &[GpuControlPoint], first: u32, n: u32, u: f32) -> Vec3 {
    let v = 1.0 - u;
    let m = (n as usize).min(MAX_GPU_DEGREE);
    let mut p = [Vec3::ZERO; MAX_GPU_DEGREE + 1];
    for (i, slot) in p.iter_mut().enumerate().take(m + 1) {
        *slot = Vec3::from(points[first as usize + i].position);
    }
    for level in (1..=m).rev() {
        for i in 0..level {
            p[i] = v * p[i] + u * p[i + 1];
        }
    }
    p[0]
}

/// `bernstein_horner4` of `shaders/bezier.wgsl` (the general kernels of both
/// tessellators): the Bernstein sum of degree `n` of the homogeneous points `(w·P, w)` by
/// Horner's rule in `1 − u`, `q ← C(n, k) uᵏ H_k + q (1 − u)` from `q = H_0`, with
/// `q (1 − u)` as the fused `q − q u` where `u < ½` and as `q v` otherwise, the binomials
/// and powers built along the way. Compiled also for AVX2 + FMA and chosen at run time
/// (`multiversion`): the fused operations are one instruction there, software elsewhere.
#[must_use]
#[multiversion::multiversion(targets("x86_64+avx2+fma"))]
pub fn bernstein_horner4(points: &[GpuControlPoint], first: u32, n: u32, u: f32) -> Vec4 {
    let v = 1.0 - u;
    let n = n.min(MAX_GPU_DEGREE as u32);
    let p = |i: u32| control_point4(points, first, i);
    let (mut power, mut binomial) = (1.0_f32, 1.0_f32);
    let mut q = p(0);
    for k in 1..=n {
        binomial = binomial * (n - k + 1) as f32 / k as f32;
        power *= u;
        let kept = if u < 0.5 {
            (-q).mul_add(Vec4::splat(u), q)
        } else {
            q * v
        };
        q = Vec4::splat(binomial * power).mul_add(p(k), kept);
    }
    q
}

/// `bernstein_horner` of `shaders/bezier.wgsl`: [`bernstein_horner4`]'s first three lanes.
#[must_use]
pub fn bernstein_horner(points: &[GpuControlPoint], first: u32, n: u32, u: f32) -> Vec3 {
    bernstein_horner4(points, first, n, u).truncate()
}

/// `rational_point` of `shaders/bezier.wgsl`: [`bernstein_horner4`] divided by its weight
/// lane.
#[must_use]
pub fn rational_point(points: &[GpuControlPoint], first: u32, n: u32, u: f32) -> Vec3 {
    let h = bernstein_horner4(points, first, n, u);
    h.truncate() / h.w
}

/// `cubic_weights` of `shaders/bezier.wgsl`: `(v³, 3v²u, 3vu², u³)`, `v = 1 − u`.
fn cubic_weights(u: f32) -> [f32; 4] {
    let v = 1.0 - u;
    let (v2, u2) = (v * v, u * u);
    [v2 * v, 3.0 * v2 * u, 3.0 * v * u2, u2 * u]
}

/// What both tessellators' kernels compute for a segment of `degree` (`shaders/bezier.wgsl`):
/// for a rational one the homogeneous Bernstein sum written out (quadratics and cubics,
/// the cubic's weights as below) divided by its weight lane, [`rational_point`] for other
/// degrees; otherwise the cubic's Bernstein form
/// `v³P₀ + 3v²uP₁ + 3vu²P₂ + u³P₃`, de Casteljau written out for quartics,
/// [`bernstein_horner`] for every other degree.
#[must_use]
pub fn fixed_kernel(
    points: &[GpuControlPoint],
    first: u32,
    degree: u32,
    rational: bool,
    u: f32,
) -> Vec3 {
    if rational {
        let h = |i: u32| control_point4(points, first, i);
        let v = 1.0 - u;
        let sum = match degree {
            2 => (v * v) * h(0) + (2.0 * v * u) * h(1) + (u * u) * h(2),
            3 => {
                let b = cubic_weights(u);
                b[0] * h(0) + b[1] * h(1) + b[2] * h(2) + b[3] * h(3)
            }
            _ => return rational_point(points, first, degree, u),
        };
        return sum.truncate() / sum.w;
    }
    match degree {
        3 => {
            let p = |i: u32| Vec3::from(points[(first + i) as usize].position);
            let b = cubic_weights(u);
            b[0] * p(0) + b[1] * p(1) + b[2] * p(2) + b[3] * p(3)
        }
        4 => de_casteljau(points, first, degree, u),
        _ => bernstein_horner(points, first, degree, u),
    }
}

/// One workgroup's body: every lane of `record` writes its sample (the kernel's `work()`
/// and entry point).
fn run_record(record: &GpuRecord, points: &[GpuControlPoint], samples: &mut [GpuVertex]) {
    for lane in 0..TESSELLATE_WORKGROUP_SIZE {
        let j = record.sample_offset + lane;
        if j >= record.sample_count {
            break;
        }
        let u = sample_param(record, j);
        samples[(record.first_sample + j) as usize] = GpuVertex {
            position: fixed_kernel(
                points,
                record.first_point,
                record.degree,
                record.rational != 0,
                u,
            )
            .to_array(),
            id: record.curve,
        };
    }
}

/// Runs the kernels' body for every lane of every record, writing into `samples`.
///
/// # Panics
/// When a record points outside `points` or `samples` (a packing bug).
pub fn tessellate(points: &[GpuControlPoint], records: &[GpuRecord], samples: &mut [GpuVertex]) {
    for record in records {
        run_record(record, points, samples);
    }
}

/// One dispatch of the kernel, as the GPU runs it: every workgroup `(x, y)` of the
/// `groups` grid takes record `record_start + x + y · groups_x` when it is below
/// `record_end` (`work()` in the shader), and each of its lanes writes one sample. The
/// twin of [`super::tessellator::plan`]'s dispatches.
///
/// # Panics
/// When a record points outside `points` or `samples` (a packing bug).
pub fn dispatch(
    params: &GpuTessParams,
    groups: (u32, u32),
    points: &[GpuControlPoint],
    records: &[GpuRecord],
    samples: &mut [GpuVertex],
) {
    for gy in 0..groups.1 {
        for gx in 0..groups.0 {
            let s = params.record_start + gx + gy * params.groups_x;
            if s < params.record_end {
                run_record(&records[s as usize], points, samples);
            }
        }
    }
}

/// The twin of `wang_count` in `shaders/adaptive.wgsl`: the samples segment `seg` gets in
/// the frame `frame` (its fixed count; 0 wholly off screen; the most when a control point
/// is at or behind the eye; otherwise Wang's bound in homogeneous pixel coordinates,
/// `docs/math.md` §5), in the shader's `f32` operations.
#[must_use]
pub fn wang_count(frame: &GpuFrame, points: &[GpuControlPoint], seg: &GpuSegment) -> u32 {
    if seg.fixed > 0 {
        return seg.fixed;
    }
    let n = (seg.degree as usize).min(MAX_GPU_DEGREE);
    let half = 0.5 * Vec2::from(frame.viewport_px);
    let m = Mat4::from_cols_array_2d(&frame.clip_from_world);
    let mut h = [Vec3::ZERO; MAX_GPU_DEGREE + 1];
    let (mut w_min, mut w_max) = (f32::MAX, 0.0_f32);
    for (i, slot) in h.iter_mut().enumerate().take(n + 1) {
        let q = points[seg.first_point as usize + i];
        let c = m * Vec3::from(q.position).extend(q.weight);
        *slot = Vec3::new(c.x * half.x, -c.y * half.y, c.w);
        w_min = w_min.min(c.w);
        w_max = w_max.max(c.w.abs());
    }
    if w_min.is_nan() || w_min <= ADAPTIVE_NEAR_W * w_max {
        return frame.max_count;
    }
    let (mut lo, mut hi, mut r) = (Vec2::splat(f32::MAX), Vec2::splat(-f32::MAX), 0.0_f32);
    for q in &h[..=n] {
        let p = q.truncate() / q.z;
        lo = lo.min(p);
        hi = hi.max(p);
    }
    // Pixel coordinates about the middle of the projected control points (see the shader).
    let centre = 0.5 * (lo + hi);
    for q in &h[..=n] {
        r = r.max((q.truncate() / q.z - centre).length());
    }
    let margin = frame.cull_margin_px;
    if hi.x < -half.x - margin
        || lo.x > half.x + margin
        || hi.y < -half.y - margin
        || lo.y > half.y + margin
    {
        return 0;
    }
    let (mut m_xy, mut m_w) = (0.0_f32, 0.0_f32);
    for i in 0..n.saturating_sub(1) {
        let d = h[i] - 2.0 * h[i + 1] + h[i + 2];
        m_xy = m_xy.max((d.truncate() - centre * d.z).length());
        m_w = m_w.max(d.z.abs());
    }
    let nn = (n * n.saturating_sub(1)) as f32;
    let intervals = (nn * (m_xy + r * m_w)
        / (8.0 * frame.tolerance_px * w_floor(&h, n, w_min, w_max)))
    .sqrt()
    .ceil();
    if intervals.is_nan() || intervals >= frame.max_count as f32 {
        return frame.max_count;
    }
    let floor = if frame.min_count == 0 {
        0
    } else {
        comb_hairs_of(frame, points, seg).min(frame.min_count)
    };
    (intervals as u32 + 1).max(floor).clamp(2, frame.max_count)
}

/// The twin of `comb_hairs_of` in `shaders/adaptive.wgsl`: the hairs of segment `seg`'s
/// comb in the frame `frame` — one every [`crate::layout::COMB_SPACING_PX`] pixels of its
/// projected control polygon and one more, from 2 to [`crate::layout::COMB_HAIRS`] (the
/// most with a point at or behind the eye, or a length that is not finite), in the
/// shader's `f32` operations.
#[must_use]
pub fn comb_hairs_of(frame: &GpuFrame, points: &[GpuControlPoint], seg: &GpuSegment) -> u32 {
    use crate::layout::{COMB_HAIRS, COMB_SPACING_PX};
    let n = (seg.degree as usize).min(MAX_GPU_DEGREE);
    let half = 0.5 * Vec2::from(frame.viewport_px);
    let m = Mat4::from_cols_array_2d(&frame.clip_from_world);
    let mut length = 0.0_f32;
    let mut previous = Vec2::ZERO;
    for i in 0..=n {
        let q = points[seg.first_point as usize + i];
        let c = m * Vec3::from(q.position).extend(q.weight);
        if c.w.is_nan() || c.w <= 0.0 {
            return COMB_HAIRS;
        }
        let p = Vec2::new(c.x * half.x, -c.y * half.y) / c.w;
        if i > 0 {
            length += p.distance(previous);
        }
        previous = p;
    }
    if length.is_nan() || length >= 1e9 {
        return COMB_HAIRS;
    }
    ((length / COMB_SPACING_PX).ceil() as u32 + 1).clamp(2, COMB_HAIRS)
}

/// A lower bound of the homogeneous `w` of `h[..=n]` (weights from `w_min` to `w_max`) on
/// `[0, 1]`, at least `w_min`: the smallest Bernstein coefficient of its two halves split
/// at ½, the `k`-th of each `2⁻ᵏ Σ_j C(k, j) w_j` from its own end, less
/// [`WEIGHT_ROUNDING`] of itself; `w_min` itself when every weight is the same. Twin of the
/// same lines of `wang_count` in `shaders/adaptive.wgsl` (the same operations in `f32`).
fn w_floor(h: &[Vec3], n: usize, w_min: f32, w_max: f32) -> f32 {
    // Equal weights (a polynomial segment seen orthographically) are their own floor.
    if w_max <= w_min {
        return w_min;
    }
    let mut low = h[0].z.min(h[n].z);
    let mut half_k = 1.0_f32;
    for k in 1..=n {
        half_k *= 0.5;
        let (mut binomial, mut left, mut right) = (1.0_f32, 0.0_f32, 0.0_f32);
        for j in 0..=k {
            left += binomial * h[j].z;
            right += binomial * h[n - k + j].z;
            binomial = binomial * (k - j) as f32 / (j + 1) as f32;
        }
        low = low.min(left.min(right) * half_k);
    }
    w_min.max(low * (1.0 - WEIGHT_ROUNDING))
}

/// Twin of `WEIGHT_ROUNDING` in `shaders/adaptive.wgsl`: above `(n + 3) 2⁻²⁴` (the relative
/// rounding of a sum of `n + 1` positive terms with rounded binomials) for every degree up
/// to 31.
pub const WEIGHT_ROUNDING: f32 = 4e-6;

/// Twin of `NEAR_W` in `shaders/adaptive.wgsl`.
pub const ADAPTIVE_NEAR_W: f32 = 1e-5;

/// The twin of `scan_blocks`, `scan_sums` and `finalize`: from each segment's requested
/// count, its offset and final count in a buffer of `capacity` samples, and the frame's
/// statistics. When the counts exceed the buffer every drawn segment keeps 2 samples and
/// the rest shrink in proportion (`placed` in the shader).
#[must_use]
pub fn scan_and_place(counts: &[u32], capacity: u32) -> (Vec<u32>, Vec<u32>, FrameStats) {
    let total: u32 = counts.iter().sum();
    let drawn_total = counts.iter().filter(|&&c| c > 0).count() as u32;
    let ratio = if total > capacity {
        (capacity - 2 * drawn_total) as f32 / (total - 2 * drawn_total) as f32
    } else {
        1.0
    };
    let placed = |offset: u32, drawn: u32| -> u32 {
        if ratio >= 1.0 {
            return offset;
        }
        let base = 2 * drawn;
        (base + ((offset - base) as f32 * ratio).floor() as u32).min(capacity)
    };
    let (mut offset, mut drawn) = (0u32, 0u32);
    let mut offsets = Vec::with_capacity(counts.len());
    let mut finals = Vec::with_capacity(counts.len());
    let mut end = 0;
    for &c in counts {
        let start = placed(offset, drawn);
        offset += c;
        drawn += u32::from(c > 0);
        end = placed(offset, drawn);
        offsets.push(start);
        finals.push(end - start);
    }
    let stats = FrameStats {
        vertex_count: super::layout::LINE_CORNERS,
        instance_count: end.max(1) - 1,
        first_vertex: 0,
        first_instance: 0,
        requested: total,
        drawn: end,
        segments_drawn: drawn_total,
        capped: u32::from(ratio < 1.0),
    };
    (offsets, finals, stats)
}

/// The twin of the adaptive `tessellate_*` kernels: segment `s` writes its `counts[s]`
/// samples at `u = j / (count − 1)` from `offsets[s]` on.
///
/// # Panics
/// When a segment points outside `points` or `samples` (a packing bug).
pub fn tessellate_adaptive(
    points: &[GpuControlPoint],
    segments: &[GpuSegment],
    offsets: &[u32],
    counts: &[u32],
    samples: &mut [GpuVertex],
) {
    for ((seg, &first), &count) in segments.iter().zip(offsets).zip(counts) {
        for j in 0..count {
            let u = if count < 2 {
                0.0
            } else {
                j as f32 / (count - 1) as f32
            };
            samples[(first + j) as usize] = GpuVertex {
                position: fixed_kernel(points, seg.first_point, seg.degree, seg.rational != 0, u)
                    .to_array(),
                id: seg.curve,
            };
        }
    }
}

/// `difference` of `shaders/comb.wgsl`: the `k`-th forward difference (`k ≤ 2`) of the
/// homogeneous control points at `first + i`.
fn comb_difference(points: &[GpuControlPoint], first: u32, i: u32, k: u32) -> Vec4 {
    let a = control_point4(points, first, i);
    if k == 0 {
        return a;
    }
    let b = control_point4(points, first, i + 1);
    if k == 1 {
        return b - a;
    }
    control_point4(points, first, i + 2) - 2.0 * b + a
}

/// `difference_sum` of `shaders/comb.wgsl`: `Σ Δᵏ H_i B_i^m(u)`, `m = n − k`, by Horner's
/// rule in `u / v` (or `v / u` past the middle), scaled by `vᵐ` (or `uᵐ`), with the
/// kernel's operations in its order.
fn comb_difference_sum(points: &[GpuControlPoint], first: u32, n: u32, k: u32, u: f32) -> Vec4 {
    let v = 1.0 - u;
    let m = n - k;
    let mut scale = 1.0_f32;
    let mut binomial = 1.0_f32;
    let mut acc;
    if u <= 0.5 {
        let x = u / v;
        acc = comb_difference(points, first, m, k);
        for i in (1..=m).rev() {
            binomial = binomial * i as f32 / (m - i + 1) as f32;
            acc = acc * x + binomial * comb_difference(points, first, i - 1, k);
            scale *= v;
        }
    } else {
        let x = v / u;
        acc = comb_difference(points, first, 0, k);
        for i in 1..=m {
            binomial = binomial * (m - i + 1) as f32 / i as f32;
            acc = acc * x + binomial * comb_difference(points, first, i, k);
            scale *= u;
        }
    }
    acc * scale
}

/// `curvature_from` of `shaders/comb.wgsl`: the point and the curvature vector
/// `K = (P″ − (P″·T) T) / |P′|²` from the homogeneous point and its first two
/// derivatives; `K = 0` at a cusp (`P′ = 0`).
fn curvature_from(h: Vec4, h1: Vec4, h2: Vec4) -> (Vec3, Vec3) {
    let p = h.truncate() / h.w;
    let d1 = (h1.truncate() - h1.w * p) / h.w;
    let d2 = (h2.truncate() - h2.w * p - 2.0 * h1.w * d1) / h.w;
    let speed2 = d1.dot(d1);
    let k = if speed2 > 0.0 {
        (d2 - (d2.dot(d1) / speed2) * d1) / speed2
    } else {
        Vec3::ZERO
    };
    (p, k)
}

/// The twin of the comb kernels' evaluation (`shaders/comb.wgsl`): the point and the
/// curvature vector at `u` of the segment of degree `n` whose homogeneous control points
/// start at `first` — a cubic (polynomial or rational) by `cubic_point_and_curvature`'s
/// Bernstein sums written out, as `comb_cubic` takes it, any other degree by
/// `point_and_curvature`'s Horner sums of differences, as `comb_narrow` and `comb_wide`.
#[must_use]
pub fn comb_point_and_curvature(
    points: &[GpuControlPoint],
    first: u32,
    n: u32,
    u: f32,
) -> (Vec3, Vec3) {
    if n == 3 {
        let h: [Vec4; 4] = std::array::from_fn(|i| control_point4(points, first, i as u32));
        let v = 1.0 - u;
        let (v2, u2) = (v * v, u * u);
        let b = cubic_weights(u);
        let point = b[0] * h[0] + b[1] * h[1] + b[2] * h[2] + b[3] * h[3];
        let (d0, d1, d2) = (h[1] - h[0], h[2] - h[1], h[3] - h[2]);
        let h1 = 3.0 * (d0 * v2 + d1 * (2.0 * u * v) + d2 * u2);
        let h2 = 6.0 * ((d1 - d0) * v + (d2 - d1) * u);
        return curvature_from(point, h1, h2);
    }
    let nf = n as f32;
    let h = comb_difference_sum(points, first, n, 0, u);
    let h1 = if n >= 1 {
        nf * comb_difference_sum(points, first, n, 1, u)
    } else {
        Vec4::ZERO
    };
    let h2 = if n >= 2 {
        nf * (nf - 1.0) * comb_difference_sum(points, first, n, 2, u)
    } else {
        Vec4::ZERO
    };
    curvature_from(h, h1, h2)
}

/// The twin of `write_hair` in `shaders/comb.wgsl`: the hair's tip from the point and
/// the curvature vector, `P − scale · K`, cut to `cap` (then `true`: the tip is marked
/// capped and the envelope breaks there).
#[must_use]
pub fn comb_hair(point: Vec3, k: Vec3, scale: f32, cap: f32) -> (Vec3, bool) {
    let mut hair = -scale * k;
    let length = hair.dot(hair).sqrt();
    let capped = length > cap;
    if capped {
        hair *= cap / length;
    }
    (point + hair, capped)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `Σ w_i B_i(t)` in `f64`, by de Casteljau.
    fn weight_at(w: &[f32], t: f64) -> f64 {
        let mut v: Vec<f64> = w.iter().map(|&x| f64::from(x)).collect();
        for level in 1..v.len() {
            for i in 0..v.len() - level {
                v[i] = (1.0 - t) * v[i] + t * v[i + 1];
            }
        }
        v[0]
    }

    #[test]
    fn the_weight_floor_stays_under_the_weight_and_above_the_smallest_one() {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        for n in 1..=MAX_GPU_DEGREE {
            for _ in 0..20 {
                // Positive weights over three orders of magnitude.
                let w: Vec<f32> = (0..=n).map(|_| 0.02 * 1000f32.powf(next())).collect();
                let h: Vec<Vec3> = w.iter().map(|&x| Vec3::new(0.0, 0.0, x)).collect();
                let w_min = w.iter().copied().fold(f32::MAX, f32::min);
                let floor = w_floor(&h, n, w_min, w.iter().copied().fold(0.0, f32::max));
                assert!(floor >= w_min, "degree {n}: {floor} below {w_min}");
                for s in 0..=4000 {
                    let t = f64::from(s) / 4000.0;
                    let v = weight_at(&w, t);
                    assert!(
                        f64::from(floor) <= v,
                        "degree {n}: {floor} above w({t}) = {v} ({w:?})"
                    );
                }
            }
        }
        // Where the smallest weight is an inner one, the floor is well above it: for
        // (1, 4, ¼, 2) the halves' coefficients are (1, 5/2, 37/16, 63/32) and
        // (63/32, 13/8, 9/8, 2), so the floor is 1 (the weight's own minimum, at t = 0).
        let h: Vec<Vec3> = [1.0, 4.0, 0.25, 2.0]
            .iter()
            .map(|&x| Vec3::new(0.0, 0.0, x))
            .collect();
        let floor = w_floor(&h, 3, 0.25, 4.0);
        assert!((floor - 1.0).abs() <= 2.0 * WEIGHT_ROUNDING, "{floor}");
    }
}
