//! The exchange structure of ISO 10303-21 (a STEP file's syntax), parsed with `winnow`:
//! the `DATA` sections' instances `#id = NAME(params);` and complex instances
//! `#id = (A(params) B(params));`, each parameter an integer, real, string, enumeration
//! (`.T.`), reference (`#12`), `$`, `*`, binary, typed value (`LENGTH_MEASURE(2.)`) or
//! list. Comments (`/* … */`) may stand wherever whitespace may. Nothing is interpreted
//! here; [`super`] maps the entities it reads.

use std::collections::HashMap;

use winnow::ModalResult;
use winnow::Parser;
use winnow::combinator::{alt, cut_err, delimited, opt, preceded, repeat, separated};
use winnow::error::{ContextError, ErrMode, StrContext};
use winnow::token::{any, literal, one_of, take_till, take_until, take_while};

/// One parameter of a record.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// An integer.
    Int(i64),
    /// A real.
    Real(f64),
    /// A string (its `''` escapes resolved; other control directives left as written).
    Str(String),
    /// An enumeration's value, without its dots (`T`, `UNSPECIFIED`).
    Enum(String),
    /// A reference to instance `#id`.
    Ref(u64),
    /// `$`: no value.
    Null,
    /// `*`: a value derived elsewhere.
    Derived,
    /// A binary value (not kept).
    Binary,
    /// A list.
    List(Vec<Value>),
    /// A typed value: `NAME(params)`.
    Typed(String, Vec<Value>),
}

/// A record: an entity's name and its parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// The entity name, upper case as the file writes it.
    pub name: String,
    /// Its parameters.
    pub params: Vec<Value>,
}

/// An instance: one record, or the records of a complex instance.
#[derive(Debug, Clone, PartialEq)]
pub struct Instance {
    /// The records (one for a simple instance).
    pub records: Vec<Record>,
    /// The byte offset of its `#id` in the file.
    pub offset: usize,
}

/// What is wrong with a file's syntax, and where (a byte offset).
#[derive(Debug, Clone, PartialEq)]
pub struct SyntaxError {
    /// The byte offset.
    pub offset: usize,
    /// What is wrong.
    pub message: String,
}

/// Limits on what one file may hold.
#[derive(Debug, Clone, Copy)]
pub struct Bounds {
    /// Instances in all.
    pub instances: u64,
    /// Nesting of lists and typed values.
    pub depth: u64,
}

/// Whitespace and comments.
fn ws(i: &mut &str) -> ModalResult<()> {
    repeat(
        0..,
        alt((
            take_while(1.., |c: char| c.is_whitespace()).void(),
            ("/*", take_until(0.., "*/"), "*/").void(),
        )),
    )
    .parse_next(i)
}

fn keyword<'i>(i: &mut &'i str) -> ModalResult<&'i str> {
    (
        one_of(|c: char| c.is_ascii_alphabetic() || c == '!' || c == '_'),
        take_while(0.., |c: char| {
            c.is_ascii_alphanumeric() || c == '_' || c == '-'
        }),
    )
        .take()
        .parse_next(i)
}

fn number(i: &mut &str) -> ModalResult<Value> {
    let text = (
        opt(one_of(['+', '-'])),
        take_while(1.., |c: char| c.is_ascii_digit()),
        opt(('.', take_while(0.., |c: char| c.is_ascii_digit()))),
        opt((
            one_of(['E', 'e']),
            opt(one_of(['+', '-'])),
            take_while(1.., |c: char| c.is_ascii_digit()),
        )),
    )
        .take()
        .parse_next(i)?;
    if text.contains(['.', 'E', 'e']) {
        text.parse::<f64>()
            .map(Value::Real)
            .map_err(|_| ErrMode::Cut(ContextError::new()))
    } else {
        // Integers past i64 are reals in all but name.
        Ok(text.parse::<i64>().map_or_else(
            |_| Value::Real(text.parse().unwrap_or(f64::NAN)),
            Value::Int,
        ))
    }
}

fn string(i: &mut &str) -> ModalResult<Value> {
    let parts: Vec<&str> = preceded('\'', cut_err(terminated_string)).parse_next(i)?;
    Ok(Value::Str(parts.join("'")))
}

/// The rest of a string after its opening quote: pieces between `''` escapes.
fn terminated_string<'i>(i: &mut &'i str) -> ModalResult<Vec<&'i str>> {
    let mut parts = Vec::new();
    loop {
        let piece = take_till(0.., '\'').parse_next(i)?;
        parts.push(piece);
        '\''.parse_next(i)?;
        if opt('\'').parse_next(i)?.is_none() {
            return Ok(parts);
        }
    }
}

fn enumeration(i: &mut &str) -> ModalResult<Value> {
    delimited(
        '.',
        take_while(1.., |c: char| c.is_ascii_alphanumeric() || c == '_'),
        '.',
    )
    .map(|s: &str| Value::Enum(s.to_owned()))
    .parse_next(i)
}

fn reference(i: &mut &str) -> ModalResult<Value> {
    preceded('#', take_while(1.., |c: char| c.is_ascii_digit()))
        .try_map(|d: &str| d.parse::<u64>().map(Value::Ref))
        .parse_next(i)
}

fn binary(i: &mut &str) -> ModalResult<Value> {
    delimited('"', take_while(0.., |c: char| c.is_ascii_hexdigit()), '"')
        .value(Value::Binary)
        .parse_next(i)
}

/// A parameter, lists and typed values at most `depth` deep.
fn value(depth: u64) -> impl FnMut(&mut &str) -> ModalResult<Value> {
    move |i: &mut &str| {
        ws(i)?;
        if depth == 0 && (i.starts_with('(') || starts_typed(i)) {
            let mut e = ContextError::new();
            e.push(StrContext::Label("nesting"));
            return Err(ErrMode::Cut(e));
        }
        let v = match i.chars().next() {
            Some('(') => list(depth - 1).map(Value::List).parse_next(i)?,
            Some('\'') => string(i)?,
            Some('.') => enumeration(i)?,
            Some('#') => reference(i)?,
            Some('$') => any.value(Value::Null).parse_next(i)?,
            Some('*') => any.value(Value::Derived).parse_next(i)?,
            Some('"') => binary(i)?,
            Some(c) if c.is_ascii_digit() || c == '-' || c == '+' => number(i)?,
            Some(c) if c.is_ascii_alphabetic() => {
                let name = keyword(i)?;
                ws(i)?;
                let params = cut_err(list(depth - 1)).parse_next(i)?;
                Value::Typed(name.to_owned(), params)
            }
            _ => return Err(ErrMode::Backtrack(ContextError::new())),
        };
        ws(i)?;
        Ok(v)
    }
}

fn starts_typed(i: &str) -> bool {
    i.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
}

/// `( v, v, … )`.
fn list(depth: u64) -> impl FnMut(&mut &str) -> ModalResult<Vec<Value>> {
    move |i: &mut &str| {
        '('.parse_next(i)?;
        ws(i)?;
        let items: Vec<Value> = separated(0.., value(depth), ',').parse_next(i)?;
        ws(i)?;
        cut_err(')').parse_next(i)?;
        Ok(items)
    }
}

fn record(depth: u64) -> impl FnMut(&mut &str) -> ModalResult<Record> {
    move |i: &mut &str| {
        ws(i)?;
        let name = keyword(i)?.to_ascii_uppercase();
        ws(i)?;
        let params = cut_err(list(depth)).parse_next(i)?;
        ws(i)?;
        Ok(Record { name, params })
    }
}

/// Parses a whole exchange structure: every instance of every `DATA` section, by id.
///
/// # Errors
/// [`SyntaxError`] at the first place the file breaks the syntax, a repeated `#id`, or
/// past `bounds`.
pub fn parse(text: &str, bounds: Bounds) -> Result<HashMap<u64, Instance>, SyntaxError> {
    let total = text.len();
    let at = |rest: &str| total - rest.len();
    let fail = |rest: &str, message: String| SyntaxError {
        offset: total - rest.len(),
        message,
    };
    let mut i = text;
    let mut instances = HashMap::new();
    let head: ModalResult<_> = (ws, literal("ISO-10303-21"), ws, ';').parse_next(&mut i);
    if head.is_err() {
        return Err(fail(
            i,
            "not a STEP file: it does not begin with ISO-10303-21;".to_owned(),
        ));
    }
    loop {
        // Sections: HEADER (skipped record by record), DATA, ANCHOR/REFERENCE/SIGNATURE
        // (skipped), then the end.
        let _ = ws(&mut i);
        if i.is_empty() {
            return Err(fail(i, "the file ends before END-ISO-10303-21;".to_owned()));
        }
        if i.starts_with("END-ISO-10303-21") {
            return Ok(instances);
        }
        let section = keyword(&mut i)
            .map_err(|_| fail(i, "a section (HEADER; or DATA;) expected".to_owned()))?;
        let section = section.to_ascii_uppercase();
        // DATA may carry a name and schema list: DATA('name', ('schema'));
        let _ = ws(&mut i);
        if i.starts_with('(') {
            list(bounds.depth)
                .parse_next(&mut i)
                .map_err(|_| fail(i, format!("{section}'s parameters do not parse")))?;
        }
        let _ = ws(&mut i);
        if !eat(&mut i, ';') {
            return Err(fail(i, format!("';' expected after {section}")));
        }
        loop {
            let _ = ws(&mut i);
            if i.len() >= 6 && i[..6].eq_ignore_ascii_case("ENDSEC") {
                i = &i[6..];
                let _ = ws(&mut i);
                if !eat(&mut i, ';') {
                    return Err(fail(i, "';' expected after ENDSEC".to_owned()));
                }
                break;
            }
            if i.is_empty() {
                return Err(fail(
                    i,
                    format!("the file ends inside the {section} section"),
                ));
            }
            let offset = at(i);
            if section == "DATA" {
                let id = match reference(&mut i) {
                    Ok(Value::Ref(id)) => id,
                    _ => return Err(fail(i, "an instance (#id = …;) expected".to_owned())),
                };
                let _ = ws(&mut i);
                if !eat(&mut i, '=') {
                    return Err(fail(i, format!("'=' expected after #{id}")));
                }
                let _ = ws(&mut i);
                let records = if i.starts_with('(') {
                    i = &i[1..];
                    let rs: Result<Vec<Record>, _> =
                        repeat(1.., record(bounds.depth)).parse_next(&mut i);
                    let rs = rs.map_err(|e| syntax_at(i, total, id, &e))?;
                    if !eat(&mut i, ')') {
                        return Err(fail(
                            i,
                            format!("#{id}: ')' expected to close the complex instance"),
                        ));
                    }
                    rs
                } else {
                    vec![
                        record(bounds.depth)
                            .parse_next(&mut i)
                            .map_err(|e| syntax_at(i, total, id, &e))?,
                    ]
                };
                let _ = ws(&mut i);
                if !eat(&mut i, ';') {
                    return Err(fail(i, format!("#{id}: ';' expected after the instance")));
                }
                if instances.len() as u64 >= bounds.instances {
                    return Err(fail(i, format!("more than {} instances", bounds.instances)));
                }
                if instances.insert(id, Instance { records, offset }).is_some() {
                    return Err(SyntaxError {
                        offset,
                        message: format!("#{id} is defined twice"),
                    });
                }
            } else {
                record(bounds.depth)
                    .parse_next(&mut i)
                    .map_err(|_| fail(i, format!("a record of the {section} section expected")))?;
                let _ = ws(&mut i);
                if !eat(&mut i, ';') {
                    return Err(fail(i, format!("';' expected in the {section} section")));
                }
            }
        }
    }
}

/// Whether the next character is `c` (taken when it is).
fn eat(i: &mut &str, mut c: char) -> bool {
    let taken: ModalResult<char> = c.parse_next(i);
    taken.is_ok()
}

fn syntax_at(rest: &str, total: usize, id: u64, e: &ErrMode<ContextError>) -> SyntaxError {
    let deep = matches!(e, ErrMode::Cut(c) if c.context().any(|c| matches!(c, StrContext::Label("nesting"))));
    SyntaxError {
        offset: total - rest.len(),
        message: if deep {
            format!("#{id}: lists nested past the limit")
        } else {
            format!("#{id}: the instance does not parse")
        },
    }
}
