//! Provider selection shared by `generate` and `batch`: which planner and judge a run uses, and
//! how the OpenAI-compatible models behind them are reached, recorded and replayed.
//!
//! The offline default (knowledge planner, geometric judge) reads no configuration and needs
//! no key; only `--planner llm`, `--judge vlm` or `--online` resolve a client configuration
//! (flags over environment over `--llm-config`).

use std::path::PathBuf;
use std::time::Duration;

use anyhow::{Context, Result};
use scenethesis_language::{LlmPlanner, VlmJudge};
use scenethesis_models::{CacheMode, Cached, ChatModel, ImageGenerator, ResponseCache};
use scenethesis_openai::{ApiKey, ClientConfig, OpenAiChat, OpenAiClient, OpenAiImages, Overrides};
use scenethesis_pipeline::Pipeline;

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
    /// timeout_secs, max_attempts, budget_secs, backoff_ms.
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

    /// The client configuration: flags over environment over --llm-config.
    pub(crate) fn config(&self) -> Result<ClientConfig> {
        let api_key = match &self.api_key_env {
            Some(var) => {
                let key = std::env::var(var).ok().filter(|k| !k.trim().is_empty());
                Some(ApiKey::new(key.with_context(|| {
                    format!("--api-key-env {var}: the environment variable {var} is not set")
                })?))
            }
            None => None,
        };
        let timeout = match self.llm_timeout {
            Some(s) if s.is_finite() && s > 0.0 && s < 86_400.0 => Some(Duration::from_secs_f64(s)),
            Some(s) => anyhow::bail!("--llm-timeout: expected seconds in (0, 86400), found {s}"),
            None => None,
        };
        let overrides = Overrides {
            base_url: self.base_url.clone(),
            api_key,
            llm_model: self.llm_model.clone(),
            vlm_model: self.vlm_model.clone(),
            image_model: self.image_model.clone(),
            embedding_model: None,
            timeout,
        };
        ClientConfig::resolve(&overrides, self.llm_config.as_deref())
            .context("configuring the model provider")
    }

    /// Wraps `chat` in the response cache when --llm-cache is given; its meter counts requests,
    /// tokens and cache hits (each run's share goes into its `report.json`).
    pub(crate) fn wrap(&self, chat: OpenAiChat) -> Result<Box<dyn ChatModel>> {
        let meter = chat.meter().clone();
        Ok(match self.cache()? {
            Some(cache) => Box::new(Cached::new(chat, cache).with_meter(meter)),
            None => Box::new(chat),
        })
    }

    /// The response cache of --llm-cache (read-write, or replay-only with --llm-replay).
    fn cache(&self) -> Result<Option<ResponseCache>> {
        let Some(dir) = &self.llm_cache else {
            return Ok(None);
        };
        let mode = if self.llm_replay {
            CacheMode::ReplayOnly
        } else {
            CacheMode::ReadWrite
        };
        ResponseCache::open(dir, mode)
            .with_context(|| format!("opening the response cache {}", dir.display()))
            .map(Some)
    }

    /// Wraps the image model in the response cache when --llm-cache is given, like
    /// [`Self::wrap`]: an edit is recorded under its model, prompt, size, seed and the digest
    /// of the image it edits.
    pub(crate) fn wrap_images(&self, images: OpenAiImages) -> Result<Box<dyn ImageGenerator>> {
        let meter = images.meter().clone();
        Ok(match self.cache()? {
            Some(cache) => Box::new(Cached::new(images, cache).with_meter(meter)),
            None => Box::new(images),
        })
    }

    /// Installs the selected planner and judge into `pipeline`. The offline choices leave it
    /// as it is and read no configuration.
    pub fn apply(&self, mut pipeline: Pipeline) -> Result<Pipeline> {
        let planner = self.planner_choice();
        let judge = self.judge_choice();
        if planner == PlannerChoice::Knowledge && judge == JudgeChoice::Geometric {
            return Ok(pipeline);
        }
        let config = self.config()?;
        let client = OpenAiClient::new(config).context("building the model client")?;
        if planner == PlannerChoice::Llm {
            let chat = client.llm().context("choosing the planner's model")?;
            let model = self.wrap(chat)?;
            pipeline = pipeline.with_planner(LlmPlanner::new(model));
        }
        if judge == JudgeChoice::Vlm {
            let chat = client.vlm().context("choosing the judge's model")?;
            let model = self.wrap(chat)?;
            let renderer = scenethesis_pipeline::WgpuPreviews::from_env()
                .context("--judge vlm needs a renderer for the previews it shows the model")?;
            pipeline = pipeline.with_judge(VlmJudge::new(model, renderer));
        }
        Ok(pipeline)
    }
}
