//! Helpers shared by the export tests.

use std::path::{Path, PathBuf};

use nalgebra::Point3;
use scenethesis_scene_graph::{Aabb, AssetRef, Mesh, ParentRef, Pose, RelationKind, SceneObject};

/// A rigid object of a procedural asset (generator `category`, seed 7) whose local bounds are
/// its mesh's.
pub fn object(
    id: &str,
    category: &str,
    mesh: &Mesh,
    pose: Pose,
    parent: ParentRef,
    support: RelationKind,
) -> SceneObject {
    SceneObject {
        id: id.into(),
        category: category.into(),
        asset: AssetRef::Procedural {
            generator: category.into(),
            seed: 7,
            look: None,
        },
        pose,
        parent,
        support,
        relations: Vec::new(),
        local_bounds: mesh
            .bounds()
            .unwrap_or(Aabb::new(Point3::origin(), Point3::origin())),
        joints: Vec::new(),
        parent_link: None,
        room: None,
    }
}

/// Where a test writes its exports: `SCENETHESIS_EXPORT_DIR` when set (CI's Python consumers
/// read them there), else `temp`; created if missing.
pub fn export_dir(temp: &Path) -> PathBuf {
    let dir = std::env::var_os("SCENETHESIS_EXPORT_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| temp.to_owned());
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
