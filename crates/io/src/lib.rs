//! splinescope's I/O policy, shared by every layer that reads input or writes files: the
//! documented input [`limits`] (each checked before anything is allocated, each raised by
//! an environment variable, a breach an error naming the value, the limit and the
//! variable) and the output-path policy of [`files`] (atomic replacement, all-or-none
//! groups, links and devices handled on purpose).
//!
//! What it may use: the standard library and thiserror — nothing of splinescope, no
//! format, no GPU. Every other crate of the workspace may use it.
//!
//! ```
//! use splinescope_io::{files, limits};
//!
//! let dir = std::env::temp_dir().join(format!("splinescope-io-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! let path = dir.join("out.txt");
//! files::write_atomic(&path, b"curves").unwrap();
//! assert_eq!(std::fs::read(&path).unwrap(), b"curves");
//! // A request over a limit is an error naming the limit's variable.
//! let e = limits::CURVES.check(u64::MAX).unwrap_err();
//! assert!(e.to_string().contains(limits::CURVES.var), "{e}");
//! std::fs::remove_dir_all(&dir).unwrap();
//! ```

#![forbid(unsafe_code)]

pub mod files;
pub mod limits;
