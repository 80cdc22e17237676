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

/// Deprecated: the input limits are `splinescope_io::limits`.
#[deprecated(note = "use splinescope_io::limits")]
pub mod limits {
    pub use splinescope_io::limits::*;
}

/// Deprecated: the file helpers are `splinescope_io::files`.
#[deprecated(note = "use splinescope_io::files")]
pub mod files {
    pub use splinescope_io::files::*;
}

/// Deprecated: the camera is the encoding's, `splinescope_encoding::camera`.
#[deprecated(note = "use splinescope_encoding::camera")]
pub mod camera {
    pub use splinescope_encoding::camera::*;
}
