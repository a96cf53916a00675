//! Support relations stated by a vision-language model: one structured request asking, for
//! every recovered object, what it stands on, is inside or hangs on. The answer is
//! cross-checked with the lifted geometry ([`scenethesis_vision::cross_check`]).

use scenethesis_agents::Plan;
use scenethesis_models::{ChatModel, ChatRequest, ImageData, JsonSchema, Message};
use scenethesis_vision::{SupportGuess, SupportKind};
use serde_json::{json, Value};

/// Stated supports, and `(name, why)` for each answer entry left out.
pub type Stated = (Vec<SupportGuess>, Vec<(String, String)>);

/// The structured answer the model must give: one entry per object, `relation` one of
/// `floor`, `on`, `inside`, `wall`, and `parent` the supporting object's id (empty for the
/// floor and a wall).
pub fn supports_schema() -> JsonSchema {
    JsonSchema::new(
        "object_supports",
        json!({
            "type": "object",
            "additionalProperties": false,
            "required": ["supports"],
            "properties": {
                "supports": {
                    "type": "array",
                    "items": {
                        "type": "object",
                        "additionalProperties": false,
                        "required": ["id", "relation", "parent"],
                        "properties": {
                            "id": {"type": "string", "minLength": 1},
                            "relation": {"type": "string", "enum": ["floor", "on", "inside", "wall"]},
                            "parent": {"type": "string"}
                        }
                    }
                }
            }
        }),
    )
    .expect("the supports schema is valid")
}

/// The request asking what holds up each of `objects` (`(id, category)` of the objects seen
/// in `image`); `plan` describes the scene.
pub fn supports_request(
    plan: &Plan,
    objects: &[(&str, &str)],
    image: ImageData,
    seed: u64,
) -> ChatRequest {
    let list: Vec<String> = objects
        .iter()
        .map(|(id, category)| format!("- {id}: {}", category.replace('_', " ")))
        .collect();
    let text = format!(
        "The image shows a {} ({}). For every object of this list, say what holds it up: \
         `floor` if it stands on the floor, `on` if it rests on top of another object of the \
         list, `inside` if it sits inside one (on a shelf, in a cabinet), `wall` if it hangs on \
         a wall. For `on` and `inside` give that object's id as `parent`, else an empty \
         string.\n{}\nAnswer with JSON: {{\"supports\": [{{\"id\": \"...\", \"relation\": \
         \"floor|on|inside|wall\", \"parent\": \"...\"}}, ...]}}.",
        plan.scene_type.replace('_', " "),
        plan.description,
        list.join("\n")
    );
    let mut request = ChatRequest::structured(
        vec![
            Message::system("You judge how the objects in photographs of rooms are supported."),
            Message::user(text).with_image(image),
        ],
        supports_schema(),
    );
    request.seed = Some(seed);
    request
}

/// Reads the answer: one stated support per known id (of `ids`). Entries naming other objects,
/// repeated ids, unknown relations and `on`/`inside` without a known parent are left out and
/// said in the second list as `(name, why)`.
pub fn parse_supports(ids: &[&str], answer: &Value) -> Stated {
    let mut out: Vec<SupportGuess> = Vec::new();
    let mut notes = Vec::new();
    let items = answer
        .get("supports")
        .and_then(Value::as_array)
        .cloned()
        .unwrap_or_default();
    for item in items {
        let field = |k: &str| item.get(k).and_then(Value::as_str).unwrap_or("").to_owned();
        let (id, relation, parent) = (field("id"), field("relation"), field("parent"));
        if !ids.contains(&id.as_str()) {
            notes.push((
                id,
                "the model named its support but it was not recovered".into(),
            ));
            continue;
        }
        if out.iter().any(|s| s.id == id) {
            notes.push((
                id,
                "the model named its support twice; the first is kept".into(),
            ));
            continue;
        }
        let kind = match relation.as_str() {
            "floor" => SupportKind::Ground,
            "on" => SupportKind::On,
            "inside" => SupportKind::Inside,
            "wall" => SupportKind::Mounted,
            other => {
                notes.push((id, format!("unknown support relation `{other}`")));
                continue;
            }
        };
        let parent = match kind {
            SupportKind::On | SupportKind::Inside => {
                if parent == id || !ids.contains(&parent.as_str()) {
                    notes.push((
                        id,
                        format!(
                            "`{relation}` names `{parent}`, which is not another recovered object"
                        ),
                    ));
                    continue;
                }
                Some(parent)
            }
            _ => None,
        };
        out.push(SupportGuess { id, parent, kind });
    }
    (out, notes)
}

/// Asks `vlm` for the supports of `objects` (`(id, category)`); the error names the model.
pub fn ask_supports(
    vlm: &dyn ChatModel,
    plan: &Plan,
    objects: &[(&str, &str)],
    image: ImageData,
    seed: u64,
) -> Result<Stated, String> {
    let ids: Vec<&str> = objects.iter().map(|(id, _)| *id).collect();
    let answer = vlm
        .chat(&supports_request(plan, objects, image, seed))
        .map_err(|e| e.to_string())?;
    let json = answer
        .json
        .ok_or_else(|| format!("{}: the answer holds no JSON", vlm.name()))?;
    Ok(parse_supports(&ids, &json))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn answers_are_read_and_bad_entries_said() {
        let ids = ["table_0", "lamp_0", "painting_0"];
        let answer = json!({"supports": [
            {"id": "table_0", "relation": "floor", "parent": ""},
            {"id": "lamp_0", "relation": "on", "parent": "table_0"},
            {"id": "lamp_0", "relation": "floor", "parent": ""},
            {"id": "painting_0", "relation": "on", "parent": "sofa_0"},
            {"id": "ghost_0", "relation": "floor", "parent": ""},
            {"id": "table_0", "relation": "levitates", "parent": ""}
        ]});
        let (got, notes) = parse_supports(&ids, &answer);
        assert_eq!(got.len(), 2);
        assert_eq!(got[0].kind, SupportKind::Ground);
        assert_eq!(
            (got[1].kind, got[1].parent.as_deref()),
            (SupportKind::On, Some("table_0"))
        );
        let said: Vec<&str> = notes.iter().map(|(id, _)| id.as_str()).collect();
        assert_eq!(said, ["lamp_0", "painting_0", "ghost_0", "table_0"]);
    }
}
