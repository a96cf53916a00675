//! Planning agents: turn a prompt into a scene plan (objects, anchor, hierarchy, relations) and
//! a plan into an initial layout, behind the [`Planner`] and [`Guide`] seams with offline
//! defaults.
//!
//! - [`KnowledgePlanner`] plans from scene archetypes kept in data files
//!   (`knowledge/*.toml`, embedded at build time): room size, object groups with counts, the
//!   anchor, relation templates and walkway rules, plus what the prompt itself says (objects
//!   with counts, and spatial phrases as hard constraints).
//! - [`ProceduralGuide`] lays a [`Plan`] out as a [`scenethesis_scene_graph::Scene`]: a room
//!   (or open ground), floor objects placed by their relations while one connected walkway
//!   reaches the door and every object, and children packed onto their parents' support
//!   surfaces.
//! - [`FixedPlanner`] returns a plan written beforehand (a hand-edited `plan.json`), checked
//!   field by field by [`check_plan`].
//! - [`relation_holds`] checks a scene relation geometrically; [`check_prompt`] checks that a
//!   scene holds every object its prompt names and every relation it states;
//!   [`check_arrangement`] checks the functional-arrangement rules (`knowledge/arrangement.toml`:
//!   seating faces what it serves, a bed's head against a wall, kitchen runs, …) with the same
//!   relation code.
//!
//! An LLM planner and a vision guide implement the same traits.
#![warn(missing_docs)]

pub mod arrangement;
mod fidelity;
mod fixed;
mod guide;
pub mod knowledge;
pub mod looks;
pub mod places;
mod plan;
mod planner;
mod prompt;
mod text;

pub use arrangement::{
    check_arrangement, core_categories, run_layout, ArrangementCheck, BrokenRule,
};
pub use fidelity::{
    check_prompt, constraint_holds, BrokenRelation, MissedAttribute, MissingObject, PromptCheck,
};
pub use fixed::{check_plan, FixedPlanner, PlanFileError, PlanIssue};
pub use guide::{
    room_architecture, Adoption, AssetLookup, CatalogAssets, DroppedObject, Guide, GuideError,
    GuidedLayout, NominalAssets, ProceduralGuide, UnmappedLabel, WalkwayReport,
};
pub use knowledge::{Knowledge, KnowledgeError};
pub use places::{Family, PlaceKind, Thesaurus};
pub use plan::{
    cut_prompt, Attribute, AttributeKind, ConstraintTarget, KeepClear, Layer, PlaceReading, Plan,
    PlanConstraint, PlanError, PlanRequest, PlannedObject, Planner, ReadingSource, RequestedObject,
    RoomLook, StyleSource, SurfaceLook, UnavailableAttribute, Zone, BACK_WALL, FRONT_WALL,
    LEFT_WALL, LOW_CONFIDENCE, MAX_AISLE, MAX_COUNT_PER_OBJECT, MAX_DOOR_CLEARANCE,
    MAX_PLANNED_OBJECTS, MAX_PLAN_CONSTRAINTS, MAX_PROMPT_CHARS, MAX_ROOM_SIDE, MIN_ROOM_SIDE,
    RIGHT_WALL,
};
pub use planner::KnowledgePlanner;
/// Relation semantics live in the shared model (`scenethesis-scene-graph`); re-exported here.
pub use scenethesis_scene_graph::relation_holds;
