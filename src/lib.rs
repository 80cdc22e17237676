//! splinescope: a GPU-rendered, real-time viewer and evaluation engine for families of
//! parametric curves.
//!
//! The library is a workspace of layers, one crate each (arrows point down only, and the
//! compiler keeps them); each item has one path, in the crate that defines it:
//!
//! * [`splinescope_core`] — `geom`, the exact curve math in `f64` (every family and its
//!   lowering to Bézier segments), `poly` (Bernstein polynomials and their roots),
//!   `analysis`, `ops` and `solve` (the solvers of papers 000 and 001). No GPU, window,
//!   command-line or image crate in its dependency tree.
//! * [`splinescope_io`] — the input limits and the output-path policy: std and thiserror
//!   only.
//! * [`splinescope_image`] — RGBA images, PNG reading within the limits and atomic
//!   writing, per-channel and FLIP comparison; no GPU.
//! * [`splinescope_present`] — what a curve says to a person (summaries, panel controls,
//!   `inspect`).
//! * [`splinescope_encoding`] — what the GPU layer is handed: each curve's exact segments,
//!   samples and stroke, the draw list, colours and the camera; no format, no GPU.
//! * [`splinescope_scene`] — the JSON scene format (`format`) and solve requests
//!   (`request`) with typed, path-naming errors, and a scene's encoding.
//! * [`splinescope_import`] — SVG, fonts, DXF and STEP read as scenes; DXF written.
//! * [`splinescope_gpu`] — the only layer that names `wgpu`: device setup, the WGSL
//!   kernels and their CPU twins, the renderer, offscreen capture; handed an encoding,
//!   never a scene file.
//! * [`splinescope_figure`] — SVG and PDF figures with exact curves.
//! * [`splinescope_render`] — a scene drawn offscreen: one `RenderRequest` taken by
//!   `render`, which every caller uses.
//! * [`splinescope_viewer`] — the interactive winit + egui viewer.
//! * this package — the command line, and what only it prints or writes: [`outputs`] of
//!   `eval`/`check`, [`regress`]ion runs and the JSON [`schemas`].
//!
//! The modules that once re-exported the layers here (`splinescope::geom`,
//! `splinescope::scene`, `splinescope::gpu`, …) are deprecated: name the crate that
//! defines the item (`CHANGELOG.md`).
//!
//! The road through the program: scene → curve families → lowering to Bézier segments →
//! packing (f32) → compute de Casteljau (`shaders/tessellate.wgsl`) → render pass →
//! window or PNG.

#![forbid(unsafe_code)]

pub mod outputs;
pub mod regress;
pub mod schemas;

#[deprecated(
    note = "use splinescope_render (RenderRequest and render) or splinescope_gpu::capture"
)]
pub mod offscreen;

/// Deprecated re-exports of the layers, kept for one release: each names the crate and
/// module that defines its items.
macro_rules! deprecated_alias {
    ($($name:ident => $path:path, $note:literal;)*) => {$(
        #[doc = concat!("Deprecated: ", $note, ".")]
        #[deprecated(note = $note)]
        pub mod $name {
            pub use $path::*;
        }
    )*};
}

deprecated_alias! {
    analysis => splinescope_core::analysis, "use splinescope_core::analysis";
    geom => splinescope_core::geom, "use splinescope_core::geom";
    num => splinescope_core::num, "use splinescope_core::num";
    ops => splinescope_core::ops, "use splinescope_core::ops";
    solve => splinescope_core::solve, "use splinescope_core::solve";
    gpu => splinescope_gpu, "use splinescope_gpu";
    import => splinescope_import, "use splinescope_import";
    files => splinescope_io::files, "use splinescope_io::files";
    limits => splinescope_io::limits, "use splinescope_io::limits";
    present => splinescope_present, "use splinescope_present";
    inspect => splinescope_present::inspect, "use splinescope_present::inspect";
    camera => splinescope_encoding::camera, "use splinescope_encoding::camera";
    scene => splinescope_scene::format, "use splinescope_scene::format";
    request => splinescope_scene::request, "use splinescope_scene::request";
    app => splinescope_viewer, "use splinescope_viewer";
}

/// Deprecated: use `splinescope_image` (the image type, PNG reading and writing) and
/// `splinescope_image::compare` (per-channel and FLIP comparison).
#[deprecated(note = "use splinescope_image and splinescope_image::compare")]
pub mod image {
    pub use splinescope_image::compare::*;
    pub use splinescope_image::{ImageError, RgbaImage};
}
