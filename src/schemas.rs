//! JSON Schemas of every format splinescope reads or writes, generated from the Rust types
//! (never written by hand). `splinescope schema --write docs/schemas` writes them; a test
//! checks that the shipped files match and that every example validates.
//!
//! Input formats (scene, request) are described as read: an optional field may be left
//! out, never written as `null`. Output formats are described as written: every field that
//! is always written is required.

use schemars::JsonSchema;
use schemars::generate::{Contract, SchemaSettings};
use serde_json::Value;

/// The schemas: file stem (`docs/schemas/<stem>.schema.json`) and schema.
#[must_use]
pub fn all() -> Vec<(&'static str, Value)> {
    vec![
        ("scene", input::<splinescope_scene::format::doc::SceneDoc>()),
        (
            "request",
            input::<splinescope_scene::request::types::RequestDocument>(),
        ),
        (
            "report",
            output::<splinescope_scene::request::types::SolveOutput>(),
        ),
        (
            "inspect",
            output::<splinescope_present::inspect::InspectOutput>(),
        ),
        (
            "analyze",
            output::<splinescope_core::analysis::report::AnalyzeOutput>(),
        ),
        ("eval", output::<crate::outputs::EvalOutput>()),
        ("check", output::<crate::outputs::CheckOutput>()),
    ]
}

/// The schema of a format splinescope reads.
fn input<T: JsonSchema>() -> Value {
    let mut v = SchemaSettings::draft2020_12()
        .with(|s| s.contract = Contract::Deserialize)
        .into_generator()
        .into_root_schema_for::<T>()
        .to_value();
    strip_null(&mut v);
    v
}

/// The schema of a format splinescope writes.
fn output<T: JsonSchema>() -> Value {
    SchemaSettings::draft2020_12()
        .with(|s| s.contract = Contract::Serialize)
        .into_generator()
        .into_root_schema_for::<T>()
        .to_value()
}

/// Removes `null` as an allowed value: readers refuse `null` where a field is optional
/// (leave the field out instead).
fn strip_null(v: &mut Value) {
    match v {
        Value::Object(map) => {
            if let Some(Value::Array(types)) = map.get_mut("type") {
                types.retain(|t| t != "null");
                if types.len() == 1 {
                    let only = types.remove(0);
                    map.insert("type".into(), only);
                }
            }
            if let Some(Value::Array(options)) = map.get_mut("anyOf") {
                options.retain(|o| o.get("type").is_none_or(|t| t != "null"));
                if options.len() == 1 {
                    let only = options.remove(0);
                    map.remove("anyOf");
                    if let Value::Object(inner) = only {
                        for (k, val) in inner {
                            map.entry(k).or_insert(val);
                        }
                    }
                }
            }
            for item in map.values_mut() {
                strip_null(item);
            }
        }
        Value::Array(items) => items.iter_mut().for_each(strip_null),
        _ => {}
    }
}

/// One schema as the file holds it: pretty JSON and a final newline.
#[must_use]
pub fn to_text(schema: &Value) -> String {
    let mut text = serde_json::to_string_pretty(schema)
        .unwrap_or_else(|e| unreachable!("a schema value serialises: {e}"));
    text.push('\n');
    text
}
