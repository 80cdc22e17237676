//! Numbers in messages: the shortest text that reads back as the same `f64`.

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

#[cfg(test)]
mod tests {
    use super::Num;

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
}
