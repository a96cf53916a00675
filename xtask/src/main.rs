//! Developer tasks:
//!
//! - `cargo xtask ci` runs the same checks as `.ci/run` (without installing system packages);
//! - `cargo xtask bench [--json] [FILTER]` runs every crate's criterion benchmarks in release
//!   mode and prints their figures — mean time per iteration and, where a benchmark declares a
//!   throughput, elements per second — as a table or as one JSON object; it also runs the
//!   vision round trip over the benchmark prompts (`roundtrip/none`, `roundtrip/default`), the
//!   optimizer ablation against ground truth (`roundtrip/ablation`) and the content of the
//!   benchmark and kitchen scenes over seeds 0–3 (`rooms/…`: acceptance, stated relations held,
//!   functional-arrangement rules held, run layouts, category-set diversity) and batch
//!   throughput (`throughput/…`: scenes per hour per core through the CLI batch and Ray), and
//!   the density and physics of the benchmark scenes over seeds 0–2 (`density/…`: objects and
//!   small objects per scene, Col-O, Col-arch, Inst-O, Walk, Reach, acceptance) and the time of
//!   a five-room apartment with previews over seeds 0–4 (`houses/five_room_apartment`), and
//!   the seconds per benchmark scene without and with previews over seeds 0–2 (`speed/…`),
//!   and the vision path against the offline one per benchmark prompt (`vision/…`: seconds
//!   from guidance files against offline, and with a generic prompt the share of the image's
//!   objects recovered within 10 cm). Naming only those sections (`roundtrip`, `rooms`,
//!   `throughput`, `density`, `speed`, `houses`, `vision`) skips the criterion runs.

mod density;
mod houses;
mod rooms;
mod speed;
mod throughput;
mod vision;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{bail, Context, Result};
use serde_json::{json, Value};

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("ci") => ci(),
        Some("bench") => bench(&args[1..]),
        _ => {
            eprintln!(
                "usage: cargo xtask ci                    fmt --check, clippy -D warnings, tests"
            );
            eprintln!("       cargo xtask bench [--json] [FILTER] criterion benchmarks → figures");
            bail!("unknown or missing task {:?}", args.first());
        }
    }
}

fn cargo(args: &[&str]) -> Result<()> {
    let status = Command::new(env!("CARGO"))
        .args(args)
        .status()
        .with_context(|| format!("cannot run cargo {}", args.join(" ")))?;
    if !status.success() {
        bail!("cargo {} failed with {status}", args.join(" "));
    }
    Ok(())
}

fn ci() -> Result<()> {
    cargo(&["fmt", "--all", "--", "--check"])?;
    cargo(&[
        "clippy",
        "--workspace",
        "--all-targets",
        "--",
        "-D",
        "warnings",
    ])?;
    cargo(&["test", "--workspace"])
}

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives in the workspace")
        .to_owned()
}

fn bench(args: &[String]) -> Result<()> {
    let json_out = args.iter().any(|a| a == "--json");
    let filter: Vec<&str> = args
        .iter()
        .filter(|a| !a.starts_with("--"))
        .map(String::as_str)
        .collect();
    let root = workspace_root();
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target"));
    let criterion_dir = target.join("criterion");
    // Stale results of benchmarks that no longer exist must not be reported.
    if criterion_dir.exists() {
        std::fs::remove_dir_all(&criterion_dir)
            .with_context(|| format!("cannot clear {}", criterion_dir.display()))?;
    }
    let sections_only = !filter.is_empty() && filter.iter().all(|f| SECTIONS.contains(f));
    if !sections_only {
        run_criterion(&root, &filter, json_out)?;
    }
    let mut figures = collect_figures(&criterion_dir)?;
    add_end_to_end_median(&mut figures);
    if filter.is_empty() || filter.iter().any(|f| "roundtrip".contains(f)) {
        add_roundtrip(&root, &target, json_out, &mut figures)?;
    }
    if filter.is_empty() || filter.iter().any(|f| "rooms".contains(f)) {
        rooms::add_rooms(&root, &target, json_out, &mut figures)?;
    }
    if filter.is_empty() || filter.contains(&"density") {
        density::add_density(&root, &target, json_out, &mut figures)?;
    }
    if filter.is_empty() || filter.contains(&"speed") {
        speed::add_speed(&root, &target, json_out, &mut figures)?;
    }
    if filter.is_empty() || filter.contains(&"houses") {
        houses::add_houses(&root, &target, json_out, &mut figures)?;
    }
    if filter.is_empty() || filter.contains(&"vision") {
        vision::add_vision(&root, &target, json_out, &mut figures)?;
    }
    if filter.is_empty() || filter.contains(&"throughput") {
        let exe = release_cli(&root, &target, json_out)?;
        throughput::add_throughput(&root, &target, &exe, &mut figures)?;
    }
    if json_out {
        println!(
            "{}",
            serde_json::to_string_pretty(&Value::Object(figures.into_iter().collect()))?
        );
    } else {
        for (name, value) in &figures {
            println!("{name:<60} {value}");
        }
    }
    Ok(())
}

/// The sections `bench` runs itself (not through criterion).
const SECTIONS: [&str; 7] = [
    "roundtrip",
    "rooms",
    "throughput",
    "density",
    "speed",
    "houses",
    "vision",
];

/// Runs every crate's criterion benchmarks in release mode (bench targets only), filtered.
fn run_criterion(root: &Path, filter: &[&str], json_out: bool) -> Result<()> {
    let mut cmd = Command::new(env!("CARGO"));
    cmd.current_dir(root)
        // Bench targets only: library test harnesses would reject criterion's flags.
        .args(["bench", "--workspace", "--bench", "*", "--quiet", "--"]);
    cmd.args(filter);
    cmd.arg("--noplot");
    if json_out {
        // Keep stdout for the JSON object alone.
        cmd.stdout(std::process::Stdio::null());
    }
    let status = cmd.status().context("cannot run cargo bench")?;
    if !status.success() {
        bail!("cargo bench failed with {status}");
    }
    Ok(())
}

/// The vision round trip over the benchmark prompts (`fixtures/prompts/benchmark.txt`, seed 0):
/// each prompt is generated with the release binary (no previews), then `scenethesis roundtrip
/// --json` runs unperturbed and with the default perturbation. Adds `roundtrip/none` and
/// `roundtrip/default`: the median over prompts of each scene's median errors, the mean
/// parent accuracy, and object counts. Adds `roundtrip/ablation`: `scenethesis roundtrip
/// --ablation --perturb default --json` per prompt, each stage's (raw, alignment, collision,
/// stability) median over prompts of the scene medians and mean over prompts of Col-O / Inst-O.
fn add_roundtrip(
    root: &Path,
    target: &Path,
    json_out: bool,
    figures: &mut BTreeMap<String, Value>,
) -> Result<()> {
    let exe = release_cli(root, target, json_out)?;
    let prompts_text = benchmark_prompts(root)?;
    let prompts = prompt_lines(&prompts_text);
    let scratch = fresh_scratch(target, "xtask-roundtrip")?;
    let mut rows: BTreeMap<&str, Vec<Value>> = BTreeMap::new();
    let mut ablations: Vec<Value> = Vec::new();
    for (k, prompt) in prompts.iter().enumerate() {
        let dir = scratch.join(format!("p{k:02}"));
        generate(&exe, prompt, 0, &dir)?;
        for perturb in ["none", "default"] {
            let out = Command::new(&exe)
                .arg("roundtrip")
                .arg(&dir)
                .args(["--perturb", perturb, "--json"])
                .output()
                .context("cannot run scenethesis roundtrip")?;
            if !out.status.success() {
                bail!(
                    "roundtrip of {prompt:?} failed: {}",
                    String::from_utf8_lossy(&out.stderr)
                );
            }
            rows.entry(perturb)
                .or_default()
                .push(serde_json::from_slice(&out.stdout)?);
        }
        let out = Command::new(&exe)
            .arg("roundtrip")
            .arg(&dir)
            .args(["--ablation", "--perturb", "default", "--json"])
            .output()
            .context("cannot run scenethesis roundtrip --ablation")?;
        if !out.status.success() {
            bail!(
                "ablation of {prompt:?} failed: {}",
                String::from_utf8_lossy(&out.stderr)
            );
        }
        ablations.push(serde_json::from_slice(&out.stdout)?);
    }
    for (perturb, reports) in rows {
        let field =
            |name: &str| -> Vec<f64> { reports.iter().filter_map(|r| r[name].as_f64()).collect() };
        let parent = field("parent_accuracy");
        figures.insert(
            format!("roundtrip/{perturb}"),
            json!({
                "prompts": reports.len(),
                "objects": reports.iter().filter_map(|r| r["objects"].as_u64()).sum::<u64>(),
                "missing": reports.iter().filter_map(|r| r["missing"].as_array().map(Vec::len)).sum::<usize>(),
                "translation_median_m": median(field("translation_median_m")),
                "yaw_median_deg": median(field("yaw_median_deg")),
                "size_error_median": median(field("size_error_median")),
                "iou_median": median(field("iou_median")),
                "parent_accuracy": parent.iter().sum::<f64>() / parent.len().max(1) as f64,
            }),
        );
    }
    // The ablation: per stage, the median over prompts of each scene's medians, and the mean
    // over prompts of Col-O and Inst-O.
    let mut ablation_rows = Vec::new();
    for stage in ["raw", "alignment", "collision", "stability"] {
        let reports: Vec<&Value> = ablations
            .iter()
            .filter_map(|a| {
                a["rows"]
                    .as_array()?
                    .iter()
                    .find(|r| r["stage"].as_str() == Some(stage))
            })
            .collect();
        let field =
            |name: &str| -> Vec<f64> { reports.iter().filter_map(|r| r[name].as_f64()).collect() };
        let mean = |v: Vec<f64>| v.iter().sum::<f64>() / v.len().max(1) as f64;
        ablation_rows.push(json!({
            "stage": stage,
            "translation_median_m": median(field("translation_median_m")),
            "yaw_median_deg": median(field("yaw_median_deg")),
            "scale_error_median": median(field("scale_error_median")),
            "iou_median": median(field("iou_median")),
            "col_o": mean(field("col_o")),
            "inst_o": mean(field("inst_o")),
        }));
    }
    figures.insert(
        "roundtrip/ablation".to_owned(),
        json!({ "prompts": ablations.len(), "rows": ablation_rows }),
    );
    Ok(())
}

/// Builds the release `scenethesis` binary and returns its path.
fn release_cli(root: &Path, target: &Path, json_out: bool) -> Result<PathBuf> {
    let mut build = Command::new(env!("CARGO"));
    build
        .current_dir(root)
        .args(["build", "--release", "--quiet", "-p", "scenethesis-cli"]);
    if json_out {
        build.stdout(std::process::Stdio::null());
    }
    if !build
        .status()
        .context("cannot build scenethesis")?
        .success()
    {
        bail!("building scenethesis failed");
    }
    Ok(target.join("release").join("scenethesis"))
}

/// An empty scratch folder `name` under `target` for one bench section's scenes: whatever an
/// earlier run left there is removed first.
fn fresh_scratch(target: &Path, name: &str) -> Result<PathBuf> {
    let scratch = target.join(name);
    let _ = std::fs::remove_dir_all(&scratch);
    std::fs::create_dir_all(&scratch)?;
    Ok(scratch)
}

/// The text of `fixtures/prompts/benchmark.txt`.
fn benchmark_prompts(root: &Path) -> Result<String> {
    let prompts_file = root.join("fixtures/prompts/benchmark.txt");
    std::fs::read_to_string(&prompts_file)
        .with_context(|| format!("cannot read {}", prompts_file.display()))
}

/// The prompts of a prompts file: non-empty lines that are not `#` comments.
fn prompt_lines(text: &str) -> Vec<&str> {
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .collect()
}

/// `scenethesis generate PROMPT --seed SEED --no-preview --out DIR`; an unaccepted scene is
/// still a result (its folder is written), a run that writes no scene is an error.
fn generate(exe: &Path, prompt: &str, seed: u64, dir: &Path) -> Result<()> {
    run_generate(exe, prompt, seed, false, dir)
}

/// `scenethesis generate PROMPT --seed SEED [--no-preview] --out DIR`, as [`generate`] but
/// with previews when `previews` is set.
fn run_generate(exe: &Path, prompt: &str, seed: u64, previews: bool, dir: &Path) -> Result<()> {
    let mut command = Command::new(exe);
    command
        .arg("generate")
        .arg(prompt)
        .args(["--seed", &seed.to_string()]);
    if !previews {
        command.arg("--no-preview");
    }
    let out = command
        .arg("--out")
        .arg(dir)
        .output()
        .context("cannot run scenethesis generate")?;
    if !out.status.success() && !dir.join("scene.json").exists() {
        bail!(
            "generate {prompt:?} (seed {seed}) failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    Ok(())
}

/// The median of the finite values (NaN when there are none).
fn median(mut v: Vec<f64>) -> f64 {
    v.retain(|x| x.is_finite());
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

/// Group of the end-to-end benchmark (one function per prompt) in `crates/pipeline`.
const END_TO_END: &str = "end_to_end/";

/// Adds seconds to every end-to-end figure and one `end_to_end/median` figure: the median over
/// prompts of the mean seconds per generated scene (the target is under 2 s).
fn add_end_to_end_median(figures: &mut BTreeMap<String, Value>) {
    let mut seconds: Vec<f64> = Vec::new();
    for (name, value) in figures.iter_mut() {
        if let (true, Some(ms)) = (name.starts_with(END_TO_END), value["mean_ms"].as_f64()) {
            value["seconds"] = json!(ms / 1e3);
            seconds.push(ms / 1e3);
        }
    }
    if seconds.is_empty() {
        return;
    }
    seconds.sort_by(f64::total_cmp);
    let n = seconds.len();
    let median = if n % 2 == 1 {
        seconds[n / 2]
    } else {
        (seconds[n / 2 - 1] + seconds[n / 2]) / 2.0
    };
    figures.insert(
        format!("{END_TO_END}median"),
        json!({ "seconds": median, "prompts": n, "max_seconds": seconds[n - 1] }),
    );
}

/// Reads every `new/benchmark.json` + `new/estimates.json` pair under criterion's output folder.
fn collect_figures(dir: &Path) -> Result<BTreeMap<String, Value>> {
    let mut figures = BTreeMap::new();
    let mut stack = vec![dir.to_owned()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                if path.file_name().is_some_and(|n| n == "new") {
                    if let Some((name, value)) = read_benchmark(&path)? {
                        figures.insert(name, value);
                    }
                } else {
                    stack.push(path);
                }
            }
        }
    }
    Ok(figures)
}

fn read_benchmark(new_dir: &Path) -> Result<Option<(String, Value)>> {
    let (bench, estimates) = (
        new_dir.join("benchmark.json"),
        new_dir.join("estimates.json"),
    );
    if !bench.exists() || !estimates.exists() {
        return Ok(None);
    }
    let bench: Value = serde_json::from_str(&std::fs::read_to_string(&bench)?)?;
    let estimates: Value = serde_json::from_str(&std::fs::read_to_string(&estimates)?)?;
    let name = bench["full_id"].as_str().unwrap_or("unnamed").to_owned();
    let mean_ns = estimates["mean"]["point_estimate"]
        .as_f64()
        .unwrap_or(f64::NAN);
    let mut value = json!({ "mean_ms": mean_ns / 1e6 });
    if let Some(elements) = bench["throughput"]["Elements"].as_f64() {
        value["elements_per_s"] = json!(elements / (mean_ns / 1e9));
    }
    Ok(Some((name, value)))
}
