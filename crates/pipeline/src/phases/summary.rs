//! Report: what the run did, written once the best attempt is chosen.

use std::collections::BTreeSet;

use scenethesis_agents::{Adoption, Plan};

use super::judge::Attempt;
use crate::report::{ObjectIssue, Replan, Report, StageTiming};

/// What a run knows beyond its best attempt when it writes the report.
pub(crate) struct RunRecord<'a> {
    pub(crate) prompt: &'a str,
    pub(crate) seed: u64,
    pub(crate) options_digest: String,
    pub(crate) planner: &'a str,
    pub(crate) guide: &'a str,
    pub(crate) judge: &'a str,
    pub(crate) matcher: Option<&'a str>,
    pub(crate) asset_source: &'a str,
    pub(crate) original_plan: &'a Plan,
    pub(crate) adoption: &'a Adoption,
    pub(crate) replans: Vec<Replan>,
    pub(crate) notes: Vec<String>,
    pub(crate) timings: Vec<StageTiming>,
    pub(crate) total_seconds: f64,
}

/// The report of a run whose chosen attempt is `best`.
pub(crate) fn report(best: &Attempt, run: RunRecord<'_>) -> Report {
    let optimizer_issues = best
        .placement
        .failures()
        .map(|r| ObjectIssue {
            id: r.id.clone(),
            issues: r.issues.iter().map(|i| i.to_string()).collect(),
        })
        .collect();
    let present: BTreeSet<&str> = best.scene.objects.iter().map(|o| o.id.as_str()).collect();
    let not_in_scene = run
        .original_plan
        .objects
        .iter()
        .chain(&run.adoption.objects)
        .filter(|o| !present.contains(o.id.as_str()))
        .map(|o| o.id.clone())
        .collect();
    Report {
        prompt: run.prompt.to_owned(),
        seed: run.seed,
        options_digest: run.options_digest,
        scene_type: best.plan.scene_type.clone(),
        accepted: best.verdict.accepted,
        planner: run.planner.to_owned(),
        guide: run.guide.to_owned(),
        judge: run.judge.to_owned(),
        optimizer: best.placement.optimizer.clone(),
        matcher: run.matcher.map(str::to_owned),
        asset_source: run.asset_source.to_owned(),
        attempts: run.replans.len() + 1,
        chosen_attempt: best.round,
        planned_objects: run.original_plan.objects.len(),
        objects: best.scene.objects.len(),
        not_in_scene,
        guide_dropped: best.guide_dropped.clone(),
        guide_adopted: run.adoption.objects.iter().map(|o| o.id.clone()).collect(),
        guide_unmapped: run.adoption.unmapped.clone(),
        alignment: crate::report::AlignmentReport {
            kept_lift: best.kept_lift.clone(),
        },
        replans: run.replans,
        verdict: best.verdict.clone(),
        optimizer_issues,
        plan_notes: best.plan.notes.clone(),
        assumptions: run.original_plan.assumptions.clone(),
        reading: run.original_plan.reading.clone(),
        limits: run.original_plan.limits.clone(),
        prompt_check: scenethesis_agents::check_prompt(run.original_plan, &best.scene),
        notes: best.guide_notes.iter().cloned().chain(run.notes).collect(),
        timings: run.timings,
        total_seconds: run.total_seconds,
        providers: Vec::new(),
        house: None,
    }
}
