//! Optimize: every laid-out object gets its prepared asset, the optimizer moves the poses, and
//! the scene takes the result.

use std::collections::BTreeMap;
use std::time::Instant;

use scenethesis_correspondence::PoseAlignment;
use scenethesis_physics_opt::{
    optimize_scene, OptimizeSettings, Optimizer, Placement, SceneProblem,
};
use scenethesis_scene_graph::{Mesh, Scene};

use super::retrieve::{AssetCache, Retrieved};
use crate::{GenerateOptions, PipelineError};

/// Optimizes `scene` in place, with the pose-alignment correspondences of `alignments` (by
/// object id; empty without guidance), within the optimizer's own time budget and by
/// `deadline` (the end of the run's time limit); returns the placement report and each
/// object's mesh, and the seconds spent preparing the assets (the stage's `prepare` part).
pub(crate) fn optimize(
    scene: &mut Scene,
    alignments: &BTreeMap<String, PoseAlignment>,
    retrieved: &Retrieved,
    cache: &mut AssetCache,
    optimizer: &dyn Optimizer,
    options: &GenerateOptions,
    deadline: Option<Instant>,
) -> Result<(Placement, BTreeMap<String, Mesh>, f64), PipelineError> {
    let prepare_started = Instant::now();
    let mut meshes = BTreeMap::new();
    let mut problem = SceneProblem::new(scene.clone());
    for object in &scene.objects {
        let key = retrieved
            .chosen
            .get(&object.id)
            .ok_or_else(|| PipelineError::Inconsistent {
                detail: format!(
                    "the guide returned object `{}` that the plan does not hold",
                    object.id
                ),
            })?;
        problem.set_asset(&object.id, cache.prepared(key, &options.prepare)?);
        meshes.insert(object.id.clone(), cache.asset(key).mesh.clone());
    }
    for (id, alignment) in alignments {
        problem.set_alignment(id, alignment.clone());
    }
    let prepare_seconds = prepare_started.elapsed().as_secs_f64();
    let settings = OptimizeSettings {
        deadline,
        ..options.optimize.clone()
    };
    let placement = optimize_scene(&problem, optimizer, &settings)?;
    placement.apply_to(scene);
    Ok((placement, meshes, prepare_seconds))
}
