//! The procedural PBR material library: at least 30 physically based materials (woods,
//! fabrics, metals, stone and ceramic, glass, plastics, paper, plaster and paint, carpet,
//! concrete) generated from code, never downloaded.
//!
//! A library material ([`LibraryMaterial`]) is a family **pattern** (wood grain, weave, pebbled
//! leather, brushed streaks, marble veins, tiles, speckle, …) plus a default colour, roughness
//! and metalness and the real-world size one tile covers. Its [`Maps`] — base colour, tangent-
//! space normal and glTF metallic-roughness (G roughness, B metalness) — are [`TEXTURE_SIZE`]²
//! texels, tileable (the noise is periodic over the tile), deterministic (integer hashing, the
//! same bytes every run) and generated once per process, or once per machine when a folder
//! keeps them between processes ([`keep_maps_in`]). The base-colour map is an albedo
//! *multiplier*: a surface's own colour tints it ([`Maps::color_factor`]), so a red leather and
//! a black leather share one leather texture.
//!
//! A scene [`Material`](scenethesis_scene_graph::Material) finds its library material by name
//! ([`resolve`]): `oak`, `navy_fabric`, `brushed_steel`, `clear_glass`, `red_leather`.
//! Exporters and renderers project texture coordinates per face in metres
//! ([`BoxProjection`]), so grain and tiles have their real size without any generator knowing
//! about textures.
//!
//! ```
//! use scenethesis_materials::{maps, resolve, BoxProjection, MapKind};
//!
//! let leather = resolve("red_leather").expect("a library material");
//! let maps = maps(leather);
//! assert_eq!(&maps.png(MapKind::Normal)[1..4], b"PNG");
//! let seat = BoxProjection::new(leather.tile_size_m, &[[0.0, 0.0, 0.0], [0.5, 0.1, 0.5]]);
//! let top = seat.face([0.0, 1.0, 0.0]);
//! assert_eq!(top.uv([0.5, 0.1, 0.0]), [0.5 / leather.tile_size_m, 0.0]);
//! ```

#![warn(missing_docs)]

pub mod color;
mod kept;
mod library;
mod maps;
pub mod noise;
mod pattern;
mod projection;
mod resolve;
mod surfaces;

pub use kept::{default_maps_folder, keep_maps_in, kept_maps_folder, make_maps, maps};
pub use library::{by_id, library, Family, LibraryMaterial};
pub use maps::{MapKind, Maps, TEXTURE_SIZE};
pub use pattern::{Pattern, Texel};
pub use projection::{BoxProjection, FaceProjection};
pub use resolve::resolve;
pub use surfaces::{
    floor_material, glass_material, ground_material, outdoor_ground, surface_or, wall_material,
    GROUND_SURFACE,
};
