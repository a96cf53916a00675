//! Reading a vision-language model's review leniently, as plans are: an answer cut off part
//! way (by `max_tokens`, a timeout or a closed connection) or partly off the schema keeps what
//! is valid. The three scores come first in the schema, so a cut-off answer usually has them;
//! without all three there is nothing to judge by, and the review is refused naming the missing
//! score. Blamed objects that are not an id and a reason are dropped, reasons and the summary
//! are cut to their length limit, and a missing summary is left empty, each with a note.

use scenethesis_scene_graph::is_printable_id;
use serde::{Deserialize, Serialize};
use serde_json::Value;

/// The most objects a review may blame (`objects.maxItems` of [`review_schema`](crate::review_schema)).
pub const MAX_REVIEW_OBJECTS: usize = 50;
/// Longest reason or summary of a review, in characters (`maxLength`).
pub const MAX_REVIEW_TEXT_CHARS: usize = 400;

/// One object the model found wrong.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ObjectReason {
    /// The object's id.
    pub id: String,
    /// Why it is wrong.
    pub reason: String,
}

/// The scores of a review, in the schema's order.
pub(crate) const SCORES: [&str; 3] = [
    "category_accuracy",
    "orientation_alignment",
    "spatial_coherence",
];

/// What a review answer says, read leniently.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ReadReview {
    /// The scores of [`SCORES`], clamped to [0, 1].
    pub(crate) scores: [f64; 3],
    /// The usable blamed objects.
    pub(crate) objects: Vec<ObjectReason>,
    /// The summary (empty when the answer has none).
    pub(crate) summary: String,
    /// What was dropped or cut.
    pub(crate) notes: Vec<String>,
}

/// Reads `value` (a review answer, maybe closed after a cut); `Err` says which score is missing.
pub(crate) fn read_review(value: &Value) -> Result<ReadReview, String> {
    let mut notes = Vec::new();
    let mut scores = [0.0; 3];
    for (slot, name) in scores.iter_mut().zip(SCORES) {
        *slot = score(value.get(name)).ok_or_else(|| match value.get(name) {
            None => format!("has no `{name}` score"),
            Some(found) => format!("has no usable `{name}` score (found `{found}`)"),
        })?;
    }
    let objects = read_objects(value.get("objects"), &mut notes);
    let summary = match value.get("summary").and_then(Value::as_str) {
        Some(text) => cut_text(text, "the summary", &mut notes),
        None => {
            notes.push("the review has no summary".to_owned());
            String::new()
        }
    };
    Ok(ReadReview {
        scores,
        objects,
        summary,
        notes,
    })
}

/// A score: a number, or a string holding one, clamped to [0, 1].
fn score(value: Option<&Value>) -> Option<f64> {
    let v = match value? {
        Value::Number(n) => n.as_f64()?,
        Value::String(s) => s.trim().parse().ok()?,
        _ => return None,
    };
    v.is_finite().then(|| v.clamp(0.0, 1.0))
}

/// The usable entries of `objects` (at most [`MAX_REVIEW_OBJECTS`]), noting what was dropped.
fn read_objects(objects: Option<&Value>, notes: &mut Vec<String>) -> Vec<ObjectReason> {
    let Some(items) = objects.and_then(Value::as_array) else {
        if objects.is_some() {
            notes.push("the review's `objects` is not a list and was ignored".to_owned());
        }
        return Vec::new();
    };
    let mut kept = Vec::new();
    let mut dropped = 0;
    for item in items {
        let id = item.get("id").and_then(Value::as_str);
        let reason = item.get("reason").and_then(Value::as_str);
        match (id, reason) {
            (Some(id), Some(reason)) if is_printable_id(id) => {
                kept.push(ObjectReason {
                    id: id.to_owned(),
                    reason: cut_text(reason, &format!("the reason for `{id}`"), notes),
                });
            }
            _ => dropped += 1,
        }
    }
    if dropped > 0 {
        notes.push(format!(
            "{dropped} blamed object(s) without a usable id and reason dropped"
        ));
    }
    if kept.len() > MAX_REVIEW_OBJECTS {
        notes.push(format!(
            "{} blamed objects cut to {MAX_REVIEW_OBJECTS}",
            kept.len()
        ));
        kept.truncate(MAX_REVIEW_OBJECTS);
    }
    kept
}

/// `text` cut to [`MAX_REVIEW_TEXT_CHARS`] characters, noting a cut of `what`.
fn cut_text(text: &str, what: &str, notes: &mut Vec<String>) -> String {
    if text.chars().count() <= MAX_REVIEW_TEXT_CHARS {
        return text.to_owned();
    }
    notes.push(format!(
        "{what} was cut to {MAX_REVIEW_TEXT_CHARS} characters"
    ));
    text.chars().take(MAX_REVIEW_TEXT_CHARS).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::salvage::close_truncated;
    use serde_json::json;

    #[test]
    fn a_valid_review_reads_unchanged() {
        let v = json!({"category_accuracy": 0.9, "orientation_alignment": 0.3,
                       "spatial_coherence": 1.4, "objects": [{"id": "a", "reason": "r"}],
                       "summary": "s"});
        let r = read_review(&v).unwrap();
        assert_eq!(r.scores, [0.9, 0.3, 1.0]);
        assert_eq!(
            r.objects,
            vec![ObjectReason {
                id: "a".into(),
                reason: "r".into()
            }]
        );
        assert_eq!((r.summary.as_str(), r.notes.len()), ("s", 0));
    }

    #[test]
    fn a_cut_off_or_partly_invalid_review_keeps_what_is_valid() {
        let cut = r#"{"category_accuracy": 0.8, "orientation_alignment": "0.4",
            "spatial_coherence": 0.7, "objects": [{"id": "chair_1", "reason": "faces the wall"},
            {"id": 7, "reason": "bad id"}, {"id": "lamp\u202e_1", "reason": "bidi"},
            {"id": "desk_1", "reas"#;
        let r = read_review(&close_truncated(cut).unwrap()).unwrap();
        assert_eq!(r.scores, [0.8, 0.4, 0.7]);
        assert_eq!(r.objects.len(), 1);
        assert_eq!(r.objects[0].id, "chair_1");
        assert_eq!(r.summary, "");
        let notes = r.notes.join("; ");
        assert!(notes.contains("3 blamed object(s)"), "{notes}");
        assert!(notes.contains("no summary"), "{notes}");
        let long = json!({"category_accuracy": 1, "orientation_alignment": 1,
                          "spatial_coherence": 1, "summary": "x".repeat(1000)});
        let r = read_review(&long).unwrap();
        assert_eq!(r.summary.chars().count(), MAX_REVIEW_TEXT_CHARS);
    }

    #[test]
    fn a_review_without_its_scores_is_refused_naming_the_score() {
        let cut = close_truncated(r#"{"category_accuracy": 0.8, "orientation_al"#).unwrap();
        assert_eq!(
            read_review(&cut).unwrap_err(),
            "has no `orientation_alignment` score"
        );
        let v = json!({"category_accuracy": "high"});
        assert!(read_review(&v).unwrap_err().contains("found `\"high\"`"));
    }
}
