//! The per-scene metrics and their aggregate over many scenes.

use std::collections::BTreeSet;

use scenethesis_scene_graph::RelationKind;
use serde::{Deserialize, Serialize};

use crate::collision::{collisions_with, ArchPenetration, CollidingPair, SceneFields};
use crate::opening::{opening_clearances_with, OpeningClearance};
use crate::raster::walk_and_reach;
use crate::scene::EvalScene;
use crate::stability::{simulate_with, DecompositionCache, Simulation, UnstableObject};

/// Every metric of one scene (see `metrics.md`), with the details a judge can act on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SceneMetrics {
    /// Number of movable objects.
    pub objects: usize,
    /// Number of distinct categories.
    pub categories: usize,
    /// The distinct categories, sorted.
    pub category_names: Vec<String>,
    /// Number of distinct relation kinds used (supports and relations, `on-floor` not counted).
    pub relation_kinds: usize,
    /// The distinct relation kinds used, in declaration order.
    pub relation_kind_names: Vec<String>,
    /// Col-O: colliding objects / objects (0 for an empty scene).
    pub col_o: f64,
    /// Whether any object collides (this scene's share of Col-S).
    pub col_s: bool,
    /// The colliding object ids, in scene order.
    pub colliding_objects: Vec<String>,
    /// The colliding pairs with their penetration depths.
    pub colliding_pairs: Vec<CollidingPair>,
    /// Pairs whose boxes touch, tested with the meshes.
    pub pairs_tested: usize,
    /// Col-arch: objects penetrating the floor or a wall / objects.
    pub col_arch: f64,
    /// Penetrations of the floor and walls.
    pub arch_penetrations: Vec<ArchPenetration>,
    /// Inst-O: unstable objects / objects simulated as free bodies (0 when none).
    pub inst_o: f64,
    /// Whether any object is unstable (this scene's share of Inst-S).
    pub inst_s: bool,
    /// Objects simulated as free bodies.
    pub stability_tested: usize,
    /// The unstable objects with how far they moved and turned.
    pub unstable: Vec<UnstableObject>,
    /// Objects mounted on a wall (support `mounted`), welded and excluded from stability.
    pub welded: Vec<String>,
    /// Objects without volume, excluded from stability.
    pub stability_skipped: Vec<String>,
    /// Simulated time of the stability simulation (s): its full duration, or less when every
    /// body fell asleep earlier.
    #[serde(default)]
    pub stability_simulated_seconds: f64,
    /// Walk: largest walkable component / walkable area.
    pub walk: f64,
    /// Reach over floor-standing objects; `None` without any.
    pub reach_floor: Option<f64>,
    /// Reach over all objects; `None` without any.
    pub reach_all: Option<f64>,
    /// Walkable floor area (m²) of the Walk raster.
    pub walkable_area: f64,
    /// Floor-standing objects no walkable component touches.
    pub unreachable_floor_objects: Vec<String>,
    /// Opening clearance of every door, drawer and lid (empty when nothing opens).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub openings: Vec<OpeningClearance>,
}

impl SceneMetrics {
    /// The joints that cannot open to [`OPEN_SHARE`](scenethesis_scene_graph::OPEN_SHARE) of
    /// their range.
    pub fn blocked_openings(&self) -> impl Iterator<Item = &OpeningClearance> {
        self.openings.iter().filter(|o| !o.held)
    }
}

/// Evaluates one scene with a fresh decomposition cache.
pub fn evaluate(scene: &EvalScene) -> SceneMetrics {
    evaluate_with_cache(scene, &DecompositionCache::new())
}

/// Wall-clock seconds each part of an evaluation took ([`evaluate_timed`]). The parts run side
/// by side (rayon), so on a multi-core machine they add up to more than the whole evaluation.
/// The one non-deterministic output of this crate; it is kept out of [`SceneMetrics`].
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EvalTimings {
    /// Object pairs and the architecture tested with the meshes
    /// ([`collisions`](crate::collision::collisions)).
    pub collisions: f64,
    /// The rigid-body stability simulation ([`simulate_with`]).
    pub stability: f64,
    /// The Walk and Reach floor rasters ([`walk_and_reach`]).
    pub walk_reach: f64,
    /// The opening-clearance sweep of doors, drawers and lids
    /// ([`opening_clearances`](crate::opening::opening_clearances)).
    pub openings: f64,
}

/// Evaluates one scene, reusing (and filling) `cache` for convex decompositions.
pub fn evaluate_with_cache(scene: &EvalScene, cache: &DecompositionCache) -> SceneMetrics {
    evaluate_timed(scene, cache).0
}

/// Runs `work` and returns its result with the wall-clock seconds it took.
fn timed<T>(work: impl FnOnce() -> T) -> (T, f64) {
    let started = std::time::Instant::now();
    let value = work();
    (value, started.elapsed().as_secs_f64())
}

/// Evaluates one scene like [`evaluate_with_cache`] and says how long each part took.
pub fn evaluate_timed(
    scene: &EvalScene,
    cache: &DecompositionCache,
) -> (SceneMetrics, EvalTimings) {
    evaluate_timed_with(scene, cache, &Simulation::default())
}

/// Evaluates one scene like [`evaluate_timed`], running the stability simulation as
/// `simulation` says ([`Simulation::on_one_core`] keeps it on the calling thread, for a caller
/// that runs other work meanwhile).
pub fn evaluate_timed_with(
    scene: &EvalScene,
    cache: &DecompositionCache,
    simulation: &Simulation,
) -> (SceneMetrics, EvalTimings) {
    // The collision pairs and the opening sweeps test against the same exact part fields.
    let fields = SceneFields::new(scene);
    let (
        ((collision, collisions_s), (stability, stability_s)),
        ((walk, walk_s), (openings, openings_s)),
    ) = rayon::join(
        || {
            rayon::join(
                || timed(|| collisions_with(scene, &fields)),
                || timed(|| simulate_with(scene, cache, simulation).0),
            )
        },
        || {
            rayon::join(
                || timed(|| walk_and_reach(scene)),
                || timed(|| opening_clearances_with(scene, &fields)),
            )
        },
    );
    let timings = EvalTimings {
        collisions: collisions_s,
        stability: stability_s,
        walk_reach: walk_s,
        openings: openings_s,
    };
    (
        metrics_of(scene, collision, stability, walk, openings),
        timings,
    )
}

/// The metrics of `scene` from its parts' results.
fn metrics_of(
    scene: &EvalScene,
    collision: crate::collision::CollisionReport,
    stability: crate::stability::StabilityReport,
    walk: crate::raster::WalkReach,
    openings: Vec<OpeningClearance>,
) -> SceneMetrics {
    let n = scene.objects.len();
    let rate = |k: usize, d: usize| if d == 0 { 0.0 } else { k as f64 / d as f64 };
    let category_names: Vec<String> = scene
        .objects
        .iter()
        .map(|o| o.category.clone())
        .collect::<BTreeSet<_>>()
        .into_iter()
        .collect();
    let kinds: BTreeSet<RelationKind> = scene
        .objects
        .iter()
        .flat_map(|o| {
            o.support
                .into_iter()
                .chain(o.relations.iter().map(|r| r.kind))
        })
        .filter(|k| *k != RelationKind::OnFloor)
        .collect();
    let arch_objects: BTreeSet<&str> = collision
        .architecture
        .iter()
        .map(|p| p.object.as_str())
        .collect();
    SceneMetrics {
        objects: n,
        categories: category_names.len(),
        category_names,
        relation_kinds: kinds.len(),
        relation_kind_names: kinds.iter().map(|k| k.as_str().to_owned()).collect(),
        col_o: rate(collision.colliding_objects.len(), n),
        col_s: !collision.colliding_objects.is_empty(),
        colliding_objects: collision.colliding_objects,
        colliding_pairs: collision.pairs,
        pairs_tested: collision.pairs_tested,
        col_arch: rate(arch_objects.len(), n),
        arch_penetrations: collision.architecture,
        inst_o: rate(stability.unstable.len(), stability.tested),
        inst_s: !stability.unstable.is_empty(),
        stability_tested: stability.tested,
        unstable: stability.unstable,
        welded: stability.welded,
        stability_skipped: stability.skipped,
        stability_simulated_seconds: stability.simulated_seconds,
        walk: walk.walk,
        reach_floor: walk.reach_floor,
        reach_all: walk.reach_all,
        walkable_area: walk.walkable_area,
        unreachable_floor_objects: walk.unreachable_floor_objects,
        openings,
    }
}

/// Metrics pooled over many scenes as `metrics.md` says: Col-O and Inst-O over all objects,
/// Col-S and Inst-S over scenes, Walk and Reach as means over scenes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MetricsSummary {
    /// Number of scenes.
    pub scenes: usize,
    /// Objects over all scenes.
    pub objects: usize,
    /// Colliding objects over all scenes / objects.
    pub col_o: f64,
    /// Scenes with a colliding object / scenes.
    pub col_s: f64,
    /// Objects penetrating architecture / objects.
    pub col_arch: f64,
    /// Unstable objects / objects simulated, over all scenes.
    pub inst_o: f64,
    /// Scenes with an unstable object / scenes.
    pub inst_s: f64,
    /// Mean Walk.
    pub walk: f64,
    /// Mean Reach over floor-standing objects (scenes that have some).
    pub reach_floor: Option<f64>,
    /// Mean Reach over all objects (scenes that have some).
    pub reach_all: Option<f64>,
    /// Mean objects per scene.
    pub mean_objects: f64,
    /// Mean distinct categories per scene.
    pub mean_categories: f64,
    /// Mean distinct relation kinds per scene.
    pub mean_relation_kinds: f64,
    /// Objects with at least one joint (doors, drawers, lids), over all scenes.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub openable_objects: usize,
    /// Joints over all scenes.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub joints: usize,
    /// Joints that open to 90 % of their range unobstructed / joints (`None` without joints).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub opening_clearance: Option<f64>,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

impl MetricsSummary {
    /// Pools the metrics of `scenes` (all zero / `None` for no scenes).
    pub fn from_scenes(scenes: &[SceneMetrics]) -> Self {
        let s = scenes.len();
        let rate = |k: usize, d: usize| if d == 0 { 0.0 } else { k as f64 / d as f64 };
        let mean = |v: Vec<f64>| {
            if v.is_empty() {
                None
            } else {
                Some(v.iter().sum::<f64>() / v.len() as f64)
            }
        };
        let objects: usize = scenes.iter().map(|m| m.objects).sum();
        let colliding: usize = scenes.iter().map(|m| m.colliding_objects.len()).sum();
        let arch: usize = scenes
            .iter()
            .map(|m| {
                m.arch_penetrations
                    .iter()
                    .map(|p| p.object.as_str())
                    .collect::<BTreeSet<_>>()
                    .len()
            })
            .sum();
        let tested: usize = scenes.iter().map(|m| m.stability_tested).sum();
        let unstable: usize = scenes.iter().map(|m| m.unstable.len()).sum();
        let joints: usize = scenes.iter().map(|m| m.openings.len()).sum();
        let held = joints
            - scenes
                .iter()
                .map(|m| m.blocked_openings().count())
                .sum::<usize>();
        Self {
            scenes: s,
            objects,
            col_o: rate(colliding, objects),
            col_s: rate(scenes.iter().filter(|m| m.col_s).count(), s),
            col_arch: rate(arch, objects),
            inst_o: rate(unstable, tested),
            inst_s: rate(scenes.iter().filter(|m| m.inst_s).count(), s),
            walk: mean(scenes.iter().map(|m| m.walk).collect()).unwrap_or(0.0),
            reach_floor: mean(scenes.iter().filter_map(|m| m.reach_floor).collect()),
            reach_all: mean(scenes.iter().filter_map(|m| m.reach_all).collect()),
            mean_objects: mean(scenes.iter().map(|m| m.objects as f64).collect()).unwrap_or(0.0),
            mean_categories: mean(scenes.iter().map(|m| m.categories as f64).collect())
                .unwrap_or(0.0),
            mean_relation_kinds: mean(scenes.iter().map(|m| m.relation_kinds as f64).collect())
                .unwrap_or(0.0),
            openable_objects: scenes
                .iter()
                .map(|m| {
                    m.openings
                        .iter()
                        .map(|o| o.object.as_str())
                        .collect::<BTreeSet<_>>()
                        .len()
                })
                .sum(),
            joints,
            opening_clearance: (joints > 0).then(|| rate(held, joints)),
        }
    }
}
