//! `scenethesis._native`: the Python package's native module. It wraps the library crates —
//! the pipeline, its setup from user settings, the evaluator — and never the CLI; the
//! pure-Python layer (`python/scenethesis`) turns what it returns into Pythonic objects
//! (numpy arrays, dataclasses, dicts) and checks argument types and values first.
//!
//! Long calls (generate, plan, load, save, export, evaluate) release the GIL, so Python threads
//! run them in parallel; a progress callback re-acquires it only for the call.

#![warn(missing_docs)]

use pyo3::prelude::*;

mod errors;
mod progress;
mod scene;
mod settings;

use scenethesis_pipeline::batch::{self, Prompt};
use scenethesis_pipeline::{plan_json, FixedPlanner, RetrievalSource, SavedScene};

use crate::errors::Failure;
use crate::progress::PyProgress;
use crate::scene::NativeScene;
use crate::settings::Settings;

/// Generates a scene from `prompt` (or the plan in `plan_json`) with `seed`.
#[pyfunction]
#[pyo3(signature = (prompt, seed, settings, plan_json=None, progress=None))]
fn generate(
    py: Python<'_>,
    prompt: Option<String>,
    seed: u64,
    settings: &Settings,
    plan_json: Option<String>,
    progress: Option<Py<PyAny>>,
) -> PyResult<NativeScene> {
    let (pipeline_settings, options) = (settings.pipeline.clone(), settings.options.clone());
    let mut progress = PyProgress::new(progress);
    let outcome = py.detach(|| -> Result<_, Failure> {
        let mut built = pipeline_settings.build().map_err(Failure::setup)?;
        let prompt = match &plan_json {
            Some(text) => {
                let planner = FixedPlanner::from_json(text, std::path::Path::new("plan"))
                    .map_err(Failure::plan_file)?;
                let prompt = planner.as_plan().prompt.clone();
                built.pipeline = built.pipeline.with_planner(planner);
                prompt
            }
            None => prompt.unwrap_or_default(),
        };
        let generated = built
            .pipeline
            .generate(&prompt, seed, &options, &mut progress)
            .map_err(|e| Failure::pipeline(&e, format!("generating \"{prompt}\"")))?;
        Ok((generated, built.warnings))
    });
    progress.raise_if_failed()?;
    let (generated, warnings) = outcome.map_err(|f| f.into_py())?;
    errors::warn_all(py, &warnings)?;
    Ok(NativeScene::generated(generated))
}

/// The planner's plan for `prompt` with `seed`, as the JSON `scenethesis plan` writes.
#[pyfunction]
#[pyo3(signature = (prompt, seed, settings))]
fn plan(py: Python<'_>, prompt: String, seed: u64, settings: &Settings) -> PyResult<String> {
    let mut pipeline_settings = settings.pipeline.clone();
    pipeline_settings.previews = false;
    let outcome = py.detach(|| -> Result<_, Failure> {
        let built = pipeline_settings.build().map_err(Failure::setup)?;
        let plan = built
            .pipeline
            .plan(&prompt, seed)
            .map_err(|e| Failure::pipeline(&e, format!("planning \"{prompt}\"")))?;
        Ok((plan_json(&plan), built.warnings))
    });
    let (text, warnings) = outcome.map_err(|f| f.into_py())?;
    errors::warn_all(py, &warnings)?;
    Ok(text)
}

/// Reads an output folder of `generate` (`scene.json`, `report.json`, previews); imported
/// assets are re-read from the paths in `scene.json`, or from `assets` when given.
#[pyfunction]
#[pyo3(signature = (folder, assets=None))]
fn load(
    py: Python<'_>,
    folder: std::path::PathBuf,
    assets: Option<std::path::PathBuf>,
) -> PyResult<NativeScene> {
    let outcome = py.detach(|| -> Result<_, Failure> {
        let (source, warnings) = match &assets {
            Some(dir) => RetrievalSource::from_directory(dir).map_err(|e| {
                Failure::input(&e, format!("importing assets from {}", dir.display()))
            })?,
            None => (RetrievalSource::default(), Vec::new()),
        };
        let saved = SavedScene::read(&folder, &source)
            .map_err(|e| Failure::pipeline(&e, format!("loading {}", folder.display())))?;
        Ok((saved, warnings))
    });
    let (saved, warnings) = outcome.map_err(|f| f.into_py())?;
    let warnings: Vec<String> = warnings.iter().map(|w| w.to_string()).collect();
    errors::warn_all(py, &warnings)?;
    Ok(NativeScene::saved(saved))
}

/// The metrics of `scenethesis eval PATH --json` for an output folder, a scene.json or a .glb.
#[pyfunction]
fn evaluate_path(py: Python<'_>, path: std::path::PathBuf) -> PyResult<String> {
    let outcome = py.detach(|| -> Result<_, Failure> {
        let scene = scenethesis_eval::load_path(&path).map_err(|e| {
            Failure::input(&e, format!("cannot load {} for evaluation", path.display()))
        })?;
        let metrics = scenethesis_eval::evaluate(&scene);
        Ok(serde_json::to_string(&metrics).expect("metrics serialize"))
    });
    outcome.map_err(|f| f.into_py())
}

/// The jobs `scenethesis batch` makes of `prompts` × `seeds` seeds from `base_seed`, in order:
/// `(position, prompt, seed, folder)`, the folder being the job's sub-folder name.
#[pyfunction]
#[pyo3(signature = (prompts, seeds=1, base_seed=0))]
fn batch_jobs(
    prompts: Vec<String>,
    seeds: u64,
    base_seed: u64,
) -> PyResult<Vec<(usize, String, u64, String)>> {
    let prompts: Vec<Prompt> = prompts
        .iter()
        .map(|p| Prompt::from(scenethesis_pipeline::cut_prompt(p.trim()).0))
        .collect();
    let jobs = batch::jobs(&prompts, seeds, base_seed)
        .map_err(|e| Failure::pipeline(&e, "listing batch jobs".into()).into_py())?;
    Ok(jobs
        .into_iter()
        .map(|j| (j.position, j.prompt, j.seed, j.folder))
        .collect())
}

/// The native module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // The texture maps are kept between processes where the command line keeps them.
    scenethesis_materials::keep_maps_in(scenethesis_materials::default_maps_folder());
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<Settings>()?;
    m.add_class::<NativeScene>()?;
    m.add_function(wrap_pyfunction!(generate, m)?)?;
    m.add_function(wrap_pyfunction!(plan, m)?)?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate_path, m)?)?;
    m.add_function(wrap_pyfunction!(batch_jobs, m)?)?;
    errors::register(m)
}
