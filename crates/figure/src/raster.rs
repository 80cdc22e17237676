//! The figure's guides and text drawn onto an image the GPU rendered (8-bit RGBA,
//! straight alpha, rows top to bottom), so that `render`'s PNG carries the same labels,
//! legend, axes and grid as the vector figure: text rasterised from the same font
//! (ab_glyph), lines and boxes with analytic coverage. The grid goes only onto
//! background pixels, so it stays behind the curves.

use ab_glyph::{Font, FontRef, PxScale, point};
use glam::DVec2;
use splinescope_encoding::Color;

use super::fit::Seg;
use super::text::FONT;
use super::{Anchor, Figure, FigureError, FigureOptions, Item, TextOptions};
use splinescope_scene::format::Scene;
use splinescope_scene::format::shape::ShapeOptions;

/// An image to draw on.
pub struct Canvas<'a> {
    /// Pixels, 4 bytes each.
    pub data: &'a mut [u8],
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl Canvas<'_> {
    fn blend(&mut self, x: i64, y: i64, color: Color, coverage: f64, only_on: Option<[u8; 4]>) {
        if x < 0 || y < 0 || x >= i64::from(self.width) || y >= i64::from(self.height) {
            return;
        }
        let i = ((y as usize) * self.width as usize + x as usize) * 4;
        let px = &mut self.data[i..i + 4];
        if only_on.is_some_and(|bg| px[..3] != bg[..3]) {
            return;
        }
        let a = (coverage.clamp(0.0, 1.0) * f64::from(color.0[3])) as f32;
        for (p, c) in px.iter_mut().zip(color.0).take(3) {
            let src = c.clamp(0.0, 1.0) * 255.0;
            *p = (f32::from(*p) * (1.0 - a) + src * a).round() as u8;
        }
        px[3] = px[3].max((a * 255.0) as u8);
    }

    fn segment(&mut self, a: DVec2, b: DVec2, width: f64, color: Color, only_on: Option<[u8; 4]>) {
        let r = 0.5 * width.max(0.5);
        let (lo, hi) = (
            a.min(b) - DVec2::splat(r + 1.0),
            a.max(b) + DVec2::splat(r + 1.0),
        );
        let d = b - a;
        let len2 = d.length_squared();
        for y in lo.y.floor() as i64..=hi.y.ceil() as i64 {
            for x in lo.x.floor() as i64..=hi.x.ceil() as i64 {
                let p = DVec2::new(x as f64 + 0.5, y as f64 + 0.5);
                let t = if len2 > 0.0 {
                    ((p - a).dot(d) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let dist = (a + t * d - p).length();
                let coverage = (r + 0.5 - dist).clamp(0.0, 1.0);
                if coverage > 0.0 {
                    self.blend(x, y, color, coverage, only_on);
                }
            }
        }
    }

    fn text(
        &mut self,
        font: &FontRef<'_>,
        at: DVec2,
        size: f64,
        text: &str,
        color: Color,
        anchor: Anchor,
    ) {
        // One output point per pixel: an em of `size` pixels (ab_glyph's scale is the
        // ascent-to-descent height; its pt_to_px_scale assumes 96 dpi).
        let scale = font
            .units_per_em()
            .map_or(PxScale::from(size as f32), |units| {
                PxScale::from(size as f32 * font.height_unscaled() / units)
            });
        let w = super::text::width(text, size);
        let mut x = match anchor {
            Anchor::Start => at.x,
            Anchor::Middle => at.x - 0.5 * w,
            Anchor::End => at.x - w,
        } as f32;
        for c in text.chars() {
            let id = font.glyph_id(c);
            let glyph = id.with_scale_and_position(scale, point(x, at.y as f32));
            if let Some(outlined) = font.outline_glyph(glyph) {
                let b = outlined.px_bounds();
                outlined.draw(|gx, gy, cov| {
                    self.blend(
                        i64::from(b.min.x as i32) + i64::from(gx),
                        i64::from(b.min.y as i32) + i64::from(gy),
                        color,
                        f64::from(cov),
                        None,
                    );
                });
            }
            x += (super::text::advance(id.0) * size) as f32;
        }
    }

    fn item(&mut self, font: Option<&FontRef<'_>>, item: &Item, only_on: Option<[u8; 4]>) {
        match item {
            Item::Path { runs, stroke, .. } => {
                for run in runs {
                    let mut from = run.start;
                    for piece in &run.pieces {
                        let to = piece.seg.end();
                        if let Seg::Line(_) = piece.seg {
                            self.segment(
                                from,
                                to,
                                f64::from(stroke.width_px),
                                stroke.color,
                                only_on,
                            );
                        }
                        from = to;
                    }
                }
            }
            Item::Rect {
                min,
                max,
                fill,
                stroke,
            } => {
                for y in min.y.round() as i64..max.y.round() as i64 {
                    for x in min.x.round() as i64..max.x.round() as i64 {
                        self.blend(x, y, *fill, 1.0, only_on);
                    }
                }
                if let Some(st) = stroke {
                    let corners = [
                        *min,
                        DVec2::new(max.x, min.y),
                        *max,
                        DVec2::new(min.x, max.y),
                    ];
                    for k in 0..4 {
                        self.segment(
                            corners[k],
                            corners[(k + 1) % 4],
                            f64::from(st.width_px),
                            st.color,
                            only_on,
                        );
                    }
                }
            }
            Item::Text {
                at,
                size,
                text,
                color,
                anchor,
            } => {
                if let Some(font) = font {
                    self.text(font, *at, *size, text, *color, *anchor);
                }
            }
            Item::Disc {
                center,
                radius,
                color,
            } => {
                let r = radius + 1.0;
                for y in (center.y - r).floor() as i64..=(center.y + r).ceil() as i64 {
                    for x in (center.x - r).floor() as i64..=(center.x + r).ceil() as i64 {
                        let d = DVec2::new(x as f64 + 0.5, y as f64 + 0.5).distance(*center);
                        let coverage = (radius + 0.5 - d).clamp(0.0, 1.0);
                        if coverage > 0.0 {
                            self.blend(x, y, *color, coverage, only_on);
                        }
                    }
                }
            }
        }
    }
}

/// Draws `fig`'s grid (onto background pixels), axes, labels and legend onto `canvas`,
/// which holds the same scene rendered at the same size and camera.
pub fn draw_guides(fig: &Figure, canvas: &mut Canvas<'_>) {
    let bg = fig
        .background
        .0
        .map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8);
    // The font, parsed once for all the text.
    let font = FontRef::try_from_slice(FONT).ok();
    for item in &fig.items[..fig.behind] {
        canvas.item(font.as_ref(), item, Some(bg));
    }
    for item in &fig.items[fig.front..] {
        canvas.item(font.as_ref(), item, None);
    }
}

/// Draws `text`'s guides and text onto `canvas`, a render of `scene` with the scene's own
/// camera at the canvas's size; nothing when `text` asks for none.
///
/// # Errors
/// [`FigureError`] (axes or a grid asked of a 3D view).
pub fn annotate(
    canvas: &mut Canvas<'_>,
    scene: &Scene,
    text: TextOptions,
) -> Result<(), FigureError> {
    annotate_shaped(canvas, scene, text, &ShapeOptions::default())
}

/// [`annotate`] with the legend's marker rows for the markers `shape` shows (the picture
/// drawn with them).
///
/// # Errors
/// As [`annotate`].
pub fn annotate_shaped(
    canvas: &mut Canvas<'_>,
    scene: &Scene,
    text: TextOptions,
    shape: &ShapeOptions,
) -> Result<(), FigureError> {
    let mut opts = FigureOptions::new(canvas.width, canvas.height).with_text(text);
    opts.shape = *shape;
    annotate_with(canvas, scene, opts)
}

/// Draws the guides and text `opts` asks for onto `canvas`, a render of `scene` through
/// `opts`' camera (the scene's own when `None`) at the canvas's size — `opts`' size, shape
/// overlays (the legend's marker rows) and switches as the picture was drawn; its curves
/// are the picture's already and are not drawn again. Nothing when `opts` asks for no
/// text.
///
/// # Errors
/// As [`annotate`].
pub fn annotate_with(
    canvas: &mut Canvas<'_>,
    scene: &Scene,
    mut opts: FigureOptions,
) -> Result<(), FigureError> {
    if !opts.text().any() {
        return Ok(());
    }
    opts.curves = false;
    let fig = super::build(scene, &opts)?;
    draw_guides(&fig, canvas);
    Ok(())
}
