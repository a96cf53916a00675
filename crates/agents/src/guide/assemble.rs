//! The layout becomes a scene: ground objects' poses from their footprints (mounted ones at
//! their hanging height), then one scene object per placed plan object with its support and the
//! relations whose targets survived.

use std::collections::BTreeMap;

use nalgebra::Vector3;
use scenethesis_assets::AssetInfo;
use scenethesis_scene_graph::{Aabb, ParentRef, Pose, Relation, RelationKind, Scene, SceneObject};

use super::room::Room;
use super::shared::{wrap, WALL_MOUNT_HEIGHT};
use super::walkway::FloorState;
use crate::plan::Plan;

/// The poses of the placed floor objects by plan index, and the wall each one backs onto.
pub(super) fn ground_poses(
    state: &FloorState<'_>,
) -> (BTreeMap<usize, Pose>, BTreeMap<usize, String>) {
    let mut poses: BTreeMap<usize, Pose> = BTreeMap::new();
    let mut walls: BTreeMap<usize, String> = BTreeMap::new();
    for p in &state.placed {
        let y = if p.mounted {
            (WALL_MOUNT_HEIGHT - p.height / 2.0).max(0.5)
        } else {
            0.0
        };
        poses.insert(
            p.plan_index,
            Pose::new(1.0, wrap(p.fp.yaw), Vector3::new(p.fp.cx, y, p.fp.cz)),
        );
        if let Some(w) = &p.wall {
            walls.insert(p.plan_index, w.clone());
        }
    }
    (poses, walls)
}

/// The scene of the objects that have a pose; the anchor is the plan's when it was placed,
/// else the first floor object.
pub(super) fn build_scene(
    plan: &Plan,
    seed: u64,
    room: Room,
    infos: &[AssetInfo],
    poses: &BTreeMap<usize, Pose>,
    walls: &BTreeMap<usize, String>,
) -> Scene {
    let mut scene = Scene::new(room.architecture);
    scene.prompt = plan.prompt.clone();
    scene.seed = seed;
    let present: BTreeMap<&str, usize> = poses
        .keys()
        .map(|&i| (plan.objects[i].id.as_str(), i))
        .collect();
    for (i, o) in plan.objects.iter().enumerate() {
        let Some(pose) = poses.get(&i) else { continue };
        let info = &infos[i];
        let [sx, sy, sz] = info.size.map(f64::from);
        let mut support = o.support;
        let mut relations: Vec<Relation> = o
            .relations
            .iter()
            .filter(|r| {
                present.contains_key(r.target.as_str())
                    || scene.architecture.wall(&r.target).is_some()
                    || r.target == scenethesis_scene_graph::GROUND_ID
            })
            .cloned()
            .collect();
        if o.parent == ParentRef::Ground {
            match walls.get(&i) {
                Some(w) => {
                    support = RelationKind::AgainstWall;
                    relations.retain(|r| r.kind != RelationKind::AgainstWall);
                    relations.insert(0, Relation::new(RelationKind::AgainstWall, w.clone()));
                }
                None => {
                    if support == RelationKind::AgainstWall {
                        support = RelationKind::OnFloor;
                    }
                    relations.retain(|r| r.kind != RelationKind::AgainstWall);
                }
            }
        }
        scene.objects.push(SceneObject {
            id: o.id.clone(),
            category: o.category.clone(),
            asset: info.source.clone(),
            pose: *pose,
            parent: o.parent.clone(),
            support,
            relations,
            local_bounds: Aabb::new(
                nalgebra::Point3::new(-sx / 2.0, 0.0, -sz / 2.0),
                nalgebra::Point3::new(sx / 2.0, sy, sz / 2.0),
            ),
        });
    }
    scene.anchor = if present.contains_key(plan.anchor.as_str()) {
        Some(plan.anchor.clone())
    } else {
        scene
            .objects
            .iter()
            .find(|o| o.parent == ParentRef::Ground && !o.id.is_empty())
            .map(|o| o.id.clone())
    };
    scene
}
