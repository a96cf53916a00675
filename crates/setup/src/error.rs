//! Why a pipeline could not be built.

use std::path::PathBuf;

use scenethesis_models::ProviderError;
use scenethesis_openai::ConfigError;
use scenethesis_pipeline::{AssetError, PipelineError};

/// Why a pipeline could not be built from its settings. Each message names the setting at
/// fault (with its CLI flag) and what was expected.
#[derive(Debug, thiserror::Error)]
pub enum SetupError {
    /// The asset folder could not be imported.
    #[error("importing assets: {0}")]
    Assets(#[from] AssetError),
    /// The environment variable that should hold the API key is unset or empty.
    #[error("api_key_env (--api-key-env) {var}: the environment variable {var} is not set")]
    MissingKey {
        /// The variable's name.
        var: String,
    },
    /// The model request time limit is out of range.
    #[error("llm_timeout (--llm-timeout): expected seconds in (0, 86400), found {0}")]
    Timeout(f64),
    /// The client configuration (flags, environment, `llm_config` file) is not usable.
    #[error("configuring the model provider: {0}")]
    Config(#[from] ConfigError),
    /// The model client could not be built.
    #[error("building the model client: {0}")]
    Client(#[source] Box<ProviderError>),
    /// The response cache folder could not be opened.
    #[error("opening the response cache {}: {source}", dir.display())]
    Cache {
        /// The cache folder.
        dir: PathBuf,
        /// Why not.
        #[source]
        source: Box<ProviderError>,
    },
    /// `llm_replay` without `llm_cache`.
    #[error("llm_replay (--llm-replay) needs llm_cache (--llm-cache), the folder to replay from")]
    ReplayWithoutCache,
    /// The VLM judge needs a renderer for the previews it shows the model.
    #[error("judge vlm (--judge vlm) needs a renderer for the previews it shows the model: {0}")]
    NoRenderer(String),
    /// The pipeline refused a stage.
    #[error(transparent)]
    Pipeline(Box<PipelineError>),
}

impl From<PipelineError> for SetupError {
    fn from(e: PipelineError) -> Self {
        SetupError::Pipeline(Box::new(e))
    }
}
