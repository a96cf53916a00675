//! The stability metric simulates groups of free bodies that cannot reach each other in
//! separate worlds, side by side (a speed-up). That must not change what the metric sees:
//! on a room of separate groups (a stocked shop shelf, a table with things on it, tall floor
//! items), every body ends where one world for the whole scene leaves it; and when a body
//! travels far enough to reach another group (a plank falling onto a block), the scene is
//! simulated in one world again, so the block still holds the plank up.

mod support;

use scenethesis_eval::stability::{simulate_with, Simulation};
use scenethesis_eval::{DecompositionCache, EvalObject, EvalScene};
use scenethesis_primitives::cuboid;
use scenethesis_scene_graph::{Architecture, RelationKind};
use support::{
    assert_same_ends, at, block, catalog_asset, cup, mesh, place, stocked_shelf, table, SETTLE_DROP,
};

/// A shop shelf stocked with cans, a table with four cups, and a row of tall floor items,
/// each group a metre or more from the others.
fn room_of_groups() -> EvalScene {
    let mut objects: Vec<EvalObject> = stocked_shelf(-3.0, 0.0);
    let top = 0.75;
    objects.push(place(
        "table",
        "table",
        &table(1.2, 0.8, top, 0.04),
        at(0.0, SETTLE_DROP, 0.0, 0.0),
        None,
        RelationKind::OnFloor,
    ));
    for k in 0..4 {
        let x = -0.45 + 0.3 * k as f64;
        objects.push(place(
            &format!("cup_{k}"),
            "cup",
            &cup(),
            at(x, top as f64 + 2.0 * SETTLE_DROP, 0.1, 0.0),
            Some("table"),
            RelationKind::On,
        ));
    }
    for (n, name) in ["floor_lamp", "plant", "coat_rack"].iter().enumerate() {
        let asset = catalog_asset(name, 0);
        objects.push(place(
            &format!("{name}_0"),
            name,
            &asset.mesh,
            at(2.0 + 1.5 * n as f64, SETTLE_DROP, -1.0, 0.3),
            None,
            RelationKind::OnFloor,
        ));
    }
    EvalScene {
        objects,
        architecture: Architecture::open_ground(14.0, 8.0),
    }
}

#[test]
fn separate_worlds_leave_every_body_where_one_world_does() {
    let scene = room_of_groups();
    let cache = DecompositionCache::default();
    let (split, apart) = simulate_with(&scene, &cache, &Simulation::default());
    let (whole, together) = simulate_with(&scene, &cache, &Simulation::one_world());
    assert!(split.worlds > 1, "the groups shared one world");
    assert_eq!(whole.worlds, 1);
    assert_eq!(split.tested, whole.tested);
    assert!(whole.tested > 20, "only {} bodies", whole.tested);
    assert_same_ends(&apart, &together);
    // The scene does move a little (the settle drop), so the comparison is not of zeros.
    assert!(together.iter().any(|m| m.displacement > 0.0005));
}

#[test]
fn worlds_one_after_another_end_exactly_where_side_by_side_ones_do() {
    let scene = room_of_groups();
    let cache = DecompositionCache::default();
    let side_by_side = simulate_with(&scene, &cache, &Simulation::default());
    let one_core = simulate_with(&scene, &cache, &Simulation::on_one_core());
    assert!(side_by_side.0.worlds > 1);
    assert_eq!(side_by_side, one_core);
}

/// A 1 m plank, 2 cm thick and 40 cm deep, standing on its bottom edge at the origin and
/// leaning `lean` radians towards +x, so that it falls that way.
fn leaning_plank(lean: f32) -> EvalObject {
    let mut part = cuboid("plank", 0, [-0.01, 0.0, -0.2], [0.01, 1.0, 0.2]);
    let (sin, cos) = lean.sin_cos();
    for p in &mut part.positions {
        let [x, y, z] = *p;
        // Turned about z by −lean, then lifted so that its lowest edge is at the drop height.
        *p = [x * cos + y * sin, -x * sin + y * cos + 0.01 * sin, z];
    }
    place(
        "plank",
        "plank",
        &mesh(vec![part]),
        at(0.0, SETTLE_DROP, 0.0, 0.0),
        None,
        RelationKind::OnFloor,
    )
}

#[test]
fn a_body_that_travels_far_sends_the_scene_back_to_one_world() {
    // The block is 30 cm beyond the plank's box: a group of its own, where the plank falls.
    let scene = EvalScene {
        objects: vec![
            leaning_plank(0.3),
            place(
                "block",
                "block",
                &block(0.1, 0.1, 0.1),
                at(0.65, SETTLE_DROP, 0.0, 0.0),
                None,
                RelationKind::OnFloor,
            ),
        ],
        architecture: Architecture::open_ground(6.0, 6.0),
    };
    let cache = DecompositionCache::default();
    let (report, motions) = simulate_with(&scene, &cache, &Simulation::default());
    let (whole, together) = simulate_with(&scene, &cache, &Simulation::one_world());
    assert_eq!(
        report.worlds, 1,
        "the scene stayed split after the plank fell"
    );
    assert_eq!(report, whole);
    assert_eq!(motions, together);
    // The plank lands on the block, which holds it up: alone it falls flat (turning by
    // π/2 − 0.3), which is what a world of its own would have shown.
    let alone = EvalScene {
        objects: vec![leaning_plank(0.3)],
        architecture: scene.architecture.clone(),
    };
    let (_, flat) = simulate_with(&alone, &cache, &Simulation::default());
    assert!(
        flat[0].rotation > 1.2,
        "the plank alone does not fall flat: {flat:?}"
    );
    assert!(
        motions[0].rotation < flat[0].rotation - 0.1,
        "the block does not hold the plank: {motions:?} against {flat:?}"
    );
}
