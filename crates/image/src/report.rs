//! The regression report page (`splinescope regress --report`, the pytest plugin's
//! `--splinescope-summary=html`): one row per scene — its name, status, the comparison's
//! figures and message — with the reference, actual, diff and FLIP images beside it, as
//! PNG files in the same directory and an `index.html` that shows them.

use std::fmt::Write as _;
use std::path::Path;

use crate::RgbaImage;

/// One row of the report.
#[derive(Debug, Clone)]
pub struct ReportRow<'a> {
    /// The scene's (or test's) name; it also names the row's image files.
    pub name: String,
    /// `match`, `differs`, `missing`, `blessed` or `error` (the row's colour).
    pub status: String,
    /// The comparison's figures, or empty.
    pub figures: String,
    /// Why it failed, or empty.
    pub message: String,
    /// The reference, actual, diff and FLIP images, each when there is one.
    pub images: [Option<&'a RgbaImage>; 4],
}

/// The columns of the images, in [`ReportRow::images`]' order.
pub const IMAGE_KINDS: [&str; 4] = ["reference", "actual", "diff", "flip"];

/// `text` for HTML.
#[must_use]
pub fn html_escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The file stem a row's images take: its name's last path component without a `.json`
/// extension, characters other than letters, digits, `-`, `_` and `.` replaced by `_`.
#[must_use]
pub fn file_stem(name: &str) -> String {
    let last = name.rsplit(['/', '\\']).next().unwrap_or(name);
    let stem = last.strip_suffix(".json").unwrap_or(last);
    stem.chars()
        .map(|c| {
            if c.is_alphanumeric() || matches!(c, '-' | '_' | '.') {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Writes the report into `dir` (which must exist): each row's images as
/// `<stem>.<kind>.png` and `index.html`, headed by `summary`.
///
/// # Errors
/// A file that cannot be written.
pub fn write_report(dir: &Path, summary: &str, rows: &[ReportRow<'_>]) -> std::io::Result<()> {
    let mut body = String::new();
    for r in rows {
        let stem = file_stem(&r.name);
        let mut cells = String::new();
        for (kind, image) in IMAGE_KINDS.iter().zip(r.images) {
            match image {
                Some(image) => {
                    let file = format!("{stem}.{kind}.png");
                    image
                        .write_png(&dir.join(&file))
                        .map_err(|e| std::io::Error::other(e.to_string()))?;
                    let file = html_escape(&file);
                    let _ = write!(
                        cells,
                        "<td><a href=\"{file}\"><img src=\"{file}\" alt=\"{kind}\"></a></td>"
                    );
                }
                None => cells.push_str("<td class=\"none\">—</td>"),
            }
        }
        let status = html_escape(&r.status);
        let _ = writeln!(
            body,
            "<tr class=\"{status}\"><th>{}<br><span class=\"status\">{status}</span><p>{}</p><p>{}</p></th>{cells}</tr>",
            html_escape(&r.name),
            html_escape(&r.figures),
            html_escape(&r.message),
        );
    }
    let page = format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
<title>splinescope regression report</title><style>\
body{{font-family:sans-serif;margin:1em}}table{{border-collapse:collapse}}\
td,th{{border:1px solid #ccc;padding:4px;vertical-align:top;text-align:left}}\
th{{max-width:18em;font-weight:normal}}img{{width:240px;image-rendering:pixelated}}\
.status{{font-weight:bold}}.differs .status,.missing .status,.error .status{{color:#c00}}\
.match .status{{color:#080}}.blessed .status{{color:#a60}}</style></head><body>\
<h1>splinescope regression report</h1><p>{}</p>\
<table><tr><th>scene</th><th>reference</th><th>actual</th>\
<th>diff (red: a channel off by more than the tolerance)</th>\
<th>FLIP error (black: same, yellow: most different)</th></tr>\n{body}</table></body></html>\n",
        html_escape(summary)
    );
    splinescope_io::files::write_atomic(&dir.join("index.html"), page.as_bytes())
}

/// The figures of a comparison as a report row shows them.
#[must_use]
pub fn figures_text(c: &crate::compare::Comparison) -> String {
    format!(
        "{} px differ ({:.3} %), largest channel difference {}, FLIP mean {:.4}, max {:.4}",
        c.differing_pixels,
        c.differing_fraction * 100.0,
        c.max_channel_diff,
        c.flip_mean,
        c.flip_max
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn html_is_escaped_and_stems_are_file_names() {
        assert_eq!(
            html_escape("<a href=\"x\">&</a>"),
            "&lt;a href=&quot;x&quot;&gt;&amp;&lt;/a&gt;"
        );
        assert_eq!(file_stem("scenes/a b.json"), "a_b");
        assert_eq!(file_stem("test_x.py::test_y[gl]"), "test_x.py__test_y_gl_");
    }
}
