//! Per-asset preparation, done once per asset and shared by every object that uses it: the
//! exact and baked signed distance fields, seeded surface and bottom samples, the centroid, and
//! the metadata the losses need (support surfaces, scale range, placement).

use std::sync::{Arc, OnceLock};

use nalgebra::{Point3, Vector3};
use scenethesis_scene_graph::{Aabb, Mesh, Pose};
use scenethesis_scene_graph::{Asset, Placement, SupportSurface};
use scenethesis_sdf::{sampling, GridSdf, MeshSdf, SignedDistance};
use serde::{Deserialize, Serialize};

use crate::footprint::Footprint;
use crate::PhysicsOptError;

/// How densely to sample an asset.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PrepareSettings {
    /// Least number of surface samples used by the collision losses (the paper uses n = 400).
    pub surface_samples: usize,
    /// Largest mean spacing of the collision samples, metres: big assets get more than
    /// `surface_samples` so that thin parts (a 4 cm table top) cannot slip between them.
    pub surface_spacing: f64,
    /// Upper limit of the collision samples.
    pub max_surface_samples: usize,
    /// Samples on the bottom face of the bounding box used by the stability loss.
    pub bottom_samples: usize,
    /// Least number of surface samples (besides every vertex) used to check the
    /// post-conditions.
    pub check_samples: usize,
    /// Largest mean spacing of the check samples, metres (the collision metric uses about one
    /// sample per cm²).
    pub check_spacing: f64,
    /// Upper limit of the check samples.
    pub max_check_samples: usize,
    /// Largest cell edge of the baked grid in metres (`None`: the grid's default, at most
    /// 2 cm and at most 1/64 of the longest side).
    pub grid_cell: Option<f32>,
    /// Seed of all sampling.
    pub seed: u64,
}

impl Default for PrepareSettings {
    fn default() -> Self {
        Self {
            surface_samples: 400,
            surface_spacing: 0.02,
            max_surface_samples: 6000,
            bottom_samples: 32,
            check_samples: 2000,
            check_spacing: 0.01,
            max_check_samples: 12000,
            grid_cell: None,
            seed: 0x5ce7_e515,
        }
    }
}

/// An asset ready for optimization.
pub struct PreparedAsset {
    exact: Arc<MeshSdf>,
    grid: Arc<LazyGrid>,
    surface_points: Vec<Point3<f64>>,
    bottom_points: Vec<Point3<f64>>,
    check_points: Vec<Point3<f64>>,
    centroid: Point3<f64>,
    bounds: Aabb,
    footprint: Footprint,
    sample_spacing: f64,
    support_surfaces: Vec<SupportSurface>,
    scale_range: [f64; 2],
    placement: Placement,
}

impl std::fmt::Debug for PreparedAsset {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PreparedAsset")
            .field("bounds", &self.bounds)
            .field("surface_points", &self.surface_points.len())
            .field("scale_range", &self.scale_range)
            .field("placement", &self.placement)
            .finish_non_exhaustive()
    }
}

impl PreparedAsset {
    /// Prepares a mesh (asset frame) with its support surfaces, allowed scale range and
    /// placement. `name` only labels errors.
    pub fn new(
        name: &str,
        mesh: &Mesh,
        support_surfaces: Vec<SupportSurface>,
        scale_range: [f64; 2],
        placement: Placement,
        settings: &PrepareSettings,
    ) -> Result<Self, PhysicsOptError> {
        let bounds = mesh.bounds().ok_or_else(|| PhysicsOptError::EmptyMesh {
            asset: name.to_owned(),
        })?;
        if !(scale_range[0] > 0.0 && scale_range[0] <= scale_range[1]) {
            return Err(PhysicsOptError::InvalidScaleRange {
                asset: name.to_owned(),
                range: scale_range,
            });
        }
        let exact = MeshSdf::from_mesh(mesh).map_err(|source| PhysicsOptError::Sdf {
            asset: name.to_owned(),
            source,
        })?;
        let to64 = |p: &Point3<f32>| p.cast::<f64>();
        let area = surface_area(mesh);
        let count = |least: usize, spacing: f64, most: usize| {
            let by_area = (area / (spacing * spacing).max(1e-12)).ceil() as usize;
            by_area.clamp(least, most.max(least))
        };
        let surface_count = count(
            settings.surface_samples,
            settings.surface_spacing,
            settings.max_surface_samples,
        );
        let surface: Vec<Point3<f64>> =
            sampling::surface_points(mesh, surface_count, settings.seed)
                .iter()
                .map(to64)
                .collect();
        if surface.is_empty() {
            return Err(PhysicsOptError::EmptyMesh {
                asset: name.to_owned(),
            });
        }
        let sample_spacing = (area / surface.len() as f64).sqrt();
        let centroid = Point3::from(
            surface
                .iter()
                .fold(Vector3::zeros(), |acc, p| acc + p.coords)
                / surface.len() as f64,
        );
        let mut surface = surface;
        // Corners are where thin penetrations hide between random samples: add the vertices
        // (evenly thinned to at most as many as the samples).
        let vertex_count = mesh.vertex_count().max(1);
        let stride = vertex_count.div_ceil(surface_count.max(1)).max(1);
        surface.extend(
            mesh.parts
                .iter()
                .flat_map(|p| p.positions.iter())
                .step_by(stride)
                .map(|p| Point3::from(*p).cast::<f64>()),
        );
        let (lo, hi) = (bounds.min.cast::<f32>(), bounds.max.cast::<f32>());
        let bottom = sampling::bottom_points(
            lo,
            hi,
            0.0,
            settings.bottom_samples.max(1),
            settings.seed ^ 0xb0,
        )
        .iter()
        .map(to64)
        .collect();
        let mut check: Vec<Point3<f64>> = sampling::surface_points(
            mesh,
            count(
                settings.check_samples,
                settings.check_spacing,
                settings.max_check_samples,
            ),
            settings.seed ^ 0xc4,
        )
        .iter()
        .map(to64)
        .collect();
        for part in &mesh.parts {
            check.extend(
                part.positions
                    .iter()
                    .map(|p| Point3::from(*p).cast::<f64>()),
            );
        }
        let footprint = Footprint::of(
            mesh.parts
                .iter()
                .flat_map(|p| p.positions.iter())
                .map(|p| Point3::from(*p).cast::<f64>()),
        );
        let exact = Arc::new(exact);
        Ok(Self {
            grid: Arc::new(LazyGrid::new(exact.clone(), settings.grid_cell)),
            exact,
            surface_points: surface,
            bottom_points: bottom,
            check_points: check,
            centroid,
            bounds,
            footprint,
            sample_spacing,
            support_surfaces,
            scale_range,
            placement,
        })
    }

    /// The same asset with its dense check samples as collision samples: the final separation
    /// pass ([`crate::optimize_scene`]) resolves penetration as the post-conditions see it, at
    /// about one sample per cm² plus every vertex, instead of the inner loop's sparse samples.
    pub(crate) fn densified(&self) -> Self {
        let ratio = self.surface_points.len() as f64 / self.check_points.len().max(1) as f64;
        Self {
            exact: self.exact.clone(),
            grid: self.grid.clone(),
            surface_points: self.check_points.clone(),
            bottom_points: self.bottom_points.clone(),
            check_points: self.check_points.clone(),
            centroid: self.centroid,
            bounds: self.bounds,
            footprint: self.footprint.clone(),
            sample_spacing: self.sample_spacing * ratio.sqrt(),
            support_surfaces: self.support_surfaces.clone(),
            scale_range: self.scale_range,
            placement: self.placement,
        }
    }

    /// Prepares a library asset with its own metadata.
    pub fn from_asset(asset: &Asset, settings: &PrepareSettings) -> Result<Self, PhysicsOptError> {
        let [lo, hi] = asset.info.scale_range;
        Self::new(
            &asset.info.source.to_string(),
            &asset.mesh,
            asset.info.support_surfaces.clone(),
            [lo as f64, hi as f64],
            asset.info.placement,
            settings,
        )
    }

    /// The exact field (for post-condition checks).
    pub fn exact_field(&self) -> Arc<dyn SignedDistance> {
        self.exact.clone()
    }

    /// The baked grid field (for the inner loop), baked the first time it is asked for a
    /// distance: an asset no other object comes near never pays for its grid.
    pub fn grid_field(&self) -> Arc<dyn SignedDistance> {
        self.grid.clone()
    }

    /// Surface samples for the collision losses (area-uniform samples plus the mesh's
    /// vertices), asset frame.
    pub fn surface_points(&self) -> &[Point3<f64>] {
        &self.surface_points
    }

    /// Samples on the bottom face of the bounding box, asset frame.
    pub fn bottom_points(&self) -> &[Point3<f64>] {
        &self.bottom_points
    }

    /// Dense surface samples plus every vertex, asset frame, for the post-conditions.
    pub fn check_points(&self) -> &[Point3<f64>] {
        &self.check_points
    }

    /// The centroid of the surface samples, asset frame.
    pub fn centroid(&self) -> Point3<f64> {
        self.centroid
    }

    /// The mesh's bounding box, asset frame.
    pub fn bounds(&self) -> &Aabb {
        &self.bounds
    }

    /// The world box the asset spans at `pose`: the heights of its turned bounding box, and
    /// across the floor the extent of its footprint (the convex hull of its outline seen from
    /// above), which for a turned asset whose outline is not its bounding rectangle is
    /// tighter than the turned box (a round plant turned by 30° still spans its radius).
    pub fn footprint_box(&self, pose: &Pose) -> Aabb {
        let turned = self.bounds.transformed(pose);
        match self.footprint.extent(pose) {
            Some((lo, hi)) => Aabb::new(
                Point3::new(lo.x, turned.min.y, lo.y),
                Point3::new(hi.x, turned.max.y, hi.y),
            ),
            None => turned,
        }
    }

    /// The mean spacing of the surface samples, metres (at scale 1).
    pub fn sample_spacing(&self) -> f64 {
        self.sample_spacing
    }

    /// The support surfaces (asset frame).
    pub fn support_surfaces(&self) -> &[SupportSurface] {
        &self.support_surfaces
    }

    /// The allowed uniform scale range.
    pub fn scale_range(&self) -> [f64; 2] {
        self.scale_range
    }

    /// Where the asset is normally placed.
    pub fn placement(&self) -> Placement {
        self.placement
    }
}

/// Total triangle area of a mesh (overlapping parts counted once each).
fn surface_area(mesh: &Mesh) -> f64 {
    mesh.parts
        .iter()
        .flat_map(|part| (0..part.triangles.len()).map(move |t| part.triangle(t)))
        .map(|[a, b, c]| ((b - a).cross(&(c - a))).norm() as f64 / 2.0)
        .sum()
}

/// An asset's baked grid field, baked from its exact field the first time a distance or
/// gradient is asked of it (its bounds are the exact field's, known without baking). Most of
/// a room's small objects are never an obstacle close enough to another object's samples to
/// be queried, and baking was the largest share of preparing an asset.
struct LazyGrid {
    exact: Arc<MeshSdf>,
    max_cell: Option<f32>,
    grid: OnceLock<GridSdf>,
}

impl LazyGrid {
    fn new(exact: Arc<MeshSdf>, max_cell: Option<f32>) -> Self {
        Self {
            exact,
            max_cell,
            grid: OnceLock::new(),
        }
    }

    /// The grid, baked now if it is not yet. The bake runs on the calling thread alone: a
    /// query can come from inside a rayon job, and a worker waiting for the bake's own tasks
    /// could otherwise pick up another job that waits for this same grid.
    fn grid(&self) -> &GridSdf {
        self.grid
            .get_or_init(|| GridSdf::bake_on_this_thread(&self.exact, self.max_cell))
    }
}

impl SignedDistance for LazyGrid {
    fn distance(&self, p: &Point3<f32>) -> f32 {
        self.grid().distance(p)
    }

    fn gradient(&self, p: &Point3<f32>) -> Vector3<f32> {
        self.grid().gradient(p)
    }

    fn local_bounds(&self) -> (Point3<f32>, Point3<f32>) {
        self.exact.local_bounds()
    }

    fn distance_and_gradient(&self, p: &Point3<f32>) -> (f32, Vector3<f32>) {
        self.grid().distance_and_gradient(p)
    }
}
