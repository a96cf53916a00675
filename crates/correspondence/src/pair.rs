//! One matched pair between an asset and the guidance image.

use nalgebra::{Point2, Point3};
use serde::{Deserialize, Serialize};

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
}
