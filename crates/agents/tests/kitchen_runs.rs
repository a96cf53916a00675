//! Kitchen runs (issue #16): the guide places the counters, cabinets, sink, stove and fridge of
//! a kitchen edge to edge along the walls — one wall, an L, a U or a galley, varying with the
//! seed — and the arrangement rules (`knowledge/arrangement.toml`) hold in the guided scenes.

mod common;

use std::collections::{BTreeMap, BTreeSet};

use common::{layout, walk_and_reach};
use scenethesis_agents::check_arrangement;
use scenethesis_scene_graph::{ParentRef, RelationKind, Scene};

/// The kitchen prompts of the issue.
const KITCHENS: &[&str] = &[
    "a kitchen",
    "a kitchen with an island",
    "a small galley kitchen",
    "a family kitchen with a dining table",
];

const MEMBERS: &[&str] = &[
    "kitchen_counter",
    "cabinet",
    "sink",
    "stove",
    "refrigerator",
];

/// The walls the run members stand against, as a layout name.
fn run_shape(scene: &Scene) -> String {
    let walls: BTreeSet<String> = scene
        .objects
        .iter()
        .filter(|o| o.parent == ParentRef::Ground && MEMBERS.contains(&o.category.as_str()))
        .filter_map(|o| {
            o.relations
                .iter()
                .find(|r| r.kind == RelationKind::AgainstWall)
                .map(|r| r.target.clone())
        })
        .collect();
    let w: Vec<&str> = walls.iter().map(String::as_str).collect();
    match w.as_slice() {
        ["wall_0"] => "one-wall".into(),
        ["wall_0", "wall_1"] | ["wall_0", "wall_3"] => "l-shaped".into(),
        ["wall_0", "wall_1", "wall_3"] => "u-shaped".into(),
        ["wall_0", "wall_2"] => "galley".into(),
        other => format!("other {other:?}"),
    }
}

#[test]
fn kitchen_runs_hold_vary_and_stay_walkable() {
    let mut lines = Vec::new();
    let mut broken = Vec::new();
    let (mut held, mut checked) = (0, 0);
    let mut shapes: BTreeMap<&str, BTreeSet<String>> = BTreeMap::new();
    for prompt in KITCHENS {
        for seed in 0..4 {
            let (_, laid) = layout(prompt, seed);
            let scene = &laid.scene;
            let check = check_arrangement(scene);
            held += check.held;
            checked += check.checked;
            broken.extend(check.broken.iter().map(|b| {
                format!(
                    "{prompt} #{seed}: `{}` {} ({})",
                    b.subject, b.reason, b.rule
                )
            }));
            let shape = run_shape(scene);
            let cats: BTreeSet<&str> = scene.objects.iter().map(|o| o.category.as_str()).collect();
            for c in ["sink", "stove", "refrigerator", "kitchen_counter"] {
                assert!(cats.contains(c), "{prompt} #{seed}: no {c}");
            }
            let (walk, reach) = walk_and_reach(scene);
            let eval = scenethesis_eval::EvalScene::from_scene_procedural(scene).unwrap();
            let unreachable =
                scenethesis_eval::raster::walk_and_reach(&eval).unreachable_floor_objects;
            lines.push(format!(
                "{prompt} #{seed}: {shape}, {} objects, rules {}/{}, walk {walk:.3} reach {reach:.3} {unreachable:?}, dropped {:?}",
                scene.objects.len(),
                check.held,
                check.checked,
                laid.dropped.iter().map(|d| format!("{}: {}", d.id, d.reason)).collect::<Vec<_>>()
            ));
            shapes.entry(prompt).or_default().insert(shape);
        }
    }
    println!("{}\n{}", lines.join("\n"), broken.join("\n"));
    assert_eq!(held, checked, "{}", broken.join("\n"));
    assert!(
        shapes["a kitchen"].len() >= 2,
        "one layout for every seed: {shapes:?}"
    );
    assert!(
        shapes["a small galley kitchen"].contains("galley"),
        "{shapes:?}"
    );
}
