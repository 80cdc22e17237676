//! The CPU twin of `shaders/layer.wgsl`'s rasterizers: the curves' pieces and the comb's
//! hairs and envelope pieces into a layer of one `u32` per pixel, with the same operations
//! in `f32`. Tests compare the GPU's layer with it (pixels where a line's position rounds
//! differently may move by one, and a coverage by one step).

use glam::{Mat4, Vec2, Vec4};

use super::layout::{
    GpuCamera, GpuLineStyle, GpuVertex, LINE_CAP_SHIFT, LINE_CLOSED, LINE_CONTINUES_AFTER,
    LINE_CONTINUES_BEFORE, LINE_JOIN_SHIFT, LINE_MITER_SHIFT, LINE_SHAPE_MASK,
};

/// What a pixel holds (bits 31–30 of its value): the highest wins. A comb's hair.
pub const KIND_HAIR: u32 = 1;
/// A comb's envelope.
pub const KIND_ENVELOPE: u32 = 2;
/// A curve.
pub const KIND_CURVE: u32 = 3;
/// Twin: `EYE_W` in `shaders/common.wgsl`.
const NEAR_W: f32 = 1e-6;

/// The lines of one chunk's comb as the comb pass left them.
#[derive(Debug, Clone, Copy)]
pub struct CombLines<'a> {
    /// Two vertices per hair: the curve's point, the tip.
    pub hairs: &'a [GpuVertex],
    /// One vertex per sample: the tips, consecutive ones joined.
    pub envelope: &'a [GpuVertex],
    /// The hairs' styles, by tag.
    pub hair_styles: &'a [GpuLineStyle],
    /// The envelope's styles, by tag.
    pub envelope_styles: &'a [GpuLineStyle],
    /// Hairs drawn (the samples placed this frame).
    pub hair_count: u32,
    /// Envelope pieces drawn (one less).
    pub piece_count: u32,
}

/// A curve's place in the scene's style table, as a pixel's value holds it (23 bits).
pub const ORDER_MASK: u32 = 0x007f_ffff;
/// The bit of a stroke's core (a curve covering at least half the pixel, a comb line).
pub const CORE_BIT: u32 = 0x2000_0000;

/// `key_of` of the shader: the kind in bits 31–30, the core bit, the order in bits 28–6,
/// the alpha in 5–0.
#[must_use]
pub fn key_of(kind: u32, core: bool, order: u32, alpha: u32) -> u32 {
    (kind << 30) | if core { CORE_BIT } else { 0 } | ((order & ORDER_MASK) << 6) | alpha
}

/// `packed` of the shader: a comb line's value, its style's alpha times `alpha_scale`; 0
/// for an alpha that would not show.
#[must_use]
pub fn packed(style: &GpuLineStyle, alpha_scale: f32, kind: u32) -> u32 {
    let alpha = ((style.color[3] * alpha_scale).clamp(0.0, 1.0) * 63.0).round_ties_even() as u32;
    if alpha == 0 {
        return 0;
    }
    key_of(kind, true, style.order, alpha)
}

/// The layer's width and height for `camera` (`layer_size` of the shader).
#[must_use]
pub fn layer_size(camera: &GpuCamera) -> [u32; 2] {
    camera.viewport_px.map(|x| x as u32)
}

/// Rasterizes `lines` into `layer` (`layer_size` wide, row by row) by maximum, as
/// `raster_comb` does.
///
/// # Panics
/// If a line's two tags are equal but not an index of its style table (the comb pass
/// never writes one).
pub fn raster_comb(camera: &GpuCamera, lines: &CombLines<'_>, layer: &mut [u32]) {
    for p in 0..lines.hair_count as usize {
        let (foot, tip) = (lines.hairs[2 * p], lines.hairs[2 * p + 1]);
        // Tags that differ (another curve, a hidden comb) draw nothing.
        if foot.id == tip.id {
            let key = packed(&lines.hair_styles[foot.id as usize], 1.0, KIND_HAIR);
            raster_line(camera, foot, tip, key, layer);
        } else if foot.id == tip.id & !crate::layout::COMB_CAPPED {
            // A capped hair: in the envelope's stroke.
            let key = packed(&lines.envelope_styles[foot.id as usize], 1.0, KIND_ENVELOPE);
            raster_line(camera, foot, tip, key, layer);
        }
        if p < lines.piece_count as usize {
            let (a, b) = (lines.envelope[p], lines.envelope[p + 1]);
            if a.id == b.id {
                let key = packed(&lines.envelope_styles[a.id as usize], 1.0, KIND_ENVELOPE);
                raster_line(camera, a, b, key, layer);
            }
        }
    }
}

fn pixel_from_clip(camera: &GpuCamera, c: Vec4) -> Vec2 {
    let ndc = Vec2::new(c.x, c.y) / c.w;
    let [w, h] = camera.viewport_px;
    Vec2::new((ndc.x * 0.5 + 0.5) * w, (0.5 - ndc.y * 0.5) * h)
}

/// `clip_range` of the shader: `range` narrowed to where `p_k t ≤ q`.
fn clip_range(mut range: Vec2, p_k: f32, q: f32) -> Vec2 {
    if p_k == 0.0 {
        if q < 0.0 {
            range = Vec2::new(1.0, 0.0);
        }
    } else {
        let t = q / p_k;
        if p_k < 0.0 {
            range.x = range.x.max(t);
        } else {
            range.y = range.y.min(t);
        }
    }
    range
}

fn plot(x: i32, y: i32, size: [u32; 2], key: u32, layer: &mut [u32]) {
    if x >= 0 && y >= 0 && (x as u32) < size[0] && (y as u32) < size[1] {
        let index = (y as u32 * size[0] + x as u32) as usize;
        if let Some(slot) = layer.get_mut(index) {
            *slot = (*slot).max(key);
        }
    }
}

/// `half_width_px` of the shader: half a style's line width in pixels where the line is
/// at clip-space `w` (a width in scene units times the pixels one unit spans there).
#[must_use]
pub fn half_width_px(style: &GpuLineStyle, camera: &GpuCamera, w: f32) -> f32 {
    if style.flags & crate::layout::LINE_WIDTH_IN_SCENE != 0 {
        let m = camera.clip_from_world;
        let s = glam::Vec3::new(m[0][1], m[1][1], m[2][1]).length();
        return (0.25 * style.width_px * s * camera.viewport_px[1] / w.max(1e-6)).min(16384.0);
    }
    0.5 * style.width_px * camera.width_scale
}

/// The clip-space w of a piece's ends, averaged (where its width in scene units is
/// measured).
fn mean_w(camera: &GpuCamera, a: GpuVertex, b: GpuVertex) -> f32 {
    let m = Mat4::from_cols_array_2d(&camera.clip_from_world);
    let ca = m * glam::Vec3::from(a.position).extend(1.0);
    let cb = m * glam::Vec3::from(b.position).extend(1.0);
    0.5 * (ca.w + cb.w)
}

/// `pixel_ends` of the shader: the ends in pixels, clipped to the plane in front of the
/// eye; `None` when both are behind it or an end is not finite.
fn pixel_ends(camera: &GpuCamera, a: GpuVertex, b: GpuVertex) -> Option<(Vec2, Vec2)> {
    let m = Mat4::from_cols_array_2d(&camera.clip_from_world);
    let mut ca = m * glam::Vec3::from(a.position).extend(1.0);
    let mut cb = m * glam::Vec3::from(b.position).extend(1.0);
    if ca.w < NEAR_W && cb.w < NEAR_W {
        return None;
    }
    if ca.w < NEAR_W {
        ca = ca.lerp(cb, (NEAR_W - ca.w) / (cb.w - ca.w));
    } else if cb.w < NEAR_W {
        cb = cb.lerp(ca, (NEAR_W - cb.w) / (ca.w - cb.w));
    }
    let (p, q) = (pixel_from_clip(camera, ca), pixel_from_clip(camera, cb));
    (p.is_finite() && q.is_finite()).then_some((p, q))
}

/// Rasterizes curve pieces `0 .. pieces` (samples `p`, `p + 1` with the same tag) into
/// `layer` by maximum, as `raster_curves` does.
///
/// # Panics
/// If a piece's tag is not an index of `styles` (the tessellator never writes one).
pub fn raster_curves(
    camera: &GpuCamera,
    samples: &[GpuVertex],
    styles: &[GpuLineStyle],
    pieces: u32,
    layer: &mut [u32],
) {
    let pieces = (pieces as usize).min(samples.len().max(1) - 1);
    for p in 0..pieces {
        let (a, b) = (samples[p], samples[p + 1]);
        if a.id == b.id {
            let style = &styles[a.id as usize];
            if style.flags & LINE_SHAPE_MASK == 0 {
                raster_piece(camera, a, b, style, END_ROUND, END_ROUND, layer);
            } else {
                raster_shaped(camera, samples, p, pieces, style, layer);
            }
        }
    }
}

/// How a piece's end is drawn (`END_*` of the shader): a half disc, cut at the end point
/// with an anti-aliased edge, cut half the width beyond it, cut with a hard edge.
const END_ROUND: u32 = 0;
const END_BUTT: u32 = 1;
const END_SQUARE: u32 = 2;
const END_HARD: u32 = 3;
const JOIN_ROUND: u32 = 0;
const JOIN_MITER: u32 = 1;

/// `before` of the shader: the sample before `p` on its run at another place (one repeat
/// passed over), or `p`.
fn before(samples: &[GpuVertex], p: usize) -> usize {
    let s = samples[p];
    let mut i = p;
    for _ in 0..2 {
        if i == 0 {
            break;
        }
        let q = samples[i - 1];
        if q.id != s.id {
            return p;
        }
        i -= 1;
        if q.position != s.position {
            return i;
        }
    }
    p
}

/// `after` of the shader: the sample after `p` (at most `last`) on its run at another
/// place, or `p`.
fn after(samples: &[GpuVertex], p: usize, last: usize) -> usize {
    let s = samples[p];
    let mut i = p;
    for _ in 0..2 {
        if i >= last {
            break;
        }
        let q = samples[i + 1];
        if q.id != s.id {
            return p;
        }
        i += 1;
        if q.position != s.position {
            return i;
        }
    }
    p
}

/// `raster_shaped` of the shader: piece `p` (samples `p`, `p + 1` of `last + 1`) with caps
/// where its run ends and joins where it goes on.
fn raster_shaped(
    camera: &GpuCamera,
    samples: &[GpuVertex],
    p: usize,
    last: usize,
    style: &GpuLineStyle,
    layer: &mut [u32],
) {
    let cap = (style.flags >> LINE_CAP_SHIFT) & 3;
    let join = (style.flags >> LINE_JOIN_SHIFT) & 3;
    let closed = style.flags & LINE_CLOSED != 0;
    let at_join = if join == JOIN_ROUND {
        END_ROUND
    } else {
        END_HARD
    };
    let start = if before(samples, p) != p {
        at_join
    } else if closed {
        END_HARD
    } else if style.flags & LINE_CONTINUES_BEFORE != 0 {
        END_ROUND
    } else {
        cap
    };
    let next = after(samples, p + 1, last);
    let end = if next != p + 1 {
        at_join
    } else if closed {
        END_HARD
    } else if style.flags & LINE_CONTINUES_AFTER != 0 {
        END_ROUND
    } else {
        cap
    };
    let (a, b) = (samples[p], samples[p + 1]);
    raster_piece(camera, a, b, style, start, end, layer);
    if next != p + 1
        && join != JOIN_ROUND
        && let (Some((pa, pb)), Some((qa, qb))) = (
            pixel_ends(camera, a, b),
            pixel_ends(camera, b, samples[next]),
        )
    {
        let (d1, d2) = (pb - pa, qb - qa);
        if d1.length() > 1e-6 && d2.length() > 1e-6 {
            let half_width = half_width_px(style, camera, mean_w(camera, a, b));
            raster_join(
                camera,
                pb,
                d1.normalize(),
                d2.normalize(),
                style,
                half_width,
                layer,
            );
        }
    }
}

/// `raster_join` of the shader: the wedge of a miter or bevel join at `at`.
fn raster_join(
    camera: &GpuCamera,
    at: Vec2,
    d1: Vec2,
    d2: Vec2,
    style: &GpuLineStyle,
    half_width: f32,
    layer: &mut [u32],
) {
    let turn = d1.x * d2.y - d1.y * d2.x;
    let cosine = d1.dot(d2);
    if turn.abs() < 1e-6 && cosine > 0.0 {
        return;
    }
    let mut n1 = Vec2::new(-d1.y, d1.x);
    if n1.dot(d2) > 0.0 {
        n1 = -n1;
    }
    let mut n2 = Vec2::new(-d2.y, d2.x);
    if n2.dot(d1) < 0.0 {
        n2 = -n2;
    }
    let limit = (style.flags >> LINE_MITER_SHIFT) as f32 / 1024.0;
    let miter =
        (style.flags >> LINE_JOIN_SHIFT) & 3 == JOIN_MITER && 2.0 <= limit * limit * (1.0 + cosine);
    let a = at + half_width * n1;
    let b = at + half_width * n2;
    let mut lo = at.min(a.min(b));
    let mut hi = at.max(a.max(b));
    let mut bevel = Vec2::ZERO;
    if miter {
        let tip = at + half_width * (n1 + n2) / (1.0 + cosine);
        lo = lo.min(tip);
        hi = hi.max(tip);
    } else {
        bevel = (n1 + n2).normalize();
    }
    let size = layer_size(camera);
    let (w, h) = (size[0] as f32, size[1] as f32);
    let (x0, x1) = (
        (lo.x - 1.0).floor().max(0.0),
        (hi.x + 1.0).ceil().min(w - 1.0),
    );
    let (y0, y1) = (
        (lo.y - 1.0).floor().max(0.0),
        (hi.y + 1.0).ceil().min(h - 1.0),
    );
    let opacity = style.color[3].clamp(0.0, 1.0) * 63.0;
    let mut y = y0;
    while y <= y1 {
        let mut x = x0;
        while x <= x1 {
            let pixel = Vec2::new(x + 0.5, y + 0.5);
            let v = pixel - at;
            if v.dot(d1) >= 0.0 && v.dot(d2) < 0.0 {
                let inside = if miter {
                    (half_width - v.dot(n1)).min(half_width - v.dot(n2))
                } else {
                    half_width * n1.dot(bevel) - v.dot(bevel)
                };
                let coverage = (0.5 + inside).clamp(0.0, 1.0);
                let alpha = (opacity * coverage).round_ties_even() as u32;
                if alpha > 0 {
                    let index = (y as u32 * size[0] + x as u32) as usize;
                    if let Some(slot) = layer.get_mut(index) {
                        *slot =
                            (*slot).max(key_of(KIND_CURVE, coverage >= 0.5, style.order, alpha));
                    }
                }
            }
            x += 1.0;
        }
        y += 1.0;
    }
}

/// `end_coverage` of the shader: how much of a pixel `t` inside an end drawn as `mode`
/// leaves.
fn end_coverage(t: f32, mode: u32, half_width: f32) -> f32 {
    match mode {
        END_BUTT => (0.5 + t).clamp(0.0, 1.0),
        END_SQUARE => (0.5 + t + half_width).clamp(0.0, 1.0),
        END_HARD => {
            if t >= 0.0 {
                1.0
            } else {
                0.0
            }
        }
        _ => 1.0,
    }
}

/// `along_major` of the shader: `a` and `b` with the major axis first, in order along it.
fn along_major(a: Vec2, b: Vec2, x_major: bool) -> (Vec2, Vec2) {
    let swap = |v: Vec2| if x_major { v } else { Vec2::new(v.y, v.x) };
    let (s, e) = (swap(a), swap(b));
    if s.x > e.x { (e, s) } else { (s, e) }
}

/// `raster_piece` of the shader.
fn raster_piece(
    camera: &GpuCamera,
    a: GpuVertex,
    b: GpuVertex,
    style: &GpuLineStyle,
    start: u32,
    end: u32,
    layer: &mut [u32],
) {
    let Some((pa, pb)) = pixel_ends(camera, a, b) else {
        return;
    };
    let opacity = style.color[3].clamp(0.0, 1.0) * 63.0;
    let half_width = half_width_px(style, camera, mean_w(camera, a, b));
    let dash = style.dash_px * camera.width_scale;
    let reach = half_width + 0.5;
    let d = pb - pa;
    let len = d.length();
    let dir = if len > 1e-6 {
        d / len
    } else if start != END_ROUND || end != END_ROUND {
        return;
    } else {
        Vec2::X
    };
    let sa = pa - if start == END_SQUARE { half_width } else { 0.0 } * dir;
    let sb = pb + if end == END_SQUARE { half_width } else { 0.0 } * dir;
    let size = layer_size(camera);
    let x_major = d.x.abs() >= d.y.abs();
    let swap = |v: Vec2| if x_major { v } else { Vec2::new(v.y, v.x) };
    let (s, e) = along_major(sa, sb, x_major);
    let extent = swap(Vec2::new(size[0] as f32, size[1] as f32));
    let slope = (e.y - s.y) / (e.x - s.x).max(1e-30);
    let across = reach * (1.0 + slope * slope).sqrt();
    let first = (s.x - reach - 0.5).ceil().max(0.0);
    let last = (e.x + reach - 0.5).floor().min(extent.x - 1.0);
    let mut column = first;
    while column <= last {
        let xc = column + 0.5;
        let yc = s.y + (xc.clamp(s.x, e.x) - s.x) * slope;
        let top = (yc - across - 0.5).ceil().max(0.0);
        let bottom = (yc + across - 0.5).floor().min(extent.y - 1.0);
        let mut row = top;
        while row <= bottom {
            let pixel = swap(Vec2::new(xc, row + 0.5));
            let t = (pixel - pa).dot(dir);
            let mut along = t.clamp(0.0, len);
            if (t < 0.0 && start != END_ROUND) || (t > len && end != END_ROUND) {
                along = t;
            }
            let dist = (pixel - (pa + along * dir)).length();
            let mut coverage = (half_width + 0.5 - dist).clamp(0.0, 1.0);
            coverage = coverage.min(end_coverage(t, start, half_width));
            coverage = coverage.min(end_coverage(len - t, end, half_width));
            if dash > 0.0 && (along / dash).fract() >= 0.5 {
                coverage = 0.0;
            }
            let alpha = (opacity * coverage).round_ties_even() as u32;
            if alpha > 0 {
                let index = (pixel.y as u32 * size[0] + pixel.x as u32) as usize;
                if let Some(slot) = layer.get_mut(index) {
                    *slot = (*slot).max(key_of(KIND_CURVE, coverage >= 0.5, style.order, alpha));
                }
            }
            row += 1.0;
        }
        column += 1.0;
    }
}

fn raster_line(camera: &GpuCamera, a: GpuVertex, b: GpuVertex, key: u32, layer: &mut [u32]) {
    if key == 0 {
        return;
    }
    let Some((p, q)) = pixel_ends(camera, a, b) else {
        return;
    };
    let size = layer_size(camera);
    let extent = Vec2::new(size[0] as f32, size[1] as f32);
    let d = q - p;
    let mut range = Vec2::new(0.0, 1.0);
    range = clip_range(range, -d.x, p.x);
    range = clip_range(range, d.x, extent.x - p.x);
    range = clip_range(range, -d.y, p.y);
    range = clip_range(range, d.y, extent.y - p.y);
    if range.x > range.y {
        return;
    }
    let x_major = d.x.abs() >= d.y.abs();
    let (s, e) = along_major(p + range.x * d, p + range.y * d, x_major);
    let first = (s.x - 0.5).ceil() as i32;
    let last = (e.x - 0.5).floor() as i32;
    if last < first {
        return;
    }
    let slope = (e.y - s.y) / (e.x - s.x).max(1e-30);
    let limit = (size[0] + size[1]) as i32;
    for i in 0..=(last - first).min(limit) {
        let column = first + i;
        let row = (s.y + (column as f32 + 0.5 - s.x) * slope).floor() as i32;
        if x_major {
            plot(column, row, size, key, layer);
        } else {
            plot(row, column, size, key, layer);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera(w: f32, h: f32) -> GpuCamera {
        // World = pixels: x right, y down, from the top-left corner.
        let m = Mat4::from_cols(
            Vec4::new(2.0 / w, 0.0, 0.0, 0.0),
            Vec4::new(0.0, -2.0 / h, 0.0, 0.0),
            Vec4::new(0.0, 0.0, 1.0, 0.0),
            Vec4::new(-1.0, 1.0, 0.0, 1.0),
        );
        GpuCamera {
            clip_from_world: m.to_cols_array_2d(),
            viewport_px: [w, h],
            width_scale: 1.0,
            _padding: 0.0,
        }
    }

    fn v(x: f32, y: f32, id: u32) -> GpuVertex {
        GpuVertex {
            position: [x, y, 0.0],
            id,
        }
    }

    fn style(color: [f32; 4]) -> GpuLineStyle {
        GpuLineStyle {
            color,
            width_px: 1.0,
            dash_px: 0.0,
            order: 7,
            flags: 0,
        }
    }

    fn lit(layer: &[u32], w: u32) -> Vec<(u32, u32, u32)> {
        (0..layer.len() as u32)
            .filter(|&i| layer[i as usize] != 0)
            .map(|i| (i % w, i / w, layer[i as usize]))
            .collect()
    }

    #[test]
    fn lines_light_one_pixel_per_column_or_row_and_the_envelope_wins() {
        let cam = camera(16.0, 8.0);
        let red = [1.0, 0.0, 0.0, 0.5];
        let blue = [0.0, 0.0, 1.0, 1.0];
        // A hair straight down through column 3 (rows 1..=5), and an envelope piece
        // along row 3 from x = 1 to x = 6.
        let hairs = [v(3.5, 1.0, 0), v(3.5, 6.0, 0)];
        let envelope = [v(1.0, 3.5, 0), v(6.0, 3.5, 0)];
        let (hs, es) = ([style(red)], [style(blue)]);
        let lines = CombLines {
            hairs: &hairs,
            envelope: &envelope,
            hair_styles: &hs,
            envelope_styles: &es,
            hair_count: 1,
            piece_count: 1,
        };
        let mut layer = vec![0; 16 * 8];
        raster_comb(&cam, &lines, &mut layer);
        let hair_key = key_of(KIND_HAIR, true, 7, 32);
        let envelope_key = key_of(KIND_ENVELOPE, true, 7, 63);
        let mut want: Vec<(u32, u32, u32)> = (1..=5).map(|y| (3, y, hair_key)).collect();
        want.extend((1..=5).map(|x| (x, 3, envelope_key)));
        want.sort_by_key(|&(x, y, _)| (y, x));
        want.dedup_by_key(|&mut (x, y, _)| (x, y));
        // Where the two cross (3, 3), the envelope is drawn.
        for w in &mut want {
            if (w.0, w.1) == (3, 3) {
                w.2 = envelope_key;
            }
        }
        assert_eq!(lit(&layer, 16), want);
    }

    #[test]
    fn lines_are_clipped_to_the_layer_and_tags_that_differ_draw_nothing() {
        let cam = camera(8.0, 8.0);
        let s = [style([0.0, 1.0, 0.0, 1.0])];
        // A diagonal from far outside to far outside through the layer, and a hidden hair.
        let hairs = [
            v(-1e6, -1e6, 0),
            v(1e6, 1e6, 0),
            v(2.5, 2.5, 0),
            v(2.5, 6.5, 1),
        ];
        let lines = CombLines {
            hairs: &hairs,
            envelope: &[],
            hair_styles: &s,
            envelope_styles: &s,
            hair_count: 2,
            piece_count: 0,
        };
        let mut layer = vec![0; 64];
        raster_comb(&cam, &lines, &mut layer);
        let got: Vec<(u32, u32)> = lit(&layer, 8).iter().map(|&(x, y, _)| (x, y)).collect();
        assert_eq!(got, (0..8).map(|i| (i, i)).collect::<Vec<_>>());
    }

    #[test]
    fn colours_that_would_not_show_are_not_drawn() {
        assert_eq!(packed(&style([1.0, 1.0, 1.0, 0.001]), 1.0, KIND_HAIR), 0);
        let mut s = style([0.0, 0.0, 0.0, 1.0]);
        assert_eq!(
            packed(&s, 1.0, KIND_HAIR),
            (1 << 30) | CORE_BIT | (7 << 6) | 63
        );
        // Alpha scaled, then clamped; the order's 23 bits alone.
        assert_eq!(packed(&s, 0.5, KIND_HAIR) & 63, 32);
        assert_eq!(packed(&s, 3.0, KIND_HAIR) & 63, 63);
        s.order = 0x0080_0005;
        assert_eq!(packed(&s, 1.0, KIND_ENVELOPE) >> 6 & ORDER_MASK, 5);
    }

    #[test]
    fn a_curve_piece_covers_as_the_line_pipeline_and_wins_over_a_comb() {
        let cam = camera(16.0, 8.0);
        // A horizontal piece along y = 4 (between rows 3 and 4), two pixels wide, from
        // x = 2 to x = 10: rows 3 and 4 fully covered (distance ½ ≤ w/2 + ½ − 1), rows 2
        // and 5 at distance 3/2 (coverage 0), the round caps reaching 1½ beyond the ends.
        let samples = [v(2.0, 4.0, 0), v(10.0, 4.0, 0)];
        let mut s = style([0.0, 1.0, 0.0, 1.0]);
        s.width_px = 2.0;
        let mut layer = vec![key_of(KIND_ENVELOPE, true, 0, 63); 16 * 8];
        raster_curves(&cam, &samples, &[s], 1, &mut layer);
        let at = |x: usize, y: usize| layer[y * 16 + x];
        let full = key_of(KIND_CURVE, true, 7, 63);
        for x in 2..10 {
            assert_eq!(at(x, 3), full, "({x}, 3)");
            assert_eq!(at(x, 4), full, "({x}, 4)");
            // Distance 3/2: nothing of the curve; the comb's envelope stays.
            assert_eq!(at(x, 2) >> 30, KIND_ENVELOPE, "({x}, 2)");
        }
        // Pixel (1, 3): centre (1.5, 3.5), distance √(½² + ½²) ≈ 0.707 from the end:
        // coverage 1.5 − 0.707 = 0.79, alpha 50 of 63.
        let cap = at(1, 3);
        assert_eq!(cap, key_of(KIND_CURVE, true, 7, 50));
        // Pixel (1, 2): distance √(½² + (3/2)²) ≈ 1.58 from the end — beyond reach; (0, 3):
        // distance 1.58 too; (1, 4) as (1, 3). An edge pixel: (11, 3), centre (11.5, 3.5),
        // distance √(1.5² + ½²) ≈ 1.58: none; (10, 3): distance √(½² + ½²): a core.
        assert_eq!(at(1, 2) >> 30, KIND_ENVELOPE);
        assert_eq!(at(10, 3), key_of(KIND_CURVE, true, 7, 50));
        // The same piece again as a later curve (order 9): it wins where both cover a
        // pixel alike; an earlier one (order 3) does not.
        let mut later = s;
        later.order = 9;
        let mut earlier = s;
        earlier.order = 3;
        raster_curves(&cam, &samples, &[later], 1, &mut layer);
        raster_curves(&cam, &samples, &[earlier], 1, &mut layer);
        assert_eq!(layer[3 * 16 + 5], key_of(KIND_CURVE, true, 9, 63));
        // An edge (coverage below ½) of a later curve does not cut into an earlier core.
        let mut faint = s;
        faint.order = 12;
        faint.width_px = 0.4;
        let mut layer = vec![0; 16 * 8];
        raster_curves(&cam, &samples, &[s], 1, &mut layer);
        raster_curves(
            &cam,
            &[v(2.0, 3.0, 0), v(10.0, 3.0, 0)],
            &[faint],
            1,
            &mut layer,
        );
        assert_eq!(layer[3 * 16 + 5], key_of(KIND_CURVE, true, 7, 63));
        // A dashed piece of 4-pixel dashes: [0, 2) drawn, [2, 4) not, …
        let mut dashed = s;
        dashed.dash_px = 4.0;
        let mut layer = vec![0; 16 * 8];
        raster_curves(&cam, &samples, &[dashed], 1, &mut layer);
        let lit: Vec<usize> = (2..10).filter(|&x| layer[3 * 16 + x] != 0).collect();
        assert_eq!(lit, vec![2, 3, 6, 7]);
    }
}
