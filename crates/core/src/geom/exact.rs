//! Exact rational arithmetic for derived data that is rational (degree-elevation
//! coefficients of decimal knots), and the scalar trait that lets one algorithm run in
//! `f64` and in exact rationals.

use std::ops::{Add, Div, Mul, Sub};

use num_bigint::BigInt;
use num_traits::{One, ToPrimitive, Zero};

/// An exact rational number.
pub type Rational = num_rational::BigRational;

/// A field the generic algorithms run over: `f64` for speed, [`Rational`] for exact
/// results.
pub trait Scalar:
    Clone
    + PartialEq
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
{
    /// 0.
    fn zero() -> Self;
    /// 1.
    fn one() -> Self;
    /// `n` as a scalar.
    fn from_usize(n: usize) -> Self;
    /// The nearest `f64`.
    fn to_f64(&self) -> f64;
}

impl Scalar for f64 {
    fn zero() -> Self {
        0.0
    }
    fn one() -> Self {
        1.0
    }
    fn from_usize(n: usize) -> Self {
        n as f64
    }
    fn to_f64(&self) -> f64 {
        *self
    }
}

impl Scalar for Rational {
    fn zero() -> Self {
        Zero::zero()
    }
    fn one() -> Self {
        One::one()
    }
    fn from_usize(n: usize) -> Self {
        Rational::from_integer(BigInt::from(n))
    }
    fn to_f64(&self) -> f64 {
        ToPrimitive::to_f64(self).unwrap_or(f64::NAN)
    }
}

/// The exact value of a finite `f64` (every one is a dyadic rational).
#[must_use]
pub fn rational_from_f64(x: f64) -> Option<Rational> {
    Rational::from_float(x)
}

/// Parses a JSON-style decimal (`-12`, `0.89`, `1.5e-3`, `2E+2`) exactly.
#[must_use]
pub fn parse_decimal(text: &str) -> Option<Rational> {
    let text = text.trim();
    let (mantissa, exponent) = match text.find(['e', 'E']) {
        Some(i) => (&text[..i], text[i + 1..].parse::<i64>().ok()?),
        None => (text, 0),
    };
    let (negative, digits) = match mantissa.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, mantissa.strip_prefix('+').unwrap_or(mantissa)),
    };
    let (int_part, frac_part) = match digits.find('.') {
        Some(i) => (&digits[..i], &digits[i + 1..]),
        None => (digits, ""),
    };
    if int_part.is_empty() && frac_part.is_empty() {
        return None;
    }
    if !int_part
        .chars()
        .chain(frac_part.chars())
        .all(|c| c.is_ascii_digit())
    {
        return None;
    }
    let all: BigInt = format!("{int_part}{frac_part}0").parse::<BigInt>().ok()? / BigInt::from(10);
    let scale = exponent - frac_part.len() as i64;
    if scale.abs() > 10_000 {
        return None;
    }
    let ten = BigInt::from(10);
    let mut value = Rational::from_integer(all);
    if scale >= 0 {
        value *= Rational::from_integer(num_traits::pow(ten, scale as usize));
    } else {
        value /= Rational::from_integer(num_traits::pow(ten, (-scale) as usize));
    }
    Some(if negative { -value } else { value })
}

/// A rational as text: `3`, `-7/20`.
#[must_use]
pub fn format_rational(r: &Rational) -> String {
    if r.denom().is_one() {
        r.numer().to_string()
    } else {
        format!("{}/{}", r.numer(), r.denom())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> Rational {
        Rational::new(BigInt::from(n), BigInt::from(d))
    }

    #[test]
    fn decimals_parse_exactly() {
        assert_eq!(parse_decimal("0.89"), Some(q(89, 100)));
        assert_eq!(parse_decimal("-0.3"), Some(q(-3, 10)));
        assert_eq!(parse_decimal("1"), Some(q(1, 1)));
        assert_eq!(parse_decimal("1.5e-3"), Some(q(3, 2000)));
        assert_eq!(parse_decimal("2E+2"), Some(q(200, 1)));
        assert_eq!(parse_decimal(".5"), Some(q(1, 2)));
        assert_eq!(parse_decimal("abc"), None);
        assert_eq!(parse_decimal("-"), None);
        assert_eq!(format_rational(&q(-7, 20)), "-7/20");
        assert_eq!(format_rational(&q(6, 2)), "3");
    }
}
