//! The compute pipelines, in their own value: the device opens in [`super::context`],
//! the pipelines are built on it once and handed to whoever dispatches (the renderer, GPU
//! evaluation, the benchmarks), as the wgpu examples hand device and queue around instead
//! of hiding them in a context.

use super::adaptive::AdaptiveTessellator;
use super::tessellator::Tessellator;

/// Both tessellators' pipelines. Cloning is cheap (wgpu handles are shared), so the
/// renderer keeps its own handle to the adaptive ones.
#[derive(Debug, Clone)]
pub struct Pipelines {
    /// The fixed-count kernels (one sample count per curve): GPU evaluation, the
    /// benchmarks and the self-test run when a device opens.
    pub tessellator: Tessellator,
    /// The adaptive passes the renderer runs every frame.
    pub adaptive: AdaptiveTessellator,
}

impl Pipelines {
    /// Builds every compute pipeline on `device`.
    #[must_use]
    pub fn new(device: &wgpu::Device) -> Pipelines {
        Pipelines::with_tessellator(device, Tessellator::new(device))
    }

    /// The pipelines around an already built fixed-count tessellator (the one a self-test
    /// checked), adding the adaptive passes.
    #[must_use]
    pub fn with_tessellator(device: &wgpu::Device, tessellator: Tessellator) -> Pipelines {
        Pipelines {
            tessellator,
            adaptive: AdaptiveTessellator::new(device),
        }
    }
}
