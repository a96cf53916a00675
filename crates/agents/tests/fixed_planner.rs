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

/// The index of the first object resting on another.
fn supported(p: &Plan) -> usize {
    p.objects
        .iter()
        .position(|o| o.parent != ParentRef::Ground)
        .expect("the plan has a supported object")
}

#[test]
fn a_parent_must_be_a_planned_object_listed_before_its_child() {
    let mut p = knowledge_plan();
    let i = supported(&p);
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

#[test]
fn an_object_resting_on_itself_is_refused_not_a_panic() {
    let mut p = knowledge_plan();
    let i = supported(&p);
    p.objects[i].parent = ParentRef::Object(p.objects[i].id.clone());
    let (field, message) = invalid(&p);
    assert_eq!(field, format!("objects[{i}].parent"));
    assert!(
        message.contains(&format!("`{}` cannot rest on itself", p.objects[i].id)),
        "{message}"
    );
}

#[test]
fn room_size_wall_height_aisle_and_door_clearance_are_bounded() {
    use scenethesis_agents::{MAX_AISLE, MAX_DOOR_CLEARANCE, MAX_ROOM_SIDE};
    use scenethesis_scene_graph::limits::MAX_WALL_HEIGHT;
    let at = |edit: &dyn Fn(&mut Plan)| {
        let mut p = knowledge_plan();
        edit(&mut p);
        p
    };
    // At each limit: accepted.
    for p in [
        at(&|p| p.room_size = [MAX_ROOM_SIDE, MAX_ROOM_SIDE]),
        at(&|p| p.wall_height = MAX_WALL_HEIGHT),
        at(&|p| p.aisle = MAX_AISLE),
        at(&|p| p.door_clearance = MAX_DOOR_CLEARANCE),
    ] {
        check_plan(&p, None).unwrap();
    }
    // Just past it, or the issue's sizes: refused naming the field and the limit.
    for (p, want_field, limit) in [
        (
            at(&|p| p.room_size[0] = 1e6),
            "room_size (x)",
            "MAX_ROOM_SIDE",
        ),
        (
            at(&|p| p.room_size[1] = MAX_ROOM_SIDE + 0.01),
            "room_size (z)",
            "MAX_ROOM_SIDE",
        ),
        (
            at(&|p| p.wall_height = 1e6),
            "wall_height",
            "MAX_WALL_HEIGHT",
        ),
        (at(&|p| p.aisle = MAX_AISLE + 0.01), "aisle", "MAX_AISLE"),
        (at(&|p| p.aisle = 0.59), "aisle", "MAX_AISLE"),
        (
            at(&|p| p.door_clearance = 1e9),
            "door_clearance",
            "MAX_DOOR_CLEARANCE",
        ),
        (
            at(&|p| p.door_clearance = -0.1),
            "door_clearance",
            "MAX_DOOR_CLEARANCE",
        ),
    ] {
        let (field, message) = invalid(&p);
        assert_eq!(field, want_field);
        assert!(message.contains(limit), "{message}");
    }
    // JSON cannot hold a NaN; a plan built in code can.
    let issue = check_plan(&at(&|p| p.wall_height = f64::NAN), None).unwrap_err();
    assert_eq!(issue.field, "wall_height");
}

#[test]
fn a_constraint_on_itself_is_refused() {
    use scenethesis_agents::{ConstraintTarget, PlanConstraint};
    let mut p = knowledge_plan();
    let id = p.objects[0].id.clone();
    p.constraints.push(PlanConstraint {
        subject: id.clone(),
        kind: RelationKind::Beside,
        target: ConstraintTarget::Object(id.clone()),
        phrase: "beside itself".into(),
    });
    let k = p.constraints.len() - 1;
    let (field, message) = invalid(&p);
    assert_eq!(field, format!("constraints[{k}].target"));
    assert!(
        message.contains("cannot be constrained to itself"),
        "{message}"
    );
}

#[test]
fn ids_and_categories_the_scene_validator_refuses_are_refused() {
    for bad in [
        "lamp\u{1b}[31m".to_string(),
        "lamp\n0".to_string(),
        "lamp\u{202e}0".to_string(),
        " lamp".to_string(),
        "x".repeat(10_000),
    ] {
        let mut p = knowledge_plan();
        let i = p.objects.len() - 1;
        p.objects[i].id = bad.clone();
        let (field, message) = invalid(&p);
        assert_eq!(field, format!("objects[{i}].id"), "{bad:?}");
        assert!(message.contains("printable"), "{message}");
        assert!(
            !message.contains('\u{1b}') && !message.contains('\n'),
            "{message}"
        );
        assert!(message.len() < 600, "the id is shortened: {message}");

        let mut p = knowledge_plan();
        p.objects[i].category = bad.clone();
        let (field, _) = invalid(&p);
        assert_eq!(field, format!("objects[{i}].category"), "{bad:?}");
    }
    // The longest id scene.json accepts is accepted.
    let mut p = knowledge_plan();
    let mut o = p.objects[0].clone();
    o.id = "y".repeat(scenethesis_scene_graph::limits::MAX_ID_BYTES);
    o.relations.clear();
    p.objects.push(o);
    check_plan(&p, None).unwrap();
}

#[test]
fn object_relation_and_constraint_counts_are_capped() {
    use scenethesis_agents::{MAX_PLANNED_OBJECTS, MAX_PLAN_CONSTRAINTS};
    let base = knowledge_plan();
    let extra = |n: usize| {
        let mut p = base.clone();
        let template = p
            .objects
            .iter()
            .find(|o| o.parent == ParentRef::Ground && o.id != p.anchor)
            .unwrap()
            .clone();
        for k in 0..n {
            let mut o = template.clone();
            o.id = format!("extra_{k}");
            o.relations.clear();
            p.objects.push(o);
        }
        p
    };
    let at_limit = extra(MAX_PLANNED_OBJECTS - base.objects.len());
    assert!(check_plan(&at_limit, None).is_ok());
    let (field, message) = invalid(&extra(MAX_PLANNED_OBJECTS + 1 - base.objects.len()));
    assert_eq!(field, "objects");
    assert!(
        message.contains(&format!("{} objects", MAX_PLANNED_OBJECTS + 1))
            && message.contains("MAX_PLANNED_OBJECTS"),
        "{message}"
    );

    let mut p = base.clone();
    let id = p.objects[1].id.clone();
    p.objects[0].relations = vec![Relation::new(RelationKind::Beside, id); 257];
    let (field, message) = invalid(&p);
    assert_eq!(field, "objects[0].relations");
    assert!(message.contains("MAX_RELATIONS"), "{message}");

    let mut p = base;
    let constraint = scenethesis_agents::PlanConstraint {
        subject: p.objects[0].id.clone(),
        kind: RelationKind::Beside,
        target: scenethesis_agents::ConstraintTarget::Object(p.objects[1].id.clone()),
        phrase: String::new(),
    };
    p.constraints = vec![constraint; MAX_PLAN_CONSTRAINTS + 1];
    let (field, message) = invalid(&p);
    assert_eq!(field, "constraints");
    assert!(message.contains("MAX_PLAN_CONSTRAINTS"), "{message}");
}
