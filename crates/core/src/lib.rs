//! splinescope's core layer: the exact curve math in `f64` ([`geom`]) and the solvers
//! ([`solve`]), with the number formatting both use in messages ([`num`]) and the
//! per-curve report of `splinescope inspect` ([`inspect`]).
//!
//! What it may use: glam, nalgebra, rayon, exact rationals, serde and schemars (reports
//! are serialisable). Nothing GPU, window, command-line or image related is in its
//! dependency tree, so a program that only evaluates or modifies curves compiles this
//! crate alone. Every layer above (scene, gpu, viewer, the command line) builds on it.

#![forbid(unsafe_code)]

pub mod analysis;
pub mod geom;
pub mod inspect;
pub mod num;
pub mod solve;
