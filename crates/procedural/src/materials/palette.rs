//! The palettes: families of plausible materials (wood tones, metals, fabrics, …) an asset
//! picks from per seed, and fixed materials for parts that do not vary.

use scenethesis_scene_graph::Material;

/// Families of plausible materials an asset picks from per seed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Palette {
    /// Natural wood tones (oak, walnut, pine, maple, cherry, teak).
    Wood,
    /// Painted or laminated wood (white, black, grey, sage, navy).
    PaintedWood,
    /// Bright metals (steel, aluminium, chrome, brass).
    Metal,
    /// Powder-coated metal (black, graphite, white, blue, red, green).
    CoatedMetal,
    /// Upholstery fabric (grey, beige, navy, olive, rust, charcoal, cream).
    Fabric,
    /// Leather and vinyl (brown, black, tan, oxblood).
    Leather,
    /// Plastics in muted colours (white, grey, black, beige).
    Plastic,
    /// Toy-like saturated plastics (red, yellow, blue, green, orange, purple).
    BrightPlastic,
    /// Clear or tinted glass (semi-transparent base colour).
    Glass,
    /// Stone and concrete (marble, granite, slate, concrete).
    Stone,
    /// Plant foliage greens.
    Foliage,
    /// Glazed ceramic (white, terracotta, blue, sage, black).
    Ceramic,
    /// Rubber and foam (black, dark grey, blue, purple, green yoga mats).
    Rubber,
    /// Paper, canvas and board (white, cream, kraft, coloured covers).
    Paper,
}

impl Palette {
    /// Every palette, in declaration order.
    pub const ALL: [Palette; 14] = [
        Palette::Wood,
        Palette::PaintedWood,
        Palette::Metal,
        Palette::CoatedMetal,
        Palette::Fabric,
        Palette::Leather,
        Palette::Plastic,
        Palette::BrightPlastic,
        Palette::Glass,
        Palette::Stone,
        Palette::Foliage,
        Palette::Ceramic,
        Palette::Rubber,
        Palette::Paper,
    ];

    /// The family's name in looks and knowledge files (`wood`, `painted_wood`, …).
    pub fn name(self) -> &'static str {
        match self {
            Palette::Wood => "wood",
            Palette::PaintedWood => "painted_wood",
            Palette::Metal => "metal",
            Palette::CoatedMetal => "coated_metal",
            Palette::Fabric => "fabric",
            Palette::Leather => "leather",
            Palette::Plastic => "plastic",
            Palette::BrightPlastic => "bright_plastic",
            Palette::Glass => "glass",
            Palette::Stone => "stone",
            Palette::Foliage => "foliage",
            Palette::Ceramic => "ceramic",
            Palette::Rubber => "rubber",
            Palette::Paper => "paper",
        }
    }

    /// The palette of this name ([`Palette::name`]).
    pub fn from_name(name: &str) -> Option<Palette> {
        Palette::ALL.into_iter().find(|p| p.name() == name)
    }

    /// The names of the palette's entries, in order.
    pub fn entry_names(self) -> impl Iterator<Item = &'static str> {
        palette_entries(self).iter().map(|e| e.0)
    }
}

/// The palette and unjittered material of the palette entry named `name` (`oak`,
/// `white_marble`); glass gets an alpha of 0.3.
pub fn named_material(name: &str) -> Option<(Palette, Material)> {
    Palette::ALL.into_iter().find_map(|palette| {
        palette_entries(palette).iter().find(|e| e.0 == name).map(
            |&(name, rgb, roughness, metallic)| {
                let mut m = fixed_material(name, rgb, roughness, metallic);
                if palette == Palette::Glass {
                    m.base_color[3] = 0.3;
                }
                (palette, m)
            },
        )
    })
}

/// (name, sRGB colour, roughness, metallic) entries of each palette.
pub(crate) fn palette_entries(palette: Palette) -> &'static [(&'static str, [u8; 3], f32, f32)] {
    match palette {
        Palette::Wood => &[
            ("oak", [0xB8, 0x8A, 0x5A], 0.6, 0.0),
            ("walnut", [0x5D, 0x40, 0x2C], 0.55, 0.0),
            ("pine", [0xD8, 0xB4, 0x7E], 0.65, 0.0),
            ("maple", [0xE0, 0xC0, 0x90], 0.6, 0.0),
            ("cherry", [0x8E, 0x4A, 0x32], 0.5, 0.0),
            ("teak", [0x9A, 0x6A, 0x3C], 0.55, 0.0),
            ("ash", [0xC9, 0xB0, 0x8C], 0.6, 0.0),
        ],
        Palette::PaintedWood => &[
            ("white_paint", [0xEE, 0xEC, 0xE6], 0.5, 0.0),
            ("black_paint", [0x24, 0x24, 0x26], 0.45, 0.0),
            ("grey_paint", [0x8C, 0x8E, 0x90], 0.5, 0.0),
            ("sage_paint", [0x9C, 0xAF, 0x88], 0.5, 0.0),
            ("navy_paint", [0x2A, 0x3A, 0x5C], 0.5, 0.0),
            ("cream_paint", [0xE8, 0xDC, 0xC0], 0.5, 0.0),
        ],
        Palette::Metal => &[
            ("steel", [0xA8, 0xAA, 0xAD], 0.35, 1.0),
            ("aluminium", [0xC8, 0xCA, 0xCC], 0.3, 1.0),
            ("chrome", [0xDD, 0xDE, 0xE0], 0.12, 1.0),
            ("brass", [0xC8, 0xA0, 0x50], 0.3, 1.0),
            ("brushed_steel", [0x9A, 0x9C, 0x9E], 0.45, 1.0),
        ],
        Palette::CoatedMetal => &[
            ("black_metal", [0x2A, 0x2A, 0x2C], 0.5, 0.6),
            ("graphite_metal", [0x4A, 0x4C, 0x50], 0.5, 0.6),
            ("white_metal", [0xE4, 0xE4, 0xE2], 0.45, 0.4),
            ("blue_metal", [0x2E, 0x5A, 0x9C], 0.45, 0.5),
            ("red_metal", [0xB0, 0x2A, 0x24], 0.45, 0.5),
            ("green_metal", [0x3A, 0x6A, 0x48], 0.45, 0.5),
            ("grey_metal", [0x80, 0x84, 0x88], 0.45, 0.6),
        ],
        Palette::Fabric => &[
            ("grey_fabric", [0x80, 0x80, 0x82], 0.95, 0.0),
            ("beige_fabric", [0xC8, 0xB8, 0x9A], 0.95, 0.0),
            ("navy_fabric", [0x2C, 0x3A, 0x5A], 0.95, 0.0),
            ("olive_fabric", [0x6E, 0x70, 0x44], 0.95, 0.0),
            ("rust_fabric", [0xA4, 0x54, 0x32], 0.95, 0.0),
            ("charcoal_fabric", [0x3C, 0x3C, 0x40], 0.95, 0.0),
            ("cream_fabric", [0xE6, 0xDE, 0xCC], 0.95, 0.0),
            ("teal_fabric", [0x2E, 0x6E, 0x6E], 0.95, 0.0),
        ],
        Palette::Leather => &[
            ("brown_leather", [0x6A, 0x40, 0x28], 0.6, 0.0),
            ("black_leather", [0x22, 0x20, 0x20], 0.55, 0.0),
            ("tan_leather", [0xB0, 0x7A, 0x48], 0.6, 0.0),
            ("oxblood_leather", [0x5A, 0x1E, 0x1E], 0.55, 0.0),
        ],
        Palette::Plastic => &[
            ("white_plastic", [0xEC, 0xEC, 0xEA], 0.5, 0.0),
            ("grey_plastic", [0x90, 0x92, 0x94], 0.5, 0.0),
            ("black_plastic", [0x26, 0x26, 0x28], 0.45, 0.0),
            ("beige_plastic", [0xD6, 0xCC, 0xB4], 0.5, 0.0),
        ],
        Palette::BrightPlastic => &[
            ("red_plastic", [0xD8, 0x30, 0x2C], 0.4, 0.0),
            ("yellow_plastic", [0xF2, 0xC8, 0x1E], 0.4, 0.0),
            ("blue_plastic", [0x24, 0x6C, 0xD0], 0.4, 0.0),
            ("green_plastic", [0x3C, 0xA8, 0x48], 0.4, 0.0),
            ("orange_plastic", [0xF0, 0x80, 0x20], 0.4, 0.0),
            ("purple_plastic", [0x84, 0x4C, 0xC0], 0.4, 0.0),
        ],
        Palette::Glass => &[
            ("clear_glass", [0xDC, 0xEC, 0xF0], 0.05, 0.0),
            ("tinted_glass", [0xA8, 0xC0, 0xC0], 0.05, 0.0),
        ],
        Palette::Stone => &[
            ("white_marble", [0xE8, 0xE6, 0xE2], 0.25, 0.0),
            ("black_granite", [0x30, 0x30, 0x32], 0.3, 0.0),
            ("slate", [0x5C, 0x62, 0x68], 0.6, 0.0),
            ("concrete", [0xA0, 0x9E, 0x98], 0.85, 0.0),
            ("travertine", [0xD6, 0xC8, 0xAC], 0.5, 0.0),
        ],
        Palette::Foliage => &[
            ("leaf_green", [0x3C, 0x7A, 0x34], 0.8, 0.0),
            ("dark_leaf", [0x24, 0x50, 0x28], 0.8, 0.0),
            ("yellow_leaf", [0x7A, 0x94, 0x38], 0.8, 0.0),
            ("blue_leaf", [0x3A, 0x6A, 0x58], 0.8, 0.0),
        ],
        Palette::Ceramic => &[
            ("white_ceramic", [0xF0, 0xEE, 0xEA], 0.2, 0.0),
            ("terracotta", [0xB8, 0x5C, 0x38], 0.8, 0.0),
            ("blue_ceramic", [0x3A, 0x5E, 0x90], 0.2, 0.0),
            ("sage_ceramic", [0x9C, 0xB0, 0x94], 0.25, 0.0),
            ("black_ceramic", [0x28, 0x28, 0x2A], 0.25, 0.0),
        ],
        Palette::Rubber => &[
            ("black_rubber", [0x1E, 0x1E, 0x20], 0.9, 0.0),
            ("grey_rubber", [0x50, 0x52, 0x54], 0.9, 0.0),
            ("blue_foam", [0x3A, 0x6E, 0xB0], 0.85, 0.0),
            ("purple_foam", [0x7A, 0x4E, 0x9E], 0.85, 0.0),
            ("green_foam", [0x58, 0x9A, 0x5C], 0.85, 0.0),
        ],
        Palette::Paper => &[
            ("white_paper", [0xF4, 0xF2, 0xEC], 0.9, 0.0),
            ("cream_paper", [0xEC, 0xE2, 0xC8], 0.9, 0.0),
            ("kraft", [0xB8, 0x94, 0x68], 0.9, 0.0),
            ("red_cover", [0xA0, 0x2C, 0x2C], 0.7, 0.0),
            ("blue_cover", [0x2C, 0x4C, 0x8C], 0.7, 0.0),
            ("green_cover", [0x2C, 0x6C, 0x44], 0.7, 0.0),
        ],
    }
}

/// sRGB byte to linear channel.
fn srgb_to_linear(c: u8) -> f32 {
    let c = c as f32 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// A material drawn from `palette`: one of its entries, brightness jittered by up to ±8 % so
/// that two seeds rarely share exactly the same colour. Glass gets an alpha of 0.3.
pub fn pick_material(palette: Palette, rng: &mut impl rand::Rng) -> Material {
    let entries = palette_entries(palette);
    let (name, rgb, roughness, metallic) = entries[rng.random_range(0..entries.len())];
    let jitter = rng.random_range(0.92f32..1.08);
    let c = rgb.map(|v| (srgb_to_linear(v) * jitter).clamp(0.0, 1.0));
    let alpha = if palette == Palette::Glass { 0.3 } else { 1.0 };
    Material {
        name: name.into(),
        base_color: [c[0], c[1], c[2], alpha],
        roughness,
        metallic,
        texture: None,
    }
}

/// A material with a fixed sRGB colour (for parts that do not vary: screens, rubber feet).
pub fn fixed_material(name: &str, srgb: [u8; 3], roughness: f32, metallic: f32) -> Material {
    let c = srgb.map(srgb_to_linear);
    Material {
        name: name.into(),
        base_color: [c[0], c[1], c[2], 1.0],
        roughness,
        metallic,
        texture: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn palettes_vary_with_the_seed_and_repeat_with_it() {
        use rand::SeedableRng;
        let draw = |seed| {
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
            pick_material(Palette::Wood, &mut rng)
        };
        assert_eq!(draw(3), draw(3));
        assert!((0..8).any(|s| draw(s) != draw(0)));
        assert_eq!(
            scenethesis_primitives::regular_polygon([0.0, 0.0], 1.0, 4).len(),
            4
        );
    }

    #[test]
    fn entry_names_are_unique_across_palettes_and_resolve_to_their_palette() {
        let mut seen = std::collections::BTreeSet::new();
        for palette in Palette::ALL {
            assert_eq!(Palette::from_name(palette.name()), Some(palette));
            for name in palette.entry_names() {
                assert!(seen.insert(name), "`{name}` is in two palettes");
                assert_eq!(named_material(name).map(|(p, _)| p), Some(palette));
            }
        }
        assert_eq!(named_material("clear_glass").unwrap().1.base_color[3], 0.3);
        assert!(named_material("plaid").is_none());
    }
}
