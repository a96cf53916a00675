//! The texture files the text formats (USD, MJCF, URDF) reference beside their main file: one
//! PNG per map of each library material the scene wears, named `<material>_<map>.png`
//! (`oak_color.png`, `oak_normal.png`, `oak_mr.png`), and one per imported image a part shows
//! (`image_<digest>.png`, the image's own PNG bytes), written once however many objects and
//! formats share them.

use std::collections::BTreeMap;

use scenethesis_materials::{maps, LibraryMaterial, MapKind};

use crate::architecture::{leaves, pieces};
use crate::geometry::{image_file_name, library_of, worn};
use crate::ExportScene;

/// The folder beside an output folder's main files that holds their textures.
pub const TEXTURE_DIR: &str = "textures";

/// The file name of one map of a library material.
pub(crate) fn file_name(material: &LibraryMaterial, kind: MapKind) -> String {
    format!("{}_{}.png", material.id, kind.suffix())
}

/// Every texture file the scene's materials need, by file name.
pub(crate) fn files(export: &ExportScene<'_>) -> BTreeMap<String, Vec<u8>> {
    let scene = export.scene();
    let mut meshes: Vec<scenethesis_scene_graph::Mesh> = pieces(&scene.architecture, &scene.look)
        .iter()
        .map(|p| p.to_mesh())
        .collect();
    meshes.extend(leaves(&scene.architecture).into_iter().map(|l| l.mesh));
    let all = || {
        meshes
            .iter()
            .chain(scene.objects.iter().map(|o| export.mesh(o)))
    };
    let used = all()
        .flat_map(|m| m.materials.iter())
        .filter_map(library_of);
    let mut out = BTreeMap::new();
    for mesh in all() {
        for part in &mesh.parts {
            let material = &mesh.materials[part.material];
            if let Some(image) = worn(part, material).texture.as_ref() {
                out.entry(image_file_name(image))
                    .or_insert_with(|| image.png().to_vec());
            }
        }
    }
    for material in used {
        for kind in MapKind::ALL {
            out.entry(file_name(material, kind))
                .or_insert_with(|| maps(material).png(kind).to_vec());
        }
    }
    out
}
