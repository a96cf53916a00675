//! The pipeline: plan → retrieve → guide → optimize → judge (→ re-plan) → render.

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::{Duration, Instant};

use scenethesis_agents::{Guide, KnowledgePlanner, Plan, PlanRequest, Planner, ProceduralGuide};
use scenethesis_correspondence::{GuidedSettings, Matcher};
use scenethesis_physics_opt::{
    OptimizeSettings, Optimizer, Placement, PrepareSettings, ProjectedGaussNewton,
};
use scenethesis_render_api::SceneRenderer;
use scenethesis_retrieval::{AssetSource, RetrievalSource};
use scenethesis_scene_graph::{Mesh, OpenState, Scene};
use serde::{Deserialize, Serialize};

use crate::house::RoomShell;
use crate::judge::{GeometricJudge, Judge};
use crate::phases::beside::PreviewsBeside;
use crate::phases::clock::StageClock;
use crate::phases::correspond::{correspond, Aligned, AlignmentMemo};
use crate::phases::judge::{judge, verdict_note, Attempt};
use crate::phases::layout::lay_out;
use crate::phases::optimize::optimize;
use crate::phases::previews::previews;
use crate::phases::retrieve::AssetCache;
use crate::phases::rework::{rework, unmendable};
use crate::phases::summary::{report, RunRecord};
use crate::report::{Replan, Report};
use crate::stage::{Progress, Stage};
use crate::PipelineError;

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
    /// Wall-clock budget of the whole run ([`DEFAULT_TIME_LIMIT`] by default; `None` for
    /// none). It is checked before every stage: once it is spent, a run that already has a
    /// scene stops re-planning and keeps its best attempt (without previews if their turn had
    /// not come), saying so in the report's notes; a run without one fails with
    /// [`PipelineError::OutOfTime`]. Not part of [`GenerateOptions::digest`]: a limit that is
    /// not reached changes nothing.
    #[serde(skip)]
    pub time_limit: Option<Duration>,
    /// The state the scene's doors, drawers and lids are left in (closed by default); random
    /// states follow from the seed.
    #[serde(default, skip_serializing_if = "OpenState::is_closed")]
    pub open_state: OpenState,
}

/// The default [`GenerateOptions::time_limit`]: ten minutes, several hundred times what an
/// offline run takes and twice the LLM client's own budget per request.
pub const DEFAULT_TIME_LIMIT: Duration = Duration::from_secs(600);

/// The longest [`GenerateOptions::time_limit`] accepted from a user: a week.
pub const MAX_TIME_LIMIT: Duration = Duration::from_secs(7 * 24 * 3600);

/// A time limit given in seconds, as the CLI's `--time-limit` and Python's `time_limit=` take
/// it: `0` for none, else finite and at most [`MAX_TIME_LIMIT`].
///
/// ```
/// use scenethesis_pipeline::time_limit_from_secs;
/// assert_eq!(time_limit_from_secs(0.0), Ok(None));
/// assert_eq!(time_limit_from_secs(1.5), Ok(Some(std::time::Duration::from_millis(1500))));
/// assert!(time_limit_from_secs(f64::NAN).is_err());
/// ```
pub fn time_limit_from_secs(seconds: f64) -> Result<Option<Duration>, String> {
    let max = MAX_TIME_LIMIT.as_secs_f64();
    if !(seconds.is_finite() && (0.0..=max).contains(&seconds)) {
        return Err(format!(
            "expected seconds from 0 (no limit) to {max} (a week), found {seconds}"
        ));
    }
    Ok((seconds > 0.0).then(|| Duration::from_secs_f64(seconds)))
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
            time_limit: Some(DEFAULT_TIME_LIMIT),
            open_state: OpenState::Closed,
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
    /// What the guide of the chosen attempt saw — camera, guidance image, depth and masks —
    /// when it read an image (the vision guide); `None` for the procedural guide. A VLM judge
    /// can compare the scene with this image.
    pub guidance: Option<scenethesis_imagery::Guidance>,
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
    renderer: Option<Arc<dyn SceneRenderer>>,
    matcher: Option<(Box<dyn Matcher>, GuidedSettings)>,
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
            .field("matcher", &self.matcher.as_ref().map(|(m, _)| m.name()))
            .finish_non_exhaustive()
    }
}

impl Default for Pipeline {
    fn default() -> Self {
        Self::offline()
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
            matcher: None,
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

    /// Sets the matcher of the correspond stage (e.g. `scenethesis_correspondence::ShapeMatcher`) and its settings: when
    /// the guide hands over guidance with metric depth, every object is aligned to it before
    /// optimization. Without a matcher (the default), or when the guidance has no depth, the
    /// stage does not run.
    pub fn with_matcher(
        mut self,
        matcher: impl Matcher + 'static,
        settings: GuidedSettings,
    ) -> Self {
        self.matcher = Some((Box::new(matcher), settings));
        self
    }

    /// Sets the renderer of the previews ([`scenethesis_render_api::render_previews`]), e.g.
    /// `scenethesis_render::Renderer`.
    pub fn with_renderer(mut self, renderer: impl SceneRenderer + 'static) -> Self {
        self.renderer = Some(Arc::new(renderer));
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

    /// The preview renderer, if one is configured.
    pub(crate) fn renderer(&self) -> Option<&dyn SceneRenderer> {
        self.renderer.as_deref()
    }

    /// Generates a scene for `prompt` with `seed`: plans, retrieves assets, lays out, optimizes
    /// and judges; while the judge rejects the scene and re-plans remain, moves the objects at
    /// fault (new asset variants and a new layout seed) and then drops them (those the prompt
    /// asked for last), keeping the best attempt. Deterministic for the same prompt, seed,
    /// options and providers.
    ///
    /// The report's `providers` lists what the run used of each model, counted on the calling
    /// thread ([`scenethesis_models::metered`]), so parallel runs sharing providers each report
    /// their own use.
    pub fn generate(
        &self,
        prompt: &str,
        seed: u64,
        options: &GenerateOptions,
        progress: &mut dyn Progress,
    ) -> Result<GeneratedScene, PipelineError> {
        let (generated, used) =
            scenethesis_models::metered(|| self.run(prompt, seed, options, progress));
        let mut generated = generated?;
        generated.report.providers = used;
        Ok(generated)
    }

    /// [`Pipeline::generate`] without the usage accounting: a house when the prompt names a
    /// dwelling or several rooms, else one room.
    fn run(
        &self,
        prompt: &str,
        seed: u64,
        options: &GenerateOptions,
        progress: &mut dyn Progress,
    ) -> Result<GeneratedScene, PipelineError> {
        // A fixed plan (`generate --plan`) is one room whatever its prompt says.
        let reads_prompt = self.planner.name() != "fixed";
        match crate::house::program_of(prompt).filter(|_| reads_prompt) {
            Some(program) => self.run_house(prompt, seed, options, progress, &program),
            None => self.run_room(prompt, seed, options, progress, None),
        }
    }

    /// One room: planned, then laid out, optimized and judged until accepted or out of
    /// re-plans. With a `shell` (a house's room), the plan takes the shell's size and keeps
    /// its doors' and windows' floor clear, and every attempt is judged inside the shell.
    pub(crate) fn run_room(
        &self,
        prompt: &str,
        seed: u64,
        options: &GenerateOptions,
        progress: &mut dyn Progress,
        shell: Option<&RoomShell>,
    ) -> Result<GeneratedScene, PipelineError> {
        let started = Instant::now();
        let mut clock = StageClock::new(progress, options.time_limit);
        clock.check(Stage::Plan, 0)?;
        let mut original_plan = clock.run(
            Stage::Plan,
            0,
            || self.plan(prompt, seed),
            |plan| format!("{} ({} objects)", plan.scene_type, plan.objects.len()),
        )?;
        if let Some(shell) = shell {
            shell.fit_plan(&mut original_plan);
        }

        // The image leads: what the guide's image shows beyond the plan joins it before any
        // asset is retrieved (nothing for guides that read no image).
        // Timed with the guide stage but not announced: most guides adopt nothing.
        let adoption =
            clock.run_quietly(Stage::Guide, || self.guide.adopt(&original_plan, seed))?;
        let mut plan = adoption.apply(&original_plan);
        let mut cache = AssetCache::default();
        let mut alignments = AlignmentMemo::default();
        clock.run_quietly(Stage::Retrieve, || {
            cache.fit_variants(self.assets.as_ref(), &plan, seed, &adoption.sizes)
        })?;
        let mut replans: Vec<Replan> = Vec::new();
        let mut best: Option<Attempt> = None;
        let mut stopped: Option<String> = None;
        let mut unmended: Option<String> = None;
        for round in 0..=options.max_replans {
            let attempt = match self.attempt(
                &plan,
                (&mut cache, &mut alignments),
                &mut clock,
                prompt,
                seed,
                round,
                options,
                shell,
            ) {
                Ok(attempt) => attempt,
                Err(PipelineError::OutOfTime {
                    stage,
                    limit_seconds,
                    ..
                }) if best.is_some() => {
                    stopped = Some(format!(
                        "the time limit of {limit_seconds} s was reached before the {stage} \
                             stage of re-plan round {round}"
                    ));
                    break;
                }
                Err(e) => return Err(e),
            };
            let accepted = attempt.verdict.accepted;
            unmended = (!accepted).then(|| unmendable(&attempt)).flatten();
            if !accepted && round < options.max_replans && unmended.is_none() {
                replans.push(rework(
                    &mut plan,
                    &mut cache,
                    &attempt,
                    seed,
                    options.max_replans,
                ));
            }
            if best.as_ref().is_none_or(|b| attempt.better_than(b)) {
                best = Some(attempt);
            }
            if accepted || unmended.is_some() {
                break;
            }
        }

        let mut best = best.expect("at least one attempt ran");
        let mut notes = adoption.notes.clone();
        if let Some(why) = stopped {
            notes.push(time_limit_note(&why, best.round));
        }
        notes.extend(unmended);
        let (previews, preview_notes) = match clock.check(Stage::Render, best.round) {
            Ok(()) => previews(self.renderer.as_deref(), &mut best, options, &mut clock),
            // The error's own text says no scene was finished, which is not so here.
            Err(PipelineError::OutOfTime { limit_seconds, .. })
                if options.previews && self.renderer.is_some() =>
            {
                let note = format!(
                    "no previews: the time limit of {limit_seconds} s was spent before the render \
                     stage"
                );
                (Vec::new(), vec![note])
            }
            Err(e @ PipelineError::Stopped { .. }) => return Err(e),
            Err(_) => (Vec::new(), Vec::new()),
        };
        notes.extend(preview_notes);
        let report = report(
            &best,
            RunRecord {
                prompt,
                seed,
                options_digest: options.digest(self.assets.name()),
                planner: self.planner.name(),
                guide: self.guide.name(),
                judge: self.judge.name(),
                matcher: self.matcher.as_ref().map(|(m, _)| m.name()),
                asset_source: self.assets.name(),
                original_plan: &original_plan,
                adoption: &adoption,
                replans,
                notes,
                timings: clock.timings(),
                total_seconds: started.elapsed().as_secs_f64(),
            },
        );
        Ok(GeneratedScene {
            scene: best.scene,
            meshes: best.meshes,
            plan: best.plan,
            previews,
            report,
            guidance: best.guidance,
        })
    }

    /// One round: retrieve, lay out, optimize and judge `plan`, with the assets and the
    /// alignments kept from earlier rounds.
    #[allow(clippy::too_many_arguments)]
    fn attempt(
        &self,
        plan: &Plan,
        (cache, alignments): (&mut AssetCache, &mut AlignmentMemo),
        clock: &mut StageClock<'_>,
        prompt: &str,
        seed: u64,
        round: usize,
        options: &GenerateOptions,
        shell: Option<&RoomShell>,
    ) -> Result<Attempt, PipelineError> {
        clock.check(Stage::Retrieve, round)?;
        let retrieved = clock.run(
            Stage::Retrieve,
            round,
            || cache.retrieve(self.assets.as_ref(), plan, seed),
            |r| format!("{} assets", r.infos.len()),
        )?;
        clock.check(Stage::Guide, round)?;
        let layout = clock.run(
            Stage::Guide,
            round,
            || lay_out(self.guide.as_ref(), plan, &retrieved, prompt, seed, round),
            |l| {
                format!(
                    "{} placed, {} dropped",
                    l.scene.objects.len(),
                    l.dropped.len()
                )
            },
        )?;
        let mut scene = layout.scene;
        if let Some(shell) = shell {
            // A house room is judged in its real walls, doors and windows.
            scene.architecture = shell.architecture.clone();
        }
        // Alignment needs metric depth: without it nothing but the outline says how far away an
        // object is, and a box-shaped mask pulls objects toward the camera to fill it; the
        // guide's single-view metrology (where the mask meets the floor) places them better.
        let aligned = match (&layout.guidance, &self.matcher) {
            (Some(guidance), Some((matcher, settings))) if guidance.depth.is_some() => {
                clock.check(Stage::Correspond, round)?;
                clock.run(
                    Stage::Correspond,
                    round,
                    || {
                        correspond(
                            &mut scene,
                            guidance,
                            &retrieved,
                            cache,
                            alignments,
                            matcher.as_ref(),
                            settings,
                            options,
                        )
                    },
                    |a| {
                        format!(
                            "{} objects aligned, {} kept their lift",
                            a.alignments.len(),
                            a.kept_lift.len()
                        )
                    },
                )?
            }
            _ => Aligned::default(),
        };
        clock.check(Stage::Optimize, round)?;
        let deadline = clock.deadline();
        let (placement, meshes, prepare_seconds) = clock.run(
            Stage::Optimize,
            round,
            || {
                optimize(
                    &mut scene,
                    &aligned.alignments,
                    &retrieved,
                    cache,
                    self.optimizer.as_ref(),
                    options,
                    deadline,
                )
            },
            |(p, _, _)| {
                format!(
                    "{} objects, {} with issues{}",
                    p.objects.len(),
                    p.failures().count(),
                    if p.out_of_time { ", out of time" } else { "" }
                )
            },
        )?;
        clock.add_parts(Stage::Optimize, &[("prepare", prepare_seconds)]);
        clock.add_parts(Stage::Optimize, &placement.timings.parts());
        // What rests in a drawer rides with it; the judge sees the doors and drawers in the
        // state the scene is delivered in.
        scene.assign_parent_links(&meshes);
        crate::phases::looks::record_looks(&mut scene, plan, &meshes);
        crate::phases::looks::make_maps_beside(&scene, &meshes);
        options.open_state.apply(&mut scene, seed);
        clock.check(Stage::Judge, round)?;
        // Most attempts are accepted: their previews are drawn on the core the judge's
        // simulation leaves idle, and kept if this attempt is the one delivered.
        let previews_beside = match &self.renderer {
            Some(renderer) if options.previews => Some(PreviewsBeside::start(
                renderer.clone(),
                &scene,
                &meshes,
                options.preview_size,
            )),
            _ => None,
        };
        // The image leads: what it shows an object resting on is what the scene is held to,
        // unless the prompt said otherwise.
        let judged_plan = match &layout.guidance {
            Some(_) => Cow::Owned(plan.with_supports_of(&scene)),
            None => Cow::Borrowed(plan),
        };
        let verdict = clock.run(
            Stage::Judge,
            round,
            || {
                judge(
                    self.judge.as_ref(),
                    &judged_plan,
                    &scene,
                    &meshes,
                    layout.guidance.as_ref(),
                    previews_beside.is_some(),
                )
            },
            verdict_note,
        )?;
        if let Some(timings) = &verdict.timings {
            clock.add_parts(Stage::Judge, &timings.parts());
        }
        Ok(Attempt {
            plan: plan.clone(),
            scene,
            meshes,
            guide_notes: optimize_notes(layout.notes, &placement),
            placement,
            verdict,
            guide_dropped: layout.dropped,
            kept_lift: aligned.kept_lift,
            guidance: layout.guidance,
            previews_beside,
            round,
        })
    }
}

/// The notes of an attempt: the guide's, and one when the optimizer ran out of time.
fn optimize_notes(mut notes: Vec<String>, placement: &Placement) -> Vec<String> {
    if placement.out_of_time {
        notes.push(
            "the optimize stage ran out of time (its own budget or the run's time limit): \
             objects it had not reached keep their starting poses, the others the poses \
             reached so far"
                .to_owned(),
        );
    }
    notes
}

/// The report note of a run that stopped re-planning at its time limit.
fn time_limit_note(why: &str, kept_round: usize) -> String {
    format!("{why}: re-planning stopped and the best scene so far (round {kept_round}) is kept")
}
