//! Provider flags shared by `generate`, `plan` and `batch`: which planner and judge a run uses,
//! and how the OpenAI-compatible models behind them are reached, recorded and replayed. The
//! flags fill the library's [`ProviderSettings`] (`scenethesis-setup`), which builds them.
//!
//! The offline default (knowledge planner, geometric judge) reads no configuration and needs
//! no key; only `--planner llm`, `--judge vlm` or `--online` resolve a client configuration
//! (flags over environment over `--llm-config`).

use std::path::PathBuf;

use anyhow::Result;
use scenethesis_models::{ChatModel, ImageGenerator};
use scenethesis_openai::{OpenAiChat, OpenAiClient, OpenAiImages};
use scenethesis_setup::{self as setup, ProviderSettings};

/// Which planner turns the prompt into a plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum PlannerChoice {
    /// The built-in offline knowledge planner (the default).
    Knowledge,
    /// A chat model behind an OpenAI-compatible endpoint.
    Llm,
}

/// Which judge accepts or rejects a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum JudgeChoice {
    /// The offline geometric judge (the default).
    Geometric,
    /// The geometric judge, then a vision-language model looking at rendered previews.
    Vlm,
}

/// The provider flags of `generate` and `batch`.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct ProviderArgs {
    /// The planner: `knowledge` (offline, default) or `llm` (a chat model).
    #[arg(long, value_enum, value_name = "PLANNER")]
    pub planner: Option<PlannerChoice>,
    /// The judge: `geometric` (offline, default) or `vlm` (geometric, then a vision-language
    /// model scoring rendered previews).
    #[arg(long, value_enum, value_name = "JUDGE")]
    pub judge: Option<JudgeChoice>,
    /// Shorthand for `--planner llm --judge vlm`.
    #[arg(long)]
    pub online: bool,
    /// Language model of the planner (else SCENETHESIS_LLM_MODEL, else `llm_model` of
    /// --llm-config).
    #[arg(long, value_name = "MODEL")]
    pub llm_model: Option<String>,
    /// Vision-language model of the judge (else SCENETHESIS_VLM_MODEL, else `vlm_model` of
    /// --llm-config, else the language model).
    #[arg(long, value_name = "MODEL")]
    pub vlm_model: Option<String>,
    /// Image model (else SCENETHESIS_IMAGE_MODEL, else `image_model` of --llm-config).
    #[arg(long, value_name = "MODEL")]
    pub image_model: Option<String>,
    /// Base URL of an OpenAI-compatible endpoint, e.g. http://127.0.0.1:11434/v1 (else
    /// OPENAI_BASE_URL, else `base_url` of --llm-config, else https://api.openai.com/v1).
    #[arg(long, value_name = "URL")]
    pub base_url: Option<String>,
    /// Read the API key from this environment variable instead of OPENAI_API_KEY.
    #[arg(long, value_name = "VAR")]
    pub api_key_env: Option<String>,
    /// A TOML file with any of base_url, api_key_env, llm_model, vlm_model, image_model,
    /// timeout_secs, max_attempts, budget_secs, backoff_ms, server, stream.
    #[arg(long, value_name = "FILE")]
    pub llm_config: Option<PathBuf>,
    /// Time limit of one model request, in seconds.
    #[arg(long, value_name = "SECONDS")]
    pub llm_timeout: Option<f64>,
    /// Record every model answer in this folder (keyed by a hash of the request) and answer
    /// repeated requests from it, so a run can be replayed offline byte for byte.
    #[arg(long, value_name = "DIR")]
    pub llm_cache: Option<PathBuf>,
    /// Answer only from --llm-cache; a request it does not hold is an error (no network).
    #[arg(long, requires = "llm_cache")]
    pub llm_replay: bool,
}

impl ProviderArgs {
    /// The planner these flags select.
    pub fn planner_choice(&self) -> PlannerChoice {
        match (self.online, self.planner) {
            (_, Some(p)) => p,
            (true, None) => PlannerChoice::Llm,
            (false, None) => PlannerChoice::Knowledge,
        }
    }

    /// The judge these flags select.
    pub fn judge_choice(&self) -> JudgeChoice {
        match (self.online, self.judge) {
            (_, Some(j)) => j,
            (true, None) => JudgeChoice::Vlm,
            (false, None) => JudgeChoice::Geometric,
        }
    }

    /// The library's provider settings these flags ask for.
    pub fn settings(&self) -> ProviderSettings {
        ProviderSettings {
            planner: match self.planner_choice() {
                PlannerChoice::Knowledge => setup::PlannerChoice::Knowledge,
                PlannerChoice::Llm => setup::PlannerChoice::Llm,
            },
            judge: match self.judge_choice() {
                JudgeChoice::Geometric => setup::JudgeChoice::Geometric,
                JudgeChoice::Vlm => setup::JudgeChoice::Vlm,
            },
            llm_model: self.llm_model.clone(),
            vlm_model: self.vlm_model.clone(),
            image_model: self.image_model.clone(),
            base_url: self.base_url.clone(),
            api_key_env: self.api_key_env.clone(),
            llm_config: self.llm_config.clone(),
            llm_timeout: self.llm_timeout,
            llm_cache: self.llm_cache.clone(),
            llm_replay: self.llm_replay,
        }
    }

    /// The model client (flags over environment over --llm-config).
    pub(crate) fn client(&self) -> Result<OpenAiClient> {
        Ok(self.settings().client()?)
    }

    /// Wraps `chat` in the response cache when --llm-cache is given.
    pub(crate) fn wrap(&self, chat: OpenAiChat) -> Result<Box<dyn ChatModel>> {
        Ok(self.settings().wrap(chat)?)
    }

    /// Wraps the image model in the response cache when --llm-cache is given.
    pub(crate) fn wrap_images(&self, images: OpenAiImages) -> Result<Box<dyn ImageGenerator>> {
        Ok(self.settings().wrap_images(images)?)
    }
}
