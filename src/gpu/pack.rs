//! Packing lowered curves into the GPU layout (`f32`, `Pod`), split into chunks that each
//! fit the device's buffer-binding limits.
//!
//! Pure CPU code with no `wgpu` calls, so it is tested without an adapter. A chunk is
//! self-contained: its segments index its own points and samples, and its samples' tags
//! index its own style table.

use glam::DVec3;
use thiserror::Error;

use super::layout::{
    GpuLineStyle, GpuRecord, GpuVertex, MAX_GPU_DEGREE, TESSELLATE_KERNELS,
    TESSELLATE_WORKGROUP_SIZE as WORKGROUP, kernel_class,
};
use crate::geom::{BezierSegment, Lower, OverlayKind};
use crate::scene::{AnnotationShape, Color, Scene, auto_samples};

/// Why a scene cannot be packed for the GPU.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PackError {
    /// A lowered segment's degree is over [`MAX_GPU_DEGREE`].
    #[error(
        "curves[{curve}]: Bézier segment {segment} has degree {degree}, over the GPU maximum of {max} (the CPU path, e.g. `eval --backend cpu`, takes any degree)"
    )]
    DegreeTooHigh {
        /// The curve's index in the scene.
        curve: usize,
        /// The segment's index in the curve's lowering.
        segment: usize,
        /// Its degree.
        degree: usize,
        /// [`MAX_GPU_DEGREE`].
        max: usize,
    },
    /// A lowered control point has a coordinate the kernel cannot work with in `f32`: its
    /// `f32` form, or a de Casteljau intermediate (a sum of two products), would overflow.
    #[error(
        "curves[{curve}]: Bézier segment {segment}, control point {point} has coordinate {value:e}, beyond the GPU's f32 range of ±{limit:e} (the CPU path, e.g. `eval --backend cpu`, takes it)"
    )]
    CoordinateTooLarge {
        /// The curve's index in the scene.
        curve: usize,
        /// The segment's index in the curve's lowering.
        segment: usize,
        /// The point's index in the segment.
        point: usize,
        /// The offending coordinate.
        value: f64,
        /// [`GPU_COORDINATE_LIMIT`].
        limit: f64,
    },
    /// An annotation point has a coordinate beyond [`GPU_COORDINATE_LIMIT`].
    #[error(
        "annotations[{annotation}].points[{point}] has coordinate {value:e}, beyond the GPU's f32 range of ±{limit:e}"
    )]
    AnnotationTooLarge {
        /// The annotation's index in the scene.
        annotation: usize,
        /// The point's index.
        point: usize,
        /// The offending coordinate.
        value: f64,
        /// [`GPU_COORDINATE_LIMIT`].
        limit: f64,
    },
    /// The scene needs more samples than [`crate::limits::SAMPLES`] allows.
    #[error("the scene's curves need {0}")]
    TooManySamples(String),
    /// The chunk limits are too small to hold even one segment.
    #[error("GPU buffer limits too small: one chunk holds {what}")]
    LimitsTooSmall {
        /// What did not fit.
        what: String,
    },
}

/// The most each chunk may hold, derived from the device's binding and buffer limits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ChunkLimits {
    /// Output samples per chunk.
    pub max_samples: usize,
    /// Control points per chunk.
    pub max_points: usize,
    /// Records (runs of at most one workgroup of samples) per chunk.
    pub max_records: usize,
    /// Style-table entries per chunk.
    pub max_styles: usize,
}

impl ChunkLimits {
    /// Limits for buffers of at most `max_bytes` each (the smaller of the device's
    /// `max_storage_buffer_binding_size` and `max_buffer_size`).
    #[must_use]
    pub fn for_binding_size(max_bytes: u64) -> ChunkLimits {
        let per = |size: usize| (max_bytes / size as u64).min(u64::from(u32::MAX)) as usize;
        ChunkLimits {
            max_samples: per(size_of::<GpuVertex>()),
            max_points: per(size_of::<GpuVertex>()),
            max_records: per(size_of::<GpuRecord>()),
            max_styles: per(size_of::<GpuLineStyle>()),
        }
    }
}

/// One self-contained unit of tessellation work.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TessChunk {
    /// Control points of this chunk's segments.
    pub points: Vec<GpuVertex>,
    /// Records (indices local to this chunk), sorted by kernel class (see
    /// [`TESSELLATE_KERNELS`]).
    pub records: Vec<GpuRecord>,
    /// Where each kernel class's records end in `segments` (class `k` holds
    /// `class_ends[k − 1] .. class_ends[k]`, class 0 starting at 0).
    pub class_ends: [u32; TESSELLATE_KERNELS.len()],
    /// Number of samples the kernel writes.
    pub sample_count: u32,
    /// The scene index of the curve whose tag is 0 in this chunk.
    pub first_curve: usize,
    /// Style of each curve in the chunk, by local tag.
    pub styles: Vec<GpuLineStyle>,
}

/// Where a copy of one lowered segment's control points lives on the GPU: the chunk and
/// the index of its first point there (a segment split across chunks has several).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Placement {
    /// The chunk.
    pub chunk: usize,
    /// The first control point's index in the chunk's points.
    pub first_point: u32,
    /// The segment's index in the curve's lowering.
    pub segment: usize,
    /// Its number of control points.
    pub len: u32,
}

/// Builds chunks segment by segment, opening a new chunk whenever the next record would
/// not fit.
#[derive(Debug)]
pub struct ChunkBuilder {
    limits: ChunkLimits,
    chunks: Vec<TessChunk>,
    /// The open segment: its curve, style, control points, and where they start in the
    /// current chunk (re-pushed when a run of samples spills into a new chunk).
    open: Option<OpenSegment>,
    /// Per curve, where its segments' points went.
    placements: Vec<Vec<Placement>>,
}

#[derive(Debug, Clone)]
struct OpenSegment {
    curve: usize,
    segment: usize,
    style: GpuLineStyle,
    points: Vec<GpuVertex>,
    first_point: u32,
}

impl ChunkBuilder {
    /// A builder with the given limits.
    #[must_use]
    pub fn new(limits: ChunkLimits) -> ChunkBuilder {
        ChunkBuilder {
            limits,
            chunks: vec![TessChunk::default()],
            open: None,
            placements: Vec::new(),
        }
    }

    fn current(&self) -> &TessChunk {
        self.chunks
            .last()
            .unwrap_or_else(|| unreachable!("never empty"))
    }

    fn current_mut(&mut self) -> &mut TessChunk {
        self.chunks
            .last_mut()
            .unwrap_or_else(|| unreachable!("never empty"))
    }

    /// Whether the current chunk can take `points` more control points and one more
    /// record of at least `samples` samples for `curve`.
    fn has_room(&self, curve: usize, points: usize, samples: usize) -> bool {
        let l = self.limits;
        let c = self.current();
        let new_style = c.styles.is_empty() || curve - c.first_curve >= c.styles.len();
        c.points.len() + points <= l.max_points
            && c.records.len() < l.max_records
            && c.sample_count as usize + samples <= l.max_samples
            && (!new_style || c.styles.len() < l.max_styles)
    }

    /// Starts a segment of scene curve `curve` (curves come in non-decreasing order) with
    /// the given control points, rounded to `f32`.
    ///
    /// # Errors
    /// [`PackError::LimitsTooSmall`] when a segment does not fit an empty chunk.
    pub fn begin_segment(
        &mut self,
        curve: usize,
        style: GpuLineStyle,
        points: &[DVec3],
    ) -> Result<(), PackError> {
        let segment = self
            .placements
            .get(curve)
            .and_then(|p| p.last())
            .map_or(0, |p| p.segment + 1);
        let l = self.limits;
        if points.len() > l.max_points
            || l.max_samples < 2
            || l.max_records == 0
            || l.max_styles == 0
        {
            return Err(PackError::LimitsTooSmall {
                what: format!(
                    "{} control points, {} samples, {} segments, {} styles; a segment needs {} points",
                    l.max_points,
                    l.max_samples,
                    l.max_records,
                    l.max_styles,
                    points.len()
                ),
            });
        }
        let points: Vec<GpuVertex> = points
            .iter()
            .map(|p| GpuVertex {
                position: p.as_vec3().to_array(),
                id: 0,
            })
            .collect();
        self.open = None;
        if !self.has_room(curve, points.len(), 1) {
            self.chunks.push(TessChunk::default());
        }
        let first_point = self.current().points.len() as u32;
        self.current_mut().points.extend_from_slice(&points);
        self.place(curve, segment, first_point, points.len());
        self.open = Some(OpenSegment {
            curve,
            segment,
            style,
            points,
            first_point,
        });
        Ok(())
    }

    fn place(&mut self, curve: usize, segment: usize, first_point: u32, len: usize) {
        if self.placements.len() <= curve {
            self.placements.resize(curve + 1, Vec::new());
        }
        let chunk = self.chunks.len() - 1;
        self.placements[curve].push(Placement {
            chunk,
            first_point,
            segment,
            len: len as u32,
        });
    }

    /// Opens a new chunk and re-pushes the open segment's control points there.
    fn spill(&mut self) {
        self.chunks.push(TessChunk::default());
        let open = self
            .open
            .take()
            .unwrap_or_else(|| unreachable!("spill needs an open segment"));
        let first_point = self.current().points.len() as u32;
        self.current_mut().points.extend_from_slice(&open.points);
        self.place(open.curve, open.segment, first_point, open.points.len());
        self.open = Some(OpenSegment {
            first_point,
            ..open
        });
    }

    /// Adds `count ≥ 1` samples of the open segment at parameters from `u0` to `u1` (see
    /// [`GpuRecord`]). A run that does not fit the chunk continues in the next one,
    /// repeating its last sample there so that polylines stay joined.
    ///
    /// # Panics
    /// If no segment is open or `count` is 0 (bugs in the caller).
    pub fn add_samples(&mut self, count: u32, u0: f64, u1: f64) {
        assert!(count > 0, "add_samples needs at least one sample");
        let at = |j: u32| {
            if count > 1 {
                u0 + (u1 - u0) * f64::from(j) / f64::from(count - 1)
            } else {
                u0
            }
        };
        let mut start = 0u32;
        loop {
            let open = self.open.clone().expect("add_samples needs begin_segment");
            let remaining = count - start;
            // A partial run must write at least 2 samples to make progress (it repeats one).
            if !self.has_room(open.curve, 0, remaining.min(2) as usize) {
                self.spill();
                continue;
            }
            let room_samples = self.limits.max_samples - self.current().sample_count as usize;
            let room_records = self.limits.max_records - self.current().records.len();
            let take = (remaining as usize)
                .min(room_samples)
                .min(room_records * WORKGROUP as usize) as u32;
            let (ua, ub) = if take == count {
                (u0, u1)
            } else {
                (at(start), at(start + take - 1))
            };
            let c = self.current_mut();
            if c.styles.is_empty() {
                c.first_curve = open.curve;
            }
            let tag = open.curve - c.first_curve;
            if tag >= c.styles.len() {
                // Tags stay dense: a curve that lowered to no segment keeps its slot.
                c.styles.resize(tag + 1, open.style);
            }
            // One record per workgroup's worth of samples of this run.
            for sample_offset in (0..take).step_by(WORKGROUP as usize) {
                c.records.push(GpuRecord {
                    first_point: open.first_point,
                    degree: (open.points.len() - 1) as u32,
                    curve: tag as u32,
                    first_sample: c.sample_count,
                    sample_count: take,
                    u0: ua as f32,
                    u1: ub as f32,
                    sample_offset,
                });
            }
            c.sample_count += take;
            if take == remaining {
                return;
            }
            start += take - 1;
            self.spill();
        }
    }

    /// The chunks built, without empty ones, their records sorted by kernel class.
    #[must_use]
    pub fn finish(self) -> Vec<TessChunk> {
        self.finish_with_placements().0
    }

    /// [`ChunkBuilder::finish`], with the placements of every curve's points.
    #[must_use]
    pub fn finish_with_placements(self) -> (Vec<TessChunk>, Vec<Vec<Placement>>) {
        // Only a builder that never got a segment has an empty chunk (the first): chunk
        // indices in the placements stay valid.
        let placements = self.placements;
        let chunks = self
            .chunks
            .into_iter()
            .filter(|c| !c.records.is_empty())
            .map(|mut c| {
                // Records are independent (each writes its own samples), so their order is
                // free: group them by the kernel that evaluates them.
                c.records.sort_by_key(|s| kernel_class(s.degree));
                let mut ends = [0u32; TESSELLATE_KERNELS.len()];
                for s in &c.records {
                    ends[kernel_class(s.degree)] += 1;
                }
                for k in 1..ends.len() {
                    ends[k] += ends[k - 1];
                }
                c.class_ends = ends;
                c
            })
            .collect();
        (chunks, placements)
    }
}

impl GpuLineStyle {
    /// A solid style.
    #[must_use]
    pub fn solid(color: Color, width_px: f32) -> GpuLineStyle {
        GpuLineStyle {
            color: color.0,
            width_px,
            dash_px: 0.0,
            _padding0: 0,
            _padding1: 0,
        }
    }
}

/// The largest coordinate magnitude the GPU path takes: half of `f32::MAX` (≈ 1.7e38)
/// rounded down, so that a de Casteljau step `v·a + u·b` of two such coordinates cannot
/// overflow (`|v·a| + |u·b| ≤ max(|a|, |b|)` in exact arithmetic, and rounding stays far
/// below the other half).
pub const GPU_COORDINATE_LIMIT: f64 = 1e38;

/// Checks that the kernel can evaluate every segment: its degree is at most
/// [`MAX_GPU_DEGREE`] and every coordinate is within [`GPU_COORDINATE_LIMIT`].
///
/// # Errors
/// [`PackError::DegreeTooHigh`] or [`PackError::CoordinateTooLarge`] naming the curve,
/// the segment and the point.
pub fn check_gpu_fit(curve: usize, segments: &[BezierSegment]) -> Result<(), PackError> {
    for (segment, s) in segments.iter().enumerate() {
        let degree = s.bezier.degree();
        if degree > MAX_GPU_DEGREE {
            return Err(PackError::DegreeTooHigh {
                curve,
                segment,
                degree,
                max: MAX_GPU_DEGREE,
            });
        }
        for (point, p) in s.bezier.points().iter().enumerate() {
            if let Some(&value) = p.to_array().iter().find(|c| c.abs() > GPU_COORDINATE_LIMIT) {
                return Err(PackError::CoordinateTooLarge {
                    curve,
                    segment,
                    point,
                    value,
                    limit: GPU_COORDINATE_LIMIT,
                });
            }
        }
    }
    Ok(())
}

/// Checks every annotation point against [`GPU_COORDINATE_LIMIT`].
///
/// # Errors
/// [`PackError::AnnotationTooLarge`] naming the annotation and the point.
pub fn check_annotations(scene: &Scene) -> Result<(), PackError> {
    for (annotation, a) in scene.annotations.iter().enumerate() {
        let (AnnotationShape::Polyline(points) | AnnotationShape::Points(points)) = &a.shape;
        for (point, p) in points.iter().enumerate() {
            if let Some(&value) = p.to_array().iter().find(|c| c.abs() > GPU_COORDINATE_LIMIT) {
                return Err(PackError::AnnotationTooLarge {
                    annotation,
                    point,
                    value,
                    limit: GPU_COORDINATE_LIMIT,
                });
            }
        }
    }
    Ok(())
}

/// Tagged polylines or points with their style table, split so each batch fits a
/// binding.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LineBatch {
    /// The vertices; a change of tag separates polylines.
    pub vertices: Vec<GpuVertex>,
    /// Styles by tag.
    pub styles: Vec<GpuLineStyle>,
}

/// Builds [`LineBatch`]es from polylines (or point sets), one style entry per polyline.
#[derive(Debug)]
pub struct BatchBuilder {
    max_vertices: usize,
    max_styles: usize,
    batches: Vec<LineBatch>,
}

impl BatchBuilder {
    /// A builder with per-batch limits.
    #[must_use]
    pub fn new(limits: ChunkLimits) -> BatchBuilder {
        BatchBuilder {
            max_vertices: limits.max_points.max(2),
            max_styles: limits.max_styles.max(1),
            batches: vec![LineBatch::default()],
        }
    }

    /// Adds one polyline (or point set) drawn with `style`. Polylines longer than a batch
    /// continue in the next one from their last vertex.
    pub fn push(&mut self, points: &[DVec3], style: GpuLineStyle) {
        let mut rest = points;
        while !rest.is_empty() {
            let full = {
                let b = self
                    .batches
                    .last()
                    .unwrap_or_else(|| unreachable!("never empty"));
                b.styles.len() >= self.max_styles || b.vertices.len() + 2 > self.max_vertices
            };
            if full {
                self.batches.push(LineBatch::default());
            }
            let b = self
                .batches
                .last_mut()
                .unwrap_or_else(|| unreachable!("never empty"));
            let tag = b.styles.len() as u32;
            b.styles.push(style);
            let take = rest.len().min(self.max_vertices - b.vertices.len());
            b.vertices.extend(rest[..take].iter().map(|p| GpuVertex {
                position: p.as_vec3().to_array(),
                id: tag,
            }));
            if take == rest.len() {
                break;
            }
            // Repeat the last vertex in the next batch so the polyline stays joined.
            rest = &rest[take - 1..];
        }
    }

    /// The batches built, without empty ones.
    #[must_use]
    pub fn finish(self) -> Vec<LineBatch> {
        self.batches
            .into_iter()
            .filter(|b| !b.vertices.is_empty())
            .collect()
    }
}

/// Everything the GPU needs to draw a scene, packed on the CPU.
#[derive(Debug, Clone, PartialEq)]
pub struct PreparedScene {
    /// Curve tessellation work.
    pub chunks: Vec<TessChunk>,
    /// Overlay polylines (control polygons, …).
    pub lines: Vec<LineBatch>,
    /// Overlay points (control points, …).
    pub points: Vec<LineBatch>,
    /// The clear colour.
    pub background: Color,
    /// Per curve, where its lowered control points are (for in-place updates).
    pub placements: Vec<Vec<Placement>>,
    /// Per curve, the sample count each of its segments was packed with.
    pub sample_counts: Vec<Vec<u32>>,
}

/// The new control points of a curve whose lowering kept its structure (same segments,
/// degrees and sample counts: `samples` is the curve's fixed count, `None` for automatic),
/// as `(chunk, first point, points)` writes; `None` when the structure changed and the
/// scene must be packed again.
#[must_use]
pub fn repack_points(
    placements: &[Placement],
    packed_counts: &[u32],
    segments: &[BezierSegment],
    samples: Option<u32>,
) -> Option<Vec<(usize, u32, Vec<GpuVertex>)>> {
    if segments.len() != packed_counts.len() {
        return None;
    }
    for (seg, &count) in segments.iter().zip(packed_counts) {
        if samples.unwrap_or_else(|| auto_samples(seg.bezier.points())) != count {
            return None;
        }
    }
    placements
        .iter()
        .map(|p| {
            let seg = segments.get(p.segment)?;
            if seg.bezier.points().len() != p.len as usize {
                return None;
            }
            let verts = seg
                .bezier
                .points()
                .iter()
                .map(|q| GpuVertex {
                    position: q.as_vec3().to_array(),
                    id: 0,
                })
                .collect();
            Some((p.chunk, p.first_point, verts))
        })
        .collect()
}

/// Width in pixels of control polygons.
pub const POLYGON_WIDTH_PX: f32 = 1.25;
/// Diameter in pixels of control points.
pub const POINT_DIAMETER_PX: f32 = 7.0;

/// Diameter in pixels of derived points (dual control points, inner Bézier points).
pub const DERIVED_POINT_DIAMETER_PX: f32 = 5.0;
/// The colour of NUBMP dual polygons and points.
pub const DUAL_COLOR: Color = Color([0.95, 0.55, 0.05, 0.95]);

/// The style of an overlay polyline of `kind` over a curve of colour `curve`.
#[must_use]
pub fn overlay_style(kind: OverlayKind, curve: Color) -> GpuLineStyle {
    let grey = Color([0.55, 0.55, 0.55, 1.0]);
    match kind {
        OverlayKind::ControlPolygon => {
            let mut c = curve.mix(grey, 0.55);
            c.0[3] = 0.9;
            GpuLineStyle::solid(c, POLYGON_WIDTH_PX)
        }
        OverlayKind::DualPolygon => GpuLineStyle {
            dash_px: 8.0,
            ..GpuLineStyle::solid(DUAL_COLOR, POLYGON_WIDTH_PX)
        },
        OverlayKind::TangentHandles => {
            let mut c = curve.mix(grey, 0.7);
            c.0[3] = 0.85;
            GpuLineStyle::solid(c, 1.0)
        }
        OverlayKind::BumpVector => GpuLineStyle {
            dash_px: 6.0,
            ..GpuLineStyle::solid(curve.mix(Color([0.0, 0.0, 0.0, 1.0]), 0.3), 2.0)
        },
    }
}

/// The style of the derived points shown with an overlay of `kind`, if any.
#[must_use]
pub fn overlay_point_style(kind: OverlayKind, curve: Color) -> Option<GpuLineStyle> {
    match kind {
        OverlayKind::DualPolygon => {
            Some(GpuLineStyle::solid(DUAL_COLOR, DERIVED_POINT_DIAMETER_PX))
        }
        OverlayKind::TangentHandles => Some(GpuLineStyle::solid(
            curve.mix(Color([0.55, 0.55, 0.55, 1.0]), 0.6),
            DERIVED_POINT_DIAMETER_PX - 1.0,
        )),
        OverlayKind::ControlPolygon | OverlayKind::BumpVector => None,
    }
}

/// Lowers and packs every curve of `scene` for drawing: each Bézier segment gets the
/// curve's sample count (or the automatic one, [`auto_samples`]), uniformly in its own
/// parameter.
///
/// # Errors
/// [`PackError`] when a segment's degree is over the GPU maximum or a coordinate beyond
/// [`GPU_COORDINATE_LIMIT`].
pub fn prepare_scene(scene: &Scene, limits: ChunkLimits) -> Result<PreparedScene, PackError> {
    // The sample total first, before any buffer is built.
    let mut total = 0u64;
    for (index, sc) in scene.curves.iter().enumerate() {
        let samples = scene.samples_for(index);
        for seg in sc.curve.lower() {
            total += u64::from(samples.unwrap_or_else(|| auto_samples(seg.bezier.points())));
        }
    }
    crate::limits::SAMPLES
        .check(total)
        .map_err(|e| PackError::TooManySamples(e.to_string()))?;
    let mut chunks = ChunkBuilder::new(limits);
    let mut sample_counts = Vec::with_capacity(scene.curves.len());
    for (index, sc) in scene.curves.iter().enumerate() {
        let segments = sc.curve.lower();
        check_gpu_fit(index, &segments)?;
        let style = GpuLineStyle::solid(sc.style.color, sc.style.width);
        let samples = scene.samples_for(index);
        let mut counts = Vec::with_capacity(segments.len());
        for seg in &segments {
            chunks.begin_segment(index, style, seg.bezier.points())?;
            let count = samples.unwrap_or_else(|| auto_samples(seg.bezier.points()));
            chunks.add_samples(count, 0.0, 1.0);
            counts.push(count);
        }
        sample_counts.push(counts);
    }
    check_annotations(scene)?;
    let (lines, points) = prepare_overlays(scene, limits);
    let (chunks, placements) = chunks.finish_with_placements();
    Ok(PreparedScene {
        chunks,
        placements,
        sample_counts,
        lines,
        points,
        background: scene.background,
    })
}

/// The overlay polylines and points of a scene (control polygons, control points, the
/// families' explaining polylines, annotations): rebuilt on their own when curves are
/// edited in place.
#[must_use]
pub fn prepare_overlays(scene: &Scene, limits: ChunkLimits) -> (Vec<LineBatch>, Vec<LineBatch>) {
    let mut lines = BatchBuilder::new(limits);
    let mut points = BatchBuilder::new(limits);
    for sc in &scene.curves {
        if sc.style.show_polygon {
            for overlay in sc.curve.overlays() {
                lines.push(&overlay.points, overlay_style(overlay.kind, sc.style.color));
                if let Some(style) = overlay_point_style(overlay.kind, sc.style.color) {
                    points.push(&overlay.points, style);
                }
            }
        }
        if sc.style.show_points {
            let dot = sc.style.color.mix(Color([0.0, 0.0, 0.0, 1.0]), 0.15);
            points.push(
                sc.curve.control_points(),
                GpuLineStyle::solid(dot, POINT_DIAMETER_PX),
            );
        }
    }
    if !scene.is_planar() {
        // An axis triad at the scene's lowest corner: x red, y green, z blue.
        let bounds = scene.bounds();
        let length = 0.2 * bounds.diagonal();
        for (axis, color) in [
            (DVec3::X, Color([0.85, 0.2, 0.2, 1.0])),
            (DVec3::Y, Color([0.2, 0.6, 0.2, 1.0])),
            (DVec3::Z, Color([0.2, 0.35, 0.85, 1.0])),
        ] {
            lines.push(
                &[bounds.min, bounds.min + axis * length],
                GpuLineStyle::solid(color, 2.0),
            );
        }
    }
    for a in &scene.annotations {
        let style = GpuLineStyle::solid(a.color, a.width);
        match &a.shape {
            AnnotationShape::Polyline(p) => lines.push(p, style),
            AnnotationShape::Points(p) => points.push(p, style),
        }
    }
    (lines.finish(), points.finish())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Bezier;

    fn style() -> GpuLineStyle {
        GpuLineStyle::solid(Color::WHITE, 1.0)
    }

    #[test]
    fn runs_spill_into_new_chunks_repeating_the_joint_sample() {
        let limits = ChunkLimits {
            max_samples: 10,
            max_points: 100,
            max_records: 100,
            max_styles: 100,
        };
        let mut b = ChunkBuilder::new(limits);
        let cubic = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE];
        b.begin_segment(0, style(), &cubic).unwrap();
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
        let mut b = ChunkBuilder::new(ChunkLimits::for_binding_size(1 << 20));
        b.begin_segment(0, style(), &[DVec3::ZERO, DVec3::X])
            .unwrap();
        b.add_samples(150, 0.0, 1.0);
        b.begin_segment(1, style(), &[DVec3::ZERO, DVec3::Y])
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
        assert_eq!(chunks[0].class_ends, [0, 0, 4]);
    }

    #[test]
    fn records_are_grouped_by_kernel_class() {
        let mut b = ChunkBuilder::new(ChunkLimits::for_binding_size(1 << 20));
        for (curve, degree) in [5usize, 3, 4, 3, 1].into_iter().enumerate() {
            b.begin_segment(curve, style(), &vec![DVec3::ZERO; degree + 1])
                .unwrap();
            b.add_samples(8, 0.0, 1.0);
        }
        let chunks = b.finish();
        let degrees: Vec<u32> = chunks[0].records.iter().map(|s| s.degree).collect();
        assert_eq!(degrees, vec![3, 3, 4, 5, 1]);
        assert_eq!(chunks[0].class_ends, [2, 3, 5]);
        // Each record still writes its own curve's samples.
        let firsts: Vec<(u32, u32)> = chunks[0]
            .records
            .iter()
            .map(|s| (s.curve, s.first_sample))
            .collect();
        assert_eq!(firsts, vec![(1, 8), (3, 24), (2, 16), (0, 0), (4, 32)]);
    }

    #[test]
    fn degree_over_the_gpu_maximum_is_an_error_not_a_clamp() {
        let b = Bezier::new(vec![DVec3::ZERO; MAX_GPU_DEGREE + 2]);
        let err = check_gpu_fit(4, &b.lower()).unwrap_err();
        assert_eq!(
            err,
            PackError::DegreeTooHigh {
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
    fn coordinates_beyond_the_f32_range_are_refused_with_the_point_named() {
        let at = |x: f64| {
            Bezier::new(vec![
                DVec3::ZERO,
                DVec3::new(1.0, 2.0, 0.0),
                DVec3::new(0.0, x, 0.0),
            ])
        };
        assert!(check_gpu_fit(0, &at(GPU_COORDINATE_LIMIT).lower()).is_ok());
        assert!(check_gpu_fit(0, &at(-GPU_COORDINATE_LIMIT).lower()).is_ok());
        for x in [1e308, -2e38, f64::from(f32::MAX)] {
            let err = check_gpu_fit(7, &at(x).lower()).unwrap_err();
            assert_eq!(
                err,
                PackError::CoordinateTooLarge {
                    curve: 7,
                    segment: 0,
                    point: 2,
                    value: x,
                    limit: GPU_COORDINATE_LIMIT
                }
            );
            assert!(
                err.to_string()
                    .starts_with("curves[7]: Bézier segment 0, control point 2")
            );
        }
        // The limit keeps every de Casteljau step finite in f32: two coordinates at the
        // limit, of opposite signs and the same sign, at every parameter tried.
        let lim = GPU_COORDINATE_LIMIT as f32;
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
        use crate::geom::{Curve, Nubmp};
        use crate::scene::{SceneCurve, Style, ViewSpec};
        let pts: Vec<DVec3> = (0..7)
            .map(|i| DVec3::new(f64::from(i), f64::from(i % 2), 0.0))
            .collect();
        let knots = vec![0., 0., 0., 0., 0.3, 0.5, 0.89, 1., 1., 1., 1.];
        let nub = Nubmp::try_new(pts.clone(), knots, 4).unwrap();
        let scene = |n: &Nubmp| Scene {
            name: None,
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
        let limits = ChunkLimits {
            max_samples: 100,
            max_points: 1000,
            max_records: 1000,
            max_styles: 1000,
        };
        let before = prepare_scene(&scene(&nub), limits).unwrap();
        assert!(before.chunks.len() > 2);
        assert!(before.placements[1].len() > 4, "{:?}", before.placements[1]);
        let mut edited = nub.clone();
        edited.set_group(5, &[0.5, 0.2, 0.3]).unwrap();
        let after = prepare_scene(&scene(&edited), limits).unwrap();
        let mut chunks: Vec<Vec<GpuVertex>> =
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
        let fresh: Vec<Vec<GpuVertex>> = after.chunks.iter().map(|c| c.points.clone()).collect();
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
        let limits = ChunkLimits {
            max_samples: 4,
            max_points: 4,
            max_records: 4,
            max_styles: 4,
        };
        let mut b = BatchBuilder::new(limits);
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
