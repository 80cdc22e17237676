//! Colours as the encoding carries them.

/// A colour with straight (not premultiplied) alpha, each channel in `[0, 1]`, sRGB.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Color(pub [f32; 4]);

impl Color {
    /// Opaque white.
    pub const WHITE: Color = Color([1.0, 1.0, 1.0, 1.0]);

    /// This colour mixed with `other` by `f` (`0` keeps `self`).
    #[must_use]
    pub fn mix(self, other: Color, f: f32) -> Color {
        let mut c = self.0;
        for (ch, o) in c.iter_mut().zip(other.0) {
            *ch += (o - *ch) * f;
        }
        Color(c)
    }

    /// As `#rrggbb` or `#rrggbbaa` (alpha written only when not opaque).
    #[must_use]
    pub fn to_hex(self) -> String {
        let b = self.0.map(|c| (c * 255.0).round() as u8);
        if b[3] == 255 {
            format!("#{:02x}{:02x}{:02x}", b[0], b[1], b[2])
        } else {
            format!("#{:02x}{:02x}{:02x}{:02x}", b[0], b[1], b[2], b[3])
        }
    }
}
