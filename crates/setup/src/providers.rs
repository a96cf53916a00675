//! Provider selection: which planner and judge a run uses, and how the OpenAI-compatible models
//! behind them are reached, recorded and replayed.

use std::path::PathBuf;
use std::str::FromStr;
use std::time::Duration;

use scenethesis_language::{LlmPlanner, VlmJudge};
use scenethesis_models::{CacheMode, Cached, ChatModel, ImageGenerator, ResponseCache};
use scenethesis_openai::{ApiKey, ClientConfig, OpenAiChat, OpenAiClient, OpenAiImages, Overrides};
use scenethesis_pipeline::Pipeline;

use crate::SetupError;

/// Which planner turns the prompt into a plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PlannerChoice {
    /// The built-in offline knowledge planner (the default).
    #[default]
    Knowledge,
    /// A chat model behind an OpenAI-compatible endpoint.
    Llm,
}

impl FromStr for PlannerChoice {
    type Err = String;

    /// `knowledge` or `llm`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "knowledge" => Ok(Self::Knowledge),
            "llm" => Ok(Self::Llm),
            other => Err(format!(
                "unknown planner `{other}`: expected knowledge or llm"
            )),
        }
    }
}

/// Which judge accepts or rejects a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum JudgeChoice {
    /// The offline geometric judge (the default).
    #[default]
    Geometric,
    /// The geometric judge, then a vision-language model looking at rendered previews.
    Vlm,
}

impl FromStr for JudgeChoice {
    type Err = String;

    /// `geometric` or `vlm`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "geometric" => Ok(Self::Geometric),
            "vlm" => Ok(Self::Vlm),
            other => Err(format!(
                "unknown judge `{other}`: expected geometric or vlm"
            )),
        }
    }
}

/// The model provider settings of a run. Only a model-backed planner or judge resolves a client
/// configuration (settings over environment over the `llm_config` file); the offline default
/// reads none.
#[derive(Debug, Clone, Default)]
pub struct ProviderSettings {
    /// The planner.
    pub planner: PlannerChoice,
    /// The judge.
    pub judge: JudgeChoice,
    /// Language model of the planner (else `SCENETHESIS_LLM_MODEL`, else the config file).
    pub llm_model: Option<String>,
    /// Vision-language model of the judge (else `SCENETHESIS_VLM_MODEL`, else the config file,
    /// else the language model).
    pub vlm_model: Option<String>,
    /// Image model (else `SCENETHESIS_IMAGE_MODEL`, else the config file).
    pub image_model: Option<String>,
    /// Base URL of an OpenAI-compatible endpoint (else `OPENAI_BASE_URL`, else the config file,
    /// else OpenAI's).
    pub base_url: Option<String>,
    /// The environment variable holding the API key, instead of `OPENAI_API_KEY`.
    pub api_key_env: Option<String>,
    /// A TOML client configuration file.
    pub llm_config: Option<PathBuf>,
    /// Time limit of one model request, in seconds.
    pub llm_timeout: Option<f64>,
    /// Record every model answer in this folder and answer repeated requests from it.
    pub llm_cache: Option<PathBuf>,
    /// Answer only from `llm_cache` (no network).
    pub llm_replay: bool,
}

impl ProviderSettings {
    /// Whether the settings name a model-backed planner or judge.
    pub fn uses_models(&self) -> bool {
        self.planner == PlannerChoice::Llm || self.judge == JudgeChoice::Vlm
    }

    /// The client configuration: these settings over the environment over `llm_config`.
    pub fn config(&self) -> Result<ClientConfig, SetupError> {
        let api_key = match &self.api_key_env {
            Some(var) => {
                let key = std::env::var(var).ok().filter(|k| !k.trim().is_empty());
                Some(ApiKey::new(key.ok_or_else(|| SetupError::MissingKey {
                    var: var.clone(),
                })?))
            }
            None => None,
        };
        let timeout = match self.llm_timeout {
            Some(s) if s.is_finite() && s > 0.0 && s < 86_400.0 => Some(Duration::from_secs_f64(s)),
            Some(s) => return Err(SetupError::Timeout(s)),
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
        Ok(ClientConfig::resolve(
            &overrides,
            self.llm_config.as_deref(),
        )?)
    }

    /// The model client of [`Self::config`].
    pub fn client(&self) -> Result<OpenAiClient, SetupError> {
        OpenAiClient::new(self.config()?).map_err(|e| SetupError::Client(Box::new(e)))
    }

    /// Wraps `chat` in the response cache when `llm_cache` is set; its meter counts requests,
    /// tokens and cache hits (each run's share goes into its `report.json`).
    pub fn wrap(&self, chat: OpenAiChat) -> Result<Box<dyn ChatModel>, SetupError> {
        let meter = chat.meter().clone();
        Ok(match self.cache()? {
            Some(cache) => Box::new(Cached::new(chat, cache).with_meter(meter)),
            None => Box::new(chat),
        })
    }

    /// Wraps the image model in the response cache when `llm_cache` is set, like
    /// [`Self::wrap`]: an edit is recorded under its model, prompt, size, seed and the digest
    /// of the image it edits.
    pub fn wrap_images(&self, images: OpenAiImages) -> Result<Box<dyn ImageGenerator>, SetupError> {
        let meter = images.meter().clone();
        Ok(match self.cache()? {
            Some(cache) => Box::new(Cached::new(images, cache).with_meter(meter)),
            None => Box::new(images),
        })
    }

    /// The response cache of `llm_cache` (read-write, or replay-only with `llm_replay`).
    fn cache(&self) -> Result<Option<ResponseCache>, SetupError> {
        let Some(dir) = &self.llm_cache else {
            return if self.llm_replay {
                Err(SetupError::ReplayWithoutCache)
            } else {
                Ok(None)
            };
        };
        let mode = if self.llm_replay {
            CacheMode::ReplayOnly
        } else {
            CacheMode::ReadWrite
        };
        ResponseCache::open(dir, mode)
            .map(Some)
            .map_err(|source| SetupError::Cache {
                dir: dir.clone(),
                source: Box::new(source),
            })
    }

    /// Installs the selected planner and judge into `pipeline`. The offline choices leave it
    /// as it is and read no configuration.
    pub fn apply(&self, mut pipeline: Pipeline) -> Result<Pipeline, SetupError> {
        if !self.uses_models() {
            return Ok(pipeline);
        }
        let client = self.client()?;
        if self.planner == PlannerChoice::Llm {
            let model = self.wrap(client.llm()?)?;
            pipeline = pipeline.with_planner(LlmPlanner::new(model));
        }
        if self.judge == JudgeChoice::Vlm {
            let model = self.wrap(client.vlm()?)?;
            let renderer = scenethesis_render::Renderer::from_env()
                .map_err(|e| SetupError::NoRenderer(e.to_string()))?;
            pipeline = pipeline.with_judge(VlmJudge::new(model, renderer));
        }
        Ok(pipeline)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn choices_parse_and_refuse_unknown_names() {
        assert_eq!("llm".parse::<PlannerChoice>(), Ok(PlannerChoice::Llm));
        assert_eq!("vlm".parse::<JudgeChoice>(), Ok(JudgeChoice::Vlm));
        let err = "gpt".parse::<PlannerChoice>().unwrap_err();
        assert!(err.contains("expected knowledge or llm"), "{err}");
    }

    #[test]
    fn bad_settings_name_the_setting() {
        let settings = ProviderSettings {
            planner: PlannerChoice::Llm,
            llm_timeout: Some(-1.0),
            ..ProviderSettings::default()
        };
        let err = settings.config().unwrap_err().to_string();
        assert!(err.contains("llm_timeout (--llm-timeout)"), "{err}");
        let settings = ProviderSettings {
            api_key_env: Some("SCENETHESIS_SETUP_TEST_UNSET_KEY".into()),
            ..ProviderSettings::default()
        };
        let err = settings.config().unwrap_err().to_string();
        assert!(err.contains("SCENETHESIS_SETUP_TEST_UNSET_KEY"), "{err}");
        let settings = ProviderSettings {
            planner: PlannerChoice::Llm,
            llm_replay: true,
            llm_model: Some("m".into()),
            base_url: Some("http://127.0.0.1:9/v1".into()),
            ..ProviderSettings::default()
        };
        let err = settings.apply(Pipeline::offline()).unwrap_err().to_string();
        assert!(err.contains("needs llm_cache"), "{err}");
    }
}
