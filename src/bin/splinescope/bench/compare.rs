//! `bench --compare PREVIOUS.json`: the change of every rate per row against an earlier
//! `bench --json` output, and which fell by more than the threshold.

use std::io::Write;
use std::path::Path;

use anyhow::{Context, Result, bail};
use serde_json::Value;

use super::BenchReport;
use crate::say;

/// The rows of an earlier `bench --json` output (one object, or an array of them).
///
/// # Errors
/// An unreadable file, or JSON that is not `bench --json` output (naming what is wrong).
pub fn read(path: &Path) -> Result<Vec<Value>> {
    let text = splinescope_io::limits::read_bounded(path)
        .with_context(|| format!("reading --compare {}", path.display()))?;
    // As every file the program reads: a key given twice is refused, not last-wins.
    let value: Value = splinescope_scene::parse_json(&text)
        .with_context(|| format!("--compare {}", path.display()))?;
    let rows = match value {
        Value::Array(rows) => rows,
        one @ Value::Object(_) => vec![one],
        _ => bail!(
            "--compare {}: expected the object or array `bench --json` prints",
            path.display()
        ),
    };
    for (i, row) in rows.iter().enumerate() {
        for key in ["curves", "degree", "samples_per_curve"] {
            if !row.get(key).is_some_and(Value::is_u64) {
                bail!(
                    "--compare {}: row {i} has no whole number `{key}` (not `bench --json` output)",
                    path.display()
                );
            }
        }
        if let Some(family) = row.get("family")
            && !family.is_string()
        {
            bail!(
                "--compare {}: row {i}: `family` is {family}, not a family's name",
                path.display()
            );
        }
        // Every rate is a number (or null where it was not measured): a rate that is
        // text would silently compare with nothing.
        for (name, value) in row.as_object().into_iter().flatten() {
            let numeric =
                value.is_null() || value.as_f64().is_some_and(|v| v.is_finite() && v >= 0.0);
            if is_rate(name) && !numeric {
                bail!(
                    "--compare {}: row {i}: `{name}` is {value}, not a rate (a number of at least 0, or null)",
                    path.display()
                );
            }
        }
    }
    Ok(rows)
}

/// Whether a report field is a rate that `--compare` compares.
fn is_rate(name: &str) -> bool {
    name.ends_with("_samples_per_s") || name.starts_with("frames_per_s")
}

/// The row's identity: family (Bézier when an older report has none), curves, degree and
/// samples per curve.
fn key(row: &Value) -> (String, u64, u64, u64) {
    let n = |k: &str| row.get(k).and_then(Value::as_u64).unwrap_or(0);
    (
        row.get("family")
            .and_then(Value::as_str)
            .unwrap_or("bezier")
            .to_owned(),
        n("curves"),
        n("degree"),
        n("samples_per_curve"),
    )
}

/// Prints the change of every rate present in both runs, row by row; returns the rates
/// that fell by more than `threshold` (a fraction).
///
/// # Errors
/// Writing to standard output.
pub fn print(previous: &[Value], now: &[BenchReport], threshold: f64) -> Result<Vec<String>> {
    let mut regressions = Vec::new();
    for report in now {
        let current = serde_json::to_value(report)?;
        let id = key(&current);
        let Some(before) = previous.iter().find(|p| key(p) == id) else {
            say!(
                "compare: {} {} curves, degree {}, {} samples: not in the earlier run",
                id.0,
                id.1,
                id.2,
                id.3
            );
            continue;
        };
        say!(
            "compare: {} {} curves, degree {}, {} samples:",
            id.0,
            id.1,
            id.2,
            id.3
        );
        let Value::Object(fields) = &current else {
            continue;
        };
        for (name, value) in fields {
            let rate_like = is_rate(name);
            let (Some(new), Some(old)) = (value.as_f64(), before.get(name).and_then(Value::as_f64))
            else {
                continue;
            };
            if !rate_like || old <= 0.0 {
                continue;
            }
            let change = new / old - 1.0;
            let flag = if change < -threshold {
                regressions.push(format!(
                    "{} {} curves degree {} samples {}: {name} {:+.1} %",
                    id.0,
                    id.1,
                    id.2,
                    id.3,
                    100.0 * change
                ));
                "  << regression"
            } else {
                ""
            };
            say!(
                "  {name:<42} {old:>14.4e} → {new:>14.4e}  {:+7.1} %{flag}",
                100.0 * change
            );
        }
    }
    Ok(regressions)
}
