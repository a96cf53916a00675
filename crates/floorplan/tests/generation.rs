//! Invariants of generated floor plans, over seeds and programs.

use proptest::prelude::*;
use scenethesis_floorplan::geometry::{area, rectangles, Rect};
use scenethesis_floorplan::{
    check_privacy, generate, validate, DoorKind, Generated, Hinge, Knowledge, Program, EXTERIOR,
    HALLWAY,
};

const PROMPTS: [&str; 5] = [
    "a two-bedroom apartment",
    "a studio flat",
    "a family house with three bedrooms and two bathrooms",
    "an office suite with a meeting room, a kitchenette and four offices",
    "a clinic with a waiting room and two exam rooms",
];

fn plan_of(text: &str, seed: u64) -> Generated {
    let k = Knowledge::builtin();
    let program = Program::from_words(k, text).unwrap();
    generate(k, &program, seed).unwrap_or_else(|e| panic!("{text} seed {seed}: {e}"))
}

/// Every rule of a generated plan: exact tiling, areas, doors, windows, privacy, validity.
fn assert_invariants(k: &Knowledge, program: &Program, g: &Generated) {
    let plan = &g.plan;
    let [x0, z0, x1, z1] = g.footprint;
    let footprint = (x1 - x0) * (z1 - z0);
    let sum: f64 = plan.rooms.iter().map(|r| area(&r.polygon)).sum();
    assert!(
        (sum - footprint).abs() < 1e-6,
        "rooms {sum} vs footprint {footprint}"
    );
    let pieces: Vec<Vec<Rect>> = plan.rooms.iter().map(|r| rectangles(&r.polygon)).collect();
    for (i, a) in pieces.iter().enumerate() {
        for r in a {
            let inside = r.min.x >= x0 - 1e-9
                && r.max.x <= x1 + 1e-9
                && r.min.y >= z0 - 1e-9
                && r.max.y <= z1 + 1e-9;
            assert!(inside, "{} leaves the footprint", plan.rooms[i].id);
        }
        for b in &pieces[i + 1..] {
            let overlap: f64 = a
                .iter()
                .flat_map(|p| b.iter().map(move |q| p.overlap_area(q)))
                .sum();
            assert!(overlap < 1e-9, "overlap {overlap}");
        }
    }
    for rc in &program.rooms {
        let n = plan
            .rooms
            .iter()
            .filter(|r| r.room_type == rc.room_type)
            .count() as u32;
        let expected = if rc.room_type == HALLWAY { 1 } else { rc.count };
        assert_eq!(n, expected, "{}", rc.room_type);
    }
    for note in &g.areas {
        let [min, max] = note.range;
        let tol = scenethesis_floorplan::AREA_TOLERANCE;
        assert!(
            note.area >= min * (1.0 - tol) && note.area <= max * (1.0 + tol),
            "{note:?}"
        );
        assert_eq!(
            note.within,
            note.area >= min - 1e-6 && note.area <= max + 1e-6
        );
    }
    assert_eq!(plan.entrances().count(), 1, "one entrance");
    for door in &plan.doors {
        let ok = match door.kind {
            DoorKind::Single => (0.8..=0.9).contains(&door.width),
            DoorKind::Double => (1.4..=1.6).contains(&door.width),
            DoorKind::Passage => door.width >= 1.2,
        };
        assert!(ok && door.height >= 2.0, "{door:?}");
        match (&door.kind, &door.swing) {
            (DoorKind::Passage, s) => assert!(s.is_none()),
            (DoorKind::Double, Some(s)) => assert_eq!(s.hinge, Hinge::Both),
            (DoorKind::Single, Some(s)) => assert!(s.hinge != Hinge::Both && s.into != EXTERIOR),
            (_, None) => panic!("{} has no swing", door.id),
        }
    }
    for window in &plan.windows {
        let room = plan.room(&window.room).unwrap();
        let spec = k.room(&room.room_type).unwrap().window.unwrap();
        assert!(
            (window.sill - spec.sill).abs() < 1e-9 && window.width <= spec.width + 1e-9,
            "{window:?}"
        );
    }
    let walls = validate(plan, k).unwrap_or_else(|e| panic!("{e}\n{plan:#?}"));
    assert_eq!(walls, g.walls);
    check_privacy(plan, k).unwrap();
    assert_eq!(
        scenethesis_floorplan::leaf_clash(plan, &walls),
        None,
        "door leaves clash"
    );
    let interior: Vec<_> = walls.iter().filter(|w| !w.is_exterior()).collect();
    for (i, a) in interior.iter().enumerate() {
        for b in &interior[i + 1..] {
            let same = a.joins(&b.rooms[0], &b.rooms[1]) && a.start == b.start && a.end == b.end;
            assert!(!same, "{} listed twice", a.id);
        }
    }
}

#[test]
fn the_five_prompts_make_valid_plans() {
    let k = Knowledge::builtin();
    for text in PROMPTS {
        let program = Program::from_words(k, text).unwrap();
        for seed in 0..3 {
            let g = generate(k, &program, seed).unwrap_or_else(|e| panic!("{text}: {e}"));
            assert_invariants(k, &program, &g);
        }
    }
}

#[test]
fn hallways_where_needed() {
    assert!(plan_of("a family house with three bedrooms and two bathrooms", 0).hallway);
    assert!(plan_of("a clinic with a waiting room and two exam rooms", 0).hallway);
    let studio = plan_of("a studio flat", 0);
    assert!(!studio.hallway, "{:#?}", studio.plan.rooms);
}

#[test]
fn bathrooms_get_small_high_windows_and_kitchens_open_to_living() {
    let g = plan_of("a family house with three bedrooms and two bathrooms", 2);
    for w in g
        .plan
        .windows
        .iter()
        .filter(|w| w.room.starts_with("bathroom"))
    {
        assert!(w.sill >= 1.4 && w.width <= 0.6, "{w:?}");
    }
    let mut open = 0;
    for seed in 0..6 {
        let g = plan_of("a two-bedroom apartment", seed);
        let kitchen_living = |d: &&scenethesis_floorplan::Door| {
            d.kind == DoorKind::Passage && d.other("kitchen") == Some("living_room")
        };
        open += g.plan.doors.iter().filter(kitchen_living).count();
    }
    assert!(
        open >= 3,
        "kitchen open to the living room in {open} of 6 plans"
    );
}

#[test]
fn en_suite_is_reached_only_through_its_bedroom() {
    let g = plan_of("a family house with three bedrooms and two bathrooms", 1);
    let doors: Vec<_> = g.plan.doors_of("bathroom_2").collect();
    assert_eq!(doors.len(), 1, "{doors:?}");
    assert_eq!(doors[0].other("bathroom_2"), Some("bedroom_1"));
}

/// Which rooms share a wall, as sorted pairs: the plan's arrangement, whatever its sizes.
fn arrangement(g: &Generated) -> Vec<(String, String)> {
    let mut pairs: Vec<(String, String)> = g
        .walls
        .iter()
        .filter(|w| !w.is_exterior())
        .map(|w| {
            let (a, b) = (w.rooms[0].clone(), w.rooms[1].clone());
            if a < b {
                (a, b)
            } else {
                (b, a)
            }
        })
        .collect();
    pairs.sort();
    pairs.dedup();
    pairs
}

#[test]
fn seeds_change_the_arrangement_and_a_seed_repeats_the_plan() {
    let a = plan_of("a two-bedroom apartment", 5);
    assert_eq!(a, plan_of("a two-bedroom apartment", 5));
    for text in PROMPTS {
        let arrangements: std::collections::BTreeSet<Vec<(String, String)>> =
            (0..6).map(|s| arrangement(&plan_of(text, s))).collect();
        assert!(
            arrangements.len() >= 2,
            "{text}: {} distinct arrangements",
            arrangements.len()
        );
    }
}

#[test]
fn a_generated_plan_round_trips_through_json() {
    let g = plan_of("a clinic with a waiting room and two exam rooms", 3);
    let text = serde_json::to_string_pretty(&g).unwrap();
    let again: Generated = serde_json::from_str(&text).unwrap();
    assert_eq!(g, again);
    let plan: scenethesis_floorplan::FloorPlan =
        serde_json::from_str(&serde_json::to_string(&g.plan).unwrap()).unwrap();
    validate(&plan, Knowledge::builtin()).unwrap();
}

#[test]
fn an_unknown_kind_is_an_error() {
    let program = Program {
        kind: "castle".into(),
        rooms: vec![],
    };
    let err = generate(Knowledge::builtin(), &program, 0).unwrap_err();
    assert!(err.to_string().contains("castle"), "{err}");
}

#[test]
fn every_dwelling_kind_with_its_defaults() {
    let k = Knowledge::builtin();
    for d in &k.dwellings {
        let program = Program::new(k, &d.kind, &[]).unwrap();
        for seed in 0..3 {
            let g = generate(k, &program, seed).unwrap_or_else(|e| panic!("{}: {e}", d.kind));
            assert_invariants(k, &program, &g);
        }
    }
}

fn programs() -> impl Strategy<Value = Program> {
    let k = Knowledge::builtin();
    let kinds: Vec<String> = k.dwellings.iter().map(|d| d.kind.clone()).collect();
    (prop::sample::select(kinds), 0u32..5, 0u32..3, 0u32..2).prop_map(|(kind, a, b, c)| {
        let k = Knowledge::builtin();
        let counts: Vec<(&str, u32)> = match kind.as_str() {
            "apartment" | "house" => vec![("bedroom", a), ("bathroom", b.max(1)), ("toilet", c)],
            "office_suite" => vec![("office", a + 1), ("storeroom", c)],
            "clinic" => vec![("exam_room", a.max(1)), ("toilet", b.max(1)), ("office", c)],
            "school_wing" => vec![("classroom", a.clamp(1, 3)), ("toilet", b.max(1))],
            "restaurant" => vec![("toilet", b.max(1)), ("storeroom", c)],
            _ => vec![("toilet", c)],
        };
        Program::new(k, &kind, &counts).unwrap()
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, failure_persistence: None, ..ProptestConfig::default() })]
    #[test]
    fn generated_plans_keep_every_rule(program in programs(), seed in 0u64..1000) {
        let k = Knowledge::builtin();
        let g = generate(k, &program, seed).map_err(|e| TestCaseError::fail(format!("{program:?}: {e}")))?;
        assert_invariants(k, &program, &g);
    }
}
