//! `--keep-plan`: the planned objects the image does not show, placed offline around what the
//! image fixes.
//!
//! The procedural guide lays out the whole plan; each planned object the image left out takes
//! its spot there, parents first: a ground or wall object keeps its offline pose, an object
//! resting on one the image placed keeps its offline pose *relative to* that parent (carried
//! over to where the image put the parent), one resting on a kept object keeps its offline
//! pose. A spot whose box overlaps an object already placed (other than its parent) is taken,
//! and the object is reported instead; nothing ever moves what the image fixes.

use std::collections::BTreeMap;

use scenethesis_agents::{AssetLookup, DroppedObject, Guide, Plan, ProceduralGuide};
use scenethesis_scene_graph::{ParentRef, Pose, Scene, SceneObject};

/// How far (metres, on every axis) two boxes may overlap and still count as apart: resting
/// objects touch, and the optimizer resolves what remains.
const OVERLAP_TOLERANCE: f64 = 0.02;

/// Adds to `scene` the planned objects of `plan` it lacks, at their offline spots around what
/// the image placed (module docs). Returns the objects kept and the ones that found their spot
/// taken (or their parent missing), with why.
pub fn keep_plan(
    scene: &mut Scene,
    plan: &Plan,
    assets: &dyn AssetLookup,
    seed: u64,
) -> (Vec<String>, Vec<DroppedObject>) {
    let shown: BTreeMap<String, Pose> = scene
        .objects
        .iter()
        .map(|o| (o.id.clone(), o.pose))
        .collect();
    let missing: Vec<&str> = plan
        .objects
        .iter()
        .filter(|o| !shown.contains_key(&o.id))
        .map(|o| o.id.as_str())
        .collect();
    if missing.is_empty() {
        return (Vec::new(), Vec::new());
    }
    let offline = match ProceduralGuide::default().layout(plan, assets, seed) {
        Ok(layout) => layout.scene,
        Err(e) => {
            let reason = format!("not in the guidance image, and the offline layout failed: {e}");
            let dropped = missing
                .iter()
                .map(|id| DroppedObject {
                    id: (*id).to_owned(),
                    reason: reason.clone(),
                })
                .collect();
            return (Vec::new(), dropped);
        }
    };
    let mut kept = Vec::new();
    let mut dropped = Vec::new();
    for id in missing {
        match spot(scene, &offline, &shown, id) {
            Ok(object) => {
                scene.objects.push(object);
                kept.push(id.to_owned());
            }
            Err(reason) => dropped.push(DroppedObject {
                id: id.to_owned(),
                reason,
            }),
        }
    }
    (kept, dropped)
}

/// The object `id` at its offline spot around `scene`, or why it has none.
fn spot(
    scene: &Scene,
    offline: &Scene,
    shown: &BTreeMap<String, Pose>,
    id: &str,
) -> Result<SceneObject, String> {
    let Some(mut object) = offline.object(id).cloned() else {
        return Err(
            "not in the guidance image, and the offline layout found no spot for it \
                    either (--keep-plan)"
                .into(),
        );
    };
    if let ParentRef::Object(p) = &object.parent {
        if scene.object(p).is_none() {
            return Err(format!(
                "not in the guidance image, and its parent `{p}` is not in the scene \
                 (--keep-plan)"
            ));
        }
        if let Some(seen) = shown.get(p) {
            let offline_parent = offline.object(p).expect("the offline parent is laid out");
            object.pose = carried(&object.pose, &offline_parent.pose, seen);
        }
    }
    let bounds = object.world_aabb();
    let parent = object.parent.object_id().map(str::to_owned);
    let blocker = scene.objects.iter().find(|o| {
        Some(o.id.as_str()) != parent.as_deref()
            && o.world_aabb().overlaps(&bounds, OVERLAP_TOLERANCE)
    });
    if let Some(b) = blocker {
        return Err(format!(
            "not in the guidance image, and its offline spot overlaps `{}`, which the image \
             places (--keep-plan)",
            b.id
        ));
    }
    object.relations.retain(|r| {
        scene.object(&r.target).is_some()
            || scene.architecture.wall(&r.target).is_some()
            || r.target == scenethesis_scene_graph::GROUND_ID
    });
    Ok(object)
}

/// `pose` relative to `from` (its offline parent), carried over to `to` (where the image put
/// the parent): the same offset in the parent's frame, the same turn relative to it.
fn carried(pose: &Pose, from: &Pose, to: &Pose) -> Pose {
    let local = from.inverse_transform_point(&nalgebra::Point3::from(pose.translation));
    let world = to.transform_point(&local);
    Pose::new(
        pose.scale,
        scenethesis_scene_graph::wrap_yaw(pose.yaw - from.yaw + to.yaw),
        world.coords,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn a_child_keeps_its_offset_in_the_parents_frame() {
        let from = Pose::new(1.0, 0.0, Vector3::new(1.0, 0.0, 0.0));
        let to = Pose::new(
            1.0,
            std::f64::consts::FRAC_PI_2,
            Vector3::new(-2.0, 0.0, 3.0),
        );
        let child = Pose::new(0.9, 0.2, Vector3::new(1.5, 0.7, 0.0));
        let moved = carried(&child, &from, &to);
        // 0.5 m along the parent's +X, turned a quarter about +Y: along world −Z.
        assert!((moved.translation - Vector3::new(-2.0, 0.7, 2.5)).norm() < 1e-9);
        assert!((moved.yaw - (0.2 + std::f64::consts::FRAC_PI_2)).abs() < 1e-9);
        assert_eq!(moved.scale, 0.9);
    }
}
