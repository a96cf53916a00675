//! The JSON schema of the model's plan answer (strict-mode ready: closed objects, every
//! property required).

use scenethesis_agents::{MAX_ROOM_SIDE, MIN_ROOM_SIDE};
use scenethesis_models::JsonSchema;
use serde_json::json;

/// The most objects the plan schema lets a model list (`objects.maxItems`); answers with more
/// are cut to this many.
pub const MAX_ANSWER_OBJECTS: usize = 120;
/// Answer tokens allowed per listed object (an object of the schema is about 60 tokens).
pub const TOKENS_PER_OBJECT: u32 = 80;
/// Answer tokens allowed for everything but the objects (interpretation, description, ...).
pub const PLAN_OVERHEAD_TOKENS: u32 = 1500;

/// The `max_tokens` of a plan request: what the schema's largest answer needs.
pub const fn plan_max_tokens() -> u32 {
    PLAN_OVERHEAD_TOKENS + TOKENS_PER_OBJECT * MAX_ANSWER_OBJECTS as u32
}

/// Relation kinds the model may state between objects (supports are separate).
pub(crate) const RELATIONS: &[&str] = &[
    "beside",
    "in-front-of",
    "behind",
    "left-of",
    "right-of",
    "facing",
    "around",
];

/// The schema `scene_plan` of the planner's answer.
pub fn plan_schema() -> JsonSchema {
    let object = json!({
        "type": "object",
        "additionalProperties": false,
        "required": ["id", "category", "layer", "support", "parent", "zone", "wall", "relations", "stated"],
        "properties": {
            "id": {"type": "string", "minLength": 1, "description": "unique id such as shelf_0"},
            "category": {"type": "string", "minLength": 1, "description": "one of the available categories"},
            "layer": {"enum": ["background", "middle", "foreground"]},
            "support": {"enum": ["on-floor", "against-wall", "on", "inside", "under"]},
            "parent": {"type": "string", "description": "`ground`, or the id of the supporting object for on/inside/under"},
            "zone": {"enum": ["wall", "corner", "center", "rows", "free", "wall-mounted", "relative", "supported"]},
            "wall": {"enum": ["wall_0", "wall_1", "wall_2", "wall_3", "any"],
                     "description": "for zone wall: wall_0 back, wall_1 left, wall_2 front (door), wall_3 right"},
            "relations": {
                "type": "array",
                "items": {
                    "type": "object",
                    "additionalProperties": false,
                    "required": ["kind", "target"],
                    "properties": {
                        "kind": {"enum": RELATIONS},
                        "target": {"type": "string", "minLength": 1}
                    }
                }
            },
            "stated": {"type": "boolean", "description": "true when the user's prompt states this object's placement"}
        }
    });
    JsonSchema::new(
        "scene_plan",
        json!({
            "type": "object",
            "additionalProperties": false,
            "required": ["interpretation", "detailed", "scene_type", "environment", "room_width",
                         "room_depth", "anchor", "objects", "unavailable", "description"],
            "properties": {
                "interpretation": {"type": "string"},
                "detailed": {"type": "boolean"},
                "scene_type": {"type": "string", "minLength": 1},
                "environment": {"enum": ["indoor", "outdoor"]},
                "room_width": {"type": "number", "minimum": MIN_ROOM_SIDE, "maximum": MAX_ROOM_SIDE},
                "room_depth": {"type": "number", "minimum": MIN_ROOM_SIDE, "maximum": MAX_ROOM_SIDE},
                "anchor": {"type": "string", "minLength": 1},
                "objects": {"type": "array", "minItems": 1, "maxItems": MAX_ANSWER_OBJECTS, "items": object},
                "unavailable": {
                    "type": "array",
                    "items": {
                        "type": "object",
                        "additionalProperties": false,
                        "required": ["name", "reason"],
                        "properties": {"name": {"type": "string"}, "reason": {"type": "string"}}
                    }
                },
                "description": {"type": "string", "minLength": 1}
            }
        }),
    )
    .expect("the plan schema uses supported keywords")
}
