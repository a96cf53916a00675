//! `scenethesis plan`: a prompt in, the editable plan (`plan.json`) out.

use std::path::PathBuf;

use anyhow::{Context, Result};
use scenethesis_pipeline::write_plan;

use crate::commands::generate::PipelineArgs;
use crate::commands::providers::ProviderArgs;

/// Arguments of `scenethesis plan`.
#[derive(Debug, clap::Args)]
pub struct PlanArgs {
    /// What to plan, e.g. "a bedroom with a desk".
    pub prompt: String,
    /// The plan file to write (JSON, see docs/plan.md); written atomically.
    #[arg(long)]
    pub out: PathBuf,
    /// Replace --out when it already exists.
    #[arg(long)]
    pub force: bool,
    /// Seed: the same prompt and seed give the same plan (and `generate` with the same seed
    /// starts from it).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Bring your own assets: their categories are offered to the planner, as in `generate`.
    #[arg(long, value_name = "DIR")]
    pub assets: Option<PathBuf>,
    /// Model providers (`--planner llm` plans with a chat model; see "Using an LLM").
    #[command(flatten)]
    pub providers: ProviderArgs,
}

/// Runs `scenethesis plan`.
pub fn run(args: PlanArgs) -> Result<()> {
    let pipeline = PipelineArgs {
        max_replans: 0,
        no_preview: true,
        time_limit: 0.0,
        open_state: Default::default(),
        assets: args.assets.clone(),
        providers: args.providers.clone(),
    }
    .pipeline()?;
    let plan = pipeline
        .plan(&args.prompt, args.seed)
        .with_context(|| format!("planning \"{}\"", args.prompt))?;
    write_plan(&args.out, &plan, args.force)?;
    println!(
        "wrote {}: {} ({} objects, anchor `{}`)",
        args.out.display(),
        plan.scene_type,
        plan.objects.len(),
        plan.anchor
    );
    Ok(())
}
