//! Packing the scene's draw list ([`splinescope_encoding::draw`]) for the GPU: strokes become
//! [`GpuLineStyle`] table entries, polylines and points binding-sized batches.

use std::ops::Range;

use super::chunks::{BatchBuilder, BatchPiece, ChunkLimits, LineBatch};
use super::layout::{GpuLineStyle, GpuVertex};
use splinescope_encoding::Color;
use splinescope_encoding::draw::{CurveOverlays, DrawList, Stroke, Switches};

impl GpuLineStyle {
    /// A solid style.
    #[must_use]
    pub fn solid(color: Color, width_px: f32) -> GpuLineStyle {
        GpuLineStyle::from(Stroke::solid(color, width_px))
    }
}

impl From<Stroke> for GpuLineStyle {
    fn from(s: Stroke) -> GpuLineStyle {
        GpuLineStyle {
            color: s.color.0,
            width_px: s.width_px,
            dash_px: s.dash_px,
            order: 0,
            flags: 0,
        }
    }
}

/// One draw-list entry as packed: where its vertices went, how many it has, its stroke.
#[derive(Debug, Clone, PartialEq)]
struct Entry {
    pieces: Vec<BatchPiece>,
    len: usize,
    stroke: Stroke,
}

/// Where every overlay entry went in the batches, and which entries are each curve's and
/// the axis triad's: what rewriting one curve's overlays in place needs.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct OverlayMap {
    lines: Vec<Entry>,
    points: Vec<Entry>,
    curves: Vec<(Range<usize>, Range<usize>)>,
    axes: Range<usize>,
    switches: Option<Switches>,
}

/// Vertex writes into overlay batches: `(batch, first vertex, vertices)`.
pub type BatchWrites = Vec<(usize, usize, Vec<GpuVertex>)>;

/// The overlay polylines and points of a draw list made with `switches`, batched, and the
/// [`OverlayMap`] of where each went.
#[must_use]
pub fn prepare_overlays_mapped(
    list: &DrawList,
    switches: Switches,
    limits: ChunkLimits,
) -> (Vec<LineBatch>, Vec<LineBatch>, OverlayMap) {
    let pack = |entries: &[(Vec<glam::DVec3>, Stroke)]| {
        let mut builder = BatchBuilder::new(limits);
        let map: Vec<Entry> = entries
            .iter()
            .map(|(pts, stroke)| Entry {
                pieces: builder.push(pts, GpuLineStyle::from(*stroke)),
                len: pts.len(),
                stroke: *stroke,
            })
            .collect();
        (builder.finish(), map)
    };
    let (lines, line_map) = pack(&list.lines);
    let (points, point_map) = pack(&list.points);
    let map = OverlayMap {
        lines: line_map,
        points: point_map,
        curves: list.curves.clone(),
        axes: list.axes.clone(),
        switches: Some(switches),
    };
    (lines, points, map)
}

/// Point sets (the shape markers), batched.
#[must_use]
pub fn prepare_points(
    entries: &[(Vec<glam::DVec3>, Stroke)],
    limits: ChunkLimits,
) -> Vec<LineBatch> {
    let mut builder = BatchBuilder::new(limits);
    for (pts, stroke) in entries {
        builder.push(pts, GpuLineStyle::from(*stroke));
    }
    builder.finish()
}

/// The new overlays of an edit: the changed curves' (`splinescope_scene::format::draw::curve_overlays`
/// of each, with its index) and the 3D axis triad's (`splinescope_scene::format::draw::axis_lines`),
/// drawn with `switches` for a scene of `curve_count` curves.
#[derive(Debug, Clone)]
pub struct OverlayEdit {
    /// The overlay switches they were drawn with.
    pub switches: Switches,
    /// How many curves the scene has.
    pub curve_count: usize,
    /// Each changed curve's index and overlays.
    pub curves: Vec<(usize, CurveOverlays)>,
    /// The axis triad's polylines (none for a planar scene).
    pub axes: Vec<(Vec<glam::DVec3>, Stroke)>,
}

impl OverlayMap {
    /// The writes that put `edit`'s overlays where their old vertices are, as `(line
    /// writes, point writes)`; `None` when their shape changed — another number of
    /// polylines or vertices, another stroke, other switches, curves added or removed —
    /// and the overlays must be packed again.
    #[must_use]
    pub fn rewrite(&self, edit: &OverlayEdit) -> Option<(BatchWrites, BatchWrites)> {
        if self.switches != Some(edit.switches) || self.curves.len() != edit.curve_count {
            return None;
        }
        let (mut line_writes, mut point_writes) = (Vec::new(), Vec::new());
        for (c, (lines, points)) in &edit.curves {
            let (line_range, point_range) = self.curves.get(*c)?.clone();
            write_entries(&self.lines[line_range], lines, &mut line_writes)?;
            write_entries(&self.points[point_range], points, &mut point_writes)?;
        }
        write_entries(&self.lines[self.axes.clone()], &edit.axes, &mut line_writes)?;
        Some((line_writes, point_writes))
    }
}

/// The writes of `new` entries over `old` ones of the same shape (`None` otherwise).
fn write_entries(
    old: &[Entry],
    new: &[(Vec<glam::DVec3>, Stroke)],
    writes: &mut BatchWrites,
) -> Option<()> {
    if old.len() != new.len() {
        return None;
    }
    for (entry, (pts, stroke)) in old.iter().zip(new) {
        if entry.len != pts.len() || entry.stroke != *stroke {
            return None;
        }
        for piece in &entry.pieces {
            let verts = pts[piece.from..piece.from + piece.len]
                .iter()
                .map(|p| GpuVertex {
                    position: p.as_vec3().to_array(),
                    id: piece.tag,
                })
                .collect();
            writes.push((piece.batch, piece.first, verts));
        }
    }
    Some(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use splinescope_core::geom::ParamCurve;
    use splinescope_scene::format::Scene;
    use splinescope_scene::format::draw::{axis_lines, curve_overlays, draw_list};

    fn edit(scene: &Scene, switches: Switches, c: usize) -> OverlayEdit {
        OverlayEdit {
            switches,
            curve_count: scene.curves.len(),
            curves: vec![(c, curve_overlays(&scene.curves[c], switches))],
            axes: axis_lines(scene),
        }
    }

    fn apply(batches: &mut [LineBatch], writes: &BatchWrites) {
        for (batch, first, verts) in writes {
            batches[*batch].vertices[*first..*first + verts.len()].copy_from_slice(verts);
        }
    }

    /// Rewriting a curve's overlays in place gives exactly the batches a fresh packing of
    /// the edited scene gives — also with batches so small that polylines are split
    /// across them — and a change of shape asks for a fresh packing instead.
    #[test]
    fn rewritten_overlays_equal_a_fresh_packing() {
        let scene = splinescope_scene::format::gallery::gallery();
        for limits in [
            ChunkLimits::for_binding_size(1 << 20),
            ChunkLimits {
                max_samples: 64,
                max_points: 7,
                max_records: 64,
                max_styles: 3,
            },
        ] {
            let (mut lines, mut points, map) =
                prepare_overlays_mapped(&draw_list(&scene), Switches::ALL, limits);
            let mut edited = scene.clone();
            // A curve with a drawn polygon and points (the 3D one, so the axes move too).
            let c = (0..scene.curves.len())
                .rev()
                .find(|&i| {
                    let (l, p) = curve_overlays(&scene.curves[i], Switches::ALL);
                    !l.is_empty() && !p.is_empty()
                })
                .expect("a curve with overlays");
            let mut pts = edited.curves[c].curve.control_points().to_vec();
            pts[1] += DVec3::new(0.3, -0.7, 0.0);
            edited.curves[c].curve = edited.curves[c]
                .curve
                .with_control_points(pts)
                .expect("valid");
            assert!(edited.curves[c].curve.domain().1 > 0.0);
            let (line_writes, point_writes) = map
                .rewrite(&edit(&edited, Switches::ALL, c))
                .expect("the same shape");
            assert!(!line_writes.is_empty() && !point_writes.is_empty());
            apply(&mut lines, &line_writes);
            apply(&mut points, &point_writes);
            let (fresh_lines, fresh_points, _) =
                prepare_overlays_mapped(&draw_list(&edited), Switches::ALL, limits);
            assert_eq!(lines, fresh_lines, "lines at {limits:?}");
            assert_eq!(points, fresh_points, "points at {limits:?}");
            // Another shape: the curve's polygon hidden, other switches, another colour.
            let mut hidden = scene.clone();
            hidden.curves[c].style.show_polygon = false;
            assert!(map.rewrite(&edit(&hidden, Switches::ALL, c)).is_none());
            let off = Switches {
                polygons: false,
                points: true,
            };
            assert!(map.rewrite(&edit(&scene, off, c)).is_none());
            let mut recoloured = scene.clone();
            recoloured.curves[c].style.color = splinescope_encoding::Color([0.1, 0.2, 0.3, 1.0]);
            assert!(map.rewrite(&edit(&recoloured, Switches::ALL, c)).is_none());
        }
    }

    /// In a 3D scene the axis triad follows the bounds: moving a point past them moves the
    /// triad, and the rewrite carries it too.
    #[test]
    fn the_axis_triad_is_rewritten_with_the_curve() {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/bezier3d.json");
        let scene = Scene::load(&path).expect("the 3D scene");
        assert!(!axis_lines(&scene).is_empty(), "a 3D scene has a triad");
        let limits = ChunkLimits::for_binding_size(1 << 20);
        let (mut lines, mut points, map) =
            prepare_overlays_mapped(&draw_list(&scene), Switches::ALL, limits);
        let mut edited = scene.clone();
        let mut pts = edited.curves[0].curve.control_points().to_vec();
        pts[0] -= DVec3::new(5.0, 5.0, 5.0);
        edited.curves[0].curve = edited.curves[0]
            .curve
            .with_control_points(pts)
            .expect("valid");
        assert_ne!(axis_lines(&edited), axis_lines(&scene), "the triad moved");
        let (line_writes, point_writes) = map
            .rewrite(&edit(&edited, Switches::ALL, 0))
            .expect("the same shape");
        apply(&mut lines, &line_writes);
        apply(&mut points, &point_writes);
        let (fresh_lines, fresh_points, _) =
            prepare_overlays_mapped(&draw_list(&edited), Switches::ALL, limits);
        assert_eq!(lines, fresh_lines);
        assert_eq!(points, fresh_points);
    }
}
