//! The stability metric keeps a resting pair's contact points while the pair drifts less than
//! `CONTACT_RECYCLE_DRIFT` (a speed-up). Recycled contacts must not change what the metric
//! sees: on a room of the assets that crept under rapier's game default (tall lamps, plants,
//! umbrellas, coat racks), things standing on a table and a shop shelf stocked with round cans on every board,
//! every body ends where recomputing every contact at every step leaves it, and what falls
//! still falls; a round fruit that rolls away on bare ground still rolls (at rapier's game
//! default of 5 cm, stale contacts hold it in place).

mod support;

use scenethesis_eval::stability::{simulate_with, Simulation};
use scenethesis_eval::{DecompositionCache, EvalObject, EvalScene};
use scenethesis_scene_graph::{Architecture, Asset, RelationKind, SurfaceKind};
use support::{assert_same_ends, at, catalog_asset, clear_cut, place, stocked_shelf, SETTLE_DROP};

/// The highest surface of `kind` of `asset`: (height, centre x, centre z, half width along x).
fn surface(asset: &Asset, kind: SurfaceKind) -> (f64, f64, f64, f64) {
    let s = asset
        .info
        .support_surfaces
        .iter()
        .filter(|s| s.kind == kind)
        .max_by(|a, b| a.height.total_cmp(&b.height))
        .expect("the asset has the surface");
    let xs = s.polygon.iter().map(|p| f64::from(p[0]));
    let (x0, x1) = xs.fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
    let c = s.center();
    (
        f64::from(s.height),
        f64::from(c[0]),
        f64::from(c[1]),
        (x1 - x0) / 2.0,
    )
}

/// Tall floor items in a row, a table with small round things on it, a stocked shop shelf.
fn room() -> EvalScene {
    let mut objects: Vec<EvalObject> = Vec::new();
    let tall = [
        "floor_lamp",
        "plant",
        "coat_rack",
        "beach_umbrella",
        "guitar",
        "water_cooler",
    ];
    for (n, name) in tall.iter().enumerate() {
        for seed in 0..2u64 {
            let x = -6.0 + 2.5 * n as f64;
            let z = -3.0 + 3.0 * seed as f64;
            let id = format!("{name}_{seed}");
            let pose = at(x, SETTLE_DROP, z, 0.4 * seed as f64);
            let asset = catalog_asset(name, seed);
            objects.push(place(
                &id,
                name,
                &asset.mesh,
                pose,
                None,
                RelationKind::OnFloor,
            ));
        }
    }
    let table = catalog_asset("side_table", 0);
    let (top, cx, cz, half) = surface(&table, SurfaceKind::Top);
    objects.push(place(
        "table",
        "side_table",
        &table.mesh,
        at(0.0, SETTLE_DROP, 4.0, 0.0),
        None,
        RelationKind::OnFloor,
    ));
    for (k, name) in ["table_lamp", "candle", "bottle"].iter().enumerate() {
        let x = cx + (k as f64 - 1.0) * 0.5 * half;
        let pose = at(x, top + 2.0 * SETTLE_DROP, 4.0 + cz, 0.0);
        let asset = catalog_asset(name, 1);
        objects.push(place(
            name,
            name,
            &asset.mesh,
            pose,
            Some("table"),
            RelationKind::On,
        ));
    }
    objects.extend(stocked_shelf(4.0, 4.0));
    EvalScene {
        objects,
        architecture: Architecture::open_ground(16.0, 12.0),
    }
}

#[test]
fn recycled_contacts_leave_every_body_where_recomputed_contacts_do() {
    let scene = room();
    let cache = DecompositionCache::default();
    let (_, fast) = simulate_with(&scene, &cache, &Simulation::default());
    let (exact, reference) = simulate_with(&scene, &cache, &Simulation::recomputing_contacts());
    assert!(exact.tested > 20, "only {} bodies", exact.tested);
    let marginal = assert_same_ends(&fast, &reference);
    assert!(
        marginal.len() <= 2,
        "too many bodies at the edge: {marginal:?}"
    );
    // The scene does move a little (the settle drop), so the comparison is not of zeros.
    assert!(reference.iter().any(|m| m.displacement > 0.0005));
}

#[test]
fn a_fruit_that_rolls_away_with_recomputed_contacts_rolls_with_recycled_ones() {
    let cache = DecompositionCache::default();
    let mut rolling = 0;
    for seed in 0..6u64 {
        let fruit = catalog_asset("fruit", seed);
        for yaw in [0.0, 1.0, 2.0] {
            let scene = EvalScene {
                objects: vec![place(
                    "fruit",
                    "fruit",
                    &fruit.mesh,
                    at(0.0, SETTLE_DROP, 0.0, yaw),
                    None,
                    RelationKind::OnFloor,
                )],
                architecture: Architecture::open_ground(20.0, 20.0),
            };
            let (_, reference) = simulate_with(&scene, &cache, &Simulation::recomputing_contacts());
            if clear_cut(&reference[0]) != Some(true) {
                continue;
            }
            rolling += 1;
            let (_, fast) = simulate_with(&scene, &cache, &Simulation::default());
            assert!(
                fast[0].is_unstable(),
                "fruit seed {seed} yaw {yaw} rolls {:?} but stays with recycled contacts: {:?}",
                reference[0],
                fast[0]
            );
        }
    }
    // A fruit's hull is not quite a sphere: some of them roll, so the check is not empty.
    assert!(rolling > 0, "no fruit rolls at all");
}
