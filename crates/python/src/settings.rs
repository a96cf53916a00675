//! The settings of a run, built once from the Python keyword arguments and checked there.

use std::path::PathBuf;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use scenethesis_pipeline::{time_limit_from_secs, GenerateOptions};
use scenethesis_scene_graph::OpenState;
use scenethesis_setup::{JudgeChoice, PipelineSettings, PlannerChoice, ProviderSettings};

/// The settings `generate` and `plan` run with: how the pipeline is built (planner, judge,
/// model endpoint, response cache, assets, previews) and the generation options.
#[pyclass(frozen, module = "scenethesis._native")]
pub struct Settings {
    /// How the pipeline is built.
    pub pipeline: PipelineSettings,
    /// The generation options.
    pub options: GenerateOptions,
}

fn value_error(argument: &str, message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(format!("{argument}: {message}"))
}

#[pymethods]
impl Settings {
    /// Checks the values and builds the settings; a bad value raises `ValueError` naming the
    /// argument.
    #[new]
    #[pyo3(signature = (
        *, planner="knowledge", judge="geometric", assets=None, preview=true, max_replans=3,
        llm_model=None, vlm_model=None, image_model=None, base_url=None, api_key_env=None,
        llm_config=None, llm_timeout=None, llm_cache=None, llm_replay=false, time_limit=600.0,
        open_state="closed"
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        planner: &str,
        judge: &str,
        assets: Option<PathBuf>,
        preview: bool,
        max_replans: usize,
        llm_model: Option<String>,
        vlm_model: Option<String>,
        image_model: Option<String>,
        base_url: Option<String>,
        api_key_env: Option<String>,
        llm_config: Option<PathBuf>,
        llm_timeout: Option<f64>,
        llm_cache: Option<PathBuf>,
        llm_replay: bool,
        time_limit: Option<f64>,
        open_state: &str,
    ) -> PyResult<Self> {
        let open_state: OpenState = open_state
            .parse()
            .map_err(|e| value_error("open_state", e))?;
        let time_limit = time_limit_from_secs(time_limit.unwrap_or(0.0))
            .map_err(|e| value_error("time_limit", e))?;
        let planner: PlannerChoice = planner.parse().map_err(|e| value_error("planner", e))?;
        let judge: JudgeChoice = judge.parse().map_err(|e| value_error("judge", e))?;
        if let Some(s) = llm_timeout {
            if !(s.is_finite() && s > 0.0 && s < 86_400.0) {
                return Err(value_error(
                    "llm_timeout",
                    format!("expected seconds in (0, 86400), found {s}"),
                ));
            }
        }
        if llm_replay && llm_cache.is_none() {
            return Err(value_error(
                "llm_replay",
                "needs llm_cache, the folder to replay from",
            ));
        }
        if max_replans > 100 {
            return Err(value_error(
                "max_replans",
                format!("expected at most 100, found {max_replans}"),
            ));
        }
        let providers = ProviderSettings {
            planner,
            judge,
            llm_model,
            vlm_model,
            image_model,
            base_url,
            api_key_env,
            llm_config,
            llm_timeout,
            llm_cache,
            llm_replay,
        };
        Ok(Self {
            pipeline: PipelineSettings {
                previews: preview,
                assets,
                providers,
            },
            options: GenerateOptions {
                max_replans,
                previews: preview,
                time_limit,
                open_state,
                ..GenerateOptions::default()
            },
        })
    }
}
