//! splinescope: a GPU-rendered, real-time viewer and evaluation engine for families of
//! parametric curves.
//!
//! The library is a workspace of layers, one crate each (arrows point down only, and the
//! compiler keeps them):
//!
//! * [`splinescope_core`] — [`geom`], the exact curve math in `f64` (every family and its
//!   lowering to Bézier segments), and [`solve`], the solvers of papers 000 and 001. No
//!   GPU, window, command-line or image crate in its dependency tree.
//! * [`splinescope_io`] — the input [`limits`] and the output-path policy ([`files`]):
//!   std and thiserror only.
//! * [`splinescope_image`] ([`image`]) — RGBA images, PNG reading within the limits and
//!   atomic writing, per-channel and FLIP comparison; no GPU.
//! * [`splinescope_encoding`] — what the GPU layer is handed: each curve's exact segments,
//!   samples and stroke, the draw list, colours and the [`camera`]; no format, no GPU.
//! * [`splinescope_scene`] — the JSON [`scene`] and [`request`] formats with typed,
//!   path-naming errors, and a scene's encoding.
//! * [`splinescope_gpu`] ([`gpu`]) — the only layer that names `wgpu`: device setup, the
//!   WGSL kernels and their CPU twin, the renderer, offscreen capture; handed an
//!   encoding, never a scene file.
//! * [`splinescope_render`] ([`render`]) — a scene drawn offscreen: one
//!   [`render::RenderRequest`] (size, tolerance, camera, shape overlays, text) taken by
//!   [`render::render`], which every caller uses.
//! * [`splinescope_viewer`] ([`app`]) — the interactive winit + egui viewer.
//! * this package — the command line, and what only it prints or writes: [`outputs`] of
//!   `eval`/`check`, [`regress`]ion runs and the JSON [`schemas`]. It re-exports the layers under their module
//!   names, so `splinescope::geom`, `splinescope::gpu` and the rest name one thing each.
//!
//! The road through the program: scene → curve families → lowering to Bézier segments →
//! packing (f32) → compute de Casteljau (`shaders/tessellate.wgsl`) → render pass →
//! window or PNG.

#![forbid(unsafe_code)]

pub use splinescope_core::{analysis, geom, num, ops, solve};
pub use splinescope_gpu as gpu;
pub use splinescope_import as import;
pub use splinescope_io::{files, limits};
pub use splinescope_present as present;
pub use splinescope_present::inspect;
pub use splinescope_render as render;
pub use splinescope_scene::{camera, format as scene, request};
pub use splinescope_viewer as app;

pub mod image {
    //! Images and their comparison: [`splinescope_image`] (the image type, PNG reading
    //! and writing) and [`splinescope_image::compare`] (per-channel and FLIP).
    pub use splinescope_image::compare::*;
    pub use splinescope_image::{ImageError, RgbaImage};
}
#[deprecated(note = "use splinescope::render (RenderRequest and render)")]
pub mod offscreen;
pub mod outputs;
pub mod regress;
pub mod schemas;
