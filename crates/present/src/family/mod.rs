//! Each family's words, one file per family: its [`crate::Present`] implementation and
//! its `inspect` report types.

pub mod bezier;
pub mod bspline;
pub mod interpolation;
pub mod modified;
pub mod nubmp;
pub mod path;
pub mod rational;
