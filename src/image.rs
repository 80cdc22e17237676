//! RGBA8 images: PNG reading and atomic writing, and per-pixel comparison for image tests.

use std::fs;
use std::path::{Path, PathBuf};

use thiserror::Error;

/// An 8-bit RGBA image, rows top to bottom, no padding.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RgbaImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width · height · 4` bytes.
    pub data: Vec<u8>,
}

/// An image could not be read or written.
#[derive(Debug, Error)]
pub enum ImageError {
    /// A file system error, with the path.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The PNG encoder or decoder failed.
    #[error("{path}: PNG error: {message}")]
    Png {
        /// The file.
        path: PathBuf,
        /// The codec's message.
        message: String,
    },
    /// The PNG is not 8-bit RGBA or RGB.
    #[error("{path}: unsupported PNG format {format} (expected 8-bit RGB or RGBA)")]
    Format {
        /// The file.
        path: PathBuf,
        /// What it is.
        format: String,
    },
}

impl RgbaImage {
    /// A `width × height` image filled with `rgba`.
    #[must_use]
    pub fn filled(width: u32, height: u32, rgba: [u8; 4]) -> RgbaImage {
        RgbaImage {
            width,
            height,
            data: rgba.repeat((width * height) as usize),
        }
    }

    /// The pixel at `(x, y)`.
    ///
    /// # Panics
    /// When `(x, y)` is outside the image (a bug in the caller).
    #[must_use]
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 4] {
        assert!(
            x < self.width && y < self.height,
            "pixel ({x}, {y}) outside"
        );
        let i = ((y * self.width + x) * 4) as usize;
        [
            self.data[i],
            self.data[i + 1],
            self.data[i + 2],
            self.data[i + 3],
        ]
    }

    /// Writes the image as a PNG, atomically: to a temporary file beside `path`, then
    /// renamed over it, so a crash never leaves a half-written file.
    ///
    /// # Errors
    /// I/O or encoder errors, naming the path.
    pub fn write_png(&self, path: &Path) -> Result<(), ImageError> {
        let io = |source| ImageError::Io {
            path: path.to_path_buf(),
            source,
        };
        let png_err = |e: png::EncodingError| ImageError::Png {
            path: path.to_path_buf(),
            message: e.to_string(),
        };
        let mut bytes = Vec::new();
        {
            let mut encoder = png::Encoder::new(&mut bytes, self.width, self.height);
            encoder.set_color(png::ColorType::Rgba);
            encoder.set_depth(png::BitDepth::Eight);
            let mut writer = encoder.write_header().map_err(png_err)?;
            writer.write_image_data(&self.data).map_err(png_err)?;
            writer.finish().map_err(png_err)?;
        }
        crate::files::write_atomic(path, &bytes).map_err(io)
    }

    /// Reads an 8-bit RGB or RGBA PNG.
    ///
    /// # Errors
    /// I/O, decoder or format errors, naming the path.
    pub fn read_png(path: &Path) -> Result<RgbaImage, ImageError> {
        let file = fs::File::open(path).map_err(|source| ImageError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let png_err = |e: png::DecodingError| ImageError::Png {
            path: path.to_path_buf(),
            message: e.to_string(),
        };
        let decoder = png::Decoder::new(std::io::BufReader::new(file));
        let mut reader = decoder.read_info().map_err(png_err)?;
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).map_err(png_err)?;
        buf.truncate(info.buffer_size());
        let data = match (info.color_type, info.bit_depth) {
            (png::ColorType::Rgba, png::BitDepth::Eight) => buf,
            (png::ColorType::Rgb, png::BitDepth::Eight) => buf
                .chunks_exact(3)
                .flat_map(|c| [c[0], c[1], c[2], 255])
                .collect(),
            (color, depth) => {
                return Err(ImageError::Format {
                    path: path.to_path_buf(),
                    format: format!("{color:?} {depth:?}"),
                });
            }
        };
        Ok(RgbaImage {
            width: info.width,
            height: info.height,
            data,
        })
    }
}

/// The outcome of comparing two images pixel by pixel.
#[derive(Debug, Clone)]
pub struct ImageDiff {
    /// The largest absolute difference of any channel of any pixel.
    pub max_channel_diff: u8,
    /// How many pixels differ by more than the tolerance in some channel.
    pub pixels_over: usize,
    /// A visualisation: grey copy of the reference, with offending pixels in red.
    pub diff_image: RgbaImage,
}

/// Compares `actual` against `reference`: a pixel is *over* when any channel differs by
/// more than `channel_tolerance`. Returns `None` when the sizes differ.
#[must_use]
pub fn compare(
    actual: &RgbaImage,
    reference: &RgbaImage,
    channel_tolerance: u8,
) -> Option<ImageDiff> {
    if actual.width != reference.width || actual.height != reference.height {
        return None;
    }
    let mut max_channel_diff = 0;
    let mut pixels_over = 0;
    let mut diff = Vec::with_capacity(actual.data.len());
    for (a, r) in actual
        .data
        .chunks_exact(4)
        .zip(reference.data.chunks_exact(4))
    {
        let d = a
            .iter()
            .zip(r)
            .map(|(x, y)| x.abs_diff(*y))
            .max()
            .unwrap_or(0);
        max_channel_diff = max_channel_diff.max(d);
        if d > channel_tolerance {
            pixels_over += 1;
            diff.extend_from_slice(&[255, 0, 0, 255]);
        } else {
            let grey = ((u16::from(r[0]) + u16::from(r[1]) + u16::from(r[2])) / 3) as u8;
            let faded = 128 + grey / 2;
            diff.extend_from_slice(&[faded, faded, faded, 255]);
        }
    }
    Some(ImageDiff {
        max_channel_diff,
        pixels_over,
        diff_image: RgbaImage {
            width: actual.width,
            height: actual.height,
            data: diff,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_round_trip_and_compare() {
        let dir = std::env::temp_dir().join(format!("splinescope-img-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        let mut img = RgbaImage::filled(5, 3, [10, 20, 30, 255]);
        img.data[4 * 7] = 200;
        let path = dir.join("a.png");
        img.write_png(&path).unwrap();
        let back = RgbaImage::read_png(&path).unwrap();
        assert_eq!(back, img);
        let base = RgbaImage::filled(5, 3, [10, 20, 30, 255]);
        let d = compare(&back, &base, 2).unwrap();
        assert_eq!((d.max_channel_diff, d.pixels_over), (190, 1));
        assert_eq!(d.diff_image.pixel(2, 1), [255, 0, 0, 255]);
        assert!(compare(&back, &RgbaImage::filled(4, 3, [0; 4]), 0).is_none());
        fs::remove_dir_all(&dir).unwrap();
    }
}
