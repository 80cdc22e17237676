#![doc = include_str!("../README.md")]
#![forbid(unsafe_code)]

pub mod format;
mod jsonread;

/// JSON read as the scene and request readers read it: a syntax error with its line and
/// column, a key given twice in one object refused at its path.
///
/// # Errors
/// [`format::SceneError`] naming the syntax error or the duplicated key.
pub fn parse_json(text: &str) -> Result<serde_json::Value, format::SceneError> {
    jsonread::parse_document(text)
}
pub mod request;
pub mod text;

// The I/O policy's modules, re-exported under the names this layer's users know
// (`splinescope_io::limits`).
pub use splinescope_io::{files, limits};

// The camera is the encoding's (what the GPU layer draws through).
pub use splinescope_encoding::camera;

// The core's modules under the names the code of this layer uses (`splinescope_core::geom`).
