//! Why the viewer's window stopped.

use splinescope_gpu::GpuError;
use thiserror::Error;

/// Why the viewer stopped with an error.
#[derive(Debug, Error)]
pub enum AppError {
    /// The windowing system failed.
    #[error("window system: {0}")]
    Window(String),
    /// GPU setup or work failed.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// The window surface could not be used.
    #[error("window surface: {0}")]
    Surface(String),
}
