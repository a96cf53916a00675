//! The convex hull of points on a plane: the one routine behind footprints seen from above
//! (the vision lift's floor outlines, the optimizer's footprints and supported feet).

use nalgebra::Point2;

/// The convex hull of `points` in counter-clockwise order (Andrew's monotone chain); collinear
/// points and points with a non-finite coordinate are dropped, and fewer than three distinct
/// points are returned as they are.
///
/// ```
/// use scenethesis_scene_graph::convex_hull;
/// use scenethesis_scene_graph::nalgebra::Point2;
///
/// let square_and_inside = [
///     Point2::new(0.0, 0.0),
///     Point2::new(1.0, 0.0),
///     Point2::new(0.5, 0.0),
///     Point2::new(1.0, 1.0),
///     Point2::new(0.0, 1.0),
///     Point2::new(0.5, 0.5),
/// ];
/// assert_eq!(convex_hull(&square_and_inside).len(), 4);
/// ```
pub fn convex_hull(points: &[Point2<f64>]) -> Vec<Point2<f64>> {
    let mut pts: Vec<Point2<f64>> = points
        .iter()
        .copied()
        .filter(|p| p.x.is_finite() && p.y.is_finite())
        .collect();
    pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: &Point2<f64>, a: &Point2<f64>, b: &Point2<f64>| (a - o).perp(&(b - o));
    let mut hull: Vec<Point2<f64>> = Vec::with_capacity(pts.len() * 2);
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &Point2<f64>>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for p in iter {
            while hull.len() >= start + 2
                && cross(&hull[hull.len() - 2], &hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(*p);
        }
        hull.pop();
    }
    hull
}
