//! The optimize stage's time budget inside a run: the run's time limit bounds the stage from
//! inside (not only between stages), and a budget that is not reached changes nothing. A
//! progress that asks to stop ends the run before its next stage.

use std::sync::Mutex;
use std::time::{Duration, Instant};

use scenethesis_agents::{AssetLookup, Guide, GuideError, GuidedLayout, Plan, ProceduralGuide};
use scenethesis_pipeline::{GenerateOptions, Pipeline, PipelineError, Progress, Stage};

const PROMPT: &str = "a small office with a desk, a chair and a bookshelf with books";

fn options(time_limit: Option<Duration>) -> GenerateOptions {
    GenerateOptions {
        max_replans: 0,
        previews: false,
        time_limit,
        ..GenerateOptions::default()
    }
}

/// The report without its wall-clock fields.
fn deterministic_report(report: &scenethesis_pipeline::Report) -> serde_json::Value {
    let mut v = serde_json::to_value(report).unwrap();
    let map = v.as_object_mut().unwrap();
    map.remove("timings");
    map.remove("total_seconds");
    v
}

#[test]
fn a_budget_not_reached_changes_nothing() {
    let bounded = Pipeline::offline()
        .generate(
            PROMPT,
            2,
            &options(Some(Duration::from_secs(3600))),
            &mut (),
        )
        .unwrap();
    let mut free = options(None);
    free.optimize.time_budget = f64::INFINITY;
    let free = Pipeline::offline()
        .generate(PROMPT, 2, &free, &mut ())
        .unwrap();
    assert_eq!(
        serde_json::to_string(&bounded.scene).unwrap(),
        serde_json::to_string(&free.scene).unwrap()
    );
    assert_eq!(
        deterministic_report(&bounded.report),
        deterministic_report(&free.report)
    );
}

/// The procedural guide, after waiting until `left` before the run's time limit runs out.
struct LateGuide {
    inner: ProceduralGuide,
    until: Instant,
}

impl Guide for LateGuide {
    fn name(&self) -> &str {
        "late"
    }

    fn layout(
        &self,
        plan: &Plan,
        assets: &dyn AssetLookup,
        seed: u64,
    ) -> Result<GuidedLayout, GuideError> {
        std::thread::sleep(self.until.saturating_duration_since(Instant::now()));
        self.inner.layout(plan, assets, seed)
    }
}

/// Keeps the optimize stage's note.
#[derive(Default)]
struct OptimizeNote(Mutex<Option<String>>);

impl Progress for OptimizeNote {
    fn stage_finished(&mut self, stage: Stage, _: usize, _: Duration, note: &str) {
        if stage == Stage::Optimize {
            *self.0.lock().unwrap() = Some(note.to_owned());
        }
    }
}

#[test]
fn the_run_time_limit_bounds_the_optimize_stage_from_inside() {
    // How long the optimize stage takes here, unbounded.
    let free = Pipeline::offline()
        .generate(PROMPT, 2, &options(None), &mut ())
        .unwrap();
    let seconds = |stage| {
        free.report
            .timings
            .iter()
            .filter(|t| t.stage == stage)
            .map(|t| t.seconds)
            .sum::<f64>()
    };
    let optimize = seconds(Stage::Optimize);
    let before = seconds(Stage::Plan) + seconds(Stage::Retrieve);
    // The guide leaves a fifth of that to the optimize stage; a limit the stages before it
    // overrun (a loaded machine) is raised and the run repeated.
    let left = Duration::from_secs_f64(optimize / 5.0);
    let mut limit = Duration::from_secs_f64(2.0 * before + 1.0);
    for _ in 0..4 {
        let started = Instant::now();
        let guide = LateGuide {
            inner: ProceduralGuide::default(),
            until: started + limit - left,
        };
        let mut progress = OptimizeNote::default();
        let result = Pipeline::offline().with_guide(guide).generate(
            PROMPT,
            2,
            &options(Some(limit)),
            &mut progress,
        );
        let note = progress.0.lock().unwrap().clone();
        let Some(note) = note else {
            limit *= 2; // out of time before the optimize stage
            continue;
        };
        assert!(
            note.contains("out of time"),
            "{note} ({optimize} s unbounded)"
        );
        // Nothing is left for the judge: the run fails naming it, as runs without a scene do.
        let Err(err) = result else {
            panic!("the limit is spent after the optimize stage")
        };
        assert!(
            matches!(
                err,
                PipelineError::OutOfTime {
                    stage: Stage::Judge,
                    ..
                }
            ),
            "{err}"
        );
        return;
    }
    panic!("the stages before the optimizer overran every limit tried");
}

/// Asks the run to stop once the plan stage has started (as a failed callback does).
#[derive(Default)]
struct StopAfterPlan {
    started: Vec<Stage>,
}

impl Progress for StopAfterPlan {
    fn stage_started(&mut self, stage: Stage, _: usize) {
        self.started.push(stage);
    }

    fn stop_requested(&mut self) -> bool {
        self.started.contains(&Stage::Plan)
    }
}

#[test]
fn a_progress_that_asks_to_stop_ends_the_run_before_the_next_stage() {
    let mut progress = StopAfterPlan::default();
    let err = Pipeline::offline()
        .generate(PROMPT, 0, &options(None), &mut progress)
        .unwrap_err();
    assert!(
        matches!(
            err,
            PipelineError::Stopped {
                stage: Stage::Retrieve,
                round: 0
            }
        ),
        "{err}"
    );
    assert_eq!(progress.started, vec![Stage::Plan]);
    assert_eq!(
        err.to_string(),
        "stopped by the caller before the retrieve stage"
    );
}
