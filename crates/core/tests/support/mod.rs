//! Test support: exact arithmetic, the exact intersection oracle, and the generators of
//! the hard intersection classes.

pub mod classes;
pub mod exact;
