//! splinescope's scene layer: the JSON scene and solve-request formats with their typed,
//! path-naming errors and form-keeping writer ([`scene`], [`request`]), the documented
//! input limits ([`limits`]), the camera ([`camera`]) and the output-path policy every
//! writer follows ([`files`]).
//!
//! What it may use: [`splinescope_core`] (curves and solvers), serde, serde_json and
//! schemars — no GPU, window or command-line crate. The GPU and viewer layers build on it.

#![forbid(unsafe_code)]

pub mod camera;
pub mod files;
mod jsonread;
pub mod limits;
pub mod request;
pub mod scene;
pub mod text;

// The core's modules under the names the code of this layer uses (`crate::geom`).
use splinescope_core::{geom, solve};
