//! The asset library: procedural generators for the built-in categories, import of a user's own
//! asset folder, and the metadata every later stage relies on (category, synonyms, size,
//! placement kind, canonical front and support surfaces).
//!
//! Every asset follows the scene conventions: metres, +Y up, canonical front +Z, and the origin
//! at the centre of the footprint at the lowest point, so that a pose's translation is where the
//! asset stands. Procedural meshes are made of closed, consistently oriented parts that may
//! overlap, with real cavities (shelf compartments, open crates, hollow mugs). Parts are convex
//! wherever possible, so that per-part convex hulls (physics engines, MuJoCo) keep cavities open.

#![warn(missing_docs)]

pub mod catalog;
mod category;
mod furniture;
pub mod import;
mod items;
mod outdoor;
pub mod primitives;
mod random;

/// The asset metadata types live in `scenethesis-scene-graph` (every stage needs them, the
/// generators are one provider); re-exported here.
pub use scenethesis_scene_graph::{Asset, AssetInfo, Placement, SupportSurface, SurfaceKind};
