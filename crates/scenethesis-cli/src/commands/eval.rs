//! `scenethesis eval`: the physical-plausibility and interactivity metrics of one scene.

use std::path::PathBuf;

use anyhow::{Context, Result};

/// Evaluates `path` (an output folder, a scene.json, or any .glb scene) and prints a table, or
/// one JSON object with `json`.
pub fn run(path: PathBuf, json: bool) -> Result<()> {
    tracing::info!(path = %path.display(), "evaluating");
    let scene = scenethesis_eval::load_path(&path)
        .with_context(|| format!("cannot load {} for evaluation", path.display()))?;
    let metrics = scenethesis_eval::evaluate(&scene);
    if json {
        println!(
            "{}",
            serde_json::to_string_pretty(&metrics).context("cannot serialize the metrics")?
        );
    } else {
        println!("{}: {} objects", path.display(), metrics.objects);
        print!("{}", metrics.to_table());
    }
    Ok(())
}
