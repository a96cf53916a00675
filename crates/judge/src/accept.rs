//! A judge that accepts every scene it can measure.

use scenethesis_eval::{evaluate_with_cache, DecompositionCache};

use crate::judge::{Judge, JudgeError, JudgeInput, Verdict};

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
        let scene = input.eval_scene()?;
        Ok(Verdict {
            accepted: true,
            failures: Vec::new(),
            metrics: evaluate_with_cache(&scene, &self.cache),
            relations_checked: 0,
            arrangement: None,
            review: None,
        })
    }
}
