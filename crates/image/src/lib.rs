#![doc = include_str!("../README.md")]
#![forbid(unsafe_code)]

pub mod compare;
pub mod report;

use splinescope_io::{files, limits};

use std::fs;
use std::io::Read;
use std::path::{Path, PathBuf};

use thiserror::Error;

/// The 8 bytes every PNG file starts with.
const PNG_SIGNATURE: [u8; 8] = [137, 80, 78, 71, 13, 10, 26, 10];

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
    /// The PNG encoder failed.
    #[error("{path}: PNG error: {message}")]
    Png {
        /// The file.
        path: PathBuf,
        /// The codec's message.
        message: String,
    },
    /// The file is not a PNG, or not a whole and valid one.
    #[error("{path}: not a valid PNG image: {reason}")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// What is wrong (the decoder's words).
        reason: String,
    },
    /// The image is larger than [`limits::IMAGE_PIXELS`] allows; found from its
    /// header, before its pixels are decoded or any memory is set aside for them.
    #[error("{path}: a {width}×{height} image: {limit}")]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// The width its header declares.
        width: u32,
        /// The height its header declares.
        height: u32,
        /// The limit breached.
        limit: limits::LimitError,
    },
    /// The limit's environment variable does not hold a whole number.
    #[error("{0}")]
    BadLimit(limits::LimitError),
    /// The PNG's pixel format cannot be turned into 8-bit RGBA.
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
        let bytes = self.png_bytes(path)?;
        files::write_atomic(path, &bytes).map_err(|source| ImageError::Io {
            path: path.to_path_buf(),
            source,
        })
    }

    /// The image encoded as a PNG file's bytes (`path` only names it in errors).
    ///
    /// # Errors
    /// Encoder errors, naming the path.
    pub fn png_bytes(&self, path: &Path) -> Result<Vec<u8>, ImageError> {
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
        Ok(bytes)
    }

    /// Reads a PNG file of any colour type and bit depth as 8-bit RGBA: palette images
    /// are looked up, grey is spread to red, green and blue, a `tRNS` chunk becomes alpha,
    /// and 16-bit samples keep their high byte.
    ///
    /// The header's dimensions are checked against [`limits::IMAGE_PIXELS`] before
    /// anything is allocated for the pixels, so a few hundred bytes that declare a huge
    /// image are refused rather than decoded.
    ///
    /// # Errors
    /// I/O errors, [`ImageError::Invalid`] (not a PNG, truncated, a bad checksum),
    /// [`ImageError::TooLarge`], each naming the path.
    pub fn read_png(path: &Path) -> Result<RgbaImage, ImageError> {
        let file = fs::File::open(path).map_err(|source| ImageError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        RgbaImage::decode_png(std::io::BufReader::new(file), path)
    }

    /// [`RgbaImage::read_png`] from any reader (`path` only names it in errors).
    ///
    /// # Errors
    /// As [`RgbaImage::read_png`].
    pub fn decode_png(input: impl std::io::Read, path: &Path) -> Result<RgbaImage, ImageError> {
        let invalid = |e: png::DecodingError| match e {
            png::DecodingError::IoError(source)
                if source.kind() != std::io::ErrorKind::UnexpectedEof =>
            {
                ImageError::Io {
                    path: path.to_path_buf(),
                    source,
                }
            }
            png::DecodingError::IoError(_) => ImageError::Invalid {
                path: path.to_path_buf(),
                reason: "the file ends before the image does (truncated)".into(),
            },
            png::DecodingError::LimitsExceeded => ImageError::Invalid {
                path: path.to_path_buf(),
                reason: format!(
                    "it needs more memory to decode than {} allows",
                    limits::IMAGE_PIXELS.var
                ),
            },
            other => ImageError::Invalid {
                path: path.to_path_buf(),
                reason: plain_decoder_message(&other.to_string()),
            },
        };
        let limit = limits::IMAGE_PIXELS.value().map_err(ImageError::BadLimit)?;
        let too_large = |width: u32, height: u32| {
            limits::IMAGE_PIXELS
                .check(u64::from(width) * u64::from(height))
                .map_err(|limit| ImageError::TooLarge {
                    path: path.to_path_buf(),
                    width,
                    height,
                    limit,
                })
        };
        // The size is read from the header's first bytes before the decoder sees them: it
        // sets aside row buffers from the header alone.
        let mut input = input;
        let mut head = Vec::with_capacity(24);
        (&mut input)
            .take(24)
            .read_to_end(&mut head)
            .map_err(|source| ImageError::Io {
                path: path.to_path_buf(),
                source,
            })?;
        if head.len() == 24 && head[..8] == PNG_SIGNATURE && &head[12..16] == b"IHDR" {
            let word =
                |i: usize| u32::from_be_bytes([head[i], head[i + 1], head[i + 2], head[i + 3]]);
            too_large(word(16), word(20))?;
        }
        // The decoder's own buffers (ancillary chunks, rows) are held to the same figure.
        let bytes = usize::try_from(limit.saturating_mul(4)).unwrap_or(usize::MAX);
        let mut decoder = png::Decoder::new_with_limits(
            std::io::Cursor::new(head).chain(input),
            png::Limits { bytes },
        );
        decoder.set_transformations(png::Transformations::normalize_to_color8());
        let mut reader = decoder.read_info().map_err(invalid)?;
        let (width, height) = (reader.info().width, reader.info().height);
        too_large(width, height)?;
        let (color, depth) = reader.output_color_type();
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).map_err(invalid)?;
        buf.truncate(info.buffer_size());
        let data = match (color, depth) {
            (png::ColorType::Rgba, png::BitDepth::Eight) => buf,
            (png::ColorType::Rgb, png::BitDepth::Eight) => buf
                .chunks_exact(3)
                .flat_map(|c| [c[0], c[1], c[2], 255])
                .collect(),
            (png::ColorType::GrayscaleAlpha, png::BitDepth::Eight) => buf
                .chunks_exact(2)
                .flat_map(|c| [c[0], c[0], c[0], c[1]])
                .collect(),
            (png::ColorType::Grayscale, png::BitDepth::Eight) => {
                buf.iter().flat_map(|&g| [g, g, g, 255]).collect()
            }
            (color, depth) => {
                return Err(ImageError::Format {
                    path: path.to_path_buf(),
                    format: format!("{color:?} {depth:?}"),
                });
            }
        };
        Ok(RgbaImage {
            width,
            height,
            data,
        })
    }
}

/// The decoder's message, with its checksum report (which prints a Rust structure for the
/// chunk) put plainly: "a CRC checksum does not match in the IDAT chunk: the file is
/// damaged".
fn plain_decoder_message(message: &str) -> String {
    if message.starts_with("CRC error") {
        let chunk = message
            .split_once("type: ")
            .map(|(_, rest)| {
                rest.chars()
                    .take_while(char::is_ascii_alphabetic)
                    .collect::<String>()
            })
            .filter(|c| !c.is_empty())
            .map_or_else(String::new, |c| format!(" in the {c} chunk"));
        format!("a CRC checksum does not match{chunk}: the file is damaged")
    } else {
        message.trim_end_matches('.').to_owned()
    }
}
