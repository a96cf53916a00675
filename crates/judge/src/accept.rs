//! A judge that accepts every scene it can measure.

use scenethesis_eval::{evaluate_timed_with, DecompositionCache};

use crate::judge::{Judge, JudgeError, JudgeInput, JudgeTimings, Verdict};

/// Accepts every scene, so the pipeline never re-plans. The verdict still carries the scene's
/// metrics (as `scenethesis-eval` measures them) so `report.json` stays informative; it checks
/// no relation and lists no failure. Judging fails only when an object has no mesh.
#[derive(Debug, Clone, Default)]
pub struct AcceptAll {
    cache: DecompositionCache,
}

impl AcceptAll {
    /// A judge that accepts everything.
    pub fn new() -> Self {
        Self::default()
    }
}

impl Judge for AcceptAll {
    fn name(&self) -> &str {
        "accept-all"
    }

    fn judge(&self, input: &JudgeInput<'_>) -> Result<Verdict, JudgeError> {
        let mut meshes = 0.0;
        let scene = crate::judge::timed(&mut meshes, || input.eval_scene())?;
        let (metrics, timings) = evaluate_timed_with(&scene, &self.cache, &input.simulation());
        Ok(Verdict {
            accepted: true,
            failures: Vec::new(),
            metrics,
            relations_checked: 0,
            arrangement: None,
            review: None,
            timings: Some(JudgeTimings {
                meshes,
                metrics: timings,
                ..JudgeTimings::default()
            }),
        })
    }
}
