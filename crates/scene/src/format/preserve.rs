//! Writing a scene in the form of the file it was read from, so that a diff of the saved
//! file shows only what was edited.
//!
//! The original text is scanned once for the byte span of every value. Curves that did
//! not change are copied as they were written (their styles left implicit, their knot
//! shorthands, number spellings, comments-free layout and key order); a changed curve
//! keeps every field that still means the same (a `clamped_uniform` knot vector, an
//! omitted style) and, inside arrays of the same length, every unchanged element, so a
//! moved control point rewrites that point's numbers only. Added curves are written in
//! full; deleted ones leave with their separator. Every result is read back and compared
//! with the scene: anything that would not read back equal falls back to the full writer
//! ([`to_json_string`]).

use std::ops::Range;

use serde_json::Value;

use crate::jsonread::Node;

use super::json::{curve_doc, decode_curve, from_json_str, to_json_string, write_pretty};
use super::{Scene, SceneCurve, Style};

/// A value of the original text: its byte span and, for arrays and objects, its
/// children's.
#[derive(Debug)]
enum Spanned {
    Scalar(Range<usize>),
    Array(Range<usize>, Vec<Spanned>),
    Object(Range<usize>, Vec<(String, Spanned)>),
}

impl Spanned {
    fn range(&self) -> Range<usize> {
        match self {
            Spanned::Scalar(r) | Spanned::Array(r, _) | Spanned::Object(r, _) => r.clone(),
        }
    }

    fn member(&self, key: &str) -> Option<&Spanned> {
        match self {
            Spanned::Object(_, members) => members.iter().find(|(k, _)| k == key).map(|(_, v)| v),
            _ => None,
        }
    }
}

/// Scans the JSON text `t` (already known to be valid) for spans.
struct Scanner<'a> {
    t: &'a [u8],
    text: &'a str,
    at: usize,
}

impl Scanner<'_> {
    fn ws(&mut self) {
        while self.at < self.t.len() && self.t[self.at].is_ascii_whitespace() {
            self.at += 1;
        }
    }

    fn string_end(&mut self) -> Option<()> {
        // At the opening quote.
        self.at += 1;
        while self.at < self.t.len() {
            match self.t[self.at] {
                b'\\' => self.at += 2,
                b'"' => {
                    self.at += 1;
                    return Some(());
                }
                _ => self.at += 1,
            }
        }
        None
    }

    fn value(&mut self, depth: usize) -> Option<Spanned> {
        if depth > 256 {
            return None;
        }
        self.ws();
        let start = self.at;
        match *self.t.get(self.at)? {
            b'{' => {
                self.at += 1;
                let mut members = Vec::new();
                loop {
                    self.ws();
                    match *self.t.get(self.at)? {
                        b'}' => {
                            self.at += 1;
                            break;
                        }
                        b',' => self.at += 1,
                        b'"' => {
                            let key_start = self.at;
                            self.string_end()?;
                            let key: String =
                                serde_json::from_str(&self.text[key_start..self.at]).ok()?;
                            self.ws();
                            if self.t.get(self.at) != Some(&b':') {
                                return None;
                            }
                            self.at += 1;
                            members.push((key, self.value(depth + 1)?));
                        }
                        _ => return None,
                    }
                }
                Some(Spanned::Object(start..self.at, members))
            }
            b'[' => {
                self.at += 1;
                let mut items = Vec::new();
                loop {
                    self.ws();
                    match *self.t.get(self.at)? {
                        b']' => {
                            self.at += 1;
                            break;
                        }
                        b',' => self.at += 1,
                        _ => items.push(self.value(depth + 1)?),
                    }
                }
                Some(Spanned::Array(start..self.at, items))
            }
            b'"' => {
                self.string_end()?;
                Some(Spanned::Scalar(start..self.at))
            }
            _ => {
                while self.at < self.t.len()
                    && !matches!(self.t[self.at], b',' | b']' | b'}')
                    && !self.t[self.at].is_ascii_whitespace()
                {
                    self.at += 1;
                }
                (self.at > start).then_some(Spanned::Scalar(start..self.at))
            }
        }
    }
}

fn scan(text: &str) -> Option<Spanned> {
    let mut s = Scanner {
        t: text.as_bytes(),
        text,
        at: 0,
    };
    s.value(0)
}

/// Whether two JSON values say the same thing, numbers compared as the `f64` they read
/// as (`1` and `1.0` alike, `0` and `-0` not).
fn same(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => match (x.as_f64(), y.as_f64()) {
            (Some(x), Some(y)) => x.to_bits() == y.to_bits(),
            _ => x == y,
        },
        (Value::Array(x), Value::Array(y)) => {
            // A point written [x, y, 0] is the point [x, y].
            let planar = |long: &[Value], short: &[Value]| {
                long.len() == 3
                    && short.len() == 2
                    && long[2].as_f64().is_some_and(|z| z.to_bits() == 0)
                    && long[..2].iter().zip(short).all(|(a, b)| same(a, b))
            };
            (x.len() == y.len() && x.iter().zip(y).all(|(a, b)| same(a, b)))
                || planar(x, y)
                || planar(y, x)
        }
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len() && x.iter().all(|(k, a)| y.get(k).is_some_and(|b| same(a, b)))
        }
        _ => a == b,
    }
}

/// The column of byte `at` (spaces before it on its line).
fn column(text: &str, at: usize) -> usize {
    let line_start = text[..at].rfind('\n').map_or(0, |i| i + 1);
    at - line_start
}

/// The indentation (leading spaces) of the line holding byte `at`.
fn line_indent(text: &str, at: usize) -> usize {
    let line_start = text[..at].rfind('\n').map_or(0, |i| i + 1);
    text[line_start..at].len() - text[line_start..at].trim_start_matches(' ').len()
}

/// `new` written where `old` (a span of `text`) was: `old`'s text where they say the
/// same; inside arrays of the same length and objects, element by element (layout and
/// separators kept); elsewhere `new` written out.
fn merge(text: &str, old: &Spanned, new: &Value) -> String {
    let range = old.range();
    let old_text = &text[range.clone()];
    if serde_json::from_str::<Value>(old_text).is_ok_and(|v| same(&v, new)) {
        return old_text.to_owned();
    }
    match (old, new) {
        (Spanned::Array(_, items), Value::Array(values))
            if items.len() == values.len() && !items.is_empty() =>
        {
            splice(
                text,
                &range,
                items
                    .iter()
                    .zip(values)
                    .map(|(o, n)| (o.range(), merge(text, o, n))),
            )
        }
        (Spanned::Object(_, members), Value::Object(map))
            if members.len() == map.len() && members.iter().all(|(k, _)| map.contains_key(k)) =>
        {
            splice(
                text,
                &range,
                members
                    .iter()
                    .map(|(k, o)| (o.range(), merge(text, o, &map[k]))),
            )
        }
        _ => written(new, column(text, range.start)),
    }
}

/// `text[range]` with each of the (ascending, disjoint) `parts` replaced.
fn splice(
    text: &str,
    range: &Range<usize>,
    parts: impl IntoIterator<Item = (Range<usize>, String)>,
) -> String {
    let mut out = String::new();
    let mut at = range.start;
    for (r, replacement) in parts {
        out.push_str(&text[at..r.start]);
        out.push_str(&replacement);
        at = r.end;
    }
    out.push_str(&text[at..range.end]);
    out
}

/// `v` as the full writer writes it, for a value starting at column `indent`.
fn written(v: &Value, indent: usize) -> String {
    let mut out = String::new();
    write_pretty(v, indent, &mut out);
    out
}

/// Whether curve text, read as curve `index` of a scene, is `curve` as a file says it
/// (colours as the 8-bit hex they are written in).
fn reads_as(text: &str, index: usize, curve: &SceneCurve) -> bool {
    decode(text, index).is_some_and(|c| same_curve(&c, curve))
}

fn decode(text: &str, index: usize) -> Option<SceneCurve> {
    let value: Value = serde_json::from_str(text).ok()?;
    decode_curve(&Node::root(&value), index).ok()
}

fn same_curve(a: &SceneCurve, b: &SceneCurve) -> bool {
    a.curve == b.curve
        && a.name == b.name
        && Style {
            color: b.style.color,
            ..a.style
        } == b.style
        && a.style.color.to_hex() == b.style.color.to_hex()
}

/// An object's text from `(key, value text)` members, laid out as the full writer does
/// at `indent`.
fn object_text(members: &[(String, String)], indent: usize) -> String {
    let pad = " ".repeat(indent + 2);
    let body: Vec<String> = members
        .iter()
        .filter(|(_, v)| !v.is_empty())
        .map(|(k, v)| format!("{pad}{}: {v}", Value::from(k.as_str())))
        .collect();
    if body.is_empty() {
        return "{}".into();
    }
    format!("{{\n{}\n{}}}", body.join(",\n"), " ".repeat(indent))
}

/// The style fields that differ from a curve's defaults, as `(key, value)`.
fn style_fields(style: &Style, defaults: &Style, full: &Value) -> Vec<(String, Value)> {
    let differs = |key: &str| match key {
        "color" => style.color.to_hex() != defaults.color.to_hex(),
        "width" => style.width != defaults.width,
        "width_units" => style.width_in_scene != defaults.width_in_scene,
        "polygon" => style.show_polygon != defaults.show_polygon,
        "points" => style.show_points != defaults.show_points,
        "samples" => style.samples != defaults.samples,
        "cap" => style.stroke.cap != defaults.stroke.cap,
        "join" => style.stroke.join != defaults.stroke.join,
        "miter_limit" => style.stroke.miter_limit != defaults.stroke.miter_limit,
        _ => true,
    };
    match full {
        Value::Object(map) => map
            .iter()
            .filter(|(k, _)| differs(k))
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect(),
        _ => Vec::new(),
    }
}

/// Curve `index` of the new scene (`curve`), written in the form of the original curve
/// `old`; `None` when no such text reads back as `curve`.
fn curve_text(text: &str, old: &Spanned, curve: &SceneCurve, index: usize) -> Option<String> {
    let range = old.range();
    let old_text = &text[range.clone()];
    if reads_as(old_text, index, curve) {
        return Some(old_text.to_owned());
    }
    let Spanned::Object(_, members) = old else {
        return None;
    };
    let Value::Object(new) = serde_json::to_value(curve_doc(curve)).ok()? else {
        return None;
    };
    let indent = column(text, range.start);
    // Start from the new curve's fields in the original's order (new ones after); a
    // field keeps its original text when the curve reads the same with it.
    let mut fields: Vec<(String, String)> = Vec::new();
    for (key, o) in members {
        if let Some(n) = new.get(key) {
            fields.push((key.clone(), merge(text, o, n)));
        }
    }
    for (key, n) in &new {
        if old.member(key).is_none() {
            fields.push((key.clone(), written(n, indent + 2)));
        }
    }
    for i in 0..fields.len() {
        let key = fields[i].0.clone();
        if let Some(o) = old.member(&key) {
            let kept = text[o.range()].to_owned();
            if kept != fields[i].1 {
                let mut trial = fields.clone();
                trial[i].1 = kept;
                if reads_as(&object_text(&trial, indent), index, curve) {
                    fields = trial;
                }
            }
        } else {
            // A field the original left out: out again if the curve reads the same.
            let mut trial = fields.clone();
            trial.remove(i);
            let without = decode(&object_text(&trial, indent), index);
            if without.as_ref().is_some_and(|w| same_curve(w, curve)) {
                fields[i].1.clear();
            } else if key == "style"
                && let Some(w) = without
            {
                // Only the style fields that differ from the defaults it would get.
                let minimal = style_fields(&curve.style, &w.style, &new[&key]);
                let inner: Vec<(String, String)> = minimal
                    .iter()
                    .map(|(k, v)| (k.clone(), written(v, indent + 4)))
                    .collect();
                fields[i].1 = object_text(&inner, indent + 2);
            }
        }
    }
    fields.retain(|(_, v)| !v.is_empty());
    // The same keys as the original: its layout too (a curve on one line stays there).
    let same_keys =
        fields.len() == members.len() && fields.iter().zip(members).all(|((a, _), (b, _))| a == b);
    let out = if same_keys {
        splice(
            text,
            &range,
            members
                .iter()
                .zip(&fields)
                .map(|((_, o), (_, v))| (o.range(), v.clone())),
        )
    } else {
        object_text(&fields, indent)
    };
    reads_as(&out, index, curve).then_some(out)
}

/// For each curve of `now`, the curve of `before` it continues (equal curves in order
/// first; then a changed curve takes the unmatched original between its neighbours'),
/// or `None` for an added curve.
fn match_curves(before: &[SceneCurve], now: &[SceneCurve]) -> Vec<Option<usize>> {
    let mut matched: Vec<Option<usize>> = vec![None; now.len()];
    let mut used = vec![false; before.len()];
    let mut next = 0;
    for (j, c) in now.iter().enumerate() {
        if let Some(i) = (next..before.len()).find(|&i| same_curve(&before[i], c)) {
            matched[j] = Some(i);
            used[i] = true;
            next = i + 1;
        }
    }
    let mut from = 0;
    for j in 0..now.len() {
        match matched[j] {
            Some(i) => from = i + 1,
            None => {
                let until = matched[j + 1..]
                    .iter()
                    .flatten()
                    .next()
                    .copied()
                    .unwrap_or(before.len());
                if let Some(i) = (from..until).find(|&i| !used[i]) {
                    matched[j] = Some(i);
                    used[i] = true;
                    from = i + 1;
                }
            }
        }
    }
    matched
}

/// `scene` written in the form of `original` (the text it was read from, or last saved
/// as): see the module's description. Falls back to [`to_json_string`] when `original`
/// is not a scene or differs from `scene` in more than its curves.
#[must_use]
pub fn to_json_string_keeping(scene: &Scene, original: &str) -> String {
    keep_form(scene, original).unwrap_or_else(|| to_json_string(scene))
}

fn keep_form(scene: &Scene, original: &str) -> Option<String> {
    let before = from_json_str(original).ok()?;
    let same_but_curves = Scene {
        curves: scene.curves.clone(),
        ..before.clone()
    };
    if &same_but_curves != scene {
        return None;
    }
    let root = scan(original)?;
    let Some(Spanned::Array(array, items)) = root.member("curves") else {
        return None;
    };
    if items.len() != before.curves.len() {
        return None;
    }
    let matched = match_curves(&before.curves, &scene.curves);
    let indent = items
        .first()
        .map_or(column(original, array.start) + 2, |i| {
            column(original, i.range().start)
        });
    let texts: Vec<String> = scene
        .curves
        .iter()
        .zip(&matched)
        .enumerate()
        .map(|(j, (c, m))| {
            m.and_then(|i| curve_text(original, &items[i], c, j))
                .unwrap_or_else(|| {
                    let doc = serde_json::to_value(curve_doc(c)).unwrap_or(Value::Null);
                    written(&doc, indent)
                })
        })
        .collect();
    let identity =
        matched.len() == items.len() && matched.iter().enumerate().all(|(j, m)| *m == Some(j));
    let curves = if identity {
        splice(
            original,
            array,
            items.iter().zip(texts).map(|(o, t)| (o.range(), t)),
        )
    } else if texts.is_empty() {
        "[]".into()
    } else {
        let pad = " ".repeat(indent);
        let close = " ".repeat(line_indent(original, array.start));
        format!("[\n{pad}{}\n{close}]", texts.join(&format!(",\n{pad}")))
    };
    let mut out = String::with_capacity(original.len());
    out.push_str(&original[..array.start]);
    out.push_str(&curves);
    out.push_str(&original[array.end..]);
    // The result must read back as the scene its file would be.
    let back = from_json_str(&out).ok()?;
    (to_json_string(&back) == to_json_string(scene)).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scanner_finds_every_span() {
        let text = r#" {"a": [1, 2.50, {"b": "x\"y"}], "c": null} "#;
        let root = scan(text).unwrap();
        let Spanned::Array(r, items) = root.member("a").unwrap() else {
            panic!()
        };
        assert_eq!(&text[r.clone()], r#"[1, 2.50, {"b": "x\"y"}]"#);
        assert_eq!(&text[items[1].range()], "2.50");
        assert_eq!(&text[items[2].member("b").unwrap().range()], r#""x\"y""#);
        assert_eq!(&text[root.member("c").unwrap().range()], "null");
    }
}
