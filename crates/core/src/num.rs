//! Numbers in messages (the shortest text that reads back as the same `f64`), and exact
//! binary scaling: splitting an `f64` into mantissa and exponent and scaling by powers of
//! two without intermediate overflow or underflow.

use std::fmt;

/// Formats an `f64` as the shorter of its plain and its exponent form, both of which read
/// back exactly: `1.5`, `0.1`, `1e308`, `5e-324` (where the plain form of a subnormal
/// has 300 digits).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Num(pub f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let plain = format!("{}", self.0);
        let exp = format!("{:e}", self.0);
        f.write_str(if exp.len() < plain.len() {
            &exp
        } else {
            &plain
        })
    }
}

/// The shortest decimal within `tol` of `x` (the fewest significant digits whose value
/// differs from `x` by at most `tol`), in the shorter of its plain and exponent forms: the
/// text of a computed value that shows what is known of it and no rounding noise —
/// `shortest_within(-22.999999999999996, 1e-11)` is `-23`, `shortest_within(1.52e-15,
/// 1e-12)` is `0`. A `tol` that is not a positive finite number gives every digit
/// ([`Num`]), as does a non-finite `x`.
#[must_use]
pub fn shortest_within(x: f64, tol: f64) -> String {
    if !x.is_finite() || tol.is_nan() || tol <= 0.0 || tol.is_infinite() {
        return Num(x).to_string();
    }
    if x.abs() <= tol {
        return "0".to_owned();
    }
    for digits in 1..=17 {
        let text = format!("{:.*e}", digits - 1, x);
        let Ok(v) = text.parse::<f64>() else {
            continue;
        };
        if (v - x).abs() <= tol {
            return Num(v).to_string();
        }
    }
    Num(x).to_string()
}

/// `x` with at most `decimals` decimals, trailing zeros and a trailing point removed, and
/// `-0` written `0`: the text of panel readouts, knot lists and figure coordinates
/// (`fixed(0.25, 4)` is `0.25`, `fixed(-0.00001, 4)` is `0`, `fixed(100.0, 0)` is `100`).
#[must_use]
pub fn fixed(x: f64, decimals: usize) -> String {
    trim_zeros(format!("{x:.decimals$}"))
}

/// A decimal's text without the zeros after its last significant decimal (nor a point
/// left alone), `-0` as `0`; a text in exponent form or without a point is kept as it is.
#[must_use]
pub fn trim_zeros(text: String) -> String {
    let text = if text.contains('.') && !text.contains(['e', 'E']) {
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        text
    };
    if text == "-0" { "0".into() } else { text }
}

/// `x = f · 2^e` with `f ∈ [1, 2)`, for a finite positive `x` (subnormals included).
#[must_use]
pub fn split_exponent(x: f64) -> (f64, i32) {
    // Subnormals are brought into the normal range first (2⁶⁰ is exact).
    let (x, bias) = if x < f64::MIN_POSITIVE {
        (x * 2f64.powi(60), -60)
    } else {
        (x, 0)
    };
    let bits = x.to_bits();
    let e = ((bits >> 52) & 0x7ff) as i32 - 1023;
    let f = f64::from_bits((bits & !(0x7ff << 52)) | (1023 << 52));
    (f, e + bias)
}

/// `x · 2^e`, in steps that cannot overflow or underflow on the way (only the result can):
/// exact whenever the result is representable.
#[must_use]
pub fn scale_by_power_of_two(mut x: f64, mut e: i32) -> f64 {
    while e != 0 {
        let step = e.clamp(-1000, 1000);
        x *= 2f64.powi(step);
        e -= step;
        if x == 0.0 || x.is_infinite() {
            break;
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::{Num, fixed, scale_by_power_of_two, shortest_within, split_exponent, trim_zeros};

    #[test]
    fn shortest_within_keeps_what_is_known_and_no_noise() {
        assert_eq!(shortest_within(-22.999999999999996, 1e-11), "-23");
        assert_eq!(shortest_within(1.52e-15, 1e-12), "0");
        assert_eq!(
            shortest_within(22.44228559924098, 2.9e-13),
            "22.442285599241"
        );
        assert_eq!(shortest_within(0.7200000000000003, 1e-12), "0.72");
        assert_eq!(shortest_within(1234.5, 0.6), "1234");
        assert_eq!(shortest_within(1.0e-300, 1e-310), "1e-300");
        assert_eq!(shortest_within(0.1, 0.0), "0.1");
        assert_eq!(shortest_within(f64::NAN, 1.0), "NaN");
        // Always within the tolerance, and never longer than every digit.
        let mut x = 0.123_456_789_f64;
        for k in 0..2000 {
            x = (x * 3.7 + 0.31).fract() * 10f64.powi(k % 19 - 9);
            let tol = x.abs() * 10f64.powi(-(k % 16));
            let text = shortest_within(x, tol);
            let v: f64 = text.parse().unwrap();
            assert!((v - x).abs() <= tol, "{x} {tol}: {text}");
            assert!(text.len() <= Num(x).to_string().len(), "{x} {tol}: {text}");
        }
    }

    #[test]
    fn fixed_decimals_trimmed() {
        assert_eq!(fixed(0.25, 4), "0.25");
        assert_eq!(fixed(2.0, 6), "2");
        assert_eq!(fixed(100.0, 0), "100");
        assert_eq!(fixed(-0.000_01, 4), "0");
        assert_eq!(fixed(-1.5, 3), "-1.5");
        assert_eq!(fixed(1.0 / 3.0, 4), "0.3333");
        assert_eq!(trim_zeros("1e300".into()), "1e300");
        assert_eq!(trim_zeros("1500".into()), "1500");
    }

    #[test]
    fn shortest_form_that_reads_back() {
        for (x, want) in [
            (1.5, "1.5"),
            (0.0, "0"),
            (1.0, "1"),
            (-0.25, "-0.25"),
            (1e308, "1e308"),
            (5e-324, "5e-324"),
            (-2.5e-320, "-2.5e-320"),
            (123_456_789.0, "123456789"),
            (f64::NAN, "NaN"),
            (f64::INFINITY, "inf"),
        ] {
            let s = Num(x).to_string();
            assert_eq!(s, want);
            if x.is_finite() {
                assert_eq!(s.parse::<f64>().unwrap().to_bits(), x.to_bits());
            }
        }
    }

    #[test]
    fn the_exponent_split_is_exact() {
        for x in [
            1.0,
            1.5,
            3.0,
            1e-310,
            5e-324,
            f64::MAX,
            f64::MIN_POSITIVE,
            0.1,
        ] {
            let (f, e) = split_exponent(x);
            assert!((1.0..2.0).contains(&f), "{x:e}: {f}");
            assert_eq!(scale_by_power_of_two(f, e).to_bits(), x.to_bits(), "{x:e}");
        }
    }
}
