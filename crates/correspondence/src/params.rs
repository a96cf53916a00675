//! The five pose parameters as a vector, and the derivatives of a posed point with respect to
//! them: the parameters the alignment fit ([`crate::PoseAlignment`]) and the physics optimizer
//! of `scenethesis-physics-opt` both move.

use nalgebra::{Point3, Vector3, Vector5};
use scenethesis_scene_graph::Pose;

/// Index of the scale in a [`PoseVector`].
pub const SCALE: usize = 0;
/// Index of the yaw in a [`PoseVector`].
pub const YAW: usize = 1;
/// Index of the x translation in a [`PoseVector`].
pub const TX: usize = 2;
/// Index of the y translation in a [`PoseVector`].
pub const TY: usize = 3;
/// Index of the z translation in a [`PoseVector`].
pub const TZ: usize = 4;

/// A 5-DoF pose or a derivative with respect to one, ordered (scale, yaw, tx, ty, tz).
pub type PoseVector = Vector5<f64>;

/// The pose as a parameter vector.
pub fn to_vector(pose: &Pose) -> PoseVector {
    Vector5::new(
        pose.scale,
        pose.yaw,
        pose.translation.x,
        pose.translation.y,
        pose.translation.z,
    )
}

/// The pose of a parameter vector.
pub fn from_vector(v: &PoseVector) -> Pose {
    Pose::new(v[SCALE], v[YAW], Vector3::new(v[TX], v[TY], v[TZ]))
}

/// The rotation about +Y by `yaw` applied to `v` (positive yaw turns +Z toward +X).
pub fn rotate_y(yaw: f64, v: &Vector3<f64>) -> Vector3<f64> {
    let (s, c) = yaw.sin_cos();
    Vector3::new(c * v.x + s * v.z, v.y, -s * v.x + c * v.z)
}

/// The inverse rotation of [`rotate_y`].
pub fn unrotate_y(yaw: f64, v: &Vector3<f64>) -> Vector3<f64> {
    rotate_y(-yaw, v)
}

/// The posed world point of an asset-frame point.
pub fn world_point(pose: &Pose, local: &Point3<f64>) -> Point3<f64> {
    Point3::from(pose.translation + rotate_y(pose.yaw, &(local.coords * pose.scale)))
}

/// The Jacobian of [`world_point`] with respect to (scale, yaw, tx, ty, tz): a 3 × 5 matrix
/// returned as its five columns.
pub fn world_point_jacobian(pose: &Pose, local: &Point3<f64>) -> [Vector3<f64>; 5] {
    let (s, c) = pose.yaw.sin_cos();
    let p = local.coords;
    let d_scale = rotate_y(pose.yaw, &p);
    // d/dyaw of (c·x + s·z, y, −s·x + c·z) = (−s·x + c·z, 0, −c·x − s·z).
    let d_yaw = Vector3::new(-s * p.x + c * p.z, 0.0, -c * p.x - s * p.z) * pose.scale;
    [d_scale, d_yaw, Vector3::x(), Vector3::y(), Vector3::z()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn world_point_matches_scene_graph_pose_and_jacobian_matches_differences() {
        let pose = Pose::new(1.3, 0.7, Vector3::new(0.5, -0.2, 1.0));
        let p = Point3::new(0.3, 0.4, -0.8);
        assert!((world_point(&pose, &p) - pose.transform_point(&p)).norm() < 1e-12);
        let jac = world_point_jacobian(&pose, &p);
        let v = to_vector(&pose);
        for (k, column) in jac.iter().enumerate() {
            let h = 1e-6;
            let mut a = v;
            let mut b = v;
            a[k] += h;
            b[k] -= h;
            let fd =
                (world_point(&from_vector(&a), &p) - world_point(&from_vector(&b), &p)) / (2.0 * h);
            assert!(
                (fd - column).norm() < 1e-6,
                "column {k}: {fd:?} vs {column:?}"
            );
        }
        let w = Vector3::new(0.2, 0.1, 0.9);
        assert!((unrotate_y(0.7, &rotate_y(0.7, &w)) - w).norm() < 1e-12);
    }
}
