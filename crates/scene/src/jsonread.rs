//! Reading JSON documents (scenes, solve requests) with the path of every value, so that
//! each error names exactly where it is (`curves[3].points[2][1]: not a finite number`).
//!
//! JSON has no NaN or Infinity; files written by tools that emit them anyway (Python's
//! `json.dumps` does) get a `not a finite number` error at the value's path rather than a
//! bare syntax error. A key that appears twice in one object is an error at its path
//! (JSON parsers disagree on which copy wins, so neither is guessed).

use std::collections::HashSet;

use glam::DVec3;
use serde::de::{DeserializeSeed, Error as _, MapAccess, SeqAccess, Visitor};
use serde_json::{Map, Number, Value};

use crate::format::{SceneError, SceneErrorKind};
use splinescope_encoding::Color;

/// The number literals that stand for `NaN`, `Infinity` and `-Infinity` once rewritten
/// (numbers so large that they are not finite as `f64` either, so a value that happens to
/// be written this way is refused all the same; only its description differs).
const NON_FINITE_LITERALS: [(&str, &str); 4] = [
    ("-Infinity", "-1e9999999999999999992"),
    ("+Infinity", "1e9999999999999999992"),
    ("Infinity", "1e9999999999999999992"),
    ("NaN", "1e9999999999999999991"),
];

/// How a non-finite number is named in messages: `NaN`/`Infinity` for the rewritten
/// literals, the number's own text otherwise.
pub(crate) fn describe_number(n: &Number) -> String {
    let text = n.to_string();
    // serde_json writes the exponent with its sign (`1e+999`).
    let plain = text.replace("e+", "e");
    NON_FINITE_LITERALS
        .iter()
        .find(|(_, lit)| *lit == plain)
        .map_or(text, |(word, _)| word.trim_start_matches('+').to_owned())
}

/// Parses JSON text into a value. Bare `NaN`/`Infinity` literals (not JSON, but written by
/// some tools) become numbers that are not finite, so that readers report them at their
/// path.
///
/// # Errors
/// The syntax error (of the whole document), with line and column; a duplicated key at
/// its path.
pub(crate) fn parse_document(text: &str) -> Result<Value, SceneError> {
    let (value, parsed): (Value, std::borrow::Cow<'_, str>) = match serde_json::from_str(text) {
        Ok(v) => (v, text.into()),
        Err(original) => {
            // Retry with NaN/Infinity literals rewritten, so that the decoder can name
            // their path; otherwise report the original syntax error.
            match mark_non_finite_literals(text) {
                Some(m) => (
                    serde_json::from_str(&m).map_err(|_| syntax_error(&original))?,
                    m.into(),
                ),
                None => return Err(syntax_error(&original)),
            }
        }
    };
    check_duplicate_keys(&parsed)?;
    Ok(value)
}

/// Separates the parts of a duplicate-key report inside a serde error message.
const DUP_MARK: char = '\u{1}';

/// Walks the document once more, failing at the first object key seen twice.
fn check_duplicate_keys(text: &str) -> Result<(), SceneError> {
    struct Seed<'p>(&'p str);
    struct Walk(String);
    impl<'de> DeserializeSeed<'de> for Seed<'_> {
        type Value = ();
        fn deserialize<D: serde::Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
            d.deserialize_any(Walk(self.0.to_owned()))
        }
    }
    impl<'de> Visitor<'de> for Walk {
        type Value = ();
        fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.write_str("any JSON value")
        }
        fn visit_bool<E>(self, _: bool) -> Result<(), E> {
            Ok(())
        }
        fn visit_i64<E>(self, _: i64) -> Result<(), E> {
            Ok(())
        }
        fn visit_u64<E>(self, _: u64) -> Result<(), E> {
            Ok(())
        }
        fn visit_f64<E>(self, _: f64) -> Result<(), E> {
            Ok(())
        }
        fn visit_str<E>(self, _: &str) -> Result<(), E> {
            Ok(())
        }
        fn visit_unit<E>(self) -> Result<(), E> {
            Ok(())
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
            let mut i = 0usize;
            while seq
                .next_element_seed(Seed(&format!("{}[{i}]", self.0)))?
                .is_some()
            {
                i += 1;
            }
            Ok(())
        }
        fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
            let mut seen = HashSet::new();
            while let Some(key) = map.next_key::<String>()? {
                let path = if self.0.is_empty() {
                    key.clone()
                } else {
                    format!("{}.{key}", self.0)
                };
                if !seen.insert(key.clone()) {
                    return Err(A::Error::custom(format!(
                        "{DUP_MARK}{path}{DUP_MARK}{key}{DUP_MARK}"
                    )));
                }
                map.next_value_seed(Seed(&path))?;
            }
            Ok(())
        }
    }
    let mut de = serde_json::Deserializer::from_str(text);
    match Seed("").deserialize(&mut de) {
        Ok(()) => Ok(()),
        Err(e) => {
            let message = e.to_string();
            let mut parts = message.split(DUP_MARK).skip(1);
            match (parts.next(), parts.next()) {
                (Some(path), Some(key)) => Err(SceneError::new(
                    path,
                    SceneErrorKind::Invalid(format!(
                        "the key {key:?} appears more than once in this object"
                    )),
                )),
                _ => Err(syntax_error(&e)),
            }
        }
    }
}

fn syntax_error(e: &serde_json::Error) -> SceneError {
    let full = e.to_string();
    let message = match full.rfind(" at line ") {
        Some(i) => full[..i].to_owned(),
        None => full,
    };
    SceneError::new(
        "",
        SceneErrorKind::Syntax {
            line: e.line(),
            column: e.column(),
            message,
        },
    )
}

/// Rewrites the bare words `NaN`, `Infinity`, `-Infinity`, `+Infinity` outside strings
/// into number literals that are not finite ([`NON_FINITE_LITERALS`]). `None` when there
/// are none.
fn mark_non_finite_literals(text: &str) -> Option<String> {
    let mut out = String::with_capacity(text.len() + 16);
    let mut in_string = false;
    let mut escaped = false;
    let mut changed = false;
    let mut rest = text;
    while let Some(c) = rest.chars().next() {
        if in_string {
            if escaped {
                escaped = false;
            } else if c == '\\' {
                escaped = true;
            } else if c == '"' {
                in_string = false;
            }
        } else if c == '"' {
            in_string = true;
        } else if let Some((word, literal)) = NON_FINITE_LITERALS
            .iter()
            .find(|(w, _)| rest.starts_with(*w))
        {
            out.push_str(literal);
            rest = &rest[word.len()..];
            changed = true;
            continue;
        }
        out.push(c);
        rest = &rest[c.len_utf8()..];
    }
    changed.then_some(out)
}

/// A JSON value with its path from the document root.
pub(crate) struct Node<'a> {
    pub(crate) value: &'a Value,
    pub(crate) path: String,
}

/// A JSON object whose keys were checked against the allowed ones.
pub(crate) struct Obj<'a> {
    pub(crate) map: &'a Map<String, Value>,
    pub(crate) path: String,
}

pub(crate) fn describe(v: &Value) -> String {
    match v {
        Value::Null => "null".into(),
        Value::Bool(b) => format!("the boolean {b}"),
        Value::Number(n) if n.as_f64().is_none_or(|x| !x.is_finite()) => describe_number(n),
        Value::Number(n) => format!("the number {n}"),
        Value::String(s) => format!("the string {s:?}"),
        Value::Array(a) => format!("an array of {} items", a.len()),
        Value::Object(_) => "an object".into(),
    }
}

impl<'a> Node<'a> {
    pub(crate) fn root(value: &'a Value) -> Node<'a> {
        Node {
            value,
            path: String::new(),
        }
    }

    /// The node's JSON path (empty for the document itself).
    pub(crate) fn display_path(&self) -> String {
        self.path.clone()
    }

    pub(crate) fn err(&self, kind: SceneErrorKind) -> SceneError {
        SceneError::new(self.display_path(), kind)
    }

    pub(crate) fn invalid(&self, message: impl Into<String>) -> SceneError {
        self.err(SceneErrorKind::Invalid(message.into()))
    }

    pub(crate) fn wrong_type(&self, expected: &str) -> SceneError {
        if let Value::Number(n) = self.value
            && n.as_f64().is_none_or(|x| !x.is_finite())
        {
            return self.err(SceneErrorKind::NotFinite(describe_number(n)));
        }
        self.err(SceneErrorKind::WrongType {
            expected: expected.into(),
            found: describe(self.value),
        })
    }

    pub(crate) fn index(&self, i: usize, value: &'a Value) -> Node<'a> {
        Node {
            value,
            path: format!("{}[{i}]", self.path),
        }
    }

    pub(crate) fn object(&self, allowed: &[&str]) -> Result<Obj<'a>, SceneError> {
        let Value::Object(map) = self.value else {
            return Err(self.wrong_type("an object"));
        };
        let obj = Obj {
            map,
            path: self.path.clone(),
        };
        for key in map.keys() {
            if !allowed.contains(&key.as_str()) {
                return Err(obj.node(key, &map[key]).err(SceneErrorKind::UnknownField {
                    expected: allowed.join(", "),
                }));
            }
        }
        Ok(obj)
    }

    pub(crate) fn array(&self) -> Result<Vec<Node<'a>>, SceneError> {
        let Value::Array(items) = self.value else {
            return Err(self.wrong_type("an array"));
        };
        Ok(items
            .iter()
            .enumerate()
            .map(|(i, v)| self.index(i, v))
            .collect())
    }

    pub(crate) fn f64(&self) -> Result<f64, SceneError> {
        let Value::Number(n) = self.value else {
            return Err(self.wrong_type("a number"));
        };
        match n.as_f64() {
            Some(x) if x.is_finite() => Ok(x),
            _ => Err(self.err(SceneErrorKind::NotFinite(describe_number(n)))),
        }
    }

    pub(crate) fn positive_f64(&self) -> Result<f64, SceneError> {
        let x = self.f64()?;
        if x > 0.0 {
            Ok(x)
        } else {
            Err(self.invalid(format!("must be greater than 0, found {x}")))
        }
    }

    pub(crate) fn u32_in(&self, lo: u32, hi: u32) -> Result<u32, SceneError> {
        let Value::Number(n) = self.value else {
            return Err(self.wrong_type("an integer"));
        };
        let Some(v) = n.as_u64() else {
            return Err(self.wrong_type(&format!("an integer between {lo} and {hi}")));
        };
        if v < u64::from(lo) || v > u64::from(hi) {
            return Err(self.invalid(format!("{v} is not between {lo} and {hi}")));
        }
        Ok(v as u32)
    }

    pub(crate) fn bool(&self) -> Result<bool, SceneError> {
        self.value
            .as_bool()
            .ok_or_else(|| self.wrong_type("true or false"))
    }

    pub(crate) fn string(&self) -> Result<&'a str, SceneError> {
        match self.value {
            Value::String(s) => Ok(s),
            _ => Err(self.wrong_type("a string")),
        }
    }

    /// A string shown to people (a name, a label): no control character (`U+0000`–`U+001F`,
    /// `U+007F`–`U+009F`) and no Unicode noncharacter (`U+FFFE`, `U+FDD0`, …), which no text
    /// format of the figures can carry (XML 1.0 forbids them even escaped).
    pub(crate) fn text(&self) -> Result<&'a str, SceneError> {
        let s = self.string()?;
        match s.char_indices().find(|(_, c)| !crate::text::displayable(*c)) {
            None => Ok(s),
            Some((at, c)) => Err(self.invalid(format!(
                "the character U+{:04X} at byte {at} is a control character or a noncharacter; names and labels are text to display",
                u32::from(c)
            ))),
        }
    }

    /// A point: an array of 2 (`z = 0`) or 3 finite numbers.
    pub(crate) fn point(&self) -> Result<DVec3, SceneError> {
        let items = self.array()?;
        if !(2..=3).contains(&items.len()) {
            return Err(self.invalid(format!(
                "a point has 2 or 3 coordinates, found {}",
                items.len()
            )));
        }
        let mut p = [0.0; 3];
        for (slot, item) in p.iter_mut().zip(&items) {
            *slot = item.f64()?;
        }
        Ok(DVec3::from_array(p))
    }

    pub(crate) fn numbers(&self) -> Result<Vec<f64>, SceneError> {
        self.array()?.iter().map(Node::f64).collect()
    }

    pub(crate) fn points(&self, min: usize) -> Result<Vec<DVec3>, SceneError> {
        if let Value::Array(a) = self.value {
            splinescope_io::limits::POINTS
                .check(a.len() as u64)
                .map_err(|e| self.invalid(e.to_string()))?;
        }
        let items = self.array()?;
        if items.len() < min {
            return Err(self.invalid(format!(
                "needs at least {min} point{}, found {}",
                if min == 1 { "" } else { "s" },
                items.len()
            )));
        }
        items.iter().map(Node::point).collect()
    }

    pub(crate) fn color(&self) -> Result<Color, SceneError> {
        match self.value {
            Value::String(s) => parse_hex_color(s)
                .ok_or_else(|| {
                    self.invalid(format!(
                        "{s:?} is not a colour (use \"#rrggbb\", \"#rrggbbaa\" or [r, g, b(, a)] in [0, 1])"
                    ))
                }),
            Value::Array(_) => {
                let items = self.array()?;
                if !(3..=4).contains(&items.len()) {
                    return Err(self.invalid(format!(
                        "a colour has 3 or 4 channels, found {}",
                        items.len()
                    )));
                }
                let mut c = [1.0_f32; 4];
                for (slot, item) in c.iter_mut().zip(&items) {
                    let v = item.f64()?;
                    if !(0.0..=1.0).contains(&v) {
                        return Err(item.invalid(format!("colour channel {v} is outside [0, 1]")));
                    }
                    *slot = v as f32;
                }
                Ok(Color(c))
            }
            _ => Err(self.wrong_type("a colour (\"#rrggbb\" or [r, g, b(, a)])")),
        }
    }
}

impl<'a> Obj<'a> {
    pub(crate) fn node(&self, key: &str, value: &'a Value) -> Node<'a> {
        Node {
            value,
            path: if self.path.is_empty() {
                key.to_owned()
            } else {
                format!("{}.{key}", self.path)
            },
        }
    }

    pub(crate) fn get(&self, key: &str) -> Option<Node<'a>> {
        self.map.get(key).map(|v| self.node(key, v))
    }

    pub(crate) fn req(&self, key: &str) -> Result<Node<'a>, SceneError> {
        self.get(key).ok_or_else(|| {
            SceneError::new(
                if self.path.is_empty() {
                    key.to_owned()
                } else {
                    format!("{}.{key}", self.path)
                },
                SceneErrorKind::Missing,
            )
        })
    }
}

pub(crate) fn parse_hex_color(s: &str) -> Option<Color> {
    let hex = s.strip_prefix('#')?;
    if !(hex.len() == 6 || hex.len() == 8) || !hex.chars().all(|c| c.is_ascii_hexdigit()) {
        return None;
    }
    let mut bytes = [255_u8; 4];
    for (i, slot) in bytes.iter_mut().enumerate().take(hex.len() / 2) {
        *slot = u8::from_str_radix(&hex[2 * i..2 * i + 2], 16).ok()?;
    }
    Some(Color::from_rgba8(bytes))
}
