//! The one-dimensional root and minimum finders the solvers share: bisection of a sign
//! change, bisection of a predicate's boundary, and golden-section search.

/// A zero of `f` in `[a, b]`, where `f(a)` has the sign `fa` and `f(b)` the other (or is
/// zero): bisection until the interval cannot shrink in `f64`.
#[must_use]
pub fn bisect_sign_change(f: impl Fn(f64) -> f64, a: f64, b: f64, fa: f64) -> f64 {
    if fa == 0.0 {
        return a;
    }
    let (mut a, mut b) = (a, b);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if m == a || m == b {
            break;
        }
        if f(m).signum() == fa.signum() {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// The boundary of the set where `inside` holds, between a point `inside_at` in it and a
/// point `outside_at` out of it: `iterations` bisections; the returned point is inside.
#[must_use]
pub fn bisect_boundary(
    inside: impl Fn(f64) -> bool,
    inside_at: f64,
    outside_at: f64,
    iterations: u32,
) -> f64 {
    let (mut i, mut o) = (inside_at, outside_at);
    for _ in 0..iterations {
        let m = 0.5 * (i + o);
        if inside(m) {
            i = m;
        } else {
            o = m;
        }
    }
    i
}

/// A local minimum of `f` in `[x0, x1]` by golden-section search (`iterations` steps, each
/// shrinking the bracket by 0.618).
#[must_use]
pub fn golden_minimum(f: impl Fn(f64) -> f64, x0: f64, x1: f64, iterations: u32) -> f64 {
    let phi = 0.5 * (5f64.sqrt() - 1.0);
    let (mut x0, mut x1) = (x0, x1);
    for _ in 0..iterations {
        let c = x1 - phi * (x1 - x0);
        let d = x0 + phi * (x1 - x0);
        if f(c) < f(d) {
            x1 = d;
        } else {
            x0 = c;
        }
    }
    0.5 * (x0 + x1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_finder_against_a_closed_form() {
        let root = bisect_sign_change(|x| x * x - 2.0, 0.0, 2.0, -2.0);
        assert!((root - 2f64.sqrt()).abs() <= 2.0 * f64::EPSILON, "{root}");
        assert_eq!(bisect_sign_change(|x| x - 1.0, 1.0, 3.0, 0.0), 1.0);
        let edge = bisect_boundary(|x| x < std::f64::consts::PI, 0.0, 4.0, 60);
        assert!(edge < std::f64::consts::PI && std::f64::consts::PI - edge < 1e-15);
        let min = golden_minimum(|x| (x - 0.3).powi(2), -1.0, 2.0, 100);
        assert!((min - 0.3).abs() < 1e-7, "{min}");
    }
}
