//! Batches on clusters: several shards (and an overlapping full run) writing into one shared
//! folder at the same time, the summary they leave, and `summarize_folder` rebuilding it.
//!
//! The scenes are the offline pipeline's with each plan cut to its anchor and two more
//! free-standing objects ([`SmallPlanner`]): the folder protocol is under test, not the
//! scenes, and three full scenes would cost seconds each.

use std::path::{Path, PathBuf};
use std::sync::{Barrier, OnceLock};
use std::time::{Duration, Instant};

use scenethesis_agents::{
    check_plan, KnowledgePlanner, Plan, PlanError, PlanRequest, Planner, Zone,
};
use scenethesis_pipeline::batch::{
    self, BatchOptions, BatchSummary, JobStatus, Prompt, Shard, SUMMARY_JSON,
};
use scenethesis_pipeline::{GenerateOptions, Pipeline};
use scenethesis_scene_graph::ParentRef;
use serde_json::Value;

/// The knowledge planner's plan cut to the anchor and the next two ground objects that stand
/// on their own (no relations to objects that are cut).
struct SmallPlanner(KnowledgePlanner);

impl Planner for SmallPlanner {
    fn name(&self) -> &str {
        "small"
    }

    fn plan(&self, request: &PlanRequest) -> Result<Plan, PlanError> {
        let mut plan = self.0.plan(request)?;
        let free_standing = |o: &&scenethesis_agents::PlannedObject| {
            o.parent == ParentRef::Ground
                && matches!(o.zone, Zone::Wall { .. } | Zone::Corner | Zone::Free)
        };
        let anchor = plan.objects.iter().find(|o| o.id == plan.anchor).cloned();
        let others = plan.objects.iter().filter(|o| o.id != plan.anchor);
        let mut kept: Vec<_> = anchor.into_iter().collect();
        kept.extend(others.filter(free_standing).take(2).cloned());
        for object in &mut kept {
            object.relations.clear();
        }
        plan.objects = kept;
        plan.constraints.clear();
        plan.requested.clear();
        Ok(plan)
    }
}

fn pipeline() -> Pipeline {
    Pipeline::offline().with_planner(SmallPlanner(KnowledgePlanner::new()))
}

const PROMPTS: [&str; 3] = ["a bathroom", "a small office", "a garage"];

fn prompts() -> Vec<Prompt> {
    PROMPTS.iter().map(|p| Prompt::from(*p)).collect()
}

fn options(shard: Shard) -> BatchOptions {
    BatchOptions {
        jobs: 1,
        shard,
        seeds: 1,
        base_seed: 1,
        generate: GenerateOptions {
            max_replans: 1,
            previews: false,
            ..GenerateOptions::default()
        },
        cancel: None,
    }
}

/// One batch run by shards 0/3, 1/3 and 2/3 plus a full run (0/1), all at once in one folder.
struct SharedRun {
    out: PathBuf,
    /// Each run's summary, in the order of [`RUNS`].
    summaries: Vec<BatchSummary>,
    seconds: f64,
}

const RUNS: [Shard; 4] = [
    Shard { index: 0, count: 3 },
    Shard { index: 1, count: 3 },
    Shard { index: 2, count: 3 },
    Shard::ALL,
];

/// The shared run, done once for the tests of this file (in the target's test folder, which
/// is cleared first).
fn shared_run() -> &'static SharedRun {
    static RUN: OnceLock<SharedRun> = OnceLock::new();
    RUN.get_or_init(|| {
        let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("batch_cluster");
        let _ = std::fs::remove_dir_all(&out);
        let pipeline = pipeline();
        let prompts = prompts();
        let start = Barrier::new(RUNS.len());
        let started = Instant::now();
        let summaries = std::thread::scope(|s| {
            let runs: Vec<_> = RUNS
                .iter()
                .map(|shard| {
                    let (pipeline, prompts, out, start) = (&pipeline, &prompts, &out, &start);
                    s.spawn(move || {
                        start.wait();
                        batch::run_batch(pipeline, prompts, out, &options(*shard), &|_| {})
                            .expect("the batch runs")
                    })
                })
                .collect();
            runs.into_iter().map(|r| r.join().unwrap()).collect()
        });
        SharedRun {
            out,
            summaries,
            seconds: started.elapsed().as_secs_f64(),
        }
    })
}

fn read_json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn small_plans_hold_together() {
    let pipeline = pipeline();
    for prompt in PROMPTS {
        let plan = pipeline.plan(prompt, 1).unwrap();
        assert!((1..=3).contains(&plan.objects.len()), "{prompt}: {plan:#?}");
        check_plan(&plan, None).unwrap_or_else(|e| panic!("{prompt}: {e}"));
    }
}

#[test]
fn shards_sharing_a_folder_write_each_scene_once_and_completely() {
    let run = shared_run();
    eprintln!("4 concurrent runs of 3 jobs: {:.1} s", run.seconds);
    let all = batch::jobs(&prompts(), 1, 1).unwrap();
    // Each job generated by exactly one run; the others skipped it or found it busy.
    for job in &all {
        let statuses: Vec<JobStatus> = run
            .summaries
            .iter()
            .zip(RUNS)
            .filter(|(_, shard)| shard.contains(job.position))
            .map(|(summary, _)| summary.jobs[job.position].status)
            .collect();
        let generated = statuses
            .iter()
            .filter(|s| **s == JobStatus::Generated)
            .count();
        assert_eq!(generated, 1, "{}: {statuses:?}", job.folder);
        assert!(
            statuses.iter().all(|s| matches!(
                s,
                JobStatus::Generated | JobStatus::Skipped | JobStatus::Busy
            )),
            "{}: {statuses:?}",
            job.folder
        );
    }
    // Exactly the job folders and the summaries: no staging folder, temporary file or lock.
    let mut expected: Vec<String> = all.iter().map(|j| j.folder.clone()).collect();
    expected.extend(
        [
            "summary.json",
            "summary.shard-0-of-1.json",
            "summary.shard-0-of-3.json",
            "summary.shard-1-of-3.json",
            "summary.shard-2-of-3.json",
        ]
        .map(String::from),
    );
    expected.sort();
    assert_eq!(names(&run.out), expected);
    // Every folder is whole and holds its own job.
    for job in &all {
        let dir = run.out.join(&job.folder);
        assert_eq!(
            names(&dir),
            ["report.json", "scene.glb", "scene.json"],
            "{}",
            job.folder
        );
        let report = read_json(&dir.join("report.json"));
        assert_eq!(report["prompt"], job.prompt.as_str());
        assert_eq!(report["seed"], job.seed);
    }
    // The last run to finish wrote the complete summary.
    let summary = read_json(&run.out.join(SUMMARY_JSON));
    assert_eq!(summary["total_jobs"], 3);
    assert_eq!(summary["finished"], 3, "{summary:#}");
    for (job, written) in all.iter().zip(summary["jobs"].as_array().unwrap()) {
        assert_eq!(written["folder"], job.folder.as_str());
        assert!(written["error"].is_null(), "{written:#}");
        assert!(written["accepted"].is_boolean(), "{written:#}");
    }
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.path().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).unwrap();
        }
    }
}

/// A summary's jobs without their statuses, which a rebuilt summary cannot know.
fn without_status(summary: &Value) -> Value {
    let mut summary = summary.clone();
    for job in summary["jobs"].as_array_mut().unwrap() {
        job.as_object_mut().unwrap().remove("status");
    }
    summary
}

#[test]
fn summarize_rebuilds_the_summary_without_running_a_job() {
    let run = shared_run();
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("batch");
    copy_dir(&run.out, &out);
    let original = read_json(&out.join(SUMMARY_JSON));
    std::fs::remove_file(out.join(SUMMARY_JSON)).unwrap();
    let before = names(&out);

    let pipeline = pipeline();
    let started = Instant::now();
    let rebuilt = batch::summarize_folder(&pipeline, &prompts(), &out, &options(Shard::ALL))
        .expect("summarizes");
    eprintln!("summarize: {:.3} s", started.elapsed().as_secs_f64());
    assert_eq!(rebuilt.finished, 3);
    assert!(
        rebuilt.jobs.iter().all(|j| j.status == JobStatus::Skipped),
        "a rebuilt summary says every finished job was finished earlier"
    );
    let written = read_json(&out.join(SUMMARY_JSON));
    assert_eq!(written, serde_json::to_value(&rebuilt).unwrap());
    assert_eq!(without_status(&written), without_status(&original));
    let mut after = before.clone();
    after.push(SUMMARY_JSON.into());
    after.sort();
    assert_eq!(names(&out), after, "only summary.json written, no job run");

    // Other options: nothing counts as finished, and still nothing runs.
    let mut other = options(Shard::ALL);
    other.generate.max_replans = 0;
    let rebuilt = batch::summarize_folder(&pipeline, &prompts(), &out, &other).unwrap();
    assert_eq!(rebuilt.finished, 0);
    assert!(rebuilt.jobs.iter().all(|j| j.error.is_some()));
    assert_eq!(names(&out), after);

    // No folder: an error, nothing created.
    let missing = tmp.path().join("missing");
    assert!(batch::summarize_folder(&pipeline, &prompts(), &missing, &other).is_err());
    assert!(!missing.exists());
}

#[test]
fn summaries_are_written_one_at_a_time() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path();
    // A live batch (this very process) is writing the summary.
    let lock = out.join(format!(".{SUMMARY_JSON}.lock"));
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap_or_default();
    std::fs::write(&lock, format!("{}\n{}\n", std::process::id(), host.trim())).unwrap();
    let pipeline = pipeline();
    std::thread::scope(|s| {
        let waiting = s.spawn(|| {
            batch::summarize_folder(&pipeline, &prompts(), out, &options(Shard::ALL)).unwrap()
        });
        std::thread::sleep(Duration::from_millis(300));
        assert!(
            !out.join(SUMMARY_JSON).exists(),
            "waits for the other writer"
        );
        std::fs::remove_file(&lock).unwrap();
        let summary = waiting.join().unwrap();
        assert_eq!(summary.finished, 0);
    });
    assert!(out.join(SUMMARY_JSON).is_file());
    assert!(!lock.exists(), "its own lock is removed");
}
