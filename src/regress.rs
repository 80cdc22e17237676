//! Image regression for users' own scenes (`splinescope regress`): render every scene of a
//! directory offscreen, compare each with its reference PNG by the per-channel rule and
//! NVIDIA FLIP ([`splinescope_image::compare::compare_images`]), bless new references on request, and
//! write an HTML report with the actual, reference, diff and FLIP images.
//!
//! A run writes all or nothing: the references it blesses are staged beside their
//! targets and the report is built in a hidden directory beside its destination; only
//! when every one of them is complete are they moved into place. The report directory may
//! not be, contain or lie inside the references or scenes directory (replacing it would
//! delete them), and a `--report` path that is a symbolic link is followed, like every
//! other output.

use std::path::{Path, PathBuf};

use serde::Serialize;
use thiserror::Error;

use splinescope_gpu::{GpuContext, Pipelines};
use splinescope_image::RgbaImage;
use splinescope_image::compare::{Comparison, ComparisonImages, Tolerance, compare_images};
use splinescope_image::report::{ReportRow, figures_text, write_report};
use splinescope_scene::format::Scene;

/// How to run a regression.
#[derive(Debug, Clone, PartialEq)]
pub struct RegressOptions {
    /// Render width in pixels.
    pub width: u32,
    /// Render height in pixels.
    pub height: u32,
    /// When two images match.
    pub tolerance: Tolerance,
    /// Write missing and changed references instead of failing on them.
    pub bless: bool,
    /// Where to write the HTML report and its images, if anywhere.
    pub report: Option<PathBuf>,
}

impl Default for RegressOptions {
    fn default() -> RegressOptions {
        RegressOptions {
            width: 640,
            height: 480,
            tolerance: Tolerance::default(),
            bless: false,
            report: None,
        }
    }
}

/// What became of one scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    /// It matches its reference.
    Match,
    /// It differs from its reference beyond the tolerance.
    Differs,
    /// It has no reference (run with `--bless` to create it).
    Missing,
    /// `--bless` wrote its reference (it was missing or differed).
    Blessed,
    /// It could not be compared: the scene did not load or render, or the reference
    /// could not be read or has another size.
    Error,
}

/// One scene's outcome.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SceneResult {
    /// The scene file's name.
    pub scene: String,
    /// Its reference image.
    pub reference: PathBuf,
    /// The outcome.
    pub status: Status,
    /// The figures, when the images were compared.
    pub comparison: Option<Comparison>,
    /// What went wrong, or what was done.
    pub message: Option<String>,
}

impl SceneResult {
    /// Whether this scene makes the run fail.
    #[must_use]
    pub fn failed(&self) -> bool {
        matches!(
            self.status,
            Status::Differs | Status::Missing | Status::Error
        )
    }
}

/// The outcome of a whole run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RegressReport {
    /// Every scene, in file-name order.
    pub scenes: Vec<SceneResult>,
    /// The tolerance used, as `--tolerance` writes it.
    pub tolerance: String,
    /// The HTML report's page, when one was written.
    pub report_page: Option<PathBuf>,
}

impl RegressReport {
    /// Whether any scene failed.
    #[must_use]
    pub fn failed(&self) -> bool {
        self.scenes.iter().any(SceneResult::failed)
    }

    /// One line: how many scenes matched, differed, were missing, blessed or failed.
    #[must_use]
    pub fn summary(&self) -> String {
        format!(
            "{} scene(s): {} match, {} differ, {} missing, {} blessed, {} error(s); tolerance {}",
            self.scenes.len(),
            self.count(Status::Match),
            self.count(Status::Differs),
            self.count(Status::Missing),
            self.count(Status::Blessed),
            self.count(Status::Error),
            self.tolerance
        )
    }

    /// How many scenes have `status`.
    #[must_use]
    pub fn count(&self, status: Status) -> usize {
        self.scenes.iter().filter(|s| s.status == status).count()
    }
}

/// Why a regression could not run at all (a problem with one scene is a
/// [`SceneResult`] with [`Status::Error`] instead, and the others are still compared).
#[derive(Debug, Error)]
pub enum RegressError {
    /// The scenes directory could not be listed.
    #[error("{path}: cannot read the scenes directory: {source}")]
    ScenesDir {
        /// The directory.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// It holds no `*.json` scene.
    #[error("{0}: no scene files (*.json) to compare")]
    NoScenes(PathBuf),
    /// The references path exists and is not a directory.
    #[error("{0}: the references path is not a directory")]
    RefsNotDir(PathBuf),
    /// The references directory could not be created (`--bless`).
    #[error("{path}: cannot create the references directory: {source}")]
    RefsCreate {
        /// The directory.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The report directory exists and is not an earlier report or empty, so replacing it
    /// could destroy someone's files.
    #[error(
        "{0}: exists and is not an earlier splinescope report (no index.html) nor empty; choose another --report directory"
    )]
    ReportDirInUse(PathBuf),
    /// The report directory would replace (or sit among) the references or the scenes.
    #[error(
        "--report {report}: {relation} the {what} directory {other}; replacing it would delete them, so choose a report directory outside it"
    )]
    ReportOverlaps {
        /// The report directory, as given.
        report: PathBuf,
        /// "is", "is inside" or "contains".
        relation: &'static str,
        /// "references" or "scenes".
        what: &'static str,
        /// That directory, as given.
        other: PathBuf,
    },
    /// The render size is over [`splinescope_io::limits::IMAGE_PIXELS`].
    #[error("--width × --height: {0}")]
    TooLarge(splinescope_io::limits::LimitError),
    /// The blessed references could not be written (none was).
    #[error("{0}; nothing was written")]
    Bless(std::io::Error),
    /// Writing the report failed (nothing was left behind).
    #[error("{path}: cannot write the report: {message}")]
    Report {
        /// The report directory.
        path: PathBuf,
        /// The cause.
        message: String,
    },
}

/// The scene files directly in `dir` (`*.json`, and every format splinescope imports:
/// SVG, DXF, STEP, fonts), sorted by name.
fn scene_files(dir: &Path) -> Result<Vec<PathBuf>, RegressError> {
    let read = std::fs::read_dir(dir).map_err(|source| RegressError::ScenesDir {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut files = Vec::new();
    for entry in read {
        let entry = entry.map_err(|source| RegressError::ScenesDir {
            path: dir.to_path_buf(),
            source,
        })?;
        let path = entry.path();
        let readable = path.extension().is_some_and(|e| {
            splinescope_import::EXTENSIONS.contains(&e.to_string_lossy().to_lowercase().as_str())
        });
        if readable && path.is_file() {
            files.push(path);
        }
    }
    files.sort();
    if files.is_empty() {
        return Err(RegressError::NoScenes(dir.to_path_buf()));
    }
    Ok(files)
}

/// Where the report goes: `report` itself, or the directory a symbolic link there points
/// to (a link to nothing is refused, as for every output).
fn report_target(report: &Path) -> Result<PathBuf, RegressError> {
    let is_link = std::fs::symlink_metadata(report).is_ok_and(|m| m.file_type().is_symlink());
    if !is_link {
        return Ok(report.to_path_buf());
    }
    std::fs::canonicalize(report).map_err(|_| RegressError::Report {
        path: report.to_path_buf(),
        message: "is a symbolic link to nothing; not written".into(),
    })
}

/// Checks that `report` can be (re)placed: absent, empty, or an earlier report.
fn check_report_dir(report: &Path) -> Result<(), RegressError> {
    let parent = report
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or_else(|| Path::new("."));
    if !parent.is_dir() {
        return Err(RegressError::Report {
            path: report.to_path_buf(),
            message: format!("{} is not a directory", parent.display()),
        });
    }
    if !report.exists() {
        return Ok(());
    }
    let earlier = report.is_dir()
        && (report.join("index.html").is_file()
            || std::fs::read_dir(report).is_ok_and(|mut d| d.next().is_none()));
    if earlier {
        Ok(())
    } else {
        Err(RegressError::ReportDirInUse(report.to_path_buf()))
    }
}

/// Refuses a report directory that is, contains or lies inside `dirs` (as given and
/// resolved: links and `..` cannot hide an overlap).
fn check_report_apart(
    report: &Path,
    resolved_report: &Path,
    dirs: [(&'static str, &Path); 2],
) -> Result<(), RegressError> {
    for (what, dir) in dirs {
        let other = splinescope_io::files::resolved(dir);
        let relation = if other == resolved_report {
            "is"
        } else if resolved_report.starts_with(&other) {
            "is inside"
        } else if other.starts_with(resolved_report) {
            "contains"
        } else {
            continue;
        };
        return Err(RegressError::ReportOverlaps {
            report: report.to_path_buf(),
            relation,
            what,
            other: dir.to_path_buf(),
        });
    }
    Ok(())
}

/// One scene rendered and compared: the result and, for the report, its images.
struct Compared {
    result: SceneResult,
    /// Whether `actual` is to become the reference (`--bless`).
    bless: bool,
    actual: Option<RgbaImage>,
    reference: Option<RgbaImage>,
    pictures: Option<ComparisonImages>,
}

fn compare_one(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    path: &Path,
    refs: &Path,
    opts: &RegressOptions,
) -> Compared {
    let name = path
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let stem = path
        .file_stem()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    // A scene file's reference is `NAME.png`; an imported file's keeps its extension
    // (`logo.svg.png`), so that `logo.json` and `logo.svg` side by side do not share one.
    let imported = !splinescope_import::is_scene_file(path);
    let reference_path = refs.join(if imported {
        format!("{name}.png")
    } else {
        format!("{stem}.png")
    });
    let mut out = Compared {
        result: SceneResult {
            scene: name,
            reference: reference_path.clone(),
            status: Status::Error,
            comparison: None,
            message: None,
        },
        bless: false,
        actual: None,
        reference: None,
        pictures: None,
    };
    let loaded = if imported {
        splinescope_import::load(path)
            .map(|i| i.scene)
            .map_err(|e| e.to_string())
    } else {
        Scene::load(path).map_err(|e| format!("{}: {e}", path.display()))
    };
    let rendered = loaded.and_then(|scene| {
        splinescope_render::render(
            ctx,
            pipelines,
            &scene,
            &splinescope_render::RenderRequest::new(opts.width, opts.height),
        )
        .map_err(|e| format!("{}: {e}", path.display()))
    });
    let actual = match rendered {
        Ok(image) => image,
        Err(message) => {
            out.result.message = Some(message);
            return out;
        }
    };
    // Blessing is decided here and written by `run` with every other output.
    let bless = |out: &mut Compared, why: &str| {
        out.bless = true;
        out.result.status = Status::Blessed;
        out.result.message = Some(format!("{why}: wrote {}", reference_path.display()));
    };
    if !reference_path.exists() {
        if opts.bless {
            bless(&mut out, "no reference");
        } else {
            out.result.status = Status::Missing;
            out.result.message = Some(format!(
                "{}: no reference image (run with --bless to create it)",
                reference_path.display()
            ));
        }
        out.actual = Some(actual);
        return out;
    }
    let reference = match RgbaImage::read_png(&reference_path) {
        Ok(r) => r,
        Err(e) => {
            if opts.bless {
                bless(&mut out, &format!("unreadable reference ({e})"));
            } else {
                out.result.message = Some(format!("reference {e}"));
            }
            out.actual = Some(actual);
            return out;
        }
    };
    match compare_images(&actual, &reference, &opts.tolerance) {
        Err(mismatch) => {
            if opts.bless {
                bless(&mut out, &mismatch.to_string());
            } else {
                out.result.message = Some(format!("{}: {mismatch}", reference_path.display()));
            }
        }
        Ok((comparison, pictures)) => {
            let matches = comparison.matches;
            out.result.comparison = Some(comparison);
            out.pictures = Some(pictures);
            if matches {
                out.result.status = Status::Match;
            } else if opts.bless {
                bless(&mut out, "changed");
            } else {
                out.result.status = Status::Differs;
            }
        }
    }
    out.actual = Some(actual);
    out.reference = Some(reference);
    out
}

/// Checks a run's directories and sizes before anything is rendered (and before a GPU is
/// opened, when called first): the scenes to compare, and where the report goes (the
/// directory a `--report` link points to).
///
/// # Errors
/// No scenes, a references path that is not a directory, a report directory that is in
/// use, is, contains or lies inside the references or scenes directory, or a render size
/// over [`splinescope_io::limits::IMAGE_PIXELS`].
pub fn check_options(
    scenes: &Path,
    refs: &Path,
    opts: &RegressOptions,
) -> Result<(Vec<PathBuf>, Option<PathBuf>), RegressError> {
    let files = scene_files(scenes)?;
    if refs.exists() && !refs.is_dir() {
        return Err(RegressError::RefsNotDir(refs.to_path_buf()));
    }
    let report_dir = match &opts.report {
        Some(report) => {
            let target = report_target(report)?;
            check_report_apart(
                report,
                &splinescope_io::files::resolved(&target),
                [("references", refs), ("scenes", scenes)],
            )?;
            check_report_dir(&target)?;
            Some(target)
        }
        None => None,
    };
    splinescope_io::limits::IMAGE_PIXELS
        .check(u64::from(opts.width) * u64::from(opts.height))
        .map_err(RegressError::TooLarge)?;
    Ok((files, report_dir))
}

/// Renders every scene in `scenes` on `ctx` with `pipelines` and compares it with `refs/<stem>.png`.
///
/// # Errors
/// [`RegressError`] when the run cannot start (no scenes, unusable directories) or the
/// report cannot be written; a scene that fails is reported in its [`SceneResult`].
pub fn run(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    scenes: &Path,
    refs: &Path,
    opts: &RegressOptions,
) -> Result<RegressReport, RegressError> {
    let (files, report_dir) = check_options(scenes, refs, opts)?;
    let compared: Vec<Compared> = files
        .iter()
        .map(|f| compare_one(ctx, pipelines, f, refs, opts))
        .collect();
    let mut report = RegressReport {
        scenes: compared.iter().map(|c| c.result.clone()).collect(),
        tolerance: opts.tolerance.to_string(),
        report_page: None,
    };
    // Every output staged before any is committed: the blessed references, then the report.
    let blessed = encode_blessed(&compared)?;
    let made_refs = !blessed.is_empty() && !refs.exists();
    if !blessed.is_empty() {
        std::fs::create_dir_all(refs).map_err(|source| RegressError::RefsCreate {
            path: refs.to_path_buf(),
            source,
        })?;
    }
    let undo_refs = || {
        if made_refs {
            let _ = std::fs::remove_dir(refs);
        }
    };
    let pairs: Vec<(&Path, &[u8])> = blessed
        .iter()
        .map(|(p, b)| (p.as_path(), b.as_slice()))
        .collect();
    let staged = splinescope_io::files::stage_all(&pairs).map_err(|e| {
        undo_refs();
        RegressError::Bless(e)
    })?;
    let report_staging = match &report_dir {
        Some(dir) => match stage_report(dir, &compared, &report) {
            Ok(staging) => Some(staging),
            Err(message) => {
                drop(staged);
                undo_refs();
                return Err(RegressError::Report {
                    path: opts.report.clone().unwrap_or_default(),
                    message: message.to_string(),
                });
            }
        },
        None => None,
    };
    staged.commit().map_err(RegressError::Bless)?;
    if let (Some(dir), Some(staging)) = (&report_dir, report_staging) {
        place_report(dir, &staging).map_err(|message| RegressError::Report {
            path: opts.report.clone().unwrap_or_default(),
            message: message.to_string(),
        })?;
        report.report_page = opts.report.as_ref().map(|r| r.join("index.html"));
    }
    Ok(report)
}

/// The PNG bytes of every reference to bless, with its path.
fn encode_blessed(compared: &[Compared]) -> Result<Vec<(PathBuf, Vec<u8>)>, RegressError> {
    compared
        .iter()
        .filter(|c| c.bless)
        .filter_map(|c| c.actual.as_ref().map(|a| (&c.result.reference, a)))
        .map(|(path, actual)| {
            actual
                .png_bytes(path)
                .map(|bytes| (path.clone(), bytes))
                .map_err(|e| RegressError::Bless(std::io::Error::other(e.to_string())))
        })
        .collect()
}

/// Builds the report in a hidden directory beside `dir` and returns that directory.
fn stage_report(
    dir: &Path,
    compared: &[Compared],
    report: &RegressReport,
) -> std::io::Result<PathBuf> {
    let name = dir
        .file_name()
        .map_or_else(|| "report".to_owned(), |n| n.to_string_lossy().into_owned());
    let staging = dir.with_file_name(format!(".{name}.{}.tmp", std::process::id()));
    let _ = std::fs::remove_dir_all(&staging);
    fill_report(&staging, compared, report).inspect_err(|_| {
        let _ = std::fs::remove_dir_all(&staging);
    })?;
    Ok(staging)
}

/// Moves a staged report into place, replacing an earlier report at `dir`.
fn place_report(dir: &Path, staging: &Path) -> std::io::Result<()> {
    let result = (|| {
        if dir.exists() {
            std::fs::remove_dir_all(dir)?;
        }
        std::fs::rename(staging, dir)
    })();
    if result.is_err() {
        let _ = std::fs::remove_dir_all(staging);
    }
    result
}

fn fill_report(
    staging: &Path,
    compared: &[Compared],
    report: &RegressReport,
) -> std::io::Result<()> {
    std::fs::create_dir(staging)
        .map_err(|e| std::io::Error::new(e.kind(), format!("{}: {e}", staging.display())))?;
    let rows: Vec<ReportRow<'_>> = compared
        .iter()
        .map(|c| {
            let r = &c.result;
            ReportRow {
                name: r.scene.clone(),
                status: format!("{:?}", r.status).to_lowercase(),
                figures: r.comparison.as_ref().map_or_else(String::new, figures_text),
                message: r.message.clone().unwrap_or_default(),
                images: [
                    c.reference.as_ref(),
                    c.actual.as_ref(),
                    c.pictures.as_ref().map(|p| &p.diff),
                    c.pictures.as_ref().map(|p| &p.flip),
                ],
            }
        })
        .collect();
    write_report(staging, &report.summary(), &rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn report_directories_that_hold_other_files_are_refused() {
        let base = std::env::temp_dir().join(format!("splinescope-regress-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&base);
        std::fs::create_dir_all(base.join("earlier")).unwrap();
        std::fs::write(base.join("earlier/index.html"), "x").unwrap();
        std::fs::create_dir_all(base.join("empty")).unwrap();
        std::fs::create_dir_all(base.join("photos")).unwrap();
        std::fs::write(base.join("photos/cat.png"), "x").unwrap();
        std::fs::write(base.join("file"), "x").unwrap();
        assert!(check_report_dir(&base.join("absent")).is_ok());
        assert!(check_report_dir(&base.join("earlier")).is_ok());
        assert!(check_report_dir(&base.join("empty")).is_ok());
        for bad in ["photos", "file"] {
            let e = check_report_dir(&base.join(bad)).unwrap_err();
            assert!(e.to_string().contains(bad), "{e}");
        }
        assert!(matches!(
            scene_files(&base.join("empty")),
            Err(RegressError::NoScenes(_))
        ));
        std::fs::remove_dir_all(&base).unwrap();
    }
}
