//! Numbers and parameters as labels write them.

use glam::DVec3;

/// A number for a label: at most four decimals, trailing zeros dropped (`0.3`, `1`,
/// `0.1255`).
#[must_use]
pub fn short_number(x: f64) -> String {
    splinescope_core::num::fixed(x, 4)
}

/// `t* = …, v = (…)` for the bump families (no z for a planar `v`).
#[must_use]
pub fn bump_text(t_star: f64, v: DVec3) -> String {
    let n = short_number;
    if v.z == 0.0 {
        format!("t* = {}, v = ({}, {})", n(t_star), n(v.x), n(v.y))
    } else {
        format!(
            "t* = {}, v = ({}, {}, {})",
            n(t_star),
            n(v.x),
            n(v.y),
            n(v.z)
        )
    }
}
