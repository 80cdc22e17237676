//! The documented limits on input sizes, checked before anything is allocated for the
//! input, so that no file or argument makes the program run for hours or exhaust memory.
//! Each can be raised with an environment variable; a breach is an error that names the
//! value, the limit and the variable.

use thiserror::Error;

/// One limit: its name in messages, its environment variable and its default.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limit {
    /// What is counted, e.g. "points per curve".
    pub what: &'static str,
    /// The environment variable that raises (or lowers) it.
    pub var: &'static str,
    /// The value when the variable is unset.
    pub default: u64,
}

/// Scene files larger than this are refused before reading (a JSON document takes about
/// 40 times its size in memory while it is decoded).
pub const SCENE_BYTES: Limit = Limit {
    what: "bytes per scene or request file",
    var: "SPLINESCOPE_MAX_FILE_BYTES",
    default: 16 << 20,
};

/// Curves per scene.
pub const CURVES: Limit = Limit {
    what: "curves per scene",
    var: "SPLINESCOPE_MAX_CURVES",
    default: 1_000_000,
};

/// Control points per curve (and points per annotation).
pub const POINTS: Limit = Limit {
    what: "points per curve",
    var: "SPLINESCOPE_MAX_POINTS",
    default: 100_000,
};

/// Degree of a Bézier curve (`points − 1`): de Casteljau is quadratic in the degree, so
/// one evaluation at this degree is about 10⁶ operations.
pub const DEGREE: Limit = Limit {
    what: "for the degree of a Bézier curve",
    var: "SPLINESCOPE_MAX_DEGREE",
    default: 1_000,
};

/// Order of a B-spline or NUBMP curve: extraction costs `order³` and the NUBMP structure
/// `order⁴` per point.
pub const ORDER: Limit = Limit {
    what: "for the order of a B-spline or NUBMP curve",
    var: "SPLINESCOPE_MAX_ORDER",
    default: 64,
};

/// Samples one command evaluates or tessellates in all (`eval`, `render`, `view`, `bench`):
/// 2²⁷ samples are 2 GiB on the GPU (16 bytes each) or 3 GiB of `f64` points.
pub const SAMPLES: Limit = Limit {
    what: "samples per command",
    var: "SPLINESCOPE_MAX_SAMPLES",
    default: 1 << 27,
};

/// Pixels of an image read from a file (`diff`, `regress`'s references) or compared with
/// one (`regress`'s renders): the header's `width × height` is checked before the pixels
/// are decoded. The default, 8192 × 8192, is 256 MiB of RGBA; a comparison holds several
/// such images and NVIDIA FLIP's floating-point planes besides.
pub const IMAGE_PIXELS: Limit = Limit {
    what: "pixels per image",
    var: "SPLINESCOPE_MAX_IMAGE_PIXELS",
    default: 1 << 26,
};

/// Path pieces one figure (`export` to SVG or PDF) writes in all: the adaptive fit halves
/// a piece until it keeps the tolerance, and this bounds its time, memory and file size
/// (a piece is about 60 bytes of SVG).
pub const FIGURE_PIECES: Limit = Limit {
    what: "path pieces per figure",
    var: "SPLINESCOPE_MAX_FIGURE_PIECES",
    default: 1 << 18,
};

/// Elements an imported file is read as: SVG elements counted after every `<use>` is
/// expanded, DXF entities after every block is inserted, STEP instances. A file of a few
/// kilobytes can reference its own groups into billions of elements.
pub const IMPORT_ELEMENTS: Limit = Limit {
    what: "elements per imported file (SVG after <use> expansion, DXF after block insertion, STEP instances)",
    var: "SPLINESCOPE_MAX_IMPORT_ELEMENTS",
    default: 1_000_000,
};

/// Nesting of an imported file's groups and `<use>` references, DXF block inserts, STEP
/// lists and chains of references: the readers recurse through them.
pub const IMPORT_DEPTH: Limit = Limit {
    what: "for the nesting of groups, inserts, lists and references in an imported file",
    var: "SPLINESCOPE_MAX_IMPORT_DEPTH",
    default: 256,
};

/// Every limit, for the documentation and `--help`.
pub const ALL: [Limit; 10] = [
    SCENE_BYTES,
    CURVES,
    POINTS,
    DEGREE,
    ORDER,
    SAMPLES,
    IMAGE_PIXELS,
    FIGURE_PIECES,
    IMPORT_ELEMENTS,
    IMPORT_DEPTH,
];

/// A value over its limit, or a limit's variable that does not hold a whole number.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum LimitError {
    /// The value is over the limit in force.
    #[error(
        "{found} is over the limit of {limit} {what} (raise it with the environment variable {var}=N)"
    )]
    Exceeded {
        /// What is counted.
        what: &'static str,
        /// The value found.
        found: u64,
        /// The limit in force.
        limit: u64,
        /// The variable that raises it.
        var: &'static str,
    },
    /// The environment variable is set but is not a whole number: refused rather than
    /// silently replaced by the default.
    #[error(
        "the environment variable {var}={value:?} is not a whole number (it sets the limit of {})",
        what.strip_prefix("for ").unwrap_or(what)
    )]
    BadVariable {
        /// What the variable limits.
        what: &'static str,
        /// The variable.
        var: &'static str,
        /// What it holds.
        value: String,
    },
}

impl Limit {
    /// The limit in force: the environment variable when set (a whole number, `_` allowed
    /// between digits), else the default.
    ///
    /// # Errors
    /// [`LimitError::BadVariable`] when the variable is set to anything else.
    pub fn value(&self) -> Result<u64, LimitError> {
        match std::env::var(self.var) {
            Err(_) => Ok(self.default),
            Ok(text) => {
                text.trim()
                    .replace('_', "")
                    .parse::<u64>()
                    .map_err(|_| LimitError::BadVariable {
                        what: self.what,
                        var: self.var,
                        value: text,
                    })
            }
        }
    }

    /// Checks `found` against the limit.
    ///
    /// # Errors
    /// [`LimitError::Exceeded`] naming the value, the limit and the variable, or
    /// [`LimitError::BadVariable`].
    pub fn check(&self, found: u64) -> Result<(), LimitError> {
        let limit = self.value()?;
        if found > limit {
            Err(LimitError::Exceeded {
                what: self.what,
                found,
                limit,
                var: self.var,
            })
        } else {
            Ok(())
        }
    }
}

/// A text file that could not be read within the limits.
#[derive(Debug, Error)]
pub enum ReadError {
    /// The file system's error.
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// The file is larger than [`SCENE_BYTES`] (or its variable is malformed).
    #[error("{0}")]
    Limit(#[from] LimitError),
    /// The bytes are not UTF-8 text.
    #[error("not UTF-8 text: {0}")]
    NotText(#[from] std::string::FromUtf8Error),
}

/// Reads a file's bytes after checking its size against [`SCENE_BYTES`] (a FIFO or
/// device, which has no size, is read to one byte past the limit).
///
/// # Errors
/// [`ReadError`]: the I/O error or the limit.
pub fn read_bounded_bytes(path: &std::path::Path) -> Result<Vec<u8>, ReadError> {
    let meta = std::fs::metadata(path)?;
    if meta.is_file() {
        SCENE_BYTES.check(meta.len())?;
    }
    use std::io::Read;
    let limit = SCENE_BYTES.value()?;
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(limit.saturating_add(1)).read_to_end(&mut bytes))?;
    SCENE_BYTES.check(bytes.len() as u64)?;
    Ok(bytes)
}

/// Reads a text file after checking its size against [`SCENE_BYTES`].
///
/// # Errors
/// [`ReadError`]: the I/O error, the limit, or bytes that are not text.
pub fn read_bounded(path: &std::path::Path) -> Result<String, ReadError> {
    Ok(String::from_utf8(read_bounded_bytes(path)?)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_breach_names_the_value_the_limit_and_the_variable() {
        assert!(ORDER.check(ORDER.default).is_ok());
        let e = ORDER.check(ORDER.default + 1).unwrap_err();
        assert!(matches!(
            e,
            LimitError::Exceeded {
                found: 65,
                limit: 64,
                ..
            }
        ));
        assert_eq!(
            e.to_string(),
            "65 is over the limit of 64 for the order of a B-spline or NUBMP curve (raise it with the environment variable SPLINESCOPE_MAX_ORDER=N)"
        );
        let vars: std::collections::HashSet<_> = ALL.iter().map(|l| l.var).collect();
        assert_eq!(vars.len(), ALL.len(), "one variable per limit");
    }

    #[test]
    fn a_bad_variable_is_named_with_the_limit_it_sets_in_words() {
        for (limit, words) in [
            (&ORDER, "the order of a B-spline or NUBMP curve"),
            (&CURVES, "curves per scene"),
        ] {
            let e = LimitError::BadVariable {
                what: limit.what,
                var: limit.var,
                value: "1e9".into(),
            };
            assert_eq!(
                e.to_string(),
                format!(
                    "the environment variable {}=\"1e9\" is not a whole number (it sets the limit of {words})",
                    limit.var
                )
            );
        }
    }
}
