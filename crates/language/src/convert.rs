//! The model's answer → a [`Plan`]: categories cross-checked against the library, ids made
//! unique, supports and zones made consistent, relations to unknown targets dropped, objects
//! ordered (floor objects with the anchor first, then supported ones, parents first).

use std::collections::{BTreeMap, BTreeSet};

use scenethesis_agents::{
    ConstraintTarget, Knowledge, Layer, PlaceReading, Plan, PlanConstraint, PlannedObject,
    ReadingSource, Thesaurus, Zone, BACK_WALL, FRONT_WALL, LEFT_WALL, MAX_ROOM_SIDE, MIN_ROOM_SIDE,
    RIGHT_WALL,
};
use scenethesis_scene_graph::limits::{MAX_ID_BYTES, MAX_RELATIONS};
use scenethesis_scene_graph::{
    is_printable_id, printable, Environment, ParentRef, Relation, RelationKind,
};
use serde::Deserialize;
use serde_json::Value;

use crate::schema::MAX_ANSWER_OBJECTS;

const WALLS: [&str; 4] = [BACK_WALL, LEFT_WALL, FRONT_WALL, RIGHT_WALL];

/// The ground the knowledge gives an outdoor scene type the model named (`beach` → sand),
/// if it names a known archetype or place.
fn known_ground(scene_type: &str) -> Option<String> {
    Thesaurus::builtin()
        .archetype(scene_type, Knowledge::builtin())
        .and_then(|a| a.ground)
}

/// The model's answer, as the schema shapes it; read leniently by [`Answer::read`].
#[derive(Debug, Clone, Default)]
pub(crate) struct Answer {
    pub(crate) interpretation: String,
    pub(crate) detailed: bool,
    pub(crate) scene_type: String,
    pub(crate) environment: String,
    pub(crate) room_width: f64,
    pub(crate) room_depth: f64,
    pub(crate) anchor: String,
    pub(crate) objects: Vec<AnswerObject>,
    pub(crate) unavailable: Vec<Unavailable>,
    pub(crate) description: String,
}

#[derive(Debug, Clone, Deserialize)]
pub(crate) struct AnswerObject {
    id: String,
    category: String,
    #[serde(default = "middle")]
    layer: Layer,
    support: RelationKind,
    parent: String,
    #[serde(default)]
    zone: String,
    #[serde(default)]
    wall: String,
    #[serde(default, deserialize_with = "lenient_relations")]
    relations: Vec<AnswerRelation>,
    #[serde(default)]
    stated: bool,
}

fn middle() -> Layer {
    Layer::Middle
}

/// The relations that parse; a malformed one is left out rather than the whole object.
fn lenient_relations<'de, D: serde::Deserializer<'de>>(
    d: D,
) -> Result<Vec<AnswerRelation>, D::Error> {
    let values = Vec::<Value>::deserialize(d)?;
    Ok(values
        .into_iter()
        .take(MAX_RELATIONS)
        .filter_map(|v| serde_json::from_value(v).ok())
        .collect())
}

#[derive(Debug, Clone, Deserialize)]
pub(crate) struct AnswerRelation {
    kind: RelationKind,
    target: String,
}

#[derive(Debug, Clone, Deserialize)]
pub(crate) struct Unavailable {
    name: String,
    reason: String,
}

/// The room side assumed when an answer gives none, in metres.
const DEFAULT_ROOM_SIDE: f64 = 6.0;

/// `text` escaped for a note or message and cut to 80 characters.
pub(crate) fn shown(text: &str) -> String {
    let text = printable(text);
    if text.chars().count() > 80 {
        format!("{}…", text.chars().take(79).collect::<String>())
    } else {
        text.into_owned()
    }
}

impl Answer {
    /// Reads an answer field by field: a missing or mistyped field takes its default, an object
    /// that does not fit the schema is left out, and objects past [`MAX_ANSWER_OBJECTS`] are
    /// dropped; each of these is said in the returned notes.
    pub(crate) fn read(value: &Value) -> (Self, Vec<String>) {
        let mut notes = Vec::new();
        let text = |key: &str| {
            value
                .get(key)
                .and_then(Value::as_str)
                .unwrap_or("")
                .to_string()
        };
        let mut side = |key: &str| match value.get(key).and_then(Value::as_f64) {
            Some(v) => v,
            None => {
                notes.push(format!(
                    "`{key}` missing from the answer; {DEFAULT_ROOM_SIDE} m assumed"
                ));
                DEFAULT_ROOM_SIDE
            }
        };
        let (room_width, room_depth) = (side("room_width"), side("room_depth"));
        let objects = read_objects(value.get("objects"), &mut notes);
        let unavailable = value
            .get("unavailable")
            .and_then(Value::as_array)
            .map(|a| {
                a.iter()
                    .take(MAX_ANSWER_OBJECTS)
                    .filter_map(|u| serde_json::from_value(u.clone()).ok())
                    .collect()
            })
            .unwrap_or_default();
        let answer = Self {
            interpretation: text("interpretation"),
            detailed: value
                .get("detailed")
                .and_then(Value::as_bool)
                .unwrap_or(false),
            scene_type: text("scene_type"),
            environment: text("environment"),
            room_width,
            room_depth,
            anchor: text("anchor"),
            objects,
            unavailable,
            description: text("description"),
        };
        (answer, notes)
    }
}

/// The objects of an answer that fit the schema, at most [`MAX_ANSWER_OBJECTS`].
fn read_objects(objects: Option<&Value>, notes: &mut Vec<String>) -> Vec<AnswerObject> {
    let Some(items) = objects.and_then(Value::as_array) else {
        notes.push("the answer has no `objects` list".to_string());
        return Vec::new();
    };
    if items.len() > MAX_ANSWER_OBJECTS {
        notes.push(format!(
            "the answer lists {} objects; the first {MAX_ANSWER_OBJECTS} kept (the most the plan \
             schema allows, MAX_ANSWER_OBJECTS)",
            items.len()
        ));
    }
    let mut dropped = Vec::new();
    let kept = items
        .iter()
        .take(MAX_ANSWER_OBJECTS)
        .enumerate()
        .filter_map(|(i, item)| match serde_json::from_value(item.clone()) {
            Ok(o) => Some(o),
            Err(e) => {
                dropped.push(format!("objects[{i}] ({})", shown(&e.to_string())));
                None
            }
        })
        .collect();
    if !dropped.is_empty() {
        notes.push(format!(
            "left out what does not fit the plan schema: {}",
            dropped.join(", ")
        ));
    }
    kept
}

/// A converted plan and what is weak about it.
#[derive(Debug, Clone)]
pub(crate) struct Converted {
    pub(crate) plan: Plan,
    /// Problems worth re-asking about (too few objects, unknown categories, no anchor).
    pub(crate) issues: Vec<String>,
    /// Whether the model judged the prompt detailed.
    pub(crate) detailed: bool,
}

/// The words of a name in the one text vocabulary (`scenethesis-words`): lower case, split on
/// anything not a letter or digit, each word singular.
pub(crate) fn normalise(name: &str) -> Vec<String> {
    scenethesis_words::words(name)
}

/// The library category nearest to `name` ([`scenethesis_words::nearest_category`]): the same
/// words, else the category with the most words all contained in the name ("pharmacy shelf" →
/// `shelf`; ties go to the first in sorted order).
pub(crate) fn nearest_category(name: &str, available: &BTreeSet<String>) -> Option<String> {
    let rows: Vec<(Vec<String>, &String)> = available.iter().map(|c| (normalise(c), c)).collect();
    let rows = rows.iter().map(|(w, c)| (w.as_slice(), *c));
    scenethesis_words::nearest_category(&normalise(name), rows).cloned()
}

fn zone_of(zone: &str, wall: &str) -> Zone {
    match zone {
        "wall" => Zone::Wall {
            wall: WALLS.contains(&wall).then(|| wall.to_string()),
        },
        "corner" => Zone::Corner,
        "center" => Zone::Center,
        "rows" => Zone::Rows,
        "wall-mounted" => Zone::WallMounted,
        "relative" => Zone::Relative,
        "supported" => Zone::Supported,
        _ => Zone::Free,
    }
}

fn round_cm(x: f64) -> f64 {
    (x * 100.0).round() / 100.0
}

/// A room side from the answer, within [`MIN_ROOM_SIDE`]..=[`MAX_ROOM_SIDE`] (a non-finite one
/// becomes the default).
fn room_side(v: f64) -> f64 {
    let v = if v.is_finite() { v } else { DEFAULT_ROOM_SIDE };
    round_cm(v.clamp(MIN_ROOM_SIDE, MAX_ROOM_SIDE))
}

/// Converts a schema-valid answer for `prompt` over the `available` categories.
pub(crate) fn convert(
    answer: &Answer,
    prompt: &str,
    available: &BTreeSet<String>,
    min_objects: usize,
) -> Converted {
    let mut notes = Vec::new();
    let mut issues = Vec::new();
    let indoor = answer.environment != "outdoor";
    let (kept, id_map) = kept_objects(answer, available, &mut notes, &mut issues);
    let place = Placing {
        id_map: &id_map,
        indoor,
        detailed: answer.detailed,
    };
    let mut objects: Vec<PlannedObject> = kept
        .iter()
        .map(|(o, id, category)| planned_object(o, id, category, &place, &mut notes))
        .collect();
    break_cycles(&mut objects, &mut notes);
    let anchor = anchor_of(answer, &id_map, &objects);
    if anchor.is_none() {
        issues.push(format!(
            "the anchor `{}` is not a floor-standing object of the plan",
            shown(&answer.anchor)
        ));
    }
    if !answer.detailed && objects.len() < min_objects {
        issues.push(format!(
            "the plan has only {} usable objects; a simple prompt needs at least {min_objects}",
            objects.len()
        ));
    }
    let plan = assemble_plan(answer, prompt, objects, anchor, notes);
    Converted {
        plan,
        issues,
        detailed: answer.detailed,
    }
}

/// The objects of a known category, each with a usable unique id (renamed `CATEGORY_N` when
/// not), and the map from the answer's ids to those; unknown categories and unavailable
/// objects are noted, unknown categories also raised as an issue.
#[allow(clippy::type_complexity)]
fn kept_objects<'a>(
    answer: &'a Answer,
    available: &BTreeSet<String>,
    notes: &mut Vec<String>,
    issues: &mut Vec<String>,
) -> (
    Vec<(&'a AnswerObject, String, String)>,
    BTreeMap<String, String>,
) {
    let mut unknown = Vec::new();
    let mut id_map: BTreeMap<String, String> = BTreeMap::new();
    let mut taken: BTreeSet<String> = BTreeSet::new();
    let mut kept: Vec<(&AnswerObject, String, String)> = Vec::new(); // (object, id, category)
    for o in &answer.objects {
        let Some(category) = nearest_category(&o.category, available) else {
            unknown.push(format!("`{}` ({})", shown(&o.category), shown(&o.id)));
            continue;
        };
        if normalise(&category) != normalise(&o.category) {
            notes.push(format!(
                "`{}` ({}) mapped to the nearest library category `{category}`",
                shown(&o.category),
                shown(&o.id)
            ));
        }
        let mut id = o.id.trim().to_string();
        let usable = is_printable_id(&id);
        if !usable || taken.contains(&id) || WALLS.contains(&id.as_str()) || id == "ground" {
            let fresh = fresh_id(&category, &mut taken);
            if !usable && !id.is_empty() {
                notes.push(format!(
                    "id `{}` cannot be written to scene.json (control or bidirectional \
                 characters, or longer than {MAX_ID_BYTES} bytes); renamed {fresh}",
                    shown(&id)
                ));
            }
            id = fresh;
        }
        taken.insert(id.clone());
        id_map.entry(o.id.clone()).or_insert_with(|| id.clone());
        kept.push((o, id, category));
    }
    if !unknown.is_empty() {
        notes.push(format!(
            "not in the asset library, left out: {}",
            unknown.join(", ")
        ));
        issues.push(format!(
            "these categories are not in the library (use only the listed categories): {}",
            unknown.join(", ")
        ));
    }
    for u in &answer.unavailable {
        notes.push(format!(
            "unavailable `{}`: {}",
            shown(&u.name),
            printable(&u.reason)
        ));
    }
    (kept, id_map)
}

/// What every planned object is read against: the answer's ids mapped to the plan's, whether
/// the scene is indoors, and whether the prompt was detailed (its stated objects are hard).
struct Placing<'a> {
    id_map: &'a BTreeMap<String, String>,
    indoor: bool,
    detailed: bool,
}

/// The planned object of answer object `o` (kept as `id` of `category`): its support,
/// parent and zone made consistent, and its relations to objects of the plan (or walls).
fn planned_object(
    o: &AnswerObject,
    id: &String,
    category: &str,
    place: &Placing<'_>,
    notes: &mut Vec<String>,
) -> PlannedObject {
    let (id_map, indoor) = (place.id_map, place.indoor);
    let parent_id = id_map.get(&o.parent).filter(|p| *p != id).cloned();
    let supported = matches!(
        o.support,
        RelationKind::On | RelationKind::Inside | RelationKind::Under
    );
    let (support, parent, mut zone) = match (supported, parent_id) {
        (true, Some(p)) => (o.support, ParentRef::Object(p), Zone::Supported),
        (true, None) => {
            notes.push(if id_map.get(&o.parent) == Some(id) {
                format!("{id}: rests on itself; placed on the floor instead")
            } else {
                format!(
                    "{id}: parent `{}` is not in the plan; placed on the floor instead",
                    shown(&o.parent)
                )
            });
            (RelationKind::OnFloor, ParentRef::Ground, Zone::Free)
        }
        (false, _) => {
            let zone = match zone_of(&o.zone, &o.wall) {
                Zone::Supported => Zone::Free,
                z => z,
            };
            let zone = match (indoor, zone, o.support) {
                (false, Zone::WallMounted | Zone::Wall { .. } | Zone::Corner, _) => Zone::Free,
                (true, Zone::Free | Zone::Center | Zone::Relative, RelationKind::AgainstWall) => {
                    Zone::Wall { wall: None }
                }
                (_, z, _) => z,
            };
            let against =
                indoor && matches!(zone, Zone::Wall { .. } | Zone::Corner | Zone::WallMounted);
            let support = if against {
                RelationKind::AgainstWall
            } else {
                RelationKind::OnFloor
            };
            (support, ParentRef::Ground, zone)
        }
    };
    let mut relations = Vec::new();
    if let Zone::Wall { wall: Some(w) } = &zone {
        relations.push(Relation::new(RelationKind::AgainstWall, w.clone()));
    }
    for r in &o.relations {
        let target = if indoor && WALLS.contains(&r.target.as_str()) {
            Some(r.target.clone())
        } else {
            id_map.get(&r.target).filter(|t| *t != id).cloned()
        };
        match target {
            Some(t) if !r.kind.is_support() => relations.push(Relation::new(r.kind, t)),
            _ => notes.push(format!(
                "{id}: relation {} `{}` dropped (no such object)",
                r.kind,
                shown(&r.target)
            )),
        }
    }
    if zone == Zone::Relative && relations.is_empty() {
        zone = Zone::Free;
    }
    PlannedObject {
        id: id.clone(),
        category: category.to_owned(),
        layer: o.layer,
        support,
        parent,
        zone,
        relations,
        hard: o.stated && place.detailed,
        attributes: Vec::new(),
    }
}

/// The answer's anchor, when it is a floor-standing object of the plan.
fn anchor_of(
    answer: &Answer,
    id_map: &BTreeMap<String, String>,
    objects: &[PlannedObject],
) -> Option<String> {
    id_map
        .get(&answer.anchor)
        .filter(|a| {
            objects
                .iter()
                .any(|o| &o.id == *a && o.parent == ParentRef::Ground)
        })
        .cloned()
}

/// The plan: the objects in order around the anchor, the hard constraints of what the prompt
/// stated, the room from the answer, and the notes after the model's interpretation.
fn assemble_plan(
    answer: &Answer,
    prompt: &str,
    objects: Vec<PlannedObject>,
    anchor: Option<String>,
    notes: Vec<String>,
) -> Plan {
    let indoor = answer.environment != "outdoor";
    let constraints = constraints_of(&objects, indoor);
    let description = if answer.detailed {
        // A detailed prompt is kept as written: it already names objects and relations.
        prompt.trim().to_string()
    } else {
        answer.description.trim().to_string()
    };
    let anchor_id = anchor.clone().unwrap_or_default();
    let objects = order(objects, &anchor_id);
    let scene_type = answer.scene_type.trim().to_lowercase().replace(' ', "_");
    // The model's reading is taken as given: it read every word of the prompt.
    let reading = PlaceReading {
        place: scene_type.clone(),
        confidence: 1.0,
        basis: format!("the model read the prompt as `{}`", printable(&scene_type)),
        source: ReadingSource::Model,
    };
    let ground = (!indoor).then(|| known_ground(&scene_type)).flatten();
    Plan {
        prompt: prompt.trim().to_string(),
        scene_type,
        archetypes: Vec::new(),
        environment: if indoor {
            Environment::Indoor
        } else {
            Environment::Outdoor
        },
        ground,
        room_size: [room_side(answer.room_width), room_side(answer.room_depth)],
        wall_height: 2.8,
        aisle: 0.9,
        door_clearance: 1.0,
        anchor: anchor_id,
        objects,
        constraints,
        description,
        assumptions: Vec::new(),
        reading: Some(reading),
        limits: Vec::new(),
        requested: Vec::new(),
        look: None,
        keep_clear: Vec::new(),
        notes: {
            let mut n = vec![format!(
                "model interpretation: {}",
                printable(answer.interpretation.trim())
            )];
            n.extend(notes);
            n
        },
    }
}

/// Puts objects whose parent chain loops back onto the floor.
fn break_cycles(objects: &mut [PlannedObject], notes: &mut Vec<String>) {
    let parent_of: BTreeMap<String, Option<String>> = objects
        .iter()
        .map(|o| (o.id.clone(), o.parent.object_id().map(str::to_string)))
        .collect();
    for o in objects.iter_mut() {
        let mut seen = BTreeSet::new();
        let mut cur = o.parent.object_id().map(str::to_string);
        let mut looped = false;
        while let Some(p) = cur {
            if p == o.id || !seen.insert(p.clone()) {
                looped = true;
                break;
            }
            cur = parent_of.get(&p).cloned().flatten();
        }
        if looped {
            notes.push(format!(
                "{}: its supports form a loop; placed on the floor",
                o.id
            ));
            o.parent = ParentRef::Ground;
            o.support = RelationKind::OnFloor;
            o.zone = Zone::Free;
        }
    }
}

fn constraints_of(objects: &[PlannedObject], indoor: bool) -> Vec<PlanConstraint> {
    let mut out = Vec::new();
    for o in objects.iter().filter(|o| o.hard) {
        let phrase = format!("stated in the prompt ({})", o.category);
        match (&o.parent, &o.zone) {
            (ParentRef::Object(p), _) => out.push(PlanConstraint {
                subject: o.id.clone(),
                kind: o.support,
                target: ConstraintTarget::Object(p.clone()),
                phrase: phrase.clone(),
            }),
            (ParentRef::Ground, Zone::Wall { wall }) if indoor => out.push(PlanConstraint {
                subject: o.id.clone(),
                kind: RelationKind::AgainstWall,
                target: wall
                    .clone()
                    .map_or(ConstraintTarget::AnyWall, ConstraintTarget::Wall),
                phrase: phrase.clone(),
            }),
            (ParentRef::Ground, Zone::Corner) if indoor => out.push(PlanConstraint {
                subject: o.id.clone(),
                kind: RelationKind::AgainstWall,
                target: ConstraintTarget::Corner,
                phrase: phrase.clone(),
            }),
            _ => {}
        }
        for r in o
            .relations
            .iter()
            .filter(|r| r.kind != RelationKind::AgainstWall)
        {
            let target = if WALLS.contains(&r.target.as_str()) {
                ConstraintTarget::Wall(r.target.clone())
            } else {
                ConstraintTarget::Object(r.target.clone())
            };
            out.push(PlanConstraint {
                subject: o.id.clone(),
                kind: r.kind,
                target,
                phrase: phrase.clone(),
            });
        }
    }
    out
}

/// Floor objects first (the anchor first), then supported objects with parents before
/// children; otherwise the given order.
pub(crate) fn order(objects: Vec<PlannedObject>, anchor: &str) -> Vec<PlannedObject> {
    let (mut ground, mut supported): (Vec<_>, Vec<_>) = objects
        .into_iter()
        .partition(|o| o.parent == ParentRef::Ground);
    if let Some(i) = ground.iter().position(|o| o.id == anchor) {
        let a = ground.remove(i);
        ground.insert(0, a);
    }
    let mut placed: BTreeSet<String> = ground.iter().map(|o| o.id.clone()).collect();
    let mut out = ground;
    while !supported.is_empty() {
        let before = supported.len();
        let mut rest = Vec::new();
        for o in supported {
            if o.parent.object_id().is_some_and(|p| placed.contains(p)) {
                placed.insert(o.id.clone());
                out.push(o);
            } else {
                rest.push(o);
            }
        }
        supported = rest;
        if supported.len() == before {
            // Unreachable after break_cycles; keep the objects rather than loop.
            out.append(&mut supported);
        }
    }
    out
}

/// The first `CATEGORY_N` id not in `taken`, which it joins.
pub(crate) fn fresh_id(category: &str, taken: &mut BTreeSet<String>) -> String {
    let mut n = 0;
    while taken.contains(&format!("{category}_{n}")) {
        n += 1;
    }
    let id = format!("{category}_{n}");
    taken.insert(id.clone());
    id
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cats(names: &[&str]) -> BTreeSet<String> {
        names.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn nearest_category_by_words() {
        let c = cats(&[
            "shelf",
            "bookshelf",
            "coffee_table",
            "table",
            "chair",
            "potted_plant",
        ]);
        assert_eq!(nearest_category("Shelves", &c).as_deref(), Some("shelf"));
        assert_eq!(
            nearest_category("coffee tables", &c).as_deref(),
            Some("coffee_table")
        );
        assert_eq!(
            nearest_category("pharmacy shelf", &c).as_deref(),
            Some("shelf")
        );
        assert_eq!(
            nearest_category("small coffee table", &c).as_deref(),
            Some("coffee_table")
        );
        assert_eq!(
            nearest_category("potted plants", &c).as_deref(),
            Some("potted_plant")
        );
        assert_eq!(nearest_category("x-ray machine", &c), None);
    }
}
