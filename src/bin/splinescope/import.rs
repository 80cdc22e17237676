//! `splinescope import`: a file of another format (SVG, DXF, STEP, a font) written as a
//! splinescope scene.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

use crate::say;

/// The arguments of `splinescope import`.
#[derive(Debug, clap::Args)]
pub struct ImportArgs {
    /// The file to read: SVG (`.svg`), DXF (`.dxf`), STEP (`.step`, `.stp`), a font
    /// (`.ttf`, `.otf`, `.ttc`, `.otc`), or a scene (`.json`).
    pub file: PathBuf,
    /// Where to write the scene (JSON); the file is replaced atomically.
    #[arg(short, long, value_name = "SCENE.json")]
    pub output: PathBuf,
}

/// What to read of a font (`.ttf`, `.otf`, `.ttc`, `.otc`): by default every glyph, on a
/// grid in glyph order. Global: every command that reads a scene file takes them.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct FontArgs {
    /// These glyphs only, by name or id (`A,uni00E9,gid36`); one glyph sits at its own
    /// origin.
    #[arg(
        long,
        global = true,
        value_delimiter = ',',
        value_name = "NAMES",
        conflicts_with = "text"
    )]
    pub glyphs: Option<Vec<String>>,
    /// This text, laid out by the glyphs' advances (no shaping, no kerning).
    #[arg(long, global = true)]
    pub text: Option<String>,
    /// A variable font's location, as AXIS=VALUE pairs (`wght=700,wdth=75`); the default
    /// location otherwise. An axis the font lacks or a value outside its range is refused.
    #[arg(long, global = true, value_delimiter = ',', value_name = "AXIS=VALUE", value_parser = parse_variation)]
    pub variations: Vec<(String, f64)>,
    /// The font's index in a collection (`.ttc`, `.otc`).
    #[arg(long, global = true, default_value_t = 0)]
    pub font_index: u32,
}

impl FontArgs {
    /// The importer's options.
    pub fn options(&self) -> splinescope_import::Options {
        splinescope_import::Options {
            font: splinescope_import::font::FontOptions {
                index: self.font_index,
                glyphs: self.glyphs.clone(),
                text: self.text.clone(),
                variations: self.variations.clone(),
            },
        }
    }
}

/// `AXIS=VALUE` with a four-character axis tag and a finite number.
fn parse_variation(s: &str) -> Result<(String, f64), String> {
    let (tag, value) = s
        .split_once('=')
        .ok_or_else(|| format!("{s:?}: an axis and a value, as wght=700"))?;
    let tag = tag.trim();
    if tag.is_empty() || tag.len() > 4 || !tag.is_ascii() {
        return Err(format!(
            "{tag:?}: an axis tag is one to four ASCII characters (wght, wdth, opsz)"
        ));
    }
    let v: f64 = value
        .trim()
        .parse()
        .map_err(|_| format!("{value:?}: not a number (the axis {tag}'s value)"))?;
    if !v.is_finite() {
        return Err(format!(
            "{value:?}: not a finite number (the axis {tag}'s value)"
        ));
    }
    Ok((tag.to_owned(), v))
}

/// Runs `splinescope import`.
///
/// # Errors
/// The file does not read (naming it and where), the output is the input, or it cannot
/// be written.
pub fn run(a: &ImportArgs) -> Result<()> {
    import(&a.file, &a.output, &crate::load::options())
}

fn import(file: &Path, output: &Path, options: &splinescope_import::Options) -> Result<()> {
    if splinescope_io::files::resolved(file) == splinescope_io::files::resolved(output) {
        bail!(
            "{}: the output is the file being read; write the scene to another file (e.g. {})",
            output.display(),
            file.with_extension("json").display()
        );
    }
    let imported = splinescope_import::load_with(file, options)?;
    for w in &imported.warnings {
        eprintln!("warning: {w}");
    }
    let scene = imported.scene;
    let text = splinescope_scene::format::to_json_string(&scene);
    splinescope_io::files::write_atomic(output, text.as_bytes())
        .with_context(|| format!("{}: cannot write the scene", output.display()))?;
    say!(
        "{}: {} curve(s) written to {}",
        file.display(),
        scene.curves.len(),
        output.display()
    );
    Ok(())
}
