//! `report.json` of a house: the rooms' reports folded into one (their objects named by
//! house id), the house's own verdict over its metrics, and the `house` section.

use std::collections::BTreeMap;

use scenethesis_judge::{Failure, FailureKind, Verdict};
use scenethesis_scene_graph::Scene;

use super::assemble::house_id;
use super::furnish::RoomRun;
use super::measure::HouseMeasure;
use super::report::{HouseReport, RoomReport};
use super::HousePlan;
use crate::pipeline::Pipeline;
use crate::report::{AlignmentReport, PartTiming, Report, StageTiming};
use crate::stage::Stage;
use scenethesis_correspondence::KeptLift;

/// What the house report is made from.
pub(crate) struct HouseRun<'a> {
    pub(crate) house: &'a HousePlan<'a>,
    pub(crate) prompt: &'a str,
    pub(crate) seed: u64,
    pub(crate) options_digest: String,
    pub(crate) rooms: &'a [RoomRun],
    pub(crate) measured: &'a HouseMeasure,
    pub(crate) scene: &'a Scene,
    pub(crate) notes: Vec<String>,
    pub(crate) render_seconds: f64,
    pub(crate) total_seconds: f64,
}

/// The report of a house run.
pub(crate) fn house_report(run: HouseRun<'_>, pipeline: &Pipeline) -> Report {
    let reports: Vec<(&RoomRun, &Report)> = run
        .rooms
        .iter()
        .filter_map(|r| r.generated.as_ref().map(|g| (r, &g.report)))
        .collect();
    let first = reports.first().map(|(_, r)| *r);
    let name = |f: fn(&Report) -> String| first.map(f).unwrap_or_default();
    let verdict = house_verdict(&run);
    let house = house_section(&run);
    let prefixed = |room: &RoomRun, ids: &[String]| -> Vec<String> {
        ids.iter().map(|id| house_id(&room.shell.id, id)).collect()
    };
    let mut notes = Vec::new();
    for room in run.rooms {
        notes.extend(room.notes.iter().map(|n| format!("{}: {n}", room.shell.id)));
    }
    notes.extend(run.notes);
    let alignment = AlignmentReport {
        kept_lift: reports
            .iter()
            .flat_map(|(room, r)| {
                r.alignment.kept_lift.iter().map(|k| KeptLift {
                    id: house_id(&room.shell.id, &k.id),
                    reason: k.reason.clone(),
                })
            })
            .collect(),
    };
    Report {
        prompt: run.prompt.to_owned(),
        seed: run.seed,
        options_digest: run.options_digest,
        scene_type: run.house.kind.clone(),
        accepted: verdict.accepted,
        planner: pipeline.planner_name().to_owned(),
        guide: name(|r| r.guide.clone()),
        judge: name(|r| r.judge.clone()),
        optimizer: name(|r| r.optimizer.clone()),
        matcher: first.and_then(|r| r.matcher.clone()),
        asset_source: pipeline.assets().name().to_owned(),
        attempts: reports
            .iter()
            .map(|(_, r)| r.attempts)
            .sum::<usize>()
            .max(1),
        chosen_attempt: 0,
        planned_objects: reports.iter().map(|(_, r)| r.planned_objects).sum(),
        objects: run.scene.objects.len(),
        not_in_scene: reports
            .iter()
            .flat_map(|(room, r)| prefixed(room, &r.not_in_scene))
            .collect(),
        guide_dropped: reports
            .iter()
            .flat_map(|(room, r)| {
                r.guide_dropped
                    .iter()
                    .map(|d| scenethesis_agents::DroppedObject {
                        id: house_id(&room.shell.id, &d.id),
                        reason: d.reason.clone(),
                    })
            })
            .collect(),
        guide_adopted: Vec::new(),
        guide_unmapped: Vec::new(),
        alignment,
        replans: reports
            .iter()
            .flat_map(|(room, r)| {
                r.replans.iter().map(|p| crate::report::Replan {
                    objects: prefixed(room, &p.objects),
                    reasons: p
                        .reasons
                        .iter()
                        .map(|why| format!("{}: {why}", room.shell.id))
                        .collect(),
                    ..p.clone()
                })
            })
            .collect(),
        verdict,
        optimizer_issues: reports
            .iter()
            .flat_map(|(room, r)| {
                r.optimizer_issues
                    .iter()
                    .map(|i| crate::report::ObjectIssue {
                        id: house_id(&room.shell.id, &i.id),
                        issues: i.issues.clone(),
                    })
            })
            .collect(),
        plan_notes: Vec::new(),
        assumptions: Vec::new(),
        reading: None,
        limits: Vec::new(),
        prompt_check: Default::default(),
        notes,
        timings: timings(&reports, run.render_seconds),
        total_seconds: run.total_seconds,
        providers: reports
            .iter()
            .flat_map(|(_, r)| r.providers.iter().cloned())
            .collect(),
        house: Some(house),
    }
}

/// The house's verdict: its metrics over the whole house, every room judge's failures (objects
/// by house id), and a failure for every room the robot cannot reach from the entrance.
fn house_verdict(run: &HouseRun<'_>) -> Verdict {
    let mut failures = Vec::new();
    let mut relations_checked = 0;
    for room in run.rooms {
        let Some(generated) = &room.generated else {
            continue;
        };
        let verdict = &generated.report.verdict;
        relations_checked += verdict.relations_checked;
        failures.extend(verdict.failures.iter().map(|f| {
            Failure {
                kind: f.kind,
                objects: f
                    .objects
                    .iter()
                    .map(|o| house_id(&room.shell.id, o))
                    .collect(),
                detail: format!("{}: {}", room.shell.id, f.detail),
            }
        }));
    }
    for (room, share) in &run.measured.entrance_reach {
        if share.is_none_or(|s| s <= 0.0) {
            failures.push(Failure {
                kind: FailureKind::Unreachable,
                objects: Vec::new(),
                detail: format!(
                    "room `{room}`: a robot of radius 0.3 m cannot drive into it from the entrance"
                ),
            });
        }
    }
    let m = &run.measured.metrics;
    let clean = m.col_o == 0.0 && m.col_arch == 0.0 && m.inst_o == 0.0;
    Verdict {
        accepted: failures.is_empty() && clean,
        failures,
        metrics: m.clone(),
        relations_checked,
        arrangement: None,
        review: None,
        timings: None,
    }
}

/// The `house` section: the whole house's Walk, Reach and entrance reach, and every room.
fn house_section(run: &HouseRun<'_>) -> HouseReport {
    let rooms: Vec<RoomReport> = run.rooms.iter().map(|r| room_report(r, run)).collect();
    let entrance_reach = rooms
        .iter()
        .filter_map(|r| r.entrance_reach)
        .min_by(f64::total_cmp);
    HouseReport {
        kind: run.house.kind.clone(),
        footprint: run.house.footprint,
        hallway: run.house.hallway,
        walk: run.measured.metrics.walk,
        reach: run.measured.metrics.reach_floor,
        entrance_reach,
        rooms_accepted: rooms.iter().filter(|r| r.accepted).count(),
        rooms,
    }
}

/// One room's line of the `house` section.
fn room_report(room: &RoomRun, run: &HouseRun<'_>) -> RoomReport {
    let area = run
        .scene
        .architecture
        .room(&room.shell.id)
        .map_or(0.0, |a| a.area());
    let entrance_reach = run
        .measured
        .entrance_reach
        .get(&room.shell.id)
        .copied()
        .flatten();
    let report = room.generated.as_ref().map(|g| &g.report);
    RoomReport {
        id: room.shell.id.clone(),
        room_type: room.room.room_type.clone(),
        prompt: room.prompt.clone(),
        area,
        furnished_size: room.shell.size,
        accepted: report.is_none_or(|r| r.accepted),
        objects: room.scene().objects.len(),
        attempts: report.map_or(0, |r| r.attempts),
        walk: report.map_or(1.0, |r| r.verdict.metrics.walk),
        reach: report.and_then(|r| r.verdict.metrics.reach_floor),
        entrance_reach,
        failures: report.map_or_else(Vec::new, |r| {
            r.verdict
                .failures
                .iter()
                .map(|f| f.detail.clone())
                .collect()
        }),
        notes: room.notes.clone(),
    }
}

/// Per-stage seconds and parts: the rooms' summed (they run in parallel, so the sum can exceed
/// the wall-clock total), plus the house's render.
fn timings(reports: &[(&RoomRun, &Report)], render_seconds: f64) -> Vec<StageTiming> {
    let mut totals: BTreeMap<Stage, (f64, BTreeMap<String, f64>)> = BTreeMap::new();
    for (_, r) in reports {
        for t in &r.timings {
            let (seconds, parts) = totals.entry(t.stage).or_default();
            *seconds += t.seconds;
            for p in &t.parts {
                *parts.entry(p.part.clone()).or_default() += p.seconds;
            }
        }
    }
    totals.entry(Stage::Render).or_default().0 += render_seconds;
    Stage::ALL
        .iter()
        .filter_map(|s| {
            totals.remove(s).map(|(seconds, parts)| StageTiming {
                stage: *s,
                seconds,
                parts: parts
                    .into_iter()
                    .map(|(part, seconds)| PartTiming { part, seconds })
                    .collect(),
            })
        })
        .collect()
}
