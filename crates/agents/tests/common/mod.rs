//! Shared helpers of the agents tests: the benchmark prompts with the categories each plan
//! must hold, the library's categories, and the Walk and Reach metrics of a guided scene (from
//! `scenethesis-eval`).
#![allow(dead_code)]

use scenethesis_agents::{
    CatalogAssets, Guide, GuidedLayout, KnowledgePlanner, Plan, PlanRequest, Planner,
    ProceduralGuide,
};
use scenethesis_eval::EvalScene;
use scenethesis_scene_graph::{Scene, SceneObject};

/// The public benchmark prompts (shared/benchmarks/prompts.txt) and the key categories one
/// expects in each plan.
pub const BENCHMARK: &[(&str, &[&str])] = &[
    (
        "a cozy living room with reading materials",
        &[
            "sofa",
            "coffee_table",
            "armchair",
            "bookshelf",
            "book",
            "floor_lamp",
        ],
    ),
    (
        "a children's playroom",
        &[
            "kids_table",
            "kids_chair",
            "toy_box",
            "teddy_bear",
            "ball",
            "toy_blocks",
        ],
    ),
    (
        "a garage",
        &[
            "workbench",
            "tool_cabinet",
            "shelving_unit",
            "toolbox",
            "ladder",
            "tire",
        ],
    ),
    (
        "a warehouse",
        &["pallet_rack", "pallet", "box", "crate", "shelving_unit"],
    ),
    (
        "a bookstore",
        &[
            "bookshelf",
            "book",
            "display_table",
            "checkout_counter",
            "cash_register",
        ],
    ),
    (
        "a convenience store",
        &[
            "store_shelf",
            "drinks_fridge",
            "checkout_counter",
            "cash_register",
            "can",
            "bottle",
        ],
    ),
    (
        "a museum gallery",
        &["display_case", "pedestal", "sculpture", "painting", "bench"],
    ),
    (
        "a piano showroom",
        &["grand_piano", "upright_piano", "piano_bench", "music_stand"],
    ),
    (
        "a gym room",
        &[
            "treadmill",
            "exercise_bike",
            "weight_bench",
            "dumbbell_rack",
            "dumbbell",
            "squat_rack",
        ],
    ),
    (
        "a billiard club",
        &[
            "pool_table",
            "billiard_ball",
            "cue_rack",
            "bar_counter",
            "bar_stool",
        ],
    ),
    (
        "a hospital ward",
        &[
            "hospital_bed",
            "iv_stand",
            "nightstand",
            "patient_monitor",
            "privacy_screen",
        ],
    ),
    (
        "a chemistry laboratory",
        &[
            "lab_bench",
            "beaker",
            "flask",
            "fume_hood",
            "chemical_cabinet",
            "test_tube_rack",
        ],
    ),
    (
        "a peaceful beach during sunset",
        &[
            "beach_umbrella",
            "beach_lounger",
            "beach_towel",
            "palm_tree",
            "surfboard",
        ],
    ),
    (
        DETAILED,
        &[
            "sofa",
            "coffee_table",
            "mug",
            "vase",
            "armchair",
            "bookshelf",
            "book",
            "floor_lamp",
        ],
    ),
];

/// The benchmark's detailed prompt.
pub const DETAILED: &str = "a living room with a grey three-seat sofa against the back wall, a low round coffee table in front of it with two mugs and a small vase on top, two armchairs on either side of the table turned toward the sofa, a tall bookshelf in the corner with books and a plant inside its shelves, and a floor lamp beside the sofa";

/// The built-in library's categories.
pub fn available() -> Vec<String> {
    scenethesis_procedural::catalog::categories()
        .map(|c| c.name.to_owned())
        .collect()
}

/// Plans `prompt` with the offline planner over the built-in library.
pub fn plan(prompt: &str, seed: u64) -> Plan {
    KnowledgePlanner::new()
        .plan(&PlanRequest::new(prompt, available(), seed))
        .unwrap_or_else(|e| panic!("{prompt}: {e}"))
}

/// Plans and lays out `prompt` with the built-in catalog's assets.
pub fn layout(prompt: &str, seed: u64) -> (Plan, GuidedLayout) {
    let plan = plan(prompt, seed);
    let layout = ProceduralGuide::default()
        .layout(&plan, &CatalogAssets::new(seed), seed)
        .unwrap_or_else(|e| panic!("{prompt}: {e}"));
    (plan, layout)
}

/// An object's footprint on the floor: centre (x, z), yaw, half extents.
pub fn footprint(o: &SceneObject) -> ([f64; 2], f64, [f64; 2]) {
    let c = o.local_bounds.center();
    let w = o.pose.transform_point(&c);
    let s = o.local_bounds.size() * o.pose.scale / 2.0;
    ([w.x, w.z], o.pose.yaw, [s.x, s.z])
}

/// Walk and Reach (floor-standing objects) by the metric rules (docs: /work/shared/metrics.md),
/// computed by `scenethesis-eval` over the scene's regenerated procedural meshes. Reach is 0
/// when nothing stands on the floor.
pub fn walk_and_reach(scene: &Scene) -> (f64, f64) {
    let eval = EvalScene::from_scene_procedural(scene)
        .unwrap_or_else(|e| panic!("procedural meshes of a guided scene: {e}"));
    let metrics = scenethesis_eval::raster::walk_and_reach(&eval);
    (metrics.walk, metrics.reach_floor.unwrap_or(0.0))
}
