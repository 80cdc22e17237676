//! No file of a crate imports, directly or through others, a file that imports it back —
//! counted strictly: a path that names an item through a re-export counts as an import of
//! the file that defines the item. The README's crate map claims 0 cycles; this test is
//! that claim. Approximate, from the text (no macro expansion): `use` trees and inline
//! `crate::`/`super::` paths outside comments and test modules; `pub use` lines are the
//! module's facade, not imports.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A module path inside its crate (`[]` for the crate root).
type Module = Vec<String>;

/// The `.rs` files under `src` (binaries apart) by module path.
fn modules(src: &Path) -> BTreeMap<Module, PathBuf> {
    let mut out = BTreeMap::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("read a source directory") {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                if path.file_name().is_some_and(|n| n != "bin") {
                    stack.push(path);
                }
            } else if path.extension().is_some_and(|e| e == "rs") {
                let rel = path
                    .strip_prefix(src)
                    .expect("under src")
                    .with_extension("");
                let mut module: Module = rel
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy().into_owned())
                    .collect();
                if matches!(
                    module.last().map(String::as_str),
                    Some("mod" | "lib" | "main")
                ) {
                    module.pop();
                }
                out.insert(module, path);
            }
        }
    }
    out
}

/// The code of a file without its test module and its comments.
fn code(text: &str) -> String {
    let text = text.split("#[cfg(test)]").next().unwrap_or_default();
    text.lines()
        .map(|l| match l.find("//") {
            Some(i) => &l[..i],
            None => l,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn is_ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// The names a file defines publicly (`pub fn`, `pub(crate) struct`, `macro_rules!`, …).
fn definitions(code: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for line in code.lines() {
        let mut words = line.split_whitespace().peekable();
        let Some(first) = words.next() else { continue };
        if first == "macro_rules!" {
            if let Some(name) = words.next() {
                out.insert(name.trim_end_matches('{').to_owned());
            }
            continue;
        }
        if !first.starts_with("pub") {
            continue;
        }
        // `pub [const|unsafe|async|extern …] KIND NAME`; anything else (`pub use`) is not
        // a definition.
        let mut kind = false;
        while let Some(w) = words.next() {
            let next_is_fn = words.peek().is_some_and(|n| *n == "fn" || *n == "unsafe");
            if matches!(
                w,
                "fn" | "struct" | "enum" | "trait" | "type" | "static" | "union" | "mod"
            ) || (w == "const" && !next_is_fn)
            {
                kind = true;
                break;
            }
            if !matches!(w, "unsafe" | "async" | "const" | "extern" | "\"C\"") {
                break;
            }
        }
        if !kind {
            continue;
        }
        if let Some(name) = words.next() {
            let name: String = name.chars().take_while(|c| is_ident(*c)).collect();
            if !name.is_empty() {
                out.insert(name);
            }
        }
    }
    out
}

/// `a::{b, c::{d, e as f}}` as `a::b`, `a::c::d`, `a::c::e`.
fn expand(tree: &str) -> Vec<String> {
    let tree: String = tree.split_whitespace().collect::<Vec<_>>().join(" ");
    let Some(open) = tree.find('{') else {
        let path = tree.split(" as ").next().unwrap_or_default().trim();
        return vec![path.to_owned()];
    };
    let prefix = &tree[..open];
    let close = tree.rfind('}').unwrap_or(tree.len());
    if close < open {
        return Vec::new();
    }
    let inner = &tree[open + 1..close];
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0, 0);
    for (i, ch) in inner.char_indices() {
        match ch {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&inner[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&inner[start..]);
    let mut out = Vec::new();
    for part in parts.iter().map(|p| p.trim()).filter(|p| !p.is_empty()) {
        for sub in expand(part) {
            if sub == "self" || sub == "*" {
                out.push(prefix.trim_end_matches("::").to_owned());
            } else {
                out.push(format!("{prefix}{sub}"));
            }
        }
    }
    out
}

/// The paths a file's code uses: its (non-`pub`) `use` trees and its inline `crate::…` /
/// `super::…` paths.
fn used_paths(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    let mut outside_use = String::new();
    while let Some(i) = rest.find("use ") {
        let before = &rest[..i];
        let line_start = before.rfind('\n').map_or(0, |n| n + 1);
        let lead = rest[line_start..i].trim();
        // A `use` statement starts its line (after `pub`, `pub(crate)`, …).
        let statement = lead.is_empty() || (lead.starts_with("pub") && !lead.contains(' '));
        let end = rest[i..].find(';').map_or(rest.len(), |e| i + e);
        if statement {
            let public = !lead.is_empty();
            outside_use.push_str(before);
            if !public {
                out.extend(expand(&rest[i + 4..end]));
            }
        } else {
            outside_use.push_str(&rest[..end]);
        }
        rest = &rest[(end + 1).min(rest.len())..];
    }
    outside_use.push_str(rest);
    for root in ["crate::", "super::"] {
        let mut from = 0;
        while let Some(i) = outside_use[from..].find(root) {
            let at = from + i;
            let boundary = at == 0 || !is_ident(outside_use[..at].chars().last().unwrap_or(' '));
            let path: String = outside_use[at..]
                .chars()
                .take_while(|c| is_ident(*c) || *c == ':')
                .collect();
            if boundary {
                out.push(path.trim_end_matches(':').to_owned());
            }
            from = at + path.len().max(1);
        }
    }
    out
}

/// The module a path written in `module` names, and the item after it, if any.
fn resolve(
    module: &Module,
    path: &str,
    files: &BTreeMap<Module, PathBuf>,
) -> Option<(Module, Option<String>)> {
    let mut bits: Vec<&str> = path.split("::").filter(|b| !b.is_empty()).collect();
    let mut base: Module = module.clone();
    match bits.first().copied() {
        Some("crate") => {
            base.clear();
            bits.remove(0);
        }
        Some("super") => {
            while bits.first() == Some(&"super") {
                base.pop()?;
                bits.remove(0);
            }
        }
        Some("self") => {
            bits.remove(0);
        }
        Some(first) => {
            // A path into a child module of this one; anything else is another crate.
            let mut child = module.clone();
            child.push(first.to_owned());
            if !files.contains_key(&child) {
                return None;
            }
        }
        None => return None,
    }
    let mut target = base;
    let mut k = 0;
    while k < bits.len() {
        let mut next = target.clone();
        next.push(bits[k].to_owned());
        if !files.contains_key(&next) {
            break;
        }
        target = next;
        k += 1;
    }
    files
        .contains_key(&target)
        .then(|| (target, bits.get(k).map(|s| (*s).to_owned())))
}

/// The cycles (strongly connected components of more than one file) of one crate.
fn cycles(src: &Path) -> Vec<Vec<PathBuf>> {
    let files = modules(src);
    let codes: BTreeMap<Module, String> = files
        .iter()
        .map(|(m, p)| {
            let text = std::fs::read_to_string(p).expect("read a source file");
            (m.clone(), code(&text))
        })
        .collect();
    let mut defined_in: BTreeMap<String, BTreeSet<Module>> = BTreeMap::new();
    for (m, c) in &codes {
        for name in definitions(c) {
            defined_in.entry(name).or_default().insert(m.clone());
        }
    }
    let mut edges: BTreeMap<Module, BTreeSet<Module>> = BTreeMap::new();
    for (m, c) in &codes {
        for path in used_paths(c) {
            let Some((mut target, item)) = resolve(m, &path, &files) else {
                continue;
            };
            // Strictly: an item reached through a module that does not define it (a
            // re-export) is an import of the one file that does.
            if let Some(where_) = item.and_then(|i| defined_in.get(&i))
                && !where_.contains(&target)
                && where_.len() == 1
            {
                target = where_.iter().next().expect("one").clone();
            }
            if &target != m {
                edges.entry(m.clone()).or_default().insert(target);
            }
        }
    }
    strongly_connected(&files.keys().cloned().collect::<Vec<_>>(), &edges)
        .into_iter()
        .filter(|c| c.len() > 1)
        .map(|c| c.iter().map(|m| files[m].clone()).collect())
        .collect()
}

/// Tarjan's strongly connected components, iteratively.
fn strongly_connected(
    nodes: &[Module],
    edges: &BTreeMap<Module, BTreeSet<Module>>,
) -> Vec<Vec<Module>> {
    let id: BTreeMap<&Module, usize> = nodes.iter().enumerate().map(|(i, m)| (m, i)).collect();
    let adj: Vec<Vec<usize>> = nodes
        .iter()
        .map(|m| {
            edges
                .get(m)
                .map(|s| s.iter().filter_map(|t| id.get(t).copied()).collect())
                .unwrap_or_default()
        })
        .collect();
    let n = nodes.len();
    let (mut index, mut low) = (vec![usize::MAX; n], vec![0; n]);
    let (mut on, mut stack, mut out, mut counter) = (vec![false; n], Vec::new(), Vec::new(), 0);
    for root in 0..n {
        if index[root] != usize::MAX {
            continue;
        }
        let mut work = vec![(root, 0_usize)];
        while let Some(&mut (v, ref mut next)) = work.last_mut() {
            if *next == 0 && index[v] == usize::MAX {
                index[v] = counter;
                low[v] = counter;
                counter += 1;
                stack.push(v);
                on[v] = true;
            }
            if let Some(&w) = adj[v].get(*next) {
                *next += 1;
                if index[w] == usize::MAX {
                    work.push((w, 0));
                } else if on[w] {
                    low[v] = low[v].min(index[w]);
                }
                continue;
            }
            work.pop();
            if let Some(&(parent, _)) = work.last() {
                low[parent] = low[parent].min(low[v]);
            }
            if low[v] == index[v] {
                let mut comp = Vec::new();
                while let Some(w) = stack.pop() {
                    on[w] = false;
                    comp.push(nodes[w].clone());
                    if w == v {
                        break;
                    }
                }
                out.push(comp);
            }
        }
    }
    out
}

fn crate_sources() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut out = vec![root.join("src")];
    for entry in std::fs::read_dir(root.join("crates")).expect("crates/") {
        let src = entry.expect("an entry").path().join("src");
        if src.is_dir() {
            out.push(src);
        }
    }
    out
}

#[test]
fn no_file_imports_one_that_imports_it_back() {
    let sources = crate_sources();
    assert!(sources.len() >= 6, "the workspace's crates: {sources:?}");
    let found: Vec<Vec<PathBuf>> = sources.iter().flat_map(|s| cycles(s)).collect();
    assert!(
        found.is_empty(),
        "import cycles (a file reaching itself through its imports, re-exports followed):\n{}",
        found
            .iter()
            .map(|c| format!("  {c:?}"))
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// The check finds what it looks for: cycles through `use super::…`, through an inline
/// `crate::` path, and through a re-export, in a crate written for the purpose; and none
/// where the only way back is a `pub use` facade.
#[test]
fn the_check_finds_cycles_it_is_shown() {
    let dir = std::env::temp_dir().join(format!("splinescope-cycles-{}", std::process::id()));
    let src = dir.join("src");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(src.join("geom")).expect("create");
    let write = |p: &str, t: &str| std::fs::write(src.join(p), t).expect("write");
    write("lib.rs", "pub mod geom;\npub mod report;\n");
    write(
        "geom/mod.rs",
        "pub mod a;\npub mod b;\npub mod c;\npub use a::Alpha;\npub struct Root;\n",
    );
    write(
        "geom/a.rs",
        "use super::b::Beta;\npub struct Alpha(Beta);\n",
    );
    write("geom/b.rs", "pub struct Beta(crate::geom::a::Alpha);\n");
    // c reaches Alpha through the facade in mod.rs: strictly an import of a.rs, and a.rs
    // does not import c.rs, so no cycle with c.
    write("geom/c.rs", "use super::Alpha;\npub struct Gamma(Alpha);\n");
    // report and geom/c form a cycle through a re-export.
    write(
        "report.rs",
        "use crate::geom::c::Gamma;\npub struct Report(Gamma);\npub struct Delta;\n",
    );
    let found = cycles(&src);
    let names: Vec<Vec<String>> = found
        .iter()
        .map(|c| {
            let mut v: Vec<String> = c
                .iter()
                .map(|p| p.strip_prefix(&src).unwrap().display().to_string())
                .collect();
            v.sort();
            v
        })
        .collect();
    assert_eq!(
        names,
        vec![vec!["geom/a.rs".to_owned(), "geom/b.rs".to_owned()]]
    );
    // Close a cycle through the facade: c uses report, report uses c.
    write(
        "geom/c.rs",
        "use super::Alpha;\nuse crate::report::Delta;\npub struct Gamma(Alpha, Delta);\n",
    );
    assert_eq!(cycles(&src).len(), 2, "{:?}", cycles(&src));
    let _ = std::fs::remove_dir_all(&dir);
}
