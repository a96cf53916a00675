//! `report.json`: what a run measured and decided.

use scenethesis_agents::{DroppedObject, PromptCheck, UnmappedLabel};
use serde::{Deserialize, Serialize};

use crate::judge::Verdict;
use crate::stage::Stage;

/// What the judge did before a re-plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ReplanAction {
    /// The objects at fault got new asset variants and the layout a new seed.
    Move,
    /// The objects at fault (and everything resting on them) were removed from the plan. Objects
    /// the prompt asked for are removed only when no other offender is left or at the last
    /// re-plan; until then they are moved (new variants) alongside.
    Drop,
}

/// One re-plan the judge made.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Replan {
    /// The attempt (0-based) whose verdict caused it.
    pub after_round: usize,
    /// What was done.
    pub action: ReplanAction,
    /// The objects moved or dropped.
    pub objects: Vec<String>,
    /// The failures that caused it.
    pub reasons: Vec<String>,
    /// The layout seed of the next attempt.
    pub layout_seed: u64,
}

/// `report.json`'s `alignment`: what the correspond stage decided.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct AlignmentReport {
    /// Objects that kept the raw lift's pose because it agrees with the image better than the
    /// fitted one (the alignment never leaves an object worse than its lift), with the measures.
    #[serde(default)]
    pub kept_lift: Vec<scenethesis_correspondence::KeptLift>,
}

impl AlignmentReport {
    /// Nothing to report.
    pub fn is_empty(&self) -> bool {
        self.kept_lift.is_empty()
    }
}

/// Post-condition misses the optimizer reported for one object.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ObjectIssue {
    /// The object.
    pub id: String,
    /// The issues, as sentences.
    pub issues: Vec<String>,
}

/// Wall-clock seconds spent in one stage (summed over re-plans).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StageTiming {
    /// The stage.
    pub stage: Stage,
    /// Seconds.
    pub seconds: f64,
    /// The stage's parts as the stage itself measured them (the judge's collisions, stability
    /// simulation, relations, …; the optimizer's sweep and final pass), summed over re-plans;
    /// absent for stages that report none. Parts may run side by side, so they can add up to
    /// more than the stage.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub parts: Vec<PartTiming>,
}

/// Wall-clock seconds spent in one part of a stage (summed over re-plans).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PartTiming {
    /// The part's name (`collisions`, `sweep`, …; see `docs/report-json.md`).
    pub part: String,
    /// Seconds.
    pub seconds: f64,
}

/// The content of `report.json`. Everything except `timings`, `total_seconds` and the
/// export timing is deterministic for a fixed prompt, seed and providers.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Report {
    /// The prompt.
    pub prompt: String,
    /// The seed.
    pub seed: u64,
    /// Digest of the generation options and asset source ([`GenerateOptions::digest`]).
    ///
    /// [`GenerateOptions::digest`]: crate::GenerateOptions::digest
    #[serde(default)]
    pub options_digest: String,
    /// The scene type the planner recognised.
    pub scene_type: String,
    /// Whether the judge accepted the final scene.
    pub accepted: bool,
    /// The planner's name (`Planner::name`; empty in reports written before it was recorded).
    #[serde(default)]
    pub planner: String,
    /// The guide's name (`Guide::name`; empty in reports written before it was recorded).
    #[serde(default)]
    pub guide: String,
    /// The judge's name.
    pub judge: String,
    /// The optimizer's name.
    pub optimizer: String,
    /// The correspond stage's matcher (`shape`, or a dense model such as `onnx/loftr`), when
    /// one is configured; absent for the offline procedural path.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub matcher: Option<String>,
    /// The asset source's name.
    pub asset_source: String,
    /// Attempts made (1 + re-plans).
    pub attempts: usize,
    /// Which attempt (0-based) the output is.
    pub chosen_attempt: usize,
    /// Objects in the first plan.
    pub planned_objects: usize,
    /// Objects in the output scene.
    pub objects: usize,
    /// Planned (and adopted) objects missing from the output (dropped by the guide or the
    /// judge).
    pub not_in_scene: Vec<String>,
    /// Objects the guide could not fit in the chosen attempt, with reasons.
    pub guide_dropped: Vec<DroppedObject>,
    /// Objects the guide's image shows that the plan did not hold, added to it before retrieval
    /// (the vision guide's labelled masks); absent when none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub guide_adopted: Vec<String>,
    /// Labels of the guidance whose category the asset library cannot map, with the nearest
    /// category it has; absent when none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub guide_unmapped: Vec<UnmappedLabel>,
    /// What the correspond stage decided (vision-guided runs with a matcher); absent when it
    /// did not run or kept every fitted pose.
    #[serde(default, skip_serializing_if = "AlignmentReport::is_empty")]
    pub alignment: AlignmentReport,
    /// Every re-plan the judge made.
    pub replans: Vec<Replan>,
    /// The judge's verdict on the output, with every metric.
    pub verdict: Verdict,
    /// Post-condition misses the optimizer reported.
    pub optimizer_issues: Vec<ObjectIssue>,
    /// What the planner substituted or left out.
    pub plan_notes: Vec<String>,
    /// What the planner assumed to read the prompt (an unknown place read as a known kind,
    /// a generic room).
    #[serde(default)]
    pub assumptions: Vec<String>,
    /// The place the planner read the prompt as, how sure it is and why (absent for a plan
    /// given by file).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reading: Option<scenethesis_agents::PlaceReading>,
    /// Limits that cut the request (prompt length, instances per object, objects per plan).
    #[serde(default)]
    pub limits: Vec<String>,
    /// Whether the output holds every object the prompt names and every relation it states.
    #[serde(default)]
    pub prompt_check: PromptCheck,
    /// Other notes (e.g. why previews were skipped).
    pub notes: Vec<String>,
    /// Seconds per stage.
    pub timings: Vec<StageTiming>,
    /// Seconds from the prompt to the finished scene in memory (before writing files).
    pub total_seconds: f64,
    /// What the run used of each model provider (provider without credentials, model,
    /// requests, tokens, cache hits); absent for offline runs, which use none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub providers: Vec<scenethesis_models::UsageReport>,
    /// A house's rooms and its whole-house Walk and Reach; absent for a single room.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub house: Option<crate::HouseReport>,
}

impl Report {
    /// A one-line summary: verdict, objects, categories, requested objects present and stated
    /// relations held, metrics, time, then what was unavailable, assumed or capped.
    pub fn summary_line(&self) -> String {
        let m = &self.verdict.metrics;
        let reach = m
            .reach_floor
            .map_or("n/a".to_owned(), |r| format!("{r:.2}"));
        let p = &self.prompt_check;
        let mut line = format!(
            "{} — {} objects, {} categories, {} relation kinds; requested {}/{} present, relations {}/{} held; Col-O {:.1}% Inst-O {:.1}% Walk {:.2} Reach {}; {} attempt(s), {:.2} s",
            if self.accepted { "accepted" } else { "NOT accepted" },
            self.objects,
            m.categories,
            m.relation_kinds,
            p.present,
            p.requested,
            p.relations_held,
            p.relations_stated,
            m.col_o * 100.0,
            m.inst_o * 100.0,
            m.walk,
            reach,
            self.attempts,
            self.total_seconds,
        );
        if p.attributes_requested > 0 {
            line.push_str(&format!(
                "; attributes {}/{} honoured",
                p.attributes_honoured, p.attributes_requested
            ));
        }
        if !p.unavailable.is_empty() {
            line.push_str(&format!("; unavailable: {}", p.unavailable.join(", ")));
        }
        if !p.attributes_unavailable.is_empty() {
            line.push_str(&format!(
                "; unavailable looks: {}",
                p.attributes_unavailable.join(", ")
            ));
        }
        if let Some(r) = self.reading.as_ref().filter(|r| r.is_low()) {
            line.push_str(&format!(
                "; low-confidence reading: `{}` ({:.2}: {})",
                r.place, r.confidence, r.basis
            ));
        }
        for a in &self.assumptions {
            line.push_str(&format!("; assumed: {a}"));
        }
        for l in &self.limits {
            line.push_str(&format!("; capped: {l}"));
        }
        if let Some(house) = &self.house {
            line.push_str(&format!("; {}", house.summary()));
        }
        line
    }
}
