//! Prompt reading: unknown places, counts, exclusions, caps, nouns the library lacks.

mod common;

use std::collections::BTreeSet;

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

#[test]
fn a_place_is_read_from_its_head_noun_with_a_confidence() {
    // Named outright: sure.
    for (prompt, place) in [
        ("a kitchen", "kitchen"),
        ("a cozy bedroom with a desk and a piano", "bedroom"),
        ("three chairs and a table in a kitchen", "kitchen"),
        ("a pharmacy", "pharmacy"),
        ("a band practice room", "music_practice_room"),
    ] {
        let reading = plan(prompt)
            .reading
            .expect("the knowledge planner records its reading");
        assert_eq!(reading.place, place, "{prompt}: {reading:?}");
        assert!(!reading.is_low(), "{prompt}: {reading:?}");
    }
    // A word that only modifies the head never decides the place on its own, and a guess
    // says so.
    for (prompt, wrong) in [
        ("a golf practice area", "office"),
        ("a tattoo practice space", "office"),
    ] {
        let plan = plan(prompt);
        let reading = plan.reading.clone().unwrap();
        assert_ne!(reading.place, wrong, "{prompt}: {reading:?}");
        assert!(
            !plan.archetypes.iter().any(|a| a == wrong),
            "{prompt}: {:?}",
            plan.archetypes
        );
        assert!(reading.is_low(), "{prompt}: {reading:?}");
        assert!(!reading.basis.is_empty());
    }
    // The head decides over a modifier naming another place; a modifier naming another
    // archetype blends in second.
    let plan_ = plan("a wizard's alchemy workshop");
    assert_eq!(plan_.archetypes[0], "workshop", "{:?}", plan_.archetypes);
    assert!(plan_.archetypes.contains(&"laboratory".to_owned()));
    // Nothing known: the default room, read as a guess.
    let unknown = plan("xqzt vbnm plorf").reading.unwrap();
    assert!(unknown.is_low() && unknown.confidence < 0.2, "{unknown:?}");
}

#[test]
fn plans_are_completed_so_that_what_needs_a_partner_has_one() {
    // Dining chairs serve a table: a bedroom with dining chairs gets a table for them.
    let chairs = plan("a bedroom with four dining chairs");
    let table = chairs
        .objects
        .iter()
        .find(|o| o.category == "dining_table")
        .unwrap_or_else(|| panic!("{:?}", chairs.categories()));
    assert!(
        chairs
            .notes
            .iter()
            .any(|n| n.starts_with("added a dining_table")),
        "{:?}",
        chairs.notes
    );
    let around = chairs
        .objects
        .iter()
        .filter(|o| o.category == "dining_chair")
        .filter(|o| o.relations.iter().any(|r| r.target == table.id))
        .count();
    assert_eq!(around, 4, "{:?}", chairs.objects);
    // A monitor stands on a desk or table.
    let monitor = plan("a bedroom with a monitor");
    let m = monitor
        .objects
        .iter()
        .find(|o| o.category == "monitor")
        .unwrap();
    let parent = m
        .parent
        .object_id()
        .and_then(|p| monitor.object(p))
        .unwrap();
    assert!(
        [
            "desk",
            "dining_table",
            "side_table",
            "nightstand",
            "dresser"
        ]
        .contains(&parent.category.as_str())
            || monitor.notes.iter().any(|n| n.starts_with("added a")),
        "{parent:?}"
    );
    // A target the prompt rules out is not added: what only served it goes too.
    let bare = plan("a classroom without any chairs or desks");
    assert!(!bare.categories().contains("desk"));
    assert!(
        !bare.categories().contains("office_chair"),
        "{:?}",
        bare.notes
    );
    assert!(
        bare.notes.iter().any(|n| n.starts_with("left out")),
        "{:?}",
        bare.notes
    );
}

#[test]
fn a_word_that_is_also_an_adjective_names_the_object_only_as_a_noun() {
    for prompt in [
        "a safe playroom for kids",
        "a safe and cozy nursery",
        "a safe room",
    ] {
        assert_eq!(count(&plan(prompt), "safe"), 0, "{prompt}");
    }
    for prompt in [
        "an office with a safe",
        "a bank office with a safe in the corner",
        "a study with a safe and a desk",
    ] {
        assert!(count(&plan(prompt), "safe") >= 1, "{prompt}");
    }
}

/// The attributes of the first planned object of `category`, as (words, material, colour).
fn attributes(plan: &Plan, category: &str) -> Vec<(String, Option<String>, Option<String>)> {
    let object = plan
        .objects
        .iter()
        .find(|o| o.category == category)
        .unwrap_or_else(|| panic!("no {category} in {:?}", plan.categories()));
    object
        .attributes
        .iter()
        .map(|a| {
            (
                a.words.clone(),
                a.look.material.clone(),
                a.look.color.map(|c| c.to_string()),
            )
        })
        .collect()
}

#[test]
fn a_red_leather_sofa_asks_for_leather_upholstery_in_red() {
    use scenethesis_scene_graph::LookScope;
    let plan = plan("a living room with a red leather sofa");
    let sofa = plan.objects.iter().find(|o| o.category == "sofa").unwrap();
    assert_eq!(sofa.attributes.len(), 2, "{:?}", sofa.attributes);
    assert!(sofa
        .attributes
        .iter()
        .all(|a| a.look.scope == LookScope::Upholstery));
    let got = attributes(&plan, "sofa");
    assert!(got
        .iter()
        .any(|(w, m, _)| w == "leather" && m.as_deref().is_some_and(|m| m.ends_with("leather"))));
    assert!(got
        .iter()
        .any(|(w, _, c)| w == "red" && c.as_deref() == Some("#b22222")));
    // The same words after the noun: "the sofa is red".
    let plan = self::plan("a living room with a sofa. the sofa is red");
    assert!(attributes(&plan, "sofa").iter().any(|(w, _, _)| w == "red"));
}

#[test]
fn white_walls_and_an_oak_floor_are_the_room_surfaces() {
    let plan = plan("a living room with white walls and an oak floor");
    let look = plan.look.as_ref().unwrap();
    let walls = &look.surfaces["walls"];
    assert_eq!(walls.attributes.len(), 1);
    assert_eq!(walls.attributes[0].words, "white");
    let floor = &look.surfaces["floor"];
    assert_eq!(floor.attributes[0].look.material.as_deref(), Some("oak"));
    // No object is planned for the look words or the surfaces.
    assert!(!plan.categories().contains("whiteboard"));
    let plan = self::plan("a bedroom with walls painted sage green");
    let walls = &plan.look.as_ref().unwrap().surfaces["walls"];
    assert!(
        walls.attributes.iter().any(|a| a.words == "sage"),
        "{walls:?}"
    );
}

#[test]
fn a_glass_coffee_table_has_a_glass_top_and_no_drinking_glass() {
    use scenethesis_scene_graph::LookScope;
    let plan = plan("a living room with a glass coffee table");
    let table = plan
        .objects
        .iter()
        .find(|o| o.category == "coffee_table")
        .unwrap();
    assert_eq!(table.attributes.len(), 1);
    assert_eq!(
        table.attributes[0].look.material.as_deref(),
        Some("clear_glass")
    );
    assert_eq!(table.attributes[0].look.scope, LookScope::Top);
    let cups = plan
        .requested
        .iter()
        .filter(|r| r.category.as_deref() == Some("cup"))
        .count();
    assert_eq!(cups, 0, "{:?}", plan.requested);
    // A modifier is no lamp: "a light blue rug".
    let plan = self::plan("a bedroom with a light blue rug");
    assert!(attributes(&plan, "rug")
        .iter()
        .any(|(w, _, _)| w == "light blue"));
    assert!(!plan.requested.iter().any(|r| r.words == "light"));
}

#[test]
fn a_style_word_sets_the_room_palette_and_seeds_vary_it_without_one() {
    use scenethesis_agents::StyleSource;
    let looks = scenethesis_agents::looks::Looks::builtin();
    let scandinavian = looks.style_named("scandinavian").unwrap();
    for seed in 0..3 {
        let plan = KnowledgePlanner::new()
            .plan(&PlanRequest::new(
                "a scandinavian living room",
                available(),
                seed,
            ))
            .unwrap();
        let look = plan.look.unwrap();
        assert_eq!(look.style, "scandinavian");
        assert_eq!(look.style_source, StyleSource::Prompt);
        assert!(scandinavian.families["wood"].contains(&look.families["wood"]));
        assert!(scandinavian.surfaces["floor"].contains(&look.surfaces["floor"].base));
    }
    let styles: BTreeSet<String> = (0..12)
        .map(|seed| {
            KnowledgePlanner::new()
                .plan(&PlanRequest::new("a living room", available(), seed))
                .unwrap()
                .look
                .unwrap()
                .style
        })
        .collect();
    assert!(styles.len() >= 3, "{styles:?}");
    // The style has its own generator: the objects are those of the plan without looks.
    let a = plan("a scandinavian living room");
    let b = plan("a rustic living room");
    assert_eq!(a.categories(), b.categories());
}

#[test]
fn an_unknown_look_word_is_reported_never_dropped() {
    let plan = plan("a living room with a plaid sofa and a bamboo-coloured rug");
    let look = plan.look.as_ref().unwrap();
    let words: Vec<(&str, &str)> = look
        .unavailable
        .iter()
        .map(|u| (u.words.as_str(), u.target.as_str()))
        .collect();
    assert!(words.contains(&("plaid", "sofa")), "{words:?}");
    assert!(words.contains(&("bamboo coloured", "rug")), "{words:?}");
    assert!(plan.objects.iter().any(|o| o.category == "sofa"));
    let plan = self::plan("a dining room with a table made of bamboo");
    let look = plan.look.as_ref().unwrap();
    assert!(
        look.unavailable.iter().any(|u| u.words == "bamboo"),
        "{:?}",
        look.unavailable
    );
}

/// Plans `prompt` at `seed`.
fn plan_at(prompt: &str, seed: u64) -> Plan {
    KnowledgePlanner::new()
        .plan(&PlanRequest::new(prompt, available(), seed))
        .unwrap_or_else(|e| panic!("{prompt}: {e}"))
}

#[test]
fn a_sparse_prompt_plans_a_sparse_room_of_the_same_place_and_says_why() {
    // (sparse prompt, its plain form, a category the sparse room still holds)
    let cases = [
        ("a minimalist bedroom", "a bedroom", "bed"),
        ("a sparse office", "an office", "desk"),
        ("a bare studio apartment", "a studio apartment", "sofa"),
        ("a sparsely furnished living room", "a living room", "sofa"),
        ("an empty warehouse", "a warehouse", "pallet_rack"),
    ];
    for seed in 0..3 {
        for (sparse, plain, kept) in cases {
            let (s, p) = (plan_at(sparse, seed), plan_at(plain, seed));
            assert_eq!(s.scene_type, p.scene_type, "{sparse} (seed {seed})");
            assert!(count(&s, kept) >= 1, "{sparse} (seed {seed}) has no {kept}");
            // At most 70 % as many objects, and at least eight fewer.
            assert!(
                s.objects.len() * 10 <= p.objects.len() * 7
                    && s.objects.len() + 8 <= p.objects.len(),
                "{sparse} (seed {seed}): {} objects against {} for {plain}",
                s.objects.len(),
                p.objects.len()
            );
            assert!(
                s.assumptions.iter().any(|a| a.contains("sparse room")),
                "{sparse}: {:?}",
                s.assumptions
            );
            assert!(!p.assumptions.iter().any(|a| a.contains("sparse room")));
        }
    }
    // A minimalist room keeps its core but none of the optional extras.
    let minimalist = plan_at("a minimalist bedroom", 1);
    for core in ["bed", "nightstand", "wardrobe"] {
        assert!(count(&minimalist, core) >= 1, "no {core}");
    }
    for extra in [
        "teddy_bear",
        "suitcase",
        "laundry_hamper",
        "standing_mirror",
    ] {
        assert_eq!(
            count(&minimalist, extra),
            0,
            "{extra} in a minimalist bedroom"
        );
    }
    // An empty room is nearly nothing, but what the prompt names is still planned.
    assert!(plan_at("an empty warehouse", 0).objects.len() <= 3);
    let with_desk = plan_at("an empty warehouse with a desk", 0);
    assert_eq!(count(&with_desk, "desk"), 1);
    assert!(with_desk.objects.len() <= 4);
}
