//! The viewer's file handling, free of window types: a file dialog drawn by the panel
//! (it needs no desktop portal, so it works under Xvfb, over SSH and in minimal
//! sessions) and the list of recently opened files kept in the user's configuration
//! directory.

use std::path::{Path, PathBuf};

/// The name the save-as dialog proposes for a scene that is no file's (the gallery).
pub const DEFAULT_SAVE_NAME: &str = "splinescope-scene.json";

/// What a [`FileDialog`] is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DialogMode {
    /// Choose an existing scene file to open.
    Open,
    /// Choose where to save the scene.
    SaveAs,
    /// Choose where to export the view as a figure (`.svg` or `.pdf`).
    Export,
}

/// One listed entry of a directory.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Entry {
    /// The file or directory name.
    pub name: String,
    /// Whether it is a directory (entered rather than chosen).
    pub is_dir: bool,
}

/// A file dialog's state: the directory shown, its entries (directories and `.json`
/// files, hidden ones left out, directories first, by name), the name typed or chosen,
/// and the last problem.
#[derive(Debug, Clone, PartialEq)]
pub struct FileDialog {
    /// Open or save as.
    pub mode: DialogMode,
    /// The directory shown.
    pub dir: PathBuf,
    /// Its entries.
    pub entries: Vec<Entry>,
    /// The file name (or a path, relative to `dir` or absolute) typed or clicked.
    pub name: String,
    /// Why the last step failed, or what confirming again will do.
    pub error: Option<String>,
    /// The save-as target that exists and is replaced if the user confirms again.
    replace: Option<PathBuf>,
    /// Whether the name field still wants the keyboard focus (the dialog just opened).
    pub focus_name: bool,
}

impl FileDialog {
    /// A dialog showing `dir` with `name` proposed.
    #[must_use]
    pub fn new(mode: DialogMode, dir: &Path, name: &str) -> FileDialog {
        let mut d = FileDialog {
            mode,
            dir: dir.to_path_buf(),
            entries: Vec::new(),
            name: name.to_owned(),
            error: None,
            replace: None,
            focus_name: true,
        };
        d.refresh();
        d
    }

    /// Reads the directory again (an unreadable one is shown empty, with the reason).
    pub fn refresh(&mut self) {
        self.entries.clear();
        let read = match std::fs::read_dir(&self.dir) {
            Ok(r) => r,
            Err(e) => {
                self.error = Some(format!("{}: cannot list: {e}", self.dir.display()));
                return;
            }
        };
        for entry in read.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            if name.starts_with('.') {
                continue;
            }
            // Links are followed: a link to a directory is entered.
            let is_dir = std::fs::metadata(entry.path()).is_ok_and(|m| m.is_dir());
            // Scene files to open or save over; figures where the view is exported.
            let wanted: &[&str] = match self.mode {
                // Other formats open as scenes of path curves (saved as NAME.json).
                DialogMode::Open => splinescope_import::EXTENSIONS,
                DialogMode::SaveAs => &["json"],
                DialogMode::Export => &["svg", "pdf"],
            };
            let listed = Path::new(&name).extension().is_some_and(|e| {
                wanted
                    .iter()
                    .any(|w| e.eq_ignore_ascii_case(std::ffi::OsStr::new(w)))
            });
            if is_dir || listed {
                self.entries.push(Entry { name, is_dir });
            }
        }
        self.entries
            .sort_by(|a, b| b.is_dir.cmp(&a.is_dir).then_with(|| a.name.cmp(&b.name)));
    }

    /// Shows directory `dir` (relative to the shown one, or absolute).
    pub fn enter(&mut self, dir: &str) {
        let next = self.dir.join(dir);
        if next.is_dir() {
            self.dir = next.canonicalize().unwrap_or(next);
            self.error = None;
            self.replace = None;
            self.refresh();
        } else {
            self.error = Some(format!("{}: not a directory", next.display()));
        }
    }

    /// Shows the parent directory.
    pub fn up(&mut self) {
        if let Some(parent) = self.dir.parent() {
            self.dir = parent.to_path_buf();
            self.error = None;
            self.replace = None;
            self.refresh();
        }
    }

    /// Chooses a listed entry by a click: a directory is entered, a file's name is taken.
    pub fn pick(&mut self, index: usize) {
        let Some(entry) = self.entries.get(index).cloned() else {
            return;
        };
        if entry.is_dir {
            self.enter(&entry.name);
        } else {
            self.name = entry.name;
            self.error = None;
            self.replace = None;
        }
    }

    /// The chosen file: for opening, an existing file; for saving, a path in an
    /// existing directory (`.json` added when the name has no extension; an existing
    /// file is replaced only when confirmed twice). A typed directory is entered
    /// instead. `None` with [`FileDialog::error`] saying why when there is no choice
    /// yet.
    pub fn confirm(&mut self) -> Option<PathBuf> {
        let typed = self.name.trim();
        if typed.is_empty() {
            self.error = Some("type or click a file name".into());
            return None;
        }
        let mut path = self.dir.join(typed);
        if path.is_dir() {
            let dir = path.to_string_lossy().into_owned();
            self.name.clear();
            self.enter(&dir);
            return None;
        }
        match self.mode {
            DialogMode::Open => {
                if path.is_file() {
                    Some(path)
                } else {
                    self.error = Some(format!("{}: no such file", path.display()));
                    None
                }
            }
            DialogMode::SaveAs | DialogMode::Export => {
                if path.extension().is_none() {
                    path.set_extension(if self.mode == DialogMode::Export {
                        "svg"
                    } else {
                        "json"
                    });
                }
                if self.mode == DialogMode::Export {
                    let ext = path
                        .extension()
                        .and_then(|e| e.to_str())
                        .map(str::to_ascii_lowercase);
                    if !matches!(ext.as_deref(), Some("svg" | "pdf")) {
                        self.error = Some(format!(
                            "{}: a figure is written as .svg or .pdf",
                            path.display()
                        ));
                        return None;
                    }
                }
                match path.parent() {
                    Some(dir) if dir.as_os_str().is_empty() || dir.is_dir() => {}
                    Some(dir) => {
                        self.error = Some(format!("{}: no such directory", dir.display()));
                        return None;
                    }
                    None => {}
                }
                if path.exists() && self.replace.as_deref() != Some(path.as_path()) {
                    self.error = Some(format!(
                        "{} exists: save again to replace it",
                        path.display()
                    ));
                    self.replace = Some(path);
                    return None;
                }
                Some(path)
            }
        }
    }
}

/// How many recent files are kept.
pub const RECENT_KEPT: usize = 10;

/// The recently opened or saved scene files, newest first, kept in a file (one path per
/// line) so that they survive the session. A missing or unreadable file is an empty list;
/// a list that cannot be written is kept in memory, and the reason reported.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct RecentFiles {
    /// Where the list is kept (`None`: in memory only).
    pub store: Option<PathBuf>,
    /// The files, newest first.
    pub paths: Vec<PathBuf>,
}

impl RecentFiles {
    /// The list kept in `store` (read now).
    #[must_use]
    pub fn load(store: Option<PathBuf>) -> RecentFiles {
        let paths = store
            .as_deref()
            .and_then(|s| std::fs::read_to_string(s).ok())
            .map(|text| {
                text.lines()
                    .filter(|l| !l.trim().is_empty())
                    .map(PathBuf::from)
                    .take(RECENT_KEPT)
                    .collect()
            })
            .unwrap_or_default();
        RecentFiles { store, paths }
    }

    /// Where the list lives by default: `$SPLINESCOPE_CONFIG_DIR/recent.txt`, else
    /// `$XDG_CONFIG_HOME/splinescope/recent.txt`, else
    /// `$HOME/.config/splinescope/recent.txt`.
    #[must_use]
    pub fn default_store() -> Option<PathBuf> {
        Some(
            user_dir("SPLINESCOPE_CONFIG_DIR", "XDG_CONFIG_HOME", &[".config"])?.join("recent.txt"),
        )
    }

    /// Puts `path` first (made absolute) and writes the list.
    ///
    /// # Errors
    /// [`RecentError`] naming the list's file when it cannot be written (the list is kept
    /// in memory).
    pub fn add(&mut self, path: &Path) -> Result<(), RecentError> {
        let path = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
        self.paths.retain(|p| p != &path);
        self.paths.insert(0, path);
        self.paths.truncate(RECENT_KEPT);
        let Some(store) = self.store.as_deref() else {
            return Ok(());
        };
        let mut text = String::new();
        for p in &self.paths {
            text.push_str(&p.to_string_lossy());
            text.push('\n');
        }
        let write = || -> std::io::Result<()> {
            if let Some(dir) = store.parent() {
                std::fs::create_dir_all(dir)?;
            }
            splinescope_io::files::write_atomic(store, text.as_bytes())
        };
        write().map_err(|reason| RecentError {
            store: store.to_path_buf(),
            reason,
        })
    }
}

/// The list of recent files could not be written.
#[derive(Debug, thiserror::Error)]
#[error("{}: cannot keep the recent files: {reason}", store.display())]
pub struct RecentError {
    /// The list's file.
    pub store: std::path::PathBuf,
    /// The cause.
    pub reason: std::io::Error,
}

/// The user's splinescope directory of one kind: `$OWN` when set, else `$XDG/splinescope`,
/// else `$HOME/<home…>/splinescope` (empty variables count as unset); `None` when none is.
pub(crate) fn user_dir(own: &str, xdg: &str, home: &[&str]) -> Option<PathBuf> {
    let var = |k: &str| {
        std::env::var_os(k)
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
    };
    var(own)
        .or_else(|| var(xdg).map(|d| d.join("splinescope")))
        .or_else(|| {
            var("HOME").map(|h| {
                home.iter()
                    .fold(h, |p, part| p.join(part))
                    .join("splinescope")
            })
        })
}
