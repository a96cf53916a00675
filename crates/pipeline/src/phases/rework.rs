//! Re-plan: the pure policy of [`crate::replan`] applied to a rejected attempt — offenders get
//! a new asset variant, or leave the plan — and recorded for the report.

use scenethesis_agents::Plan;

use super::judge::Attempt;
use super::layout::layout_seed;
use super::retrieve::AssetCache;
use crate::judge::FailureKind;
use crate::replan::{drop_objects, replan_action};
use crate::report::{Replan, ReplanAction};

/// Why no re-plan can mend the rejected `attempt`, if none can: its guide read an image, and
/// every failure is an object the prompt asks for that the guide left out because the image
/// does not show it (or too little of it). A guide that reads an image never invents what the
/// image lacks, so moving or dropping other objects cannot bring it in.
pub(crate) fn unmendable(attempt: &Attempt) -> Option<String> {
    attempt.guidance.as_ref()?;
    let failures = &attempt.verdict.failures;
    let left_out = |id: &String| attempt.guide_dropped.iter().find(|d| &d.id == id);
    let unseen = failures.iter().all(|f| {
        f.kind == FailureKind::MissingObject
            && !f.objects.is_empty()
            && f.objects.iter().all(|id| left_out(id).is_some())
    });
    if failures.is_empty() || !unseen {
        return None;
    }
    let why: Vec<String> = failures
        .iter()
        .flat_map(|f| &f.objects)
        .filter_map(left_out)
        .map(|d| format!("`{}`: {}", d.id, d.reason))
        .collect();
    Some(format!(
        "no re-plan: what the prompt asks for and the scene lacks, the image does not show \
         ({}); re-planning cannot add it (--keep-plan places such objects offline around what \
         the image fixes)",
        why.join("; ")
    ))
}

/// Changes `plan` and the asset variants after the rejected `attempt` of `round`; returns the
/// record of what was done. Objects blamed only for a broken arrangement rule (a run of kitchen
/// counters with a gap) are moved — new asset variants and a new layout seed, which draws a new
/// layout — and never dropped: dropping them would only hide the rule.
pub(crate) fn rework(
    plan: &mut Plan,
    cache: &mut AssetCache,
    attempt: &Attempt,
    seed: u64,
    max_replans: usize,
) -> Replan {
    let round = attempt.round;
    let offenders = attempt.verdict.offenders();
    let droppable: Vec<String> = offenders
        .iter()
        .filter(|id| {
            attempt
                .verdict
                .failures
                .iter()
                .any(|f| f.kind != FailureKind::Arrangement && f.objects.contains(id))
        })
        .cloned()
        .collect();
    let reasons = attempt
        .verdict
        .failures
        .iter()
        .map(|f| f.detail.clone())
        .collect();
    let (action, to_drop) = replan_action(plan, &droppable, round, max_replans);
    for id in offenders.iter().filter(|id| !to_drop.contains(id)) {
        cache.next_variant(id);
    }
    let objects = match action {
        ReplanAction::Move => offenders.clone(),
        ReplanAction::Drop => drop_objects(plan, &to_drop).into_iter().collect(),
    };
    Replan {
        after_round: round,
        action,
        objects,
        reasons,
        layout_seed: layout_seed(seed, round + 1),
    }
}
