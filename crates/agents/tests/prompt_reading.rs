//! Prompt reading: unknown places, counts, exclusions, caps, nouns the library lacks.

mod common;

use common::available;
use scenethesis_agents::{
    Knowledge, KnowledgePlanner, Plan, PlanRequest, Planner, Thesaurus, Zone, MAX_COUNT_PER_OBJECT,
    MAX_PLANNED_OBJECTS, MAX_PROMPT_CHARS,
};

fn plan(prompt: &str) -> Plan {
    KnowledgePlanner::new()
        .plan(&PlanRequest::new(prompt, available(), 0))
        .unwrap_or_else(|e| panic!("{prompt}: {e}"))
}

fn count(plan: &Plan, category: &str) -> usize {
    plan.objects
        .iter()
        .filter(|o| o.category == category)
        .count()
}

/// The prompts of `fixtures/prompts/unknown_places.txt`.
fn unknown_places() -> Vec<String> {
    let text = include_str!("../../../fixtures/prompts/unknown_places.txt");
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .map(str::to_owned)
        .collect()
}

#[test]
fn the_place_thesaurus_loads_and_every_place_derives() {
    let t = Thesaurus::builtin();
    let k = Knowledge::builtin();
    for family in [
        "home", "shop", "office", "public", "workshop", "outdoor", "vehicle", "fantasy",
    ] {
        let f = t
            .family(family)
            .unwrap_or_else(|| panic!("family {family}"));
        assert!(t.archetype(&f.room, k).is_some(), "{family}: {}", f.room);
    }
    for p in &t.places {
        let a = t.archetype(&p.name, k).expect("derives");
        assert_eq!(a.name, p.name);
        assert!(a.objects.iter().any(|g| g.category == a.anchor));
    }
    // A broken entry is named in the error.
    let bad = "[[family]]\nname = \"shop\"\nroom = \"convenience_store\"\nwords = [\"shop\"]\n\
               [[place]]\nname = \"kiosk\"\nwords = [\"kiosk\"]\nfamily = \"shop\"\n\
               gloss = \"a small shop\"\nlike = \"nowhere\"\ncore = [\"store_shelf\"]\n\
               source = \"ours\"\n";
    let err = Thesaurus::from_toml(bad, "[[noun]]\nwords = [\"x\"]\n", k)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("places.toml") && err.contains("kiosk") && err.contains("nowhere"),
        "{err}"
    );
}

#[test]
fn unknown_places_plan_the_closest_scene_and_say_what_was_assumed() {
    let prompts = unknown_places();
    assert!(prompts.len() >= 60, "{} prompts", prompts.len());
    for prompt in &prompts {
        let plan = plan(prompt);
        assert!(
            !plan.assumptions.is_empty(),
            "{prompt}: the knowledge names it directly ({}), so it does not belong in the list",
            plan.scene_type
        );
        assert!(plan.objects.len() >= 5, "{prompt}: {:?}", plan.objects);
    }
    let pharmacy = plan("a pharmacy");
    assert_eq!(pharmacy.scene_type, "pharmacy");
    assert!(pharmacy.assumptions[0].contains("medicine"));
    assert!(count(&pharmacy, "store_shelf") >= 1 && count(&pharmacy, "bottle") >= 3);
    let salon = plan("a hair salon");
    for c in ["mirror", "sink", "office_chair"] {
        assert!(count(&salon, c) >= 1, "hair salon lacks {c}");
    }
    let gate = plan("an airport gate");
    assert!(
        gate.objects
            .iter()
            .filter(|o| o.category == "bench" && o.zone == Zone::Rows)
            .count()
            >= 3,
        "an airport gate has rows of seats"
    );
    // A family word alone gives the family's generic room.
    let castle = plan("a gloomy keep of the goblin king");
    assert!(
        castle.assumptions[0].contains("fantasy"),
        "{:?}",
        castle.assumptions
    );
    assert_eq!(plan("a cottage").scene_type, "living_room");
}

#[test]
fn counts_are_honoured_and_exclusions_plan_none() {
    assert_eq!(count(&plan("a kitchen with three chairs"), "chair"), 3);
    assert_eq!(count(&plan("an office with 2 desks"), "desk"), 2);
    for prompt in [
        "a classroom with 0 chairs",
        "a classroom without chairs",
        "a classroom with no chairs",
        "a classroom without any chairs or desks",
    ] {
        let p = plan(prompt);
        assert_eq!(count(&p, "chair"), 0, "{prompt}");
        let chair = p.requested.iter().find(|r| r.words == "chair").unwrap();
        assert_eq!((chair.count, chair.ids.len()), (0, 0), "{prompt}");
        assert!(!chair.expected());
    }
    assert_eq!(
        count(&plan("a classroom without any chairs or desks"), "desk"),
        0
    );
    // "without" ends at "with".
    let p = plan("a living room without a television, with two armchairs");
    assert_eq!(count(&p, "television"), 0);
    assert_eq!(count(&p, "armchair"), 2);
}

#[test]
fn caps_are_reported_not_silent() {
    let p = plan("500 chairs in a bathroom");
    assert_eq!(count(&p, "chair"), MAX_COUNT_PER_OBJECT as usize);
    let chair = p.requested.iter().find(|r| r.words == "chair").unwrap();
    assert!(
        chair.note.as_deref().unwrap_or("").contains("500"),
        "{chair:?}"
    );
    assert!(
        p.limits
            .iter()
            .any(|l| l.contains("500") && l.contains("50")),
        "{:?}",
        p.limits
    );

    // A 10 kB prompt is cut to the documented length and the plan stays bounded.
    let long =
        "a living room with two sofas, three armchairs, a table and five lamps; ".repeat(150);
    assert!(long.len() > 10_000);
    let p = plan(&long);
    assert!(p.prompt.chars().count() <= MAX_PROMPT_CHARS);
    assert!(
        p.objects.len() <= MAX_PLANNED_OBJECTS,
        "{}",
        p.objects.len()
    );
    assert!(
        p.limits.iter().any(|l| l.contains("characters")),
        "{:?}",
        p.limits
    );
}

#[test]
fn nouns_the_library_lacks_map_to_the_nearest_category_or_are_reported() {
    let p = plan("a kitchen with an island");
    let island = p.requested.iter().find(|r| r.words == "island").unwrap();
    assert_eq!(island.category.as_deref(), Some("kitchen_island"));
    assert_eq!(island.ids.len(), 1);
    let planned = p.object(&island.ids[0]).unwrap();
    assert_eq!(
        planned.zone,
        Zone::Center,
        "an island stands free in the middle"
    );
    assert!(island.note.as_deref().unwrap_or("").contains("island"));

    let p = plan("a bedroom with a dresser mirror");
    let mirror = p
        .requested
        .iter()
        .find(|r| r.words == "dresser mirror")
        .unwrap();
    assert_eq!(mirror.category.as_deref(), Some("mirror"));
    assert_eq!(mirror.ids.len(), 1);

    let p = plan("a living room with a harp and a sofa");
    let harp = p.requested.iter().find(|r| r.words == "harp").unwrap();
    assert_eq!(harp.category, None);
    assert!(harp.ids.is_empty() && !harp.expected());
    assert!(harp.note.as_deref().unwrap_or("").contains("harp"));

    // "island" outside a kitchen is a place word, not a counter.
    let p = plan("a desert island");
    assert!(p.requested.iter().all(|r| r.words != "island"));
}

#[test]
fn conflicting_and_unplannable_relations_are_reported() {
    // The mug is put on the desk and then inside the cabinet: the later relation places it,
    // both stay constraints (one will be reported broken), and the plan notes the conflict.
    let p =
        plan("an office with a desk and a cabinet, a mug on the desk, the mug inside the cabinet");
    let mug_constraints = p
        .constraints
        .iter()
        .filter(|c| c.subject.starts_with("mug"))
        .count();
    assert!(mug_constraints >= 2, "{:?}", p.constraints);
    assert!(
        p.notes.iter().any(|n| n.contains("conflicts")),
        "{:?}",
        p.notes
    );
    // A relation to an object the prompt excludes cannot hold, and the plan says so.
    let p = plan("a living room without a coffee table, a mug on the coffee table");
    assert!(
        p.notes.iter().any(|n| n.contains("not planned")),
        "{:?}",
        p.notes
    );
}
