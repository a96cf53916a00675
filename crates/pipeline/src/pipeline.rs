//! The pipeline: plan → retrieve → guide → optimize → judge (→ re-plan) → render.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;
use std::time::Instant;

use scenethesis_agents::{
    DroppedObject, Guide, KnowledgePlanner, Plan, PlanRequest, Planner, ProceduralGuide,
};
use scenethesis_assets::{Asset, AssetInfo};
use scenethesis_physics_opt::{
    optimize_scene, OptimizeSettings, Optimizer, Placement, PrepareSettings, PreparedAsset,
    ProjectedGaussNewton, SceneProblem,
};
use scenethesis_scene_graph::{Mesh, Scene};
use serde::{Deserialize, Serialize};

use crate::judge::{GeometricJudge, Judge, JudgeInput, Verdict};
use crate::replan::{drop_objects, replan_action};
use crate::report::{ObjectIssue, Replan, ReplanAction, Report, StageTiming};
use crate::stage::{Progress, Stage};
use crate::PipelineError;
use scenethesis_retrieval::{AssetQuery, AssetSource, RetrievalSource};

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
    planner: Box<dyn Planner>,
    assets: Box<dyn AssetSource>,
    guide: Box<dyn Guide>,
    optimizer: Box<dyn Optimizer>,
    judge: Box<dyn Judge>,
    renderer: Option<Box<dyn PreviewRenderer>>,
}

impl std::fmt::Debug for Pipeline {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Pipeline")
            .field("planner", &self.planner.name())
            .field("assets", &self.assets.name())
            .field("guide", &self.guide.name())
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
    pub fn with_planner(mut self, planner: impl Planner + 'static) -> Self {
        self.planner = Box::new(planner);
        self
    }

    /// Replaces the asset source (retrieval).
    pub fn with_assets(mut self, assets: impl AssetSource + 'static) -> Self {
        self.assets = Box::new(assets);
        self
    }

    /// Replaces the guide.
    pub fn with_guide(mut self, guide: impl Guide + 'static) -> Self {
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

    /// The planner's plan for `prompt` with `seed`, over the asset source's categories: the
    /// plan [`Pipeline::generate`] starts from (what `scenethesis plan` writes).
    pub fn plan(&self, prompt: &str, seed: u64) -> Result<Plan, PipelineError> {
        let request = PlanRequest::new(prompt, self.assets.categories(), seed);
        Ok(self.planner.plan(&request)?)
    }

    /// The planner's name.
    pub fn planner_name(&self) -> &str {
        self.planner.name()
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
        let original_plan = self.plan(prompt, seed)?;
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
                    let asset = self.assets.retrieve(
                        &AssetQuery::new(&object.id, &object.category),
                        seed.wrapping_add(variant),
                    )?;
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

            let (action, to_drop) = replan_action(&plan, &offenders, round, options.max_replans);
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
            planner: self.planner.name().to_owned(),
            guide: self.guide.name().to_owned(),
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
            assumptions: original_plan.assumptions.clone(),
            limits: original_plan.limits.clone(),
            prompt_check: scenethesis_agents::check_prompt(&original_plan, &best.scene),
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
