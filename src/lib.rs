//! splinescope: a GPU-rendered, real-time viewer and evaluation engine for families of
//! parametric curves.
//!
//! The library is layered (arrows point down only):
//!
//! * [`geom`] — the exact curve math in `f64`: Bézier curves of any degree and the
//!   lowering of every family to Bézier segments. No GPU types.
//! * [`scene`] — the JSON scene model (curves, styles, view) with typed, path-naming
//!   errors, the built-in gallery and stress-scene generators.
//! * [`gpu`] — the only layer that names `wgpu`: device setup, the `#[repr(C)]` layout
//!   shared with the WGSL shaders, the compute tessellator (and its CPU twin), the
//!   renderer and offscreen capture.
//! * [`solve`] — the CPU solvers: closest points, least-squares shape modification of
//!   Bézier curves (paper 000), constrained modification of NUBMP curves (paper 001), and
//!   parallel batches. No GPU types.
//! * [`app`] — the interactive `winit` viewer.
//!
//! The road through the program: scene → curve families → lowering to Bézier segments →
//! packing (f32) → compute de Casteljau (`shaders/tessellate.wgsl`) → render pass →
//! window or PNG.

#![forbid(unsafe_code)]

pub mod app;
pub mod camera;
pub mod files;
pub mod geom;
pub mod gpu;
pub mod image;
pub mod inspect;
mod jsonread;
pub mod limits;
pub mod num;
pub mod outputs;
pub mod regress;
pub mod request;
pub mod scene;
pub mod schemas;
pub mod solve;
