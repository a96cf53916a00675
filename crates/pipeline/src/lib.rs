//! The end-to-end scenethesis pipeline as a library: a prompt in, a simulation-ready scene out.
//!
//! [`Pipeline::generate`] runs the stages — **plan** (a [`scenethesis_agents::Planner`]),
//! **retrieve** (an [`AssetSource`]: one asset per planned object), **guide** (a
//! [`scenethesis_agents::Guide`]: the initial layout), **optimize** (a
//! [`scenethesis_physics_opt::Optimizer`] over signed distance fields) and **judge** (a
//! [`Judge`]) — and, while the judge rejects the scene, re-plans: first it moves the objects at
//! fault (new asset variants, a new layout seed), then drops them, up to
//! [`GenerateOptions::max_replans`] times, keeping the best attempt. An optional
//! [`SceneRenderer`](scenethesis_render_api::SceneRenderer) (the renderer seam, implemented by
//! `scenethesis_render::Renderer`) renders previews. [`GeneratedScene::write_outputs`] writes the output
//! folder atomically: `scene.glb`, `scene.json`, `preview.png` + `preview_top.png` and
//! `report.json` (metrics, verdict, every re-plan, per-stage timings).
//!
//! [`Pipeline::offline`] needs no network, API key or GPU. [`export_folder`] writes USD, MJCF,
//! URDF or GLB from a saved folder, [`export_file`] one format to a file of the user's naming;
//! [`SavedScene`] reads an output folder back; [`batch::run_batch`] runs prompts × seeds,
//! resumable and sharded (`--shard auto` from the scheduler's environment).
//!
//! ```no_run
//! use scenethesis_pipeline::{GenerateOptions, NoProgress, Pipeline};
//! let pipeline = Pipeline::offline();
//! let mut scene = pipeline.generate("a cozy living room", 0, &GenerateOptions::default(), &mut NoProgress)?;
//! println!("{}", scene.report.summary_line());
//! scene.write_outputs(std::path::Path::new("out/living_room"))?;
//! # Ok::<(), scenethesis_pipeline::PipelineError>(())
//! ```

#![warn(missing_docs)]

pub mod batch;
mod error;
mod house;
pub mod out_dir;
mod output;
mod phases;
mod pipeline;
mod plan_file;
mod replan;
mod report;
mod saved;
mod stage;

pub use error::PipelineError;
pub use house::{HousePlanFile, HouseReport, RoomReport};
pub use out_dir::{Existing, OutputDir, REPORT_JSON, SCENE_JSON};
pub use output::{export_file, export_folder, resolve_meshes};
pub use pipeline::{
    time_limit_from_secs, GenerateOptions, GeneratedScene, Pipeline, DEFAULT_TIME_LIMIT,
    MAX_TIME_LIMIT,
};
pub use plan_file::{plan_json, write_plan, PLAN_JSON};
pub use replan::replan_action;
pub use report::{
    AlignmentReport, ObjectIssue, PartTiming, Replan, ReplanAction, Report, StageTiming,
};
pub use saved::SavedScene;
/// The judge stage (its own crate, `scenethesis-judge`), re-exported for compatibility.
pub use scenethesis_judge as judge;
pub use scenethesis_judge::{
    AcceptAll, Failure, FailureKind, GeometricJudge, Judge, JudgeError, JudgeInput, Verdict,
};
pub use scenethesis_retrieval::{
    object_seed, AssetError, AssetQuery, AssetSource, CatalogSource, RetrievalSource,
};
pub use stage::{NoProgress, Progress, Stage};

pub use scenethesis_agents::{
    check_plan, cut_prompt, FixedPlanner, Plan, PlanFileError, PlanIssue,
};
/// The correspond stage's default matcher and its settings ([`Pipeline::with_matcher`]).
pub use scenethesis_correspondence::{GuidedSettings, ShapeMatcher};
pub use scenethesis_export::Format;
