//! The offline planner: knowledge files, prompt reading, benchmark plans.

mod common;

use std::collections::BTreeSet;

use common::{available, plan, BENCHMARK, DETAILED};
use scenethesis_agents::{
    ConstraintTarget, Knowledge, KnowledgePlanner, Layer, Plan, PlanError, PlanRequest, Planner,
    BACK_WALL,
};
use scenethesis_scene_graph::{Environment, ParentRef, RelationKind};

#[test]
fn knowledge_holds_at_least_30_archetypes_including_the_papers_categories() {
    let k = Knowledge::builtin();
    assert!(
        k.archetypes.len() >= 30,
        "{} archetypes",
        k.archetypes.len()
    );
    for name in [
        "living_room",
        "playroom",
        "garage",
        "warehouse",
        "bookstore",
        "convenience_store",
        "museum",
        "piano_showroom",
        "gym",
        "billiard_club",
        "hospital_ward",
        "laboratory",
        "bedroom",
        "kitchen",
        "dining_room",
        "office",
        "classroom",
        "library",
        "cafe",
        "restaurant",
        "bakery",
        "bathroom",
        "art_studio",
        "workshop",
        "beach",
        "park",
        "campsite",
        "street_cafe",
        "backyard",
    ] {
        assert!(k.archetype(name).is_some(), "missing archetype {name}");
    }
    for a in &k.archetypes {
        let floor = a
            .objects
            .iter()
            .filter(|g| !matches!(g.place, scenethesis_agents::knowledge::Place::Support(..)))
            .count();
        assert!(floor >= 5, "{}: only {floor} floor groups", a.name);
        assert!(a.size[0] >= 3.0 && a.aisle >= 0.6, "{}", a.name);
    }
}

fn doc_categories() -> BTreeSet<String> {
    let doc = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/asset-categories.md"
    ))
    .expect("docs/asset-categories.md");
    doc.lines()
        .filter(|l| l.starts_with('|') && !l.contains("---") && !l.contains("| group"))
        .filter_map(|l| l.split('|').nth(2))
        .flat_map(|cell| {
            cell.split(',')
                .map(|c| c.trim().to_owned())
                .collect::<Vec<_>>()
        })
        .filter(|c| !c.is_empty())
        .collect()
}

#[test]
fn every_knowledge_category_is_a_documented_library_category() {
    let doc = doc_categories();
    assert!(doc.len() > 100, "parsed {} categories", doc.len());
    let k = Knowledge::builtin();
    let known: BTreeSet<String> = k.category_names().map(str::to_owned).collect();
    assert_eq!(
        known, doc,
        "the category table must list exactly the documented categories"
    );
    for a in &k.archetypes {
        for g in &a.objects {
            assert!(
                doc.contains(&g.category),
                "{}: `{}` is not documented",
                a.name,
                g.category
            );
        }
    }
}

#[test]
fn every_knowledge_category_exists_in_the_asset_registry() {
    let registry: BTreeSet<String> = available().into_iter().collect();
    for name in Knowledge::builtin().category_names() {
        assert!(
            registry.contains(name),
            "`{name}` has no generator in scenethesis_procedural::catalog"
        );
    }
}

#[test]
fn benchmark_prompts_plan_their_key_categories() {
    for (prompt, expected) in BENCHMARK {
        let plan = plan(prompt, 0);
        let cats = plan.categories();
        for c in *expected {
            assert!(
                cats.contains(c),
                "{prompt}: plan lacks `{c}` (has {cats:?})"
            );
        }
        let anchor = plan.object(&plan.anchor).expect("anchor planned");
        assert_eq!(anchor.parent, ParentRef::Ground, "{prompt}");
        assert_eq!(plan.objects[0].id, plan.anchor, "{prompt}: anchor first");
    }
    assert_eq!(
        plan("a peaceful beach during sunset", 0).environment,
        Environment::Outdoor
    );
    assert_eq!(plan("a garage", 0).environment, Environment::Indoor);
    assert_eq!(plan("a gym room", 0).scene_type, "gym");
    assert_eq!(plan("a piano showroom", 0).scene_type, "piano_showroom");
}

fn assert_simple_plan_is_rich(prompt: &str, plan: &Plan) {
    let cats = plan.categories();
    assert!(
        cats.len() >= 15,
        "{prompt}: {} categories {cats:?}",
        cats.len()
    );
    assert!(
        plan.objects.len() >= 20,
        "{prompt}: {} objects",
        plan.objects.len()
    );
    for layer in [Layer::Background, Layer::Middle, Layer::Foreground] {
        assert!(
            plan.layer(layer).next().is_some(),
            "{prompt}: empty {layer:?} layer"
        );
    }
    let kinds = plan.relation_kinds();
    assert!(kinds.contains(&RelationKind::On), "{prompt}: {kinds:?}");
    assert!(kinds.len() >= 4, "{prompt}: {kinds:?}");
    // Every parent exists and comes first.
    for (i, o) in plan.objects.iter().enumerate() {
        if let ParentRef::Object(p) = &o.parent {
            let pi = plan
                .objects
                .iter()
                .position(|x| &x.id == p)
                .unwrap_or_else(|| panic!("{prompt}: {} has unknown parent {p}", o.id));
            assert!(pi < i, "{prompt}: parent {p} after child {}", o.id);
        }
        for r in &o.relations {
            assert!(
                r.target.starts_with("wall_") || plan.object(&r.target).is_some(),
                "{prompt}: {} relation to unknown {}",
                o.id,
                r.target
            );
        }
    }
}

#[test]
fn simple_prompts_yield_rich_layered_plans_with_on_inside_and_under() {
    for (prompt, _) in BENCHMARK.iter().filter(|(p, _)| *p != DETAILED) {
        let plan = plan(prompt, 1);
        let cats = plan.categories().len();
        if *prompt == "a peaceful beach during sunset" {
            assert!(cats >= 12, "{prompt}: {cats}");
        } else {
            assert_simple_plan_is_rich(prompt, &plan);
            assert!(
                plan.relation_kinds().contains(&RelationKind::Inside),
                "{prompt}: no inside relation"
            );
        }
    }
    for prompt in [
        "a cozy living room with reading materials",
        "a children's playroom",
        "a garage",
        "a gym room",
        "a chemistry laboratory",
        "a bookstore",
        "a warehouse",
        "a museum gallery",
        "a billiard club",
        "a piano showroom",
        "a convenience store",
    ] {
        assert!(
            plan(prompt, 2)
                .relation_kinds()
                .contains(&RelationKind::Under),
            "{prompt}: no under relation"
        );
    }
}

#[test]
fn detailed_prompt_relations_become_hard_constraints() {
    let plan = &plan(DETAILED, 0);
    let find =
        |subject_cat: &str, kind: RelationKind, target: &dyn Fn(&ConstraintTarget) -> bool| {
            plan.constraints
                .iter()
                .filter(|c| {
                    plan.object(&c.subject)
                        .is_some_and(|o| o.category == subject_cat)
                        && c.kind == kind
                        && target(&c.target)
                })
                .count()
        };
    let obj = |cat: &'static str| move |t: &ConstraintTarget| matches!(t, ConstraintTarget::Object(id) if plan.object(id).is_some_and(|o| o.category == cat));
    assert_eq!(
        find("sofa", RelationKind::AgainstWall, &|t| *t
            == ConstraintTarget::Wall(BACK_WALL.into())),
        1
    );
    assert_eq!(
        find("coffee_table", RelationKind::InFrontOf, &obj("sofa")),
        1
    );
    assert_eq!(
        find("mug", RelationKind::On, &obj("coffee_table")),
        2,
        "two mugs on top"
    );
    assert_eq!(find("vase", RelationKind::On, &obj("coffee_table")), 1);
    assert_eq!(
        find("armchair", RelationKind::Beside, &obj("coffee_table")),
        2
    );
    assert_eq!(find("armchair", RelationKind::Facing, &obj("sofa")), 2);
    assert_eq!(
        find("bookshelf", RelationKind::AgainstWall, &|t| *t
            == ConstraintTarget::Corner),
        1
    );
    assert!(find("book", RelationKind::Inside, &obj("bookshelf")) >= 2);
    // The plant inside the shelves becomes a surface-sized stand-in, and says so.
    assert_eq!(find("vase", RelationKind::Inside, &obj("bookshelf")), 1);
    assert!(
        plan.notes.iter().any(|n| n.contains("plant")),
        "{:?}",
        plan.notes
    );
    assert_eq!(find("floor_lamp", RelationKind::Beside, &obj("sofa")), 1);
    // Exactly the stated counts.
    assert_eq!(
        plan.objects
            .iter()
            .filter(|o| o.category == "armchair")
            .count(),
        2
    );
    assert_eq!(
        plan.objects.iter().filter(|o| o.category == "mug").count(),
        2
    );
    assert_eq!(
        plan.objects.iter().filter(|o| o.category == "sofa").count(),
        1
    );
    // The two armchairs go to opposite sides of the table.
    let sides: BTreeSet<RelationKind> = plan
        .objects
        .iter()
        .filter(|o| o.category == "armchair")
        .flat_map(|o| o.relations.iter().map(|r| r.kind))
        .filter(|k| matches!(k, RelationKind::LeftOf | RelationKind::RightOf))
        .collect();
    assert_eq!(sides.len(), 2);
    // Constraint subjects are hard and carry the relation in the plan.
    for c in &plan.constraints {
        let o = plan.object(&c.subject).unwrap();
        assert!(o.hard, "{}", c.subject);
        if let ConstraintTarget::Object(t) = &c.target {
            let in_plan = o
                .relations
                .iter()
                .any(|r| r.kind == c.kind && &r.target == t)
                || (o.support == c.kind && o.parent == ParentRef::Object(t.clone()));
            assert!(
                in_plan,
                "{} {} {t} missing from the plan object",
                c.subject, c.kind
            );
        }
    }
    assert_eq!(plan.anchor, "sofa_0");
}

#[test]
fn counts_and_relations_are_read_from_free_prompts() {
    let plan = plan(
        "a bedroom with two armchairs, a few books on the desk and a teddy bear under the bed",
        0,
    );
    assert_eq!(plan.scene_type, "bedroom");
    assert_eq!(
        plan.objects
            .iter()
            .filter(|o| o.category == "armchair")
            .count(),
        2
    );
    let books_on_desk = plan
        .objects
        .iter()
        .filter(|o| {
            o.category == "book"
                && o.support == RelationKind::On
                && plan
                    .object(o.parent.object_id().unwrap_or(""))
                    .is_some_and(|p| p.category == "desk")
        })
        .count();
    assert_eq!(books_on_desk, 3, "a few books on the desk");
    assert!(plan
        .objects
        .iter()
        .any(|o| o.category == "teddy_bear" && o.support == RelationKind::Under));

    let plan = plan_with("an office with 3 plants in the corners, a laptop to the left of the monitor and a whiteboard");
    assert_eq!(
        plan.objects
            .iter()
            .filter(|o| o.category == "plant")
            .count(),
        3
    );
    assert!(plan
        .constraints
        .iter()
        .any(|c| c.kind == RelationKind::LeftOf));
    assert!(plan.categories().contains("whiteboard"));
}

fn plan_with(prompt: &str) -> Plan {
    plan(prompt, 0)
}

#[test]
fn unknown_scene_types_fall_back_to_the_nearest_archetypes_and_keep_every_mention() {
    let plan = plan(
        "a wizard's alchemy workshop with a cauldron, three potions and a spellbook",
        0,
    );
    assert_eq!(plan.scene_type, "custom");
    assert!(
        plan.archetypes.contains(&"laboratory".to_owned())
            && plan.archetypes.contains(&"workshop".to_owned()),
        "{:?}",
        plan.archetypes
    );
    let cats = plan.categories();
    for c in ["bowl", "bottle", "book", "workbench", "lab_bench"] {
        assert!(cats.contains(c), "missing {c}: {cats:?}");
    }
    assert!(
        plan.objects
            .iter()
            .filter(|o| o.category == "bottle")
            .count()
            >= 3
    );

    // Only objects, no scene words: the archetypes that hold them.
    let plan = plan_with("a treadmill and some dumbbells");
    assert!(
        plan.archetypes.contains(&"gym".to_owned()),
        "{:?}",
        plan.archetypes
    );
    // Only a mood: the default archetype.
    let plan = plan_with("somewhere cozy and quiet");
    assert!(!plan.objects.is_empty());
}

#[test]
fn empty_prompts_are_clear_errors_and_meaningless_ones_get_a_generic_room() {
    let planner = KnowledgePlanner::new();
    let request = |p: &str| PlanRequest::new(p, available(), 0);
    assert_eq!(planner.plan(&request("")), Err(PlanError::EmptyPrompt));
    assert_eq!(
        planner.plan(&request("  ,.;  ")),
        Err(PlanError::EmptyPrompt)
    );
    // No non-empty prompt is refused: the generic room, saying what was assumed.
    let plan = planner.plan(&request("xqzt vbnm plorf")).unwrap();
    assert_eq!(plan.scene_type, "living_room");
    assert!(
        plan.assumptions
            .iter()
            .any(|a| a.contains("generic room") && a.contains("no word")),
        "{:?}",
        plan.assumptions
    );
    let none = PlanRequest::new("a garage", Vec::<String>::new(), 0);
    assert!(matches!(
        planner.plan(&none),
        Err(PlanError::NothingAvailable { .. })
    ));
}

#[test]
fn unavailable_categories_are_substituted_or_left_out() {
    let mut cats = available();
    cats.retain(|c| c != "bookshelf" && c != "television");
    let plan = KnowledgePlanner::new()
        .plan(&PlanRequest::new("a cozy living room", cats, 0))
        .unwrap();
    let have = plan.categories();
    assert!(!have.contains("bookshelf") && !have.contains("television"));
    assert!(
        have.contains("shelving_unit"),
        "bookshelf → shelving unit: {have:?}"
    );
    assert!(
        plan.notes.iter().any(|n| n.contains("television")),
        "{:?}",
        plan.notes
    );
    // User-imported categories count once they are available.
    let mut cats = available();
    cats.push("gramophone".into());
    assert!(KnowledgePlanner::new()
        .plan(&PlanRequest::new("a music room", cats, 0))
        .is_ok());
}

#[test]
fn plans_are_deterministic_per_seed_and_vary_across_seeds() {
    let a = plan("a cozy living room with reading materials", 5);
    let b = plan("a cozy living room with reading materials", 5);
    assert_eq!(a, b);
    let variants: BTreeSet<String> = (0..6)
        .map(|s| {
            serde_json::to_string(&plan("a cozy living room with reading materials", s)).unwrap()
        })
        .collect();
    assert!(
        variants.len() >= 5,
        "only {} distinct plans",
        variants.len()
    );
}

#[test]
fn plans_round_trip_through_json_for_llm_providers() {
    let p = plan(DETAILED, 0);
    let json = serde_json::to_string_pretty(&p).unwrap();
    let back: Plan = serde_json::from_str(&json).unwrap();
    assert_eq!(back, p);
    assert!(
        p.description.contains("Background") && p.description.contains("Foreground"),
        "{}",
        p.description
    );
}

#[test]
fn every_spatial_phrase_becomes_its_relation() {
    let plan = plan(
        "an office with a desk against the left wall, a chair in front of the desk, a plant next to the desk, a laptop on the desk, a trash can under the desk, a sofa facing the desk, a bookshelf to the right of the sofa with a box inside it, a cabinet behind the sofa and a vase in the corner",
        0,
    );
    let has = |subject: &str, kind: RelationKind, target: &str| {
        plan.constraints.iter().any(|c| {
            plan.object(&c.subject)
                .is_some_and(|o| o.category == subject)
                && c.kind == kind
                && match &c.target {
                    ConstraintTarget::Object(t) => {
                        plan.object(t).is_some_and(|o| o.category == target)
                    }
                    ConstraintTarget::Wall(w) => w == target,
                    ConstraintTarget::Corner => target == "corner",
                    ConstraintTarget::AnyWall => target == "any",
                }
        })
    };
    assert!(
        has("desk", RelationKind::AgainstWall, "wall_1"),
        "{:#?}",
        plan.constraints
    );
    assert!(has("chair", RelationKind::InFrontOf, "desk"));
    assert!(has("plant", RelationKind::Beside, "desk"));
    assert!(has("laptop", RelationKind::On, "desk"));
    assert!(has("trash_can", RelationKind::Under, "desk"));
    assert!(has("sofa", RelationKind::Facing, "desk"));
    assert!(has("bookshelf", RelationKind::RightOf, "sofa"));
    assert!(has("box", RelationKind::Inside, "bookshelf"));
    assert!(has("cabinet", RelationKind::Behind, "sofa"));
    assert!(has("vase", RelationKind::AgainstWall, "corner"));
}
