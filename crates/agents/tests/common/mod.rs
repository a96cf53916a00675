//! Shared helpers of the agents tests: the benchmark prompts with the categories each plan
//! must hold, the library's categories, and an independent raster implementation of the Walk
//! and Reach metrics (docs: /work/shared/metrics.md).
#![allow(dead_code)]

use scenethesis_agents::{
    CatalogAssets, Guide, GuidedLayout, KnowledgePlanner, Plan, PlanRequest, Planner,
    ProceduralGuide,
};
use scenethesis_scene_graph::{ParentRef, Scene, SceneObject};

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
    scenethesis_assets::catalog::categories()
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

fn distance_to_box(p: [f64; 2], o: &SceneObject) -> f64 {
    let (c, yaw, h) = footprint(o);
    let (s, co) = yaw.sin_cos();
    let (dx, dz) = (p[0] - c[0], p[1] - c[1]);
    let lx = dx * co - dz * s;
    let lz = dx * s + dz * co;
    let ex = (lx.abs() - h[0]).max(0.0);
    let ez = (lz.abs() - h[1]).max(0.0);
    (ex * ex + ez * ez).sqrt()
}

/// Walk and Reach (floor-standing objects) by the metric rules: a 256 × 256 raster over the
/// floor's bounding square plus 0.2 m, the floor eroded by the 0.15 m robot radius, footprints
/// grown by the radius, 8-connected components.
pub fn walk_and_reach(scene: &Scene) -> (f64, f64) {
    let floor = &scene.architecture.floor;
    let (w, d) = (floor.max.x - floor.min.x, floor.max.y - floor.min.y);
    let side = w.max(d) + 0.4;
    let (cx, cz) = (
        (floor.min.x + floor.max.x) / 2.0,
        (floor.min.y + floor.max.y) / 2.0,
    );
    let n = 256usize;
    let px = side / n as f64;
    let r = 0.15;
    let center = |i: usize, j: usize| {
        [
            cx - side / 2.0 + (i as f64 + 0.5) * px,
            cz - side / 2.0 + (j as f64 + 0.5) * px,
        ]
    };
    let on_floor = |p: [f64; 2]| {
        p[0] >= floor.min.x + r
            && p[0] <= floor.max.x - r
            && p[1] >= floor.min.y + r
            && p[1] <= floor.max.y - r
    };
    let walk_obstacles: Vec<&SceneObject> = scene
        .objects
        .iter()
        .filter(|o| o.world_aabb().center().y < 1.5)
        .collect();
    let components = |obstacles: &[&SceneObject]| {
        let mut free = vec![false; n * n];
        for j in 0..n {
            for i in 0..n {
                let p = center(i, j);
                free[j * n + i] =
                    on_floor(p) && obstacles.iter().all(|o| distance_to_box(p, o) > r);
            }
        }
        let mut labels = vec![0usize; n * n];
        let mut sizes = vec![0usize];
        for s in 0..n * n {
            if !free[s] || labels[s] != 0 {
                continue;
            }
            let l = sizes.len();
            let mut stack = vec![s];
            labels[s] = l;
            let mut size = 0;
            while let Some(k) = stack.pop() {
                size += 1;
                let (i, j) = ((k % n) as i64, (k / n) as i64);
                for dj in -1..=1 {
                    for di in -1..=1 {
                        let (a, b) = (i + di, j + dj);
                        if a >= 0 && b >= 0 && a < n as i64 && b < n as i64 {
                            let m = b as usize * n + a as usize;
                            if free[m] && labels[m] == 0 {
                                labels[m] = l;
                                stack.push(m);
                            }
                        }
                    }
                }
            }
            sizes.push(size);
        }
        (labels, sizes)
    };
    let (_, wsizes) = components(&walk_obstacles);
    let total: usize = wsizes.iter().sum();
    let walk = if total == 0 {
        0.0
    } else {
        *wsizes.iter().max().unwrap() as f64 / total as f64
    };

    let all: Vec<&SceneObject> = scene.objects.iter().collect();
    let (labels, sizes) = components(&all);
    let total: usize = sizes.iter().sum();
    let ground: Vec<&SceneObject> = scene
        .objects
        .iter()
        .filter(|o| o.parent == ParentRef::Ground)
        .collect();
    let mut touching = vec![0usize; sizes.len()];
    for o in &ground {
        let (c, _, h) = footprint(o);
        let reach_r = h[0].hypot(h[1]) + r + 3.0 * px;
        let to_px = |v: f64, c0: f64| {
            ((v - (c0 - side / 2.0)) / px)
                .floor()
                .clamp(0.0, (n - 1) as f64) as usize
        };
        let (i0, i1) = (to_px(c[0] - reach_r, cx), to_px(c[0] + reach_r, cx));
        let (j0, j1) = (to_px(c[1] - reach_r, cz), to_px(c[1] + reach_r, cz));
        let mut seen = std::collections::BTreeSet::new();
        for j in j0..=j1 {
            for i in i0..=i1 {
                let l = labels[j * n + i];
                if l != 0 && distance_to_box(center(i, j), o) <= r + px * 1.5 {
                    seen.insert(l);
                }
            }
        }
        for l in seen {
            touching[l] += 1;
        }
    }
    let mut reach = 0.0;
    for l in 1..sizes.len() {
        reach +=
            touching[l] as f64 / ground.len().max(1) as f64 * sizes[l] as f64 / total.max(1) as f64;
    }
    (walk, reach)
}
