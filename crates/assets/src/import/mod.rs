//! Bring-your-own assets: import a directory of GLB, glTF and OBJ files described by an
//! `assets.json` manifest, normalised to the scene conventions.
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
//! automatically when absent) and `scale_range` (default `[0.9, 1.1]`).
//!
//! Normalisation scales to metres, turns the up axis to +Y and the front to +Z, then moves the
//! origin to the footprint centre at the lowest point. A file that is missing, unreadable, not
//! valid GLB/glTF/OBJ or without triangles is skipped with an [`ImportWarning`] naming it; the
//! rest of the directory is still imported. Without a manifest, every mesh file in the directory
//! is imported with the defaults and its file stem as category.

mod gltf_file;
mod obj;
mod surfaces;

use std::collections::BTreeSet;
use std::fmt;
use std::path::{Path, PathBuf};

use nalgebra::{Matrix3, Rotation3, Vector3};
use scenethesis_scene_graph::{AssetRef, Mesh};
use serde::Deserialize;

use crate::{Asset, AssetInfo, Placement, SupportSurface};

pub use surfaces::{find_support_surfaces, SurfaceSearch};

/// The manifest file name looked up in an asset directory.
pub const MANIFEST_FILE: &str = "assets.json";

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
    /// The manifest is not valid JSON of the expected shape.
    #[error("invalid manifest {path}: {source} (expected an array of {{\"file\", \"category\", ...}} entries)")]
    ManifestJson {
        /// The manifest path.
        path: PathBuf,
        /// The parse error, with line and column.
        source: serde_json::Error,
    },
}

/// Why one mesh file could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum MeshLoadError {
    /// The file could not be read.
    #[error("cannot read file: {0}")]
    Io(#[from] std::io::Error),
    /// The file is not valid glTF or GLB.
    #[error("not a valid glTF/GLB file: {0}")]
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
    /// The manifest entry itself is unusable.
    #[error("invalid manifest entry: {0}")]
    Entry(String),
    /// The file extension is not one of `glb`, `gltf`, `obj`.
    #[error("unsupported file type (expected .glb, .gltf or .obj)")]
    Unsupported,
}

/// The axis that points up in a source file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
pub enum UpAxis {
    /// +Y up (glTF convention).
    #[default]
    #[serde(rename = "y", alias = "Y", alias = "+y")]
    Y,
    /// +Z up (Blender, many CAD tools).
    #[serde(rename = "z", alias = "Z", alias = "+z")]
    Z,
}

/// The direction an asset's front faces in its source file (after the up axis is turned to +Y).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
pub enum Front {
    /// Already +Z.
    #[default]
    #[serde(rename = "+z", alias = "z")]
    PosZ,
    /// Faces −Z.
    #[serde(rename = "-z")]
    NegZ,
    /// Faces +X.
    #[serde(rename = "+x", alias = "x")]
    PosX,
    /// Faces −X.
    #[serde(rename = "-x")]
    NegX,
}

/// One manifest entry.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ManifestEntry {
    /// Mesh file, relative to the asset directory.
    pub file: PathBuf,
    /// Asset id; defaults to the file stem.
    #[serde(default)]
    pub id: Option<String>,
    /// Category name, e.g. `armchair`.
    pub category: String,
    /// Other names for retrieval.
    #[serde(default)]
    pub synonyms: Vec<String>,
    /// Up axis of the file.
    #[serde(default)]
    pub up_axis: UpAxis,
    /// Metres per file unit.
    #[serde(default = "one")]
    pub unit_scale: f32,
    /// Front direction in the file (after turning the up axis to +Y).
    #[serde(default)]
    pub front: Front,
    /// Placement kind; defaults to the built-in category's placement, else floor.
    #[serde(default)]
    pub placement: Option<Placement>,
    /// Support surfaces in the normalised frame; found automatically when absent.
    #[serde(default)]
    pub support_surfaces: Option<Vec<SupportSurface>>,
    /// Allowed uniform scale range.
    #[serde(default)]
    pub scale_range: Option<[f32; 2]>,
}

fn one() -> f32 {
    1.0
}

#[derive(Deserialize)]
#[serde(untagged)]
enum Manifest {
    List(Vec<ManifestEntry>),
    Object { assets: Vec<ManifestEntry> },
}

/// Imports every asset of `dir` (see the module documentation for the manifest format).
pub fn import_directory(dir: impl AsRef<Path>) -> Result<ImportReport, ImportError> {
    let dir = dir.as_ref();
    let manifest_path = dir.join(MANIFEST_FILE);
    let mut report = ImportReport::default();
    let entries = if manifest_path.is_file() {
        let text =
            std::fs::read_to_string(&manifest_path).map_err(|source| ImportError::ManifestIo {
                path: manifest_path.clone(),
                source,
            })?;
        match serde_json::from_str::<Manifest>(&text) {
            Ok(Manifest::List(list)) | Ok(Manifest::Object { assets: list }) => list,
            Err(source) => {
                return Err(ImportError::ManifestJson {
                    path: manifest_path,
                    source,
                })
            }
        }
    } else {
        let listing = std::fs::read_dir(dir).map_err(|source| ImportError::Directory {
            path: dir.to_owned(),
            source,
        })?;
        let mut files: Vec<PathBuf> = listing
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.is_file() && mesh_kind(p).is_some())
            .collect();
        files.sort();
        if !files.is_empty() {
            report.warnings.push(ImportWarning {
                path: manifest_path.clone(),
                reason: "no manifest: importing every mesh file with its file stem as category, +Y up, metres, front +Z".into(),
            });
        }
        files
            .into_iter()
            .map(|p| {
                let stem = file_stem(&p);
                ManifestEntry {
                    file: p.file_name().map(PathBuf::from).unwrap_or_default(),
                    id: None,
                    category: stem,
                    synonyms: Vec::new(),
                    up_axis: UpAxis::Y,
                    unit_scale: 1.0,
                    front: Front::PosZ,
                    placement: None,
                    support_surfaces: None,
                    scale_range: None,
                }
            })
            .collect()
    };
    let mut ids = BTreeSet::new();
    for entry in entries {
        let path = dir.join(&entry.file);
        match import_entry(&path, &entry) {
            Ok(mut asset) => {
                let base = entry.id.clone().unwrap_or_else(|| file_stem(&entry.file));
                let mut id = base.clone();
                let mut k = 2;
                while !ids.insert(id.clone()) {
                    id = format!("{base}_{k}");
                    k += 1;
                }
                asset.info.source = AssetRef::Imported {
                    id,
                    path: path.display().to_string(),
                };
                report.assets.push(asset);
            }
            Err(e) => {
                tracing::warn!("skipping asset {}: {e}", path.display());
                report.warnings.push(ImportWarning {
                    path,
                    reason: e.to_string(),
                });
            }
        }
    }
    Ok(report)
}

/// Loads one mesh file and normalises it as `entry` says.
pub fn import_entry(path: &Path, entry: &ManifestEntry) -> Result<Asset, MeshLoadError> {
    if !(entry.unit_scale.is_finite() && entry.unit_scale > 0.0) {
        return Err(MeshLoadError::Entry(format!(
            "unit_scale must be a positive number of metres per file unit, got {}",
            entry.unit_scale
        )));
    }
    let mut mesh = load_mesh(path)?;
    if mesh.triangle_count() == 0 {
        return Err(MeshLoadError::Empty);
    }
    normalise(&mut mesh, entry.up_axis, entry.front, entry.unit_scale);
    let bounds = mesh.bounds().ok_or(MeshLoadError::Empty)?;
    let size = (bounds.max - bounds.min).map(|v| v as f32);
    let placement = entry.placement.unwrap_or_else(|| {
        crate::catalog::category(&entry.category)
            .map(|c| c.placement)
            .unwrap_or(Placement::Floor)
    });
    let support_surfaces = match &entry.support_surfaces {
        Some(s) => s.clone(),
        None => find_support_surfaces(&mesh, &SurfaceSearch::default()),
    };
    Ok(Asset {
        info: AssetInfo {
            source: AssetRef::Imported {
                id: entry.id.clone().unwrap_or_else(|| file_stem(&entry.file)),
                path: path.display().to_string(),
            },
            category: entry.category.clone(),
            synonyms: entry.synonyms.clone(),
            size: [size.x, size.y, size.z],
            placement,
            front: [0.0, 0.0, 1.0],
            support_surfaces,
            scale_range: entry.scale_range.unwrap_or([0.9, 1.1]),
        },
        mesh,
    })
}

/// Which loader reads this path, by extension.
fn mesh_kind(path: &Path) -> Option<&'static str> {
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    match ext.as_str() {
        "glb" | "gltf" => Some("gltf"),
        "obj" => Some("obj"),
        _ => None,
    }
}

/// Reads a GLB, glTF or OBJ file into a mesh in the file's own frame and units.
pub fn load_mesh(path: &Path) -> Result<Mesh, MeshLoadError> {
    match mesh_kind(path) {
        Some("gltf") => gltf_file::load(path),
        Some("obj") => obj::load(path),
        _ => Err(MeshLoadError::Unsupported),
    }
}

fn file_stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "asset".into())
}

/// Scales to metres, turns `up` to +Y and `front` to +Z, then moves the origin to the centre of
/// the footprint at the lowest point.
pub fn normalise(mesh: &mut Mesh, up: UpAxis, front: Front, unit_scale: f32) {
    let to_y_up = match up {
        UpAxis::Y => Rotation3::identity(),
        // z → y, y → −z: a rotation of −90° about +X.
        UpAxis::Z => Rotation3::from_axis_angle(&Vector3::x_axis(), -std::f32::consts::FRAC_PI_2),
    };
    let yaw = match front {
        Front::PosZ => 0.0,
        Front::NegZ => std::f32::consts::PI,
        // R_y(θ) takes +X to (cos θ, 0, −sin θ): θ = −90° gives +Z.
        Front::PosX => -std::f32::consts::FRAC_PI_2,
        Front::NegX => std::f32::consts::FRAC_PI_2,
    };
    let r: Matrix3<f32> =
        (Rotation3::from_axis_angle(&Vector3::y_axis(), yaw) * to_y_up).into_inner() * unit_scale;
    for p in mesh.parts.iter_mut().flat_map(|p| p.positions.iter_mut()) {
        let v = r * Vector3::from(*p);
        *p = [v.x, v.y, v.z];
    }
    if let Some(b) = mesh.bounds() {
        let shift = [
            -(b.min.x + b.max.x) as f32 * 0.5,
            -b.min.y as f32,
            -(b.min.z + b.max.z) as f32 * 0.5,
        ];
        for p in mesh.parts.iter_mut().flat_map(|p| p.positions.iter_mut()) {
            for k in 0..3 {
                p[k] += shift[k];
            }
        }
    }
}

#[cfg(test)]
mod tests;
