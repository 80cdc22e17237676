//! Adaptive Gauss–Kronrod quadrature (the 10-point Gauss rule inside the 21-point Kronrod
//! rule): on each interval the difference of the two rules bounds the error of the
//! coarser one, and so — far more than enough — of the Kronrod value kept; an interval is
//! halved until that difference is within its share of the tolerance. Used for arc
//! length and for the area of rational segments.

/// The Kronrod nodes on `[−1, 1]` (the positive half; the last is 0).
const XGK: [f64; 11] = [
    0.995_657_163_025_808_1,
    0.973_906_528_517_171_7,
    0.930_157_491_355_708_2,
    0.865_063_366_688_984_5,
    0.780_817_726_586_416_9,
    0.679_409_568_299_024_4,
    0.562_757_134_668_604_7,
    0.433_395_394_129_247_2,
    0.294_392_862_701_460_2,
    0.148_874_338_981_631_2,
    0.0,
];

/// The Kronrod weights of [`XGK`].
const WGK: [f64; 11] = [
    0.011_694_638_867_371_874,
    0.032_558_162_307_964_73,
    0.054_755_896_574_351_996,
    0.075_039_674_810_919_95,
    0.093_125_454_583_697_6,
    0.109_387_158_802_297_64,
    0.123_491_976_262_065_85,
    0.134_709_217_311_473_33,
    0.142_775_938_577_060_08,
    0.147_739_104_901_338_5,
    0.149_445_554_002_916_9,
];

/// The 10-point Gauss weights of the odd-indexed nodes `XGK[1], XGK[3], …, XGK[9]`.
const WG: [f64; 5] = [
    0.066_671_344_308_688_14,
    0.149_451_349_150_580_6,
    0.219_086_362_515_982_04,
    0.269_266_719_309_996_36,
    0.295_524_224_714_752_87,
];

/// A quadrature's value and the bound on its error it kept.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Quadrature {
    /// `∫ f`.
    pub value: f64,
    /// The sum over the accepted intervals of `|K₂₁ − G₁₀|`, a bound on the error of the
    /// Gauss values and so of the Kronrod values returned (for integrands smooth on each
    /// interval).
    pub error: f64,
    /// How many times `f` was evaluated.
    pub evaluations: usize,
}

/// One interval: the Kronrod value and `|K − G|`.
fn rule(f: &impl Fn(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let fc = f(c);
    let mut k = WGK[10] * fc;
    let mut g = 0.0;
    for j in 0..10 {
        let dx = h * XGK[j];
        let pair = f(c - dx) + f(c + dx);
        k += WGK[j] * pair;
        if j % 2 == 1 {
            g += WG[j / 2] * pair;
        }
    }
    (k * h, ((k - g) * h).abs())
}

/// The deepest halving: intervals `2⁻⁶⁰` of the whole are accepted as they are.
const MAX_DEPTH: u32 = 60;

/// `∫_a^b f`, adaptively, to within `tolerance` (absolute) — or, where rounding makes
/// that impossible, to within the rounding of the value (`16 ε |∫|f||`), which the
/// returned error then says.
#[must_use]
pub fn integrate(f: impl Fn(f64) -> f64, a: f64, b: f64, tolerance: f64) -> Quadrature {
    let mut out = Quadrature::default();
    if b <= a {
        return out;
    }
    let width = b - a;
    // Intervals to do: (a, b, depth).
    let mut stack: Vec<(f64, f64, u32)> = vec![(a, b, 0)];
    while let Some((lo, hi, depth)) = stack.pop() {
        let (k, e) = rule(&f, lo, hi);
        out.evaluations += 21;
        let share = tolerance * (hi - lo) / width;
        let floor = 16.0 * f64::EPSILON * k.abs();
        let mid = 0.5 * (lo + hi);
        if e <= share.max(floor) || depth >= MAX_DEPTH || mid <= lo || mid >= hi {
            out.value += k;
            out.error += e;
        } else {
            stack.push((mid, hi, depth + 1));
            stack.push((lo, mid, depth + 1));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closed_forms() {
        let q = integrate(f64::sin, 0.0, std::f64::consts::PI, 1e-14);
        assert!((q.value - 2.0).abs() <= 1e-14 && q.error <= 1e-14, "{q:?}");
        // A kink (|t − 0.3|) is found by halving.
        let q = integrate(|t| (t - 0.3).abs(), 0.0, 1.0, 1e-12);
        assert!((q.value - 0.29).abs() <= 1e-12, "{q:?}");
        // √t: an endpoint singularity of the derivative.
        let q = integrate(f64::sqrt, 0.0, 1.0, 1e-10);
        assert!((q.value - 2.0 / 3.0).abs() <= 1e-10, "{q:?}");
    }
}
