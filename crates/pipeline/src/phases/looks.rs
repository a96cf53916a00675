//! Looks: the round's scene records the room's style, its surfaces' materials (outdoors the
//! place's ground) and what every object wears, read from the meshes it was optimized with
//! (what the judge's prompt check reads and `scene.json` keeps); and the texture maps they
//! wear are made beside the judge.

use std::collections::BTreeMap;

use scenethesis_agents::Plan;
use scenethesis_materials::{
    by_id, floor_material, glass_material, make_maps, outdoor_ground, resolve, surface_or,
    wall_material, LibraryMaterial, GROUND_SURFACE,
};
use scenethesis_procedural::looks::surface_material;
use scenethesis_scene_graph::{Mesh, Scene, SceneLook, WornMaterial};

/// Sets `scene.look` from `plan`'s room look and the objects' `meshes`.
pub(crate) fn record_looks(scene: &mut Scene, plan: &Plan, meshes: &BTreeMap<String, Mesh>) {
    let mut look = SceneLook::default();
    if let Some(room) = &plan.look {
        look.style = Some(room.style.clone());
        for (name, surface) in &room.surfaces {
            let attributes: Vec<_> = surface.attributes.iter().map(|a| a.look.clone()).collect();
            if let Some(material) = surface_material(&surface.base, &attributes) {
                look.surfaces.insert(name.clone(), material);
            }
        }
    }
    if let Some(ground) = plan.ground.as_deref().and_then(by_id) {
        look.surfaces
            .insert(GROUND_SURFACE.to_owned(), ground.material());
    }
    for object in &scene.objects {
        if let Some(mesh) = meshes.get(&object.id) {
            look.objects
                .insert(object.id.clone(), WornMaterial::of_mesh(mesh));
        }
    }
    scene.look = look;
}

/// Starts making the texture maps `scene` and its `meshes` wear on a thread of its own, so
/// that the previews and the exports find them made. The judge runs next; the thread runs at
/// the lowest priority, so it takes only what the judge leaves, and where the maps are kept
/// between runs ([`keep_maps_in`](scenethesis_materials::keep_maps_in)) it mostly reads them.
/// The maps are the same whichever thread makes them first (each is made once per process).
pub(crate) fn make_maps_beside(scene: &Scene, meshes: &BTreeMap<String, Mesh>) {
    let surfaces = &scene.look.surfaces;
    let architecture = [
        surface_or(surfaces, "floor", floor_material),
        surface_or(surfaces, "walls", wall_material),
        outdoor_ground(surfaces),
        glass_material(),
    ];
    let mut worn: Vec<&'static LibraryMaterial> = meshes
        .values()
        .flat_map(|mesh| mesh.materials.iter())
        .chain(architecture.iter())
        .filter_map(|material| resolve(&material.name))
        .collect();
    worn.sort_by_key(|m| m.index());
    worn.dedup_by_key(|m| m.index());
    std::thread::spawn(move || {
        super::run_at_lowest_priority();
        make_maps(worn)
    });
}
