//! A local validator for the JSON-schema subset the project emits.
//!
//! Supported keywords: `type` (one name or a list), `properties`, `required`,
//! `additionalProperties` (boolean or schema), `items`, `enum`, `const`, `minimum`, `maximum`,
//! `exclusiveMinimum`, `exclusiveMaximum`, `minItems`, `maxItems`, `minLength`, `maxLength`;
//! annotations (`title`, `description`, `$schema`, `$id`, `default`, `examples`) are ignored.
//! Any other keyword is rejected when the schema is built, so a schema never silently checks
//! less than it says.

use std::fmt;

use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};

/// Keywords the validator checks.
const CHECKED: &[&str] = &[
    "type",
    "properties",
    "required",
    "additionalProperties",
    "items",
    "enum",
    "const",
    "minimum",
    "maximum",
    "exclusiveMinimum",
    "exclusiveMaximum",
    "minItems",
    "maxItems",
    "minLength",
    "maxLength",
];
/// Keywords that only annotate.
const ANNOTATIONS: &[&str] = &[
    "title",
    "description",
    "$schema",
    "$id",
    "default",
    "examples",
];
/// Type names of JSON schema.
const TYPES: &[&str] = &[
    "object", "array", "string", "number", "integer", "boolean", "null",
];

/// Why a schema itself is unusable.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("schema `{name}` at {path}: {message}")]
pub struct SchemaError {
    /// The schema's name.
    pub name: String,
    /// JSON pointer into the schema (`/properties/objects`), `/` for the root.
    pub path: String,
    /// What is wrong.
    pub message: String,
}

/// One place where a value does not satisfy its schema.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct SchemaViolation {
    /// JSON pointer into the value (`/objects/3/category`), `/` for the root.
    pub path: String,
    /// What was expected and what was found.
    pub message: String,
}

impl fmt::Display for SchemaViolation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "at {}: {}", self.path, self.message)
    }
}

/// A named JSON schema, checked once for supported keywords, that validates values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JsonSchema {
    /// A short name (`scene_plan`); providers that want one (OpenAI's `json_schema.name`) use it.
    pub name: String,
    /// The schema document.
    pub schema: Value,
}

impl JsonSchema {
    /// Checks that `schema` uses only supported keywords with well-formed values.
    pub fn new(name: impl Into<String>, schema: Value) -> Result<Self, SchemaError> {
        let name = name.into();
        check_schema(&name, &schema, &mut String::new())?;
        Ok(Self { name, schema })
    }

    /// Validates `value`, returning every violation in document order (empty when valid).
    pub fn violations(&self, value: &Value) -> Vec<SchemaViolation> {
        let mut out = Vec::new();
        validate(&self.schema, value, &mut String::new(), &mut out);
        out
    }

    /// Validates `value`, returning the first violation.
    pub fn validate(&self, value: &Value) -> Result<(), SchemaViolation> {
        match self.violations(value).into_iter().next() {
            Some(v) => Err(v),
            None => Ok(()),
        }
    }
}

fn pointer(path: &str) -> String {
    if path.is_empty() {
        "/".to_string()
    } else {
        path.to_string()
    }
}

/// Escapes a key for a JSON pointer (RFC 6901).
fn escape(key: &str) -> String {
    key.replace('~', "~0").replace('/', "~1")
}

fn check_schema(name: &str, schema: &Value, path: &mut String) -> Result<(), SchemaError> {
    let err = |path: &str, message: String| SchemaError {
        name: name.to_string(),
        path: pointer(path),
        message,
    };
    let Value::Object(map) = schema else {
        if schema.is_boolean() {
            return Ok(());
        }
        return Err(err(
            path,
            format!("expected an object, found {}", kind(schema)),
        ));
    };
    for (key, value) in map {
        if ANNOTATIONS.contains(&key.as_str()) {
            continue;
        }
        if !CHECKED.contains(&key.as_str()) {
            return Err(err(
                path,
                format!(
                    "unsupported keyword `{key}` (supported: {})",
                    CHECKED.join(", ")
                ),
            ));
        }
        let len = path.len();
        path.push('/');
        path.push_str(&escape(key));
        match key.as_str() {
            "type" => {
                let names: Vec<&Value> = match value {
                    Value::Array(list) => list.iter().collect(),
                    other => vec![other],
                };
                for n in names {
                    match n.as_str() {
                        Some(t) if TYPES.contains(&t) => {}
                        _ => return Err(err(path, format!("unknown type {n}"))),
                    }
                }
            }
            "properties" => {
                let Value::Object(props) = value else {
                    return Err(err(path, "expected an object of schemas".into()));
                };
                for (prop, sub) in props {
                    let l = path.len();
                    path.push('/');
                    path.push_str(&escape(prop));
                    check_schema(name, sub, path)?;
                    path.truncate(l);
                }
            }
            "required" => {
                let ok = value
                    .as_array()
                    .is_some_and(|a| a.iter().all(Value::is_string));
                if !ok {
                    return Err(err(path, "expected an array of property names".into()));
                }
            }
            "additionalProperties" | "items" => check_schema(name, value, path)?,
            "enum" => {
                if !value.is_array() {
                    return Err(err(path, "expected an array of values".into()));
                }
            }
            "const" => {}
            "minimum" | "maximum" | "exclusiveMinimum" | "exclusiveMaximum" => {
                if !value.is_number() {
                    return Err(err(
                        path,
                        format!("expected a number, found {}", kind(value)),
                    ));
                }
            }
            _ => {
                // minItems, maxItems, minLength, maxLength
                if !value.is_u64() {
                    return Err(err(
                        path,
                        format!("expected a non-negative integer, found {value}"),
                    ));
                }
            }
        }
        path.truncate(len);
    }
    Ok(())
}

/// The JSON type name of a value, as in schema `type`.
fn kind(value: &Value) -> &'static str {
    match value {
        Value::Null => "null",
        Value::Bool(_) => "boolean",
        Value::Number(n) if n.is_i64() || n.is_u64() => "integer",
        Value::Number(_) => "number",
        Value::String(_) => "string",
        Value::Array(_) => "array",
        Value::Object(_) => "object",
    }
}

fn type_matches(name: &str, value: &Value) -> bool {
    match name {
        "integer" => match value {
            Value::Number(n) => {
                n.is_i64() || n.is_u64() || n.as_f64().is_some_and(|f| f.fract() == 0.0)
            }
            _ => false,
        },
        "number" => value.is_number(),
        other => kind(value) == other,
    }
}

/// Shortens a value for a message.
fn show(value: &Value) -> String {
    let text = value.to_string();
    if text.chars().count() > 60 {
        let cut: String = text.chars().take(57).collect();
        format!("{cut}...")
    } else {
        text
    }
}

fn validate(schema: &Value, value: &Value, path: &mut String, out: &mut Vec<SchemaViolation>) {
    let map: &Map<String, Value> = match schema {
        Value::Object(m) => m,
        Value::Bool(false) => {
            out.push(SchemaViolation {
                path: pointer(path),
                message: "no value is allowed here".into(),
            });
            return;
        }
        _ => return,
    };
    let mut fail = |message: String| {
        out.push(SchemaViolation {
            path: pointer(path),
            message,
        })
    };
    if let Some(message) = type_mismatch(map, value) {
        fail(message);
        return;
    }
    if let Some(Value::Array(allowed)) = map.get("enum") {
        if !allowed.contains(value) {
            let list: Vec<String> = allowed.iter().map(show).collect();
            fail(format!(
                "expected one of {}, found {}",
                list.join(", "),
                show(value)
            ));
        }
    }
    if let Some(c) = map.get("const") {
        if c != value {
            fail(format!("expected {}, found {}", show(c), show(value)));
        }
    }
    if let Some(x) = value.as_f64() {
        number_bounds(map, x, &mut fail);
    }
    let limit = |k: &str| map.get(k).and_then(Value::as_u64);
    if let Value::String(s) = value {
        let n = s.chars().count() as u64;
        if let Some(min) = limit("minLength") {
            if n < min {
                fail(format!("expected at least {min} characters, found {n}"));
            }
        }
        if let Some(max) = limit("maxLength") {
            if n > max {
                fail(format!("expected at most {max} characters, found {n}"));
            }
        }
    }
    if let Value::Array(items) = value {
        let n = items.len() as u64;
        if let Some(min) = limit("minItems") {
            if n < min {
                fail(format!("expected at least {min} items, found {n}"));
            }
        }
        if let Some(max) = limit("maxItems") {
            if n > max {
                fail(format!("expected at most {max} items, found {n}"));
            }
        }
        if let Some(item_schema) = map.get("items") {
            for (i, item) in items.iter().enumerate() {
                let len = path.len();
                path.push_str(&format!("/{i}"));
                validate(item_schema, item, path, out);
                path.truncate(len);
            }
        }
    }
    if let Value::Object(fields) = value {
        validate_object(map, fields, path, out);
    }
}

/// The message when `value` has none of the types `schema` allows.
fn type_mismatch(schema: &Map<String, Value>, value: &Value) -> Option<String> {
    let t = schema.get("type")?;
    let names: Vec<&str> = match t {
        Value::Array(list) => list.iter().filter_map(Value::as_str).collect(),
        other => other.as_str().into_iter().collect(),
    };
    (!names.iter().any(|n| type_matches(n, value))).then(|| {
        format!(
            "expected {}, found {} {}",
            names.join(" or "),
            kind(value),
            show(value)
        )
    })
}

/// Checks number `x` against the schema's (exclusive) minimum and maximum.
fn number_bounds(schema: &Map<String, Value>, x: f64, fail: &mut dyn FnMut(String)) {
    let bound = |k: &str| schema.get(k).and_then(Value::as_f64);
    if let Some(min) = bound("minimum") {
        if x < min {
            fail(format!("expected at least {min}, found {x}"));
        }
    }
    if let Some(max) = bound("maximum") {
        if x > max {
            fail(format!("expected at most {max}, found {x}"));
        }
    }
    if let Some(min) = bound("exclusiveMinimum") {
        if x <= min {
            fail(format!("expected more than {min}, found {x}"));
        }
    }
    if let Some(max) = bound("exclusiveMaximum") {
        if x >= max {
            fail(format!("expected less than {max}, found {x}"));
        }
    }
}

/// Checks an object's required properties, then each property against its schema (or
/// `additionalProperties`).
fn validate_object(
    schema: &Map<String, Value>,
    fields: &Map<String, Value>,
    path: &mut String,
    out: &mut Vec<SchemaViolation>,
) {
    if let Some(Value::Array(required)) = schema.get("required") {
        for name in required.iter().filter_map(Value::as_str) {
            if !fields.contains_key(name) {
                out.push(SchemaViolation {
                    path: pointer(path),
                    message: format!("missing required property `{name}`"),
                });
            }
        }
    }
    let props = schema.get("properties").and_then(Value::as_object);
    for (key, field) in fields {
        let len = path.len();
        path.push('/');
        path.push_str(&escape(key));
        match props.and_then(|p| p.get(key)) {
            Some(sub) => validate(sub, field, path, out),
            None => match schema.get("additionalProperties") {
                Some(Value::Bool(false)) => out.push(SchemaViolation {
                    path: pointer(path),
                    message: format!("unexpected property `{key}`"),
                }),
                Some(sub @ Value::Object(_)) => validate(sub, field, path, out),
                _ => {}
            },
        }
        path.truncate(len);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn plan_schema() -> JsonSchema {
        JsonSchema::new(
            "plan",
            json!({
                "type": "object",
                "additionalProperties": false,
                "required": ["anchor", "objects"],
                "properties": {
                    "anchor": {"type": "string", "minLength": 1},
                    "score": {"type": "number", "minimum": 0, "maximum": 1},
                    "count": {"type": "integer", "exclusiveMinimum": 0},
                    "objects": {
                        "type": "array",
                        "minItems": 2,
                        "items": {
                            "type": "object",
                            "required": ["category", "layer"],
                            "properties": {
                                "category": {"type": "string"},
                                "layer": {"enum": ["background", "middle", "foreground"]},
                                "note": {"type": ["string", "null"]}
                            }
                        }
                    }
                }
            }),
        )
        .unwrap()
    }

    #[test]
    fn valid_value_passes() {
        let v = json!({"anchor": "desk_0", "score": 0.5, "count": 3, "objects": [
            {"category": "desk", "layer": "middle", "note": null},
            {"category": "chair", "layer": "foreground", "note": "x"}]});
        assert_eq!(plan_schema().violations(&v), vec![]);
    }

    #[test]
    fn violations_carry_pointer_paths() {
        let v = json!({"anchor": "", "score": 1.5, "count": 0, "extra": 1, "objects": [
            {"category": 3, "layer": "middle"},
            {"layer": "ceiling"}]});
        let got: Vec<String> = plan_schema()
            .violations(&v)
            .iter()
            .map(ToString::to_string)
            .collect();
        assert_eq!(
            got,
            vec![
                "at /anchor: expected at least 1 characters, found 0",
                "at /count: expected more than 0, found 0",
                "at /extra: unexpected property `extra`",
                "at /objects/0/category: expected string, found integer 3",
                "at /objects/1: missing required property `category`",
                "at /objects/1/layer: expected one of \"background\", \"middle\", \"foreground\", found \"ceiling\"",
                "at /score: expected at most 1, found 1.5",
            ]
        );
    }

    #[test]
    fn root_and_array_limits() {
        let s = plan_schema();
        let err = s.validate(&json!([1])).unwrap_err();
        assert_eq!(err.path, "/");
        assert!(err.message.starts_with("expected object, found array"));
        let err = s
            .validate(&json!({"anchor": "a", "objects": [{"category": "c", "layer": "middle"}]}))
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            "at /objects: expected at least 2 items, found 1"
        );
        // 2.0 is an integer for JSON schema.
        let ok = json!({"anchor": "a", "count": 2.0, "objects": [
            {"category": "c", "layer": "middle"}, {"category": "d", "layer": "middle"}]});
        assert_eq!(s.validate(&ok), Ok(()));
    }

    #[test]
    fn unsupported_keywords_are_refused_with_their_path() {
        let err = JsonSchema::new(
            "x",
            json!({"type": "object", "properties": {"a": {"type": "string", "pattern": "^a"}}}),
        )
        .unwrap_err();
        assert_eq!(err.path, "/properties/a");
        assert!(err.message.starts_with("unsupported keyword `pattern`"));
        let err = JsonSchema::new("x", json!({"type": "thing"})).unwrap_err();
        assert_eq!(
            err.to_string(),
            "schema `x` at /type: unknown type \"thing\""
        );
        let err = JsonSchema::new("x", json!({"minItems": -1})).unwrap_err();
        assert_eq!(err.path, "/minItems");
    }
}
