//! `scenethesis export`: write a saved output folder in the formats other tools load.

use std::path::PathBuf;

use anyhow::{Context, Result};
use scenethesis_pipeline::{export_folder, Format, RetrievalSource};

/// Arguments of `scenethesis export`.
#[derive(Debug, clap::Args)]
pub struct ExportArgs {
    /// An output folder of `scenethesis generate` (it must hold scene.json).
    pub dir: PathBuf,
    /// Formats, comma-separated or repeated: usd (OpenUSD .usda), mjcf (MuJoCo), urdf, glb.
    #[arg(long, short, value_delimiter = ',', required = true)]
    pub format: Vec<Format>,
    /// The bring-your-own asset folder the scene was generated with, if it has moved since
    /// (by default imported assets are re-read from the paths stored in scene.json).
    #[arg(long, value_name = "DIR")]
    pub assets: Option<PathBuf>,
}

/// Runs `scenethesis export`.
pub fn run(args: ExportArgs) -> Result<()> {
    let source = match &args.assets {
        Some(dir) => {
            let (source, warnings) = RetrievalSource::from_directory(dir)
                .with_context(|| format!("importing assets from {}", dir.display()))?;
            for warning in &warnings {
                eprintln!("warning: {warning}");
            }
            source
        }
        None => RetrievalSource::default(),
    };
    let written = export_folder(&args.dir, &args.format, &source)
        .with_context(|| format!("exporting {}", args.dir.display()))?;
    for path in written {
        println!("wrote {}", path.display());
    }
    Ok(())
}
