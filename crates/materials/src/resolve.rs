//! From a scene material's name to the library material whose pattern it wears: an exact id
//! (`oak`, `porcelain_tile`), a known alias (`white_marble`, `kraft`), or a token of the name
//! that names a material or a family (`navy_fabric` → cotton, `red_leather` → leather,
//! `piano_walnut` → walnut, `grey_paint` → painted wood), tried from the last token to the
//! first. A name that none of these reaches has no library material: it is drawn plain.

use crate::library::{by_id, LibraryMaterial};

/// Whole names that are not built from tokens.
const ALIASES: &[(&str, &str)] = &[
    ("door_leaf", "oak"),
    ("white_marble", "marble"),
    ("black_granite", "granite"),
    ("kraft", "cardboard"),
    ("log", "rough_timber"),
    ("mirror", "chrome"),
    ("cymbal", "brass"),
    ("rod", "steel"),
    ("hanger", "steel"),
    ("bulb", "glass"),
    ("ivory", "glazed_ceramic"),
    ("basin_white", "glazed_ceramic"),
    ("feet", "rubber"),
    ("wheels", "rubber"),
    ("surround", "rubber"),
    ("goal", "rubber"),
    ("drum_head", "plastic"),
    ("knob", "plastic"),
    ("bezel", "plastic"),
    ("dial", "plastic"),
    ("hands", "plastic"),
    ("fader_cap", "plastic"),
    ("marquee", "plastic"),
    ("mic_body", "steel"),
    ("baffle", "felt"),
    ("net", "cotton"),
    ("field", "felt"),
    ("line", "wall_paint"),
    ("firebox", "black_iron"),
    ("whiteboard", "glazed_ceramic"),
    ("fridge_liner", "plastic"),
    ("ball_skin", "leather"),
    ("cooktop_black", "glazed_ceramic"),
];

/// Tokens that name a family rather than one material, and the material they wear.
const TOKENS: &[(&str, &str)] = &[
    ("fabric", "cotton"),
    ("cloth", "cotton"),
    ("upholstery", "cotton"),
    ("leather", "leather"),
    ("vinyl", "leather"),
    ("tolex", "leather"),
    ("paint", "painted_wood"),
    ("painted", "painted_wood"),
    ("lacquer", "painted_wood"),
    ("wood", "oak"),
    ("wooden", "oak"),
    ("timber", "rough_timber"),
    ("floorboards", "oak_floorboards"),
    ("metal", "powder_coated_metal"),
    ("iron", "black_iron"),
    ("aluminum", "aluminium"),
    ("stainless", "brushed_steel"),
    ("plastic", "plastic"),
    ("team", "plastic"),
    ("glass", "glass"),
    ("ceramic", "glazed_ceramic"),
    ("porcelain", "glazed_ceramic"),
    ("tile", "porcelain_tile"),
    ("tiles", "porcelain_tile"),
    ("stone", "slate"),
    ("rubber", "rubber"),
    ("foam", "foam"),
    ("pad", "foam"),
    ("paper", "paper"),
    ("cover", "paper"),
    ("card", "cardboard"),
    ("board", "painted_wood"),
    ("leaf", "leaf"),
    ("baize", "felt"),
    ("sheet", "cotton"),
    ("pillow", "cotton"),
    ("rug", "carpet"),
    ("top", "felt"),
    ("pocket", "felt"),
    ("rack", "plastic"),
    ("safety", "powder_coated_metal"),
    ("lab", "glazed_ceramic"),
    ("dental", "glazed_ceramic"),
    ("screen", "plastic"),
    ("console", "plastic"),
    ("piano", "painted_wood"),
    ("appliance", "powder_coated_metal"),
    ("bezel", "plastic"),
    ("glaze", "glazed_ceramic"),
    ("china", "glazed_ceramic"),
    ("vitreous", "glazed_ceramic"),
    ("enamel", "glazed_ceramic"),
    ("cup", "glazed_ceramic"),
    ("holder", "glazed_ceramic"),
    ("case", "plastic"),
    ("shell", "plastic"),
    ("keycaps", "plastic"),
    ("keys", "plastic"),
    ("buttons", "plastic"),
    ("keypad", "plastic"),
    ("lever", "plastic"),
    ("latch", "steel"),
    ("control", "plastic"),
    ("display", "plastic"),
    ("panel", "plastic"),
    ("product", "plastic"),
    ("cap", "plastic"),
    ("dispenser", "plastic"),
    ("tray", "plastic"),
    ("handle", "plastic"),
    ("handles", "plastic"),
    ("pedal", "rubber"),
    ("peel", "plastic"),
    ("skin", "plastic"),
    ("brush", "plastic"),
    ("eyes", "plastic"),
    ("body", "plastic"),
    ("lid", "plastic"),
    ("base", "plastic"),
    ("printer", "plastic"),
    ("copier", "plastic"),
    ("collar", "plastic"),
    ("tank", "plastic"),
    ("bay", "plastic"),
    ("barrel", "plastic"),
    ("resin", "plastic"),
    ("soap", "plastic"),
    ("wax", "plastic"),
    ("deck", "plastic"),
    ("stringer", "plastic"),
    ("tape", "plastic"),
    ("led", "plastic"),
    ("flame", "plastic"),
    ("embers", "plastic"),
    ("digits", "plastic"),
    ("ink", "plastic"),
    ("trace", "plastic"),
    ("graduation", "plastic"),
    ("bark", "rough_timber"),
    ("coconut", "rough_timber"),
    ("foliage", "leaf"),
    ("frond", "leaf"),
    ("stem", "leaf"),
    ("borosilicate", "glass"),
    ("window", "glass"),
    ("windows", "glass"),
    ("bottle", "glass"),
    ("pet", "glass"),
    ("liquid", "glass"),
    ("chimney", "glass"),
    ("bronze", "brass"),
    ("ring", "steel"),
    ("tin", "steel"),
    ("stand", "steel"),
    ("pole", "steel"),
    ("head", "steel"),
    ("tap", "chrome"),
    ("filter", "brushed_steel"),
    ("hoop", "black_iron"),
    ("bands", "black_iron"),
    ("bail", "black_iron"),
    ("jacket", "powder_coated_metal"),
    ("nonstick", "powder_coated_metal"),
    ("towel", "cotton"),
    ("terry", "wool"),
    ("fur", "wool"),
    ("muzzle", "felt"),
    ("sling", "canvas"),
    ("canopy", "canvas"),
    ("groundsheet", "canvas"),
    ("nylon", "cotton"),
    ("straps", "cotton"),
    ("flag", "cotton"),
    ("frontal", "velvet"),
    ("shade", "linen"),
    ("mantle", "linen"),
    ("wick", "cotton"),
    ("wicker", "canvas"),
    ("pages", "paper"),
    ("tissue", "paper"),
    ("core", "cardboard"),
    ("label", "paper"),
    ("photo", "paper"),
    ("print", "paper"),
    ("land", "paper"),
    ("ocean", "paper"),
    ("rock", "slate"),
    ("plinth", "marble"),
    ("firebrick", "terracotta"),
    ("lawn", "grass"),
    ("turf", "grass"),
    ("tyre", "rubber"),
    ("frame", "painted_wood"),
];

/// The library material a scene material's name wears, or `None` when no rule reaches it.
///
/// ```
/// use scenethesis_materials::resolve;
///
/// assert_eq!(resolve("oak").map(|m| m.id), Some("oak"));
/// assert_eq!(resolve("navy_fabric").map(|m| m.id), Some("cotton"));
/// assert_eq!(resolve("red_leather").map(|m| m.id), Some("leather"));
/// assert_eq!(resolve("clear_glass").map(|m| m.id), Some("glass"));
/// assert_eq!(resolve("piano_walnut").map(|m| m.id), Some("walnut"));
/// assert!(resolve("imported_mat_3").is_none());
/// ```
pub fn resolve(name: &str) -> Option<&'static LibraryMaterial> {
    let name = name.to_ascii_lowercase();
    if let Some(m) = by_id(&name) {
        return Some(m);
    }
    if let Some((_, id)) = ALIASES.iter().find(|(alias, _)| *alias == name) {
        return by_id(id);
    }
    name.split(|c: char| !c.is_ascii_alphanumeric())
        .rev()
        .find_map(|token| {
            by_id(token).or_else(|| {
                TOKENS
                    .iter()
                    .find(|(t, _)| *t == token)
                    .and_then(|(_, id)| by_id(id))
            })
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_alias_and_token_names_a_library_material() {
        for (from, id) in ALIASES.iter().chain(TOKENS) {
            assert!(by_id(id).is_some(), "{from} -> {id}");
        }
        for m in crate::library() {
            assert_eq!(resolve(m.id).map(|r| r.id), Some(m.id));
        }
        assert_eq!(resolve("grey_paint").map(|m| m.id), Some("painted_wood"));
        assert_eq!(
            resolve("black_metal").map(|m| m.id),
            Some("powder_coated_metal")
        );
        assert_eq!(
            resolve("Brushed_Steel").map(|m| m.id),
            Some("brushed_steel")
        );
        assert_eq!(resolve("wall_0"), None);
    }
}
