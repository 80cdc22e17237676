#![doc = include_str!("../README.md")]

//!
//! Rooms: [`interaction`] is the window-free model (camera, editing, switches) that tests
//! drive; `surface` owns the window's surface; `egui_layer` runs and paints the panel
//! (`ui` draws it); `scene_view` keeps the scene on the GPU; `window` turns winit events
//! into [`interaction::Input`] and composes a frame. The window's rooms are the `window`
//! feature (on by default); without it the crate is the window-free model alone — no
//! winit, no egui — which the Python module's notebook widget drives.
//!
//! This crate is splinescope's viewer layer: it may use every layer below
//! ([`splinescope_core`], [`splinescope_scene`], [`splinescope_gpu`]), winit and egui; no
//! command-line crate.

#![forbid(unsafe_code)]

// The window-free model: what the window, the tests and the notebook widget drive.
pub mod edit;
pub mod file_dialog;
pub mod interaction;
pub mod shape;

// The window (the `window` feature, on by default; without it the crate has no winit and
// no egui, as the Python module uses it).
#[cfg(feature = "window")]
mod app_error;
#[cfg(feature = "window")]
pub use app_error::AppError;
#[cfg(feature = "window")]
mod digest;
#[cfg(feature = "window")]
mod egui_layer;
#[cfg(feature = "window")]
mod readback;
#[cfg(feature = "window")]
mod scene_view;
#[cfg(feature = "window")]
mod stress;
#[cfg(feature = "window")]
mod surface;
#[cfg(feature = "window")]
mod timing;
#[cfg(feature = "window")]
mod ui;
#[cfg(all(test, feature = "window"))]
mod ui_tests;
#[cfg(feature = "window")]
mod window;
#[cfg(feature = "window")]
pub use window::*;
