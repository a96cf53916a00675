//! One matched pair between an asset and the guidance image.

use nalgebra::{Point2, Point3};
use scenethesis_imagery::Camera;
use serde::{Deserialize, Serialize};

/// Which residuals a [`Correspondence`] contributes to the pose-alignment loss.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PairKind {
    /// The 2D distance between the projected asset point and the target pixel, plus the 3D
    /// distance to the target point when one is known (the paper's pair).
    #[default]
    Point,
    /// Only the difference in depth (along the camera's optical axis) between the posed asset
    /// point and the target point: a point-to-plane term for surface pixels whose exact partner
    /// is unknown, which does not hold the object back when it slides sideways.
    Depth,
}

/// One matched pair: a point on the asset and where the guidance image sees it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Correspondence {
    /// The matched point on the asset, in the asset's own frame (scale 1), e.g. a rendered
    /// pixel of the object lifted onto its surface.
    pub asset_point: Point3<f64>,
    /// The matching pixel in the guidance image (`u` right, `v` down).
    pub target_pixel: Point2<f64>,
    /// The matching 3D point lifted from the guidance image's depth, in world coordinates;
    /// `None` when no depth is known (the pair then only contributes to the 2D term).
    pub target_point: Option<Point3<f64>>,
    /// Matching confidence in [0, 1]; consumers ignore pairs below their threshold (the paper
    /// uses τ = 0.6).
    pub confidence: f64,
    /// Which residuals the pair contributes ([`PairKind::Point`] unless stated).
    #[serde(default)]
    pub kind: PairKind,
}

impl Correspondence {
    /// The pair an exact guidance gives for `asset_point` when it is seen at `world_point`: the
    /// pixel where `camera` projects the world point, and the world point itself, as a
    /// [`PairKind::Point`] pair with `confidence`. `None` when the point is behind the camera.
    /// Synthetic pairs like these test an alignment against a known truth.
    ///
    /// ```
    /// use nalgebra::{Point3, Vector3};
    /// use scenethesis_correspondence::Correspondence;
    /// use scenethesis_imagery::{Camera, Intrinsics};
    ///
    /// let camera = Camera::look_at(
    ///     Intrinsics::from_vertical_fov(640, 480, 1.0),
    ///     Point3::new(0.0, 1.5, 3.0),
    ///     Point3::origin(),
    ///     Vector3::y(),
    /// );
    /// let seen = Point3::new(0.0, 0.0, 0.0);
    /// let pair = Correspondence::exact(&camera, Point3::new(0.1, 0.4, 0.0), seen, 0.9).unwrap();
    /// assert_eq!(pair.target_point, Some(seen));
    /// // The point the camera looks at is seen in the middle of the image.
    /// assert!((pair.target_pixel.x - 320.0).abs() < 1e-6);
    /// // Behind the camera, nothing is seen.
    /// assert!(Correspondence::exact(&camera, seen, Point3::new(0.0, 2.0, 6.0), 0.9).is_none());
    /// ```
    pub fn exact(
        camera: &Camera,
        asset_point: Point3<f64>,
        world_point: Point3<f64>,
        confidence: f64,
    ) -> Option<Self> {
        Some(Self {
            asset_point,
            target_pixel: camera.project(&world_point)?.pixel,
            target_point: Some(world_point),
            confidence,
            kind: PairKind::Point,
        })
    }
}
