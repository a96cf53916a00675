//! The whole house measured as `metrics.md` defines the metrics (Col-O, Col-arch, Inst-O,
//! Walk, Reach over every room at once: interior walls block, door openings pass), and how
//! much of each room a 0.3 m-radius robot reaches from the entrance.

use std::collections::BTreeMap;

use scenethesis_eval::raster::{footprint, free_floor, grown_cells, metric_grid, wall_pieces};
use scenethesis_eval::{evaluate, EvalError, EvalScene, SceneMetrics};
use scenethesis_judge::JudgeError;
use scenethesis_scene_graph::{Architecture, Mesh, Scene, EXTERIOR, ROBOT_RADIUS};

use crate::PipelineError;

/// The house's metrics and, per room id, the share of its robot-free floor reached from the
/// entrance.
pub(crate) struct HouseMeasure {
    /// Every metric over the whole house.
    pub(crate) metrics: SceneMetrics,
    /// Per room id: the share (0–1) of the room's free floor (objects grown by the robot
    /// radius taken out) connected to the floor just inside the entrance; `None` for a room
    /// with no free floor at all.
    pub(crate) entrance_reach: BTreeMap<String, Option<f64>>,
}

/// Measures the house scene with its meshes (by object id).
pub(crate) fn measure(
    scene: &Scene,
    meshes: &BTreeMap<String, Mesh>,
) -> Result<HouseMeasure, PipelineError> {
    let eval = EvalScene::from_scene(scene, |o| {
        meshes
            .get(&o.id)
            .cloned()
            .ok_or_else(|| EvalError::MissingMesh {
                object: o.id.clone(),
                reason: "the house has no mesh for it".into(),
            })
    })
    .map_err(|e| PipelineError::Judge(JudgeError::Eval(e)))?;
    Ok(HouseMeasure {
        metrics: evaluate(&eval),
        entrance_reach: entrance_reach(&eval),
    })
}

/// Per room, the share of its free floor the robot reaches from the entrance.
fn entrance_reach(eval: &EvalScene) -> BTreeMap<String, Option<f64>> {
    let arch = &eval.architecture;
    let grid = metric_grid(&arch.floor);
    let mut free = free_floor(&grid, &arch.floor, &wall_pieces(eval));
    for rect in eval.objects.iter().filter_map(footprint) {
        for p in grown_cells(&grid, &rect) {
            free[p] = false;
        }
    }
    let parts = grid.components8(&free);
    let entrance = entrance_cell(arch).and_then(|[x, z]| {
        // The free cell nearest the point just inside the entrance.
        (0..grid.len())
            .filter(|&p| free[p])
            .map(|p| {
                let c = grid.center(p % grid.nx, p / grid.nx);
                ((c[0] - x).hypot(c[1] - z), p)
            })
            .filter(|(d, _)| *d < 0.5)
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, p)| parts.labels[p])
    });
    arch.rooms
        .iter()
        .map(|room| {
            let (mut total, mut reached) = (0usize, 0usize);
            for p in (0..grid.len()).filter(|&p| free[p]) {
                let [x, z] = grid.center(p % grid.nx, p / grid.nx);
                if room.contains_xz(x, z) {
                    total += 1;
                    reached += usize::from(Some(parts.labels[p]) == entrance);
                }
            }
            let share = (total > 0).then(|| reached as f64 / total as f64);
            (room.id.clone(), share)
        })
        .collect()
}

/// The floor point a robot entering the house stands on: the entrance door's centre moved in
/// by the wall's half thickness, the robot radius and a margin.
fn entrance_cell(arch: &Architecture) -> Option<[f64; 2]> {
    let door = arch.doors.iter().find(|d| {
        d.joins
            .as_ref()
            .is_some_and(|j| j.iter().any(|r| r == EXTERIOR))
    })?;
    let wall = arch.walls.iter().find(|w| w.id == door.wall)?;
    let n = wall.inward_normal();
    let at = wall.start + wall.direction() * door.offset;
    let inside = wall.thickness / 2.0 + ROBOT_RADIUS + 0.1;
    Some([at.x + n.x * inside, at.y + n.y * inside])
}
