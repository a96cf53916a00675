//! The gravity-aligned box recovered for one object, shared by the box phase ([`crate::boxes`])
//! that makes it and the support phase ([`crate::support`]) that reads it.

use nalgebra::{Point2, Point3, Vector2, Vector3};
use serde::{Deserialize, Serialize};

use crate::footprint::FloorRectangle;

/// Where a box's 3D points came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DepthSource {
    /// A metric depth map.
    Measured,
    /// Single-view metrology: the mask's floor contact under the known camera.
    FloorContact,
}

/// A gravity-aligned box recovered for one object.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LiftedBox {
    /// The object's id (its mask's key).
    pub id: String,
    /// World centre of the box in metres.
    pub center: Point3<f64>,
    /// Half extents along the box's own x, y and z axes.
    pub half_extents: Vector3<f64>,
    /// Yaw about +Y in radians (positive turns +Z toward +X); the box's own +Z is the object's
    /// front up to the 180° ambiguity a box cannot settle.
    pub yaw: f64,
    /// How many points support the box.
    pub points: usize,
    /// Where its points came from.
    pub depth_source: DepthSource,
    /// Whether a size prior completed the hidden side.
    pub completed: bool,
    /// The height the points span before a size prior is blended in (metres; the box's own
    /// height when no prior took part): what the image alone says of the object's size, for
    /// choosing among assets without the prior choosing itself.
    #[serde(default)]
    pub seen_height: f64,
}

impl LiftedBox {
    /// A box known rather than lifted (from a plan, a scene or a test): unturned, complete, its
    /// depth source [`DepthSource::Measured`] and no points behind it.
    ///
    /// ```
    /// use scenethesis_vision::LiftedBox;
    /// let table = LiftedBox::axis_aligned("table_0", [0.0, 0.375, 0.0], [0.6, 0.375, 0.4]);
    /// assert!((table.top() - 0.75).abs() < 1e-12);
    /// ```
    pub fn axis_aligned(id: &str, center: [f64; 3], half_extents: [f64; 3]) -> Self {
        Self {
            id: id.to_string(),
            center: Point3::from(center),
            half_extents: Vector3::from(half_extents),
            yaw: 0.0,
            points: 0,
            depth_source: DepthSource::Measured,
            completed: true,
            seen_height: 2.0 * half_extents[1],
        }
    }

    /// Height of the bottom face above the floor.
    pub fn bottom(&self) -> f64 {
        self.center.y - self.half_extents.y
    }

    /// Height of the top face above the floor.
    pub fn top(&self) -> f64 {
        self.center.y + self.half_extents.y
    }

    /// Full size `(x, y, z)` in metres.
    pub fn size(&self) -> Vector3<f64> {
        self.half_extents * 2.0
    }

    /// Intersection over union of the two boxes' volumes (exact for gravity-aligned boxes).
    pub fn iou(&self, other: &LiftedBox) -> f64 {
        let vertical = (self.top().min(other.top()) - self.bottom().max(other.bottom())).max(0.0);
        let inter = self.footprint().intersection_area(&other.footprint()) * vertical;
        let volume = |b: &LiftedBox| b.size().product();
        let union = volume(self) + volume(other) - inter;
        if union > 0.0 {
            inter / union
        } else {
            0.0
        }
    }

    /// The box's floor rectangle.
    pub fn footprint(&self) -> FloorRectangle {
        FloorRectangle {
            center: Point2::new(self.center.x, self.center.z),
            half_extents: Vector2::new(self.half_extents.x, self.half_extents.z),
            yaw: self.yaw,
        }
    }
}
