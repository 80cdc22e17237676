//! Adaptive Gauss–Kronrod quadrature (the 10-point Gauss rule inside the 21-point Kronrod
//! rule). On each interval, with `d = |K₂₁ − G₁₀|` and `r = ∫ |f − mean|` (by the Kronrod
//! weights), the error of the Kronrod value kept is estimated as QUADPACK does,
//! `r · min(1, (200 d / r)^{3/2})` (the Kronrod rule's error falls like the Gauss rule's
//! to the power 3/2 for smooth integrands), where the integrand is resolved — its values
//! on the interval within a factor 4 of each other — and as `d` itself elsewhere; never
//! below `50 ε ∫|f|`. An interval is halved until its estimate is within its share of the
//! tolerance. Used for arc length and for the area of rational segments.

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
    /// The sum over the accepted intervals of their error estimates (QUADPACK's, above).
    pub error: f64,
    /// How many times `f` was evaluated.
    pub evaluations: usize,
}

/// One interval: the Kronrod value and the estimate of its error.
fn rule(f: &impl Fn(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let fc = f(c);
    let mut k = WGK[10] * fc;
    let mut g = 0.0;
    let mut k_abs = WGK[10] * fc.abs();
    let mut values = [0.0_f64; 20];
    for j in 0..10 {
        let dx = h * XGK[j];
        let (f1, f2) = (f(c - dx), f(c + dx));
        values[2 * j] = f1;
        values[2 * j + 1] = f2;
        let pair = f1 + f2;
        k += WGK[j] * pair;
        k_abs += WGK[j] * (f1.abs() + f2.abs());
        if j % 2 == 1 {
            g += WG[j / 2] * pair;
        }
    }
    let mean = 0.5 * k;
    let mut asc = WGK[10] * (fc - mean).abs();
    for j in 0..10 {
        asc += WGK[j] * ((values[2 * j] - mean).abs() + (values[2 * j + 1] - mean).abs());
    }
    // Where the integrand stays within a factor RANGE over the interval (resolved: no
    // dip toward zero, no steep rise), the Kronrod error follows the Gauss error to the
    // power 3/2 (QUADPACK's estimate); elsewhere — near a cusp, where `|C′|` dips toward
    // zero and has a singularity close to the real axis — `|K − G|` itself, the Gauss
    // rule's error, bounds the Kronrod rule's.
    let (lo, hi) = values
        .iter()
        .chain(std::iter::once(&fc))
        .fold((f64::INFINITY, 0.0_f64), |(lo, hi), v| {
            (lo.min(v.abs()), hi.max(v.abs()))
        });
    let resolved = lo * RANGE >= hi;
    let (k, diff, asc, k_abs) = (k * h, ((k - g) * h).abs(), asc * h.abs(), k_abs * h.abs());
    let mut err = diff;
    if resolved && asc != 0.0 && diff != 0.0 {
        err = asc * (SCALE * diff / asc).powf(1.5).min(1.0);
    }
    (k, err.max(50.0 * f64::EPSILON * k_abs))
}

/// QUADPACK's factor in the estimate.
const SCALE: f64 = 200.0;
/// How far the integrand may vary over an interval to count as resolved.
const RANGE: f64 = 2.0;

/// The deepest halving: intervals `2⁻⁶⁰` of the whole are accepted as they are.
const MAX_DEPTH: u32 = 60;

/// The most intervals one quadrature evaluates (21 values each); past it, the intervals
/// left are accepted with their estimates, which the returned error then holds.
pub const MAX_INTERVALS: usize = 1 << 15;

/// `∫_a^b f`, adaptively, to within `tolerance` (absolute) — or, where rounding makes
/// that impossible, to within the rounding of the value (`50 ε ∫|f|`), which the returned
/// error then says. A value of `f` that is not finite stops the halving there (the error
/// returned is then infinite), and so does the budget of [`MAX_INTERVALS`]: the work is
/// bounded whatever `f` does.
#[must_use]
pub fn integrate(f: impl Fn(f64) -> f64, a: f64, b: f64, tolerance: f64) -> Quadrature {
    let mut out = Quadrature::default();
    if b <= a {
        return out;
    }
    let width = b - a;
    // Intervals to do: (a, b, depth).
    let mut stack: Vec<(f64, f64, u32)> = vec![(a, b, 0)];
    let mut intervals = 0_usize;
    while let Some((lo, hi, depth)) = stack.pop() {
        let (k, e) = rule(&f, lo, hi);
        out.evaluations += 21;
        intervals += 1;
        let (k, e) = if k.is_finite() && e.is_finite() {
            (k, e)
        } else {
            (k, f64::INFINITY)
        };
        let share = tolerance * (hi - lo) / width;
        let mid = 0.5 * (lo + hi);
        if e <= share
            || e == f64::INFINITY
            || intervals + stack.len() >= MAX_INTERVALS
            || depth >= MAX_DEPTH
            || mid <= lo
            || mid >= hi
            || e <= 64.0 * f64::EPSILON * k.abs()
        {
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
        let q = integrate(f64::sin, 0.0, std::f64::consts::PI, 1e-13);
        assert!((q.value - 2.0).abs() <= 1e-14 && q.error <= 1e-13, "{q:?}");
        // Below the rounding of the value, the error says so.
        let q = integrate(f64::sin, 0.0, std::f64::consts::PI, 1e-20);
        assert!(
            (q.value - 2.0).abs() <= 1e-14 && q.error >= 50.0 * f64::EPSILON,
            "{q:?}"
        );
        // A kink (|t − 0.3|) is found by halving.
        let q = integrate(|t| (t - 0.3).abs(), 0.0, 1.0, 1e-12);
        assert!((q.value - 0.29).abs() <= 1e-12, "{q:?}");
        // An integrand that is not finite somewhere, or never resolved, ends the work
        // and says so in the error.
        let q = integrate(|t| if t > 0.5 { f64::NAN } else { 1.0 }, 0.0, 1.0, 1e-9);
        assert!(q.error == f64::INFINITY, "{q:?}");
        let q = integrate(|t| (1e6 * t).sin().signum(), 0.0, 1.0, 1e-300);
        assert!(
            q.evaluations <= 21 * (MAX_INTERVALS + 64) && q.error > 1e-300,
            "{q:?}"
        );
        // √t: an endpoint singularity of the derivative.
        let q = integrate(f64::sqrt, 0.0, 1.0, 1e-10);
        assert!((q.value - 2.0 / 3.0).abs() <= 1e-10, "{q:?}");
    }
}
