//! The importer: a list of [`AssetLoader`]s chosen by file extension, and everything done to
//! a loaded mesh whatever its format — cleaning, normalising to the scene conventions, the size
//! and area checks, the support-surface search — for one file or a whole asset folder.

use std::collections::BTreeSet;
use std::fmt;
use std::path::{Path, PathBuf};

use nalgebra::{Matrix3, Rotation3, Vector3};
use scenethesis_scene_graph::{
    opening_sweep, Asset, AssetInfo, AssetRef, Joint, JointKind, Mesh, Placement,
};

use crate::joints::{check_joints, link_joints, Fault};
use crate::limits::{MAX_ASSET_SIZE, MAX_MANIFEST_ENTRIES};
use crate::manifest::{check_entry, read_manifest, Front, ManifestEntry, UpAxis, MANIFEST_FILE};
use crate::{
    clean_mesh, find_support_surfaces, printable, resolve_inside, AssetLoader, GltfLoader,
    ImportError, ImportReport, ImportWarning, MeshLoadError, ObjLoader, SurfaceSearch,
};

/// One manifest entry as [`read_manifest`] gives it: a label naming it in warnings, and the
/// entry or why it is unusable.
type LabelledEntry = (String, Result<ManifestEntry, String>);

/// Imports mesh files with a list of [`AssetLoader`]s, the loader chosen by file extension.
/// [`Importer::new`] knows GLB/glTF and OBJ; [`Importer::with_loader`] adds a format.
pub struct Importer {
    loaders: Vec<Box<dyn AssetLoader>>,
}

impl Default for Importer {
    fn default() -> Self {
        Self {
            loaders: vec![Box::new(GltfLoader), Box::new(ObjLoader)],
        }
    }
}

impl fmt::Debug for Importer {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Importer")
            .field("extensions", &self.extensions())
            .finish()
    }
}

impl Importer {
    /// The built-in loaders: [`GltfLoader`] (`.glb`, `.gltf`) and [`ObjLoader`] (`.obj`).
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds `loader`, consulted before the loaders already present: a loader for a new
    /// extension adds a format, one for a known extension replaces that format's reader.
    pub fn with_loader(mut self, loader: impl AssetLoader + 'static) -> Self {
        self.loaders.insert(0, Box::new(loader));
        self
    }

    /// Every extension some loader reads, in the order the loaders are consulted.
    pub fn extensions(&self) -> Vec<&str> {
        let mut seen = Vec::new();
        for ext in self
            .loaders
            .iter()
            .flat_map(|l| l.extensions().iter().copied())
        {
            if !seen.contains(&ext) {
                seen.push(ext);
            }
        }
        seen
    }

    /// The loader that reads `path`, by its extension (compared without regard to case).
    pub fn loader_for(&self, path: &Path) -> Option<&dyn AssetLoader> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        self.loaders
            .iter()
            .find(|l| l.extensions().iter().any(|e| e.eq_ignore_ascii_case(&ext)))
            .map(|l| &**l)
    }

    /// Imports every asset of `dir` (see the crate documentation for the manifest format).
    ///
    /// The manifest must be JSON holding an array of entries (or an object with an `assets`
    /// array); anything else is an [`ImportError`]. Each entry is then checked on its own: an
    /// entry with a bad field (named in the warning), a file outside `dir` (after resolving `..`
    /// and symbolic links), or a mesh that cannot be used (unreadable, no loader for its
    /// extension, NaN or absurd coordinates, no area, larger than
    /// [`limits::MAX_ASSET_SIZE`](crate::limits::MAX_ASSET_SIZE)) is skipped with an
    /// [`ImportWarning`]; the rest is imported. Without a manifest, every file some loader reads
    /// is imported. Imported assets record the canonical absolute path of their file.
    pub fn import_directory(&self, dir: impl AsRef<Path>) -> Result<ImportReport, ImportError> {
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
        let entries = if manifest_path.is_file() {
            read_manifest(&manifest_path)?
        } else {
            self.entries_without_manifest(dir, &root, &manifest_path, &mut report)?
        };
        let mut ids = BTreeSet::new();
        for (label, entry) in entries {
            self.import_listed(&root, &manifest_path, label, entry, &mut ids, &mut report)?;
        }
        Ok(report)
    }

    /// One default entry per file of `root` that some loader reads, in file-name order, with a
    /// note in `report` that the defaults apply.
    fn entries_without_manifest(
        &self,
        dir: &Path,
        root: &Path,
        manifest_path: &Path,
        report: &mut ImportReport,
    ) -> Result<Vec<LabelledEntry>, ImportError> {
        let listing = std::fs::read_dir(root).map_err(|source| ImportError::Directory {
            path: dir.to_owned(),
            source,
        })?;
        let mut files: Vec<PathBuf> = listing
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.is_file() && self.loader_for(p).is_some())
            .collect();
        files.sort();
        files.truncate(MAX_MANIFEST_ENTRIES);
        if !files.is_empty() {
            report.warnings.push(ImportWarning {
                path: manifest_path.to_owned(),
                reason: "no manifest: importing every mesh file with its file stem as category, +Y up, metres, front +Z".into(),
            });
        }
        Ok(files
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
                    joints: Vec::new(),
                };
                (label, Ok(entry))
            })
            .collect())
    }

    /// Imports one listed entry into `report` (with an id not yet in `ids`), or adds the
    /// warning that says why it was skipped; a malformed joint is an error.
    fn import_listed(
        &self,
        root: &Path,
        manifest_path: &Path,
        label: String,
        entry: Result<ManifestEntry, String>,
        ids: &mut BTreeSet<String>,
        report: &mut ImportReport,
    ) -> Result<(), ImportError> {
        let entry = match entry.and_then(|e| check_entry(&e).map(|()| e)) {
            Ok(e) => e,
            Err(reason) => {
                tracing::debug!("skipping asset {label}: {reason}");
                report.warnings.push(ImportWarning {
                    path: manifest_path.to_owned(),
                    reason: format!("{label}: {reason}"),
                });
                return Ok(());
            }
        };
        let path = match resolve_inside(root, root, &entry.file.to_string_lossy()) {
            Ok(p) => p,
            Err(reason) => {
                tracing::debug!("skipping asset {label}: field `file`: {reason}");
                report.warnings.push(ImportWarning {
                    path: manifest_path.to_owned(),
                    reason: format!("{label}: field `file` {reason}"),
                });
                return Ok(());
            }
        };
        match self.import_entry_in(&path, root, &entry) {
            Ok((mut asset, warnings)) => {
                report
                    .warnings
                    .extend(warnings.into_iter().map(|w| ImportWarning {
                        path: path.clone(),
                        reason: format!("{label}: {w}"),
                    }));
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
            Err(MeshLoadError::Joint { field, problem }) => {
                let fault = Fault { field, problem };
                return Err(ImportError::joint(manifest_path, label, fault));
            }
            Err(e) => {
                tracing::debug!("skipping asset {label}: {e}");
                report.warnings.push(ImportWarning {
                    path,
                    reason: format!("{label}: {e}"),
                });
            }
        }
        Ok(())
    }

    /// Loads one mesh file and normalises it as `entry` says. Buffers and material libraries
    /// the file names must lie in the file's own folder; see [`Importer::import_directory`] for
    /// a whole pack.
    pub fn import_entry(&self, path: &Path, entry: &ManifestEntry) -> Result<Asset, MeshLoadError> {
        check_entry(entry).map_err(MeshLoadError::Entry)?;
        let (asset, warnings) = self.import_entry_in(path, own_folder(path), entry)?;
        for w in warnings {
            tracing::warn!("{}: {w}", printable(&path.display().to_string()));
        }
        Ok(asset)
    }

    /// Reads a mesh file with the loader for its extension, in the file's own frame and units.
    /// Buffers and material libraries it names must lie in the file's own folder.
    pub fn load_mesh(&self, path: &Path) -> Result<Mesh, MeshLoadError> {
        self.load_mesh_in(path, own_folder(path))
    }

    fn load_mesh_in(&self, path: &Path, root: &Path) -> Result<Mesh, MeshLoadError> {
        let (mesh, warnings) = self.load_mesh_noting(path, root)?;
        for w in warnings {
            tracing::warn!("{}: {w}", printable(&path.display().to_string()));
        }
        Ok(mesh)
    }

    /// The mesh of `path` and the loader's warnings about it (a texture it could not use).
    fn load_mesh_noting(
        &self,
        path: &Path,
        root: &Path,
    ) -> Result<(Mesh, Vec<String>), MeshLoadError> {
        match self.loader_for(path) {
            Some(loader) => loader.load_with_warnings(path, root),
            None => Err(MeshLoadError::Unsupported {
                expected: expected_list(&self.extensions()),
            }),
        }
    }

    /// [`Importer::import_entry`] with the folder that external files must stay inside.
    /// Also returns the loader's warnings about the file (a texture it could not use).
    fn import_entry_in(
        &self,
        path: &Path,
        root: &Path,
        entry: &ManifestEntry,
    ) -> Result<(Asset, Vec<String>), MeshLoadError> {
        check_joints(&entry.joints).map_err(Fault::into_error)?;
        let (mut mesh, warnings) = self.load_mesh_noting(path, root)?;
        if mesh.triangle_count() == 0 {
            return Err(MeshLoadError::Empty);
        }
        let cleaned = clean_mesh(&mut mesh);
        if mesh.triangle_count() == 0 {
            return Err(MeshLoadError::Unusable(format!(
                "the mesh has zero surface area: no triangle is left after dropping {} zero-area and {} repeated triangles",
                cleaned.degenerate_triangles, cleaned.duplicate_triangles
            )));
        }
        let frame = normalise_frame(&mut mesh, entry.up_axis, entry.front, entry.unit_scale);
        let joints =
            link_joints(&mut mesh, &entry.joints, |j| frame.joint(j)).map_err(Fault::into_error)?;
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
            scenethesis_procedural::catalog::category(&entry.category)
                .map(|c| c.placement)
                .unwrap_or(Placement::Floor)
        });
        let support_surfaces = match &entry.support_surfaces {
            Some(s) => s.clone(),
            None => find_support_surfaces(&mesh, &SurfaceSearch::default()),
        };
        let asset = Asset {
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
                opening_bounds: opening_sweep(&mesh, &joints),
                joints,
            },
            mesh,
        };
        Ok((asset, warnings))
    }
}

/// The folder of `path`, `.` when it has none.
fn own_folder(path: &Path) -> &Path {
    path.parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

/// `.glb, .gltf or .obj`: the extensions as a message lists them.
fn expected_list(extensions: &[&str]) -> String {
    let dotted: Vec<String> = extensions.iter().map(|e| format!(".{e}")).collect();
    match dotted.split_last() {
        None => "no file type: the importer has no loader".into(),
        Some((last, [])) => last.clone(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
    }
}

/// [`Importer::import_directory`] with the built-in loaders (GLB/glTF and OBJ).
pub fn import_directory(dir: impl AsRef<Path>) -> Result<ImportReport, ImportError> {
    Importer::new().import_directory(dir)
}

/// [`Importer::import_entry`] with the built-in loaders.
pub fn import_entry(path: &Path, entry: &ManifestEntry) -> Result<Asset, MeshLoadError> {
    Importer::new().import_entry(path, entry)
}

/// [`Importer::load_mesh`] with the built-in loaders: reads a GLB, glTF or OBJ file into a
/// mesh in the file's own frame and units.
pub fn load_mesh(path: &Path) -> Result<Mesh, MeshLoadError> {
    Importer::new().load_mesh(path)
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

fn file_stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "asset".into())
}

/// Scales to metres, turns `up` to +Y and `front` to +Z, then moves the origin to the centre of
/// the footprint at the lowest point.
pub fn normalise(mesh: &mut Mesh, up: UpAxis, front: Front, unit_scale: f32) {
    normalise_frame(mesh, up, front, unit_scale);
}

/// The map [`normalise`] applies: file frame and units to the asset frame, `p ↦ linear·p +
/// shift`.
struct Frame {
    linear: Matrix3<f32>,
    shift: [f32; 3],
    unit_scale: f32,
}

impl Frame {
    /// `joint` (file frame and units) in the asset frame: the anchor mapped as a vertex, the
    /// axis turned (unit length), prismatic limits scaled to metres.
    fn joint(&self, joint: &Joint) -> Joint {
        let a = self.linear * Vector3::from(joint.anchor);
        let axis = (self.linear * Vector3::from(joint.axis)).normalize();
        let k = match joint.kind {
            JointKind::Revolute => 1.0,
            JointKind::Prismatic => self.unit_scale,
        };
        Joint {
            anchor: [
                a.x + self.shift[0],
                a.y + self.shift[1],
                a.z + self.shift[2],
            ],
            axis: [axis.x, axis.y, axis.z],
            limits: joint.limits.map(|l| l * k),
            ..joint.clone()
        }
    }
}

/// [`normalise`], returning the map it applied.
fn normalise_frame(mesh: &mut Mesh, up: UpAxis, front: Front, unit_scale: f32) -> Frame {
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
    let shift = mesh.bounds().map_or([0.0; 3], |b| {
        [
            -(b.min.x + b.max.x) as f32 * 0.5,
            -b.min.y as f32,
            -(b.min.z + b.max.z) as f32 * 0.5,
        ]
    });
    for p in mesh.parts.iter_mut().flat_map(|p| p.positions.iter_mut()) {
        for k in 0..3 {
            p[k] += shift[k];
        }
    }
    Frame {
        linear: r,
        shift,
        unit_scale,
    }
}
