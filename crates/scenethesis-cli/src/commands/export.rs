//! `scenethesis export`: write a saved output folder in the formats other tools load.

use std::path::PathBuf;

use anyhow::{Context, Result};
use scenethesis_pipeline::{export_folder, CatalogSource, Format};

/// Arguments of `scenethesis export`.
#[derive(Debug, clap::Args)]
pub struct ExportArgs {
    /// An output folder of `scenethesis generate` (it must hold scene.json).
    pub dir: PathBuf,
    /// Formats, comma-separated or repeated: usd (OpenUSD .usda), mjcf (MuJoCo), urdf, glb.
    #[arg(long, short, value_delimiter = ',', required = true)]
    pub format: Vec<Format>,
}

/// Runs `scenethesis export`.
pub fn run(args: ExportArgs) -> Result<()> {
    let written = export_folder(&args.dir, &args.format, &CatalogSource)
        .with_context(|| format!("exporting {}", args.dir.display()))?;
    for path in written {
        println!("wrote {}", path.display());
    }
    Ok(())
}
