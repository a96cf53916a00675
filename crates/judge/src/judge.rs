//! The judge stage: decides whether an optimized scene is good enough to ship, and names the
//! objects at fault when it is not, so the pipeline can re-plan.

use std::collections::{BTreeMap, BTreeSet};

use scenethesis_agents::{
    check_arrangement, check_prompt, core_categories, ArrangementCheck, Plan,
};
use scenethesis_eval::stability::Simulation;
use scenethesis_eval::{
    evaluate_timed_with, DecompositionCache, EvalError, EvalScene, EvalTimings, SceneMetrics,
};
use scenethesis_imagery::Guidance;
use scenethesis_scene_graph::{relation_holds, Mesh, ParentRef, Relation, Scene};
use serde::{Deserialize, Serialize};

/// What the judge looks at.
#[derive(Debug, Clone, Copy)]
pub struct JudgeInput<'a> {
    /// The plan the scene was made from (its relations must hold).
    pub plan: &'a Plan,
    /// The optimized scene.
    pub scene: &'a Scene,
    /// Every object's mesh in its asset frame, by object id.
    pub meshes: &'a BTreeMap<String, Mesh>,
    /// The guidance the layout was lifted from (image, camera, depth, masks), when the guide
    /// worked from one; a judge that sees images can compare the scene with it.
    pub guidance: Option<&'a Guidance>,
    /// Whether the caller runs other work on the spare core while the judge runs (the
    /// pipeline draws the previews beside it): the stability simulation then runs its
    /// separate worlds one after another on one core ([`Simulation::on_one_core`]) instead of
    /// side by side. The verdict is the same either way.
    pub cores_shared: bool,
}

impl JudgeInput<'_> {
    /// How the stability simulation runs for this input (see [`JudgeInput::cores_shared`]).
    pub fn simulation(&self) -> Simulation {
        if self.cores_shared {
            Simulation::on_one_core()
        } else {
            Simulation::default()
        }
    }
}

impl JudgeInput<'_> {
    /// The scene as `scenethesis-eval` measures it: every object with its mesh placed in the
    /// world. Fails naming the first object the judge was given no mesh for.
    pub fn eval_scene(&self) -> Result<EvalScene, EvalError> {
        EvalScene::from_scene(self.scene, |o| {
            self.meshes
                .get(&o.id)
                .cloned()
                .ok_or_else(|| EvalError::MissingMesh {
                    object: o.id.clone(),
                    reason: "the judge was given no mesh for it".into(),
                })
        })
    }
}

/// The kind of a judged failure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FailureKind {
    /// Two objects interpenetrate by more than 1 mm.
    Collision,
    /// An object penetrates the floor or a wall.
    ArchitectureCollision,
    /// An object moves or turns in the stability simulation.
    Unstable,
    /// A relation of the plan does not hold.
    Relation,
    /// A floor object has no free floor next to it that the walkway reaches.
    Unreachable,
    /// The largest walkable region is less than the required share of the free floor.
    Walk,
    /// An object the prompt asked for is not in the scene.
    MissingObject,
    /// A vision-language model scored the rendered scene below a threshold (wrong categories,
    /// orientations or spatial coherence).
    Visual,
    /// A functional-arrangement rule (`knowledge/arrangement.toml`: seating faces what it
    /// serves, kitchen counters form runs along walls, …) does not hold.
    Arrangement,
    /// A door, drawer or lid cannot open to 90 % of its range without hitting another object
    /// or the architecture.
    OpeningClearance,
    /// A floor object taller than a window's sill stands in front of the window
    /// ([`scenethesis_scene_graph::Architecture::window_covered_by`]).
    WindowCovered,
    /// An object stands in (or hangs over) an area the plan keeps clear
    /// ([`scenethesis_agents::KeepClear`]: a house door's swing and approach), or hangs in
    /// front of a window above its cover height.
    KeepClear,
}

/// One reason a scene was rejected.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Failure {
    /// What failed.
    pub kind: FailureKind,
    /// The objects to blame, best candidate for removal first (empty when no single object is
    /// at fault).
    pub objects: Vec<String>,
    /// A sentence saying what was measured.
    pub detail: String,
}

/// The judge's decision on a scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Verdict {
    /// Whether the scene passes every check.
    pub accepted: bool,
    /// Every failed check (empty when accepted).
    pub failures: Vec<Failure>,
    /// The metrics the decision was based on.
    pub metrics: SceneMetrics,
    /// Relations of the plan that were checked.
    pub relations_checked: usize,
    /// The functional-arrangement rules (seating faces what it serves, a bed's head against a
    /// wall, kitchen runs, …) checked on the scene; each broken instance is also a
    /// [`FailureKind::Arrangement`] failure. Absent when the judge did not check them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub arrangement: Option<ArrangementCheck>,
    /// A model's review of the rendered scene (scores, per-object reasons), when a model judge
    /// looked at it; absent for the geometric judge.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub review: Option<serde_json::Value>,
    /// How long the parts of judging took, when the judge measured them. Wall-clock, so the
    /// one non-deterministic part of a verdict: never serialized (the pipeline moves it into
    /// `report.json`'s `timings`).
    #[serde(skip)]
    pub timings: Option<JudgeTimings>,
}

/// Wall-clock seconds the parts of judging one scene took.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct JudgeTimings {
    /// Placing every object's mesh in the world for the metrics ([`JudgeInput::eval_scene`]).
    pub meshes: f64,
    /// The metrics' parts: collisions, the stability simulation, Walk and Reach, openings.
    /// They run side by side, so they may add up to more than the judge's own time.
    pub metrics: EvalTimings,
    /// The relations of the plan and of the prompt.
    pub relations: f64,
    /// The functional-arrangement rules.
    pub arrangement: f64,
}

impl JudgeTimings {
    /// Every part as `(name, seconds)`, in the order `report.json` lists them.
    pub fn parts(&self) -> [(&'static str, f64); 7] {
        let m = &self.metrics;
        [
            ("meshes", self.meshes),
            ("collisions", m.collisions),
            ("stability", m.stability),
            ("relations", self.relations),
            ("walk-reach", m.walk_reach),
            ("openings", m.openings),
            ("arrangement", self.arrangement),
        ]
    }
}

/// Runs `work`, adding the wall-clock seconds it took to `seconds`.
pub(crate) fn timed<T>(seconds: &mut f64, work: impl FnOnce() -> T) -> T {
    let started = std::time::Instant::now();
    let value = work();
    *seconds += started.elapsed().as_secs_f64();
    value
}

impl Verdict {
    /// The distinct objects blamed by any failure, in first-blamed order.
    pub fn offenders(&self) -> Vec<String> {
        let mut seen = BTreeSet::new();
        self.failures
            .iter()
            .flat_map(|f| f.objects.iter())
            .filter(|id| seen.insert(id.as_str()))
            .cloned()
            .collect()
    }

    /// Every failure's detail on one line, separated by `"; "` (empty when accepted): the
    /// reason a rejected scene was rejected, as the CLI prints it.
    ///
    /// ```
    /// use scenethesis_eval::{evaluate, EvalScene};
    /// use scenethesis_judge::{Failure, FailureKind, Verdict};
    ///
    /// let failures = vec![
    ///     Failure {
    ///         kind: FailureKind::Collision,
    ///         objects: vec!["cup_0".into()],
    ///         detail: "cup_0 is 4 mm into table_0".into(),
    ///     },
    ///     Failure {
    ///         kind: FailureKind::Unstable,
    ///         objects: vec!["vase_0".into()],
    ///         detail: "vase_0 moved 3 cm".into(),
    ///     },
    /// ];
    /// let v = Verdict {
    ///     accepted: false,
    ///     failures,
    ///     metrics: evaluate(&EvalScene::default()),
    ///     relations_checked: 0,
    ///     arrangement: None,
    ///     review: None,
    ///     timings: None,
    /// };
    /// assert_eq!(v.reasons(), "cup_0 is 4 mm into table_0; vase_0 moved 3 cm");
    /// ```
    pub fn reasons(&self) -> String {
        self.failures
            .iter()
            .map(|f| f.detail.as_str())
            .collect::<Vec<_>>()
            .join("; ")
    }
}

/// Why a scene could not be judged at all.
#[derive(Debug, thiserror::Error)]
pub enum JudgeError {
    /// The metrics could not be computed.
    #[error("cannot evaluate the scene: {0}")]
    Eval(#[from] EvalError),
    /// An object of the scene has no mesh.
    #[error("object `{0}` has no mesh to judge")]
    MissingMesh(String),
    /// A model judge's provider failed (the message names the endpoint and model).
    #[error("judge `{judge}` failed: {message}")]
    Provider {
        /// The judge's name.
        judge: String,
        /// What failed.
        message: String,
    },
}

/// Stage 5: accepts or rejects a scene with reasons.
///
/// A judge of its own that rejects empty scenes and otherwise defers to [`crate::AcceptAll`]:
///
/// ```
/// use std::collections::BTreeMap;
/// use scenethesis_agents::{KnowledgePlanner, PlanRequest, Planner};
/// use scenethesis_judge::{AcceptAll, Failure, FailureKind, Judge, JudgeError, JudgeInput, Verdict};
/// use scenethesis_scene_graph::{Architecture, Scene};
///
/// struct NotEmpty(AcceptAll);
///
/// impl Judge for NotEmpty {
///     fn name(&self) -> &str {
///         "not-empty"
///     }
///     fn judge(&self, input: &JudgeInput<'_>) -> Result<Verdict, JudgeError> {
///         let mut verdict = self.0.judge(input)?;
///         if input.scene.objects.is_empty() {
///             verdict.accepted = false;
///             verdict.failures.push(Failure {
///                 kind: FailureKind::MissingObject,
///                 objects: Vec::new(),
///                 detail: "the scene is empty".into(),
///             });
///         }
///         Ok(verdict)
///     }
/// }
///
/// let plan = KnowledgePlanner::new().plan(&PlanRequest::new("a bedroom", ["bed"], 0)).unwrap();
/// let scene = Scene::new(Architecture::rectangular_room(4.0, 3.0, 2.6, 0.9));
/// let meshes = BTreeMap::new();
/// let input = JudgeInput {
///     plan: &plan,
///     scene: &scene,
///     meshes: &meshes,
///     guidance: None,
///     cores_shared: false,
/// };
/// let verdict = NotEmpty(AcceptAll::new()).judge(&input).unwrap();
/// assert!(!verdict.accepted);
/// assert_eq!(verdict.reasons(), "the scene is empty");
/// ```
pub trait Judge: Send + Sync {
    /// A short name for reports.
    fn name(&self) -> &str;

    /// Judges one scene.
    fn judge(&self, input: &JudgeInput<'_>) -> Result<Verdict, JudgeError>;
}

/// The offline geometric judge. It accepts a scene only if no two objects collide and nothing
/// penetrates the architecture (Col-O = Col-arch = 0), nothing moves in the stability simulation
/// (Inst-S = false), every relation of the plan between objects present in the scene holds,
/// every functional-arrangement rule holds ([`check_arrangement`]),
/// Walk ≥ [`GeometricJudge::min_walk`], every floor object is reachable — all measured by
/// `scenethesis-eval` exactly as `metrics.md` defines them — and no floor object taller than a
/// window's sill stands in front of it.
#[derive(Debug, Clone)]
pub struct GeometricJudge {
    /// Smallest acceptable Walk (0.95 by default).
    pub min_walk: f64,
    cache: DecompositionCache,
}

impl Default for GeometricJudge {
    fn default() -> Self {
        Self {
            min_walk: 0.95,
            cache: DecompositionCache::new(),
        }
    }
}

impl Judge for GeometricJudge {
    fn name(&self) -> &str {
        "geometric"
    }

    fn judge(&self, input: &JudgeInput<'_>) -> Result<Verdict, JudgeError> {
        let scene = input.scene;
        let mut timings = JudgeTimings::default();
        let eval_scene = timed(&mut timings.meshes, || input.eval_scene())?;
        let (metrics, metrics_timings) =
            evaluate_timed_with(&eval_scene, &self.cache, &input.simulation());
        timings.metrics = metrics_timings;
        let order = placement_rank(scene);
        let anchor = scene.anchor.as_deref();
        let mut failures = Vec::new();

        for pair in &metrics.colliding_pairs {
            // Blame the object placed later (a child before its parent, never the anchor
            // before anything else); both are listed.
            let (first, second) = if rank(&order, &pair.a, anchor) >= rank(&order, &pair.b, anchor)
            {
                (&pair.a, &pair.b)
            } else {
                (&pair.b, &pair.a)
            };
            failures.push(Failure {
                kind: FailureKind::Collision,
                objects: vec![first.clone(), second.clone()],
                detail: format!(
                    "`{}` and `{}` interpenetrate by {:.1} mm",
                    pair.a,
                    pair.b,
                    pair.depth * 1000.0
                ),
            });
        }
        for p in &metrics.arch_penetrations {
            failures.push(Failure {
                kind: FailureKind::ArchitectureCollision,
                objects: vec![p.object.clone()],
                detail: format!(
                    "`{}` penetrates `{}` by {:.1} mm",
                    p.object,
                    p.architecture,
                    p.depth * 1000.0
                ),
            });
        }
        for u in &metrics.unstable {
            failures.push(Failure {
                kind: FailureKind::Unstable,
                objects: vec![u.id.clone()],
                detail: if u.non_finite {
                    format!("`{}` became non-finite in the simulation", u.id)
                } else {
                    format!(
                        "`{}` moved {:.1} cm and turned {:.3} rad in 2 s of simulation",
                        u.id,
                        u.displacement * 100.0,
                        u.rotation
                    )
                },
            });
        }
        let relations_checked = timed(&mut timings.relations, || {
            let checked = plan_relation_failures(input.plan, scene, &mut failures);
            failures.extend(prompt_failures(input.plan, scene));
            failures.extend(anchor_failure(input.plan, scene));
            checked
        });
        if !metrics.unreachable_floor_objects.is_empty() {
            failures.push(Failure {
                kind: FailureKind::Unreachable,
                objects: metrics.unreachable_floor_objects.clone(),
                detail: format!(
                    "no walkway reaches {}",
                    metrics
                        .unreachable_floor_objects
                        .iter()
                        .map(|id| format!("`{id}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            });
        }
        if metrics.walk < self.min_walk {
            failures.push(Failure {
                kind: FailureKind::Walk,
                objects: walk_blockers(scene),
                detail: format!(
                    "Walk is {:.3}, below the required {:.2}",
                    metrics.walk, self.min_walk
                ),
            });
        }
        failures.extend(opening_failures(&metrics, &order, anchor));
        failures.extend(window_failures(scene));
        failures.extend(keep_clear_failures(input.plan, scene));
        let arrangement = timed(&mut timings.arrangement, || check_arrangement(scene));
        failures.extend(arrangement_failures(&arrangement));
        Ok(Verdict {
            accepted: failures.is_empty(),
            failures,
            metrics,
            relations_checked,
            arrangement: Some(arrangement),
            review: None,
            timings: Some(timings),
        })
    }
}

/// One failure per floor object that covers a window: its top above the window's cover
/// height, standing in the clearance in front of it.
fn window_failures(scene: &Scene) -> Vec<Failure> {
    let arch = &scene.architecture;
    scene
        .objects
        .iter()
        .filter(|o| o.parent == ParentRef::Ground)
        .filter_map(|o| {
            let bounds = o.world_aabb();
            let window = arch.window_covered_by(&bounds)?;
            Some(Failure {
                kind: FailureKind::WindowCovered,
                objects: vec![o.id.clone()],
                detail: format!(
                    "`{}` ({:.2} m tall) stands in front of window `{}` and covers it above \
                     {:.2} m (its sill is {:.2} m up)",
                    o.id,
                    bounds.max.y,
                    window.id,
                    window.cover_height(),
                    window.sill
                ),
            })
        })
        .collect()
}

/// How far (m) an object may reach into an area the plan keeps clear: the optimizer's
/// settling and the difference between an asset's mesh and the size it was laid out with.
const KEEP_CLEAR_TOLERANCE: f64 = 0.01;

/// One failure per floor or hung object whose footprint reaches into an area the plan keeps
/// wholly clear (a house door's swing and approach), and per hung object reaching above the
/// height limit of one it hangs in (a window's cover height; floor objects before a window
/// are [`window_failures`]'). Objects resting on others move with them and are not checked.
fn keep_clear_failures(plan: &Plan, scene: &Scene) -> Vec<Failure> {
    let mut failures = Vec::new();
    for o in &scene.objects {
        let hung = matches!(o.parent, ParentRef::Wall(_));
        if !hung && o.parent != ParentRef::Ground {
            continue;
        }
        let top = o.world_aabb().max.y;
        let corners = footprint_corners(o);
        let zone = plan.keep_clear.iter().find(|k| {
            let limited = k
                .below
                .is_some_and(|h| hung && top > h + KEEP_CLEAR_TOLERANCE);
            (k.below.is_none() || limited) && reaches_into(&corners, k.min, k.max)
        });
        if let Some(zone) = zone {
            failures.push(Failure {
                kind: FailureKind::KeepClear,
                objects: vec![o.id.clone()],
                detail: format!(
                    "`{}` {} in the area kept clear for {}",
                    o.id,
                    if hung { "hangs" } else { "stands" },
                    zone.why
                ),
            });
        }
    }
    failures
}

/// The floor corners (x, z) of an object's box, turned with its yaw.
fn footprint_corners(o: &scenethesis_scene_graph::SceneObject) -> [[f64; 2]; 4] {
    let (b, pose) = (&o.local_bounds, &o.pose);
    let (s, c) = pose.yaw.sin_cos();
    let t = pose.translation;
    let at = |x: f64, z: f64| {
        let (x, z) = (x * pose.scale, z * pose.scale);
        [t.x + c * x + s * z, t.z - s * x + c * z]
    };
    [
        at(b.min.x, b.min.z),
        at(b.max.x, b.min.z),
        at(b.max.x, b.max.z),
        at(b.min.x, b.max.z),
    ]
}

/// Whether the rectangle with `corners` overlaps the axis-aligned `min`–`max` shrunk by
/// [`KEEP_CLEAR_TOLERANCE`] (separating axes: the two world axes and the rectangle's sides).
fn reaches_into(corners: &[[f64; 2]; 4], min: [f64; 2], max: [f64; 2]) -> bool {
    let (lo, hi) = (
        [min[0] + KEEP_CLEAR_TOLERANCE, min[1] + KEEP_CLEAR_TOLERANCE],
        [max[0] - KEEP_CLEAR_TOLERANCE, max[1] - KEEP_CLEAR_TOLERANCE],
    );
    if lo[0] >= hi[0] || lo[1] >= hi[1] {
        return false;
    }
    let zone = [lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]];
    let side = |k: usize| {
        let (a, b) = (corners[k], corners[(k + 1) % 4]);
        [b[0] - a[0], b[1] - a[1]]
    };
    let axes = [[1.0, 0.0], [0.0, 1.0], side(0), side(1)];
    axes.iter().all(|axis| {
        let project = |p: &[f64; 2]| p[0] * axis[0] + p[1] * axis[1];
        let span = |ps: &[[f64; 2]; 4]| {
            ps.iter()
                .map(project)
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                    (a.min(v), b.max(v))
                })
        };
        let ((a0, a1), (b0, b1)) = (span(corners), span(&zone));
        a1 > b0 && b1 > a0
    })
}

/// Checks every relation of the plan (each object's support first) between objects present in
/// the scene, adding a failure per relation that does not hold; returns how many were checked.
fn plan_relation_failures(plan: &Plan, scene: &Scene, failures: &mut Vec<Failure>) -> usize {
    let mut relations_checked = 0;
    for planned in &plan.objects {
        if scene.object(&planned.id).is_none() {
            continue;
        }
        // The plan's support, or for an object the layout hung on a wall, the scene's:
        // mounted on that wall (back on it, off the floor).
        let support = match scene.object(&planned.id) {
            Some(o) if o.fixed_to_world() => Relation::new(o.support, o.parent.as_str()),
            _ => Relation::new(planned.support, planned.parent.as_str()),
        };
        for relation in std::iter::once(&support).chain(&planned.relations) {
            match relation_holds(scene, &planned.id, relation) {
                Some(true) => relations_checked += 1,
                Some(false) => {
                    relations_checked += 1;
                    failures.push(Failure {
                        kind: FailureKind::Relation,
                        objects: vec![planned.id.clone()],
                        detail: format!(
                            "`{}` {} `{}` does not hold",
                            planned.id, relation.kind, relation.target
                        ),
                    });
                }
                // The target is not in the scene (dropped earlier): nothing to check.
                None => {}
            }
        }
    }
    relations_checked
}

/// One failure per door, drawer or lid that cannot open far enough. The object in the way is
/// blamed first when it was placed after the one that opens (moving it frees the opening);
/// otherwise the opening object is, and a wall or the floor blames only it.
fn opening_failures(
    metrics: &scenethesis_eval::SceneMetrics,
    order: &BTreeMap<String, usize>,
    anchor: Option<&str>,
) -> Vec<Failure> {
    metrics
        .blocked_openings()
        .map(|o| {
            let blocker = o.blocked_by.as_deref().filter(|b| order.contains_key(*b));
            let objects = match blocker {
                Some(b) if rank(order, b, anchor) >= rank(order, &o.object, anchor) => {
                    vec![b.to_owned(), o.object.clone()]
                }
                Some(b) => vec![o.object.clone(), b.to_owned()],
                None => vec![o.object.clone()],
            };
            Failure {
                kind: FailureKind::OpeningClearance,
                objects,
                detail: format!(
                    "`{}` joint `{}` opens only {:.0} % of its range: `{}` is in the way",
                    o.object,
                    o.joint,
                    o.free_share * 100.0,
                    o.blocked_by.as_deref().unwrap_or("?")
                ),
            }
        })
        .collect()
}

/// One failure per broken arrangement rule instance the judge rejects for, blaming its subject and naming the rule.
fn arrangement_failures(check: &ArrangementCheck) -> Vec<Failure> {
    check
        .broken
        .iter()
        .filter(|b| b.rejects)
        .map(|b| Failure {
            kind: FailureKind::Arrangement,
            objects: vec![b.subject.clone()],
            detail: format!("rule \"{}\": `{}` {}", b.rule, b.subject, b.reason),
        })
        .collect()
}

/// A failure when the plan's anchor — the object its room type is built around, a bedroom's
/// bed, a living room's sofa (`anchor` in `knowledge/archetypes.toml`), or what stands for it
/// ([`core_categories`]: a kitchen's runs) — is not in the scene (the guide found it no spot
/// in a house room's fixed walls): the room is re-planned with other asset variants and
/// another layout rather than accepted without its core. The anchor is blamed: the re-plan
/// gives it another asset variant (a lower or narrower bed may fit where this one did not)
/// and never drops it.
fn anchor_failure(plan: &Plan, scene: &Scene) -> Option<Failure> {
    let anchor = plan.object(&plan.anchor)?;
    let core = core_categories(&anchor.category);
    if scene.objects.iter().any(|o| core.contains(&o.category)) {
        return None;
    }
    Some(Failure {
        kind: FailureKind::MissingObject,
        objects: vec![anchor.id.clone()],
        detail: format!(
            "the room's anchor `{}` ({}) is not in the scene: it found no spot",
            anchor.id, anchor.category
        ),
    })
}

/// What the prompt asked for and the scene lacks: requested objects missing from the scene
/// (the plan lists their ids even after a re-plan dropped them) and stated relations of
/// present objects that do not hold.
fn prompt_failures(plan: &Plan, scene: &Scene) -> Vec<Failure> {
    let check = check_prompt(plan, scene);
    let mut failures: Vec<Failure> = check
        .missing
        .iter()
        .map(|m| Failure {
            kind: FailureKind::MissingObject,
            objects: m.missing_ids.clone(),
            detail: format!(
                "the prompt asks for {} \"{}\" (`{}`); {} in the scene",
                m.requested, m.words, m.category, m.present
            ),
        })
        .collect();
    failures.extend(
        check
            .broken
            .iter()
            .filter(|b| scene.object(&b.subject).is_some())
            .map(|b| Failure {
                kind: FailureKind::Relation,
                objects: vec![b.subject.clone()],
                detail: format!(
                    "stated \"{}\": `{}` {} `{}` {}",
                    b.phrase, b.subject, b.kind, b.target, b.reason
                ),
            }),
    );
    failures
}

/// Position of every object in the breadth-first placement order (stored order if the graph
/// cannot be ordered).
fn placement_rank(scene: &Scene) -> BTreeMap<String, usize> {
    match scene.bfs_order() {
        Ok(order) => order
            .iter()
            .enumerate()
            .map(|(i, o)| (o.id.clone(), i))
            .collect(),
        Err(_) => scene
            .objects
            .iter()
            .enumerate()
            .map(|(i, o)| (o.id.clone(), i))
            .collect(),
    }
}

fn rank(order: &BTreeMap<String, usize>, id: &str, anchor: Option<&str>) -> usize {
    if Some(id) == anchor {
        return 0;
    }
    order.get(id).copied().unwrap_or(usize::MAX) + 1
}

/// Floor objects that split the walkway, most likely first: free-standing (not against a wall)
/// and not the anchor, largest footprint first.
fn walk_blockers(scene: &Scene) -> Vec<String> {
    let mut candidates: Vec<(f64, &str)> = scene
        .objects
        .iter()
        .filter(|o| o.parent == ParentRef::Ground && Some(o.id.as_str()) != scene.anchor.as_deref())
        .filter(|o| o.support != scenethesis_scene_graph::RelationKind::AgainstWall)
        .map(|o| {
            let b = o.world_aabb();
            let size = b.size();
            (size.x * size.z, o.id.as_str())
        })
        .collect();
    candidates.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(b.1)));
    candidates
        .into_iter()
        .take(1)
        .map(|(_, id)| id.to_owned())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use scenethesis_scene_graph::nalgebra::Point3;
    use scenethesis_scene_graph::{Aabb, Architecture, SceneObject, WindowOpening};

    fn standing(id: &str, x: f64, z: f64, top: f64) -> SceneObject {
        let bounds = Aabb::new(Point3::new(-0.4, 0.0, -0.25), Point3::new(0.4, top, 0.25));
        SceneObject::standing_box(id, bounds, x, z)
    }

    /// A piece in a door's kept-clear approach fails, blamed on it; one beside the area, one
    /// resting on another and one turned so that only its bounding box would reach in do not.
    #[test]
    fn a_piece_in_a_doors_approach_fails_and_one_beside_it_does_not() {
        use scenethesis_agents::Planner as _;
        let mut scene = Scene::new(Architecture::rectangular_room(5.0, 4.0, 2.6, 0.9));
        let mut turned = standing("turned", 0.95, 0.7, 0.8);
        turned.pose.yaw = std::f64::consts::FRAC_PI_4;
        let mut child = standing("child", 0.0, 1.6, 0.3);
        child.parent = ParentRef::Object("hamper".into());
        scene.objects = vec![
            standing("hamper", 0.2, 1.7, 0.6),
            standing("beside", 2.0, 1.7, 0.6),
            child,
            turned,
        ];
        let mut plan = scenethesis_agents::KnowledgePlanner::new()
            .plan(&scenethesis_agents::PlanRequest::new(
                "a bedroom",
                ["bed"],
                0,
            ))
            .unwrap();
        plan.keep_clear.push(scenethesis_agents::KeepClear {
            why: "door_1 swing and approach".into(),
            min: [-0.55, 1.1],
            max: [0.55, 2.0],
            below: None,
            entrance: false,
        });
        let failures = keep_clear_failures(&plan, &scene);
        assert_eq!(failures.len(), 1, "{failures:?}");
        assert_eq!(failures[0].kind, FailureKind::KeepClear);
        assert_eq!(failures[0].objects, ["hamper"]);
        assert!(
            failures[0].detail.contains("door_1"),
            "{}",
            failures[0].detail
        );
    }

    #[test]
    fn a_wardrobe_in_front_of_a_window_fails_and_a_low_chest_does_not() {
        let mut scene = Scene::new(Architecture::rectangular_room(5.0, 4.0, 2.6, 0.9));
        scene.architecture.windows.push(WindowOpening {
            id: "window_0".into(),
            wall: "wall_0".into(),
            offset: 2.55,
            width: 1.2,
            height: 1.2,
            sill: 0.9,
            room: None,
        });
        scene.objects = vec![
            standing("wardrobe", 0.0, -1.7, 2.0),
            standing("chest", 0.2, -1.7, 0.8),
            standing("bookcase", 2.0, -1.7, 2.0),
        ];
        let failures = window_failures(&scene);
        assert_eq!(failures.len(), 1, "{failures:?}");
        assert_eq!(failures[0].kind, FailureKind::WindowCovered);
        assert_eq!(failures[0].objects, ["wardrobe"]);
        assert!(
            failures[0].detail.contains("window `window_0`"),
            "{}",
            failures[0].detail
        );
    }
}
