#![doc = include_str!("../README.md")]
#![forbid(unsafe_code)]

pub mod dxf;
pub mod font;
pub mod step;
pub mod svg;

use std::path::Path;

use splinescope_io::limits::{self, LimitError};
use splinescope_scene::format::{Scene, SceneError};
use thiserror::Error;

/// A scene read from a file, and what the reader left out (one line each).
#[derive(Debug, Clone)]
pub struct Imported {
    /// The scene.
    pub scene: Scene,
    /// What was left out, for a person (stderr, `warnings.warn`).
    pub warnings: Vec<String>,
}

impl Imported {
    /// What a reader of `file` hands back: a scene of `curves` named after the file,
    /// and one warning that counts what it left out (`kind → count`), if anything.
    pub(crate) fn of_file<N: std::fmt::Display>(
        file: &str,
        curves: Vec<splinescope_scene::format::SceneCurve>,
        left_out: &std::collections::BTreeMap<String, N>,
    ) -> Imported {
        let mut scene = Scene::of_curves(std::iter::empty());
        scene.name = Path::new(file)
            .file_name()
            .map(|n| n.to_string_lossy().into_owned());
        scene.curves = curves;
        let warnings = if left_out.is_empty() {
            Vec::new()
        } else {
            let what: Vec<String> = left_out.iter().map(|(k, n)| format!("{n} {k}")).collect();
            vec![format!(
                "{file}: left out (not curves): {}",
                what.join(", ")
            )]
        };
        Imported { scene, warnings }
    }
}

/// Why a file could not be read.
#[derive(Debug, Error)]
pub enum ImportError {
    /// The file could not be read (missing, unreadable, over the size limit, not UTF-8).
    #[error("{file}: {message}")]
    Io {
        /// The file.
        file: String,
        /// What went wrong.
        message: String,
    },
    /// The file's syntax (XML) is wrong, or it is not the format its extension says.
    #[error("{file}:{line}:{column}: {message}")]
    Syntax {
        /// The file.
        file: String,
        /// The line (from 1).
        line: u32,
        /// The column (from 1).
        column: u32,
        /// What is wrong.
        message: String,
    },
    /// An element whose geometry, reference or numbers are wrong, or past a limit.
    #[error("{file}:{line}: <{element}>: {message}")]
    Element {
        /// The file.
        file: String,
        /// The element's line (from 1).
        line: u32,
        /// The element's name.
        element: String,
        /// What is wrong.
        message: String,
    },
    /// A font that cannot be read as asked: not a font, a glyph, character or axis it
    /// does not have, an outline that cannot be drawn.
    #[error("{file}: {message}")]
    Font {
        /// The file.
        file: String,
        /// What is wrong, naming the glyph, the character or the axis.
        message: String,
    },
    /// An entity of a DXF or STEP file whose numbers or references are wrong, or past a
    /// limit: `at` names its type and handle (DXF) or its `#id` and line (STEP).
    #[error("{file}: {at}: {message}")]
    Entity {
        /// The file.
        file: String,
        /// The entity: its type and handle, or its `#id`, type and line.
        at: String,
        /// What is wrong.
        message: String,
    },
    /// A limit's environment variable that does not hold a whole number.
    #[error("{file}: {source}")]
    Limit {
        /// The file.
        file: String,
        /// The limit's error.
        source: LimitError,
    },
    /// An extension splinescope does not read.
    #[error(
        "{file}: .{extension} is not a format splinescope reads (it reads .json scenes, .svg, .dxf, .step/.stp files and fonts: .ttf, .otf, .ttc, .otc)"
    )]
    UnknownFormat {
        /// The file.
        file: String,
        /// Its extension (empty when it has none).
        extension: String,
    },
    /// A splinescope scene file's error.
    #[error("{file}: {source}")]
    Scene {
        /// The file.
        file: String,
        /// The scene reader's error (it names the value).
        source: SceneError,
    },
}

thread_local! {
    /// Whether this thread is inside [`guarded`]: its panics are the reader's, said as a
    /// typed error, not on stderr.
    static GUARDED: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Runs a third-party reader that is not written for hostile input (the `dxf` crate
/// panics on some malformed files): a panic inside it is `None` — the caller's typed
/// error — and is not printed. The panic hook this installs (once) stays quiet only on a
/// thread inside this function and hands every other panic to the hook before it.
pub(crate) fn guarded<T>(f: impl FnOnce() -> T + std::panic::UnwindSafe) -> Option<T> {
    static HOOK: std::sync::Once = std::sync::Once::new();
    HOOK.call_once(|| {
        let before = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !GUARDED.with(std::cell::Cell::get) {
                before(info);
            }
        }));
    });
    let was = GUARDED.with(|g| g.replace(true));
    let out = std::panic::catch_unwind(f).ok();
    GUARDED.with(|g| g.set(was));
    out
}

/// The formats [`load`] reads, by extension (lower case).
pub const EXTENSIONS: &[&str] = &[
    "json", "svg", "dxf", "step", "stp", "ttf", "otf", "ttc", "otc",
];

/// Whether `path` is read as a splinescope scene (`.json`, or an extension no reader
/// claims: the scene reader then says what is wrong with it) rather than imported.
#[must_use]
pub fn is_scene_file(path: &Path) -> bool {
    let ext = extension(path);
    ext == "json" || !EXTENSIONS.contains(&ext.as_str())
}

/// A path's extension, lower case (empty when it has none).
fn extension(path: &Path) -> String {
    path.extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default()
}

/// What to read of a file beyond its path (the font options; other formats have none).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Options {
    /// Which glyphs, at which location, of which font in a collection.
    pub font: font::FontOptions,
}

/// Reads `path` by its extension: a scene (`.json`), SVG (`.svg`) or a font (`.ttf`,
/// `.otf`, `.ttc`, `.otc`: every glyph on a grid) as path curves.
///
/// ```
/// let dir = std::env::temp_dir().join(format!("splinescope-import-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("wave.svg");
/// std::fs::write(&path, r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 50">
///   <path d="M0 25 C 25 0, 75 50, 100 25" fill="none" stroke="black"/>
/// </svg>"#).unwrap();
/// let imported = splinescope_import::load(&path).unwrap();
/// assert_eq!(imported.scene.curves.len(), 1);
/// std::fs::remove_dir_all(&dir).unwrap();
/// ```
///
/// # Errors
/// [`ImportError`] naming the file and where in it.
pub fn load(path: &Path) -> Result<Imported, ImportError> {
    load_with(path, &Options::default())
}

/// [`load`] with options (the font's glyphs, text, location and index).
///
/// # Errors
/// [`ImportError`] naming the file and where in it.
pub fn load_with(path: &Path, options: &Options) -> Result<Imported, ImportError> {
    let file = path.display().to_string();
    let extension = extension(path);
    let io = |e: limits::ReadError| ImportError::Io {
        file: file.clone(),
        message: e.to_string(),
    };
    match extension.as_str() {
        "svg" => {
            let text = limits::read_bounded(path).map_err(io)?;
            svg::read(&text, &file)
        }
        "step" | "stp" => {
            let text = limits::read_bounded(path).map_err(io)?;
            step::read(&text, &file)
        }
        "dxf" => {
            let bytes = limits::read_bounded_bytes(path).map_err(io)?;
            dxf::read(&bytes, &file)
        }
        "ttf" | "otf" | "ttc" | "otc" => {
            let bytes = limits::read_bounded_bytes(path).map_err(io)?;
            font::read(&bytes, &file, &options.font)
        }
        "json" => Scene::load(path)
            .map(|scene| Imported {
                scene,
                warnings: Vec::new(),
            })
            .map_err(|source| ImportError::Scene { file, source }),
        _ => Err(ImportError::UnknownFormat { file, extension }),
    }
}
