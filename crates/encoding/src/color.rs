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

    /// The colour's bytes, each channel × 255 rounded: what a scene file writes.
    #[must_use]
    pub fn to_rgba8(self) -> [u8; 4] {
        self.0.map(|c| (c * 255.0).round() as u8)
    }

    /// A colour from its bytes, each ÷ 255: what a scene file reads.
    #[must_use]
    pub const fn from_rgba8(bytes: [u8; 4]) -> Color {
        Color([
            bytes[0] as f32 / 255.0,
            bytes[1] as f32 / 255.0,
            bytes[2] as f32 / 255.0,
            bytes[3] as f32 / 255.0,
        ])
    }

    /// As `#rrggbb` or `#rrggbbaa` (alpha written only when not opaque).
    #[must_use]
    pub fn to_hex(self) -> String {
        let b = self.to_rgba8();
        if b[3] == 255 {
            format!("#{:02x}{:02x}{:02x}", b[0], b[1], b[2])
        } else {
            format!("#{:02x}{:02x}{:02x}{:02x}", b[0], b[1], b[2], b[3])
        }
    }
}
