//! The loader seam: one [`AssetLoader`] per family of mesh files, chosen by file extension.
//! GLB/glTF ([`GltfLoader`]) and OBJ ([`ObjLoader`]) are built in; an
//! [`Importer`](crate::Importer) takes further loaders for other formats.

use std::path::Path;

use scenethesis_scene_graph::Mesh;

use crate::{gltf_file, obj, MeshLoadError};

/// A reader of one family of mesh files: the seam where a new file format plugs into folder
/// import and the [`AssetResolver`](crate::AssetResolver). A loader only reads geometry and
/// materials in the file's own frame and units; the manifest's units, axes and front, the
/// checks on size and area, and the support-surface search are applied to every loader's mesh
/// alike.
pub trait AssetLoader: Send + Sync {
    /// The file extensions this loader reads, lower case and without the dot (`["obj"]`).
    fn extensions(&self) -> &[&str];

    /// Reads the file at `path` into a mesh in the file's own frame and units. Any file it
    /// names in turn (buffers, material libraries) must lie inside the folder `root`.
    fn load(&self, path: &Path, root: &Path) -> Result<Mesh, MeshLoadError>;

    /// [`AssetLoader::load`], also returning a warning for each thing the file names that could
    /// not be used but did not stop the load (a missing or broken texture: its part keeps a
    /// plain material). The default has none.
    fn load_with_warnings(
        &self,
        path: &Path,
        root: &Path,
    ) -> Result<(Mesh, Vec<String>), MeshLoadError> {
        self.load(path, root).map(|mesh| (mesh, Vec::new()))
    }
}

/// GLB and glTF files (`.glb`, `.gltf`), read by [`GltfFile`](crate::GltfFile): every triangle
/// primitive of every node instance becomes one part, materials shared by glTF index.
#[derive(Debug, Clone, Copy, Default)]
pub struct GltfLoader;

impl AssetLoader for GltfLoader {
    fn extensions(&self) -> &[&str] {
        &["glb", "gltf"]
    }

    fn load(&self, path: &Path, root: &Path) -> Result<Mesh, MeshLoadError> {
        gltf_file::load(path, root).map(|(mesh, _)| mesh)
    }

    fn load_with_warnings(
        &self,
        path: &Path,
        root: &Path,
    ) -> Result<(Mesh, Vec<String>), MeshLoadError> {
        gltf_file::load(path, root)
    }
}

/// Wavefront OBJ files (`.obj`), with the `.mtl` material libraries they name when those can be
/// read and lie inside the folder.
#[derive(Debug, Clone, Copy, Default)]
pub struct ObjLoader;

impl AssetLoader for ObjLoader {
    fn extensions(&self) -> &[&str] {
        &["obj"]
    }

    fn load(&self, path: &Path, root: &Path) -> Result<Mesh, MeshLoadError> {
        obj::load(path, root).map(|(mesh, _)| mesh)
    }

    fn load_with_warnings(
        &self,
        path: &Path,
        root: &Path,
    ) -> Result<(Mesh, Vec<String>), MeshLoadError> {
        obj::load(path, root)
    }
}

/// Parses OBJ text into a mesh in the file's own frame and units (`mtllib` files are not read:
/// parts get a grey default material). The same checks and limits as [`ObjLoader`] apply.
pub fn parse_obj(text: &str) -> Result<Mesh, MeshLoadError> {
    obj::parse(text, |_| None)
}
