//! A planner that returns a plan written beforehand: the `plan.json` a user saved with
//! `scenethesis plan` and edited by hand, or one built in code.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use scenethesis_scene_graph::limits::{MAX_ID_BYTES, MAX_RELATIONS, MAX_WALL_HEIGHT};
use scenethesis_scene_graph::{
    is_printable_id, printable, Environment, ParentRef, RelationKind, GROUND_ID,
};

use crate::plan::{
    ConstraintTarget, Plan, PlanError, PlanRequest, PlannedObject, Planner, Zone, BACK_WALL,
    FRONT_WALL, LEFT_WALL, MAX_AISLE, MAX_DOOR_CLEARANCE, MAX_PLANNED_OBJECTS,
    MAX_PLAN_CONSTRAINTS, MAX_ROOM_SIDE, RIGHT_WALL,
};

/// The wall ids of a planned room.
const WALLS: [&str; 4] = [BACK_WALL, LEFT_WALL, FRONT_WALL, RIGHT_WALL];

/// One thing wrong with a plan, located by its field path (`objects[2].parent`).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{field}: {message}")]
pub struct PlanIssue {
    /// The field, as a path into the plan (`anchor`, `objects[2].relations[0].target`).
    pub field: String,
    /// What is wrong and what was expected.
    pub message: String,
}

impl PlanIssue {
    fn new(field: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            field: field.into(),
            message: message.into(),
        }
    }
}

/// Why a plan file could not be used.
#[derive(Debug, thiserror::Error)]
pub enum PlanFileError {
    /// The file could not be read.
    #[error("cannot read the plan file {}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The file is not JSON of the plan's shape.
    #[error("plan file {}: field `{field}`: {message}", path.display())]
    Syntax {
        /// The file.
        path: PathBuf,
        /// The field the parser was in (`.` for the top level).
        field: String,
        /// The parser's message, with line and column.
        message: String,
    },
    /// The file parses but the plan contradicts itself.
    #[error("plan file {}: {issue}", path.display())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// What is wrong, and where.
        issue: PlanIssue,
    },
}

/// Checks that a plan holds together and stays within the plan limits (`docs/limits.md`): a
/// room of positive sides up to [`MAX_ROOM_SIDE`], a positive wall height up to
/// [`MAX_WALL_HEIGHT`], an aisle from 0.6 m to [`MAX_AISLE`] and a door clearance up to
/// [`MAX_DOOR_CLEARANCE`]; at most [`MAX_PLANNED_OBJECTS`] objects, [`MAX_RELATIONS`] relations
/// per object and [`MAX_PLAN_CONSTRAINTS`] constraints; a unique id per object that the scene
/// validator accepts ([`is_printable_id`]) and does not name the ground or a wall, and a
/// category it accepts too; parents that are other objects listed earlier (and a support kind
/// that fits the parent); an anchor that is a ground object; relation and constraint targets
/// that are other planned objects or walls of the room. With `categories`, every object's
/// category must be one of them. The first issue found is returned.
pub fn check_plan(plan: &Plan, categories: Option<&BTreeSet<String>>) -> Result<(), PlanIssue> {
    check_room(plan)?;
    check_counts(plan)?;
    let indoor = plan.environment == Environment::Indoor;
    let mut index: BTreeMap<&str, usize> = BTreeMap::new();
    for (i, object) in plan.objects.iter().enumerate() {
        check_object(plan, i, &mut index, categories)?;
        check_zone(i, object, indoor)?;
    }
    check_relations(plan, &index, indoor)?;
    check_anchor(plan)?;
    check_constraints(plan, &index, indoor)?;
    check_looks(plan)
}

/// The looks: every material an attribute names is a palette entry or a fabric token of
/// `knowledge/looks.toml`, every family choice an entry of its family, every surface base an
/// entry.
fn check_looks(plan: &Plan) -> Result<(), PlanIssue> {
    use scenethesis_procedural::looks::{named_material, Palette};
    let looks = crate::looks::Looks::builtin();
    let known_material = |m: &str| {
        named_material(m).is_some()
            || looks
                .materials
                .iter()
                .any(|(_, w)| w.token.as_deref() == Some(m))
    };
    let check_attributes = |field: String, attributes: &[crate::plan::Attribute]| {
        for (k, a) in attributes.iter().enumerate() {
            if let Some(m) = a.look.material.as_deref().filter(|m| !known_material(m)) {
                return Err(PlanIssue::new(
                    format!("{field}.attributes[{k}].material"),
                    format!(
                        "unknown material `{}`: expected a palette entry (`oak`, `brown_leather`, \
                         `clear_glass`, …) or a fabric token of knowledge/looks.toml (`velvet`, …)",
                        shown(m)
                    ),
                ));
            }
        }
        Ok(())
    };
    for (i, object) in plan.objects.iter().enumerate() {
        check_attributes(format!("objects[{i}]"), &object.attributes)?;
    }
    let Some(look) = &plan.look else {
        return Ok(());
    };
    for (family, entry) in &look.families {
        let field = format!("look.families.{}", shown(family));
        let Some(palette) = Palette::from_name(family) else {
            return Err(PlanIssue::new(
                field,
                "unknown palette family (`wood`, `fabric`, …)",
            ));
        };
        if named_material(entry).map(|(p, _)| p) != Some(palette) {
            return Err(PlanIssue::new(
                field,
                format!("`{}` is no `{family}` entry", shown(entry)),
            ));
        }
    }
    for (name, surface) in &look.surfaces {
        let field = format!("look.surfaces.{}", shown(name));
        if !crate::looks::SURFACES.contains(&name.as_str()) {
            return Err(PlanIssue::new(field, "expected floor, walls or ceiling"));
        }
        if named_material(&surface.base).is_none() {
            return Err(PlanIssue::new(
                format!("{field}.base"),
                format!("`{}` is no palette entry", shown(&surface.base)),
            ));
        }
        check_attributes(field, &surface.attributes)?;
    }
    Ok(())
}

/// `text` escaped for a message and cut to 80 characters.
fn shown(text: &str) -> String {
    let text = printable(text);
    if text.chars().count() > 80 {
        format!("{}…", text.chars().take(79).collect::<String>())
    } else {
        text.into_owned()
    }
}

/// Checks `value` of `field` is finite and within `min..=max` metres (`min` exclusive when
/// `open_min`).
fn check_range(
    field: String,
    value: f64,
    (min, open_min): (f64, bool),
    max: (f64, &str),
    what: &str,
) -> Result<(), PlanIssue> {
    let low_ok = if open_min { value > min } else { value >= min };
    if value.is_finite() && low_ok && value <= max.0 {
        return Ok(());
    }
    let low = if open_min {
        format!("more than {min}")
    } else {
        format!("at least {min}")
    };
    Err(PlanIssue::new(
        field,
        format!(
            "expected {what} of {low} and at most {} m (the limit {}, see docs/limits.md), \
             found {value}",
            max.0, max.1
        ),
    ))
}

/// The room's size, wall height, aisle and door clearance.
fn check_room(plan: &Plan) -> Result<(), PlanIssue> {
    for (axis, v) in ["x", "z"].iter().zip(plan.room_size) {
        check_range(
            format!("room_size ({axis})"),
            v,
            (0.0, true),
            (MAX_ROOM_SIDE, "MAX_ROOM_SIDE"),
            "a size in metres",
        )?;
    }
    check_range(
        "wall_height".into(),
        plan.wall_height,
        (0.0, true),
        (MAX_WALL_HEIGHT, "MAX_WALL_HEIGHT"),
        "a height in metres",
    )?;
    check_range(
        "aisle".into(),
        plan.aisle,
        (0.6, false),
        (MAX_AISLE, "MAX_AISLE"),
        "a walkway width in metres",
    )?;
    check_range(
        "door_clearance".into(),
        plan.door_clearance,
        (0.0, false),
        (MAX_DOOR_CLEARANCE, "MAX_DOOR_CLEARANCE"),
        "a depth in metres",
    )
}

/// The number of objects, relations per object and constraints.
fn check_counts(plan: &Plan) -> Result<(), PlanIssue> {
    let too_many = |field: String, what: &str, found: usize, limit: usize, name: &str| {
        PlanIssue::new(
            field,
            format!("{found} {what}, more than the limit of {limit} ({name}, see docs/limits.md)"),
        )
    };
    if plan.objects.len() > MAX_PLANNED_OBJECTS {
        return Err(too_many(
            "objects".into(),
            "objects",
            plan.objects.len(),
            MAX_PLANNED_OBJECTS,
            "MAX_PLANNED_OBJECTS",
        ));
    }
    if let Some((i, o)) =
        (plan.objects.iter().enumerate()).find(|(_, o)| o.relations.len() > MAX_RELATIONS)
    {
        return Err(too_many(
            format!("objects[{i}].relations"),
            "relations",
            o.relations.len(),
            MAX_RELATIONS,
            "MAX_RELATIONS",
        ));
    }
    if plan.constraints.len() > MAX_PLAN_CONSTRAINTS {
        return Err(too_many(
            "constraints".into(),
            "constraints",
            plan.constraints.len(),
            MAX_PLAN_CONSTRAINTS,
            "MAX_PLAN_CONSTRAINTS",
        ));
    }
    Ok(())
}

/// Checks that `value` of `field` is an id the scene validator accepts.
fn check_printable(field: String, value: &str) -> Result<(), PlanIssue> {
    if is_printable_id(value) {
        return Ok(());
    }
    Err(PlanIssue::new(
        field,
        format!(
            "`{}` ({} bytes) cannot be used: expected 1 to {MAX_ID_BYTES} bytes of printable \
             characters (no control or bidirectional formatting characters) without leading or \
             trailing spaces, as scene.json requires",
            shown(value),
            value.len()
        ),
    ))
}

/// Object `i`: its id (entered in `index`), category, parent and support.
fn check_object<'p>(
    plan: &'p Plan,
    i: usize,
    index: &mut BTreeMap<&'p str, usize>,
    categories: Option<&BTreeSet<String>>,
) -> Result<(), PlanIssue> {
    let object = &plan.objects[i];
    let field = |name: &str| format!("objects[{i}].{name}");
    let id = object.id.as_str();
    if id.trim().is_empty() {
        return Err(PlanIssue::new(
            field("id"),
            "expected a non-empty object id",
        ));
    }
    check_printable(field("id"), id)?;
    if id == GROUND_ID || WALLS.contains(&id) {
        return Err(PlanIssue::new(
            field("id"),
            format!("`{id}` is reserved for the ground or a wall; pick another id"),
        ));
    }
    if let Some(first) = index.insert(id, i) {
        return Err(PlanIssue::new(
            field("id"),
            format!("duplicate id `{id}` (already used by objects[{first}])"),
        ));
    }
    check_printable(field("category"), &object.category)?;
    if let Some(categories) = categories {
        if !categories.contains(&object.category) {
            return Err(PlanIssue::new(
                field("category"),
                format!(
                    "unknown category `{}`; expected one of the {} categories of the asset \
                     source (see `scenethesis assets`)",
                    object.category,
                    categories.len()
                ),
            ));
        }
    }
    check_parent(plan, i, index)
}

/// The issue of an object whose parent is a wall.
fn wall_parent(field: String, wall: &str) -> PlanIssue {
    PlanIssue::new(
        field,
        format!(
            "`{}` is a wall; a plan hangs an object on a wall with parent `ground` and \
             zone `wall-mounted` (the layout picks the wall, and scene.json then names it \
             as the parent with support `mounted`)",
            shown(wall)
        ),
    )
}

/// Object `i`'s parent and the support kind it rests on it with.
fn check_parent(plan: &Plan, i: usize, index: &BTreeMap<&str, usize>) -> Result<(), PlanIssue> {
    let object = &plan.objects[i];
    let field = |name: &str| format!("objects[{i}].{name}");
    match &object.parent {
        ParentRef::Wall(wall) => Err(wall_parent(field("parent"), wall)),
        ParentRef::Ground => check_ground_support(object, field("support"), plan.environment),
        ParentRef::Object(parent) => {
            check_object_parent(plan, i, parent, index)?;
            if !matches!(
                object.support,
                RelationKind::On | RelationKind::Inside | RelationKind::Under
            ) {
                return Err(PlanIssue::new(
                    field("support"),
                    format!(
                        "`{}` cannot hold `{}` on `{parent}`; expected `on`, `inside` or \
                         `under` for an object whose parent is another object",
                        object.support, object.id
                    ),
                ));
            }
            Ok(())
        }
    }
}

/// The support of an object standing on the ground.
fn check_ground_support(
    object: &PlannedObject,
    field: String,
    environment: Environment,
) -> Result<(), PlanIssue> {
    match object.support {
        RelationKind::Mounted => Err(PlanIssue::new(
            field,
            "`mounted` is what scene.json says of an object hanging on a wall; in a plan \
             give it support `against-wall` and zone `wall-mounted`",
        )),
        RelationKind::AgainstWall if environment != Environment::Indoor => Err(PlanIssue::new(
            field,
            "`against-wall` needs walls, but the plan is outdoor",
        )),
        RelationKind::OnFloor | RelationKind::AgainstWall => Ok(()),
        other => Err(PlanIssue::new(
            field,
            format!(
                "`{other}` cannot rest on the ground; expected `on-floor` or \
                 `against-wall` for an object whose parent is `ground`"
            ),
        )),
    }
}

/// Object `i`'s parent `parent` is another object listed before it.
fn check_object_parent(
    plan: &Plan,
    i: usize,
    parent: &str,
    index: &BTreeMap<&str, usize>,
) -> Result<(), PlanIssue> {
    let field = format!("objects[{i}].parent");
    let id = plan.objects[i].id.as_str();
    let message = match index.get(parent) {
        Some(&p) if p < i => return Ok(()),
        Some(_) => format!("`{id}` cannot rest on itself; expected `ground` or the id of another planned object listed before it"),
        None if WALLS.contains(&parent) => return Err(wall_parent(field, parent)),
        None if plan.objects.iter().any(|o| o.id == parent) => format!(
            "`{parent}` is listed after `{id}`; list parents before the objects resting on them"
        ),
        None => format!(
            "unknown object `{}`; expected `ground` or the id of a planned object",
            shown(parent)
        ),
    };
    Err(PlanIssue::new(field, message))
}

/// A wall zone names a wall of an indoor room.
fn check_zone(i: usize, object: &PlannedObject, indoor: bool) -> Result<(), PlanIssue> {
    match &object.zone {
        Zone::Wall { wall: Some(wall) } if !(indoor && WALLS.contains(&wall.as_str())) => {
            Err(PlanIssue::new(
                format!("objects[{i}].zone.wall"),
                format!(
                    "unknown wall `{}`; expected one of {}",
                    shown(wall),
                    WALLS.join(", ")
                ),
            ))
        }
        _ => Ok(()),
    }
}

/// Relation targets are other planned objects or walls of the room.
fn check_relations(
    plan: &Plan,
    index: &BTreeMap<&str, usize>,
    indoor: bool,
) -> Result<(), PlanIssue> {
    let known = |target: &str| index.contains_key(target) || (indoor && WALLS.contains(&target));
    for (i, object) in plan.objects.iter().enumerate() {
        for (j, relation) in object.relations.iter().enumerate() {
            let field = format!("objects[{i}].relations[{j}].target");
            let target = relation.target.as_str();
            if target == object.id {
                return Err(PlanIssue::new(
                    field,
                    format!("`{}` cannot relate to itself", object.id),
                ));
            }
            if !known(target) {
                let walls = if indoor {
                    " or a wall (wall_0 … wall_3)"
                } else {
                    ""
                };
                return Err(PlanIssue::new(
                    field,
                    format!(
                        "unknown object `{}`; expected the id of a planned object{walls}",
                        shown(target)
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The anchor is a planned object standing on the ground.
fn check_anchor(plan: &Plan) -> Result<(), PlanIssue> {
    match plan.object(&plan.anchor) {
        None => Err(PlanIssue::new(
            "anchor",
            format!(
                "unknown object `{}`; expected the id of a planned object",
                shown(&plan.anchor)
            ),
        )),
        Some(anchor) if anchor.parent != ParentRef::Ground => Err(PlanIssue::new(
            "anchor",
            format!(
                "`{}` rests on `{}`; the anchor must stand on the ground",
                plan.anchor, anchor.parent
            ),
        )),
        Some(_) => Ok(()),
    }
}

/// Constraint subjects are planned objects; targets are other planned objects or walls.
fn check_constraints(
    plan: &Plan,
    index: &BTreeMap<&str, usize>,
    indoor: bool,
) -> Result<(), PlanIssue> {
    let unknown = |id: &str| {
        format!(
            "unknown object `{}`; expected the id of a planned object",
            shown(id)
        )
    };
    for (k, constraint) in plan.constraints.iter().enumerate() {
        let subject = constraint.subject.as_str();
        if !index.contains_key(subject) {
            return Err(PlanIssue::new(
                format!("constraints[{k}].subject"),
                unknown(subject),
            ));
        }
        let bad = match &constraint.target {
            ConstraintTarget::Object(id) if id == subject => Some(format!(
                "`{subject}` cannot be constrained to itself; expected another planned object"
            )),
            ConstraintTarget::Object(id) if !index.contains_key(id.as_str()) => Some(unknown(id)),
            ConstraintTarget::Wall(wall) if !(indoor && WALLS.contains(&wall.as_str())) => {
                Some(format!(
                    "unknown wall `{}`; expected one of {}",
                    shown(wall),
                    WALLS.join(", ")
                ))
            }
            _ => None,
        };
        if let Some(message) = bad {
            return Err(PlanIssue::new(format!("constraints[{k}].target"), message));
        }
    }
    Ok(())
}

/// A [`Planner`] that ignores the prompt and returns one fixed [`Plan`]: a hand-edited
/// `plan.json` (`scenethesis generate --plan plan.json`) or a plan built in code. The plan is
/// checked when the planner is made ([`check_plan`]), and its categories against the request's
/// available categories when it plans, so a plan the asset source cannot furnish fails early
/// with the field named.
#[derive(Debug, Clone, PartialEq)]
pub struct FixedPlanner {
    plan: Plan,
}

impl FixedPlanner {
    /// A planner returning `plan`, after checking that it holds together.
    pub fn new(plan: Plan) -> Result<Self, PlanIssue> {
        check_plan(&plan, None)?;
        Ok(Self { plan })
    }

    /// Reads and checks the plan in the JSON file `path` (the format of `scenethesis plan`,
    /// documented in `docs/plan.md`).
    pub fn from_file(path: &Path) -> Result<Self, PlanFileError> {
        let read_err = |source| PlanFileError::Read {
            path: path.to_owned(),
            source,
        };
        let bytes = scenethesis_scene_graph::read_bounded(
            path,
            scenethesis_scene_graph::limits::MAX_PLAN_JSON_BYTES,
        )
        .map_err(read_err)?;
        let text = String::from_utf8(bytes).map_err(|_| {
            read_err(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                "is not UTF-8 text",
            ))
        })?;
        Self::from_json(&text, path)
    }

    /// Parses and checks a plan from JSON `text`; `path` names its origin in errors.
    pub fn from_json(text: &str, path: &Path) -> Result<Self, PlanFileError> {
        let de = &mut serde_json::Deserializer::from_str(text);
        let plan: Plan =
            serde_path_to_error::deserialize(de).map_err(|e| PlanFileError::Syntax {
                path: path.to_owned(),
                field: e.path().to_string(),
                message: e.into_inner().to_string(),
            })?;
        check_plan(&plan, None).map_err(|issue| PlanFileError::Invalid {
            path: path.to_owned(),
            issue,
        })?;
        Ok(Self { plan })
    }

    /// The plan this planner returns.
    pub fn as_plan(&self) -> &Plan {
        &self.plan
    }
}

impl Planner for FixedPlanner {
    fn name(&self) -> &str {
        "fixed"
    }

    /// Returns the fixed plan whatever the prompt and seed; fails with
    /// [`PlanError::InvalidPlan`] naming the field when an object's category is not among the
    /// request's available categories.
    fn plan(&self, request: &PlanRequest) -> Result<Plan, PlanError> {
        check_plan(&self.plan, Some(&request.available_categories)).map_err(|issue| {
            PlanError::InvalidPlan {
                provider: self.name().to_owned(),
                message: issue.to_string(),
            }
        })?;
        Ok(self.plan.clone())
    }
}
