//! Judge: one attempt scored by the judge, and the rule that picks the best attempt of a run.

use std::collections::BTreeMap;

use scenethesis_agents::{DroppedObject, Plan};
use scenethesis_imagery::Guidance;
use scenethesis_physics_opt::Placement;
use scenethesis_scene_graph::{Mesh, Scene};

use crate::judge::{Judge, JudgeInput, Verdict};
use crate::PipelineError;

/// One attempt's outcome, kept to pick the best when nothing is accepted.
pub(crate) struct Attempt {
    pub(crate) plan: Plan,
    pub(crate) scene: Scene,
    pub(crate) meshes: BTreeMap<String, Mesh>,
    pub(crate) placement: Placement,
    pub(crate) verdict: Verdict,
    pub(crate) guide_dropped: Vec<DroppedObject>,
    /// The objects whose raw lift the alignment kept, with why.
    pub(crate) kept_lift: Vec<scenethesis_correspondence::KeptLift>,
    /// The guide's notes for the report.
    pub(crate) guide_notes: Vec<String>,
    /// What the guide saw (vision guides), handed on to the result.
    pub(crate) guidance: Option<scenethesis_imagery::Guidance>,
    /// This attempt's previews, drawn while the judge ran (when previews are asked for).
    pub(crate) previews_beside: Option<crate::phases::beside::PreviewsBeside>,
    pub(crate) round: usize,
}

impl Attempt {
    /// Fewer failures first, then more objects.
    pub(crate) fn better_than(&self, other: &Attempt) -> bool {
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

/// The judge's verdict on `scene` laid out from `plan` (and from `guidance`, when the guide
/// had one); `cores_shared` when previews are drawn meanwhile.
pub(crate) fn judge(
    judge: &dyn Judge,
    plan: &Plan,
    scene: &Scene,
    meshes: &BTreeMap<String, Mesh>,
    guidance: Option<&Guidance>,
    cores_shared: bool,
) -> Result<Verdict, PipelineError> {
    Ok(judge.judge(&JudgeInput {
        plan,
        scene,
        meshes,
        guidance,
        cores_shared,
    })?)
}

/// A progress note for `verdict`.
pub(crate) fn verdict_note(verdict: &Verdict) -> String {
    if verdict.accepted {
        "accepted".to_owned()
    } else {
        format!("{} failure(s)", verdict.failures.len())
    }
}
