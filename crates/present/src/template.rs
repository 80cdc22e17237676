//! Shapes the families' templates ([`crate::Present::templates`]) are built from: points
//! centred on a point, about a size wide, in the plane through it parallel to `z = 0`.

use glam::DVec3;

/// The point at `(x, y)` of a unit frame centred on `center` and scaled by `size`.
#[must_use]
pub fn at(center: DVec3, size: f64, x: f64, y: f64) -> DVec3 {
    center + DVec3::new(x * size, y * size, 0.0)
}

/// Four points of an arch: a cubic's control polygon.
#[must_use]
pub fn arch(center: DVec3, size: f64) -> Vec<DVec3> {
    [(-0.5, -0.2), (-0.2, 0.3), (0.2, 0.3), (0.5, -0.2)]
        .iter()
        .map(|&(x, y)| at(center, size, x, y))
        .collect()
}

/// `n ≥ 2` points alternating below and above the centre line, evenly spaced in `x`.
#[must_use]
pub fn zigzag(center: DVec3, size: f64, n: usize) -> Vec<DVec3> {
    (0..n)
        .map(|i| {
            let x = i as f64 / (n - 1).max(1) as f64 - 0.5;
            at(center, size, x, if i % 2 == 0 { -0.2 } else { 0.2 })
        })
        .collect()
}

/// The clamped knot vector of `n ≥ k` points and order `k` with evenly spaced interior
/// knots on `[0, 1]`.
#[must_use]
pub fn clamped_knots(n: usize, k: usize) -> Vec<f64> {
    let inner = n - k;
    let mut knots = vec![0.0; k];
    knots.extend((1..=inner).map(|i| i as f64 / (inner + 1) as f64));
    knots.extend(vec![1.0; k]);
    knots
}
