//! Guide: the guide's initial layout of the plan, stamped with the prompt and the run's seed.

use scenethesis_agents::{Guide, GuidedLayout, Plan};

use super::retrieve::Retrieved;
use crate::PipelineError;

/// The layout seed of re-plan round `round` (round 0 uses the run's seed).
pub(crate) fn layout_seed(seed: u64, round: usize) -> u64 {
    seed.wrapping_add(round as u64 * 0x9e37_79b9)
}

/// Lays `plan` out with `guide` over the retrieved assets.
pub(crate) fn lay_out(
    guide: &dyn Guide,
    plan: &Plan,
    retrieved: &Retrieved,
    prompt: &str,
    seed: u64,
    round: usize,
) -> Result<GuidedLayout, PipelineError> {
    let mut layout = guide.layout(plan, &retrieved.infos, layout_seed(seed, round))?;
    layout.scene.prompt = prompt.to_owned();
    layout.scene.seed = seed;
    Ok(layout)
}
