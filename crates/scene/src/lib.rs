//! splinescope's scene layer: the JSON scene and solve-request formats with their typed,
//! path-naming errors and form-keeping writer ([`format`](mod@format), [`request`]) and the camera
//! ([`camera`]); the input limits and output-path policy it checks and follows are
//! `splinescope-io`'s ([`limits`], [`files`], re-exported).
//!
//! What it may use: [`splinescope_core`] (curves and solvers), `splinescope-io`,
//! `splinescope-encoding` (what it encodes a scene into), serde, serde_json and
//! schemars — no GPU, window or command-line crate. The GPU and viewer layers build on it.
//!
//! ```
//! use splinescope_scene::format::{from_json_str, to_json_string};
//!
//! let text = r#"{"version": 1, "curves": [
//!     {"type": "bezier", "name": "arch", "points": [[0, 0], [1, 2], [3, 2], [4, 0]]}
//! ]}"#;
//! let scene = from_json_str(text).unwrap();
//! assert_eq!(scene.curves[0].name.as_deref(), Some("arch"));
//! // Read back what it writes: the same scene.
//! assert_eq!(from_json_str(&to_json_string(&scene)).unwrap().curves.len(), 1);
//! // Bad input is an error naming the offending value's path.
//! let e = from_json_str(r#"{"version": 1, "curves": [{"type": "bezier", "points": [[0, 0], [1, "x"]]}]}"#)
//!     .unwrap_err();
//! assert!(e.to_string().contains("curves[0].points[1]"), "{e}");
//! ```

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
// (`splinescope_scene::limits`).
pub use splinescope_io::{files, limits};

// The camera is the encoding's (what the GPU layer draws through).
pub use splinescope_encoding::camera;

// The core's modules under the names the code of this layer uses (`crate::geom`).
use splinescope_core::{geom, solve};
