//! The correspond stage over a whole scene: between the guide and the optimizer, every object
//! the guidance shows is matched against its mask and depth ([`Matcher`], by default the shape
//! matcher) and its pose aligned with matches refreshed while it moves
//! ([`align_to_guidance`]). The aligned poses become the optimizer's starting poses and the
//! final matches its pose-alignment term, so the optimizer runs the paper's two stages:
//! alignment first, then the physical losses.

use std::collections::BTreeMap;

use rayon::prelude::*;
use scenethesis_imagery::{DepthMap, Guidance};
use scenethesis_scene_graph::{Mesh, RelationKind, Scene, SceneObject};
use serde::{Deserialize, Serialize};

use crate::guided::{align_to_guidance, GuidedPose, GuidedSettings};
use crate::matcher::{Matcher, TargetRegion};

/// The yaw that turns `object`'s front (+Z) the way the plan says, when it says so: toward the
/// target of a `facing` relation (an object of `scene`), or away from the wall of an
/// `against-wall` relation (a `facing` target first); for a square footprint, toward what
/// stands in front of it (`fronted_by`). This settles the front/back ambiguity of
/// silhouettes.
pub fn facing_hint(scene: &Scene, object: &SceneObject) -> Option<f64> {
    let here = object.pose.translation;
    let of = |kind: RelationKind| object.relations.iter().filter(move |r| r.kind == kind);
    let faced = of(RelationKind::Facing).find_map(|r| {
        let d = scene.object(&r.target)?.pose.translation - here;
        (d.x.hypot(d.z) > 1e-6).then(|| d.x.atan2(d.z))
    });
    // What it faces decides before the wall behind it (a desk chair beside the side wall).
    let backed = || {
        of(RelationKind::AgainstWall).find_map(|r| {
            let w = scene.architecture.walls.iter().find(|w| w.id == r.target)?;
            let n = w.inward_normal();
            Some(n.x.atan2(n.y))
        })
    };
    faced.or_else(backed).or_else(|| fronted_by(scene, object))
}

/// For a square-footprint object (a round beach umbrella, a square side table), whose
/// silhouette shows no front, the yaw toward what the scene places *in front of* it and away
/// from what it places *behind* it (unit directions summed); `None` otherwise.
fn fronted_by(scene: &Scene, object: &SceneObject) -> Option<f64> {
    if !object.local_bounds.has_square_footprint() {
        return None;
    }
    let here = object.pose.translation;
    let mut sum = (0.0, 0.0);
    for o in scene.objects.iter().filter(|o| o.id != object.id) {
        let sign = o
            .relations
            .iter()
            .filter(|r| r.target == object.id)
            .find_map(|r| match r.kind {
                RelationKind::InFrontOf => Some(1.0),
                RelationKind::Behind => Some(-1.0),
                _ => None,
            });
        let d = o.pose.translation - here;
        let length = d.x.hypot(d.z);
        if let Some(sign) = sign.filter(|_| length > 1e-6) {
            sum.0 += sign * d.x / length;
            sum.1 += sign * d.z / length;
        }
    }
    (sum.0.hypot(sum.1) > 1e-6).then(|| sum.0.atan2(sum.1))
}

/// Aligns every object of `scene` that has a mesh in `meshes` and a mask in `guidance`,
/// starting from its pose in `scene`, with scale kept within `scale_ranges` (by object id,
/// default ×0.7–×1.4 of the starting scale). `depth_scale` multiplies the guidance depth first
/// (the global scale the guide calibrated on the floor; 1 when the depth is already metric).
/// Objects run in parallel; the result does not depend on the thread count unless the
/// settings' time budget runs out (then each object keeps the best pose found in time).
pub fn correspond(
    scene: &Scene,
    meshes: &BTreeMap<String, Mesh>,
    scale_ranges: &BTreeMap<String, [f64; 2]>,
    guidance: &Guidance,
    depth_scale: f64,
    matcher: &dyn Matcher,
    settings: &GuidedSettings,
) -> BTreeMap<String, GuidedPose> {
    // One time budget for the whole stage, shared by the objects aligned in parallel.
    let settings = &settings.started();
    let scaled;
    let depth = match &guidance.depth {
        Some(d) if (depth_scale - 1.0).abs() > 1e-12 => {
            scaled = DepthMap::from_fn(d.width(), d.height(), |u, v| {
                d.get(u, v)
                    .map_or(f32::NAN, |z| (z as f64 * depth_scale) as f32)
            });
            Some(&scaled)
        }
        other => other.as_ref(),
    };
    scene
        .objects
        .par_iter()
        .filter_map(|object| {
            let mesh = meshes.get(&object.id)?;
            let mask = guidance.masks.get(&object.id)?;
            let target = TargetRegion {
                camera: &guidance.camera,
                mask,
                depth,
                image: Some(&guidance.image),
            };
            let s = object.pose.scale;
            let range = scale_ranges
                .get(&object.id)
                .copied()
                .unwrap_or([0.7 * s, 1.4 * s]);
            let hint = facing_hint(scene, object);
            align_to_guidance(mesh, &object.pose, range, &target, matcher, hint, settings)
                .map(|g| (object.id.clone(), g))
        })
        .collect::<Vec<_>>()
        .into_iter()
        .collect()
}

/// An object whose raw lift was kept because it agrees with the guidance better than the pose
/// the alignment fitted (`report.json`'s `alignment.kept_lift`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct KeptLift {
    /// The object.
    pub id: String,
    /// The measures that decided it.
    pub reason: String,
}

/// The objects of a [`correspond`] result that kept their starting pose, by id.
pub fn kept_lift(guided: &BTreeMap<String, GuidedPose>) -> Vec<KeptLift> {
    guided
        .iter()
        .filter_map(|(id, g)| {
            Some(KeptLift {
                id: id.clone(),
                reason: g.kept_start.clone()?,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point3;
    use scenethesis_scene_graph::{yaw_distance, Aabb, Architecture, Relation};

    fn object(id: &str, half: [f64; 2], at: [f64; 2], relations: Vec<Relation>) -> SceneObject {
        let bounds = Aabb::new(
            Point3::new(-half[0], 0.0, -half[1]),
            Point3::new(half[0], 1.0, half[1]),
        );
        SceneObject {
            relations,
            ..SceneObject::standing_box(id, bounds, at[0], at[1])
        }
    }

    #[test]
    fn a_square_object_faces_what_stands_in_front_of_it_and_away_from_what_is_behind() {
        let mut scene = Scene::new(Architecture::rectangular_room(8.0, 8.0, 2.8, 0.9));
        let in_front = |t: &str| vec![Relation::new(RelationKind::InFrontOf, t)];
        scene.objects = vec![
            object("umbrella", [1.0, 1.0], [0.0, 0.0], vec![]),
            object("towel_0", [0.9, 0.4], [0.5, -2.3], in_front("umbrella")),
            object("towel_1", [0.9, 0.4], [-0.5, -2.3], in_front("umbrella")),
            object(
                "cooler",
                [0.3, 0.2],
                [0.0, 1.6],
                vec![Relation::new(RelationKind::Behind, "umbrella")],
            ),
            object("bench", [1.0, 0.3], [0.0, 3.0], vec![]),
        ];
        let hint = facing_hint(&scene, &scene.objects[0]).unwrap();
        assert!(yaw_distance(hint, std::f64::consts::PI) < 1e-9, "{hint}");
        // An oblong object's silhouette shows its front: no hint from what stands around it.
        scene.objects[4] = object("bench", [1.0, 0.3], [0.0, 3.0], vec![]);
        scene.objects[1].relations = in_front("bench");
        assert_eq!(facing_hint(&scene, &scene.objects[4]), None);
    }
}
