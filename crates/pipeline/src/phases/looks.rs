//! Looks: the round's scene records the room's style, its surfaces' materials (outdoors the
//! place's ground) and what every object wears, read from the meshes it was optimized with (what the judge's prompt check
//! reads and `scene.json` keeps).

use std::collections::BTreeMap;

use scenethesis_agents::Plan;
use scenethesis_materials::{by_id, GROUND_SURFACE};
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
