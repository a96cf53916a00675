//! The pipeline: plan → retrieve → guide → optimize → judge (→ re-plan) → render.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;
use std::time::{Duration, Instant};

use scenethesis_agents::{
    DroppedObject, Guide, KnowledgePlanner, Plan, PlanRequest, Planner, ProceduralGuide,
};
use scenethesis_assets::{Asset, AssetInfo};
use scenethesis_physics_opt::{
    optimize_scene, OptimizeSettings, Optimizer, Placement, PrepareSettings, PreparedAsset,
    ProjectedGaussNewton, SceneProblem,
};
use scenethesis_scene_graph::{Mesh, ParentRef, Scene};
use serde::{Deserialize, Serialize};

use crate::assets::{AssetSource, RetrievalSource};
use crate::judge::{GeometricJudge, Judge, JudgeInput, Verdict};
use crate::report::{ObjectIssue, Replan, ReplanAction, Report, StageTiming};
use crate::PipelineError;

/// The stages of a run, in order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Stage {
    /// Prompt → plan.
    Plan,
    /// One asset per planned object.
    Retrieve,
    /// Plan → initial layout.
    Guide,
    /// Physics-aware pose optimization.
    Optimize,
    /// Geometric checks, deciding whether to re-plan.
    Judge,
    /// Preview images.
    Render,
    /// Writing the output folder.
    Export,
}

impl Stage {
    /// Every stage, in order.
    pub const ALL: [Stage; 7] = [
        Stage::Plan,
        Stage::Retrieve,
        Stage::Guide,
        Stage::Optimize,
        Stage::Judge,
        Stage::Render,
        Stage::Export,
    ];

    /// The stage's name as in `report.json`.
    pub fn as_str(&self) -> &'static str {
        match self {
            Stage::Plan => "plan",
            Stage::Retrieve => "retrieve",
            Stage::Guide => "guide",
            Stage::Optimize => "optimize",
            Stage::Judge => "judge",
            Stage::Render => "render",
            Stage::Export => "export",
        }
    }
}

impl std::fmt::Display for Stage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Receives progress events; the CLI draws them, libraries can ignore them ([`NoProgress`]).
pub trait Progress {
    /// A stage starts; `round` is 0 for the first attempt and counts re-plans after it.
    fn stage_started(&mut self, stage: Stage, round: usize);
    /// A stage ended after `elapsed`, with a short note (e.g. "24 objects").
    fn stage_finished(&mut self, stage: Stage, round: usize, elapsed: Duration, note: &str);
}

/// Ignores progress.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoProgress;

impl Progress for NoProgress {
    fn stage_started(&mut self, _: Stage, _: usize) {}
    fn stage_finished(&mut self, _: Stage, _: usize, _: Duration, _: &str) {}
}

/// Settings of a run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GenerateOptions {
    /// How many times the judge may re-plan after the first attempt.
    pub max_replans: usize,
    /// Render preview images (when a renderer is configured).
    pub previews: bool,
    /// Preview image width and height in pixels.
    pub preview_size: [u32; 2],
    /// Optimizer settings.
    pub optimize: OptimizeSettings,
    /// Asset preparation (sampling) settings.
    pub prepare: PrepareSettings,
}

impl GenerateOptions {
    /// A stable hex digest of these options and the asset source's name: two runs with the
    /// same prompt, seed and digest produce the same scene (batch resume compares it).
    pub fn digest(&self, asset_source: &str) -> String {
        let text = serde_json::to_string(&(self, asset_source)).expect("options serialize");
        format!("{:016x}", scenethesis_scene_graph::fnv1a64(text.as_bytes()))
    }
}

impl Default for GenerateOptions {
    fn default() -> Self {
        Self {
            max_replans: 3,
            previews: true,
            preview_size: [960, 640],
            optimize: OptimizeSettings::default(),
            prepare: PrepareSettings::default(),
        }
    }
}

/// A finished scene: the scene graph, every object's mesh, the plan, previews and the report.
#[derive(Debug, Clone)]
pub struct GeneratedScene {
    /// The final scene graph (optimized poses).
    pub scene: Scene,
    /// Each object's mesh in its asset frame, by object id.
    pub meshes: BTreeMap<String, Mesh>,
    /// The plan of the accepted (or best) attempt.
    pub plan: Plan,
    /// Preview images: file name (e.g. `preview.png`) and PNG bytes.
    pub previews: Vec<(String, Vec<u8>)>,
    /// Metrics, verdict, re-plans and timings.
    pub report: Report,
}

/// A preview renderer: turns a finished scene into named PNG images.
pub trait PreviewRenderer: Send + Sync {
    /// A short name (the adapter) for reports.
    fn name(&self) -> String;
    /// Renders the previews of `scene` at `size`.
    fn render(
        &self,
        scene: &Scene,
        meshes: &BTreeMap<String, Mesh>,
        size: [u32; 2],
    ) -> Result<Vec<(String, Vec<u8>)>, String>;
}

/// The end-to-end pipeline with pluggable stages. [`Pipeline::offline`] needs no network, no
/// API key and no GPU: the knowledge planner, retrieval over the built-in procedural library,
/// the procedural guide,
/// the projected Gauss–Newton optimizer and the geometric judge.
pub struct Pipeline {
    planner: Box<dyn Planner + Send + Sync>,
    assets: Box<dyn AssetSource>,
    guide: Box<dyn Guide + Send + Sync>,
    optimizer: Box<dyn Optimizer>,
    judge: Box<dyn Judge>,
    renderer: Option<Box<dyn PreviewRenderer>>,
}

impl std::fmt::Debug for Pipeline {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Pipeline")
            .field("assets", &self.assets.name())
            .field("optimizer", &self.optimizer.name())
            .field("judge", &self.judge.name())
            .field("renderer", &self.renderer.as_ref().map(|r| r.name()))
            .finish_non_exhaustive()
    }
}

impl Default for Pipeline {
    fn default() -> Self {
        Self::offline()
    }
}

/// One attempt's outcome, kept to pick the best when nothing is accepted.
struct Attempt {
    plan: Plan,
    scene: Scene,
    meshes: BTreeMap<String, Mesh>,
    placement: Placement,
    verdict: Verdict,
    guide_dropped: Vec<DroppedObject>,
    round: usize,
}

impl Attempt {
    /// Fewer failures first, then more objects.
    fn better_than(&self, other: &Attempt) -> bool {
        let key = |a: &Attempt| {
            (
                !a.verdict.accepted,
                a.verdict.failures.len(),
                usize::MAX - a.scene.objects.len(),
            )
        };
        key(self) < key(other)
    }
}

impl Pipeline {
    /// The offline default pipeline (no renderer; add one with [`Pipeline::with_renderer`]).
    pub fn offline() -> Self {
        Self {
            planner: Box::new(KnowledgePlanner::new()),
            assets: Box::new(RetrievalSource::default()),
            guide: Box::new(ProceduralGuide::default()),
            optimizer: Box::new(ProjectedGaussNewton::default()),
            judge: Box::new(GeometricJudge::default()),
            renderer: None,
        }
    }

    /// Replaces the planner.
    pub fn with_planner(mut self, planner: impl Planner + Send + Sync + 'static) -> Self {
        self.planner = Box::new(planner);
        self
    }

    /// Replaces the asset source (retrieval).
    pub fn with_assets(mut self, assets: impl AssetSource + 'static) -> Self {
        self.assets = Box::new(assets);
        self
    }

    /// Replaces the guide.
    pub fn with_guide(mut self, guide: impl Guide + Send + Sync + 'static) -> Self {
        self.guide = Box::new(guide);
        self
    }

    /// Replaces the optimizer.
    pub fn with_optimizer(mut self, optimizer: impl Optimizer + 'static) -> Self {
        self.optimizer = Box::new(optimizer);
        self
    }

    /// Replaces the judge.
    pub fn with_judge(mut self, judge: impl Judge + 'static) -> Self {
        self.judge = Box::new(judge);
        self
    }

    /// Sets the preview renderer.
    pub fn with_renderer(mut self, renderer: impl PreviewRenderer + 'static) -> Self {
        self.renderer = Some(Box::new(renderer));
        self
    }

    /// The asset source (to regenerate meshes of a saved scene).
    pub fn assets(&self) -> &dyn AssetSource {
        self.assets.as_ref()
    }

    /// Generates a scene for `prompt` with `seed`: plans, retrieves assets, lays out, optimizes
    /// and judges; while the judge rejects the scene and re-plans remain, moves the objects at
    /// fault (new asset variants and a new layout seed) and then drops them (those the prompt
    /// asked for last), keeping the best attempt. Deterministic for the same prompt, seed,
    /// options and providers.
    pub fn generate(
        &self,
        prompt: &str,
        seed: u64,
        options: &GenerateOptions,
        progress: &mut dyn Progress,
    ) -> Result<GeneratedScene, PipelineError> {
        let started = Instant::now();
        let mut timings: BTreeMap<Stage, f64> = BTreeMap::new();
        let mut timed = |stage: Stage, since: Instant| {
            *timings.entry(stage).or_default() += since.elapsed().as_secs_f64();
        };

        progress.stage_started(Stage::Plan, 0);
        let t = Instant::now();
        let request = PlanRequest::new(prompt, self.assets.categories(), seed);
        let original_plan = self.planner.plan(&request)?;
        timed(Stage::Plan, t);
        progress.stage_finished(
            Stage::Plan,
            0,
            t.elapsed(),
            &format!(
                "{} ({} objects)",
                original_plan.scene_type,
                original_plan.objects.len()
            ),
        );

        let mut plan = original_plan.clone();
        let mut variants: BTreeMap<String, u64> = BTreeMap::new();
        let mut assets: BTreeMap<(String, u64), Asset> = BTreeMap::new();
        let mut prepared: BTreeMap<String, Arc<PreparedAsset>> = BTreeMap::new();
        let mut replans: Vec<Replan> = Vec::new();
        let mut best: Option<Attempt> = None;

        for round in 0..=options.max_replans {
            // Retrieve.
            progress.stage_started(Stage::Retrieve, round);
            let t = Instant::now();
            let mut infos: BTreeMap<String, AssetInfo> = BTreeMap::new();
            let mut chosen: BTreeMap<String, (String, u64)> = BTreeMap::new();
            for object in &plan.objects {
                let variant = variants.get(&object.id).copied().unwrap_or(0);
                let key = (object.id.clone(), variant);
                if !assets.contains_key(&key) {
                    let asset = self.assets.retrieve(object, seed.wrapping_add(variant))?;
                    assets.insert(key.clone(), asset);
                }
                infos.insert(object.id.clone(), assets[&key].info.clone());
                chosen.insert(object.id.clone(), key);
            }
            timed(Stage::Retrieve, t);
            progress.stage_finished(
                Stage::Retrieve,
                round,
                t.elapsed(),
                &format!("{} assets", infos.len()),
            );

            // Guide.
            progress.stage_started(Stage::Guide, round);
            let t = Instant::now();
            let layout_seed = seed.wrapping_add(round as u64 * 0x9e37_79b9);
            let layout = self.guide.layout(&plan, &infos, layout_seed)?;
            let mut scene = layout.scene;
            scene.prompt = prompt.to_owned();
            scene.seed = seed;
            timed(Stage::Guide, t);
            progress.stage_finished(
                Stage::Guide,
                round,
                t.elapsed(),
                &format!(
                    "{} placed, {} dropped",
                    scene.objects.len(),
                    layout.dropped.len()
                ),
            );

            // Optimize.
            progress.stage_started(Stage::Optimize, round);
            let t = Instant::now();
            let mut meshes = BTreeMap::new();
            let mut problem = SceneProblem::new(scene.clone());
            for object in &scene.objects {
                let key = chosen
                    .get(&object.id)
                    .ok_or_else(|| PipelineError::Inconsistent {
                        detail: format!(
                            "the guide returned object `{}` that the plan does not hold",
                            object.id
                        ),
                    })?;
                let asset = &assets[key];
                let asset_key = asset.info.source.to_string();
                let prep = match prepared.get(&asset_key) {
                    Some(p) => p.clone(),
                    None => {
                        let p = Arc::new(PreparedAsset::from_asset(asset, &options.prepare)?);
                        prepared.insert(asset_key, p.clone());
                        p
                    }
                };
                problem.set_asset(&object.id, prep);
                meshes.insert(object.id.clone(), asset.mesh.clone());
            }
            let placement = optimize_scene(&problem, self.optimizer.as_ref(), &options.optimize)?;
            placement.apply_to(&mut scene);
            timed(Stage::Optimize, t);
            let failing = placement.failures().count();
            progress.stage_finished(
                Stage::Optimize,
                round,
                t.elapsed(),
                &format!("{} objects, {failing} with issues", placement.objects.len()),
            );

            // Judge.
            progress.stage_started(Stage::Judge, round);
            let t = Instant::now();
            let verdict = self.judge.judge(&JudgeInput {
                plan: &plan,
                scene: &scene,
                meshes: &meshes,
            })?;
            timed(Stage::Judge, t);
            progress.stage_finished(
                Stage::Judge,
                round,
                t.elapsed(),
                &if verdict.accepted {
                    "accepted".to_owned()
                } else {
                    format!("{} failure(s)", verdict.failures.len())
                },
            );

            let attempt = Attempt {
                plan: plan.clone(),
                scene,
                meshes,
                placement,
                verdict,
                guide_dropped: layout.dropped,
                round,
            };
            let accepted = attempt.verdict.accepted;
            let offenders = attempt.verdict.offenders();
            let reasons: Vec<String> = attempt
                .verdict
                .failures
                .iter()
                .map(|f| f.detail.clone())
                .collect();
            if best.as_ref().is_none_or(|b| attempt.better_than(b)) {
                best = Some(attempt);
            }
            if accepted || round == options.max_replans {
                break;
            }

            // Re-plan: first move the offenders (new asset variants, new layout seed); from
            // the second re-plan on, drop them (never the anchor) with everything they hold.
            // Objects the prompt asked for are dropped last: while other offenders remain, or
            // until the final re-plan, they are moved again instead.
            let movable: Vec<String> = offenders
                .iter()
                .filter(|id| **id != plan.anchor)
                .cloned()
                .collect();
            let requested = |id: &String| plan.object(id).is_some_and(|o| o.hard);
            let (asked_for, optional): (Vec<String>, Vec<String>) =
                movable.iter().cloned().partition(requested);
            let last_chance = round + 1 == options.max_replans;
            let to_drop: Vec<String> = if round == 0 || movable.is_empty() {
                Vec::new()
            } else if !optional.is_empty() {
                optional
            } else if last_chance {
                asked_for
            } else {
                Vec::new()
            };
            let action = if to_drop.is_empty() {
                ReplanAction::Move
            } else {
                ReplanAction::Drop
            };
            for id in offenders.iter().filter(|id| !to_drop.contains(id)) {
                *variants.entry(id.clone()).or_default() += 1;
            }
            let objects = match action {
                ReplanAction::Move => offenders.clone(),
                ReplanAction::Drop => drop_objects(&mut plan, &to_drop).into_iter().collect(),
            };
            replans.push(Replan {
                after_round: round,
                action,
                objects,
                reasons,
                layout_seed: seed.wrapping_add((round as u64 + 1) * 0x9e37_79b9),
            });
        }

        let best = best.expect("at least one attempt ran");
        let mut previews = Vec::new();
        let mut notes = Vec::new();
        if options.previews {
            match &self.renderer {
                Some(renderer) => {
                    progress.stage_started(Stage::Render, best.round);
                    let t = Instant::now();
                    match renderer.render(&best.scene, &best.meshes, options.preview_size) {
                        Ok(images) => previews = images,
                        Err(e) => notes.push(format!("previews skipped: {e}")),
                    }
                    timed(Stage::Render, t);
                    progress.stage_finished(
                        Stage::Render,
                        best.round,
                        t.elapsed(),
                        &format!("{} image(s) with {}", previews.len(), renderer.name()),
                    );
                }
                None => notes.push("previews skipped: no renderer configured".into()),
            }
        }

        let object_issues = best
            .placement
            .failures()
            .map(|r| ObjectIssue {
                id: r.id.clone(),
                issues: r.issues.iter().map(|i| i.to_string()).collect(),
            })
            .collect();
        let present: BTreeSet<&str> = best.scene.objects.iter().map(|o| o.id.as_str()).collect();
        let missing_from_plan: Vec<String> = original_plan
            .objects
            .iter()
            .filter(|o| !present.contains(o.id.as_str()))
            .map(|o| o.id.clone())
            .collect();
        let report = Report {
            prompt: prompt.to_owned(),
            seed,
            options_digest: options.digest(self.assets.name()),
            scene_type: best.plan.scene_type.clone(),
            accepted: best.verdict.accepted,
            judge: self.judge.name().to_owned(),
            optimizer: best.placement.optimizer.clone(),
            asset_source: self.assets.name().to_owned(),
            attempts: replans.len() + 1,
            chosen_attempt: best.round,
            planned_objects: original_plan.objects.len(),
            objects: best.scene.objects.len(),
            not_in_scene: missing_from_plan,
            guide_dropped: best.guide_dropped.clone(),
            replans,
            verdict: best.verdict.clone(),
            optimizer_issues: object_issues,
            plan_notes: best.plan.notes.clone(),
            notes,
            timings: Stage::ALL
                .iter()
                .filter_map(|s| {
                    timings
                        .get(s)
                        .map(|&seconds| StageTiming { stage: *s, seconds })
                })
                .collect(),
            total_seconds: started.elapsed().as_secs_f64(),
            providers: Vec::new(),
        };
        Ok(GeneratedScene {
            scene: best.scene,
            meshes: best.meshes,
            plan: best.plan,
            previews,
            report,
        })
    }
}

/// Removes `ids` and every object resting on them (recursively) from the plan, with the
/// relations and constraints that mention them; returns what was removed.
fn drop_objects(plan: &mut Plan, ids: &[String]) -> BTreeSet<String> {
    let mut gone: BTreeSet<String> = ids.iter().cloned().collect();
    loop {
        let more: Vec<String> = plan
            .objects
            .iter()
            .filter(|o| !gone.contains(&o.id))
            .filter(|o| matches!(&o.parent, ParentRef::Object(p) if gone.contains(p)))
            .map(|o| o.id.clone())
            .collect();
        if more.is_empty() {
            break;
        }
        gone.extend(more);
    }
    plan.objects.retain(|o| !gone.contains(&o.id));
    for object in &mut plan.objects {
        object.relations.retain(|r| !gone.contains(&r.target));
    }
    plan.constraints.retain(|c| {
        !gone.contains(&c.subject)
            && !matches!(&c.target, scenethesis_agents::ConstraintTarget::Object(t) if gone.contains(t))
    });
    gone
}
