//! Looks applied to a generated asset: the room style's material per palette family, then the
//! object's requested colours and materials on the parts they qualify. Only materials change
//! (never geometry, parts or indices), so an asset keeps its size, surfaces and joints.
//!
//! A material's palette family is known from its name (the palette entry it was drawn from);
//! fixed materials (screens, rubber feet, labels) belong to no family and are never changed.
//! Materials a look makes are named `<colour>_<token>` (`red_leather`, `black_paint`,
//! `navy_velvet`) or by their palette entry (`oak`, `white_marble`), with the requested colour
//! as base colour, so a texture library that reads names by their tokens textures them.

use scenethesis_scene_graph::{Asset, AssetLook, LookAttribute, LookScope, Material, Mesh};

use super::palette::{named_material, Palette};

/// The smallest share of an asset's surface a material must cover to count as part of its
/// body (handles and knobs stay as they are).
const BODY_SHARE: f32 = 0.05;

/// Part names of a table's or counter's top, for [`LookScope::Top`].
const TOP_PARTS: [&str; 5] = ["top", "worktop", "countertop", "tabletop", "table_top"];

/// The palette family of a generated material, from the palette entry it is named after.
pub fn family_of(name: &str) -> Option<Palette> {
    named_material(name).map(|(p, _)| p)
}

/// Applies `look` to `asset`'s materials: first every material of a family the look's
/// `families` names becomes that family's named material, then each requested attribute is
/// applied to the materials its scope selects.
pub fn apply_look(asset: &mut Asset, look: &AssetLook) {
    let mesh = &mut asset.mesh;
    let mut families: Vec<Option<Palette>> =
        mesh.materials.iter().map(|m| family_of(&m.name)).collect();
    for (material, family) in mesh.materials.iter_mut().zip(&families) {
        let Some(family) = family else { continue };
        let chosen = look
            .families
            .get(family.name())
            .and_then(|name| named_material(name))
            .filter(|(p, _)| p == family);
        if let Some((_, styled)) = chosen {
            *material = styled;
        }
    }
    let areas = material_areas(mesh);
    // Materials first, then colours ("a red leather sofa": leather, then red leather).
    let materials = look.attributes.iter().map(|a| LookAttribute {
        color: None,
        color_name: None,
        ..a.clone()
    });
    let colours = look.attributes.iter().map(|a| LookAttribute {
        material: None,
        ..a.clone()
    });
    for attribute in materials.chain(colours) {
        for i in scope_targets(mesh, &areas, &families, attribute.scope) {
            apply_attribute(&mut mesh.materials[i], &mut families[i], &attribute);
        }
    }
}

/// A room surface's material: the named material `base` (a palette entry) with `attributes`
/// applied in order; `None` when `base` names no palette entry.
pub fn surface_material(base: &str, attributes: &[LookAttribute]) -> Option<Material> {
    let (family, mut material) = named_material(base)?;
    let mut family = Some(family);
    for attribute in attributes {
        apply_attribute(&mut material, &mut family, attribute);
    }
    Some(material)
}

/// The surface area each material covers, by material index.
fn material_areas(mesh: &Mesh) -> Vec<f32> {
    let mut areas = vec![0.0f32; mesh.materials.len()];
    for part in &mesh.parts {
        let area: f32 = (0..part.triangles.len())
            .map(|t| {
                let [a, b, c] = part.triangle(t);
                0.5 * (b - a).cross(&(c - a)).norm()
            })
            .sum();
        if let Some(slot) = areas.get_mut(part.material) {
            *slot += area;
        }
    }
    areas
}

fn is_upholstery(family: Option<Palette>) -> bool {
    matches!(family, Some(Palette::Fabric | Palette::Leather))
}

/// The material indices an attribute of `scope` changes (only materials of a family).
fn scope_targets(
    mesh: &Mesh,
    areas: &[f32],
    families: &[Option<Palette>],
    scope: LookScope,
) -> Vec<usize> {
    let known: Vec<usize> = (0..families.len())
        .filter(|&i| families[i].is_some() && areas[i] > 0.0)
        .collect();
    let total: f32 = known.iter().map(|&i| areas[i]).sum();
    let largest = |among: &[usize]| {
        among
            .iter()
            .copied()
            .max_by(|&a, &b| areas[a].total_cmp(&areas[b]).then(b.cmp(&a)))
    };
    let upholstery: Vec<usize> = known
        .iter()
        .copied()
        .filter(|&i| is_upholstery(families[i]) && areas[i] >= BODY_SHARE * total)
        .collect();
    let body = || -> Vec<usize> {
        let body: Vec<usize> = known
            .iter()
            .copied()
            .filter(|&i| !is_upholstery(families[i]) && areas[i] >= BODY_SHARE * total)
            .collect();
        if body.is_empty() {
            known.clone()
        } else {
            body
        }
    };
    match scope {
        LookScope::Upholstery if !upholstery.is_empty() => upholstery,
        LookScope::Upholstery | LookScope::Body => body(),
        LookScope::Top => {
            let tops: Vec<usize> = known
                .iter()
                .copied()
                .filter(|&i| {
                    mesh.parts
                        .iter()
                        .any(|p| p.material == i && TOP_PARTS.contains(&p.name.as_str()))
                })
                .collect();
            if tops.is_empty() {
                largest(&known).into_iter().collect()
            } else {
                tops
            }
        }
        LookScope::Main if !upholstery.is_empty() => upholstery,
        LookScope::Main => match largest(&known) {
            Some(main) => known
                .iter()
                .copied()
                .filter(|&i| families[i] == families[main])
                .collect(),
            None => Vec::new(),
        },
    }
}

/// The last `_`-separated token of a material name (`marble` of `white_marble`).
fn last_token(name: &str) -> &str {
    name.rsplit('_').next().unwrap_or(name)
}

/// The colour word of a two-token material name (`navy` of `navy_fabric`).
fn colour_token(name: &str) -> Option<&str> {
    name.split_once('_').map(|(colour, _)| colour)
}

/// The first entry of a palette: its default material.
fn default_entry(palette: Palette) -> Material {
    let name = palette.entry_names().next().unwrap_or_default();
    named_material(name).map_or_else(|| Material::new(name, [0.5; 3], 0.5), |(_, m)| m)
}

/// Changes one material as `attribute` asks; `family` follows the change.
fn apply_attribute(
    material: &mut Material,
    family: &mut Option<Palette>,
    attribute: &LookAttribute,
) {
    if let Some(requested) = &attribute.material {
        apply_material(material, family, requested);
    }
    if let Some(colour) = attribute.color {
        let current = family.unwrap_or(Palette::Plastic);
        // Colouring natural wood paints it; colouring bright metal coats it.
        let coloured = match current {
            Palette::Wood => Palette::PaintedWood,
            Palette::Metal => Palette::CoatedMetal,
            Palette::BrightPlastic => Palette::Plastic,
            other => other,
        };
        if coloured != current {
            let base = default_entry(coloured);
            material.roughness = base.roughness;
            material.metallic = base.metallic;
        }
        let token = match coloured {
            Palette::PaintedWood => "paint",
            Palette::CoatedMetal => "metal",
            Palette::Plastic => "plastic",
            Palette::Glass => "glass",
            Palette::Leather | Palette::Fabric | Palette::Stone | Palette::Ceramic => {
                last_token(&material.name)
            }
            Palette::Rubber => "rubber",
            Palette::Paper => "paper",
            Palette::Foliage => "leaf",
            Palette::Wood | Palette::Metal | Palette::BrightPlastic => "paint",
        }
        .to_owned();
        let word = attribute
            .color_name
            .clone()
            .unwrap_or_else(|| colour.to_string().trim_start_matches('#').to_owned());
        material.name = format!("{word}_{token}");
        let [r, g, b] = colour.to_linear();
        material.base_color = [r, g, b, material.base_color[3]];
        *family = Some(coloured);
    }
}

/// Makes `material` the requested material: a palette entry as it is, or a family token
/// (`velvet`) that keeps the part's colour when it is already of the token's family.
fn apply_material(material: &mut Material, family: &mut Option<Palette>, requested: &str) {
    if let Some((palette, named)) = named_material(requested) {
        *material = named;
        *family = Some(palette);
        return;
    }
    // A token of the fabric family (velvet, linen, wool …): the planner only sends tokens
    // of upholstery materials; anything else keeps the material as it is.
    let target = Palette::Fabric;
    if *family != Some(target) {
        *material = default_entry(target);
    }
    let colour = colour_token(&material.name).unwrap_or("grey").to_owned();
    material.name = format!("{colour}_{requested}");
    *family = Some(target);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::catalog;
    use scenethesis_scene_graph::Srgb;

    fn attribute(scope: LookScope, material: Option<&str>, colour: Option<&str>) -> LookAttribute {
        LookAttribute {
            scope,
            material: material.map(str::to_owned),
            color: colour.map(|_| Srgb([0xb2, 0x22, 0x22])),
            color_name: colour.map(str::to_owned),
        }
    }

    fn worn_by(asset: &Asset, part: &str) -> Material {
        let p = asset.mesh.parts.iter().find(|p| p.name == part).unwrap();
        asset.mesh.materials[p.material].clone()
    }

    #[test]
    fn a_red_leather_sofa_has_red_leather_upholstery_and_keeps_its_wooden_feet() {
        let sofa = catalog::category("sofa").unwrap();
        let plain = catalog::generate(sofa, 4);
        let look = AssetLook {
            attributes: vec![
                attribute(LookScope::Upholstery, None, Some("red")),
                attribute(LookScope::Upholstery, Some("brown_leather"), None),
            ],
            ..AssetLook::default()
        };
        // Materials first, then colours, whatever the order of the attributes.
        let mut asset = plain.clone();
        apply_look(&mut asset, &look);
        for part in ["frame", "back", "arm_0"] {
            let m = worn_by(&asset, part);
            assert_eq!(m.name, "red_leather");
            assert_eq!(
                Srgb::from_linear([m.base_color[0], m.base_color[1], m.base_color[2]]),
                Srgb([0xb2, 0x22, 0x22])
            );
        }
        assert_eq!(worn_by(&asset, "foot_0"), worn_by(&plain, "foot_0"));
        assert_eq!(asset.mesh.parts, plain.mesh.parts);
        assert_eq!(asset.info, plain.info);
    }

    #[test]
    fn a_glass_coffee_table_has_a_glass_top_and_a_wooden_table_wooden_legs() {
        let table = catalog::category("coffee_table").unwrap();
        for seed in 0..6 {
            let plain = catalog::generate(table, seed);
            let mut glass = plain.clone();
            let top = attribute(LookScope::Top, Some("clear_glass"), None);
            apply_look(
                &mut glass,
                &AssetLook {
                    attributes: vec![top],
                    ..AssetLook::default()
                },
            );
            assert_eq!(worn_by(&glass, "top").name, "clear_glass");
            assert!(worn_by(&glass, "top").base_color[3] < 1.0);
            let mut wooden = plain.clone();
            let body = attribute(LookScope::Body, Some("oak"), None);
            apply_look(
                &mut wooden,
                &AssetLook {
                    attributes: vec![body],
                    ..AssetLook::default()
                },
            );
            assert_eq!(worn_by(&wooden, "top").name, "oak");
            if wooden.mesh.parts.iter().any(|p| p.name == "leg_0") {
                assert_eq!(worn_by(&wooden, "leg_0").name, "oak", "seed {seed}");
            }
        }
    }

    #[test]
    fn a_style_makes_every_wood_one_tone_and_a_colour_paints_wood() {
        let desk = catalog::category("desk").unwrap();
        let mut look = AssetLook::default();
        look.families.insert("wood".into(), "ash".into());
        look.families
            .insert("painted_wood".into(), "white_paint".into());
        for seed in 0..4 {
            let mut asset = catalog::generate(desk, seed);
            apply_look(&mut asset, &look);
            let top = worn_by(&asset, "top").name;
            assert!(top == "ash" || top == "white_paint", "{top}");
            let mut black = catalog::generate(desk, seed);
            let main = attribute(LookScope::Main, None, Some("black"));
            apply_look(
                &mut black,
                &AssetLook {
                    attributes: vec![main],
                    ..AssetLook::default()
                },
            );
            let top = worn_by(&black, "top");
            assert_eq!(top.name, "black_paint");
        }
    }

    #[test]
    fn surfaces_take_their_attributes() {
        let white = attribute(LookScope::Main, None, Some("white"));
        let walls = surface_material("white_paint", &[white]).unwrap();
        assert_eq!(walls.name, "white_paint");
        let floor = surface_material("oak", &[]).unwrap();
        assert_eq!(floor.name, "oak");
        let velvet = attribute(LookScope::Main, Some("velvet"), None);
        assert_eq!(
            surface_material("navy_fabric", &[velvet]).unwrap().name,
            "navy_velvet"
        );
        assert!(surface_material("plaid", &[]).is_none());
    }
}
