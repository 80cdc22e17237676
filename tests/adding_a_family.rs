//! A new family touches its math file, its presentation file and its codec — three files
//! of one name in three crates — and its row in the family table; nothing else lists the
//! families. This test reads the sources: every row of `family_table!` has its
//! `impl Family` in `crates/core/src/geom/<f>.rs`, its `impl Present` in
//! `crates/present/src/family/<f>.rs` and its `impl Codec` / `impl Written` in
//! `crates/scene/src/format/codec/<f>.rs`; and no other source file names every
//! variant (an exhaustive list kept by hand elsewhere would need a fourth edit).

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

use splinescope_core::geom::Curve;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn read(path: &Path) -> String {
    fs::read_to_string(path).unwrap_or_else(|e| panic!("read {}: {e}", path.display()))
}

/// `(Variant, Type, "name")` for every row of the family table, read from its source.
fn table_rows() -> Vec<(String, String, String)> {
    let text = read(&root().join("crates/core/src/geom/curve.rs"));
    let start = text
        .find("macro_rules! family_table")
        .expect("the family table");
    let body = &text[start..start + text[start..].find("\n}\n").expect("its end")];
    body.lines()
        .filter_map(|line| {
            let line = line.trim();
            let (variant, rest) = line.split_once("($crate::geom::")?;
            let (ty, rest) = rest.split_once(") = \"")?;
            let name = rest.strip_suffix("\",")?;
            Some((variant.to_owned(), ty.to_owned(), name.to_owned()))
        })
        .collect()
}

/// The `.rs` files under `dir` (recursively), without test files.
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.expect("entry").path();
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if path.is_dir() {
            if name != "tests" && name != "target" {
                sources(&path, out);
            }
        } else if name.ends_with(".rs") && !name.ends_with("tests.rs") {
            out.push(path);
        }
    }
}

/// The files of `dir` whose text contains `needle`.
fn files_with(dir: &str, needle: &str) -> Vec<String> {
    let mut files = Vec::new();
    sources(&root().join(dir), &mut files);
    files
        .into_iter()
        .filter(|f| read(f).contains(needle))
        .map(|f| {
            f.strip_prefix(root())
                .expect("under the root")
                .display()
                .to_string()
        })
        .collect()
}

#[test]
fn each_family_is_three_files_of_one_name() {
    let rows = table_rows();
    let names: Vec<&str> = rows.iter().map(|(_, _, n)| n.as_str()).collect();
    // The rows read from the source are the families the library knows.
    assert_eq!(
        names,
        Curve::FAMILY_NAMES,
        "family table as read from curve.rs"
    );
    for (_, ty, name) in &rows {
        let math = files_with("crates/core/src/geom", &format!("impl Family for {ty} {{"));
        assert_eq!(math.len(), 1, "{name}: `impl Family for {ty}` in {math:?}");
        let stem = Path::new(&math[0])
            .file_stem()
            .and_then(|s| s.to_str())
            .expect("a file name")
            .to_owned();
        // Bézier is the one family whose Family side has a file of its own: the
        // lowering imports its math file (`BezierSegment`), and the trait imports the
        // lowering.
        let stem = if stem == "family" {
            "bezier".to_owned()
        } else {
            stem
        };
        let present = format!("crates/present/src/family/{stem}.rs");
        assert!(
            read(&root().join(&present)).contains(&format!("impl Present for {ty} {{")),
            "{name}: no `impl Present for {ty}` in {present}"
        );
        let codec = format!("crates/scene/src/format/codec/{stem}.rs");
        let codec_text = read(&root().join(&codec));
        for needle in [
            format!("impl Codec for {ty} {{"),
            format!("impl Written for {ty} {{"),
        ] {
            assert!(
                codec_text.contains(&needle),
                "{name}: no `{needle}` in {codec}"
            );
        }
    }
}

#[test]
fn no_other_file_lists_every_family() {
    let rows = table_rows();
    assert!(rows.len() >= 7, "the table read: {rows:?}");
    let allowed: BTreeSet<&str> = ["crates/core/src/geom/curve.rs"].into();
    let mut files = Vec::new();
    for dir in ["crates", "src"] {
        sources(&root().join(dir), &mut files);
    }
    let mut listing = Vec::new();
    for f in &files {
        let text = read(f);
        // Code under `#[cfg(test)]` may name families freely.
        let text = text.split("#[cfg(test)]").next().unwrap_or("");
        let every = rows
            .iter()
            .all(|(variant, _, _)| text.contains(&format!("Curve::{variant}(")));
        let rel = f
            .strip_prefix(root())
            .expect("under the root")
            .display()
            .to_string();
        if every && !allowed.contains(rel.as_str()) {
            listing.push(rel);
        }
    }
    assert!(
        listing.is_empty(),
        "these files match on every family by hand; generate the list from \
         `family_table!` or dispatch with `each_family!`: {listing:?}"
    );
    // The check sees a list when there is one: curve.rs's `each_family!` names them all.
    let curve = read(&root().join("crates/core/src/geom/curve.rs"));
    assert!(
        rows.iter()
            .all(|(v, _, _)| curve.contains(&format!("$crate::geom::Curve::{v}(")))
    );
}
