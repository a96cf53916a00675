//! A child carried by its parent: when the optimizer moves a parent, the objects it holds move
//! rigidly with it, so that a cup stays where it stood on the table.

use scenethesis_correspondence::params::{rotate_y, unrotate_y};
use scenethesis_scene_graph::Pose;

/// A child's pose moved rigidly with its parent from `before` to `after` (position and yaw
/// follow the parent; the child's own scale is kept).
pub(crate) fn carry(before: &Pose, after: &Pose, child: &Pose) -> Pose {
    let local = unrotate_y(before.yaw, &(child.translation - before.translation)) / before.scale;
    let translation = after.translation + rotate_y(after.yaw, &(local * after.scale));
    Pose::new(
        child.scale,
        child.yaw + (after.yaw - before.yaw),
        translation,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn carried_child_keeps_its_place_relative_to_the_parent() {
        let before = Pose::new(1.0, 0.0, Vector3::new(0.0, 0.0, 0.0));
        let after = Pose::new(
            1.0,
            std::f64::consts::FRAC_PI_2,
            Vector3::new(1.0, 0.0, 0.0),
        );
        let child = Pose::new(0.8, 0.1, Vector3::new(0.0, 0.75, 0.3));
        let moved = carry(&before, &after, &child);
        // +Z turns toward +X under a quarter-turn yaw.
        assert!((moved.translation - Vector3::new(1.3, 0.75, 0.0)).norm() < 1e-12);
        assert!((moved.yaw - (0.1 + std::f64::consts::FRAC_PI_2)).abs() < 1e-12);
        assert_eq!(moved.scale, 0.8);
    }
}
