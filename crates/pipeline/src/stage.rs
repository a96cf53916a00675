//! The stages of a run and the progress events about them.

use std::time::Duration;

use scenethesis_models::AnswerListener;
use serde::{Deserialize, Serialize};

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
    /// Matching each object's asset against the guidance image and aligning its pose (only
    /// when the guide produced guidance and a matcher is configured).
    Correspond,
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
    pub const ALL: [Stage; 8] = [
        Stage::Plan,
        Stage::Retrieve,
        Stage::Guide,
        Stage::Correspond,
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
            Stage::Correspond => "correspond",
            Stage::Optimize => "optimize",
            Stage::Judge => "judge",
            Stage::Render => "render",
            Stage::Export => "export",
        }
    }
}

impl std::fmt::Display for Stage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(self.as_str())
    }
}

/// Receives progress events; the CLI draws them, libraries can ignore them (pass `&mut ()`).
/// Every method does nothing by default.
pub trait Progress {
    /// A stage starts; `round` is 0 for the first attempt and counts re-plans after it.
    fn stage_started(&mut self, stage: Stage, round: usize) {
        let _ = (stage, round);
    }
    /// A stage ended after `elapsed`, with a short note (e.g. "24 objects").
    fn stage_finished(&mut self, stage: Stage, round: usize, elapsed: Duration, note: &str) {
        let _ = (stage, round, elapsed, note);
    }
    /// A listener of how much of a model's answer has arrived while `stage` of `round` runs
    /// (a streamed plan or review), called on the thread running the stage; `None` (the
    /// default) hears nothing.
    fn answer_listener(&mut self, stage: Stage, round: usize) -> Option<AnswerListener> {
        let _ = (stage, round);
        None
    }
    /// Whether the caller wants the run to end now (a callback that failed, an interrupt).
    /// Asked before every stage; `true` ends the run with [`PipelineError::Stopped`] and
    /// nothing is written. The default never stops.
    ///
    /// [`PipelineError::Stopped`]: crate::PipelineError::Stopped
    fn stop_requested(&mut self) -> bool {
        false
    }
}

/// The null progress: ignores every event.
impl Progress for () {}

/// Ignores progress (the same as `()`).
#[derive(Debug, Clone, Copy, Default)]
pub struct NoProgress;

impl Progress for NoProgress {}
