//! The planner seam's second implementation: a fixed plan read from JSON, with errors that
//! name the field at fault.

mod common;

use std::collections::BTreeSet;
use std::path::Path;

use common::{available, plan};
use scenethesis_agents::{
    check_plan, FixedPlanner, Plan, PlanError, PlanFileError, PlanRequest, Planner,
};
use scenethesis_scene_graph::{ParentRef, Relation, RelationKind};

const PROMPT: &str = "a bedroom with a desk and a lamp on the desk";

fn knowledge_plan() -> Plan {
    plan(PROMPT, 3)
}

fn json(plan: &Plan) -> String {
    serde_json::to_string_pretty(plan).unwrap()
}

fn load(text: &str) -> Result<FixedPlanner, PlanFileError> {
    FixedPlanner::from_json(text, Path::new("plan.json"))
}

/// The issue's field and message of a plan that must be refused.
fn invalid(plan: &Plan) -> (String, String) {
    match load(&json(plan)) {
        Err(PlanFileError::Invalid { issue, .. }) => (issue.field, issue.message),
        other => panic!("expected an invalid-plan error, got {other:?}"),
    }
}

#[test]
fn a_saved_plan_round_trips_and_is_returned_for_any_prompt_and_seed() {
    let original = knowledge_plan();
    let categories: BTreeSet<String> = available().into_iter().collect();
    assert!(check_plan(&original, Some(&categories)).is_ok());
    let fixed = load(&json(&original)).expect("a planner's own plan is valid");
    assert_eq!(fixed.as_plan(), &original);
    assert_eq!(fixed.name(), "fixed");
    let request = PlanRequest::new("something else entirely", available(), 99);
    assert_eq!(fixed.plan(&request).unwrap(), original);
}

#[test]
fn duplicate_ids_are_refused_naming_the_second_object() {
    let mut p = knowledge_plan();
    let first = p.objects[0].id.clone();
    p.objects[1].id = first.clone();
    let (field, message) = invalid(&p);
    assert_eq!(field, "objects[1].id");
    assert!(
        message.contains(&format!("duplicate id `{first}`")),
        "{message}"
    );
    assert!(message.contains("objects[0]"), "{message}");
}

#[test]
fn a_relation_to_an_unknown_object_is_refused() {
    let mut p = knowledge_plan();
    let i = p.objects.len() - 1;
    p.objects[i]
        .relations
        .push(Relation::new(RelationKind::Beside, "unicorn_0"));
    let j = p.objects[i].relations.len() - 1;
    let (field, message) = invalid(&p);
    assert_eq!(field, format!("objects[{i}].relations[{j}].target"));
    assert!(message.contains("unknown object `unicorn_0`"), "{message}");
}

#[test]
fn a_parent_must_be_a_planned_object_listed_before_its_child() {
    let mut p = knowledge_plan();
    let i = p
        .objects
        .iter()
        .position(|o| o.parent != ParentRef::Ground)
        .expect("the plan has a supported object");
    p.objects[i].parent = ParentRef::Object("nowhere_0".into());
    let (field, message) = invalid(&p);
    assert_eq!(field, format!("objects[{i}].parent"));
    assert!(message.contains("unknown object `nowhere_0`"), "{message}");

    let mut p = knowledge_plan();
    let child = p.objects.remove(i);
    p.objects.insert(0, child);
    let (field, _) = invalid(&p);
    assert_eq!(field, "objects[0].parent");
}

#[test]
fn an_anchor_that_is_not_a_ground_object_is_refused() {
    let mut p = knowledge_plan();
    p.anchor = "ghost".into();
    assert_eq!(invalid(&p).0, "anchor");
    let mut p = knowledge_plan();
    p.anchor = p
        .objects
        .iter()
        .find(|o| o.parent != ParentRef::Ground)
        .unwrap()
        .id
        .clone();
    let (field, message) = invalid(&p);
    assert_eq!(field, "anchor");
    assert!(message.contains("must stand on the ground"), "{message}");
}

#[test]
fn a_support_that_does_not_fit_the_parent_is_refused() {
    let mut p = knowledge_plan();
    p.objects[0].support = RelationKind::On;
    let (field, message) = invalid(&p);
    assert_eq!(field, "objects[0].support");
    assert!(message.contains("on-floor"), "{message}");
}

#[test]
fn a_plan_hangs_objects_by_zone_not_by_a_wall_parent_or_a_mounted_support() {
    // Support `mounted` on the ground: refused, pointing at the zone.
    let mut p = knowledge_plan();
    let last = p.objects.len() - 1;
    p.objects[last].parent = ParentRef::Ground;
    p.objects[last].support = RelationKind::Mounted;
    let (field, message) = invalid(&p);
    assert_eq!(field, format!("objects[{last}].support"));
    assert!(message.contains("wall-mounted"), "{message}");
    // A wall id as parent: refused the same way, not as an unknown object.
    let mut p = knowledge_plan();
    p.objects[last].parent = ParentRef::Object("wall_0".into());
    p.objects[last].support = RelationKind::On;
    let (field, message) = invalid(&p);
    assert_eq!(field, format!("objects[{last}].parent"));
    assert!(
        message.contains("`wall_0` is a wall") && message.contains("wall-mounted"),
        "{message}"
    );
}

#[test]
fn an_unknown_category_fails_when_planning_with_the_sources_categories() {
    let mut p = knowledge_plan();
    p.objects[2].category = "hoverboard".into();
    // Structurally fine: the category list belongs to the asset source.
    let fixed = load(&json(&p)).expect("structure is valid");
    let request = PlanRequest::new(PROMPT, available(), 0);
    match fixed.plan(&request) {
        Err(PlanError::InvalidPlan { provider, message }) => {
            assert_eq!(provider, "fixed");
            assert!(message.starts_with("objects[2].category: "), "{message}");
            assert!(message.contains("`hoverboard`"), "{message}");
        }
        other => panic!("expected InvalidPlan, got {other:?}"),
    }
    let only: BTreeSet<String> = p.categories().iter().map(|c| c.to_string()).collect();
    assert!(check_plan(&p, Some(&only)).is_ok());
}

#[test]
fn syntax_errors_name_the_field_and_the_file() {
    let p = knowledge_plan();
    let i = p
        .objects
        .iter()
        .position(|o| o.support == RelationKind::OnFloor)
        .expect("a floor object");
    let text = json(&p).replacen("\"on-floor\"", "\"hovering\"", 1);
    match load(&text) {
        Err(e @ PlanFileError::Syntax { .. }) => {
            let PlanFileError::Syntax { field, message, .. } = &e else {
                unreachable!()
            };
            assert_eq!(field, &format!("objects[{i}].support"));
            assert!(message.contains("hovering"), "{message}");
            let shown = e.to_string();
            assert!(
                shown.starts_with(&format!(
                    "plan file plan.json: field `objects[{i}].support`"
                )),
                "{shown}"
            );
        }
        other => panic!("expected a syntax error, got {other:?}"),
    }
    let missing = json(&p).replacen("\"anchor\"", "\"anchorr\"", 1);
    match load(&missing) {
        Err(PlanFileError::Syntax { message, .. }) => {
            assert!(message.contains("missing field `anchor`"), "{message}")
        }
        other => panic!("expected a syntax error, got {other:?}"),
    }
}

#[test]
fn a_missing_file_is_a_read_error_naming_it() {
    let err = FixedPlanner::from_file(Path::new("/nonexistent/plan.json")).unwrap_err();
    assert!(matches!(err, PlanFileError::Read { .. }));
    assert!(err.to_string().contains("/nonexistent/plan.json"), "{err}");
}
