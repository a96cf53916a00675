//! Round-based assets (lamps on tables, queue posts) must stand still after the small drop the
//! optimizer leaves below every object: it rests each object `support_clearance` (1.25 mm)
//! above its support, and the stability simulation lets it fall that far. A frustum-shaped
//! base simulated as a many-sided convex hull rocked after that drop (a table lamp tilted by
//! up to 0.1 rad, a stanchion slid 1.3 cm, a palm tree 2.4 cm, a beach umbrella 2 cm); a flat cylindrical foot rests still.

mod support;

use scenethesis_eval::stability::simulate;
use scenethesis_eval::{DecompositionCache, EvalScene};
use scenethesis_scene_graph::{Architecture, RelationKind};
use support::{at, catalog_asset, place, SETTLE_DROP};

#[test]
fn round_based_assets_stand_still_after_the_settle_drop() {
    let cache = DecompositionCache::default();
    let mut failures = Vec::new();
    for name in [
        "stanchion",
        "table_lamp",
        "floor_lamp",
        "palm_tree",
        "beach_umbrella",
    ] {
        for seed in 0..24u64 {
            let asset = catalog_asset(name, seed);
            for yaw in [0.0, std::f64::consts::PI] {
                let scene = EvalScene {
                    objects: vec![place(
                        name,
                        name,
                        &asset.mesh,
                        at(-0.87, SETTLE_DROP, -0.82, yaw),
                        None,
                        RelationKind::OnFloor,
                    )],
                    architecture: Architecture::open_ground(20.0, 20.0),
                };
                for u in &simulate(&scene, &cache).unstable {
                    failures.push(format!("{name} seed {seed} yaw {yaw:.2}: {u:?}"));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
