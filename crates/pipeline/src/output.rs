//! Output folders: writing a generated scene atomically, and exporting a saved one.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use scenethesis_eval::EvalObject;
use scenethesis_export::{ExportScene, Format};
use scenethesis_scene_graph::{Mesh, Scene};

use crate::assets::AssetSource;
use crate::pipeline::{GeneratedScene, Stage};
use crate::report::StageTiming;
use crate::PipelineError;

/// The scene graph file of an output folder.
pub const SCENE_JSON: &str = "scene.json";
/// The report file of an output folder.
pub const REPORT_JSON: &str = "report.json";

fn io_error(path: &Path) -> impl FnOnce(std::io::Error) -> PipelineError + '_ {
    move |source| PipelineError::Io {
        path: path.to_owned(),
        source,
    }
}

/// The objects the physics formats should weld to the world: the same rule the stability metric
/// uses (wall and ceiling categories, and anything standing against a wall high above the
/// floor).
pub fn welded_objects(scene: &Scene, meshes: &BTreeMap<String, Mesh>) -> Vec<String> {
    scene
        .objects
        .iter()
        .filter(|o| {
            meshes
                .get(&o.id)
                .is_some_and(|m| EvalObject::from_scene_object(o, m).welded)
        })
        .map(|o| o.id.clone())
        .collect()
}

impl GeneratedScene {
    /// Writes the output folder `dir`: `scene.glb`, `scene.json`, the previews and
    /// `report.json` (with the export time added to its timings). Atomic: everything is written
    /// into a temporary folder next to `dir` and renamed into place, so a failed run leaves no
    /// half-written scene; an existing `dir` is replaced only once the new one is complete.
    pub fn write_outputs(&mut self, dir: &Path) -> Result<PathBuf, PipelineError> {
        let started = Instant::now();
        let name = dir
            .file_name()
            .ok_or_else(|| PipelineError::BadOutput {
                path: dir.to_owned(),
                reason: "the output path has no folder name".into(),
            })?
            .to_string_lossy()
            .into_owned();
        let parent = match dir.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_owned(),
            _ => PathBuf::from("."),
        };
        std::fs::create_dir_all(&parent).map_err(io_error(&parent))?;
        let staging = tempfile::Builder::new()
            .prefix(&format!(".{name}.partial-"))
            .tempdir_in(&parent)
            .map_err(io_error(&parent))?;
        let tmp = staging.path();

        let welded = welded_objects(&self.scene, &self.meshes);
        let export = ExportScene::new(&self.scene, &self.meshes)?.with_fixed(welded);
        Format::Glb.write(&export, tmp)?;
        let scene_path = tmp.join(SCENE_JSON);
        self.scene.write_json_atomic(&scene_path)?;
        for (file, png) in &self.previews {
            let path = tmp.join(file);
            std::fs::write(&path, png).map_err(io_error(&path))?;
        }
        self.report.timings.push(StageTiming {
            stage: Stage::Export,
            seconds: started.elapsed().as_secs_f64(),
        });
        let report_path = tmp.join(REPORT_JSON);
        let text = serde_json::to_string_pretty(&self.report).expect("report serializes") + "\n";
        std::fs::write(&report_path, text).map_err(io_error(&report_path))?;

        replace_dir(staging, dir, &parent, &name)?;
        Ok(dir.to_owned())
    }
}

/// Moves the finished staging folder to `dir`, replacing an existing folder only after the new
/// one is complete.
fn replace_dir(
    staging: tempfile::TempDir,
    dir: &Path,
    parent: &Path,
    name: &str,
) -> Result<(), PipelineError> {
    let old = if dir.exists() {
        let aside = tempfile::Builder::new()
            .prefix(&format!(".{name}.old-"))
            .tempdir_in(parent)
            .map_err(io_error(parent))?;
        let aside_path = aside.path().join("previous");
        std::fs::rename(dir, &aside_path).map_err(io_error(dir))?;
        Some(aside)
    } else {
        None
    };
    let staged = staging.keep();
    if let Err(source) = std::fs::rename(&staged, dir) {
        let _ = std::fs::remove_dir_all(&staged);
        if let Some(old) = &old {
            let _ = std::fs::rename(old.path().join("previous"), dir);
        }
        return Err(PipelineError::Io {
            path: dir.to_owned(),
            source,
        });
    }
    // Dropping `old` deletes the previous output.
    drop(old);
    Ok(())
}

/// Exports a saved output folder (`dir/scene.json`) in the given formats, regenerating each
/// object's mesh with `assets`; returns the written files.
pub fn export_folder(
    dir: &Path,
    formats: &[Format],
    assets: &dyn AssetSource,
) -> Result<Vec<PathBuf>, PipelineError> {
    let scene = Scene::read_json(&dir.join(SCENE_JSON))?;
    let meshes = resolve_meshes(&scene, assets)?;
    let welded = welded_objects(&scene, &meshes);
    let export = ExportScene::new(&scene, &meshes)?.with_fixed(welded);
    let mut written = Vec::new();
    for format in formats {
        written.push(format.write(&export, dir)?);
    }
    Ok(written)
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
