use nalgebra::Point3;
use serde::{Deserialize, Serialize};

use crate::Pose;

/// Footprints whose two sides differ by at most this fraction of the longer count as square.
pub const SQUARE_FOOTPRINT: f64 = 0.15;

/// Whether footprint sides `a` and `b` (metres, either order) are square within
/// [`SQUARE_FOOTPRINT`].
pub fn is_square_footprint(a: f64, b: f64) -> bool {
    (a - b).abs() <= SQUARE_FOOTPRINT * a.max(b)
}

/// An axis-aligned bounding box, in metres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Aabb {
    /// Corner with the smallest coordinates.
    pub min: Point3<f64>,
    /// Corner with the largest coordinates.
    pub max: Point3<f64>,
}

impl Aabb {
    /// A box from its two corners (callers keep `min <= max` on every axis).
    pub fn new(min: Point3<f64>, max: Point3<f64>) -> Self {
        Self { min, max }
    }

    /// The smallest box holding every point, or `None` for no points.
    pub fn from_points<'a>(points: impl IntoIterator<Item = &'a Point3<f64>>) -> Option<Self> {
        let mut iter = points.into_iter();
        let first = *iter.next()?;
        Some(iter.fold(Self::new(first, first), |b, p| b.including(p)))
    }

    /// This box grown to include `p`.
    pub fn including(&self, p: &Point3<f64>) -> Self {
        Self::new(self.min.inf(p), self.max.sup(p))
    }

    /// The smallest box holding both boxes.
    pub fn union(&self, other: &Aabb) -> Self {
        Self::new(self.min.inf(&other.min), self.max.sup(&other.max))
    }

    /// Edge lengths along x, y and z.
    pub fn size(&self) -> nalgebra::Vector3<f64> {
        self.max - self.min
    }

    /// Whether the footprint (x by z) is square within [`SQUARE_FOOTPRINT`]: a silhouette or a
    /// box of it cannot tell front from side.
    ///
    /// ```
    /// use scenethesis_scene_graph::{nalgebra::Point3, Aabb};
    /// let stool = Aabb::new(Point3::new(-0.2, 0.0, -0.19), Point3::new(0.2, 0.45, 0.19));
    /// let bench = Aabb::new(Point3::new(-0.6, 0.0, -0.2), Point3::new(0.6, 0.45, 0.2));
    /// assert!(stool.has_square_footprint());
    /// assert!(!bench.has_square_footprint());
    /// ```
    pub fn has_square_footprint(&self) -> bool {
        let size = self.size();
        is_square_footprint(size.x, size.z)
    }

    /// The centre point.
    pub fn center(&self) -> Point3<f64> {
        nalgebra::center(&self.min, &self.max)
    }

    /// The eight corners.
    pub fn corners(&self) -> [Point3<f64>; 8] {
        let (a, b) = (self.min, self.max);
        [
            Point3::new(a.x, a.y, a.z),
            Point3::new(b.x, a.y, a.z),
            Point3::new(a.x, b.y, a.z),
            Point3::new(b.x, b.y, a.z),
            Point3::new(a.x, a.y, b.z),
            Point3::new(b.x, a.y, b.z),
            Point3::new(a.x, b.y, b.z),
            Point3::new(b.x, b.y, b.z),
        ]
    }

    /// The world-space box of this asset-frame box placed with `pose` (tight for yaw about +Y).
    pub fn transformed(&self, pose: &Pose) -> Self {
        let corners = self.corners().map(|c| pose.transform_point(&c));
        Self::from_points(corners.iter()).expect("eight corners")
    }

    /// Whether the boxes overlap by more than `tolerance` on every axis.
    pub fn overlaps(&self, other: &Aabb, tolerance: f64) -> bool {
        (0..3).all(|i| {
            self.min[i] + tolerance < other.max[i] && other.min[i] + tolerance < self.max[i]
        })
    }

    /// Whether `p` lies inside or on the box.
    pub fn contains_point(&self, p: &Point3<f64>) -> bool {
        // Spelled out per axis: the collision metric calls this for every surface sample of
        // every candidate pair.
        let (lo, hi) = (&self.min, &self.max);
        lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y && lo.z <= p.z && p.z <= hi.z
    }

    /// Whether both corners are finite and ordered on every axis.
    pub fn is_valid(&self) -> bool {
        (0..3).all(|i| {
            self.min[i].is_finite() && self.max[i].is_finite() && self.min[i] <= self.max[i]
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn quarter_turn_swaps_extents() {
        let b = Aabb::new(Point3::new(-1.0, 0.0, -0.5), Point3::new(1.0, 1.0, 0.5));
        let pose = Pose::new(
            2.0,
            std::f64::consts::FRAC_PI_2,
            Vector3::new(10.0, 0.0, 0.0),
        );
        let w = b.transformed(&pose);
        assert!(
            (w.size() - Vector3::new(2.0, 2.0, 4.0)).norm() < 1e-9,
            "{w:?}"
        );
        assert!((w.center() - Point3::new(10.0, 1.0, 0.0)).norm() < 1e-9);
    }
}
