//! File output shared by every writer in the program (images, scenes, reports).
//!
//! The policy, for a path `-o`, `--report` or a save names:
//!
//! * a regular file, or nothing yet: written atomically — to a temporary file in the same
//!   directory, then renamed over the path, so a crash or a full disk never leaves a
//!   half-written file. An existing file keeps its permissions; a **read-only** file is
//!   refused (`… is read-only; not replaced`) rather than silently replaced.
//! * a **symbolic link**: followed deliberately — the file it points to is replaced
//!   atomically and the link stays a link; a link to nothing is refused. The system's
//!   links under `/dev` and `/proc` (`/dev/stdout`) are written through instead.
//! * a **FIFO or a character device** (`/dev/stdout`, a pipe): written through in place,
//!   never replaced by a regular file.
//! * a directory, a socket or a block device: refused.
//!
//! [`write_all_atomic`] writes several files all or none: every file is first written to
//! its temporary beside the target; only when all of them succeeded are they renamed into
//! place (renames in one directory do not fail for lack of space). [`stage_all`] is its
//! first half, for commands that stage something else too (a report directory) before
//! committing anything.

use std::fs;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// How a target path is written.
enum Target {
    /// Written through in place (FIFO, character device).
    Through(PathBuf),
    /// Replaced atomically (regular file or nothing, after following links); the
    /// permissions to give the new file, when one existed.
    Replace(PathBuf, Option<fs::Permissions>),
}

fn refuse(path: &Path, why: &str) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidInput,
        format!("{}: {why}", path.display()),
    )
}

/// What a (followed) file type means for writing.
enum Kind {
    File,
    Dir,
    Through,
    Other,
}

fn target_kind(ty: &fs::FileType) -> Kind {
    #[cfg(unix)]
    use std::os::unix::fs::FileTypeExt;
    if ty.is_dir() {
        return Kind::Dir;
    }
    #[cfg(unix)]
    if ty.is_fifo() || ty.is_char_device() {
        return Kind::Through;
    }
    if ty.is_file() {
        Kind::File
    } else {
        Kind::Other
    }
}

/// Decides how to write `path` (see the module doc).
fn target(path: &Path) -> io::Result<Target> {
    let meta = match fs::symlink_metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            return Ok(Target::Replace(path.to_path_buf(), None));
        }
        Err(e) => return Err(e),
    };
    let ty = meta.file_type();
    if ty.is_symlink() {
        let followed = fs::metadata(path)
            .map_err(|_| refuse(path, "is a symbolic link to nothing; not written"))?;
        // The system's links (`/dev/stdout` → `/proc/self/fd/1` → whatever the shell
        // opened) are written through: replacing their target would cut it off from the
        // process that has it open.
        if path.starts_with("/dev") || path.starts_with("/proc") || !followed.is_file() {
            return match target_kind(&followed.file_type()) {
                Kind::Through | Kind::File => Ok(Target::Through(path.to_path_buf())),
                Kind::Dir => Err(refuse(path, "is a directory")),
                Kind::Other => Err(refuse(
                    path,
                    "is neither a regular file, a FIFO nor a character device; not written",
                )),
            };
        }
        let resolved = fs::canonicalize(path)
            .map_err(|_| refuse(path, "is a symbolic link to nothing; not written"))?;
        return target(&resolved);
    }
    match target_kind(&ty) {
        Kind::Dir => return Err(refuse(path, "is a directory")),
        Kind::Through => return Ok(Target::Through(path.to_path_buf())),
        Kind::Other => {
            return Err(refuse(
                path,
                "is neither a regular file, a FIFO nor a character device; not written",
            ));
        }
        Kind::File => {}
    }
    if meta.permissions().readonly() {
        return Err(io::Error::new(
            io::ErrorKind::PermissionDenied,
            format!("{}: is read-only; not replaced", path.display()),
        ));
    }
    Ok(Target::Replace(
        path.to_path_buf(),
        Some(meta.permissions()),
    ))
}

/// A temporary file name in the same directory as `path` (so `rename` is atomic).
fn temp_path_beside(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map_or_else(|| "output".to_owned(), |n| n.to_string_lossy().into_owned());
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// A file staged for replacement: its temporary, written in full.
#[derive(Debug)]
struct Staged {
    tmp: PathBuf,
    dest: PathBuf,
}

fn stage(dest: PathBuf, perms: Option<fs::Permissions>, bytes: &[u8]) -> io::Result<Staged> {
    let tmp = temp_path_beside(&dest);
    let written: io::Result<()> = (|| {
        let mut f = fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        if let Some(p) = perms {
            fs::set_permissions(&tmp, p)?;
        }
        Ok(())
    })();
    match written {
        Ok(()) => Ok(Staged { tmp, dest }),
        Err(e) => {
            let _ = fs::remove_file(&tmp);
            Err(io::Error::new(e.kind(), format!("{}: {e}", dest.display())))
        }
    }
}

fn write_through(path: &Path, bytes: &[u8]) -> io::Result<()> {
    // Appending: a `/dev/stdout` that the shell pointed at a regular file is added to,
    // not overwritten from its start.
    let mut f = fs::OpenOptions::new().append(true).open(path)?;
    f.write_all(bytes)?;
    f.flush()
}

/// Writes `bytes` to `path` by the policy of the module doc.
///
/// # Errors
/// The I/O error, or a refusal naming the path (read-only file, directory, link to
/// nothing); the temporary file is removed on failure and an existing file is kept.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> io::Result<()> {
    write_all_atomic(&[(path, bytes)])
}

/// Writes every `(path, bytes)` pair, all or none: every target is checked and every
/// replacement staged before any file changes.
///
/// # Errors
/// The first refusal or I/O error, naming its path; then no target has changed (a FIFO or
/// device written through is written last, after every staged file is in place).
pub fn write_all_atomic(files: &[(&Path, &[u8])]) -> io::Result<()> {
    stage_all(files)?.commit()
}

/// Files written in full to temporaries beside their targets, not yet in place:
/// [`StagedFiles::commit`] moves them there; dropping them uncommitted removes the
/// temporaries and leaves every target as it was. A command that writes several kinds of
/// output (files and a report directory, say) stages them all before it commits any.
#[derive(Debug)]
#[must_use = "staged files are removed unless committed"]
pub struct StagedFiles<'a> {
    staged: Vec<Staged>,
    through: Vec<(PathBuf, &'a [u8])>,
}

/// Checks every target and stages every replacement of `files` (see [`StagedFiles`]).
///
/// # Errors
/// The first refusal or I/O error, naming its path; nothing is left behind.
pub fn stage_all<'a>(files: &[(&Path, &'a [u8])]) -> io::Result<StagedFiles<'a>> {
    let targets: Vec<Target> = files
        .iter()
        .map(|(p, _)| target(p))
        .collect::<io::Result<_>>()?;
    let mut out = StagedFiles {
        staged: Vec::new(),
        through: Vec::new(),
    };
    for (t, (_, bytes)) in targets.into_iter().zip(files) {
        match t {
            Target::Through(p) => out.through.push((p, *bytes)),
            // On an error `out` is dropped, removing what was staged so far.
            Target::Replace(dest, perms) => out.staged.push(stage(dest, perms, bytes)?),
        }
    }
    Ok(out)
}

impl StagedFiles<'_> {
    /// Moves every staged file into place (renames within a directory), then writes the
    /// FIFOs and devices through.
    ///
    /// # Errors
    /// A rename or write that failed, naming its path; the temporaries not yet moved are
    /// removed.
    pub fn commit(mut self) -> io::Result<()> {
        let staged = std::mem::take(&mut self.staged);
        for (i, s) in staged.iter().enumerate() {
            if let Err(e) = fs::rename(&s.tmp, &s.dest) {
                for rest in &staged[i..] {
                    let _ = fs::remove_file(&rest.tmp);
                }
                return Err(io::Error::new(
                    e.kind(),
                    format!("{}: {e}", s.dest.display()),
                ));
            }
        }
        for (p, bytes) in std::mem::take(&mut self.through) {
            write_through(&p, bytes)
                .map_err(|e| io::Error::new(e.kind(), format!("{}: {e}", p.display())))?;
        }
        Ok(())
    }
}

impl Drop for StagedFiles<'_> {
    fn drop(&mut self) {
        for s in &self.staged {
            let _ = fs::remove_file(&s.tmp);
        }
    }
}

/// `path` made absolute with every symbolic link resolved, for telling whether two paths
/// name the same place or one lies inside the other. The part that does not exist yet is
/// appended as written, with `.` and `..` resolved by name.
#[must_use]
pub fn resolved(path: &Path) -> PathBuf {
    let absolute = if path.is_absolute() {
        path.to_path_buf()
    } else {
        std::env::current_dir()
            .unwrap_or_else(|_| PathBuf::from("/"))
            .join(path)
    };
    let mut existing = absolute.as_path();
    let mut rest = Vec::new();
    loop {
        if let Ok(real) = fs::canonicalize(existing) {
            let mut out = real;
            for part in rest.iter().rev() {
                match part {
                    std::path::Component::ParentDir => {
                        out.pop();
                    }
                    std::path::Component::CurDir => {}
                    other => out.push(other.as_os_str()),
                }
            }
            return out;
        }
        let Some(parent) = existing.parent() else {
            return absolute;
        };
        if let Some(last) = existing.components().next_back() {
            rest.push(last);
        }
        existing = parent;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("splinescope-files-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut n: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        n.sort();
        n
    }

    #[test]
    fn replaces_the_file_and_leaves_no_temporary_behind() {
        let dir = scratch("replace");
        let path = dir.join("out.txt");
        fs::write(&path, b"old contents").unwrap();
        write_atomic(&path, b"new").unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"new");
        assert_eq!(names(&dir), vec!["out.txt"]);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_failed_write_keeps_the_old_file() {
        let missing = std::env::temp_dir()
            .join(format!("splinescope-no-such-dir-{}", std::process::id()))
            .join("out.txt");
        assert!(write_atomic(&missing, b"x").is_err());
        assert!(!missing.exists());
    }

    #[test]
    fn several_files_are_written_all_or_none() {
        let dir = scratch("all");
        let a = dir.join("a.json");
        fs::write(&a, b"old a").unwrap();
        let bad = dir.join("missing").join("b.json");
        let err = write_all_atomic(&[(&a, b"new a"), (&bad, b"new b")]).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::NotFound);
        assert_eq!(
            fs::read(&a).unwrap(),
            b"old a",
            "the first file is untouched"
        );
        assert_eq!(names(&dir), vec!["a.json"], "no temporary left");
        let b = dir.join("b.json");
        write_all_atomic(&[(&a, b"new a"), (&b, b"new b")]).unwrap();
        assert_eq!(fs::read(&a).unwrap(), b"new a");
        assert_eq!(fs::read(&b).unwrap(), b"new b");
        fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn links_are_followed_and_read_only_files_and_directories_refused() {
        use std::os::unix::fs::PermissionsExt;
        let dir = scratch("special");
        let real = dir.join("real.txt");
        fs::write(&real, b"old").unwrap();
        fs::set_permissions(&real, fs::Permissions::from_mode(0o640)).unwrap();
        let link = dir.join("link.txt");
        std::os::unix::fs::symlink(&real, &link).unwrap();
        write_atomic(&link, b"via link").unwrap();
        assert!(
            fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(fs::read(&real).unwrap(), b"via link");
        assert_eq!(
            fs::metadata(&real).unwrap().permissions().mode() & 0o777,
            0o640,
            "the replaced file keeps its permissions"
        );
        let dangling = dir.join("dangling.txt");
        std::os::unix::fs::symlink(dir.join("nowhere"), &dangling).unwrap();
        let e = write_atomic(&dangling, b"x").unwrap_err();
        assert!(e.to_string().contains("symbolic link to nothing"), "{e}");
        let ro = dir.join("ro.txt");
        fs::write(&ro, b"keep").unwrap();
        fs::set_permissions(&ro, fs::Permissions::from_mode(0o444)).unwrap();
        let e = write_atomic(&ro, b"x").unwrap_err();
        assert!(e.to_string().contains("is read-only; not replaced"), "{e}");
        assert_eq!(fs::read(&ro).unwrap(), b"keep");
        let e = write_atomic(&dir, b"x").unwrap_err();
        assert!(e.to_string().contains("is a directory"), "{e}");
        fs::set_permissions(&ro, fs::Permissions::from_mode(0o644)).unwrap();
        fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_character_device_is_written_through_not_replaced() {
        let null = Path::new("/dev/null");
        if !null.exists() {
            panic!("/dev/null is missing on this system");
        }
        write_atomic(null, b"discarded").unwrap();
        use std::os::unix::fs::FileTypeExt;
        assert!(
            fs::symlink_metadata(null)
                .unwrap()
                .file_type()
                .is_char_device(),
            "/dev/null is still a device"
        );
    }
}
