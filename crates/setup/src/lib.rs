//! Builds a [`Pipeline`] from the settings a user gives: which planner and judge run, how the
//! OpenAI-compatible models behind them are reached, recorded and replayed, which asset folder
//! is imported and whether previews are rendered.
//!
//! The CLI's flags and the Python package's keyword arguments both fill a [`PipelineSettings`]
//! and call [`PipelineSettings::build`], so the same settings give the same pipeline (and, for
//! the same prompt and seed, byte-identical scenes) from either front end.
//!
//! The offline default (knowledge planner, geometric judge) reads no configuration and needs no
//! key:
//!
//! ```
//! use scenethesis_setup::PipelineSettings;
//! let settings = PipelineSettings { previews: false, ..PipelineSettings::default() };
//! let built = settings.build().unwrap();
//! assert_eq!(built.pipeline.planner_name(), "knowledge");
//! assert!(built.warnings.is_empty());
//! ```

#![warn(missing_docs)]

mod error;
mod providers;

use std::path::PathBuf;

pub use error::SetupError;
pub use providers::{JudgeChoice, PlannerChoice, ProviderSettings};
use scenethesis_pipeline::{Pipeline, RetrievalSource};

/// Everything a front end says about how to build the pipeline.
#[derive(Debug, Clone)]
pub struct PipelineSettings {
    /// Render preview images (when a renderer can be opened; otherwise a warning is returned).
    pub previews: bool,
    /// A bring-your-own asset folder (GLB/glTF/OBJ plus an optional `assets.json`), preferred
    /// over the built-in generators of its categories.
    pub assets: Option<PathBuf>,
    /// Planner, judge and model provider selection.
    pub providers: ProviderSettings,
}

impl Default for PipelineSettings {
    /// The offline default: previews on, no asset folder, knowledge planner, geometric judge.
    fn default() -> Self {
        Self {
            previews: true,
            assets: None,
            providers: ProviderSettings::default(),
        }
    }
}

/// A built pipeline and what the front end should tell the user about how it was built.
#[derive(Debug)]
pub struct BuiltPipeline {
    /// The pipeline.
    pub pipeline: Pipeline,
    /// Things worth a warning that did not stop the build: asset files skipped on import,
    /// previews turned off because no renderer could be opened.
    pub warnings: Vec<String>,
    /// Things worth a note: how many assets were imported from where.
    pub notes: Vec<String>,
}

impl PipelineSettings {
    /// Builds the offline pipeline over the built-in library plus the asset folder, with
    /// previews when a renderer can be opened, then installs the planner and judge the provider
    /// settings select.
    pub fn build(&self) -> Result<BuiltPipeline, SetupError> {
        let mut built = BuiltPipeline {
            pipeline: Pipeline::offline(),
            warnings: Vec::new(),
            notes: Vec::new(),
        };
        if let Some(dir) = &self.assets {
            let (source, warnings) = RetrievalSource::from_directory(dir)?;
            built
                .warnings
                .extend(warnings.iter().map(|w| w.to_string()));
            built.notes.push(format!(
                "imported {} assets from {}",
                source.imported_count(),
                dir.display()
            ));
            built.pipeline = built.pipeline.with_assets(source);
        }
        if self.previews {
            match scenethesis_render::Renderer::from_env() {
                Ok(renderer) => built.pipeline = built.pipeline.with_renderer(renderer),
                Err(e) => built
                    .warnings
                    .push(format!("no previews: cannot open a renderer ({e})")),
            }
        }
        built.pipeline = self.providers.apply(built.pipeline)?;
        Ok(built)
    }
}
