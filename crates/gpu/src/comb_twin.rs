//! The CPU twin of `shaders/comb.wgsl`'s rasterizer: the comb's hairs and envelope pieces
//! into a layer of one `u32` per pixel, with the same operations in `f32`. Tests compare
//! the GPU's layer with it (pixels where a line's position rounds differently may move by
//! one).

use glam::{Mat4, Vec2, Vec4};

use super::layout::{GpuCamera, GpuLineStyle, GpuVertex};

const ENVELOPE_BIT: u32 = 0x8000_0000;
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

/// `packed` of the shader: bit 31 for the envelope, a 7-bit alpha, 8-bit red, green, blue;
/// 0 for a colour that would not show.
#[must_use]
pub fn packed(color: [f32; 4], envelope: bool) -> u32 {
    let c = Vec4::from(color).clamp(Vec4::ZERO, Vec4::ONE);
    let alpha = (c.w * 127.0).round_ties_even() as u32;
    if alpha == 0 {
        return 0;
    }
    let [r, g, b] = [c.x, c.y, c.z].map(|x| (x * 255.0).round_ties_even() as u32);
    (if envelope { ENVELOPE_BIT } else { 0 }) | (alpha << 24) | (r << 16) | (g << 8) | b
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
            let key = packed(lines.hair_styles[foot.id as usize].color, false);
            raster_line(camera, foot, tip, key, layer);
        }
        if p < lines.piece_count as usize {
            let (a, b) = (lines.envelope[p], lines.envelope[p + 1]);
            if a.id == b.id {
                let key = packed(lines.envelope_styles[a.id as usize].color, true);
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

fn raster_line(camera: &GpuCamera, a: GpuVertex, b: GpuVertex, key: u32, layer: &mut [u32]) {
    if key == 0 {
        return;
    }
    let m = Mat4::from_cols_array_2d(&camera.clip_from_world);
    let mut ca = m * glam::Vec3::from(a.position).extend(1.0);
    let mut cb = m * glam::Vec3::from(b.position).extend(1.0);
    if ca.w < NEAR_W && cb.w < NEAR_W {
        return;
    }
    if ca.w < NEAR_W {
        ca = ca.lerp(cb, (NEAR_W - ca.w) / (cb.w - ca.w));
    } else if cb.w < NEAR_W {
        cb = cb.lerp(ca, (NEAR_W - cb.w) / (ca.w - cb.w));
    }
    let p = pixel_from_clip(camera, ca);
    let q = pixel_from_clip(camera, cb);
    if !(p.is_finite() && q.is_finite()) {
        return;
    }
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
    let (mut s, mut e) = (p + range.x * d, p + range.y * d);
    if !x_major {
        (s, e) = (Vec2::new(s.y, s.x), Vec2::new(e.y, e.x));
    }
    if s.x > e.x {
        (s, e) = (e, s);
    }
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
            _padding0: 0,
            _padding1: 0,
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
        let hair_key = (64 << 24) | (255 << 16);
        let envelope_key = ENVELOPE_BIT | (127 << 24) | 255;
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
        assert_eq!(packed([1.0, 1.0, 1.0, 0.001], false), 0);
        assert_eq!(packed([0.0, 0.0, 0.0, 1.0], false), 127 << 24);
        assert_eq!(
            packed([2.0, -1.0, 0.5, 1.0], true) & 0xff_ffff,
            (255 << 16) | 128
        );
    }
}
