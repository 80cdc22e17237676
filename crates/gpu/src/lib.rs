#![doc = include_str!("../README.md")]
#![forbid(unsafe_code)]

pub mod adaptive;
pub mod bindings;
pub mod capture;
pub mod chunks;
pub mod context;
pub mod eval;
pub mod layer_twin;
pub mod layout;
pub mod overlays;
pub mod pack;
pub mod pack_error;
pub mod pipelines;
pub mod renderer;
pub mod selftest;
pub mod shaders;
pub mod tessellator;
pub mod twin;

use thiserror::Error;

// The lower layers' modules under the names the code of this layer uses (`splinescope_core::geom`).

/// A buffer holding `contents` (like wgpu's `create_buffer_init`, which panics when the
/// device is lost: here the failure goes to the device's error handler and shows in
/// [`GpuContext::check_health`]).
#[must_use]
pub fn init_buffer(
    device: &wgpu::Device,
    label: &str,
    contents: &[u8],
    usage: wgpu::BufferUsages,
) -> wgpu::Buffer {
    let align = wgpu::COPY_BUFFER_ALIGNMENT;
    let size = (contents.len() as u64).div_ceil(align).max(1) * align;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage,
        mapped_at_creation: true,
    });
    if let Ok(mut view) = buffer.get_mapped_range_mut(..) {
        view.slice(..contents.len()).copy_from_slice(contents);
    }
    buffer.unmap();
    buffer
}

use crate::pack_error::PackError;
pub use context::{AdapterReport, BackendChoice, ContextOptions, GpuContext};
pub use pipelines::Pipelines;

/// Why GPU work failed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GpuError {
    /// No adapter matched.
    #[error(
        "no GPU adapter found (backends {backends}{}; adapters seen: {seen}); {}",
        wanted.as_ref().map(|w| format!(", name containing {w:?}")).unwrap_or_default(),
        context::INSTALL_HINT
    )]
    NoAdapter {
        /// The backends searched.
        backends: String,
        /// The name filter, if any.
        wanted: Option<String>,
        /// Every adapter found before filtering.
        seen: String,
    },
    /// Every adapter that matched was refused: its device did not open, or a kernel
    /// computed wrong samples in the self-test run when a device opens.
    #[error(
        "no usable GPU adapter: {reasons}. Pick another with --gpu-backend or WGPU_ADAPTER_NAME (`splinescope adapters` lists them), or use the CPU path where the command has one"
    )]
    Refused {
        /// Each adapter tried and why it was refused.
        reasons: String,
    },
    /// The adapter refused to give a device.
    #[error("could not open the GPU device: {0}")]
    Device(String),
    /// The device was lost or reported an error no scope caught; its results are not
    /// trusted.
    #[error(
        "the GPU device failed: {0}. Its results were discarded; run the command again (with --gpu-backend or WGPU_ADAPTER_NAME to try another adapter)"
    )]
    DeviceLost(String),
    /// Reading a buffer back failed.
    #[error("reading GPU results back failed: {0}")]
    Readback(String),
    /// The scene does not fit the GPU layout.
    #[error(transparent)]
    Pack(#[from] PackError),
    /// An image size the device cannot render.
    #[error(
        "image size {width}×{height} is not allowed (each side between 1 and {max} on this device)"
    )]
    ImageSize {
        /// Requested width.
        width: u32,
        /// Requested height.
        height: u32,
        /// The device's `max_texture_dimension_2d`.
        max: u32,
    },
}
