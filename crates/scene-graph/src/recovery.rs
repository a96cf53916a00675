//! How closely one scene recovers the objects of another whose ids it need not share (a scene
//! built from a guidance image with a different plan): objects pair up by category, nearest
//! first.

use std::collections::BTreeSet;

use crate::Scene;

/// For each object of `truth` named in `ids` (in that order), the distance in metres between
/// its translation and that of the object of `found` of the same category paired with it, or
/// infinity when none is left. Pairs are taken nearest first (ties by the order of `ids`, then
/// by `found`'s id), each object of either scene at most once; an id `truth` lacks is infinite.
///
/// ```
/// use nalgebra::Vector3;
/// use scenethesis_scene_graph::{recovery_errors, Architecture, Scene};
///
/// let truth = Scene::new(Architecture::rectangular_room(4.0, 4.0, 2.6, 0.9));
/// let errors = recovery_errors(&truth, &["sofa_0".to_string()], &truth);
/// assert!(errors[0].is_infinite()); // the truth has no `sofa_0`
/// ```
pub fn recovery_errors(truth: &Scene, ids: &[String], found: &Scene) -> Vec<f64> {
    let mut pairs: Vec<(f64, usize, &str)> = Vec::new();
    for (i, id) in ids.iter().enumerate() {
        let Some(t) = truth.object(id) else {
            continue;
        };
        for o in found.objects.iter().filter(|o| o.category == t.category) {
            let d = (o.pose.translation - t.pose.translation).norm();
            pairs.push((d, i, o.id.as_str()));
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(b.2)));
    let mut errors = vec![f64::INFINITY; ids.len()];
    let mut taken = BTreeSet::new();
    for (d, i, id) in pairs {
        if errors[i].is_finite() || taken.contains(id) {
            continue;
        }
        errors[i] = d;
        taken.insert(id);
    }
    errors
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::object;
    use crate::{Architecture, ParentRef, RelationKind};

    fn scene(objects: &[(&str, &str, f64)]) -> Scene {
        let mut scene = Scene::new(Architecture::rectangular_room(6.0, 6.0, 2.6, 0.9));
        for &(id, category, x) in objects {
            let mut o = object(id, ParentRef::Ground, RelationKind::OnFloor);
            o.category = category.into();
            o.pose.translation.x = x;
            scene.objects.push(o);
        }
        scene
    }

    #[test]
    fn objects_pair_once_nearest_first_and_by_category() {
        let truth = scene(&[
            ("chair_0", "chair", 0.0),
            ("chair_1", "chair", 1.0),
            ("lamp_0", "lamp", 2.0),
        ]);
        // One chair found near chair_1; the lamp found only as a chair.
        let found = scene(&[("chair_7", "chair", 1.05), ("chair_8", "chair", 2.0)]);
        let ids: Vec<String> = ["chair_0", "chair_1", "lamp_0"].map(String::from).into();
        let error = recovery_errors(&truth, &ids, &found);
        assert!((error[1] - 0.05).abs() < 1e-9, "{error:?}");
        assert!(
            (error[0] - 2.0).abs() < 1e-9,
            "chair_0 gets the chair left: {error:?}"
        );
        assert!(error[2].is_infinite(), "no lamp was found: {error:?}");
    }
}
