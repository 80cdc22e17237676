//! Value parsers for options whose refusals say the allowed range in words (`between 1
//! and 31`, `a finite number greater than 0`), as every other message does, where clap's
//! own say `1..=31`.

/// A parser of whole numbers from `lo` to `hi` inclusive.
pub fn between<T>(
    lo: T,
    hi: T,
) -> impl Fn(&str) -> Result<T, String> + Clone + Send + Sync + 'static
where
    T: std::str::FromStr + PartialOrd + Copy + std::fmt::Display + Send + Sync + 'static,
{
    move |s: &str| {
        let refuse = || format!("{s} is not a whole number between {lo} and {hi}");
        let v: T = s.trim().parse().map_err(|_| refuse())?;
        if v < lo || v > hi {
            return Err(refuse());
        }
        Ok(v)
    }
}

/// A parser of whole numbers of at least `lo`.
pub fn at_least<T>(lo: T) -> impl Fn(&str) -> Result<T, String> + Clone + Send + Sync + 'static
where
    T: std::str::FromStr + PartialOrd + Copy + std::fmt::Display + Send + Sync + 'static,
{
    move |s: &str| {
        let refuse = || format!("{s} is not a whole number of at least {lo}");
        let v: T = s.trim().parse().map_err(|_| refuse())?;
        if v < lo {
            return Err(refuse());
        }
        Ok(v)
    }
}

/// A parser of finite numbers greater than 0 (`positive`) or at least 0, its refusal
/// naming the option as `what`: `tolerance -1: must be a finite number greater than 0`.
pub fn number(
    what: &'static str,
    positive: bool,
) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync + 'static {
    move |s: &str| {
        let v: f64 = s
            .trim()
            .parse()
            .map_err(|_| format!("{s:?} is not a number"))?;
        let ok = v.is_finite() && if positive { v > 0.0 } else { v >= 0.0 };
        if ok {
            Ok(v)
        } else {
            Err(format!(
                "{what} {}: must be a finite number {}",
                splinescope_core::num::Num(v),
                if positive {
                    "greater than 0"
                } else {
                    "at least 0"
                }
            ))
        }
    }
}
