//! `splinescope schema`: print or write the JSON Schemas of the formats.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

use crate::say;

/// The arguments of `splinescope schema`.
#[derive(Debug, clap::Args)]
pub struct SchemaArgs {
    /// Which schema.
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

/// Prints one schema, or writes every schema into `dir`.
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
        if let Err(e) = splinescope::files::write_all_atomic(&files) {
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
        bail!("name a schema ({}) or give --write DIR", names.join(", "));
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
