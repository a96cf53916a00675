//! `scenethesis roundtrip`: render a saved scene's guidance, lift it with the vision guide's
//! geometry and compare every recovered object with the scene (translation, yaw, size, IoU,
//! support parent); with `--ablation`, the optimizer's ablation against the same truth.

use std::path::PathBuf;

use anyhow::{Context, Result};
use scenethesis_experiments::ablation::ablation;
use scenethesis_experiments::roundtrip::{roundtrip, Perturbation, RoundtripOptions};
use scenethesis_pipeline::{resolve_meshes, RetrievalSource};
use scenethesis_render::BackendChoice;
use scenethesis_scene_graph::Scene;

use super::render::{open_renderer, Size};

/// Arguments of `scenethesis roundtrip`.
#[derive(Debug, clap::Args)]
pub struct RoundtripArgs {
    /// Output folder holding scene.json (or the scene.json itself).
    pub dir: PathBuf,
    /// Degrade the rendered guidance as real models would: `none` or `default` (2 % depth
    /// noise, ±7 % depth scale, masks eroded/dilated by 2 px, 10 % of masks dropped).
    /// Default: `none`, or `default` with `--ablation`.
    #[arg(long, value_enum)]
    pub perturb: Option<PerturbArg>,
    /// Measure the optimizer's ablation instead: the recovered objects posed by the raw lift,
    /// then + pose alignment (correspond stage), + collision, + stability; each row gives the
    /// median translation, yaw, scale error and 3D IoU against the scene, and Col-O / Inst-O.
    #[arg(long)]
    pub ablation: bool,
    /// Seed of the perturbation.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Guidance image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "640x480")]
    pub size: Size,
    /// Graphics backend: auto, gl or vulkan (default: `WGPU_BACKEND`, else auto).
    #[arg(long)]
    pub backend: Option<BackendChoice>,
    /// Print one JSON object (with per-category and per-object results) instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// The `--perturb` choices.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum PerturbArg {
    /// The render as is.
    None,
    /// Model-like errors in depth and masks.
    Default,
}

/// Runs the round trip and prints the result.
pub fn run(args: RoundtripArgs) -> Result<()> {
    let file = if args.dir.is_dir() {
        args.dir.join("scene.json")
    } else {
        args.dir.clone()
    };
    let scene = Scene::read_json(&file).context("cannot run the round trip")?;
    let meshes = resolve_meshes(&scene, &RetrievalSource::default())
        .with_context(|| format!("cannot rebuild the meshes of {}", file.display()))?;
    let renderer = open_renderer(args.backend)?;
    let perturb = match args.perturb {
        Some(PerturbArg::None) => Perturbation::None,
        Some(PerturbArg::Default) => Perturbation::Default,
        None if args.ablation => Perturbation::Default,
        None => Perturbation::None,
    };
    let options = RoundtripOptions {
        size: [args.size.width, args.size.height],
        perturb,
        seed: args.seed,
    };
    if args.ablation {
        let report = ablation(&renderer, &scene, &meshes, &options)
            .with_context(|| format!("ablation of {}", file.display()))?;
        if args.json {
            println!("{}", serde_json::to_string_pretty(&report)?);
            return Ok(());
        }
        println!("ablation of {} (perturbation {perturb:?})", file.display());
        println!(
            "{:<10} {:>9} {:>8} {:>8} {:>6} {:>7} {:>7}",
            "stage", "transl_m", "yaw_deg", "scale_%", "IoU", "Col-O", "Inst-O"
        );
        for r in &report.rows {
            println!(
                "{:<10} {:>9.3} {:>8.1} {:>8.1} {:>6.2} {:>6.1}% {:>6.1}%",
                serde_json::to_value(r.stage)?.as_str().unwrap_or("?"),
                r.translation_median_m,
                r.yaw_median_deg,
                r.scale_error_median * 100.0,
                r.iou_median,
                r.col_o * 100.0,
                r.inst_o * 100.0
            );
        }
        return Ok(());
    }
    let report = roundtrip(&renderer, &scene, &meshes, &options)
        .with_context(|| format!("round trip of {}", file.display()))?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    println!(
        "round trip of {} ({} objects, perturbation {:?}): {} recovered, {} missing",
        file.display(),
        report.scene_objects,
        report.perturb,
        report.objects,
        report.missing.len()
    );
    println!(
        "{:<24} {:>5} {:>9} {:>8} {:>7} {:>6} {:>7}",
        "category", "n", "transl_m", "yaw_deg", "size_%", "IoU", "parent"
    );
    for (category, s) in &report.per_category {
        println!(
            "{:<24} {:>5} {:>9.3} {:>8.1} {:>7.1} {:>6.2} {:>6.0}%",
            category,
            s.objects,
            s.translation_median_m,
            s.yaw_median_deg,
            s.size_error_median * 100.0,
            s.iou_median,
            s.parent_accuracy * 100.0
        );
    }
    println!(
        "{:<24} {:>5} {:>9.3} {:>8.1} {:>7.1} {:>6.2} {:>6.0}%",
        "all (median)",
        report.objects,
        report.translation_median_m,
        report.yaw_median_deg,
        report.size_error_median * 100.0,
        report.iou_median,
        report.parent_accuracy * 100.0
    );
    if !report.missing.is_empty() {
        println!("missing: {}", report.missing.join(", "));
    }
    Ok(())
}
