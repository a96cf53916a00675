//! Clients for OpenAI-compatible endpoints (OpenAI, vLLM, Ollama, llama.cpp, LM Studio,
//! LocalAI, stable-diffusion.cpp), implementing the provider traits of
//! [`scenethesis_models`]: [`OpenAiChat`] ([`ChatModel`](scenethesis_models::ChatModel), text
//! and image parts, structured output with format fallback, local validation and one repair
//! round), [`OpenAiImages`] ([`ImageGenerator`](scenethesis_models::ImageGenerator):
//! generations and multipart edits, `b64_json` or `url` answers) and [`OpenAiEmbedder`]
//! ([`TextEmbedder`](scenethesis_models::TextEmbedder), the one embedder trait retrieval uses too).
//!
//! This is the workspace's only crate with HTTP. Its methods are synchronous: each client
//! drives reqwest on a private current-thread tokio runtime, so callers need no async runtime
//! (and must not call it from inside one). Configuration comes from flags over environment
//! (`OPENAI_BASE_URL`, `OPENAI_API_KEY`, `SCENETHESIS_LLM_MODEL`, `SCENETHESIS_VLM_MODEL`,
//! `SCENETHESIS_IMAGE_MODEL`, `SCENETHESIS_EMBEDDING_MODEL`) over a TOML file
//! ([`ClientConfig::resolve`]). The API key never appears in `Debug` output, errors or logs.
//! Requests time out, transient failures (429, 5xx, refused connections, timeouts) are
//! retried with exponential backoff or the server's `Retry-After`, within a total budget, and
//! every error names the endpoint and the model.
//!
//! ```
//! use scenethesis_openai::{ClientConfig, OpenAiClient, Overrides};
//!
//! // Flags win over the environment (here a stand-in for the process environment).
//! let env = |name: &str| match name {
//!     "OPENAI_BASE_URL" => Some("http://127.0.0.1:11434/v1".to_string()),
//!     "OPENAI_API_KEY" => Some("sk-example-key".to_string()),
//!     "SCENETHESIS_LLM_MODEL" => Some("qwen2.5:7b".to_string()),
//!     _ => None,
//! };
//! let flags = Overrides { llm_model: Some("llama3.1:8b".into()), ..Overrides::default() };
//! let config = ClientConfig::resolve_with(&flags, &env, None)?;
//! assert_eq!(config.require_llm()?, "llama3.1:8b");
//! assert!(!format!("{config:?}").contains("sk-example-key"));
//!
//! // Building clients contacts no server.
//! let client = OpenAiClient::new(config)?;
//! assert_eq!(client.llm()?.model(), "llama3.1:8b");
//! assert!(client.image_model().is_err(), "no image model configured");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]

mod chat;
mod config;
mod embed;
mod http;
mod images;
mod mask;
mod message;
mod stream;
#[cfg(feature = "test-server")]
pub mod testing;

use std::sync::Arc;

pub use chat::{OpenAiChat, OutputFormat};
pub use config::{
    redact_url, ApiKey, ClientConfig, ConfigError, Overrides, ServerKind, DEFAULT_BASE_URL,
    ENV_API_KEY, ENV_BASE_URL, ENV_EMBEDDING_MODEL, ENV_IMAGE_MODEL, ENV_LLM_MODEL, ENV_SERVER,
    ENV_VLM_MODEL, MAX_CONFIG_BYTES,
};
pub use embed::OpenAiEmbedder;
pub use http::MAX_RESPONSE_BYTES;
pub use images::OpenAiImages;
pub use mask::{min_masked_run, MIN_RESHAPED_KEY_CHARS};
use scenethesis_models::ProviderError;
pub use stream::STREAM_MIN_TOKENS;

/// A connection to one OpenAI-compatible endpoint; hands out model clients that share it.
#[derive(Debug, Clone)]
pub struct OpenAiClient {
    transport: Arc<http::Transport>,
}

impl OpenAiClient {
    /// A client for `config` (builds the HTTP client; does not contact the server).
    pub fn new(config: ClientConfig) -> Result<Self, ProviderError> {
        Ok(Self {
            transport: Arc::new(http::Transport::new(config)?),
        })
    }

    /// The configuration.
    pub fn config(&self) -> &ClientConfig {
        self.transport.config()
    }

    /// A chat model by name.
    pub fn chat(&self, model: impl Into<String>) -> OpenAiChat {
        OpenAiChat::new(Arc::clone(&self.transport), model.into())
    }

    /// The configured language model.
    pub fn llm(&self) -> Result<OpenAiChat, ConfigError> {
        Ok(self.chat(self.config().require_llm()?))
    }

    /// The configured vision-language model (the language model when none is set).
    pub fn vlm(&self) -> Result<OpenAiChat, ConfigError> {
        Ok(self.chat(self.config().require_vlm()?))
    }

    /// An image model by name.
    pub fn images(&self, model: impl Into<String>) -> OpenAiImages {
        OpenAiImages::new(Arc::clone(&self.transport), model.into())
    }

    /// The configured image model.
    pub fn image_model(&self) -> Result<OpenAiImages, ConfigError> {
        Ok(self.images(self.config().require_image()?))
    }

    /// An embedding model by name.
    pub fn embedder(&self, model: impl Into<String>) -> OpenAiEmbedder {
        OpenAiEmbedder::new(Arc::clone(&self.transport), model.into())
    }

    /// The configured embedding model.
    pub fn embedding_model(&self) -> Result<OpenAiEmbedder, ConfigError> {
        Ok(self.embedder(self.config().require_embedding()?))
    }
}
