//! `scenethesis`: the thin command-line front end. Each subcommand parses its arguments, calls
//! into the library crates and reports; no pipeline logic lives here.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use clap::{Parser, Subcommand};

mod commands;
mod interrupt;

/// Text to simulation-ready 3D scenes.
#[derive(Debug, Parser)]
#[command(name = "scenethesis", version, about, long_about = None)]
struct Cli {
    /// More log output (-v info, -vv debug, -vvv trace); `RUST_LOG` overrides.
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    verbose: u8,
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Generate a simulation-ready scene from a prompt (offline by default): scene.glb,
    /// scene.json, previews and report.json in the output folder.
    Generate(commands::generate::GenerateArgs),
    /// Plan a prompt without building it: writes the editable plan (objects, anchor, supports,
    /// relations, room) as JSON; `generate --plan` builds a scene from it.
    Plan(commands::plan::PlanArgs),
    /// Export a generated folder to another format (usd, mjcf, urdf, glb).
    Export(commands::export::ExportArgs),
    /// Generate many prompts × seeds into one folder each; resumable and shardable.
    Batch(commands::batch::BatchArgs),
    /// Inspect the built-in procedural asset library (`assets list`).
    Assets {
        #[command(subcommand)]
        command: commands::assets::AssetsCommand,
    },
    /// Measure a scene (output folder, scene.json or any .glb): collision, stability, Walk,
    /// Reach and content, as a table (goals from metrics.md) or one JSON object.
    Eval {
        /// An output folder, a scene.json, or a .glb / .gltf scene.
        path: PathBuf,
        /// Print one JSON object instead of the table.
        #[arg(long)]
        json: bool,
    },
    /// Check a scene.json: schema, ids, parents, relations, numbers; prints the BFS order.
    Validate {
        /// Path of a scene.json file, or of an output folder holding one.
        path: PathBuf,
    },
    /// Render an output folder's previews: preview.png, preview_top.png and view_K.png.
    Render(commands::render::RenderArgs),
    /// Render a saved scene's guidance, lift it back to 3D boxes with the vision guide's
    /// geometry and compare each recovered object with the scene.
    Roundtrip(commands::roundtrip::RoundtripArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    init_logging(cli.verbose);
    // The texture maps a run generates are the same bytes every time: keep them for the next.
    scenethesis_materials::keep_maps_in(scenethesis_materials::default_maps_folder());
    match run(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => {
            for (k, line) in error_lines(&err).iter().enumerate() {
                if k == 0 {
                    eprintln!("error: {line}");
                } else {
                    eprintln!("  caused by: {line}");
                }
            }
            ExitCode::FAILURE
        }
    }
}

/// The lines to print for an error chain: each cause once, leaving out a cause whose text the
/// messages printed before it already contain (many errors quote their source), with control
/// characters escaped so that no id or file content can drive the terminal.
fn error_lines(err: &anyhow::Error) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for cause in err.chain() {
        let text = cause.to_string();
        let text = text.trim();
        if text.is_empty() || lines.iter().any(|l| l.contains(text)) {
            continue;
        }
        lines.push(scenethesis_scene_graph::printable(text).into_owned());
    }
    lines
}

fn init_logging(verbose: u8) {
    let default = match verbose {
        0 => "warn",
        1 => "info",
        2 => "debug",
        _ => "trace",
    };
    let filter = tracing_subscriber::EnvFilter::try_from_default_env()
        .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new(default));
    tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr()))
        .with_writer(std::io::stderr)
        .with_target(false)
        .init();
}

fn run(command: Command) -> Result<()> {
    match command {
        Command::Generate(args) => commands::generate::run(args),
        Command::Plan(args) => commands::plan::run(args),
        Command::Export(args) => commands::export::run(args),
        Command::Batch(args) => commands::batch::run(args),
        Command::Assets { command } => commands::assets::run(command),
        Command::Eval { path, json } => commands::eval::run(path, json),
        Command::Validate { path } => commands::validate::run(path),
        Command::Render(args) => commands::render::run(args),
        Command::Roundtrip(args) => commands::roundtrip::run(args),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn error_chains_print_each_cause_once_and_escaped() {
        let io = std::io::Error::other("disk full");
        let err = anyhow::Error::new(io)
            .context("cannot write /x/scene.json: disk full")
            .context("generation failed\x1b[31m");
        let lines = error_lines(&err);
        assert_eq!(
            lines,
            vec![
                "generation failed\\u{1b}[31m".to_owned(),
                "cannot write /x/scene.json: disk full".to_owned()
            ]
        );
    }
}
