//! Bring-your-own assets: import a directory of mesh files (GLB, glTF and OBJ built in)
//! described by an `assets.json` manifest, normalised to the scene conventions; and the
//! [`AssetResolver`] that turns any asset reference of a scene, procedural or imported, back
//! into an asset.
//!
//! The manifest is a JSON array of entries, or an object with an `assets` array:
//!
//! ```json
//! [
//!   { "file": "armchair.glb", "category": "armchair", "synonyms": ["lounge chair"],
//!     "up_axis": "z", "unit_scale": 0.01, "front": "-x" },
//!   { "file": "lamp.obj", "id": "lamp_brass", "category": "floor_lamp", "placement": "floor" }
//! ]
//! ```
//!
//! Fields: `file` (path relative to the directory), `category`, and optionally `id` (defaults to
//! the file stem, made unique), `synonyms`, `up_axis` (`"y"` or `"z"`, default `"y"`),
//! `unit_scale` (metres per file unit, default 1), `front` (`"+z"`, `"-z"`, `"+x"` or `"-x"`:
//! the asset's front in the file's frame after the up axis has been turned to +Y; default
//! `"+z"`), `placement` (`floor`, `wall`, `surface` or `ceiling`; defaults to the built-in
//! category's, else `floor`), `support_surfaces` (in the normalised asset frame, metres; found
//! automatically when absent), `scale_range` (default `[0.9, 1.1]`) and `joints` (the moving
//! parts, below).
//!
//! Normalisation scales to metres, turns the up axis to +Y and the front to +Z, then moves the
//! origin to the footprint centre at the lowest point. A file that is missing, unreadable, not
//! readable by its loader or without triangles is skipped with an [`ImportWarning`] naming it;
//! the rest of the directory is still imported. Without a manifest, every mesh file in the directory
//! is imported with the defaults and its file stem as category.
//!
//! Materials keep their base colour, roughness and metalness. A base-colour texture (glTF
//! `baseColorTexture` from a file, a data URI or the GLB's buffer; OBJ `map_Kd`) is decoded and
//! kept on its material as a PNG [`TextureImage`](scenethesis_scene_graph::TextureImage) with
//! its mean colour, shared by every object of the asset; the parts wearing it keep their texture
//! coordinates ([`MeshPart::uvs`](scenethesis_scene_graph::MeshPart::uvs): glTF's `TEXCOORD_n`
//! set the texture names; OBJ `vt` when every face corner of the part names one, v flipped to
//! glTF's v-down convention). The renderer and the exporters draw the image at those
//! coordinates; a part without them shows the material's flat colour, its base colour times the
//! image's mean ([`Material::flat_color`](scenethesis_scene_graph::Material::flat_color)), as
//! every import did before images were kept. A texture that is missing, outside the directory, over
//! [`limits::MAX_TEXTURE_BYTES`] / [`limits::MAX_TEXTURE_PIXELS`] or not a readable PNG or JPEG
//! is an [`ImportWarning`] naming the asset, the material and the file; the asset is still
//! imported with the plain colour.
//!
//! ## Moving parts
//!
//! `joints` lists an asset's doors, drawers and lids as a procedural asset carries them
//! ([`Joint`](scenethesis_scene_graph::Joint); the fields are described with `scene.json`'s
//! joints, `docs/scene-json.md`), each with the `part` it moves ([`ManifestJoint`]):
//!
//! ```json
//! { "file": "cabinet.glb", "category": "cabinet", "up_axis": "z", "unit_scale": 0.01,
//!   "joints": [
//!     { "part": "door", "name": "door", "kind": "revolute", "axis": [0, 0, -1],
//!       "anchor": [-20, -27, 0], "limits": [0, 1.7], "opens_to": "left" },
//!     { "part": "drawer", "name": "drawer", "kind": "prismatic", "axis": [0, -1, 0],
//!       "anchor": [0, -27, 10], "limits": [0, 30], "opens_to": "out" }
//!   ] }
//! ```
//!
//! `part` is the name of a glTF node (all its triangle primitives move; a node without a name
//! goes by its mesh's name), or for an OBJ file the group (`g door`; `door_oak` when the group
//! uses material `oak`). `axis` and `anchor` are in the file's frame and units like its
//! vertices, and so are prismatic `limits` (revolute ones are radians): the import turns and
//! scales them with the mesh. Every joint is closed at state 0 (`lower <= 0 <= upper`) and
//! the mesh is drawn closed; `parent` names a joint listed before it (a lid on a seat). The
//! asset gets the joints, its parts the joint that moves them, and the box their opening
//! sweeps ([`AssetInfo::opening_bounds`](scenethesis_scene_graph::AssetInfo)), exactly as a
//! generated one.
//!
//! A malformed joint is not skipped like a bad mesh: a zero or non-finite axis, reversed
//! limits or limits without 0, a part the file does not hold, a part two joints move, a
//! repeated name or a parent not listed before fails the whole import with one
//! [`ImportError::Joint`] naming the manifest, the entry and the field, e.g.
//! ``assets.json: entry #0 (file `cabinet.glb`): joints[0].axis is [0, 0, 0]; expected a
//! finite, non-zero direction``.
//!
//! ## Loaders
//!
//! Each file format is read by an [`AssetLoader`], chosen by file extension: [`GltfLoader`]
//! (`.glb`, `.gltf`) and [`ObjLoader`] (`.obj`) are built in. An [`Importer`] holds the list;
//! [`Importer::with_loader`] adds a format, and everything after loading (cleaning, units,
//! axes, front, limits, support surfaces) applies to its meshes as to the built-in ones:
//!
//! ```
//! use std::path::Path;
//! use scenethesis_import::{AssetLoader, Importer, MeshLoadError};
//! use scenethesis_scene_graph::{Material, Mesh, MeshPart};
//!
//! /// `.box` files: "width height depth" in the file's units.
//! struct BoxLoader;
//!
//! impl AssetLoader for BoxLoader {
//!     fn extensions(&self) -> &[&str] {
//!         &["box"]
//!     }
//!     fn load(&self, path: &Path, _root: &Path) -> Result<Mesh, MeshLoadError> {
//!         let text = std::fs::read_to_string(path)?;
//!         let size: Vec<f32> = text.split_whitespace().filter_map(|w| w.parse().ok()).collect();
//!         let [w, h, d] = size[..] else {
//!             return Err(MeshLoadError::Unusable("expected three sizes".into()));
//!         };
//!         Ok(Mesh {
//!             materials: vec![Material {
//!                 name: "pine".into(),
//!                 base_color: [0.8, 0.6, 0.4, 1.0],
//!                 roughness: 0.7,
//!                 metallic: 0.0,
//!                 texture: None,
//!             }],
//!             parts: vec![MeshPart::cuboid("box", 0, [0.0; 3], [w, h, d])],
//!         })
//!     }
//! }
//!
//! let dir = tempfile::tempdir()?;
//! std::fs::write(dir.path().join("crate.box"), "50 40 30")?;
//! std::fs::write(
//!     dir.path().join("assets.json"),
//!     r#"[{ "file": "crate.box", "category": "crate", "unit_scale": 0.01 }]"#,
//! )?;
//! let report = Importer::new().with_loader(BoxLoader).import_directory(dir.path())?;
//! assert!(report.warnings.is_empty(), "{:?}", report.warnings);
//! let size = report.assets[0].info.size;
//! assert!((size[0] - 0.5).abs() < 1e-6 && (size[1] - 0.4).abs() < 1e-6);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![warn(missing_docs)]

mod clean;
mod gltf_file;
mod importer;
mod joints;
pub mod limits;
mod loader;
mod manifest;
mod obj;
mod resolver;
mod surfaces;
mod textures;

use std::fmt;
use std::path::PathBuf;

use scenethesis_scene_graph::Asset;

pub use clean::{clean_mesh, Cleaned};
pub use gltf_file::{resolve_inside, GltfError, GltfFile, GltfMaterial, GltfNode, GltfPrimitive};
pub use importer::{import_directory, import_entry, load_mesh, normalise, Importer};
pub use joints::ManifestJoint;
pub use loader::{parse_obj, AssetLoader, GltfLoader, ObjLoader};
pub use manifest::{Front, ManifestEntry, UpAxis, MANIFEST_FILE};
pub use resolver::{AssetResolver, ResolveError};
pub use surfaces::{find_support_surfaces, SurfaceSearch};

/// What importing a directory produced: the assets that loaded and a warning for each file that
/// did not.
#[derive(Debug, Clone, Default)]
pub struct ImportReport {
    /// Imported assets in manifest order (or file-name order without a manifest).
    pub assets: Vec<Asset>,
    /// One warning per skipped entry or file, and notes about defaults that were applied.
    pub warnings: Vec<ImportWarning>,
}

/// A file that was skipped (or imported with a caveat), and why.
#[derive(Debug, Clone, PartialEq)]
pub struct ImportWarning {
    /// The file concerned.
    pub path: PathBuf,
    /// What went wrong, e.g. `not a valid GLB: ...`.
    pub reason: String,
}

impl fmt::Display for ImportWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path.display(), self.reason)
    }
}

/// Why a directory could not be imported at all (a single bad mesh file is only a warning).
#[derive(Debug, thiserror::Error)]
pub enum ImportError {
    /// The directory could not be listed.
    #[error("cannot read asset directory {path}: {source}")]
    Directory {
        /// The directory.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The manifest exists but could not be read.
    #[error("cannot read manifest {path}: {source}")]
    ManifestIo {
        /// The manifest path.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The manifest is JSON but not an array of entries (nor an object with an `assets` array).
    #[error("invalid manifest {path}: {reason}")]
    ManifestShape {
        /// The manifest path.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// The manifest is not valid JSON.
    #[error("invalid manifest {path}: {source}")]
    ManifestJson {
        /// The manifest path.
        path: PathBuf,
        /// The parse error, with line and column.
        source: serde_json::Error,
    },
    /// A manifest entry declares a malformed joint (a zero axis, reversed limits, a part the
    /// file does not hold, ...): unlike a bad mesh, this fails the whole import, so that no
    /// scene is made with the asset silently rigid.
    #[error("{}: {entry}: {field} {problem}", path.display())]
    Joint {
        /// The manifest path.
        path: PathBuf,
        /// The entry, e.g. ``entry #0 (file `cabinet.glb`)``.
        entry: String,
        /// The field at fault, e.g. `joints[1].axis`.
        field: String,
        /// What it is and what was expected, e.g. `is [0, 0, 0]; expected a finite, non-zero
        /// direction`.
        problem: String,
    },
}

impl ImportError {
    /// The [`ImportError::Joint`] for `fault` in entry `entry` of the manifest at `path`.
    pub(crate) fn joint(path: &std::path::Path, entry: String, fault: joints::Fault) -> Self {
        ImportError::Joint {
            path: path.to_owned(),
            entry,
            field: fault.field,
            problem: fault.problem,
        }
    }
}

/// Why one mesh file could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum MeshLoadError {
    /// The file could not be read.
    #[error("cannot read file: {0}")]
    Io(#[from] std::io::Error),
    /// The file is not valid glTF or GLB.
    #[error("{0}")]
    Gltf(String),
    /// The OBJ file has a malformed line.
    #[error("invalid OBJ at line {line}: {message}")]
    Obj {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The file holds no triangles.
    #[error("the file holds no triangles")]
    Empty,
    /// The mesh loaded but cannot be used as an asset (no area, too large, ...).
    #[error("{0}")]
    Unusable(String),
    /// The manifest entry itself is unusable.
    #[error("invalid manifest entry: {0}")]
    Entry(String),
    /// A joint of the manifest entry is malformed (see [`ImportError::Joint`], which
    /// [`Importer::import_directory`] turns this into).
    #[error("{field} {problem}")]
    Joint {
        /// The field at fault, e.g. `joints[0].part`.
        field: String,
        /// What it is and what was expected.
        problem: String,
    },
    /// No loader of the importer reads the file's extension.
    #[error("unsupported file type (expected {expected})")]
    Unsupported {
        /// The extensions the importer's loaders read, as a list (`.glb, .gltf or .obj`).
        expected: String,
    },
}

fn printable(text: &str) -> std::borrow::Cow<'_, str> {
    scenethesis_scene_graph::printable(text)
}

#[cfg(test)]
mod tests;
