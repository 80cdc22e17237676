//! `splinescope schema`: print or write the JSON Schemas of the formats.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

use crate::say;

/// The arguments of `splinescope schema`.
#[derive(Debug, clap::Args)]
pub struct SchemaArgs {
    /// Which schema (without one, the list of them).
    pub name: Option<String>,
    /// Write every schema as DIR/<name>.schema.json.
    #[arg(long, value_name = "DIR")]
    pub write: Option<PathBuf>,
}

/// Runs `splinescope schema`.
///
/// # Errors
/// An unknown schema, or files that cannot be written (then none is).
pub fn run(a: &SchemaArgs) -> Result<()> {
    schema(a.name.as_deref(), a.write.as_deref())
}

/// Prints one schema, lists them (no name), or writes every schema into `dir`.
fn schema(name: Option<&str>, write: Option<&Path>) -> Result<()> {
    let all = splinescope::schemas::all();
    if let Some(dir) = write {
        // All or none: every schema is staged beside its target before any is moved into
        // place; a directory made for them is removed again when that fails.
        let made = !dir.exists();
        std::fs::create_dir_all(dir).with_context(|| format!("{}", dir.display()))?;
        let texts: Vec<(PathBuf, String)> = all
            .iter()
            .map(|(stem, schema)| {
                (
                    dir.join(format!("{stem}.schema.json")),
                    splinescope::schemas::to_text(schema),
                )
            })
            .collect();
        let files: Vec<(&Path, &[u8])> = texts
            .iter()
            .map(|(p, t)| (p.as_path(), t.as_bytes()))
            .collect();
        if let Err(e) = splinescope_io::files::write_all_atomic(&files) {
            if made {
                let _ = std::fs::remove_dir(dir);
            }
            return Err(anyhow::Error::new(e).context("nothing was written"));
        }
        for (path, _) in &texts {
            say!("wrote {}", path.display());
        }
        return Ok(());
    }
    let names: Vec<&str> = all.iter().map(|(n, _)| *n).collect();
    let Some(name) = name else {
        // The list: each name with the first sentence its schema gives of itself.
        let mut out = std::io::stdout().lock();
        let width = names.iter().map(|n| n.len()).max().unwrap_or(0);
        for (n, schema) in &all {
            let about = schema["description"].as_str().unwrap_or_default();
            let first = about.split(". ").next().unwrap_or_default();
            let first = first.trim_end_matches('.');
            let _ = writeln!(out, "{n:<width$}  {first}");
        }
        let _ = writeln!(
            out,
            "\nsplinescope schema NAME prints one; --write DIR writes them all"
        );
        return Ok(());
    };
    let Some((_, schema)) = all.iter().find(|(n, _)| *n == name) else {
        bail!(
            "unknown schema {name:?} (expected one of: {})",
            names.join(", ")
        );
    };
    print!("{}", splinescope::schemas::to_text(schema));
    Ok(())
}
