//! Splitting GPU work into chunks that each fit the device's buffer-binding limits:
//! tessellation records with their control points and samples ([`ChunkBuilder`]), and
//! overlay polylines or points with their style tables ([`BatchBuilder`]). Pure CPU code.

use glam::DVec3;

use super::layout::{
    GpuControlPoint, GpuLineStyle, GpuRecord, GpuSegment, GpuVertex, MAX_ADAPTIVE_SEGMENTS,
    TESSELLATE_KERNELS, TESSELLATE_WORKGROUP_SIZE as WORKGROUP, kernel_class,
};
use super::pack_error::PackError;

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
            max_points: per(size_of::<GpuControlPoint>()),
            max_records: per(size_of::<GpuRecord>()),
            max_styles: per(size_of::<GpuLineStyle>()),
        }
    }
}

/// One self-contained unit of tessellation work.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TessChunk {
    /// Control points of this chunk's segments (homogeneous).
    pub points: Vec<GpuControlPoint>,
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
    /// The Bézier segments drawn from this chunk with per-frame sample counts (adaptive
    /// tessellation; each segment whose first record is here), sorted by kernel class.
    pub segments: Vec<GpuSegment>,
    /// Where each kernel class's segments end in `segments`.
    pub segment_class_ends: [u32; TESSELLATE_KERNELS.len()],
}

/// A segment's control points in the GPU's homogeneous form ([`GpuControlPoint`]):
/// `(P, 1)` for a polynomial segment; for a rational one `(w·P, w)` with the weights first
/// scaled by the power of two that brings the largest into `[½, 1)` (exact, and the same
/// curve), the product formed in `f64` and rounded once to `f32`.
#[must_use]
pub fn gpu_control_points(points: &[DVec3], weights: Option<&[f64]>) -> Vec<GpuControlPoint> {
    match weights {
        None => points
            .iter()
            .map(|p| GpuControlPoint {
                position: p.as_vec3().to_array(),
                weight: 1.0,
            })
            .collect(),
        Some(w) => {
            let largest = w.iter().copied().fold(0.0, f64::max);
            let e = if largest > 0.0 && largest.is_finite() {
                splinescope_core::num::split_exponent(largest).1 + 1
            } else {
                0
            };
            points
                .iter()
                .zip(w)
                .map(|(p, &w)| {
                    let w = splinescope_core::num::scale_by_power_of_two(w, -e);
                    GpuControlPoint {
                        position: (*p * w).as_vec3().to_array(),
                        weight: w as f32,
                    }
                })
                .collect()
        }
    }
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
    /// Whether it was packed as a rational segment (evaluated in homogeneous coordinates).
    pub rational: bool,
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
    /// The last curve given samples and the chunk they went to (a curve whose samples
    /// go on in a later chunk has its ends there drawn as joins, not caps).
    last_drawn: Option<(usize, usize)>,
}

#[derive(Debug, Clone)]
struct OpenSegment {
    curve: usize,
    segment: usize,
    style: GpuLineStyle,
    points: Vec<GpuControlPoint>,
    rational: bool,
    first_point: u32,
    /// For a drawn segment, its fixed sample count (0: adaptive); registered in the chunk
    /// that gets its first record.
    drawn: Option<u32>,
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
            last_drawn: None,
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
            && c.segments.len() < MAX_ADAPTIVE_SEGMENTS
            && c.sample_count as usize + samples <= l.max_samples
            && (!new_style || c.styles.len() < l.max_styles)
    }

    /// Starts a segment of scene curve `curve` (curves come in non-decreasing order) with
    /// the given control points and, for a rational segment, their weights, in the GPU's
    /// homogeneous form ([`gpu_control_points`]).
    ///
    /// # Errors
    /// [`PackError::LimitsTooSmall`] when a segment does not fit an empty chunk.
    pub fn begin_segment(
        &mut self,
        curve: usize,
        style: GpuLineStyle,
        points: &[DVec3],
        weights: Option<&[f64]>,
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
        let points = gpu_control_points(points, weights);
        self.open = None;
        if !self.has_room(curve, points.len(), 1) {
            self.chunks.push(TessChunk::default());
        }
        let first_point = self.current().points.len() as u32;
        self.current_mut().points.extend_from_slice(&points);
        self.place(curve, segment, first_point, points.len(), weights.is_some());
        self.open = Some(OpenSegment {
            curve,
            segment,
            style,
            points,
            rational: weights.is_some(),
            first_point,
            drawn: None,
        });
        Ok(())
    }

    fn place(
        &mut self,
        curve: usize,
        segment: usize,
        first_point: u32,
        len: usize,
        rational: bool,
    ) {
        if self.placements.len() <= curve {
            self.placements.resize(curve + 1, Vec::new());
        }
        let chunk = self.chunks.len() - 1;
        self.placements[curve].push(Placement {
            chunk,
            first_point,
            segment,
            len: len as u32,
            rational,
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
        self.place(
            open.curve,
            open.segment,
            first_point,
            open.points.len(),
            open.rational,
        );
        self.open = Some(OpenSegment {
            first_point,
            ..open
        });
    }

    /// Adds the open segment's `count ≥ 1` samples over its whole parameter range, as a
    /// drawn segment: it is also entered in its chunk's adaptive segment table, with
    /// `count` as its fixed count when `fixed` (otherwise chosen every frame).
    ///
    /// # Panics
    /// If no segment is open or `count` is 0 (bugs in the caller).
    pub fn add_drawn_samples(&mut self, count: u32, fixed: bool) {
        if let Some(open) = &mut self.open {
            open.drawn = Some(if fixed { count } else { 0 });
        }
        self.add_samples(count, 0.0, 1.0);
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
            let here = self.chunks.len() - 1;
            let earlier = match self.last_drawn {
                Some((curve, chunk)) if curve == open.curve && chunk != here => Some(chunk),
                _ => None,
            };
            self.last_drawn = Some((open.curve, here));
            if let Some(chunk) = earlier {
                // The curve went on from that chunk into this one: its run there does not
                // end, nor does this one start, where the chunks meet.
                let c = &mut self.chunks[chunk];
                let tag = open.curve - c.first_curve;
                if let Some(style) = c.styles.get_mut(tag) {
                    style.flags |= crate::layout::LINE_CONTINUES_AFTER;
                }
            }
            let c = self.current_mut();
            if c.styles.is_empty() {
                c.first_curve = open.curve;
            }
            let tag = open.curve - c.first_curve;
            if tag >= c.styles.len() {
                // Tags stay dense: a curve that lowered to no segment keeps its slot.
                c.styles.resize(tag + 1, open.style);
            }
            if earlier.is_some() {
                c.styles[tag].flags |= crate::layout::LINE_CONTINUES_BEFORE;
            }
            if start == 0
                && let Some(fixed) = open.drawn
            {
                c.segments.push(GpuSegment {
                    first_point: open.first_point,
                    degree: (open.points.len() - 1) as u32,
                    curve: tag as u32,
                    fixed,
                    rational: u32::from(open.rational),
                });
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
                    rational: u32::from(open.rational),
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
                c.records
                    .sort_by_key(|s| kernel_class(s.degree, s.rational != 0));
                let mut ends = [0u32; TESSELLATE_KERNELS.len()];
                for s in &c.records {
                    ends[kernel_class(s.degree, s.rational != 0)] += 1;
                }
                for k in 1..ends.len() {
                    ends[k] += ends[k - 1];
                }
                c.class_ends = ends;
                // Segments are laid out in this order (their samples follow one another
                // along each curve), so a curve whose segments need different kernels (a
                // path of lines, quadratics and cubics) keeps them together in the
                // general kernel's class.
                let mut classes: std::collections::HashMap<u32, Option<usize>> =
                    std::collections::HashMap::new();
                for s in &c.segments {
                    let k = kernel_class(s.degree, s.rational != 0);
                    classes
                        .entry(s.curve)
                        .and_modify(|e| {
                            if *e != Some(k) {
                                *e = None;
                            }
                        })
                        .or_insert(Some(k));
                }
                let general = TESSELLATE_KERNELS.len() - 1;
                let class_of = |s: &GpuSegment| classes[&s.curve].unwrap_or(general);
                c.segments.sort_by_key(class_of);
                let mut ends = [0u32; TESSELLATE_KERNELS.len()];
                for s in &c.segments {
                    ends[class_of(s)] += 1;
                }
                for k in 1..ends.len() {
                    ends[k] += ends[k - 1];
                }
                c.segment_class_ends = ends;
                c
            })
            .collect();
        (chunks, placements)
    }
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
    /// continue in the next one from their last vertex. Returns where its vertices went.
    pub fn push(&mut self, points: &[DVec3], style: GpuLineStyle) -> Vec<BatchPiece> {
        let mut pieces = Vec::new();
        let mut rest = points;
        let mut from = 0;
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
            let batch = self.batches.len() - 1;
            let b = self
                .batches
                .last_mut()
                .unwrap_or_else(|| unreachable!("never empty"));
            let tag = b.styles.len() as u32;
            b.styles.push(style);
            let take = rest.len().min(self.max_vertices - b.vertices.len());
            pieces.push(BatchPiece {
                batch,
                first: b.vertices.len(),
                tag,
                from,
                len: take,
            });
            b.vertices.extend(rest[..take].iter().map(|p| GpuVertex {
                position: p.as_vec3().to_array(),
                id: tag,
            }));
            if take == rest.len() {
                break;
            }
            // Repeat the last vertex in the next batch so the polyline stays joined.
            rest = &rest[take - 1..];
            from += take - 1;
        }
        pieces
    }

    /// The batches built, without empty ones (only the first can be: batches are opened
    /// for a polyline's vertices, so the [`BatchPiece::batch`] indices stay right).
    #[must_use]
    pub fn finish(self) -> Vec<LineBatch> {
        self.batches
            .into_iter()
            .filter(|b| !b.vertices.is_empty())
            .collect()
    }
}

/// Where part of a polyline went: `len` of its vertices from its `from`-th on, at vertex
/// `first` of batch `batch`, with style tag `tag` there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BatchPiece {
    /// The batch.
    pub batch: usize,
    /// The first vertex in the batch.
    pub first: usize,
    /// The style tag the vertices carry.
    pub tag: u32,
    /// The first vertex of the polyline this piece holds.
    pub from: usize,
    /// How many vertices.
    pub len: usize,
}
