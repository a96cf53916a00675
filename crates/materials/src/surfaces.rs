//! What a room's own surfaces wear: the defaults (oak floorboards, matte wall paint, soil
//! outdoors where the scene records no `ground`) and how a scene look's palette material is laid on a floor or a wall. Exporters
//! and the renderer both dress the architecture from here, so that a preview and an export
//! agree.

use std::collections::BTreeMap;

use scenethesis_scene_graph::Material;

use crate::library::{by_id, Family};
use crate::resolve::resolve;

/// The material of floors: the library's oak floorboards.
pub fn floor_material() -> Material {
    library_material("oak_floorboards")
}

/// The material of open ground (outdoor scenes) that records no `ground` surface of its own
/// (a place's ground, `knowledge/archetypes.toml`): the library's soil.
pub fn ground_material() -> Material {
    library_material("soil")
}

/// The name of an outdoor scene's ground among a scene look's surfaces (`scene.json` →
/// `look.surfaces.ground`), beside `floor` and `walls` indoors.
pub const GROUND_SURFACE: &str = "ground";

/// The material open ground wears: the one `surfaces` (a scene look's surfaces by name)
/// records for [`GROUND_SURFACE`], else [`ground_material`].
pub fn outdoor_ground(surfaces: &BTreeMap<String, Material>) -> Material {
    surface_or(surfaces, GROUND_SURFACE, ground_material)
}

/// The material of walls: the library's matte wall paint.
pub fn wall_material() -> Material {
    library_material("wall_paint")
}

/// The material of window panes: the library's clear glass (transmissive).
pub fn glass_material() -> Material {
    library_material("glass")
}

fn library_material(id: &str) -> Material {
    by_id(id)
        .expect("the architecture's materials are in the library")
        .material()
}

/// The material `surfaces` (a scene look's surfaces by name, `floor`, `walls`) gives the room
/// surface `surface`, else `default`. The look names palette entries, which dress furniture:
/// on a floor a wood is laid as floorboards of its tone, and on walls a paint is the library's
/// wall paint of its colour.
///
/// ```
/// use std::collections::BTreeMap;
/// use scenethesis_materials::{floor_material, resolve, surface_or};
/// use scenethesis_scene_graph::Material;
///
/// let mut surfaces = BTreeMap::new();
/// surfaces.insert("floor".to_owned(), Material::new("walnut", [0.11, 0.05, 0.03], 0.5));
/// let floor = surface_or(&surfaces, "floor", floor_material);
/// assert_eq!(resolve(&floor.name).unwrap().id, "oak_floorboards");
/// assert_eq!(surface_or(&BTreeMap::new(), "floor", floor_material), floor_material());
/// ```
pub fn surface_or(
    surfaces: &BTreeMap<String, Material>,
    surface: &str,
    default: fn() -> Material,
) -> Material {
    let Some(mut material) = surfaces.get(surface).cloned() else {
        return default();
    };
    let library = resolve(&material.name);
    let painted = library.is_some_and(|l| l.id == "painted_wood");
    let wood = library.is_some_and(|l| l.family == Family::Wood);
    if surface == "floor" && wood && !painted {
        material.name = format!("{}_floorboards", material.name);
    } else if surface == "walls" && painted {
        material.name = "wall_paint".into();
    }
    material
}
