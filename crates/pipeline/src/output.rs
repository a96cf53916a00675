//! Output folders: writing a generated scene atomically, and exporting a saved one.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use scenethesis_export::{ExportError, ExportScene, Format};
use scenethesis_scene_graph::{Mesh, Scene, SceneIoError};

use crate::error::PipelineError;
use crate::out_dir::{OutputDir, REPORT_JSON, SCENE_JSON};
use crate::pipeline::GeneratedScene;
use crate::report::{Report, StageTiming};
use crate::stage::Stage;
use scenethesis_retrieval::AssetSource;

impl GeneratedScene {
    /// Writes the output folder `dir` after checking it with [`OutputDir::prepare`] (without
    /// `force`: a folder holding anything scenethesis did not write is refused). See
    /// [`GeneratedScene::write_to`].
    pub fn write_outputs(&mut self, dir: &Path) -> Result<PathBuf, PipelineError> {
        let out = OutputDir::prepare(dir, false)?;
        self.write_to(&out)
    }

    /// Writes `scene.glb`, `scene.json`, the previews and `report.json` (with the export time
    /// added to its timings) into a checked output folder. Atomic: everything is written into a
    /// private staging folder next to it and swapped into place, so a failed or killed run
    /// leaves no half-written scene, and the previous output is replaced only once the new one
    /// is complete. Returns the absolute path written.
    pub fn write_to(&mut self, out: &OutputDir) -> Result<PathBuf, PipelineError> {
        let started = Instant::now();
        write_staged(out, |dir| self.write_files(dir, started))
    }

    fn write_files(&mut self, tmp: &Path, started: Instant) -> Result<(), PipelineError> {
        write_scene_files(tmp, &self.scene, &self.meshes, &self.previews)?;
        self.report.timings.push(StageTiming {
            stage: Stage::Export,
            seconds: started.elapsed().as_secs_f64(),
            parts: Vec::new(),
        });
        write_report(tmp, &self.report)
    }
}

/// Writes `scene.glb`, `scene.json` and the previews into the folder `dir`.
pub(crate) fn write_scene_files(
    dir: &Path,
    scene: &Scene,
    meshes: &BTreeMap<String, Mesh>,
    previews: &[(String, Vec<u8>)],
) -> Result<(), PipelineError> {
    let export = ExportScene::new(scene, meshes)?;
    Format::Glb.write(&export, dir)?;
    scene.write_json_atomic(&dir.join(SCENE_JSON))?;
    for (file, png) in previews {
        let path = dir.join(file);
        std::fs::write(&path, png).map_err(|source| PipelineError::Write { path, source })?;
    }
    Ok(())
}

/// Writes `report.json` into the folder `dir`.
pub(crate) fn write_report(dir: &Path, report: &Report) -> Result<(), PipelineError> {
    let path = dir.join(REPORT_JSON);
    let text = serde_json::to_string_pretty(report).expect("report serializes") + "\n";
    std::fs::write(&path, text).map_err(|source| PipelineError::Write { path, source })
}

/// Writes a staged output folder's files with `write`, then swaps it into place; an error
/// names the final path, not the private staging folder.
pub(crate) fn write_staged(
    out: &OutputDir,
    write: impl FnOnce(&Path) -> Result<(), PipelineError>,
) -> Result<PathBuf, PipelineError> {
    let staging = out.stage()?;
    write(staging.path()).map_err(|e| unstage(e, staging.path(), out.path()))?;
    out.commit(staging)?;
    Ok(out.path().to_owned())
}

/// Names the final output path instead of the private staging folder in a write error.
fn unstage(e: PipelineError, staging: &Path, out: &Path) -> PipelineError {
    let fix = |path: PathBuf| match path.strip_prefix(staging) {
        Ok(rest) => out.join(rest),
        Err(_) => path,
    };
    match e {
        PipelineError::Write { path, source } => PipelineError::Write {
            path: fix(path),
            source,
        },
        PipelineError::Export(ExportError::Write { path, source }) => {
            PipelineError::Export(ExportError::Write {
                path: fix(path),
                source,
            })
        }
        PipelineError::SceneIo(SceneIoError::Write { path, source }) => {
            PipelineError::SceneIo(SceneIoError::Write {
                path: fix(path),
                source,
            })
        }
        other => other,
    }
}

/// Exports a saved output folder (`dir/scene.json`) in the given formats, regenerating each
/// object's mesh with `assets`; returns the written files. All or nothing: every format is
/// built in memory and staged before any file in `dir` is replaced.
pub fn export_folder(
    dir: &Path,
    formats: &[Format],
    assets: &dyn AssetSource,
) -> Result<Vec<PathBuf>, PipelineError> {
    let scene = Scene::read_json(&dir.join(SCENE_JSON))?;
    let meshes = resolve_meshes(&scene, assets)?;
    let export = ExportScene::new(&scene, &meshes)?;
    Ok(scenethesis_export::write_formats(formats, &export, dir)?)
}

/// Every object's asset-frame mesh, regenerated from its asset reference (shared assets are
/// built once).
pub fn resolve_meshes(
    scene: &Scene,
    assets: &dyn AssetSource,
) -> Result<BTreeMap<String, Mesh>, PipelineError> {
    let mut by_asset: BTreeMap<String, Mesh> = BTreeMap::new();
    let mut meshes = BTreeMap::new();
    for object in &scene.objects {
        let key = object.asset.to_string();
        if !by_asset.contains_key(&key) {
            let mesh = assets.mesh(&object.asset)?;
            by_asset.insert(key.clone(), mesh);
        }
        meshes.insert(object.id.clone(), by_asset[&key].clone());
    }
    Ok(meshes)
}

/// Writes `scene` in the format its file name's suffix asks for (`.glb`, `.usda`, `.xml` for
/// MJCF, `.urdf`) to `path`, regenerating nothing: `meshes` holds every object's asset-frame
/// mesh. Returns the files written (a URDF's mesh folder too); all or nothing.
pub fn export_file(
    scene: &Scene,
    meshes: &BTreeMap<String, Mesh>,
    path: &Path,
) -> Result<Vec<PathBuf>, PipelineError> {
    let format = Format::from_path(path).ok_or_else(|| PipelineError::BadOutput {
        path: path.to_owned(),
        reason: "unknown export format: expected a file name ending in .glb, .usda, .xml \
                 (MJCF) or .urdf"
            .into(),
    })?;
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !parent.is_dir() {
        return Err(PipelineError::BadOutput {
            path: path.to_owned(),
            reason: format!("the folder {} does not exist", parent.display()),
        });
    }
    if path.is_dir() {
        return Err(PipelineError::BadOutput {
            path: path.to_owned(),
            reason: "is a folder; give the file to write".into(),
        });
    }
    let export = ExportScene::new(scene, meshes)?;
    Ok(format.write_file(&export, path)?)
}
