//! The JSON schema of the model's plan answer (strict-mode ready: closed objects, every
//! property required).

use scenethesis_models::JsonSchema;
use serde_json::json;

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
                "room_width": {"type": "number", "minimum": 2, "maximum": 40},
                "room_depth": {"type": "number", "minimum": 2, "maximum": 40},
                "anchor": {"type": "string", "minLength": 1},
                "objects": {"type": "array", "minItems": 1, "maxItems": 120, "items": object},
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
