use nalgebra::{Matrix4, Point3, Rotation3, Vector3};
use serde::{Deserialize, Serialize};

/// `yaw` wrapped into (−π, π], the range every yaw the stages write lies in.
///
/// ```
/// use scenethesis_scene_graph::wrap_yaw;
/// use std::f64::consts::PI;
/// assert_eq!(wrap_yaw(1.5 * PI), -0.5 * PI);
/// assert_eq!(wrap_yaw(-PI), PI);
/// assert_eq!(wrap_yaw(0.25), 0.25);
/// ```
pub fn wrap_yaw(yaw: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    let pi = std::f64::consts::PI;
    let mut y = yaw % tau;
    if y > pi {
        y -= tau;
    }
    if y <= -pi {
        y += tau;
    }
    y
}

/// The angle between two yaws, in [0, π].
///
/// ```
/// use scenethesis_scene_graph::yaw_distance;
/// use std::f64::consts::PI;
/// assert!((yaw_distance(0.9 * PI, -0.9 * PI) - 0.2 * PI).abs() < 1e-12);
/// ```
pub fn yaw_distance(a: f64, b: f64) -> f64 {
    yaw_distance_modulo(a, b, std::f64::consts::TAU)
}

/// The angle between two yaws when turns of `period` radians look the same (a shape with a
/// `TAU / period`-fold symmetry: `PI` for a rectangle's axes, `FRAC_PI_2` for a square), in
/// [0, `period` / 2].
///
/// ```
/// use scenethesis_scene_graph::yaw_distance_modulo;
/// use std::f64::consts::{FRAC_PI_2, PI};
/// assert!(yaw_distance_modulo(0.1, 0.1 + PI, PI) < 1e-12);
/// assert!((yaw_distance_modulo(0.0, 0.4 * PI, FRAC_PI_2) - 0.1 * PI).abs() < 1e-12);
/// ```
pub fn yaw_distance_modulo(a: f64, b: f64, period: f64) -> f64 {
    let d = (a - b).rem_euclid(period);
    d.min(period - d)
}

/// The 5-DoF pose of an object: uniform scale, yaw about +Y and translation.
///
/// A point `p` of the asset's own frame maps to the world as `translation + R_y(yaw) · (scale · p)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    /// Uniform scale factor applied to the asset (must be positive).
    pub scale: f64,
    /// Rotation about the world +Y axis in radians; positive turns +Z toward +X.
    pub yaw: f64,
    /// World position of the asset frame's origin, in metres.
    pub translation: Vector3<f64>,
}

impl Default for Pose {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Pose {
    /// Unit scale, no rotation, at the world origin.
    pub const IDENTITY: Pose = Pose {
        scale: 1.0,
        yaw: 0.0,
        translation: Vector3::new(0.0, 0.0, 0.0),
    };

    /// A pose from its three parts.
    pub fn new(scale: f64, yaw: f64, translation: Vector3<f64>) -> Self {
        Self {
            scale,
            yaw,
            translation,
        }
    }

    /// The pose's five numbers bit for bit (scale, yaw, translation x, y, z): a key under which
    /// two poses are equal exactly when every later computation from them gives the same
    /// result (`-0.0` and `0.0` differ).
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use scenethesis_scene_graph::Pose;
    /// let p = Pose::new(1.0, 0.0, Vector3::new(0.5, 0.0, -1.0));
    /// assert_eq!(p.to_bits(), p.to_bits());
    /// assert_ne!(p.to_bits(), Pose::new(1.0, -0.0, p.translation).to_bits());
    /// ```
    pub fn to_bits(&self) -> [u64; 5] {
        let t = self.translation;
        [self.scale, self.yaw, t.x, t.y, t.z].map(f64::to_bits)
    }

    /// The rotation about +Y by [`Pose::yaw`].
    pub fn rotation(&self) -> Rotation3<f64> {
        Rotation3::from_axis_angle(&Vector3::y_axis(), self.yaw)
    }

    /// Maps a point of the asset's frame to world coordinates.
    pub fn transform_point(&self, local: &Point3<f64>) -> Point3<f64> {
        Point3::from(self.rotation() * (local.coords * self.scale) + self.translation)
    }

    /// Maps a world point into the asset's frame (the inverse of [`Pose::transform_point`]).
    pub fn inverse_transform_point(&self, world: &Point3<f64>) -> Point3<f64> {
        Point3::from(self.rotation().inverse() * (world.coords - self.translation) / self.scale)
    }

    /// Maps a direction of the asset's frame to world coordinates (rotation only).
    pub fn transform_vector(&self, local: &Vector3<f64>) -> Vector3<f64> {
        self.rotation() * local
    }

    /// The object's canonical front (+Z of its frame) in world coordinates.
    pub fn front(&self) -> Vector3<f64> {
        self.transform_vector(&Vector3::z())
    }

    /// The 4×4 homogeneous world-from-asset matrix.
    pub fn to_matrix(&self) -> Matrix4<f64> {
        let mut m = self.rotation().to_homogeneous() * Matrix4::new_scaling(self.scale);
        m.fixed_view_mut::<3, 1>(0, 3).copy_from(&self.translation);
        m
    }

    /// Whether every number of the pose is finite.
    pub fn is_finite(&self) -> bool {
        self.scale.is_finite()
            && self.yaw.is_finite()
            && self.translation.iter().all(|v| v.is_finite())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn yaw_turns_front_toward_plus_x() {
        let pose = Pose::new(1.0, FRAC_PI_2, Vector3::zeros());
        let front = pose.front();
        assert!((front - Vector3::x()).norm() < 1e-12, "front was {front:?}");
    }

    #[test]
    fn inverse_undoes_transform_and_matches_matrix() {
        let pose = Pose::new(1.7, 0.4, Vector3::new(1.0, -2.0, 3.0));
        let p = Point3::new(0.3, 0.2, -0.9);
        let w = pose.transform_point(&p);
        assert!((pose.inverse_transform_point(&w) - p).norm() < 1e-12);
        let h = pose.to_matrix() * p.to_homogeneous();
        assert!((Point3::from_homogeneous(h).unwrap() - w).norm() < 1e-12);
    }
}
