//! `scenethesis batch`: many prompts × seeds, one folder each, resumable and shardable.

use std::path::PathBuf;

use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use scenethesis_pipeline::batch::{self, BatchOptions, JobOutcome, JobStatus, Shard};

/// Arguments of `scenethesis batch`.
#[derive(Debug, clap::Args)]
pub struct BatchArgs {
    /// A text file with one prompt per line (blank lines and `#` comments skipped).
    pub prompts: PathBuf,
    /// Output folder: one sub-folder per prompt and seed, plus summary.json.
    #[arg(long)]
    pub out: PathBuf,
    /// Scenes generated at the same time.
    #[arg(long, default_value_t = 1)]
    pub jobs: usize,
    /// Run only shard I of N (0-based), e.g. `--shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT`
    /// or `--shard $JOB_COMPLETION_INDEX/N` in a Kubernetes indexed job.
    #[arg(long, default_value = "0/1")]
    pub shard: Shard,
    /// Seeds per prompt (seed, seed + 1, …).
    #[arg(long, default_value_t = 1)]
    pub seeds: u64,
    /// The first seed.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Pipeline options shared with `generate`.
    #[command(flatten)]
    pub pipeline: super::generate::PipelineArgs,
}

/// Runs `scenethesis batch`.
pub fn run(args: BatchArgs) -> Result<()> {
    let prompts = batch::read_prompts(&args.prompts)?;
    let options = BatchOptions {
        jobs: args.jobs,
        shard: args.shard,
        seeds: args.seeds,
        base_seed: args.seed,
        generate: args.pipeline.options(),
    };
    let all = batch::jobs(&prompts, options.seeds, options.base_seed);
    let mine = all
        .iter()
        .filter(|j| options.shard.contains(j.position))
        .count();
    let pipeline = args.pipeline.pipeline()?;
    let bar = ProgressBar::new(mine as u64);
    bar.set_style(
        ProgressStyle::with_template("{bar:30.cyan/blue} {pos}/{len} scenes {elapsed} (eta {eta})")
            .expect("valid template"),
    );
    let on_done = |o: &JobOutcome| {
        let line = match o.status {
            JobStatus::Skipped => format!("skip {} (already finished)", o.job.folder),
            JobStatus::Generated => format!(
                "done {} — {}, {} objects, {:.2} s",
                o.job.folder,
                if o.accepted == Some(true) {
                    "accepted"
                } else {
                    "NOT accepted"
                },
                o.objects.unwrap_or(0),
                o.seconds.unwrap_or(0.0)
            ),
            JobStatus::Failed => format!(
                "FAIL {}: {}",
                o.job.folder,
                o.error.as_deref().unwrap_or("unknown error")
            ),
        };
        bar.println(line);
        bar.inc(1);
    };
    let summary = batch::run_batch(&pipeline, &prompts, &args.out, &options, &on_done)
        .with_context(|| {
            format!(
                "batch {} into {}",
                args.prompts.display(),
                args.out.display()
            )
        })?;
    bar.finish_and_clear();
    let failed = summary
        .jobs
        .iter()
        .filter(|j| j.status == JobStatus::Failed)
        .count();
    let m = &summary.metrics;
    println!(
        "{}/{} scenes finished, {} accepted, {failed} failed; Col-O {:.1}% Col-S {:.0}% Inst-O {:.1}% Inst-S {:.0}% Walk {:.3}; median {:.2} s/scene",
        summary.finished,
        summary.total_jobs,
        summary.accepted,
        m.col_o * 100.0,
        m.col_s * 100.0,
        m.inst_o * 100.0,
        m.inst_s * 100.0,
        m.walk,
        summary.median_seconds.unwrap_or(f64::NAN),
    );
    println!("wrote {}", args.out.join("summary.json").display());
    if failed > 0 {
        anyhow::bail!("{failed} job(s) failed (see summary.json)");
    }
    Ok(())
}
