//! A planner that returns a plan written beforehand: the `plan.json` a user saved with
//! `scenethesis plan` and edited by hand, or one built in code.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use scenethesis_scene_graph::{Environment, ParentRef, RelationKind, GROUND_ID};

use crate::plan::{
    ConstraintTarget, Plan, PlanError, PlanRequest, Planner, Zone, BACK_WALL, FRONT_WALL,
    LEFT_WALL, RIGHT_WALL,
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

/// Checks that a plan holds together: a non-empty, unique id per object that does not name the
/// ground or a wall; parents that are objects listed earlier (and a support kind that fits the
/// parent); an anchor that is a ground object; relation and constraint targets that are
/// planned objects or walls of the room; a positive room size and wall height and an aisle of
/// at least 0.6 m. With `categories`, every object's category must be one of them. The first
/// issue found is returned.
pub fn check_plan(plan: &Plan, categories: Option<&BTreeSet<String>>) -> Result<(), PlanIssue> {
    let positive = |v: f64| v.is_finite() && v > 0.0;
    for (axis, v) in ["x", "z"].iter().zip(plan.room_size) {
        if !positive(v) {
            return Err(PlanIssue::new(
                format!("room_size ({axis})"),
                format!("expected a positive size in metres, found {v}"),
            ));
        }
    }
    if !positive(plan.wall_height) {
        return Err(PlanIssue::new(
            "wall_height",
            format!(
                "expected a positive height in metres, found {}",
                plan.wall_height
            ),
        ));
    }
    if !(plan.aisle.is_finite() && plan.aisle >= 0.6) {
        return Err(PlanIssue::new(
            "aisle",
            format!(
                "expected a walkway width of at least 0.6 m, found {}",
                plan.aisle
            ),
        ));
    }
    if !(plan.door_clearance.is_finite() && plan.door_clearance >= 0.0) {
        return Err(PlanIssue::new(
            "door_clearance",
            format!(
                "expected a non-negative depth in metres, found {}",
                plan.door_clearance
            ),
        ));
    }
    let indoor = plan.environment == Environment::Indoor;
    let is_wall = |id: &str| indoor && WALLS.contains(&id);

    let mut index: BTreeMap<&str, usize> = BTreeMap::new();
    for (i, object) in plan.objects.iter().enumerate() {
        let field = |name: &str| format!("objects[{i}].{name}");
        let id = object.id.as_str();
        if id.trim().is_empty() {
            return Err(PlanIssue::new(
                field("id"),
                "expected a non-empty object id",
            ));
        }
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
        let wall_parent = |wall: &str| {
            PlanIssue::new(
                field("parent"),
                format!(
                    "`{wall}` is a wall; a plan hangs an object on a wall with parent `ground` and \
                     zone `wall-mounted` (the layout picks the wall, and scene.json then names it \
                     as the parent with support `mounted`)"
                ),
            )
        };
        match &object.parent {
            ParentRef::Wall(wall) => return Err(wall_parent(wall)),
            ParentRef::Ground if object.support == RelationKind::Mounted => {
                return Err(PlanIssue::new(
                    field("support"),
                    "`mounted` is what scene.json says of an object hanging on a wall; in a plan \
                     give it support `against-wall` and zone `wall-mounted`",
                ));
            }
            ParentRef::Ground => {
                if !matches!(
                    object.support,
                    RelationKind::OnFloor | RelationKind::AgainstWall
                ) {
                    return Err(PlanIssue::new(
                        field("support"),
                        format!(
                            "`{}` cannot rest on the ground; expected `on-floor` or \
                             `against-wall` for an object whose parent is `ground`",
                            object.support
                        ),
                    ));
                }
                if object.support == RelationKind::AgainstWall && !indoor {
                    return Err(PlanIssue::new(
                        field("support"),
                        "`against-wall` needs walls, but the plan is outdoor",
                    ));
                }
            }
            ParentRef::Object(parent) => {
                match index.get(parent.as_str()) {
                    Some(&p) if p < i => {}
                    Some(_) => unreachable!("ids are unique and this one was just inserted"),
                    None if WALLS.contains(&parent.as_str()) => return Err(wall_parent(parent)),
                    None => {
                        let known = plan.objects.iter().any(|o| &o.id == parent);
                        return Err(PlanIssue::new(
                            field("parent"),
                            if known {
                                format!(
                                    "`{parent}` is listed after `{id}`; list parents before \
                                     the objects resting on them"
                                )
                            } else {
                                format!("unknown object `{parent}`; expected `ground` or the id of a planned object")
                            },
                        ));
                    }
                }
                if !matches!(
                    object.support,
                    RelationKind::On | RelationKind::Inside | RelationKind::Under
                ) {
                    return Err(PlanIssue::new(
                        field("support"),
                        format!(
                            "`{}` cannot hold `{id}` on `{parent}`; expected `on`, `inside` or \
                             `under` for an object whose parent is another object",
                            object.support
                        ),
                    ));
                }
            }
        }
        if let Zone::Wall { wall: Some(wall) } = &object.zone {
            if !is_wall(wall) {
                return Err(PlanIssue::new(
                    field("zone.wall"),
                    format!(
                        "unknown wall `{wall}`; expected one of {}",
                        WALLS.join(", ")
                    ),
                ));
            }
        }
    }
    let known = |target: &str| index.contains_key(target) || is_wall(target);
    for (i, object) in plan.objects.iter().enumerate() {
        for (j, relation) in object.relations.iter().enumerate() {
            let target = relation.target.as_str();
            if target == object.id {
                return Err(PlanIssue::new(
                    format!("objects[{i}].relations[{j}].target"),
                    format!("`{}` cannot relate to itself", object.id),
                ));
            }
            if !known(target) {
                return Err(PlanIssue::new(
                    format!("objects[{i}].relations[{j}].target"),
                    format!(
                        "unknown object `{target}`; expected the id of a planned object{}",
                        if indoor {
                            " or a wall (wall_0 … wall_3)"
                        } else {
                            ""
                        }
                    ),
                ));
            }
        }
    }
    match plan.object(&plan.anchor) {
        None => {
            return Err(PlanIssue::new(
                "anchor",
                format!(
                    "unknown object `{}`; expected the id of a planned object",
                    plan.anchor
                ),
            ))
        }
        Some(anchor) if anchor.parent != ParentRef::Ground => {
            return Err(PlanIssue::new(
                "anchor",
                format!(
                    "`{}` rests on `{}`; the anchor must stand on the ground",
                    plan.anchor, anchor.parent
                ),
            ))
        }
        Some(_) => {}
    }
    for (k, constraint) in plan.constraints.iter().enumerate() {
        if !index.contains_key(constraint.subject.as_str()) {
            return Err(PlanIssue::new(
                format!("constraints[{k}].subject"),
                format!(
                    "unknown object `{}`; expected the id of a planned object",
                    constraint.subject
                ),
            ));
        }
        let bad = match &constraint.target {
            ConstraintTarget::Object(id) if !index.contains_key(id.as_str()) => Some(format!(
                "unknown object `{id}`; expected the id of a planned object"
            )),
            ConstraintTarget::Wall(wall) if !is_wall(wall) => Some(format!(
                "unknown wall `{wall}`; expected one of {}",
                WALLS.join(", ")
            )),
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
