//! splinescope's core layer: the exact curve math in `f64` ([`geom`]) and the solvers
//! ([`solve`]), with the number formatting both use in messages ([`num`]) and the
//! per-curve report of `splinescope inspect`.
//!
//! What it may use: glam, nalgebra, rayon, exact rationals, and — behind the `serde`
//! feature, on by default — serde and schemars (reports and details serialise; with
//! `default-features = false` no serde is in the tree). Nothing GPU, window, command-line or image related is in its
//! dependency tree, so a program that only evaluates or modifies curves compiles this
//! crate alone. Every layer above (scene, gpu, viewer, the command line) builds on it.
//!
//! ```
//! use glam::DVec3;
//! use splinescope_core::analysis::CurveAnalysis;
//! use splinescope_core::geom::{Bezier, Lower, Nurbs, ParamCurve};
//!
//! // A cubic Bézier curve, evaluated by de Casteljau (paper 002).
//! let cubic = Bezier::new(vec![
//!     DVec3::new(0.0, 0.0, 0.0),
//!     DVec3::new(1.0, 2.0, 0.0),
//!     DVec3::new(3.0, 2.0, 0.0),
//!     DVec3::new(4.0, 0.0, 0.0),
//! ]);
//! assert_eq!(cubic.eval(0.5), DVec3::new(2.0, 1.5, 0.0));
//!
//! // A NURBS circle of radius 2 lowers to exact rational Bézier segments, and its
//! // length is 4π within the accuracy asked for.
//! let circle = Nurbs::circle(DVec3::ZERO, 2.0).unwrap();
//! assert!(circle.lower().iter().all(|s| s.is_rational()));
//! let analysis = CurveAnalysis::new(&circle);
//! let (a, b) = analysis.domain();
//! let length = analysis.length(a, b, 1e-12).unwrap();
//! assert!((length.value - 4.0 * std::f64::consts::PI).abs() <= 1e-12);
//! ```

#![forbid(unsafe_code)]

pub mod analysis;
pub mod geom;
pub mod num;
pub mod ops;
pub mod rng;
pub mod solve;
