//! An asset's footprint: the convex hull of its outline seen from above, and the floor extent
//! it covers at a pose. A turned object whose outline is not its bounding rectangle (a round
//! plant, a chair's splayed legs) covers less of the floor than its turned bounding box, so the
//! room's walls are kept by the footprint, not by the box.

use nalgebra::{Point2, Point3};
use scenethesis_correspondence::params::world_point;
use scenethesis_scene_graph::{convex_hull, Pose};

/// The outline of an asset seen from above, as the convex hull of its vertices' (x, z) in the
/// asset frame.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Footprint {
    hull: Vec<Point2<f64>>,
}

impl Footprint {
    /// The footprint of the asset-frame points `points` (its vertices).
    pub(crate) fn of(points: impl IntoIterator<Item = Point3<f64>>) -> Self {
        let outline: Vec<Point2<f64>> = points.into_iter().map(|p| Point2::new(p.x, p.z)).collect();
        Self {
            hull: convex_hull(&outline),
        }
    }

    /// The smallest and largest world (x, z) the footprint covers at `pose`; `None` for an
    /// empty footprint.
    pub(crate) fn extent(&self, pose: &Pose) -> Option<(Point2<f64>, Point2<f64>)> {
        let mut corners = self
            .hull
            .iter()
            .map(|c| world_point(pose, &Point3::new(c.x, 0.0, c.y)));
        let first = corners.next()?;
        let start = (Point2::new(first.x, first.z), Point2::new(first.x, first.z));
        Some(corners.fold(start, |(lo, hi), w| {
            (
                Point2::new(lo.x.min(w.x), lo.y.min(w.z)),
                Point2::new(hi.x.max(w.x), hi.y.max(w.z)),
            )
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn a_turned_disc_covers_its_radius_where_its_box_covers_the_diagonal() {
        let rim: Vec<Point3<f64>> = (0..64)
            .map(|k| {
                let a = k as f64 / 64.0 * std::f64::consts::TAU;
                Point3::new(0.3 * a.cos(), 0.0, 0.3 * a.sin())
            })
            .collect();
        let disc = Footprint::of(rim);
        let turned = Pose::new(1.0, 0.5, Vector3::new(2.0, 0.0, -1.0));
        let (lo, hi) = disc.extent(&turned).unwrap();
        // Within the rim's chord sag of the radius, while the turned 0.6 m box would reach
        // 0.3 (cos 0.5 + sin 0.5) = 0.407 m from the centre.
        assert!((hi.x - 2.0 - 0.3).abs() < 2e-3 && (2.0 - lo.x - 0.3).abs() < 2e-3);
        assert!((hi.y + 1.0 - 0.3).abs() < 2e-3, "{hi}");
    }
}
