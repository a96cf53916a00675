//! Closed, outward-oriented mesh parts to build assets from. Every function returns a part that
//! passes
//! [`MeshPart::is_closed_and_oriented`](scenethesis_scene_graph::MeshPart::is_closed_and_oriented)
//! with positive volume, and [`AssetBuilder`] gathers parts and support surfaces into an asset
//! whose origin is the centre of its footprint at its lowest point (the scene conventions:
//! metres, +Y up, front +Z).
//!
//! The building blocks of the procedural generators (`scenethesis-procedural`), also used by
//! the importers (to tidy parts) and by tests and benches that need simple shapes. One module per
//! kind of shape: boxes (cuboids, oriented and sheared boxes, beams, struts,
//! rounded boxes), round solids (cylinders, cones, spheres, rods, tubes, ring slabs), sweeps
//! (lofts, prisms, polylines, arcs), the convex hull, transforms, polygons in the floor plane and
//! support surfaces.
//!
//! ```
//! use scenethesis_primitives::{cuboid, cylinder, rect_surface, AssetBuilder};
//! use scenethesis_scene_graph::{Material, Placement, SurfaceKind};
//!
//! // A stool: a round seat on a square post, standing on the floor.
//! let mut b = AssetBuilder::new();
//! let wood = b.material(Material {
//!     name: "oak".into(),
//!     base_color: [0.5, 0.3, 0.2, 1.0],
//!     roughness: 0.6,
//!     metallic: 0.0,
//!     texture: None,
//! });
//! b.part(cuboid("post", wood, [-0.03, 0.0, -0.03], [0.03, 0.42, 0.03]));
//! b.part(cylinder("seat", wood, [0.0, 0.0], 0.17, 0.42, 0.45, 24));
//! b.surface(rect_surface("seat", SurfaceKind::Top, [-0.1, -0.1], [0.1, 0.1], 0.45, None, 0.0));
//! let stool = b.finish(Placement::Floor, [0.9, 1.1]);
//! assert!(stool.mesh.parts.iter().all(|p| p.is_closed_and_oriented()));
//! assert!((stool.info.size[1] - 0.45).abs() < 1e-6);
//! ```

#![warn(missing_docs)]

mod boxes;
mod builder;
mod hull;
mod polygon;
mod round;
mod surfaces;
mod sweep;
mod transform;

pub use boxes::{
    beam, box_yaw, cuboid, hexahedron, oriented_box, rotated_box, rounded_box, square_post, strut,
};
pub use builder::AssetBuilder;
pub use hull::convex_hull;
pub use polygon::{disc, rect, regular_polygon};
pub use round::{cylinder, ellipsoid, frustum, ring_slab, rod, rotated_ellipsoid, sphere, tube};
pub use surfaces::{disc_surface, rect_surface};
pub use sweep::{arc, loft, polyline, prism_x, prism_y, prism_z};
pub(crate) use transform::frame;
pub use transform::{
    compact, orient_outward, rotated_y, rotation, rotation_from_y, transformed, translated,
};

#[cfg(test)]
mod tests;
