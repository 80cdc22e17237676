//! Evaluating curves at given parameters with the GPU kernel (`eval --backend gpu`).
//!
//! Each requested parameter becomes a one-sample record of the segment that holds it, so
//! the kernel evaluates exactly that parameter (rounded to `f32`); results are read back.
//!
//! Each segment goes to the kernel scaled by a power of two that brings its largest
//! coordinate into `[1, 2)`, and its values are scaled back after: exact in both
//! directions, so a curve whose coordinates are far below `f32`'s normal range (`1e-111`)
//! is evaluated within the same relative bound as any other instead of being flushed to
//! zero, while ordinary curves get the very values they got unscaled.

use glam::DVec3;

use super::GpuError;
use super::context::GpuContext;
use super::layout::GpuVertex;
use super::pack::check_gpu_fit;
use super::pipelines::Pipelines;
use crate::chunks::{ChunkBuilder, ChunkLimits};
use splinescope_core::geom::{BezierSegment, locate};
use splinescope_core::num::{scale_by_power_of_two, split_exponent};
use splinescope_encoding::Color;

/// Evaluates each curve (given as its lowered segments, with its scene index for error
/// messages) at its parameters, on the GPU.
///
/// # Errors
/// [`GpuError::Pack`] for a degree over the GPU maximum, [`GpuError::Readback`] when
/// reading fails or a sample was left unwritten.
pub fn evaluate(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    curves: &[(usize, Vec<BezierSegment>)],
    params: &[Vec<f64>],
) -> Result<Vec<Vec<DVec3>>, GpuError> {
    evaluate_with_limits(
        ctx,
        pipelines,
        curves,
        params,
        ChunkLimits::for_binding_size(ctx.max_binding_bytes()),
    )
}

/// [`evaluate`] with explicit chunk limits (tests use small ones to exercise chunking).
///
/// # Errors
/// As [`evaluate`].
pub fn evaluate_with_limits(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    curves: &[(usize, Vec<BezierSegment>)],
    params: &[Vec<f64>],
    limits: ChunkLimits,
) -> Result<Vec<Vec<DVec3>>, GpuError> {
    let style = super::layout::GpuLineStyle::solid(Color::WHITE, 1.0);
    let mut builder = ChunkBuilder::new(limits);
    // The binary exponent each sample's value is to be scaled back by.
    let mut scales: Vec<i32> = Vec::with_capacity(params.iter().map(Vec::len).sum());
    for (slot, ((index, segments), ts)) in curves.iter().zip(params).enumerate() {
        check_gpu_fit(*index, segments)?;
        let mut open: Option<(usize, i32)> = None;
        for &t in ts {
            let Some((s, u)) = locate(segments, t) else {
                continue;
            };
            let scale = match open {
                Some((o, scale)) if o == s => scale,
                _ => {
                    let seg = &segments[s];
                    let (points, scale) = unit_scaled(seg.points());
                    builder.begin_segment(slot, style, &points, seg.weights.as_deref())?;
                    open = Some((s, scale));
                    scale
                }
            };
            builder.add_samples(1, u, u);
            scales.push(scale);
        }
    }
    let chunks = builder.finish();
    let tessellator = &pipelines.tessellator;
    let mut all: Vec<GpuVertex> = Vec::with_capacity(params.iter().map(Vec::len).sum());
    ctx.check_health()?;
    let read = tessellator.tessellate_and_read(&ctx.device, &ctx.queue, &chunks, |_, samples| {
        all.extend_from_slice(samples);
    });
    ctx.check_health()?;
    read?;
    if let Some(i) = all
        .iter()
        .position(|v| v.position.iter().any(|c| c.is_nan()))
    {
        return Err(GpuError::Readback(format!(
            "sample {i} was not written by the kernel"
        )));
    }
    let mut out = Vec::with_capacity(curves.len());
    let mut it = all.into_iter().zip(scales).map(|(v, e)| {
        let p = glam::Vec3::from(v.position).as_dvec3();
        DVec3::from_array(p.to_array().map(|c| scale_by_power_of_two(c, e)))
    });
    for ((_, segments), ts) in curves.iter().zip(params) {
        let n = if segments.is_empty() { 0 } else { ts.len() };
        out.push(it.by_ref().take(n).collect());
    }
    Ok(out)
}

/// `points` divided by the power of two `2^e` that brings their largest coordinate
/// magnitude into `[1, 2)`, and `e` (0 for all-zero points). Exact (barring points below
/// `2^e · 2⁻¹⁰⁷⁴`, which no `f32` result could show anyway); a value of the scaled points
/// is scaled back with [`splinescope_core::num::scale_by_power_of_two`].
#[must_use]
pub fn unit_scaled(points: &[DVec3]) -> (Vec<DVec3>, i32) {
    let largest = points
        .iter()
        .map(|p| p.abs().max_element())
        .fold(0.0, f64::max);
    if largest == 0.0 || !largest.is_finite() {
        return (points.to_vec(), 0);
    }
    let (_, e) = split_exponent(largest);
    let down = |p: &DVec3| DVec3::from_array(p.to_array().map(|c| scale_by_power_of_two(c, -e)));
    (points.iter().map(down).collect(), e)
}

/// The `order`-th hodograph of each lowered segment (same `t0`, `t1`): the Bézier curve
/// whose value at `u` is `dᵏP/duᵏ`. Degree `n − k`; a segment of degree below `k` has the
/// zero curve of degree 0. A rational segment's hodograph is taken of its homogeneous
/// part `A = Σ w_i P_i B_i` (polynomial; see [`evaluate_derivative`]).
#[must_use]
pub fn hodographs(segments: &[BezierSegment], order: u32) -> Vec<BezierSegment> {
    part_hodographs(segments, order, false)
}

/// The `order`-th hodograph of each segment's homogeneous part `A` or, with `weight`,
/// `W` ([`BezierSegment::homogeneous`]), on the same parameter ranges.
fn part_hodographs(segments: &[BezierSegment], order: u32, weight: bool) -> Vec<BezierSegment> {
    segments
        .iter()
        .map(|s| {
            let (a, w) = s.homogeneous();
            let mut b = if weight { w } else { a };
            for _ in 0..order {
                b = b.deriv();
            }
            BezierSegment::polynomial(b, s.t0, s.t1)
        })
        .collect()
}

/// Evaluates the `order`-th derivative (1 or 2) of each curve at its parameters on the
/// GPU: the hodographs go through the same kernel as the curves, and the chain rule
/// divides by `(t1 − t0)ᵏ` of the segment holding each parameter. A curve with rational
/// segments has its homogeneous parts `A`, `W` and their hodographs evaluated by the
/// kernel, with the curve itself, and the quotient rule combines
/// them on the CPU: `C′ = (A′ − W′C) / W`, `C″ = (A″ − 2W′C′ − W″C) / W`.
///
/// # Errors
/// As [`evaluate`].
pub fn evaluate_derivative(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    curves: &[(usize, Vec<BezierSegment>)],
    params: &[Vec<f64>],
    order: u32,
) -> Result<Vec<Vec<DVec3>>, GpuError> {
    let rational = curves
        .iter()
        .any(|(_, segs)| segs.iter().any(BezierSegment::is_rational));
    let by_u = if rational {
        quotient_rule(ctx, pipelines, curves, params, order)?
    } else {
        let hodo: Vec<(usize, Vec<BezierSegment>)> = curves
            .iter()
            .map(|(i, segs)| (*i, hodographs(segs, order)))
            .collect();
        evaluate(ctx, pipelines, &hodo, params)?
    };
    Ok(curves
        .iter()
        .zip(params)
        .zip(by_u)
        .map(|(((_, segs), ts), vs)| {
            ts.iter()
                .zip(vs)
                .map(|(&t, v)| match locate(segs, t) {
                    Some((s, _)) => v / (segs[s].t1 - segs[s].t0).powi(order as i32),
                    None => v,
                })
                .collect()
        })
        .collect())
}

/// The `order`-th derivative (1 or 2) with respect to each segment's own parameter, by
/// the quotient rule over GPU evaluations of `C`, `A^(k)` and `W^(k)`.
fn quotient_rule(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    curves: &[(usize, Vec<BezierSegment>)],
    params: &[Vec<f64>],
    order: u32,
) -> Result<Vec<Vec<DVec3>>, GpuError> {
    // Per derivative k = 0..=order, the parts A^(k) and W^(k) of every curve, then the
    // curve itself: evaluated together in one call.
    let part = |k: u32, weight: bool| -> Vec<(usize, Vec<BezierSegment>)> {
        curves
            .iter()
            .map(|(i, segs)| (*i, part_hodographs(segs, k, weight)))
            .collect()
    };
    let mut all: Vec<(usize, Vec<BezierSegment>)> = curves.to_vec();
    let mut all_params: Vec<Vec<f64>> = params.to_vec();
    for k in 0..=order {
        for weight in [false, true] {
            all.extend(part(k, weight));
            all_params.extend(params.iter().cloned());
        }
    }
    let values = evaluate(ctx, pipelines, &all, &all_params)?;
    let n = curves.len();
    // values[(1 + 2k + weight) · n + curve]
    let at = |k: u32, weight: bool, c: usize| {
        &values[(1 + 2 * k as usize + usize::from(weight)) * n + c]
    };
    Ok((0..n)
        .map(|c| {
            (0..values[c].len())
                .map(|j| {
                    let point = values[c][j];
                    let w = at(0, true, c)[j].x;
                    let d1 = (at(1, false, c)[j] - at(1, true, c)[j].x * point) / w;
                    if order == 1 {
                        d1
                    } else {
                        (at(2, false, c)[j]
                            - 2.0 * at(1, true, c)[j].x * d1
                            - at(2, true, c)[j].x * point)
                            / w
                    }
                })
                .collect()
        })
        .collect())
}
