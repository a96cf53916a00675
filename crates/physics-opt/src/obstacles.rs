//! The obstacles an object is optimized against: a [`SceneSdf`] of the objects already placed
//! and of the architecture, with stable indices and world boxes so that the inner loop only
//! queries the few fields near the object.

use std::sync::Arc;

use nalgebra::{Point3, Vector3};
use scenethesis_scene_graph::{Aabb, Pose};
use scenethesis_sdf::{SceneSdf, SignedDistance};

use scenethesis_correspondence::params::world_point;

/// A [`SceneSdf`] (negative inside) plus, per field, a stable index, its world box and whether
/// it is architecture.
#[derive(Default)]
pub struct Obstacles {
    scene: SceneSdf,
    ids: Vec<String>,
    bounds: Vec<Aabb>,
    architecture: Vec<bool>,
    points: Vec<Vec<Point3<f64>>>,
    lipschitz: Vec<bool>,
    exact: bool,
}

impl Obstacles {
    /// An empty set. `exact` says whether its fields are exact mesh fields (objects optimized
    /// against it then use their own exact field too) or baked grids.
    pub fn new(exact: bool) -> Self {
        Self {
            exact,
            ..Self::default()
        }
    }

    /// Whether the fields are exact (rather than baked grids).
    pub fn is_exact(&self) -> bool {
        self.exact
    }

    /// Adds (or re-places) the field `id` with `pose`. `architecture` marks floors and walls.
    /// `samples` are surface points of the object in its own frame: they are posed and kept so
    /// that an object optimized later can test them against its own field (penetration is
    /// checked in both directions).
    pub fn insert(
        &mut self,
        id: &str,
        field: Arc<dyn SignedDistance>,
        pose: Pose,
        architecture: bool,
        samples: &[Point3<f64>],
    ) {
        let world: Vec<Point3<f64>> = samples.iter().map(|p| world_point(&pose, p)).collect();
        let lipschitz = field.is_lipschitz();
        self.scene.insert(id, field, pose);
        let (lo, hi) = self
            .scene
            .world_bounds(id)
            .unwrap_or((Point3::origin(), Point3::origin()));
        let bounds = Aabb::new(lo.cast::<f64>(), hi.cast::<f64>());
        match self.index_of(id) {
            Some(i) => {
                self.bounds[i] = bounds;
                self.architecture[i] = architecture;
                self.points[i] = world;
                self.lipschitz[i] = lipschitz;
            }
            None => {
                self.ids.push(id.to_owned());
                self.bounds.push(bounds);
                self.architecture.push(architecture);
                self.points.push(world);
                self.lipschitz.push(lipschitz);
            }
        }
    }

    /// The underlying scene field.
    pub fn scene(&self) -> &SceneSdf {
        &self.scene
    }

    /// Number of fields.
    pub fn len(&self) -> usize {
        self.ids.len()
    }

    /// Whether there are no fields.
    pub fn is_empty(&self) -> bool {
        self.ids.is_empty()
    }

    /// The id of field `index`.
    pub fn id(&self, index: usize) -> &str {
        &self.ids[index]
    }

    /// Whether field `index` is architecture (floor or wall).
    pub fn is_architecture(&self, index: usize) -> bool {
        self.architecture[index]
    }

    /// The index of the field `id`.
    pub fn index_of(&self, id: &str) -> Option<usize> {
        self.ids.iter().position(|f| f == id)
    }

    /// The world bounding box of field `index`.
    pub fn bounds(&self, index: usize) -> &Aabb {
        &self.bounds[index]
    }

    /// The posed surface samples of field `index` (empty for architecture).
    pub fn samples(&self, index: usize) -> &[Point3<f64>] {
        &self.points[index]
    }

    /// Whether field `index` is a true signed distance
    /// ([`SignedDistance::is_lipschitz`]).
    pub fn is_lipschitz(&self, index: usize) -> bool {
        self.lipschitz[index]
    }

    /// The signed distance from world point `p` to field `index`.
    pub fn distance_to(&self, index: usize, p: &Point3<f64>) -> f64 {
        self.scene
            .distance_to(&self.ids[index], &p.cast::<f32>())
            .map_or(f64::INFINITY, f64::from)
    }

    /// Whether the surface of field `index` comes within `radius` of world point `p`, when
    /// its field answers that more cheaply than a distance
    /// ([`SignedDistance::surface_within`]).
    pub fn surface_within(&self, index: usize, p: &Point3<f64>, radius: f64) -> Option<bool> {
        self.scene
            .surface_within(&self.ids[index], &p.cast::<f32>(), radius as f32)
    }

    /// The outward unit gradient of field `index` at world point `p`.
    pub fn gradient_of(&self, index: usize, p: &Point3<f64>) -> Vector3<f64> {
        self.scene
            .distance_and_gradient_to(&self.ids[index], &p.cast::<f32>())
            .and_then(|(_, g)| g.cast::<f64>().try_normalize(1e-12))
            .unwrap_or_else(Vector3::y)
    }

    /// Indices of the fields whose boxes come within `margin` of `region`.
    pub fn near_box(&self, region: &Aabb, margin: f64) -> Vec<usize> {
        (0..self.ids.len())
            .filter(|&i| box_gap(&self.bounds[i], region) < margin)
            .collect()
    }
}

/// The largest per-axis separation between two boxes (negative when they overlap).
pub fn box_gap(a: &Aabb, b: &Aabb) -> f64 {
    (0..3)
        .map(|i| (a.min[i] - b.max[i]).max(b.min[i] - a.max[i]))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// Euclidean distance from `p` to a box (0 inside).
pub fn box_distance(b: &Aabb, p: &Point3<f64>) -> f64 {
    let mut s = 0.0;
    for i in 0..3 {
        let d = (b.min[i] - p[i]).max(p[i] - b.max[i]).max(0.0);
        s += d * d;
    }
    s.sqrt()
}

/// The world points of `local` points under `pose`.
pub fn posed_points(pose: &Pose, local: &[Point3<f64>]) -> Vec<Point3<f64>> {
    local.iter().map(|p| world_point(pose, p)).collect()
}
