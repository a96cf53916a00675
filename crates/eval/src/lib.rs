//! Scene metrics, exactly as `metrics.md` defines them: collision between real meshes (Col-O,
//! Col-S) and with the floor and walls (Col-arch), stability under a whole-scene rigid-body
//! simulation (Inst-O, Inst-S), walkability (Walk) and reachability (Reach) on a floor raster,
//! and scene content (objects, categories, relation kinds).
//!
//! The input is an [`EvalScene`]: objects with world-space meshes, their support links and the
//! room. The pipeline builds one in memory ([`EvalScene::from_scene`]); [`load_path`] builds one
//! from an output folder (`scene.json` + `scene.glb`, or regenerated procedural assets) or from
//! any glTF / GLB scene. [`evaluate`] returns the [`SceneMetrics`] of one scene, and
//! [`MetricsSummary::from_scenes`] pools many.
//!
//! ```no_run
//! let scene = scenethesis_eval::load_path(std::path::Path::new("out/living_room"))?;
//! let metrics = scenethesis_eval::evaluate(&scene);
//! println!("{}", metrics.to_table());
//! # Ok::<(), scenethesis_eval::EvalError>(())
//! ```

#![warn(missing_docs)]

pub mod collision;
mod error;
pub mod glb;
pub mod limits;
mod load;
mod metrics;
pub mod opening;
pub mod raster;
mod report;
mod scene;
pub mod stability;

pub use error::EvalError;
pub use load::{load_folder, load_glb, load_path};
pub use metrics::{
    evaluate, evaluate_timed, evaluate_timed_with, evaluate_with_cache, EvalTimings,
    MetricsSummary, SceneMetrics,
};
pub use scene::{procedural_mesh, EvalObject, EvalScene};
pub use stability::DecompositionCache;
