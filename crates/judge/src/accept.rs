//! A judge that accepts every scene it can measure.

use scenethesis_eval::{evaluate_with_cache, DecompositionCache, EvalError, EvalScene};

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
        let scene = EvalScene::from_scene(input.scene, |o| {
            input
                .meshes
                .get(&o.id)
                .cloned()
                .ok_or_else(|| EvalError::MissingMesh {
                    object: o.id.clone(),
                    reason: "the judge was given no mesh for it".into(),
                })
        })?;
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
