#![doc = include_str!("../README.md")]
#![forbid(unsafe_code)]

pub mod analysis;
pub mod geom;
pub mod num;
pub mod ops;
pub mod poly;
pub mod rng;
pub mod solve;
