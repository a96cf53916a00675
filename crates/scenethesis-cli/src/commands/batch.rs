//! `scenethesis batch`: many prompts × seeds, one folder each, resumable and shardable; on a
//! cluster `--shard auto` takes the shard from the scheduler (SLURM, Kubernetes, AWS Batch,
//! Google Cloud Batch; see `docs/clusters.md`), and `--summarize` rebuilds `summary.json`.

use std::path::PathBuf;
use std::sync::atomic::AtomicBool;
use std::sync::{Arc, Mutex};

use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use scenethesis_pipeline::batch::{
    self, BatchEvent, BatchOptions, BatchSummary, JobOutcome, JobStatus, RelationsHeld, Shard,
    ShardSpec,
};

/// Arguments of `scenethesis batch`.
#[derive(Debug, clap::Args)]
pub struct BatchArgs {
    /// A text file with one prompt per line (blank lines and `#` comments skipped).
    pub prompts: PathBuf,
    /// Output folder: one sub-folder per prompt and seed, plus summary.json.
    #[arg(long)]
    pub out: PathBuf,
    /// Scenes generated at the same time.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..=256))]
    pub jobs: u64,
    /// Run only shard I of N (0-based): job j runs in shard j mod N. `auto` reads I and N from
    /// the scheduler: a SLURM job array (SLURM_ARRAY_TASK_ID, _MIN, _STEP, _COUNT), an AWS
    /// Batch array job (AWS_BATCH_JOB_ARRAY_INDEX, _SIZE) or Google Cloud Batch
    /// (BATCH_TASK_INDEX, BATCH_TASK_COUNT); `auto/N` gives N too, as a Kubernetes Indexed Job
    /// (JOB_COMPLETION_INDEX) needs, and must agree with a scheduler's own count. Any number of
    /// shards may share one --out folder.
    #[arg(long, default_value = "0/1", value_name = "I/N|auto|auto/N")]
    pub shard: ShardSpec,
    /// Seeds per prompt (seed, seed + 1, …); at least 1.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
    pub seeds: u64,
    /// The first seed.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Run no job: rebuild summary.json from the finished folders of --out (give the same
    /// prompts file, seeds and options as the batch; --shard and --jobs do not matter). Every
    /// finished job shows as "skipped" (finished earlier), every other one as not finished.
    #[arg(long)]
    pub summarize: bool,
    /// Pipeline options shared with `generate`.
    #[command(flatten)]
    pub pipeline: super::generate::PipelineArgs,
}

/// Runs `scenethesis batch`.
pub fn run(args: BatchArgs) -> Result<()> {
    let file = batch::read_prompts(&args.prompts)?;
    let skipped = file
        .skipped
        .iter()
        .map(|s| (s.line, format!("{}; skipped", s.reason)));
    let cut = file.cut.iter().map(|c| (c.line, c.note.clone()));
    for (line, message) in skipped.chain(cut) {
        eprintln!("warning: {} line {line}: {message}", args.prompts.display());
    }
    let shard = if args.summarize {
        Shard::ALL
    } else {
        resolve_shard(args.shard)?
    };
    let cancel = Arc::new(AtomicBool::new(false));
    let options = BatchOptions {
        jobs: args.jobs as usize,
        shard,
        seeds: args.seeds,
        base_seed: args.seed,
        generate: args.pipeline.options(),
        cancel: Some(cancel.clone()),
    };
    if args.summarize {
        return summarize(&args, &file.prompts, &options);
    }
    crate::interrupt::on_interrupt(cancel.clone());
    let all = batch::jobs(&file.prompts, options.seeds, options.base_seed)?;
    let mine = all
        .iter()
        .filter(|j| options.shard.contains(j.position))
        .count();
    let pipeline = args.pipeline.pipeline()?;
    let bar = ProgressBar::new(mine as u64);
    bar.set_style(
        ProgressStyle::with_template(
            "{bar:30.cyan/blue} {pos}/{len} scenes {elapsed} (eta {eta}) {wide_msg}",
        )
        .expect("valid template"),
    );
    let running: Mutex<Vec<String>> = Mutex::new(Vec::new());
    let show_running = |running: &[String]| bar.set_message(running.join(", "));
    let on_event = |event: BatchEvent<'_>| match event {
        BatchEvent::Started(job) => {
            let mut r = running.lock().expect("progress lock");
            r.push(job.folder.clone());
            show_running(&r);
        }
        BatchEvent::Finished(o) => {
            let mut r = running.lock().expect("progress lock");
            r.retain(|f| *f != o.job.folder);
            show_running(&r);
            if let Some(line) = outcome_line(o) {
                // A hidden bar (stderr is not a terminal) prints nothing itself.
                if bar.is_hidden() {
                    eprintln!("{line}");
                } else {
                    bar.println(line);
                }
            }
            bar.inc(1);
        }
    };
    let summary = batch::run_batch(&pipeline, &file.prompts, &args.out, &options, &on_event)
        .with_context(|| {
            format!(
                "batch {} into {}",
                args.prompts.display(),
                args.out.display()
            )
        })?;
    bar.finish_and_clear();
    let count = |status| summary.jobs.iter().filter(|j| j.status == status).count();
    let (failed, busy, interrupted) = (
        count(JobStatus::Failed),
        count(JobStatus::Busy),
        count(JobStatus::Interrupted),
    );
    print_summary(&summary, &args.out);
    if interrupted > 0 {
        anyhow::bail!(
            "interrupted: {interrupted} job(s) not started; run the same command again to resume"
        );
    }
    if failed > 0 {
        anyhow::bail!("{failed} job(s) failed (see summary.json)");
    }
    if busy > 0 {
        eprintln!("note: {busy} job(s) are being run by another batch right now (lock files)");
    }
    Ok(())
}

/// `--summarize`: rebuilds summary.json from the finished folders, running no job.
fn summarize(args: &BatchArgs, prompts: &[batch::Prompt], options: &BatchOptions) -> Result<()> {
    let pipeline = args.pipeline.pipeline()?;
    let summary = batch::summarize_folder(&pipeline, prompts, &args.out, options)
        .with_context(|| format!("summarize {}", args.out.display()))?;
    print_summary(&summary, &args.out);
    Ok(())
}

/// The shard `--shard` names; one from the scheduler is said on stderr.
fn resolve_shard(spec: ShardSpec) -> Result<Shard> {
    let (shard, scheduler) = spec.resolve(batch::process_env)?;
    if let Some(scheduler) = scheduler {
        eprintln!(
            "shard {shard} from {} ({scheduler})",
            scheduler.index_variable()
        );
    }
    Ok(shard)
}

/// The final summary line and where the summary was written.
fn print_summary(summary: &BatchSummary, out: &std::path::Path) {
    let m = &summary.metrics;
    println!(
        "{}/{} scenes finished, {} accepted, {} failed; relations {}; Col-O {:.1}% Col-S {:.0}% Inst-O {:.1}% Inst-S {:.0}% Walk {:.3}; median {:.2} s/scene",
        summary.finished,
        summary.total_jobs,
        summary.accepted,
        summary.jobs.iter().filter(|j| j.status == JobStatus::Failed).count(),
        relations_text(summary.relations),
        m.col_o * 100.0,
        m.col_s * 100.0,
        m.inst_o * 100.0,
        m.inst_s * 100.0,
        m.walk,
        summary.median_seconds.unwrap_or(f64::NAN),
    );
    println!("wrote {}", out.join(batch::SUMMARY_JSON).display());
}

/// "H/S held (P %)" for stated relations, or "none stated".
fn relations_text(r: RelationsHeld) -> String {
    match r.share {
        Some(share) => format!("{}/{} held ({:.0} %)", r.held, r.stated, share * 100.0),
        None => "none stated".to_owned(),
    }
}

/// One progress line per finished job (none for jobs an interrupt kept from starting).
fn outcome_line(o: &JobOutcome) -> Option<String> {
    let line = match o.status {
        JobStatus::Skipped => format!("skip {} (already finished)", o.job.folder),
        JobStatus::Generated => format!(
            "done {} — {}, {} objects, relations {}, {:.2} s{}",
            o.job.folder,
            if o.accepted == Some(true) {
                "accepted"
            } else {
                "NOT accepted"
            },
            o.objects.unwrap_or(0),
            o.relations.map_or("n/a".to_owned(), relations_text),
            o.seconds.unwrap_or(0.0),
            o.note
                .as_deref()
                .map(|n| format!(" ({n})"))
                .unwrap_or_default()
        ),
        JobStatus::Failed => format!(
            "FAIL {}: {}",
            o.job.folder,
            o.error.as_deref().unwrap_or("unknown error")
        ),
        JobStatus::Busy => format!("busy {} (another batch is running it)", o.job.folder),
        JobStatus::Interrupted => return None,
    };
    Some(line)
}
