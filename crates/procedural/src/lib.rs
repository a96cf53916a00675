//! The built-in procedural asset library: one category table ([`catalog::CATEGORIES_TOML`], read
//! by retrieval and the planner too) and a seeded generator per category, in folders by the
//! kind of thing they build (furniture, items, outdoor). The mesh building blocks live in
//! `scenethesis-primitives`; importing a user's own files is `scenethesis-import`'s job.
//!
//! Every asset follows the scene conventions: metres, +Y up, canonical front +Z, and the origin
//! at the centre of the footprint at the lowest point, so that a pose's translation is where the
//! asset stands. Procedural meshes are made of closed, consistently oriented parts that may
//! overlap, with real cavities (shelf compartments, open crates, hollow mugs). Parts are convex
//! wherever possible, so that per-part convex hulls (physics engines, MuJoCo) keep cavities open.
//!
//! The entry point is [`catalog`]: look a category up by name or word, then generate it from a
//! seed (the same seed always gives the same asset):
//!
//! ```
//! use scenethesis_procedural::catalog;
//! use scenethesis_scene_graph::{AssetRef, Placement};
//!
//! let desk = catalog::category("desk").expect("a built-in category");
//! let asset = catalog::generate(desk, 7);
//! assert_eq!(asset.info.category, "desk");
//! assert_eq!(asset.info.placement, Placement::Floor);
//! assert!(matches!(&asset.info.source, AssetRef::Procedural { seed: 7, .. }));
//! assert_eq!(catalog::generate(desk, 7).mesh, asset.mesh);
//! ```
//!
//! Module layout: `catalog` (the registry) and `category` (the type of a row) on top, the
//! generator tables below it, `random` (the seeded draws every generator uses) and `materials`
//! (palettes) beside them; materials and articulated parts grow in folders of their own
//! (`materials/`, an `articulation/` beside it) rather than inside the generator files.

#![warn(missing_docs)]

mod articulation;
pub mod catalog;
mod category;
mod furniture;
mod items;
mod materials;
mod outdoor;
mod random;

/// Looks: the palette families, their named materials, and applying a room style and an
/// object's requested colours and materials to a generated asset
/// ([`catalog::generate_with_look`] generates with one).
pub mod looks {
    pub use crate::materials::{apply_look, family_of, named_material, surface_material, Palette};
}
