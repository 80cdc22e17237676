//! Comparing images for image tests, `regress`/`diff` and the Python module:
//! per-channel and NVIDIA FLIP, on the [`RgbaImage`]s the renderer makes. No GPU is
//! needed.

use crate::RgbaImage;

use thiserror::Error;

/// When two images count as the same: a pixel *differs* when any channel is off by more
/// than `channel`; the images match when at most `max_differing_fraction` of the pixels
/// differ and, if `max_flip_mean` is set, NVIDIA FLIP's mean error is at most that.
///
/// Written `channel=24,pixels=0.1%,flip=0.05` (any subset, in any order; `pixels` takes a
/// fraction or a percentage).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// Largest per-channel difference (0–255) that does not make a pixel differ.
    pub channel: u8,
    /// Largest fraction of differing pixels (0–1).
    pub max_differing_fraction: f64,
    /// Largest FLIP mean (0–1), or `None` to report FLIP without gating on it.
    pub max_flip_mean: Option<f64>,
}

impl Default for Tolerance {
    /// `channel=24,pixels=0.1%`: rasterisers differ slightly in edge coverage, which this
    /// absorbs, while a missing, moved or recoloured curve changes far more pixels.
    fn default() -> Tolerance {
        Tolerance {
            channel: 24,
            max_differing_fraction: 0.001,
            max_flip_mean: None,
        }
    }
}

impl std::fmt::Display for Tolerance {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "channel={},pixels={}%",
            self.channel,
            self.max_differing_fraction * 100.0
        )?;
        if let Some(flip) = self.max_flip_mean {
            write!(f, ",flip={flip}")?;
        }
        Ok(())
    }
}

/// What the tolerance text gets wrong, naming it.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ToleranceError {
    /// Nothing was given.
    #[error("{text:?} is empty; {EXPECTED_TOLERANCE}")]
    Empty {
        /// The text.
        text: String,
    },
    /// Two commas with nothing between, or one at an end.
    #[error("{text:?} has an empty item; {EXPECTED_TOLERANCE}")]
    EmptyItem {
        /// The text.
        text: String,
    },
    /// A key given twice.
    #[error("{text:?} gives {key} twice")]
    Twice {
        /// The text.
        text: String,
        /// The key.
        key: String,
    },
    /// An item without `=`.
    #[error("{item:?}: expected key=value (channel=24, pixels=0.1%, flip=0.05)")]
    NotKeyValue {
        /// The item.
        item: String,
    },
    /// A key that is not `channel`, `pixels` or `flip`.
    #[error("unknown tolerance key {key:?} (expected channel, pixels or flip)")]
    UnknownKey {
        /// The key.
        key: String,
    },
    /// A value that is not what its key takes (a finite number in range; for `channel`
    /// a whole number 0..=255).
    #[error("{key}={value}: {expected}")]
    BadValue {
        /// The key.
        key: &'static str,
        /// The value as given.
        value: String,
        /// What it must be.
        expected: String,
    },
}

/// What a tolerance looks like, for messages.
const EXPECTED_TOLERANCE: &str =
    "expected key=value items such as channel=24,pixels=0.1%,flip=0.05";

impl std::str::FromStr for Tolerance {
    type Err = ToleranceError;
    /// Strict: an empty text, an empty item (`channel=4,`), a key given twice, or a value
    /// that is not a number in range is an error naming it; keys left out keep their
    /// defaults.
    fn from_str(text: &str) -> Result<Tolerance, ToleranceError> {
        if text.trim().is_empty() {
            return Err(ToleranceError::Empty { text: text.into() });
        }
        let mut tol = Tolerance::default();
        let mut seen: Vec<&str> = Vec::new();
        for item in text.split(',').map(str::trim) {
            if item.is_empty() {
                return Err(ToleranceError::EmptyItem { text: text.into() });
            }
            let Some((key, value)) = item.split_once('=') else {
                return Err(ToleranceError::NotKeyValue { item: item.into() });
            };
            let key_name = key.trim();
            if seen.contains(&key_name) {
                return Err(ToleranceError::Twice {
                    text: text.into(),
                    key: key_name.into(),
                });
            }
            seen.push(key_name);
            let bad = |key: &'static str, expected: String| ToleranceError::BadValue {
                key,
                value: value.into(),
                expected,
            };
            let number = |key: &'static str, v: &str| -> Result<f64, ToleranceError> {
                v.trim()
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| bad(key, format!("{v:?} is not a finite number")))
            };
            match key_name {
                "channel" => {
                    tol.channel = value.trim().parse::<u8>().map_err(|_| {
                        bad(
                            "channel",
                            "expected a whole number between 0 and 255".into(),
                        )
                    })?;
                }
                "pixels" => {
                    let fraction = match value.trim().strip_suffix('%') {
                        Some(pct) => number("pixels", pct)? / 100.0,
                        None => number("pixels", value)?,
                    };
                    if !(0.0..=1.0).contains(&fraction) {
                        return Err(bad("pixels", "not between 0 and 100 %".into()));
                    }
                    tol.max_differing_fraction = fraction;
                }
                "flip" => {
                    let flip = number("flip", value)?;
                    if !(0.0..=1.0).contains(&flip) {
                        return Err(bad("flip", "not between 0 and 1".into()));
                    }
                    tol.max_flip_mean = Some(flip);
                }
                other => return Err(ToleranceError::UnknownKey { key: other.into() }),
            }
        }
        Ok(tol)
    }
}

/// The figures of one comparison.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Comparison {
    /// Width of both images.
    pub width: u32,
    /// Height of both images.
    pub height: u32,
    /// The largest absolute difference of any channel of any pixel.
    pub max_channel_diff: u8,
    /// How many pixels differ by more than the tolerance in some channel.
    pub differing_pixels: usize,
    /// `differing_pixels` over all pixels.
    pub differing_fraction: f64,
    /// NVIDIA FLIP's mean perceptual error (0 = identical, 1 = as different as can be);
    /// alpha is ignored (renders are opaque).
    pub flip_mean: f64,
    /// FLIP's largest per-pixel error.
    pub flip_max: f64,
    /// Whether the images match within the tolerance.
    pub matches: bool,
}

/// The pictures of one comparison.
#[derive(Debug, Clone)]
pub struct ComparisonImages {
    /// A grey copy of the reference with differing pixels in red.
    pub diff: RgbaImage,
    /// FLIP's error map as a heat map (magma: black = same, yellow = most different).
    pub flip: RgbaImage,
}

/// Two images of different sizes cannot be compared.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error(
    "image size {actual_width}×{actual_height} differs from the reference's {reference_width}×{reference_height}"
)]
pub struct SizeMismatch {
    /// The actual image's width.
    pub actual_width: u32,
    /// The actual image's height.
    pub actual_height: u32,
    /// The reference's width.
    pub reference_width: u32,
    /// The reference's height.
    pub reference_height: u32,
}

fn rgb(image: &RgbaImage) -> Vec<u8> {
    image
        .data
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect()
}

/// Compares `actual` against `reference` with both metrics: per-channel (a pixel differs
/// when any channel is off by more than `tolerance.channel`) and NVIDIA FLIP.
///
/// # Errors
/// [`SizeMismatch`] when the sizes differ.
pub fn compare_images(
    actual: &RgbaImage,
    reference: &RgbaImage,
    tolerance: &Tolerance,
) -> Result<(Comparison, ComparisonImages), SizeMismatch> {
    if actual.width != reference.width || actual.height != reference.height {
        return Err(SizeMismatch {
            actual_width: actual.width,
            actual_height: actual.height,
            reference_width: reference.width,
            reference_height: reference.height,
        });
    }
    let (width, height) = (actual.width, actual.height);
    let mut max_channel_diff = 0;
    let mut differing_pixels = 0;
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
        if d > tolerance.channel {
            differing_pixels += 1;
            diff.extend_from_slice(&[255, 0, 0, 255]);
        } else {
            let grey = ((u16::from(r[0]) + u16::from(r[1]) + u16::from(r[2])) / 3) as u8;
            let faded = 128 + grey / 2;
            diff.extend_from_slice(&[faded, faded, faded, 255]);
        }
    }
    let pixels = f64::from(width) * f64::from(height);
    let differing_fraction = if pixels > 0.0 {
        differing_pixels as f64 / pixels
    } else {
        0.0
    };
    let (flip_mean, flip_max, flip) = if width == 0 || height == 0 {
        (0.0, 0.0, RgbaImage::filled(width, height, [0, 0, 0, 255]))
    } else {
        let test = nv_flip::FlipImageRgb8::with_data(width, height, &rgb(actual));
        let refr = nv_flip::FlipImageRgb8::with_data(width, height, &rgb(reference));
        let error = nv_flip::flip(refr, test, nv_flip::DEFAULT_PIXELS_PER_DEGREE);
        let pool = nv_flip::FlipPool::from_image(&error);
        let heat = error.apply_color_lut(&nv_flip::magma_lut()).to_vec();
        let data = heat
            .chunks_exact(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect();
        (
            f64::from(pool.mean()),
            // The pool starts from the smallest positive f32: identical images report 0.
            if pool.mean() > 0.0 {
                f64::from(pool.max_value())
            } else {
                0.0
            },
            RgbaImage {
                width,
                height,
                data,
            },
        )
    };
    let matches = differing_fraction <= tolerance.max_differing_fraction
        && tolerance.max_flip_mean.is_none_or(|m| flip_mean <= m);
    Ok((
        Comparison {
            width,
            height,
            max_channel_diff,
            differing_pixels,
            differing_fraction,
            flip_mean,
            flip_max,
            matches,
        },
        ComparisonImages {
            diff: RgbaImage {
                width,
                height,
                data: diff,
            },
            flip,
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

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
        let tol = Tolerance {
            channel: 2,
            max_differing_fraction: 0.0,
            max_flip_mean: None,
        };
        let (c, pictures) = compare_images(&back, &base, &tol).unwrap();
        assert_eq!((c.max_channel_diff, c.differing_pixels), (190, 1));
        assert!((c.differing_fraction - 1.0 / 15.0).abs() < 1e-15);
        assert!(!c.matches);
        assert_eq!(pictures.diff.pixel(2, 1), [255, 0, 0, 255]);
        assert!(c.flip_mean > 0.0 && c.flip_max > c.flip_mean);
        let (same, _) = compare_images(&base, &base, &tol).unwrap();
        assert_eq!((same.differing_pixels, same.flip_mean), (0, 0.0));
        assert!(same.matches);
        let err = compare_images(&back, &RgbaImage::filled(4, 3, [0; 4]), &tol).unwrap_err();
        assert_eq!(
            err.to_string(),
            "image size 5×3 differs from the reference's 4×3"
        );
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn flip_gates_only_when_asked() {
        // Half the image changed from black to white: FLIP's mean is about one half.
        let a = RgbaImage::filled(16, 16, [0, 0, 0, 255]);
        let mut b = a.clone();
        for px in b.data.chunks_exact_mut(4).take(128) {
            px.copy_from_slice(&[255, 255, 255, 255]);
        }
        let lax = Tolerance {
            channel: 255,
            max_differing_fraction: 1.0,
            max_flip_mean: None,
        };
        let (c, _) = compare_images(&b, &a, &lax).unwrap();
        assert!(c.matches, "{c:?}");
        assert!(c.flip_mean > 0.3 && c.flip_mean < 0.7, "{c:?}");
        let strict = Tolerance {
            max_flip_mean: Some(0.1),
            ..lax
        };
        assert!(!compare_images(&b, &a, &strict).unwrap().0.matches);
    }

    #[test]
    fn tolerances_parse_and_name_bad_values() {
        let t: Tolerance = "channel=10, pixels=0.5%, flip=0.02".parse().unwrap();
        assert_eq!(
            t,
            Tolerance {
                channel: 10,
                max_differing_fraction: 0.005,
                max_flip_mean: Some(0.02)
            }
        );
        assert_eq!(
            "pixels=0.25"
                .parse::<Tolerance>()
                .unwrap()
                .max_differing_fraction,
            0.25
        );
        assert_eq!(
            "channel=24".parse::<Tolerance>().unwrap(),
            Tolerance::default()
        );
        for (bad, says) in [
            ("", "is empty"),
            ("  ", "is empty"),
            ("channel=4,", "empty item"),
            (",", "empty item"),
            ("channel=4,,pixels=1%", "empty item"),
            ("channel=4,channel=5", "channel twice"),
            ("channel=", "channel="),
            ("pixels=%", "pixels=%"),
            ("pixels=1%%", "pixels=1%%"),
            ("channel=300", "channel=300"),
            ("pixels=150%", "pixels=150%"),
            ("flip=nan", "flip=nan"),
            ("flip=2", "flip=2"),
            ("colour=3", "\"colour\""),
            ("channel", "key=value"),
        ] {
            let e = bad.parse::<Tolerance>().unwrap_err().to_string();
            assert!(e.contains(says), "{bad}: {e}");
        }
        let round: Tolerance = Tolerance::default().to_string().parse().unwrap();
        assert_eq!(round, Tolerance::default());
    }
}
