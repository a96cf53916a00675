//! Reading what can be read of a structured answer that is not valid JSON: a small model, or
//! one stopped by `max_tokens`, often ends mid-object. The complete elements are kept and the
//! brackets still open are closed.

use serde_json::Value;

/// Nesting depth beyond which an answer is not salvaged (the plan schema nests 4 deep).
const MAX_DEPTH: usize = 64;

/// Where the scanner is inside a container.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Frame {
    /// In an array.
    Array,
    /// In an object, before a key (`true`) or before a value (`false`).
    Object { expect_key: bool },
}

/// Scanner state over the answer text.
struct Scan {
    stack: Vec<Frame>,
    in_string: bool,
    escaped: bool,
    in_scalar: bool,
    /// The last point (byte offset, depth) at which cutting leaves only complete values.
    cut: Option<(usize, usize)>,
}

impl Scan {
    /// A value ended just before byte `at`: in an object its key/value pair is complete.
    fn value_ended(&mut self, at: usize) {
        if let Some(Frame::Object { expect_key }) = self.stack.last_mut() {
            *expect_key = true;
        }
        self.cut = Some((at, self.stack.len()));
    }

    /// Reads byte `b` at offset `i`; `false` stops the scan (too deep, or the top value ended).
    fn step(&mut self, i: usize, b: u8) -> bool {
        if self.in_string {
            match (self.escaped, b) {
                (true, _) => self.escaped = false,
                (false, b'\\') => self.escaped = true,
                (false, b'"') => {
                    self.in_string = false;
                    let is_key =
                        matches!(self.stack.last(), Some(Frame::Object { expect_key: true }));
                    if !is_key {
                        self.value_ended(i + 1);
                    }
                }
                _ => {}
            }
            return true;
        }
        if self.in_scalar && !(b.is_ascii_alphanumeric() || matches!(b, b'.' | b'-' | b'+')) {
            self.in_scalar = false;
            self.value_ended(i);
        }
        match b {
            b'{' | b'[' => {
                if self.stack.len() >= MAX_DEPTH {
                    return false;
                }
                self.stack.push(if b == b'{' {
                    Frame::Object { expect_key: true }
                } else {
                    Frame::Array
                });
                self.cut = Some((i + 1, self.stack.len()));
            }
            b'}' | b']' => {
                self.stack.pop();
                if self.stack.is_empty() {
                    // The whole value is complete: keep it, ignore what follows.
                    self.cut = Some((i + 1, 0));
                    return false;
                }
                self.value_ended(i + 1);
            }
            b'"' => self.in_string = true,
            b':' => {
                if let Some(Frame::Object { expect_key }) = self.stack.last_mut() {
                    *expect_key = false;
                }
            }
            b',' | b' ' | b'\n' | b'\r' | b'\t' => {}
            _ => self.in_scalar = true,
        }
        true
    }
}

/// The JSON object at the start of `text` (after any prose), with an answer cut off part way
/// closed after its last complete value: a trailing partial element, key or string is dropped
/// and the open arrays and objects are closed. `None` when no object starts in `text`.
pub(crate) fn close_truncated(text: &str) -> Option<Value> {
    let start = text.find('{')?;
    let body = &text[start..];
    let mut scan = Scan {
        stack: Vec::new(),
        in_string: false,
        escaped: false,
        in_scalar: false,
        cut: None,
    };
    for (i, b) in body.bytes().enumerate() {
        if !scan.step(i, b) {
            break;
        }
    }
    let (at, depth) = scan.cut?;
    let mut repaired = body[..at].to_string();
    for frame in scan.stack[..depth.min(scan.stack.len())].iter().rev() {
        repaired.push(match frame {
            Frame::Array => ']',
            Frame::Object { .. } => '}',
        });
    }
    serde_json::from_str(&repaired).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn a_cut_off_answer_keeps_its_complete_elements() {
        let full = r#"{"a": 1, "objects": [{"id": "x", "n": [1, 2]}, {"id": "y", "n": [3]}], "z": "done"}"#;
        // Every prefix from the first complete value on is closed into valid JSON.
        for cut in 8..full.len() {
            let v = close_truncated(&full[..cut]).unwrap_or_else(|| panic!("{}", &full[..cut]));
            assert_eq!(v["a"], json!(1), "{}", &full[..cut]);
        }
        let v = close_truncated(&full[..full.find("\"y\"").unwrap() + 5]).unwrap();
        assert_eq!(v["objects"][0], json!({"id": "x", "n": [1, 2]}));
        assert_eq!(v["objects"][1], json!({"id": "y"}));
        let v = close_truncated(&full[..full.find("\"y\"").unwrap() + 2]).unwrap();
        assert_eq!(v["objects"].as_array().unwrap().len(), 2, "{v}");
        assert_eq!(v["objects"][1], json!({}), "a cut key is dropped");
    }

    #[test]
    fn strings_with_brackets_escapes_and_prose_around_are_read() {
        let v = close_truncated(r#"Sure! {"t": "a } \" ] {", "u": [tru"#).unwrap();
        assert_eq!(v, json!({"t": "a } \" ] {", "u": []}));
        let v = close_truncated(r#"{"n": 12.5e1, "m": "half"#).unwrap();
        assert_eq!(v, json!({"n": 125.0}));
        assert_eq!(close_truncated("no json here"), None);
        assert_eq!(
            close_truncated(r#"{"a": 1} trailing {"#).unwrap(),
            json!({"a": 1})
        );
    }

    #[test]
    fn deep_nesting_is_not_followed() {
        let deep = format!("{{\"a\": {}", "[".repeat(10_000));
        // Cut where the depth limit stops the scan; whatever comes back is bounded JSON.
        let v = close_truncated(&deep).unwrap();
        assert!(v.get("a").is_some());
    }
}
