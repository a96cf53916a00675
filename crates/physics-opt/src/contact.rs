//! Penetrations between an object and its obstacles, and their grouping into separate
//! regions: the exchange between the prepared assets and the objective.

use nalgebra::{Point3, Vector3};
use scenethesis_sdf::sampling;

/// A penetration between the object and an obstacle, found from either side: one of the
/// object's surface points inside (or within the margin of) an obstacle, or one of an already
/// placed object's surface points inside the object.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// The contact point in the object's asset frame (scale 1), for clustering.
    pub local: Point3<f64>,
    /// The contact point in world coordinates.
    pub world: Point3<f64>,
    /// Signed distance between the point and the other body (negative inside).
    pub distance: f64,
    /// How much it violates the margin: `margin − distance` (positive).
    pub violation: f64,
    /// Index of the obstacle in the [`crate::Obstacles`].
    pub obstacle: usize,
    /// Unit direction in which moving the object separates this contact fastest: the
    /// obstacle's outward gradient for the object's own points, minus the object's gradient
    /// for an obstacle's points inside the object.
    pub push: Vector3<f64>,
    /// Whether the point belongs to the obstacle (found inside the object).
    pub foreign: bool,
}

/// The collision state of an object at a pose.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CollisionState {
    /// Every violating surface point.
    pub contacts: Vec<Contact>,
    /// The contacts grouped into clusters of nearby points (indices into `contacts`).
    pub clusters: Vec<Vec<usize>>,
}

impl CollisionState {
    /// Whether no point violates the margin.
    pub fn is_free(&self) -> bool {
        self.contacts.is_empty()
    }

    /// The largest violation, 0 when free.
    pub fn worst_violation(&self) -> f64 {
        self.contacts
            .iter()
            .map(|c| c.violation)
            .fold(0.0, f64::max)
    }
}

/// Groups contacts into clusters of points closer than `link_spacings` × `sample_spacing` (the
/// mean spacing of the asset's surface samples) to each other: the paper's `N_cluster`,
/// separate penetration regions. Clusters hold indices into `contacts`.
pub fn cluster_contacts(
    contacts: &[Contact],
    sample_spacing: f64,
    link_spacings: f64,
) -> Vec<Vec<usize>> {
    let points: Vec<Point3<f32>> = contacts.iter().map(|c| c.local.cast::<f32>()).collect();
    let distances = vec![-1.0f32; points.len()];
    sampling::negative_clusters(&points, &distances, (sample_spacing * link_spacings) as f32)
}
