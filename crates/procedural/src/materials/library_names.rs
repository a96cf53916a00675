//! Every palette entry's name wears a material of the texture library.

use super::palette::{palette_entries, Palette};

/// Every palette. The match is exhaustive, so a new palette fails to compile here until it is
/// listed (and its names are checked).
fn all_palettes() -> Vec<Palette> {
    let listed = |p: Palette| match p {
        Palette::Wood
        | Palette::PaintedWood
        | Palette::Metal
        | Palette::CoatedMetal
        | Palette::Fabric
        | Palette::Leather
        | Palette::Plastic
        | Palette::BrightPlastic
        | Palette::Glass
        | Palette::Stone
        | Palette::Foliage
        | Palette::Ceramic
        | Palette::Rubber
        | Palette::Paper => p,
    };
    [
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
    ]
    .map(listed)
    .to_vec()
}

#[test]
fn every_palette_name_resolves_to_a_library_material() {
    let mut unmapped = Vec::new();
    for palette in all_palettes() {
        for (name, ..) in palette_entries(palette) {
            if scenethesis_materials::resolve(name).is_none() {
                unmapped.push(*name);
            }
        }
    }
    assert!(
        unmapped.is_empty(),
        "palette names without a library material (add them to scenethesis-materials' \
         resolve tables): {unmapped:?}"
    );
    let glass = scenethesis_materials::resolve("clear_glass").unwrap();
    assert!(glass.transmissive);
}
