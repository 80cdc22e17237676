//! Packing lowered curves into the GPU layout (`f32`, `Pod`): the checks that a scene fits
//! the kernel, the whole scene's preparation, and in-place rewrites of edited curves. The
//! chunking itself is in [`super::chunks`], the overlays in [`super::overlays`].
//!
//! Pure CPU code with no `wgpu` calls, so it is tested without an adapter. A chunk is
//! self-contained: its records index its own points and samples, and its samples' tags
//! index its own style table.

use glam::DVec3;

use super::chunks;
use super::chunks::gpu_control_points;
use super::layout::{GpuControlPoint, GpuLineStyle, MAX_GPU_DEGREE};
use super::{overlays, pack_error};
use splinescope_core::geom::BezierSegment;
use splinescope_encoding::Encoding;
use splinescope_encoding::{Color, auto_samples};

/// Checks that the kernel can evaluate every segment: its degree is at most
/// [`MAX_GPU_DEGREE`], every coordinate is within [`GPU_COORDINATE_LIMIT`] and every
/// weight of a rational segment is at least [`GPU_WEIGHT_RATIO`] times its largest.
///
/// # Errors
/// [`PackError::DegreeTooHigh`], [`PackError::WeightRange`] or
/// [`PackError::CoordinateTooLarge`] naming the curve, the segment and the point.
pub fn check_gpu_fit(
    curve: usize,
    segments: &[BezierSegment],
) -> Result<(), pack_error::PackError> {
    for (segment, s) in segments.iter().enumerate() {
        let degree = s.bezier.degree();
        if degree > MAX_GPU_DEGREE {
            return Err(pack_error::PackError::DegreeTooHigh {
                curve,
                segment,
                degree,
                max: MAX_GPU_DEGREE,
            });
        }
        if let Some(w) = &s.weights {
            let largest = w.iter().copied().fold(0.0, f64::max);
            if let Some((point, &value)) = w
                .iter()
                .enumerate()
                .find(|(_, w)| **w < pack_error::GPU_WEIGHT_RATIO * largest)
            {
                return Err(pack_error::PackError::WeightRange {
                    curve,
                    segment,
                    point,
                    ratio: value / largest,
                    limit: pack_error::GPU_WEIGHT_RATIO,
                });
            }
        }
        if let Some((point, value)) = first_too_large(s.bezier.points()) {
            return Err(pack_error::PackError::CoordinateTooLarge {
                curve,
                segment,
                point,
                value,
                limit: pack_error::GPU_COORDINATE_LIMIT,
            });
        }
    }
    Ok(())
}

/// The first point with a coordinate beyond [`GPU_COORDINATE_LIMIT`]: its index and that
/// coordinate.
fn first_too_large(points: &[DVec3]) -> Option<(usize, f64)> {
    points.iter().enumerate().find_map(|(i, p)| {
        p.to_array()
            .into_iter()
            .find(|c| c.abs() > pack_error::GPU_COORDINATE_LIMIT)
            .map(|c| (i, c))
    })
}

/// Checks every annotation point (each annotation's points, in order) against
/// [`GPU_COORDINATE_LIMIT`].
///
/// # Errors
/// [`PackError::AnnotationTooLarge`] naming the annotation and the point.
pub fn check_annotations(annotations: &[Vec<DVec3>]) -> Result<(), pack_error::PackError> {
    for (annotation, points) in annotations.iter().enumerate() {
        if let Some((point, value)) = first_too_large(points) {
            return Err(pack_error::PackError::AnnotationTooLarge {
                annotation,
                point,
                value,
                limit: pack_error::GPU_COORDINATE_LIMIT,
            });
        }
    }
    Ok(())
}

/// Everything the GPU needs to draw a scene, packed on the CPU.
#[derive(Debug, Clone, PartialEq)]
pub struct PreparedScene {
    /// Curve tessellation work.
    pub chunks: Vec<chunks::TessChunk>,
    /// Overlay polylines (control polygons, …).
    pub lines: Vec<chunks::LineBatch>,
    /// Overlay points (control points, …).
    pub points: Vec<chunks::LineBatch>,
    /// The clear colour.
    pub background: Color,
    /// Per curve, where its lowered control points are (for in-place updates).
    pub placements: Vec<Vec<chunks::Placement>>,
    /// Per curve, the sample count each of its segments was packed with.
    pub sample_counts: Vec<Vec<u32>>,
    /// Where the overlays' vertices are (for in-place updates).
    pub overlay_map: overlays::OverlayMap,
}

/// The new control points of a curve whose lowering kept its structure (the same number
/// of segments of the same degrees, each still polynomial or still rational, and, for a
/// fixed count `samples`, the same count; an
/// automatic count is chosen by the GPU every frame, so it may change freely), as
/// `(chunk, first point, points)` writes; `None` when the structure changed and the scene
/// must be packed again.
#[must_use]
pub fn repack_points(
    placements: &[chunks::Placement],
    packed_counts: &[u32],
    segments: &[BezierSegment],
    samples: Option<u32>,
) -> Option<Vec<(usize, u32, Vec<GpuControlPoint>)>> {
    if segments.len() != packed_counts.len() {
        return None;
    }
    if let Some(fixed) = samples
        && packed_counts.iter().any(|&count| count != fixed)
    {
        return None;
    }
    placements
        .iter()
        .map(|p| {
            let seg = segments.get(p.segment)?;
            if seg.bezier.points().len() != p.len as usize || seg.is_rational() != p.rational {
                return None;
            }
            let verts = gpu_control_points(seg.points(), seg.weights.as_deref());
            Some((p.chunk, p.first_point, verts))
        })
        .collect()
}

/// The segments a curve is drawn with: its own, and for a closed curve with a cap or
/// join other than round its first again after its last (so that where it closes is a
/// join between two pieces, drawn like every other; the repeat covers pixels already
/// covered, which the layer does not blend twice).
fn drawn_segments(
    curve: &splinescope_encoding::EncodedCurve,
) -> impl Iterator<Item = &BezierSegment> + '_ {
    let wrap = (curve.closed && !curve.stroke.is_round())
        .then(|| curve.segments.first())
        .flatten();
    curve.segments.iter().chain(wrap)
}

/// Packs an [`Encoding`] for the GPU: every curve's segments into chunks (the sample
/// total checked against [`splinescope_io::limits::SAMPLES`] before any buffer is built), the
/// overlays into batches, with where everything went (for in-place updates).
///
/// # Errors
/// A degree over the GPU maximum, a coordinate beyond the `f32` range, too many samples,
/// or chunk limits too small for one segment.
pub fn prepare(
    encoding: &Encoding,
    limits: chunks::ChunkLimits,
) -> Result<PreparedScene, pack_error::PackError> {
    // Check and count first: the sample total is checked before any buffer is built.
    let mut counts_all = Vec::with_capacity(encoding.curves.len());
    let mut total = 0u64;
    for (index, curve) in encoding.curves.iter().enumerate() {
        check_gpu_fit(index, &curve.segments)?;
        let counts: Vec<u32> = drawn_segments(curve)
            .map(|seg| {
                curve
                    .samples
                    .unwrap_or_else(|| auto_samples(seg.bezier.points()))
            })
            .collect();
        total += counts.iter().map(|&c| u64::from(c)).sum::<u64>();
        counts_all.push(counts);
    }
    splinescope_io::limits::SAMPLES
        .check(total)
        .map_err(|e| pack_error::PackError::TooManySamples(e.to_string()))?;
    let mut chunks = chunks::ChunkBuilder::new(limits);
    for (index, (curve, counts)) in encoding.curves.iter().zip(&counts_all).enumerate() {
        let mut style = GpuLineStyle::solid(curve.color, curve.width);
        if curve.width_in_scene {
            style.flags |= crate::layout::LINE_WIDTH_IN_SCENE;
        }
        if !curve.stroke.is_round() {
            style.flags |= crate::layout::stroke_flags(&curve.stroke, curve.closed);
        }
        let fixed = curve.samples.is_some();
        for (seg, &count) in drawn_segments(curve).zip(counts) {
            chunks.begin_segment(index, style, seg.points(), seg.weights.as_deref())?;
            chunks.add_drawn_samples(count, fixed);
        }
    }
    check_annotations(&encoding.annotations)?;
    let (lines, points, overlay_map) =
        overlays::prepare_overlays_mapped(&encoding.overlays, encoding.switches, limits);
    let (chunks, placements) = chunks.finish_with_placements();
    Ok(PreparedScene {
        chunks,
        placements,
        sample_counts: counts_all,
        lines,
        points,
        background: encoding.background,
        overlay_map,
    })
}

/// The `(chunk, tag)` pairs under which curve `curve` of a prepared scene was packed: what
/// a comb for that curve alone is given ([`super::renderer::CombRequest::only`]).
#[must_use]
pub fn curve_tags(prepared: &PreparedScene, curve: usize) -> Vec<(usize, u32)> {
    let mut out: Vec<(usize, u32)> = Vec::new();
    for p in prepared.placements.get(curve).into_iter().flatten() {
        let tag = prepared.chunks[p.chunk]
            .segments
            .iter()
            .find(|s| s.first_point == p.first_point)
            .map(|s| s.curve);
        if let Some(tag) = tag
            && !out.contains(&(p.chunk, tag))
        {
            out.push((p.chunk, tag));
        }
    }
    out
}

/// Deprecated: `splinescope_gpu::chunks::BatchBuilder`.
#[deprecated(note = "use splinescope_gpu::chunks::BatchBuilder")]
pub type BatchBuilder = chunks::BatchBuilder;

/// Deprecated: `splinescope_gpu::chunks::ChunkBuilder`.
#[deprecated(note = "use splinescope_gpu::chunks::ChunkBuilder")]
pub type ChunkBuilder = chunks::ChunkBuilder;

/// Deprecated: `splinescope_gpu::chunks::ChunkLimits`.
#[deprecated(note = "use splinescope_gpu::chunks::ChunkLimits")]
pub type ChunkLimits = chunks::ChunkLimits;

/// Deprecated: `splinescope_gpu::chunks::LineBatch`.
#[deprecated(note = "use splinescope_gpu::chunks::LineBatch")]
pub type LineBatch = chunks::LineBatch;

/// Deprecated: `splinescope_gpu::chunks::Placement`.
#[deprecated(note = "use splinescope_gpu::chunks::Placement")]
pub type Placement = chunks::Placement;

/// Deprecated: `splinescope_gpu::chunks::TessChunk`.
#[deprecated(note = "use splinescope_gpu::chunks::TessChunk")]
pub type TessChunk = chunks::TessChunk;

/// Deprecated: `splinescope_gpu::overlays::OverlayEdit`.
#[deprecated(note = "use splinescope_gpu::overlays::OverlayEdit")]
pub type OverlayEdit = overlays::OverlayEdit;

/// Deprecated: `splinescope_gpu::overlays::OverlayMap`.
#[deprecated(note = "use splinescope_gpu::overlays::OverlayMap")]
pub type OverlayMap = overlays::OverlayMap;

/// Deprecated: `splinescope_gpu::overlays::prepare_overlays_mapped`.
#[deprecated(note = "use splinescope_gpu::overlays::prepare_overlays_mapped")]
#[must_use]
pub fn prepare_overlays_mapped(
    list: &splinescope_encoding::draw::DrawList,
    switches: splinescope_encoding::draw::Switches,
    limits: chunks::ChunkLimits,
) -> (
    Vec<chunks::LineBatch>,
    Vec<chunks::LineBatch>,
    overlays::OverlayMap,
) {
    overlays::prepare_overlays_mapped(list, switches, limits)
}

/// Deprecated: `splinescope_gpu::pack_error::GPU_COORDINATE_LIMIT`.
#[deprecated(note = "use splinescope_gpu::pack_error::GPU_COORDINATE_LIMIT")]
pub const GPU_COORDINATE_LIMIT: f64 = pack_error::GPU_COORDINATE_LIMIT;

/// Deprecated: `splinescope_gpu::pack_error::GPU_WEIGHT_RATIO`.
#[deprecated(note = "use splinescope_gpu::pack_error::GPU_WEIGHT_RATIO")]
pub const GPU_WEIGHT_RATIO: f64 = pack_error::GPU_WEIGHT_RATIO;

/// Deprecated: `splinescope_gpu::pack_error::PackError`.
#[deprecated(note = "use splinescope_gpu::pack_error::PackError")]
pub type PackError = pack_error::PackError;

#[cfg(test)]
mod tests {
    use super::*;
    use splinescope_core::geom::{Bezier, Lower};
    use splinescope_scene::format::Scene;

    fn style() -> GpuLineStyle {
        GpuLineStyle::solid(Color::WHITE, 1.0)
    }

    #[test]
    fn runs_spill_into_new_chunks_repeating_the_joint_sample() {
        let limits = chunks::ChunkLimits {
            max_samples: 10,
            max_points: 100,
            max_records: 100,
            max_styles: 100,
        };
        let mut b = chunks::ChunkBuilder::new(limits);
        let cubic = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE];
        b.begin_segment(0, style(), &cubic, None).unwrap();
        b.add_samples(25, 0.0, 1.0);
        let chunks = b.finish();
        // 10 + 9 new + 6 new = 25 distinct samples over three chunks.
        let counts: Vec<u32> = chunks.iter().map(|c| c.sample_count).collect();
        assert_eq!(counts, vec![10, 10, 7]);
        // The second chunk starts at the first chunk's last parameter (9/24).
        assert_eq!(chunks[0].records[0].u1, (9.0_f64 / 24.0) as f32);
        assert_eq!(chunks[1].records[0].u0, (9.0_f64 / 24.0) as f32);
        assert_eq!(chunks[2].records[0].u1, 1.0);
        for c in &chunks {
            assert_eq!(c.points.len(), 4, "each chunk carries the control points");
            assert_eq!(c.styles.len(), 1);
        }
    }

    #[test]
    fn long_runs_become_one_record_per_workgroup() {
        let mut b = chunks::ChunkBuilder::new(chunks::ChunkLimits::for_binding_size(1 << 20));
        b.begin_segment(0, style(), &[DVec3::ZERO, DVec3::X], None)
            .unwrap();
        b.add_samples(150, 0.0, 1.0);
        b.begin_segment(1, style(), &[DVec3::ZERO, DVec3::Y], None)
            .unwrap();
        b.add_samples(64, 0.0, 1.0);
        let chunks = b.finish();
        let records: Vec<(u32, u32, u32, u32)> = chunks[0]
            .records
            .iter()
            .map(|s| (s.curve, s.first_sample, s.sample_count, s.sample_offset))
            .collect();
        assert_eq!(
            records,
            vec![
                (0, 0, 150, 0),
                (0, 0, 150, 64),
                (0, 0, 150, 128),
                (1, 150, 64, 0)
            ]
        );
        assert_eq!(chunks[0].sample_count, 214);
        // Both are degree 1: all records in the general class.
        assert_eq!(chunks[0].class_ends, [0, 0, 0, 0, 4]);
    }

    #[test]
    fn records_are_grouped_by_kernel_class() {
        let mut b = chunks::ChunkBuilder::new(chunks::ChunkLimits::for_binding_size(1 << 20));
        let weights = [1.0, 2.0, 1.0, 0.5];
        let curves = [
            (5usize, false),
            (3, true),
            (3, false),
            (4, false),
            (3, false),
            (1, false),
        ];
        for (curve, (degree, rational)) in curves.into_iter().enumerate() {
            let w = rational.then(|| &weights[..=degree]);
            b.begin_segment(curve, style(), &vec![DVec3::ZERO; degree + 1], w)
                .unwrap();
            b.add_samples(8, 0.0, 1.0);
        }
        let chunks = b.finish();
        let degrees: Vec<(u32, u32)> = chunks[0]
            .records
            .iter()
            .map(|s| (s.degree, s.rational))
            .collect();
        // A rational cubic goes to its own kernel, not the polynomial cubic one.
        assert_eq!(
            degrees,
            vec![(3, 0), (3, 0), (4, 0), (3, 1), (5, 0), (1, 0)]
        );
        assert_eq!(chunks[0].class_ends, [2, 3, 3, 4, 6]);
        // Each record still writes its own curve's samples.
        let firsts: Vec<(u32, u32)> = chunks[0]
            .records
            .iter()
            .map(|s| (s.curve, s.first_sample))
            .collect();
        assert_eq!(
            firsts,
            vec![(2, 16), (4, 32), (3, 24), (1, 8), (0, 0), (5, 40)]
        );
    }

    /// A path's segments of different degrees stay in order, one after another, in the
    /// general kernel's class (their samples are laid out in the segments' order, so a
    /// curve split across classes would be drawn with its pieces out of order); a curve
    /// whose segments share a class keeps it.
    #[test]
    fn a_curve_of_mixed_degrees_keeps_its_segments_together_and_in_order() {
        let mut b = chunks::ChunkBuilder::new(chunks::ChunkLimits::for_binding_size(1 << 20));
        // Curve 0: a line, a quadratic, a cubic and a quintic; curve 1: two cubics.
        let curves: [&[usize]; 2] = [&[1, 2, 3, 5], &[3, 3]];
        for (curve, degrees) in curves.into_iter().enumerate() {
            for &degree in degrees {
                b.begin_segment(curve, style(), &vec![DVec3::ZERO; degree + 1], None)
                    .unwrap();
                b.add_drawn_samples(8, false);
            }
        }
        let chunks = b.finish();
        let order: Vec<(u32, u32)> = chunks[0]
            .segments
            .iter()
            .map(|s| (s.curve, s.degree))
            .collect();
        assert_eq!(order, vec![(1, 3), (1, 3), (0, 1), (0, 2), (0, 3), (0, 5)]);
        assert_eq!(chunks[0].segment_class_ends, [2, 2, 2, 2, 6]);
    }

    #[test]
    fn degree_over_the_gpu_maximum_is_an_error_not_a_clamp() {
        let b = Bezier::new(vec![DVec3::ZERO; MAX_GPU_DEGREE + 2]);
        let err = check_gpu_fit(4, &b.lower()).unwrap_err();
        assert_eq!(
            err,
            pack_error::PackError::DegreeTooHigh {
                curve: 4,
                segment: 0,
                degree: 32,
                max: 31
            }
        );
        assert!(err.to_string().starts_with("curves[4]: "));
        let ok = Bezier::new(vec![DVec3::ZERO; MAX_GPU_DEGREE + 1]);
        assert!(check_gpu_fit(0, &ok.lower()).is_ok());
    }

    #[test]
    fn rational_weights_are_scaled_exactly_and_a_vanishing_one_is_refused() {
        use splinescope_core::geom::RationalBezier;
        let pts = vec![DVec3::ZERO, DVec3::new(1.0, 2.0, 0.0), DVec3::X * 2.0];
        // Weights scaled by a power of two into [1/2, 1): the products exact in f32 here.
        let gpu = super::gpu_control_points(&pts, Some(&[1.0, 3.0, 0.5]));
        let w: Vec<f32> = gpu.iter().map(|c| c.weight).collect();
        assert_eq!(w, vec![0.25, 0.75, 0.125]);
        assert_eq!(gpu[1].position, [0.75, 1.5, 0.0]);
        let tiny = RationalBezier::try_new(pts.clone(), vec![1.0, 1e-40, 1.0]).unwrap();
        let err = check_gpu_fit(2, &tiny.lower()).unwrap_err();
        assert!(
            matches!(
                err,
                pack_error::PackError::WeightRange {
                    curve: 2,
                    segment: 0,
                    point: 1,
                    ..
                }
            ),
            "{err}"
        );
        assert!(err.to_string().contains("weight 1"), "{err}");
        let fine = RationalBezier::try_new(pts, vec![1.0, 1e-20, 1.0]).unwrap();
        assert!(check_gpu_fit(0, &fine.lower()).is_ok());
    }

    #[test]
    fn coordinates_beyond_the_f32_range_are_refused_with_the_point_named() {
        let at = |x: f64| {
            Bezier::new(vec![
                DVec3::ZERO,
                DVec3::new(1.0, 2.0, 0.0),
                DVec3::new(0.0, x, 0.0),
            ])
        };
        assert!(check_gpu_fit(0, &at(pack_error::GPU_COORDINATE_LIMIT).lower()).is_ok());
        assert!(check_gpu_fit(0, &at(-pack_error::GPU_COORDINATE_LIMIT).lower()).is_ok());
        for x in [1e308, -2e38, f64::from(f32::MAX)] {
            let err = check_gpu_fit(7, &at(x).lower()).unwrap_err();
            assert_eq!(
                err,
                pack_error::PackError::CoordinateTooLarge {
                    curve: 7,
                    segment: 0,
                    point: 2,
                    value: x,
                    limit: pack_error::GPU_COORDINATE_LIMIT
                }
            );
            assert!(
                err.to_string()
                    .starts_with("curves[7]: Bézier segment 0, control point 2")
            );
        }
        // The limit keeps every de Casteljau step finite in f32: two coordinates at the
        // limit, of opposite signs and the same sign, at every parameter tried.
        let lim = pack_error::GPU_COORDINATE_LIMIT as f32;
        for (a, b) in [(lim, lim), (lim, -lim), (-lim, -lim)] {
            for k in 0..=64 {
                let u = k as f32 / 64.0;
                let v = 1.0 - u;
                assert!((v * a + u * b).is_finite());
            }
        }
    }

    #[test]
    fn repacking_an_edited_curve_in_place_equals_packing_it_anew() {
        use splinescope_core::geom::{Curve, Nubmp};
        use splinescope_scene::format::{SceneCurve, Style, ViewSpec};
        let pts: Vec<DVec3> = (0..7)
            .map(|i| DVec3::new(f64::from(i), f64::from(i % 2), 0.0))
            .collect();
        let knots = vec![0., 0., 0., 0., 0.3, 0.5, 0.89, 1., 1., 1., 1.];
        let nub = Nubmp::try_new(pts.clone(), knots, 4).unwrap();
        let scene = |n: &Nubmp| Scene {
            name: None,
            unit: None,
            background: Color::WHITE,
            samples_per_segment: Some(40),
            view: ViewSpec::Auto,
            curves: vec![
                SceneCurve {
                    name: None,
                    curve: Curve::Bezier(Bezier::new(pts.clone())),
                    style: Style::default_for(0),
                },
                SceneCurve {
                    name: None,
                    curve: Curve::Nubmp(n.clone()),
                    style: Style::default_for(1),
                },
            ],
            annotations: Vec::new(),
        };
        // Small chunks so that segments spill and are placed twice.
        let limits = chunks::ChunkLimits {
            max_samples: 100,
            max_points: 1000,
            max_records: 1000,
            max_styles: 1000,
        };
        let before = prepare(
            &splinescope_scene::format::encoding::encode(&scene(&nub)),
            limits,
        )
        .unwrap();
        assert!(before.chunks.len() > 2);
        assert!(before.placements[1].len() > 4, "{:?}", before.placements[1]);
        let mut edited = nub.clone();
        edited.set_group(5, &[0.5, 0.2, 0.3]).unwrap();
        let after = prepare(
            &splinescope_scene::format::encoding::encode(&scene(&edited)),
            limits,
        )
        .unwrap();
        let mut chunks: Vec<Vec<GpuControlPoint>> =
            before.chunks.iter().map(|c| c.points.clone()).collect();
        let writes = repack_points(
            &before.placements[1],
            &before.sample_counts[1],
            &edited.lower(),
            Some(40),
        )
        .expect("same structure");
        for (chunk, first, verts) in writes {
            let f = first as usize;
            chunks[chunk][f..f + verts.len()].copy_from_slice(&verts);
        }
        let fresh: Vec<Vec<GpuControlPoint>> =
            after.chunks.iter().map(|c| c.points.clone()).collect();
        assert_eq!(chunks, fresh);
        assert_ne!(
            chunks,
            before
                .chunks
                .iter()
                .map(|c| c.points.clone())
                .collect::<Vec<_>>()
        );
        // A different structure is refused.
        let other = Bezier::new(vec![DVec3::ZERO; 5]);
        assert!(
            repack_points(
                &before.placements[0],
                &before.sample_counts[0],
                &other.lower(),
                Some(40)
            )
            .is_none()
        );
        // A different sample count is a different structure too.
        assert!(
            repack_points(
                &before.placements[1],
                &before.sample_counts[1],
                &edited.lower(),
                Some(41)
            )
            .is_none()
        );
    }

    #[test]
    fn batches_split_long_polylines_and_keep_them_joined() {
        let limits = chunks::ChunkLimits {
            max_samples: 4,
            max_points: 4,
            max_records: 4,
            max_styles: 4,
        };
        let mut b = chunks::BatchBuilder::new(limits);
        let pts: Vec<DVec3> = (0..6).map(|i| DVec3::new(f64::from(i), 0.0, 0.0)).collect();
        b.push(&pts, style());
        let batches = b.finish();
        let xs: Vec<Vec<f32>> = batches
            .iter()
            .map(|b| b.vertices.iter().map(|v| v.position[0]).collect())
            .collect();
        assert_eq!(xs, vec![vec![0.0, 1.0, 2.0, 3.0], vec![3.0, 4.0, 5.0]]);
    }
}
