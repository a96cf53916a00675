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

mod clean;
mod gltf_file;
pub mod limits;
mod obj;
mod surfaces;

use std::collections::BTreeSet;
use std::fmt;
use std::path::{Path, PathBuf};

use nalgebra::{Matrix3, Rotation3, Vector3};
use scenethesis_scene_graph::{AssetRef, Mesh};
use serde::Deserialize;

use crate::{Asset, AssetInfo, Placement, SupportSurface};

pub use clean::{clean_mesh, Cleaned};
pub use gltf_file::{resolve_inside, GltfError, GltfFile, GltfMaterial, GltfNode, GltfPrimitive};
pub use surfaces::{find_support_surfaces, SurfaceSearch};

use limits::{
    MAX_ASSET_SCALE, MAX_ASSET_SIZE, MAX_MANIFEST_BYTES, MAX_MANIFEST_ENTRIES, MAX_SYNONYMS,
};

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

/// Imports every asset of `dir` (see the module documentation for the manifest format).
///
/// The manifest must be JSON holding an array of entries (or an object with an `assets` array);
/// anything else is an [`ImportError`]. Each entry is then checked on its own: an entry with a
/// bad field (named in the warning), a file outside `dir` (after resolving `..` and symbolic
/// links), or a mesh that cannot be used (unreadable, NaN or absurd coordinates, no area, larger
/// than [`limits::MAX_ASSET_SIZE`]) is skipped with an [`ImportWarning`]; the rest is imported.
/// Imported assets record the canonical absolute path of their file.
pub fn import_directory(dir: impl AsRef<Path>) -> Result<ImportReport, ImportError> {
    let dir = dir.as_ref();
    let root = dir
        .canonicalize()
        .map_err(|source| ImportError::Directory {
            path: dir.to_owned(),
            source,
        })?;
    if !root.is_dir() {
        return Err(ImportError::Directory {
            path: dir.to_owned(),
            source: std::io::Error::new(std::io::ErrorKind::NotADirectory, "not a directory"),
        });
    }
    let manifest_path = root.join(MANIFEST_FILE);
    let mut report = ImportReport::default();
    let entries: Vec<(String, Result<ManifestEntry, String>)> = if manifest_path.is_file() {
        read_manifest(&manifest_path)?
    } else {
        let listing = std::fs::read_dir(&root).map_err(|source| ImportError::Directory {
            path: dir.to_owned(),
            source,
        })?;
        let mut files: Vec<PathBuf> = listing
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.is_file() && mesh_kind(p).is_some())
            .collect();
        files.sort();
        files.truncate(MAX_MANIFEST_ENTRIES);
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
                let label = format!("file `{}`", printable(&stem));
                let entry = ManifestEntry {
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
                };
                (label, Ok(entry))
            })
            .collect()
    };
    let mut ids = BTreeSet::new();
    for (label, entry) in entries {
        let entry = match entry.and_then(|e| check_entry(&e).map(|()| e)) {
            Ok(e) => e,
            Err(reason) => {
                tracing::debug!("skipping asset {label}: {reason}");
                report.warnings.push(ImportWarning {
                    path: manifest_path.clone(),
                    reason: format!("{label}: {reason}"),
                });
                continue;
            }
        };
        let path = match resolve_inside(&root, &root, &entry.file.to_string_lossy()) {
            Ok(p) => p,
            Err(reason) => {
                tracing::debug!("skipping asset {label}: field `file`: {reason}");
                report.warnings.push(ImportWarning {
                    path: manifest_path.clone(),
                    reason: format!("{label}: field `file` {reason}"),
                });
                continue;
            }
        };
        match import_entry_in(&path, &root, &entry) {
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
                tracing::debug!("skipping asset {label}: {e}");
                report.warnings.push(ImportWarning {
                    path,
                    reason: format!("{label}: {e}"),
                });
            }
        }
    }
    Ok(report)
}

/// Reads `assets.json` into one (label, entry or error naming the field) per entry.
#[allow(clippy::type_complexity)]
fn read_manifest(path: &Path) -> Result<Vec<(String, Result<ManifestEntry, String>)>, ImportError> {
    let bytes =
        scenethesis_scene_graph::read_bounded(path, MAX_MANIFEST_BYTES).map_err(|source| {
            ImportError::ManifestIo {
                path: path.to_owned(),
                source,
            }
        })?;
    let value: serde_json::Value =
        serde_json::from_slice(&bytes).map_err(|source| ImportError::ManifestJson {
            path: path.to_owned(),
            source,
        })?;
    let shape = |reason: &str| ImportError::ManifestShape {
        path: path.to_owned(),
        reason: reason.to_owned(),
    };
    let list = match value {
        serde_json::Value::Array(list) => list,
        serde_json::Value::Object(mut map) => match map.remove("assets") {
            Some(serde_json::Value::Array(list)) => list,
            Some(_) => return Err(shape("field `assets` must be an array of entries")),
            None => {
                return Err(shape(
                    "expected an array of {\"file\", \"category\", ...} entries or an object with an `assets` array",
                ))
            }
        },
        _ => {
            return Err(shape(
                "expected an array of {\"file\", \"category\", ...} entries or an object with an `assets` array",
            ))
        }
    };
    if list.len() > MAX_MANIFEST_ENTRIES {
        return Err(shape(&format!(
            "{} entries, more than the limit of {MAX_MANIFEST_ENTRIES}",
            list.len()
        )));
    }
    Ok(list
        .into_iter()
        .enumerate()
        .map(|(k, value)| {
            let file = value
                .get("file")
                .and_then(|f| f.as_str())
                .map(|f| format!(" (file `{}`)", printable(f)))
                .unwrap_or_default();
            let label = format!("entry #{k}{file}");
            (label, parse_entry(value))
        })
        .collect())
}

/// One manifest entry, or why it is unusable, naming the field.
fn parse_entry(value: serde_json::Value) -> Result<ManifestEntry, String> {
    use serde_json::from_value as de;
    let serde_json::Value::Object(map) = &value else {
        return Err("expected an object with `file` and `category`".into());
    };
    for (key, v) in map {
        let v = v.clone();
        let result = match key.as_str() {
            "file" => de::<PathBuf>(v).map(drop),
            "id" => de::<Option<String>>(v).map(drop),
            "category" => de::<String>(v).map(drop),
            "synonyms" => de::<Vec<String>>(v).map(drop),
            "up_axis" => de::<UpAxis>(v).map(drop),
            "unit_scale" => de::<f32>(v).map(drop),
            "front" => de::<Front>(v).map(drop),
            "placement" => de::<Option<Placement>>(v).map(drop),
            "support_surfaces" => de::<Option<Vec<SupportSurface>>>(v).map(drop),
            "scale_range" => de::<Option<[f32; 2]>>(v).map(drop),
            other => {
                return Err(format!(
                    "unknown field `{}` (expected file, id, category, synonyms, up_axis, unit_scale, front, placement, support_surfaces or scale_range)",
                    printable(other)
                ))
            }
        };
        if let Err(e) = result {
            return Err(format!("field `{key}`: {e}"));
        }
    }
    for required in ["file", "category"] {
        if !map.contains_key(required) {
            return Err(format!("missing field `{required}`"));
        }
    }
    de::<ManifestEntry>(value).map_err(|e| e.to_string())
}

/// Checks the values of a parsed entry, naming the field at fault.
fn check_entry(entry: &ManifestEntry) -> Result<(), String> {
    let names = [
        ("category", Some(&entry.category)),
        ("id", entry.id.as_ref()),
    ];
    for (field, value) in names {
        if let Some(v) = value {
            if !scenethesis_scene_graph::is_printable_id(v) {
                return Err(format!(
                    "field `{field}` is `{}`, expected 1 to {} bytes of printable characters",
                    printable(v),
                    scenethesis_scene_graph::limits::MAX_ID_BYTES
                ));
            }
        }
    }
    if entry.synonyms.len() > MAX_SYNONYMS {
        return Err(format!(
            "field `synonyms` has {} names, more than the limit of {MAX_SYNONYMS}",
            entry.synonyms.len()
        ));
    }
    if let Some(s) = entry
        .synonyms
        .iter()
        .find(|s| !scenethesis_scene_graph::is_printable_id(s))
    {
        return Err(format!(
            "field `synonyms` holds `{}`, expected printable names",
            printable(s)
        ));
    }
    if !(entry.unit_scale.is_finite() && entry.unit_scale > 0.0 && entry.unit_scale <= 1000.0) {
        return Err(format!(
            "field `unit_scale` is {}, expected a positive number of metres per file unit (at most 1000)",
            entry.unit_scale
        ));
    }
    if let Some([lo, hi]) = entry.scale_range {
        if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && lo <= hi && hi <= MAX_ASSET_SCALE) {
            return Err(format!(
                "field `scale_range` is [{lo}, {hi}], expected [min, max] with 0 < min <= max <= {MAX_ASSET_SCALE}"
            ));
        }
    }
    if let Some(surfaces) = &entry.support_surfaces {
        if let Some(k) = surfaces.iter().position(|s| !surface_ok(s)) {
            return Err(format!(
                "field `support_surfaces[{k}]` has a non-finite number or a coordinate beyond ±{MAX_ASSET_SIZE} m"
            ));
        }
    }
    Ok(())
}

fn surface_ok(surface: &SupportSurface) -> bool {
    serde_json::to_value(surface)
        .ok()
        .map(|v| numbers_ok(&v))
        .unwrap_or(false)
}

/// Every number in `v` is finite and within ±[`MAX_ASSET_SIZE`].
fn numbers_ok(v: &serde_json::Value) -> bool {
    match v {
        serde_json::Value::Number(n) => n
            .as_f64()
            .is_some_and(|x| x.is_finite() && x.abs() <= MAX_ASSET_SIZE),
        serde_json::Value::Array(a) => a.iter().all(numbers_ok),
        serde_json::Value::Object(o) => o.values().all(numbers_ok),
        _ => true,
    }
}

fn printable(text: &str) -> std::borrow::Cow<'_, str> {
    scenethesis_scene_graph::printable(text)
}

/// Loads one mesh file and normalises it as `entry` says. Buffers and material libraries the
/// file names must lie in the file's own folder; see [`import_directory`] for a whole pack.
pub fn import_entry(path: &Path, entry: &ManifestEntry) -> Result<Asset, MeshLoadError> {
    let root = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    check_entry(entry).map_err(MeshLoadError::Entry)?;
    import_entry_in(path, root, entry)
}

/// [`import_entry`] with the folder that external files must stay inside.
fn import_entry_in(
    path: &Path,
    root: &Path,
    entry: &ManifestEntry,
) -> Result<Asset, MeshLoadError> {
    let mut mesh = load_mesh_in(path, root)?;
    if mesh.triangle_count() == 0 {
        return Err(MeshLoadError::Empty);
    }
    let cleaned = clean::clean_mesh(&mut mesh);
    if mesh.triangle_count() == 0 {
        return Err(MeshLoadError::Unusable(format!(
            "the mesh has zero surface area: no triangle is left after dropping {} zero-area and {} repeated triangles",
            cleaned.degenerate_triangles, cleaned.duplicate_triangles
        )));
    }
    normalise(&mut mesh, entry.up_axis, entry.front, entry.unit_scale);
    let bounds = mesh.bounds().ok_or(MeshLoadError::Empty)?;
    let extent = bounds.max - bounds.min;
    if !extent.iter().all(|v| v.is_finite()) || extent.max() > MAX_ASSET_SIZE {
        return Err(MeshLoadError::Unusable(format!(
            "the mesh is {:.3} x {:.3} x {:.3} m after unit_scale, larger than the limit of {MAX_ASSET_SIZE} m",
            extent.x, extent.y, extent.z
        )));
    }
    if mesh_area(&mesh) <= 1e-12 {
        return Err(MeshLoadError::Unusable(
            "the mesh has zero surface area (every triangle is degenerate)".into(),
        ));
    }
    let size = extent.map(|v| v as f32);
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

/// Surface area of a mesh (m²).
fn mesh_area(mesh: &Mesh) -> f64 {
    mesh.parts
        .iter()
        .flat_map(|p| {
            p.triangles.iter().map(move |t| {
                let [a, b, c] = t.map(|i| Vector3::from(p.positions[i as usize]).cast::<f64>());
                (b - a).cross(&(c - a)).norm() / 2.0
            })
        })
        .sum()
}

/// Which loader reads this path, by extension.
/// Which loader reads this path, by extension.
fn mesh_kind(path: &Path) -> Option<&'static str> {
    let ext = path.extension()?.to_str()?.to_ascii_lowercase();
    match ext.as_str() {
        "glb" | "gltf" => Some("gltf"),
        "obj" => Some("obj"),
        _ => None,
    }
}

/// Reads a GLB, glTF or OBJ file into a mesh in the file's own frame and units. Buffers and
/// material libraries it names must lie in the file's own folder.
pub fn load_mesh(path: &Path) -> Result<Mesh, MeshLoadError> {
    let root = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    load_mesh_in(path, root)
}

/// Parses OBJ text into a mesh in the file's own frame and units (`mtllib` files are not read:
/// parts get a grey default material). The same checks and limits as [`load_mesh`] apply.
pub fn parse_obj(text: &str) -> Result<Mesh, MeshLoadError> {
    obj::parse(text, |_| None)
}

fn load_mesh_in(path: &Path, root: &Path) -> Result<Mesh, MeshLoadError> {
    match mesh_kind(path) {
        Some("gltf") => gltf_file::load(path, root),
        Some("obj") => obj::load(path, root),
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

/// Why an asset reference could not be turned into an asset.
#[derive(Debug, thiserror::Error)]
pub enum ResolveError {
    /// A procedural reference names a generator the built-in library does not have.
    #[error("unknown procedural generator `{generator}`")]
    UnknownGenerator {
        /// The generator name (escaped for printing).
        generator: String,
    },
    /// An imported asset's folder could not be imported again, or no longer holds the asset.
    #[error("imported asset `{id}` ({path}): {reason}")]
    Imported {
        /// The asset id (escaped for printing).
        id: String,
        /// The stored path of its file (escaped for printing).
        path: String,
        /// What went wrong.
        reason: String,
    },
}

/// The one place that turns an [`AssetRef`] back into an [`Asset`] (mesh in the asset frame
/// plus metadata), used by export, `render` and `eval`: a procedural reference is regenerated
/// from its generator and seed; an imported one by importing its asset folder again (so the
/// manifest's units, axes and front apply) and picking the asset by id. The asset folder is the
/// nearest folder above the file that holds an `assets.json`, else the file's own folder.
/// Imported folders are cached, so resolving many objects of one pack imports it once.
#[derive(Debug, Default)]
pub struct AssetResolver {
    folders: std::collections::BTreeMap<PathBuf, Vec<Asset>>,
}

impl AssetResolver {
    /// A resolver with an empty cache.
    pub fn new() -> Self {
        Self::default()
    }

    /// The asset a reference names.
    pub fn asset(&mut self, asset: &AssetRef) -> Result<Asset, ResolveError> {
        match asset {
            AssetRef::Procedural { generator, seed } => {
                let category = crate::catalog::category(generator).ok_or_else(|| {
                    ResolveError::UnknownGenerator {
                        generator: printable(generator).into_owned(),
                    }
                })?;
                Ok(crate::catalog::generate(category, *seed))
            }
            AssetRef::Imported { id, path } => self.imported(id, path),
        }
    }

    /// The mesh (asset frame) of the asset a reference names.
    pub fn mesh(&mut self, asset: &AssetRef) -> Result<Mesh, ResolveError> {
        self.asset(asset).map(|a| a.mesh)
    }

    fn imported(&mut self, id: &str, path: &str) -> Result<Asset, ResolveError> {
        let err = |reason: String| ResolveError::Imported {
            id: printable(id).into_owned(),
            path: printable(path).into_owned(),
            reason,
        };
        let file = Path::new(path);
        if !file.is_absolute() {
            tracing::debug!(
                "imported asset path {path} is relative: resolved from the working directory"
            );
        }
        let folder = asset_folder(file).ok_or_else(|| err("its file no longer exists".into()))?;
        if !self.folders.contains_key(&folder) {
            let report = import_directory(&folder)
                .map_err(|e| err(format!("cannot re-import {}: {e}", folder.display())))?;
            self.folders.insert(folder.clone(), report.assets);
        }
        self.folders[&folder]
            .iter()
            .find(|a| matches!(&a.info.source, AssetRef::Imported { id: found, .. } if found == id))
            .cloned()
            .ok_or_else(|| {
                err(format!(
                    "the asset folder {} no longer holds an asset with this id",
                    folder.display()
                ))
            })
    }
}

/// The canonical asset folder of an imported file: the nearest of its (up to eight) ancestor
/// folders holding an `assets.json`, else its own folder. `None` when the file cannot be found.
fn asset_folder(file: &Path) -> Option<PathBuf> {
    let file = file.canonicalize().ok()?;
    let own = file.parent()?.to_owned();
    own.ancestors()
        .take(8)
        .find(|d| d.join(MANIFEST_FILE).is_file())
        .map(Path::to_owned)
        .or(Some(own))
}
