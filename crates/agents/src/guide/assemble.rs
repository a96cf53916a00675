//! The layout becomes a scene: ground objects' poses from their footprints (mounted ones at
//! their hanging height), then one scene object per placed plan object with its support and the
//! relations whose targets survived. A wall-mounted object names its wall as parent, with
//! support `mounted`.

use std::collections::BTreeMap;

use nalgebra::Vector3;
use scenethesis_scene_graph::{
    wrap_yaw, Aabb, AssetInfo, ParentRef, Pose, Relation, RelationKind, Scene, SceneObject,
};

use super::room::Room;
use super::shared::WALL_MOUNT_HEIGHT;
use super::walkway::FloorState;
use crate::plan::Plan;

/// Where a placed floor object's back is: against a wall (standing on the floor) or mounted
/// on it (hanging, off the floor).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) enum WallContact {
    /// Standing on the floor with its back against the wall of this id.
    Against(String),
    /// Hanging on the wall of this id.
    Mounted(String),
}

/// The poses of the placed floor objects by plan index, and the wall each one backs onto or
/// hangs on.
pub(super) fn ground_poses(
    state: &FloorState<'_>,
) -> (BTreeMap<usize, Pose>, BTreeMap<usize, WallContact>) {
    let mut poses: BTreeMap<usize, Pose> = BTreeMap::new();
    let mut walls: BTreeMap<usize, WallContact> = BTreeMap::new();
    for p in &state.placed {
        let y = if p.mounted {
            p.bottom
                .unwrap_or((WALL_MOUNT_HEIGHT - p.height / 2.0).max(0.5))
        } else {
            0.0
        };
        poses.insert(
            p.plan_index,
            Pose::new(1.0, wrap_yaw(p.fp.yaw), Vector3::new(p.fp.cx, y, p.fp.cz)),
        );
        if let Some(w) = &p.wall {
            let contact = if p.mounted {
                WallContact::Mounted(w.clone())
            } else {
                WallContact::Against(w.clone())
            };
            walls.insert(p.plan_index, contact);
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
    walls: &BTreeMap<usize, WallContact>,
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
        let mut parent = o.parent.clone();
        if o.parent == ParentRef::Ground {
            match walls.get(&i) {
                Some(WallContact::Against(w)) => {
                    support = RelationKind::AgainstWall;
                    relations.retain(|r| r.kind != RelationKind::AgainstWall);
                    relations.insert(0, Relation::new(RelationKind::AgainstWall, w.clone()));
                }
                Some(WallContact::Mounted(w)) => {
                    // The wall holds it: it names the wall as parent, and the parent link says
                    // what an `against-wall` relation would repeat.
                    parent = ParentRef::Wall(w.clone());
                    support = RelationKind::Mounted;
                    relations.retain(|r| r.kind != RelationKind::AgainstWall);
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
            parent,
            support,
            relations,
            local_bounds: Aabb::new(
                nalgebra::Point3::new(-sx / 2.0, 0.0, -sz / 2.0),
                nalgebra::Point3::new(sx / 2.0, sy, sz / 2.0),
            ),
            joints: scenethesis_scene_graph::JointState::all_closed(&info.joints),
            parent_link: None,
            room: None,
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
