//! Value parsers for whole-number options whose refusals say the allowed range in words
//! (`between 1 and 31`), as every other message does, where clap's own say `1..=31`.

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
