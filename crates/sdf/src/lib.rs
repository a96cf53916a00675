//! Signed distance fields for triangle meshes and whole scenes: exact BVH-accelerated queries,
//! baked grids with trilinear interpolation, and scene-level queries over posed objects. It is
//! the engine under physics-aware optimization and evaluation, and depends on no GPU or async
//! runtime so other projects can use it alone.
//!
//! Conventions: distances are in metres, **negative inside** a solid, and gradients are unit
//! vectors pointing away from the surface (the direction in which the signed distance grows).
//! Queries use `f32` throughout for speed.
//!
//! - [`MeshSdf`]: exact signed distance, closest point and gradient for a triangle mesh. Closed
//!   parts get their sign from angle-weighted pseudo-normals; open parts (meshes with holes) from
//!   the generalized winding number; several overlapping parts combine as a union.
//! - [`GridSdf`]: a grid baked from a [`MeshSdf`] in the object's own frame, with trilinear
//!   value and gradient lookups.
//! - [`BoxSdf`], [`SphereSdf`], [`PlaneSdf`]: analytic fields for architecture and tests.
//! - [`SceneSdf`]: many posed objects (5-DoF [`Pose`]), queried with objects excluded; moving an
//!   object only changes its transform.
//! - [`sampling`]: seeded surface and bottom-band sampling and clustering of penetrating points.
//!
//! The exact field of a 1 m cube next to the analytic one:
//!
//! ```
//! use nalgebra::{Point3, Vector3};
//! use scenethesis_scene_graph::MeshPart;
//! use scenethesis_sdf::{BoxSdf, MeshSdf, SignedDistance};
//!
//! let cube = MeshPart::cuboid("cube", 0, [-0.5; 3], [0.5; 3]);
//! let sdf = MeshSdf::new(&cube.positions, &cube.triangles)?;
//! let exact = BoxSdf::new(Vector3::new(0.5, 0.5, 0.5));
//! for p in [Point3::origin(), Point3::new(1.5, 0.0, 0.0), Point3::new(0.2, 0.45, -0.1)] {
//!     assert!((sdf.signed_distance(&p) - exact.distance(&p)).abs() < 1e-5);
//! }
//! assert!(sdf.contains(&Point3::new(0.4, 0.4, 0.4)));
//! // Outside, the gradient points away from the surface.
//! let (d, g) = sdf.distance_and_gradient(&Point3::new(0.0, 2.0, 0.0));
//! assert!((d - 1.5).abs() < 1e-5 && (g.y - 1.0).abs() < 1e-4);
//! # Ok::<(), scenethesis_sdf::SdfError>(())
//! ```

#![warn(missing_docs)]

mod analytic;
mod bvh;
mod geometry;
mod grid;
mod mesh_sdf;
pub mod sampling;
mod scene;
pub mod shapes;

pub use analytic::{BoxSdf, PlaneSdf, SphereSdf};
pub use grid::GridSdf;
pub use mesh_sdf::{MeshSdf, SignRule};
pub use scene::{SceneQuery, SceneSdf};

pub use scenethesis_scene_graph::{Mesh, Pose};

use nalgebra::{Point3, Vector3};

/// A signed distance field in its own local frame: negative inside, positive outside.
pub trait SignedDistance: Send + Sync {
    /// Signed distance from `p` to the surface, negative inside.
    fn distance(&self, p: &Point3<f32>) -> f32;

    /// Unit gradient of the distance at `p`: points away from the surface (outward outside the
    /// solid, toward the nearest surface point inside it).
    fn gradient(&self, p: &Point3<f32>) -> Vector3<f32>;

    /// The box `(min, max)` holding the solid (its surface and everything inside) in the field's
    /// own frame. Outside this box the distance is positive and at least the distance to the
    /// box; unbounded solids use infinite coordinates.
    fn local_bounds(&self) -> (Point3<f32>, Point3<f32>);

    /// Distance and gradient together (implementations override this when sharing work is
    /// cheaper than two separate queries).
    fn distance_and_gradient(&self, p: &Point3<f32>) -> (f32, Vector3<f32>) {
        (self.distance(p), self.gradient(p))
    }

    /// Whether the distance is 1-Lipschitz: between any two points it changes by at most
    /// their distance, and its sign flips only across the surface (a true signed distance).
    /// A caller that measured `d` at a point then knows, without a query, that the distance is
    /// at least `d − δ` anywhere within `δ` of it. `false` unless the field proves it.
    fn is_lipschitz(&self) -> bool {
        false
    }

    /// Whether some point of the surface lies within `radius` of `p`, ignoring the sign:
    /// `Some` when the field answers that more cheaply than a distance query (a search that
    /// stops at the first triangle found within `radius`), `None` when it cannot.
    fn surface_within(&self, _p: &Point3<f32>, _radius: f32) -> Option<bool> {
        None
    }
}

/// The result of an exact query against a [`MeshSdf`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SdfQuery {
    /// Signed distance, negative inside.
    pub distance: f32,
    /// The surface point nearest to the query point (on the part that decides the distance).
    pub closest_point: Point3<f32>,
    /// Unit gradient of the signed distance, pointing away from the surface.
    pub gradient: Vector3<f32>,
}

/// Errors building signed distance fields or editing a [`SceneSdf`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SdfError {
    /// The mesh holds no usable triangle.
    #[error("{mesh}: no non-degenerate triangles, expected at least one to build a signed distance field")]
    EmptyMesh {
        /// Which mesh or part (e.g. "part `leg_0`").
        mesh: String,
    },
    /// A triangle names a vertex that does not exist.
    #[error("{mesh}: triangle {triangle} uses vertex {index}, but there are only {vertex_count} vertices")]
    IndexOutOfRange {
        /// Which mesh or part.
        mesh: String,
        /// Index of the offending triangle.
        triangle: usize,
        /// The out-of-range vertex index.
        index: u32,
        /// Number of vertices available.
        vertex_count: usize,
    },
    /// A vertex position is NaN or infinite.
    #[error("{mesh}: vertex {index} has non-finite position {position:?}, expected finite metres")]
    NonFiniteVertex {
        /// Which mesh or part.
        mesh: String,
        /// Index of the vertex.
        index: usize,
        /// Its coordinates.
        position: [f32; 3],
    },
    /// A scene edit named an object the [`SceneSdf`] does not hold.
    #[error("scene SDF has no object `{0}`")]
    UnknownObject(String),
    /// A pose had a non-finite number or a non-positive scale.
    #[error("object `{id}`: pose must be finite with positive scale, got {pose:?}")]
    InvalidPose {
        /// The object.
        id: String,
        /// The rejected pose.
        pose: Pose,
    },
}
