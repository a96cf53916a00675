//! The library's materials: a family pattern, the size of one tile in metres, and the default
//! colour, roughness and metalness a surface gets when it names the material itself (a room's
//! floor, a prompt's "marble").

use scenethesis_scene_graph::Material;

use crate::pattern::Pattern;

/// The families users name, grouping the library's materials.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Family {
    /// Natural and painted wood, floorboards.
    Wood,
    /// Woven and pile fabrics, felt, leather.
    Fabric,
    /// Bare and coated metals.
    Metal,
    /// Stone, ceramic and concrete.
    Stone,
    /// Glass.
    Glass,
    /// Plastics, rubber and foam.
    Plastic,
    /// Paper and cardboard.
    Paper,
    /// Plaster and wall paint.
    Wall,
    /// Carpet.
    Carpet,
    /// Plants and soil.
    Plant,
}

/// One material of the library.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LibraryMaterial {
    /// Stable identifier, e.g. `oak` or `porcelain_tile`; texture files are named by it.
    pub id: &'static str,
    /// The family it belongs to.
    pub family: Family,
    /// Its pattern.
    pub pattern: Pattern,
    /// The real-world width (and height) one texture tile covers, metres.
    pub tile_size_m: f32,
    /// Default sRGB colour.
    pub srgb: [u8; 3],
    /// Default perceptual roughness.
    pub roughness: f32,
    /// Default metalness (0 or 1 for bare materials; coatings in between).
    pub metallic: f32,
    /// Strength of the normal map: slope of the height field per texel.
    pub bump: f32,
    /// Whether light passes through it (glass): written with a transmission extension.
    pub transmissive: bool,
}

impl LibraryMaterial {
    /// Its index in [`library`].
    pub fn index(&self) -> usize {
        library()
            .iter()
            .position(|m| m.id == self.id)
            .expect("a library material is in the library")
    }

    /// A scene material with the library's defaults, named by its id (so it resolves back to
    /// itself through [`crate::resolve`]).
    pub fn material(&self) -> Material {
        let c = self.srgb.map(crate::color::srgb_byte_to_linear);
        let alpha = if self.transmissive { 0.3 } else { 1.0 };
        Material {
            name: self.id.to_owned(),
            base_color: [c[0], c[1], c[2], alpha],
            roughness: self.roughness,
            metallic: self.metallic,
            texture: None,
        }
    }
}

#[allow(clippy::too_many_arguments)] // one row of the table, read as a row
const fn entry(
    id: &'static str,
    family: Family,
    pattern: Pattern,
    tile_size_m: f32,
    srgb: [u8; 3],
    roughness: f32,
    metallic: f32,
    bump: f32,
) -> LibraryMaterial {
    LibraryMaterial {
        id,
        family,
        pattern,
        tile_size_m,
        srgb,
        roughness,
        metallic,
        bump,
        transmissive: false,
    }
}

const fn wood(rings: u32, contrast: f32, warp: f32, pores: f32) -> Pattern {
    Pattern::Wood {
        rings,
        contrast,
        warp,
        pores,
    }
}

use Family as F;
use Pattern as P;

static LIBRARY: [LibraryMaterial; 49] = [
    // Woods: one tile is a length of board, grain along u.
    entry(
        "oak",
        F::Wood,
        wood(7, 0.35, 1.2, 0.7),
        0.8,
        [0xB8, 0x8A, 0x5A],
        0.6,
        0.0,
        2.0,
    ),
    entry(
        "walnut",
        F::Wood,
        wood(9, 0.45, 2.0, 0.4),
        0.8,
        [0x5D, 0x40, 0x2C],
        0.55,
        0.0,
        1.5,
    ),
    entry(
        "pine",
        F::Wood,
        wood(5, 0.5, 1.0, 0.15),
        0.8,
        [0xD8, 0xB4, 0x7E],
        0.65,
        0.0,
        1.5,
    ),
    entry(
        "maple",
        F::Wood,
        wood(10, 0.15, 0.8, 0.1),
        0.8,
        [0xE0, 0xC0, 0x90],
        0.6,
        0.0,
        1.0,
    ),
    entry(
        "cherry",
        F::Wood,
        wood(8, 0.2, 1.0, 0.15),
        0.8,
        [0x8E, 0x4A, 0x32],
        0.5,
        0.0,
        1.0,
    ),
    entry(
        "teak",
        F::Wood,
        wood(12, 0.3, 0.6, 0.3),
        0.8,
        [0x9A, 0x6A, 0x3C],
        0.55,
        0.0,
        1.5,
    ),
    entry(
        "ash",
        F::Wood,
        wood(6, 0.4, 1.0, 0.6),
        0.8,
        [0xC9, 0xB0, 0x8C],
        0.6,
        0.0,
        2.0,
    ),
    entry(
        "ebony",
        F::Wood,
        wood(14, 0.25, 0.5, 0.1),
        0.8,
        [0x2A, 0x22, 0x1E],
        0.4,
        0.0,
        1.0,
    ),
    entry(
        "rosewood",
        F::Wood,
        wood(11, 0.45, 1.8, 0.3),
        0.8,
        [0x65, 0x30, 0x22],
        0.45,
        0.0,
        1.5,
    ),
    entry(
        "rough_timber",
        F::Wood,
        wood(4, 0.5, 2.5, 0.9),
        0.6,
        [0x5A, 0x3E, 0x28],
        0.9,
        0.0,
        4.0,
    ),
    entry(
        "painted_wood",
        F::Wood,
        P::PaintedWood,
        0.8,
        [0xEE, 0xEC, 0xE6],
        0.5,
        0.0,
        1.0,
    ),
    entry(
        "oak_floorboards",
        F::Wood,
        P::Planks { boards: 7 },
        1.4,
        [0xB0, 0x84, 0x58],
        0.55,
        0.0,
        2.0,
    ),
    // Fabrics: a tile is a small swatch.
    entry(
        "cotton",
        F::Fabric,
        P::Weave {
            threads: 64,
            slub: 0.3,
        },
        0.12,
        [0x80, 0x80, 0x82],
        0.95,
        0.0,
        2.0,
    ),
    entry(
        "linen",
        F::Fabric,
        P::Weave {
            threads: 48,
            slub: 1.0,
        },
        0.12,
        [0xD8, 0xCC, 0xB4],
        0.9,
        0.0,
        2.5,
    ),
    entry(
        "canvas",
        F::Fabric,
        P::Weave {
            threads: 32,
            slub: 0.5,
        },
        0.1,
        [0xD6, 0xCC, 0xB0],
        0.9,
        0.0,
        3.0,
    ),
    entry(
        "wool",
        F::Fabric,
        P::Weave {
            threads: 24,
            slub: 0.8,
        },
        0.15,
        [0x9A, 0x90, 0x84],
        1.0,
        0.0,
        3.5,
    ),
    entry(
        "velvet",
        F::Fabric,
        P::Velvet,
        0.4,
        [0x6A, 0x1E, 0x2E],
        0.85,
        0.0,
        0.8,
    ),
    entry(
        "felt",
        F::Fabric,
        P::Felt,
        0.2,
        [0x2C, 0x6C, 0x44],
        1.0,
        0.0,
        1.5,
    ),
    entry(
        "leather",
        F::Fabric,
        P::Leather,
        0.25,
        [0x6A, 0x40, 0x28],
        0.6,
        0.0,
        2.0,
    ),
    // Metals.
    entry(
        "steel",
        F::Metal,
        P::Polished,
        0.5,
        [0xA8, 0xAA, 0xAD],
        0.35,
        1.0,
        0.3,
    ),
    entry(
        "brushed_steel",
        F::Metal,
        P::Brushed,
        0.3,
        [0x9A, 0x9C, 0x9E],
        0.45,
        1.0,
        0.8,
    ),
    entry(
        "aluminium",
        F::Metal,
        P::Brushed,
        0.4,
        [0xC8, 0xCA, 0xCC],
        0.3,
        1.0,
        0.5,
    ),
    entry(
        "chrome",
        F::Metal,
        P::Polished,
        1.0,
        [0xDD, 0xDE, 0xE0],
        0.08,
        1.0,
        0.1,
    ),
    entry(
        "brass",
        F::Metal,
        P::Polished,
        0.5,
        [0xC8, 0xA0, 0x50],
        0.3,
        1.0,
        0.3,
    ),
    entry(
        "black_iron",
        F::Metal,
        P::CastIron,
        0.3,
        [0x2A, 0x2A, 0x2C],
        0.7,
        1.0,
        2.0,
    ),
    entry(
        "powder_coated_metal",
        F::Metal,
        P::PowderCoat,
        0.2,
        [0x2A, 0x2A, 0x2C],
        0.5,
        0.6,
        0.6,
    ),
    // Stone, ceramic, concrete.
    entry(
        "marble",
        F::Stone,
        P::Marble,
        1.2,
        [0xE8, 0xE6, 0xE2],
        0.25,
        0.0,
        0.5,
    ),
    entry(
        "granite",
        F::Stone,
        P::Granite,
        0.6,
        [0x30, 0x30, 0x32],
        0.3,
        0.0,
        0.5,
    ),
    entry(
        "slate",
        F::Stone,
        P::Slate,
        0.8,
        [0x5C, 0x62, 0x68],
        0.6,
        0.0,
        2.0,
    ),
    entry(
        "travertine",
        F::Stone,
        P::Travertine,
        1.0,
        [0xD6, 0xC8, 0xAC],
        0.5,
        0.0,
        1.5,
    ),
    entry(
        "porcelain_tile",
        F::Stone,
        P::Tiles { tiles: 2 },
        1.2,
        [0xE6, 0xE4, 0xDE],
        0.3,
        0.0,
        3.0,
    ),
    entry(
        "terracotta",
        F::Stone,
        P::Terracotta,
        0.5,
        [0xB8, 0x5C, 0x38],
        0.8,
        0.0,
        1.5,
    ),
    entry(
        "glazed_ceramic",
        F::Stone,
        P::Glaze,
        0.4,
        [0xF0, 0xEE, 0xEA],
        0.2,
        0.0,
        0.3,
    ),
    entry(
        "concrete",
        F::Stone,
        P::Concrete,
        1.5,
        [0xA0, 0x9E, 0x98],
        0.85,
        0.0,
        2.0,
    ),
    // Glass.
    LibraryMaterial {
        transmissive: true,
        ..entry(
            "glass",
            F::Glass,
            P::Polished,
            1.0,
            [0xDC, 0xEC, 0xF0],
            0.05,
            0.0,
            0.05,
        )
    },
    // Plastics, rubber, foam.
    entry(
        "plastic",
        F::Plastic,
        P::Plastic,
        0.3,
        [0xEC, 0xEC, 0xEA],
        0.5,
        0.0,
        0.4,
    ),
    entry(
        "rubber",
        F::Plastic,
        P::Rubber,
        0.2,
        [0x1E, 0x1E, 0x20],
        0.9,
        0.0,
        1.0,
    ),
    entry(
        "foam",
        F::Plastic,
        P::Foam,
        0.15,
        [0x3A, 0x6E, 0xB0],
        0.85,
        0.0,
        2.0,
    ),
    // Paper and cardboard.
    entry(
        "paper",
        F::Paper,
        P::Paper,
        0.3,
        [0xF4, 0xF2, 0xEC],
        0.9,
        0.0,
        0.5,
    ),
    entry(
        "cardboard",
        F::Paper,
        P::Cardboard,
        0.3,
        [0xB8, 0x94, 0x68],
        0.9,
        0.0,
        1.0,
    ),
    // Walls.
    entry(
        "plaster",
        F::Wall,
        P::Plaster,
        2.0,
        [0xE4, 0xDF, 0xD6],
        0.9,
        0.0,
        1.5,
    ),
    entry(
        "wall_paint",
        F::Wall,
        P::Paint,
        0.5,
        [0xD6, 0xD2, 0xC8],
        0.8,
        0.0,
        0.8,
    ),
    // Carpet, plants.
    entry(
        "carpet",
        F::Carpet,
        P::Carpet,
        0.3,
        [0x8A, 0x80, 0x74],
        1.0,
        0.0,
        3.0,
    ),
    entry(
        "leaf",
        F::Plant,
        P::Leaf,
        0.3,
        [0x3C, 0x7A, 0x34],
        0.8,
        0.0,
        1.0,
    ),
    entry(
        "soil",
        F::Plant,
        P::Soil,
        0.3,
        [0x4A, 0x36, 0x26],
        1.0,
        0.0,
        3.0,
    ),
    // Outdoor ground (the places' `ground`, knowledge/archetypes.toml): a tile is a metre of
    // lawn or beach, half a metre of 1.5 cm gravel, 1.2 m of 0.6 × 0.3 m paving slabs.
    entry(
        "sand",
        F::Stone,
        P::Sand,
        1.0,
        [0xD6, 0xC2, 0x98],
        0.95,
        0.0,
        1.5,
    ),
    entry(
        "grass",
        F::Plant,
        P::Grass,
        1.0,
        [0x5E, 0x8C, 0x3C],
        0.95,
        0.0,
        2.0,
    ),
    entry(
        "gravel",
        F::Stone,
        P::Gravel,
        0.5,
        [0xA8, 0xA2, 0x96],
        0.95,
        0.0,
        3.0,
    ),
    entry(
        "paving",
        F::Stone,
        P::Pavers { rows: 4 },
        1.2,
        [0xA6, 0xA0, 0x96],
        0.85,
        0.0,
        2.0,
    ),
];

/// Every material of the library, in a stable order (its index is [`LibraryMaterial::index`]).
pub fn library() -> &'static [LibraryMaterial] {
    &LIBRARY
}

/// The library material with this exact id.
pub fn by_id(id: &str) -> Option<&'static LibraryMaterial> {
    library().iter().find(|m| m.id == id)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn at_least_thirty_materials_with_unique_ids_and_real_sizes() {
        let all = library();
        assert!(all.len() >= 30, "{} materials", all.len());
        let ids: std::collections::BTreeSet<_> = all.iter().map(|m| m.id).collect();
        assert_eq!(ids.len(), all.len(), "duplicate ids");
        for m in all {
            assert!(m.tile_size_m > 0.05 && m.tile_size_m <= 3.0, "{}", m.id);
            assert_eq!(by_id(m.id).map(|f| f.index()), Some(m.index()));
        }
        for family in [
            F::Wood,
            F::Fabric,
            F::Metal,
            F::Stone,
            F::Glass,
            F::Plastic,
            F::Paper,
            F::Wall,
            F::Carpet,
        ] {
            assert!(all.iter().any(|m| m.family == family), "{family:?}");
        }
        assert!(by_id("glass").unwrap().transmissive && !by_id("oak").unwrap().transmissive);
    }
}
