//! Batches: many prompts × seeds into one output folder each, resumable and shardable across
//! machines with no coordinator.
//!
//! The job list is every (prompt, seed) pair in file order; shard `I/N` (0-based `I`) runs the
//! jobs whose position `j` satisfies `j mod N = I`. On a cluster every task of an array or
//! indexed job passes its own index — or `--shard auto` ([`ShardSpec::Auto`]), which reads it
//! from SLURM, Kubernetes, AWS Batch or Google Cloud Batch ([`scheduler`]). Any number of
//! shards (and repeated runs) may share one output folder:
//! - a job's folder appears only once complete: it is written in a private staging folder and
//!   renamed into place, so no half scene is ever visible, even when a task is killed;
//! - a folder whose `report.json` records the job's prompt, seed and options digest is
//!   finished and skipped on the next run; a folder of another prompt or other options under
//!   the same name is generated again;
//! - each running job holds a lock file (`.FOLDER.lock`), and a job is checked again for being
//!   finished once its lock is taken, so two batches over the same folder never do the same
//!   job at once nor redo one that the other just finished;
//! - `summary.json` aggregates every finished folder of the whole batch (all shards). Shards
//!   write it one at a time (`.summary.json.lock`), each after its own jobs, so the last shard
//!   to finish writes the complete summary; each shard also writes its own
//!   `summary.shard-I-of-N.json`. A batch that is interrupted still writes its summary, and
//!   [`summarize_folder`] rebuilds `summary.json` from the folder without running any job.

use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant, SystemTime};

use rayon::prelude::*;
use scenethesis_eval::{MetricsSummary, SceneMetrics};
use scenethesis_scene_graph::write_file_atomic;
use serde::{Deserialize, Serialize};

use crate::out_dir::REPORT_JSON;
use crate::pipeline::{GenerateOptions, Pipeline};
use crate::report::Report;
use crate::stage::NoProgress;
use crate::PipelineError;

pub mod scheduler;

pub use scheduler::{process_env, Scheduler, ShardSpec};

/// One slice of a batch: shard `index` of `count` (0-based).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// This shard, `0 ≤ index < count`.
    pub index: usize,
    /// Number of shards.
    pub count: usize,
}

impl Shard {
    /// The whole batch.
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// Whether job `position` belongs to this shard.
    pub fn contains(&self, position: usize) -> bool {
        position % self.count == self.index
    }
}

impl std::fmt::Display for Shard {
    /// `I/N`, as `--shard` takes it.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl FromStr for Shard {
    type Err = PipelineError;

    /// Parses `I/N`, e.g. `0/4` … `3/4`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || {
            PipelineError::Batch(format!(
                "shard `{s}` must be I/N with 0 <= I < N, e.g. 0/4, or auto / auto/N to read \
                 it from SLURM, Kubernetes, AWS Batch or Google Cloud Batch"
            ))
        };
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let index: usize = i.trim().parse().map_err(|_| bad())?;
        let count: usize = n.trim().parse().map_err(|_| bad())?;
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }
}

/// Settings of a batch.
#[derive(Debug, Clone)]
pub struct BatchOptions {
    /// Scenes generated at the same time on this machine.
    pub jobs: usize,
    /// Which slice of the job list this run does.
    pub shard: Shard,
    /// Seeds per prompt: `base_seed`, `base_seed + 1`, …
    pub seeds: u64,
    /// The first seed.
    pub base_seed: u64,
    /// Options of every run.
    pub generate: GenerateOptions,
    /// Set (e.g. by a Ctrl-C handler) to stop starting new jobs; running jobs finish and the
    /// summary is still written.
    pub cancel: Option<Arc<AtomicBool>>,
}

impl Default for BatchOptions {
    fn default() -> Self {
        Self {
            jobs: 1,
            shard: Shard::ALL,
            seeds: 1,
            base_seed: 0,
            generate: GenerateOptions::default(),
            cancel: None,
        }
    }
}

impl BatchOptions {
    fn cancelled(&self) -> bool {
        self.cancel
            .as_ref()
            .is_some_and(|c| c.load(Ordering::SeqCst))
    }
}

/// One (prompt, seed) job.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct BatchJob {
    /// Position in the full job list (all shards).
    pub position: usize,
    /// 0-based index of the prompt among the prompts.
    pub prompt_index: usize,
    /// 1-based line of the prompt in the prompts file (0 when the prompts came from elsewhere).
    pub line: usize,
    /// The prompt.
    pub prompt: String,
    /// The seed.
    pub seed: u64,
    /// The job's folder name inside the batch output folder.
    pub folder: String,
}

/// What happened to one job.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum JobStatus {
    /// Generated by this run.
    Generated,
    /// Not run by this run: finished earlier (by an earlier run or another shard), or — with
    /// the error "not finished …" — another shard's job not done yet. Every job of a summary
    /// rebuilt by [`summarize_folder`] has this status.
    Skipped,
    /// Failed; see the error.
    Failed,
    /// Another batch is running this job right now (it holds the job's lock); not run.
    Busy,
    /// Not started: the batch was interrupted.
    Interrupted,
}

/// One job's outcome.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JobOutcome {
    /// The job.
    #[serde(flatten)]
    pub job: BatchJob,
    /// What happened.
    pub status: JobStatus,
    /// Whether the judge accepted the scene (finished jobs).
    pub accepted: Option<bool>,
    /// Objects in the scene (finished jobs).
    pub objects: Option<usize>,
    /// Seconds of generation (finished jobs; from its report).
    pub seconds: Option<f64>,
    /// Relations the prompt states and how many hold in the scene (finished jobs; from its
    /// report's `prompt_check`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub relations: Option<RelationsHeld>,
    /// Why it failed.
    pub error: Option<String>,
    /// Anything else worth knowing (e.g. an earlier scene of another prompt was replaced).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// Relations a prompt states and how many of them hold: one scene's, or pooled over scenes.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct RelationsHeld {
    /// Stated relations that hold in the scene.
    pub held: u32,
    /// Relations the prompt states.
    pub stated: u32,
    /// `held / stated`; absent when the prompt states none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub share: Option<f64>,
}

impl RelationsHeld {
    /// Held / stated, with the share computed.
    pub fn new(held: u32, stated: u32) -> Self {
        Self {
            held,
            stated,
            share: (stated > 0).then(|| f64::from(held) / f64::from(stated)),
        }
    }

    /// The stated relations of a finished scene's report.
    pub fn of(report: &Report) -> Self {
        Self::new(
            report.prompt_check.relations_held,
            report.prompt_check.relations_stated,
        )
    }
}

/// One prompt's stated relations held, pooled over its finished seeds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PromptRelations {
    /// 0-based index of the prompt among the prompts.
    pub prompt_index: usize,
    /// The prompt.
    pub prompt: String,
    /// Finished scenes (seeds) of the prompt.
    pub scenes: usize,
    /// Its stated relations held over those scenes.
    pub relations: RelationsHeld,
}

/// What a batch reports while it runs.
#[derive(Debug, Clone, Copy)]
pub enum BatchEvent<'a> {
    /// A job started.
    Started(&'a BatchJob),
    /// A job ended (generated, skipped, failed, busy or interrupted).
    Finished(&'a JobOutcome),
}

/// `summary.json`: aggregate metrics over every finished scene of the batch.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BatchSummary {
    /// Jobs in the whole batch (all shards).
    pub total_jobs: usize,
    /// Finished scenes found in the output folder.
    pub finished: usize,
    /// Finished scenes the judge accepted.
    pub accepted: usize,
    /// Pooled metrics over the finished scenes.
    pub metrics: MetricsSummary,
    /// Median seconds per scene over the finished scenes.
    pub median_seconds: Option<f64>,
    /// Stated relations held over the finished scenes (each job's own share is in `jobs`).
    #[serde(default)]
    pub relations: RelationsHeld,
    /// Stated relations held per prompt, pooled over its finished seeds, in prompt order.
    #[serde(default)]
    pub prompts: Vec<PromptRelations>,
    /// Every job of the batch; those not finished yet have no figures.
    pub jobs: Vec<JobOutcome>,
}

/// One prompt of a prompts file.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Prompt {
    /// 1-based line in the file (0 when the prompt did not come from a file).
    pub line: usize,
    /// The prompt, trimmed.
    pub text: String,
}

impl From<&str> for Prompt {
    fn from(text: &str) -> Self {
        Self {
            line: 0,
            text: text.to_owned(),
        }
    }
}

/// A line of a prompts file that was skipped, and why.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct SkippedLine {
    /// 1-based line number.
    pub line: usize,
    /// Why it was skipped.
    pub reason: String,
}

/// The prompts of a prompts file, and the lines that could not be used.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct PromptsFile {
    /// The usable prompts, in file order.
    pub prompts: Vec<Prompt>,
    /// Lines skipped (e.g. not valid UTF-8), each with its line number.
    pub skipped: Vec<SkippedLine>,
    /// Prompts cut to the prompt length limit, each with its line number.
    pub cut: Vec<CutLine>,
}

/// A line of a prompts file whose prompt was cut to
/// [`MAX_PROMPT_CHARS`](scenethesis_agents::MAX_PROMPT_CHARS) characters.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct CutLine {
    /// 1-based line number.
    pub line: usize,
    /// How long the prompt was and how much of it was kept.
    pub note: String,
}

/// Reads a prompts file: one prompt per line; blank lines and lines starting with `#` are
/// ignored; a line that is not valid UTF-8 is skipped and reported with its line number.
pub fn read_prompts(path: &Path) -> Result<PromptsFile, PipelineError> {
    let bytes = scenethesis_scene_graph::read_bounded(
        path,
        scenethesis_scene_graph::limits::MAX_PROMPTS_FILE_BYTES,
    )
    .map_err(|source| PipelineError::Read {
        path: path.to_owned(),
        source,
    })?;
    let mut file = PromptsFile::default();
    for (i, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line = i + 1;
        let raw = raw.strip_suffix(b"\r").unwrap_or(raw);
        let Ok(text) = std::str::from_utf8(raw) else {
            file.skipped.push(SkippedLine {
                line,
                reason: "not valid UTF-8".into(),
            });
            continue;
        };
        let text = text.trim();
        if text.is_empty() || text.starts_with('#') {
            continue;
        }
        let (text, cut) = scenethesis_agents::cut_prompt(text);
        if let Some(note) = cut {
            file.cut.push(CutLine { line, note });
        }
        file.prompts.push(Prompt {
            line,
            text: text.to_owned(),
        });
    }
    if file.prompts.is_empty() {
        return Err(PipelineError::Batch(format!(
            "{} holds no prompts (one per line; # starts a comment)",
            path.display()
        )));
    }
    Ok(file)
}

/// The most jobs (prompts × seeds) one batch may hold: the job list and the summaries hold a
/// line per job, so this bounds a batch's memory before any job runs (about 1 KB per job with
/// the longest prompts). Larger datasets are several batches (other prompts files, or other
/// `--seed` bases), each of which can be sharded.
pub const MAX_BATCH_JOBS: u64 = 100_000;

/// Every job of a batch, in order: for each prompt, each seed (`seeds` ≥ 1). Refuses a batch of
/// more than [`MAX_BATCH_JOBS`] jobs before making any.
pub fn jobs(
    prompts: &[Prompt],
    seeds: u64,
    base_seed: u64,
) -> Result<Vec<BatchJob>, PipelineError> {
    let seeds = seeds.max(1);
    let total = (prompts.len() as u64).saturating_mul(seeds);
    if total > MAX_BATCH_JOBS {
        return Err(PipelineError::Batch(format!(
            "{} prompts × {seeds} seeds make {total} jobs, over the limit of {MAX_BATCH_JOBS} \
             jobs per batch (docs/limits.md); split the prompts file or run several batches \
             with other --seed bases",
            prompts.len()
        )));
    }
    let mut out = Vec::with_capacity(total as usize);
    for (i, prompt) in prompts.iter().enumerate() {
        for k in 0..seeds {
            let seed = base_seed.wrapping_add(k);
            out.push(BatchJob {
                position: out.len(),
                prompt_index: i,
                line: prompt.line,
                prompt: prompt.text.clone(),
                seed,
                folder: format!("{:03}_{}_s{seed}", i + 1, slug(&prompt.text)),
            });
        }
    }
    Ok(out)
}

/// A file-name-safe short form of a prompt: lower-case words joined by `_`, at most 40
/// characters.
pub fn slug(prompt: &str) -> String {
    let mut s = String::new();
    for word in prompt
        .split(|c: char| !c.is_ascii_alphanumeric())
        .filter(|w| !w.is_empty())
    {
        if s.len() + word.len() + 1 > 40 {
            break;
        }
        if !s.is_empty() {
            s.push('_');
        }
        s.push_str(&word.to_ascii_lowercase());
    }
    if s.is_empty() {
        s.push_str("scene");
    }
    s
}

fn read_report(dir: &Path) -> Option<Report> {
    let text = std::fs::read_to_string(dir.join(REPORT_JSON)).ok()?;
    serde_json::from_str(&text).ok()
}

/// The report of `job`'s folder when it holds this job's scene: same prompt, seed and options
/// digest (not merely the same folder name).
fn finished_report(dir: &Path, job: &BatchJob, digest: &str) -> Option<Report> {
    read_report(dir)
        .filter(|r| r.prompt == job.prompt && r.seed == job.seed && r.options_digest == digest)
}

/// A job's lock: `.FOLDER.lock` in the batch folder, created exclusively, removed on drop.
struct JobLock {
    path: PathBuf,
}

/// A lock older than this is taken over even when its owner cannot be checked (another host).
const LOCK_STALE_AFTER: Duration = Duration::from_secs(6 * 3600);

impl JobLock {
    /// Takes the lock of `folder`, or `None` when another live batch holds it. A lock whose
    /// owner is gone (same host, dead process) or that is older than [`LOCK_STALE_AFTER`] is
    /// taken over.
    fn acquire(out: &Path, folder: &str) -> Result<Option<Self>, PipelineError> {
        let path = out.join(format!(".{folder}.lock"));
        let me = format!("{}\n{}\n", std::process::id(), host_name());
        for _ in 0..2 {
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&path)
            {
                Ok(mut f) => {
                    use std::io::Write;
                    f.write_all(me.as_bytes())
                        .map_err(|source| PipelineError::Write {
                            path: path.clone(),
                            source,
                        })?;
                    return Ok(Some(Self { path }));
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
                    if !lock_is_stale(&path) {
                        return Ok(None);
                    }
                    let _ = std::fs::remove_file(&path);
                }
                Err(source) => return Err(PipelineError::Write { path, source }),
            }
        }
        Ok(None)
    }
}

impl Drop for JobLock {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

fn lock_is_stale(path: &Path) -> bool {
    let old = std::fs::metadata(path)
        .and_then(|m| m.modified())
        .ok()
        .and_then(|t| SystemTime::now().duration_since(t).ok())
        .is_some_and(|age| age > LOCK_STALE_AFTER);
    if old {
        return true;
    }
    let Ok(text) = std::fs::read_to_string(path) else {
        return false;
    };
    let mut lines = text.lines();
    let (Some(pid), Some(host)) = (lines.next(), lines.next()) else {
        return false;
    };
    let Ok(pid) = pid.trim().parse::<u32>() else {
        return false;
    };
    host == host_name()
        && !Path::new("/proc").join(pid.to_string()).exists()
        && cfg!(target_os = "linux")
}

fn host_name() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .or_else(|_| std::fs::read_to_string("/etc/hostname"))
        .map(|h| h.trim().to_owned())
        .unwrap_or_else(|_| "unknown-host".into())
}

/// Runs this shard's jobs of a batch into `out` (skipping jobs already finished with the same
/// prompt, seed and options), reporting each job's start and end to `on_event`, then writes
/// `summary.json` over every finished folder and this shard's `summary.shard-I-of-N.json` —
/// also when the batch was interrupted through [`BatchOptions::cancel`]. A failing job does not
/// stop the others.
pub fn run_batch(
    pipeline: &Pipeline,
    prompts: &[Prompt],
    out: &Path,
    options: &BatchOptions,
    on_event: &(dyn Fn(BatchEvent<'_>) + Sync),
) -> Result<BatchSummary, PipelineError> {
    std::fs::create_dir_all(out).map_err(|source| PipelineError::Write {
        path: out.to_owned(),
        source,
    })?;
    let all = jobs(prompts, options.seeds, options.base_seed)?;
    let digest = options.generate.digest(pipeline.assets().name());
    let mine: Vec<&BatchJob> = all
        .iter()
        .filter(|j| options.shard.contains(j.position))
        .collect();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.jobs.max(1))
        .build()
        .map_err(|e| PipelineError::Batch(format!("cannot start {} workers: {e}", options.jobs)))?;
    let run_one = |job: &BatchJob| -> JobOutcome {
        let dir = out.join(&job.folder);
        let outcome = |status, report: Option<&Report>, error: Option<String>| JobOutcome {
            job: job.clone(),
            status,
            accepted: report.map(|r| r.accepted),
            objects: report.map(|r| r.objects),
            seconds: report.map(|r| r.total_seconds),
            relations: report.map(RelationsHeld::of),
            error,
            note: None,
        };
        if let Some(report) = finished_report(&dir, job, &digest) {
            return outcome(JobStatus::Skipped, Some(&report), None);
        }
        if options.cancelled() {
            return outcome(JobStatus::Interrupted, None, None);
        }
        let _lock = match JobLock::acquire(out, &job.folder) {
            Ok(Some(lock)) => lock,
            Ok(None) => return outcome(JobStatus::Busy, None, None),
            Err(e) => return outcome(JobStatus::Failed, None, Some(error_chain(&e))),
        };
        // Another batch may have finished it while we waited for the lock.
        if let Some(report) = finished_report(&dir, job, &digest) {
            return outcome(JobStatus::Skipped, Some(&report), None);
        }
        let replaced = read_report(&dir).map(|r| {
            format!(
                "replaced an earlier scene of this folder made from prompt {:?}, seed {} \
                 and other options or assets",
                r.prompt, r.seed
            )
        });
        on_event(BatchEvent::Started(job));
        let started = Instant::now();
        let result = pipeline
            .generate(&job.prompt, job.seed, &options.generate, &mut NoProgress)
            .and_then(|mut generated| {
                generated.write_outputs(&dir)?;
                Ok(generated.report)
            });
        match result {
            Ok(report) => JobOutcome {
                note: replaced,
                ..outcome(JobStatus::Generated, Some(&report), None)
            },
            Err(e) => {
                tracing::warn!(
                    "job {} failed after {:.1} s: {e}",
                    job.folder,
                    started.elapsed().as_secs_f64()
                );
                outcome(JobStatus::Failed, None, Some(error_chain(&e)))
            }
        }
    };
    let outcomes: Vec<JobOutcome> = pool.install(|| {
        mine.par_iter()
            .map(|job| {
                let o = run_one(job);
                on_event(BatchEvent::Finished(&o));
                o
            })
            .collect()
    });

    let shard_path = out.join(format!(
        "summary.shard-{}-of-{}.json",
        options.shard.index, options.shard.count
    ));
    let _lock = summary_lock(out)?;
    let shard_summary = summarize(&all, out, &outcomes, &digest);
    let mut mine_only = shard_summary.clone();
    mine_only
        .jobs
        .retain(|j| options.shard.contains(j.job.position));
    write_json(&shard_path, &mine_only)?;
    write_json(&out.join(SUMMARY_JSON), &shard_summary)?;
    Ok(shard_summary)
}

/// The batch summary file of an output folder.
pub const SUMMARY_JSON: &str = "summary.json";

/// Rebuilds `summary.json` of the batch folder `out` from its finished folders without running
/// any job, and returns it. `prompts` and `options` must be those of the batch (the same
/// prompts file, seeds and generation options: a folder counts as finished only when its report
/// records the same prompt, seed and options digest); `options.jobs`, `shard` and `cancel` do
/// not matter.
///
/// A rebuilt summary cannot know what earlier runs did, only what they left: every finished job
/// is [`JobStatus::Skipped`] ("finished earlier") with its figures, and every other job is
/// `Skipped` with the error "not finished …" — including jobs that failed, since a failure
/// leaves no folder (its error is still in that shard's `summary.shard-I-of-N.json`). The
/// totals, metrics and relations are those of [`run_batch`]'s summary over the same folders.
pub fn summarize_folder(
    pipeline: &Pipeline,
    prompts: &[Prompt],
    out: &Path,
    options: &BatchOptions,
) -> Result<BatchSummary, PipelineError> {
    if !out.is_dir() {
        return Err(PipelineError::Batch(format!(
            "{} is not a folder: nothing to summarize",
            out.display()
        )));
    }
    let all = jobs(prompts, options.seeds, options.base_seed)?;
    let digest = options.generate.digest(pipeline.assets().name());
    let _lock = summary_lock(out)?;
    let summary = summarize(&all, out, &[], &digest);
    write_json(&out.join(SUMMARY_JSON), &summary)?;
    Ok(summary)
}

/// How long a batch waits for another shard's summary lock before taking it over.
const SUMMARY_LOCK_WAIT: Duration = Duration::from_secs(120);

/// Takes the lock of `summary.json` (`.summary.json.lock`): shards summarize and write one at a
/// time, so the summary written last is computed last and sees every shard's finished jobs.
/// A lock held longer than [`SUMMARY_LOCK_WAIT`] (left by a task killed on another host) is
/// taken over; should another shard grab it in that instant, this one writes without it
/// (`None`), which at worst lets an older summary land last (`--summarize` rebuilds it).
fn summary_lock(out: &Path) -> Result<Option<JobLock>, PipelineError> {
    let started = Instant::now();
    loop {
        if let Some(lock) = JobLock::acquire(out, SUMMARY_JSON)? {
            return Ok(Some(lock));
        }
        if started.elapsed() > SUMMARY_LOCK_WAIT {
            let path = out.join(format!(".{SUMMARY_JSON}.lock"));
            tracing::warn!(
                "{} held for over {} s; taking it over",
                path.display(),
                SUMMARY_LOCK_WAIT.as_secs()
            );
            let _ = std::fs::remove_file(&path);
            return JobLock::acquire(out, SUMMARY_JSON);
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// Aggregates every finished folder of the batch; `ran` supplies this run's outcomes (for
/// failures, which leave no folder).
fn summarize(all: &[BatchJob], out: &Path, ran: &[JobOutcome], digest: &str) -> BatchSummary {
    let mut metrics: Vec<SceneMetrics> = Vec::new();
    let mut seconds: Vec<f64> = Vec::new();
    let mut accepted = 0;
    let (mut held, mut stated) = (0, 0);
    let jobs: Vec<JobOutcome> = all
        .iter()
        .map(|job| {
            let ran_here = ran.iter().find(|o| o.job.position == job.position);
            match finished_report(&out.join(&job.folder), job, digest) {
                Some(report) => {
                    metrics.push(report.verdict.metrics.clone());
                    seconds.push(report.total_seconds);
                    accepted += usize::from(report.accepted);
                    let relations = RelationsHeld::of(&report);
                    held += relations.held;
                    stated += relations.stated;
                    JobOutcome {
                        job: job.clone(),
                        status: ran_here.map_or(JobStatus::Skipped, |o| o.status),
                        accepted: Some(report.accepted),
                        objects: Some(report.objects),
                        seconds: Some(report.total_seconds),
                        relations: Some(relations),
                        error: None,
                        note: ran_here.and_then(|o| o.note.clone()),
                    }
                }
                None => ran_here.cloned().unwrap_or(JobOutcome {
                    job: job.clone(),
                    status: JobStatus::Skipped,
                    accepted: None,
                    objects: None,
                    seconds: None,
                    relations: None,
                    error: Some("not finished (another shard, or not run yet)".into()),
                    note: None,
                }),
            }
        })
        .collect();
    seconds.sort_by(f64::total_cmp);
    let median_seconds = (!seconds.is_empty()).then(|| {
        let n = seconds.len();
        if n % 2 == 1 {
            seconds[n / 2]
        } else {
            (seconds[n / 2 - 1] + seconds[n / 2]) / 2.0
        }
    });
    let mut prompts: Vec<PromptRelations> = Vec::new();
    for job in &jobs {
        let Some(r) = job.relations else { continue };
        let at = match prompts
            .iter()
            .position(|p| p.prompt_index == job.job.prompt_index)
        {
            Some(at) => at,
            None => {
                prompts.push(PromptRelations {
                    prompt_index: job.job.prompt_index,
                    prompt: job.job.prompt.clone(),
                    scenes: 0,
                    relations: RelationsHeld::default(),
                });
                prompts.len() - 1
            }
        };
        let p = &mut prompts[at];
        p.scenes += 1;
        p.relations = RelationsHeld::new(p.relations.held + r.held, p.relations.stated + r.stated);
    }
    prompts.sort_by_key(|p| p.prompt_index);
    BatchSummary {
        total_jobs: all.len(),
        finished: metrics.len(),
        accepted,
        metrics: MetricsSummary::from_scenes(&metrics),
        median_seconds,
        relations: RelationsHeld::new(held, stated),
        prompts,
        jobs,
    }
}

fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<(), PipelineError> {
    let text = serde_json::to_string_pretty(value).expect("summary serializes") + "\n";
    write_file_atomic(path, text.as_bytes()).map_err(|source| PipelineError::Write {
        path: PathBuf::from(path),
        source,
    })
}

/// An error with its causes, `: `-separated; a cause whose text the message already holds
/// (many errors quote their source) is not repeated.
pub fn error_chain(e: &dyn std::error::Error) -> String {
    let mut s = e.to_string();
    let mut source = e.source();
    while let Some(cause) = source {
        let text = cause.to_string();
        if !text.is_empty() && !s.contains(&text) {
            s.push_str(": ");
            s.push_str(&text);
        }
        source = cause.source();
    }
    s
}

#[cfg(test)]
mod error_chain_tests {
    use super::*;

    #[test]
    fn quoted_causes_are_not_repeated() {
        let e = PipelineError::Plan(scenethesis_agents::PlanError::EmptyPrompt);
        assert_eq!(error_chain(&e), e.to_string(), "the plan error's text once");
        let io = PipelineError::Write {
            path: PathBuf::from("/x/scene.json"),
            source: std::io::Error::other("disk full"),
        };
        assert_eq!(error_chain(&io), "cannot write /x/scene.json: disk full");
    }
}

#[cfg(test)]
mod limit_tests {
    use super::*;

    #[test]
    fn a_batch_over_the_job_limit_is_refused_before_any_job_is_made() {
        let prompts = vec![Prompt::from("a kitchen"), Prompt::from("an office")];
        assert_eq!(
            jobs(&prompts, MAX_BATCH_JOBS / 2, 0).unwrap().len(),
            100_000
        );
        let err = jobs(&prompts, MAX_BATCH_JOBS / 2 + 1, 0).unwrap_err();
        assert!(err.to_string().contains("100002 jobs"), "{err}");
        assert!(jobs(&prompts, u64::MAX, 0).is_err(), "no overflow");
    }

    #[test]
    fn a_prompt_longer_than_the_limit_is_cut_when_read() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("prompts.txt");
        let long = "a kitchen with a table ".repeat(10_000);
        std::fs::write(&path, format!("a bedroom\n{long}\n")).unwrap();
        let file = read_prompts(&path).unwrap();
        assert_eq!(file.prompts.len(), 2);
        let cut = &file.prompts[1];
        assert!(cut.text.chars().count() <= scenethesis_agents::MAX_PROMPT_CHARS);
        assert!(file.skipped.is_empty());
        assert_eq!(file.cut.len(), 1);
        assert_eq!(file.cut[0].line, 2);
        assert!(
            file.cut[0].note.contains("the limit is 2000"),
            "{:?}",
            file.cut
        );
    }
}
