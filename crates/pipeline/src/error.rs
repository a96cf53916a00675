//! The pipeline's error type.

use std::path::PathBuf;

use scenethesis_agents::{GuideError, PlanError};
use scenethesis_export::ExportError;
use scenethesis_physics_opt::PhysicsOptError;
use scenethesis_scene_graph::SceneIoError;

use crate::judge::JudgeError;
use scenethesis_retrieval::AssetError;

/// Why a run, an export or a batch failed.
#[derive(Debug, thiserror::Error)]
pub enum PipelineError {
    /// The planner could not plan the prompt.
    #[error("plan: {0}")]
    Plan(#[from] PlanError),
    /// An asset could not be retrieved or regenerated.
    #[error("retrieve: {0}")]
    Asset(#[from] AssetError),
    /// The guide could not lay the plan out.
    #[error("guide: {0}")]
    Guide(#[from] GuideError),
    /// The optimizer could not be set up.
    #[error("optimize: {0}")]
    Optimize(#[from] PhysicsOptError),
    /// The judge could not evaluate the scene.
    #[error("judge: {0}")]
    Judge(#[from] JudgeError),
    /// No floor plan could be made for the house the prompt names.
    #[error("floor plan: {0}")]
    Layout(#[from] scenethesis_floorplan::LayoutError),
    /// A floor plan given by file breaks a rule (the error names the room, door or window).
    #[error("floor plan: {0}")]
    FloorPlan(#[from] scenethesis_floorplan::PlanError),
    /// A house plan file is not valid JSON of the house plan's shape.
    #[error("{path}: {message}")]
    PlanSyntax {
        /// The file.
        path: std::path::PathBuf,
        /// What is wrong, with the line and column.
        message: String,
    },
    /// A stage returned something the next stage cannot use.
    #[error("internal inconsistency: {detail}")]
    Inconsistent {
        /// What does not fit.
        detail: String,
    },
    /// Writing an export failed.
    #[error("export: {0}")]
    Export(#[from] ExportError),
    /// Reading or writing `scene.json` failed.
    #[error(transparent)]
    SceneIo(#[from] SceneIoError),
    /// A file or folder could not be read.
    #[error("cannot read {path}")]
    Read {
        /// The file or folder.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// A file or folder could not be written or created.
    #[error("cannot write {path}")]
    Write {
        /// The file or folder.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The output path cannot be used.
    #[error("output {path}: {reason}")]
    BadOutput {
        /// The path.
        path: PathBuf,
        /// Why not.
        reason: String,
    },
    /// A batch argument or prompts file is malformed.
    #[error("batch: {0}")]
    Batch(String),
    /// The run's time limit ([`GenerateOptions::time_limit`](crate::GenerateOptions)) was
    /// reached before any attempt had made a scene.
    #[error(
        "the time limit of {limit_seconds} s was reached before the {stage} stage{}, and no \
         scene was finished in time; give the run more time (--time-limit)",
        if *.round > 0 { format!(" of re-plan round {}", .round) } else { String::new() }
    )]
    OutOfTime {
        /// The stage that was about to start.
        stage: crate::Stage,
        /// The attempt (0 = first) it belonged to.
        round: usize,
        /// The limit, in seconds.
        limit_seconds: f64,
    },
    /// The caller's [`Progress`](crate::Progress) asked the run to stop
    /// ([`Progress::stop_requested`](crate::Progress::stop_requested)).
    #[error(
        "stopped by the caller before the {stage} stage{}",
        if *.round > 0 { format!(" of re-plan round {}", .round) } else { String::new() }
    )]
    Stopped {
        /// The stage that was about to start.
        stage: crate::Stage,
        /// The attempt (0 = first) it belonged to.
        round: usize,
    },
}
