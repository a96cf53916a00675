//! `scenethesis assets`: inspect the built-in procedural asset library.

use std::io::{self, Write};

use anyhow::{Context, Result};
use clap::Subcommand;
use scenethesis_procedural::catalog;
use scenethesis_scene_graph::Placement;

/// The `assets` subcommands.
#[derive(Debug, Subcommand)]
pub enum AssetsCommand {
    /// List every built-in category: placement, typical size W×H×D in metres (the asset of
    /// `--seed`), documented size range, number of support surfaces, synonyms.
    List {
        /// Print a JSON array instead of a table.
        #[arg(long)]
        json: bool,
        /// Seed of the example asset whose size and surfaces are shown.
        #[arg(long, default_value_t = 0)]
        seed: u64,
    },
    /// Render a contact sheet of several seeds of one category: a grid of photo views on a
    /// neutral floor, each labelled with its seed.
    Sheet(super::render::SheetArgs),
}

/// Runs an `assets` subcommand.
pub fn run(command: AssetsCommand) -> Result<()> {
    match command {
        AssetsCommand::Sheet(args) => super::render::run_sheet(args),
        AssetsCommand::List { json, seed } => {
            let out = if json {
                list_json(seed)?
            } else {
                list_table(seed)
            };
            let mut stdout = io::stdout().lock();
            match stdout
                .write_all(out.as_bytes())
                .and_then(|_| stdout.flush())
            {
                // A closed pipe (`| head`) is not an error worth reporting.
                Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Ok(()),
                other => other.context("cannot write the category list to stdout"),
            }
        }
    }
}

fn placement_name(p: Placement) -> &'static str {
    match p {
        Placement::Floor => "floor",
        Placement::Wall => "wall",
        Placement::Surface => "surface",
        Placement::Ceiling => "ceiling",
    }
}

fn list_table(seed: u64) -> String {
    let mut out = format!(
        "{:<18} {:<9} {:<20} {:>8}  synonyms\n",
        "category", "placement", "size W×H×D (m)", "surfaces"
    );
    let mut count = 0;
    for c in catalog::categories() {
        let asset = catalog::generate(c, seed);
        let [w, h, d] = asset.info.size;
        out.push_str(&format!(
            "{:<18} {:<9} {:<20} {:>8}  {}\n",
            c.name,
            placement_name(c.placement),
            format!("{w:.2}×{h:.2}×{d:.2}"),
            asset.info.support_surfaces.len(),
            c.synonyms.join(", ")
        ));
        count += 1;
    }
    out.push_str(&format!("{count} categories (sizes of seed {seed})\n"));
    out
}

fn list_json(seed: u64) -> Result<String> {
    let rows: Vec<serde_json::Value> = catalog::categories()
        .map(|c| {
            let asset = catalog::generate(c, seed);
            serde_json::json!({
                "name": c.name,
                "placement": placement_name(c.placement),
                "size": asset.info.size,
                "size_range": c.size_range,
                "support_surfaces": asset.info.support_surfaces.iter().map(|s| &s.name).collect::<Vec<_>>(),
                "synonyms": c.synonyms,
                "triangles": asset.mesh.triangle_count(),
            })
        })
        .collect();
    let mut text =
        serde_json::to_string_pretty(&rows).context("cannot serialise the category list")?;
    text.push('\n');
    Ok(text)
}
