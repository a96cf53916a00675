//! A saved output folder read back: its scene, report and previews, to inspect, measure,
//! export or save elsewhere (what the Python package's `load` returns).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use scenethesis_render_api::PREVIEW_FILES;
use scenethesis_retrieval::AssetSource;
use scenethesis_scene_graph::{limits, read_bounded, Mesh, Scene};

use crate::error::PipelineError;
use crate::out_dir::{OutputDir, REPORT_JSON, SCENE_JSON};
use crate::output::{resolve_meshes, write_report, write_scene_files, write_staged};
use crate::report::Report;

/// Largest preview image read back, in bytes (a 4096×4096 RGBA PNG stays far below it).
const MAX_PREVIEW_BYTES: u64 = 256 * 1024 * 1024;

/// An output folder of `generate` read back.
#[derive(Debug, Clone)]
pub struct SavedScene {
    /// The folder it was read from.
    pub dir: PathBuf,
    /// The scene graph (`scene.json`).
    pub scene: Scene,
    /// Each object's asset-frame mesh, regenerated from its asset reference.
    pub meshes: BTreeMap<String, Mesh>,
    /// The report (`report.json`), when the folder holds a readable one.
    pub report: Option<Report>,
    /// The preview images the folder holds: file name and PNG bytes.
    pub previews: Vec<(String, Vec<u8>)>,
}

impl SavedScene {
    /// Reads the output folder `dir`: `scene.json` (required and validated), every object's
    /// mesh regenerated through `assets`, and `report.json` and the previews when present.
    pub fn read(dir: &Path, assets: &dyn AssetSource) -> Result<Self, PipelineError> {
        let scene = Scene::read_json(&dir.join(SCENE_JSON))?;
        let meshes = resolve_meshes(&scene, assets)?;
        let report = read_report(dir)?;
        let mut previews = Vec::new();
        for name in PREVIEW_FILES {
            let path = dir.join(name);
            if !path.is_file() {
                continue;
            }
            let bytes = read_bounded(&path, MAX_PREVIEW_BYTES)
                .map_err(|source| PipelineError::Read { path, source })?;
            previews.push((name.to_owned(), bytes));
        }
        Ok(Self {
            dir: dir.to_owned(),
            scene,
            meshes,
            report,
            previews,
        })
    }

    /// Writes the scene into a checked output folder, as `generate` does (atomically:
    /// `scene.glb`, `scene.json`, the previews and the report unchanged).
    pub fn write_to(&self, out: &OutputDir) -> Result<PathBuf, PipelineError> {
        write_staged(out, |dir| {
            write_scene_files(dir, &self.scene, &self.meshes, &self.previews)?;
            match &self.report {
                Some(report) => write_report(dir, report),
                None => Ok(()),
            }
        })
    }
}

/// `dir/report.json` when it exists; a file that exists but is not a report is an error.
fn read_report(dir: &Path) -> Result<Option<Report>, PipelineError> {
    let path = dir.join(REPORT_JSON);
    if !path.is_file() {
        return Ok(None);
    }
    let bytes = read_bounded(&path, limits::MAX_SCENE_JSON_BYTES).map_err(|source| {
        PipelineError::Read {
            path: path.clone(),
            source,
        }
    })?;
    serde_json::from_slice(&bytes)
        .map(Some)
        .map_err(|e| PipelineError::Read {
            path,
            source: std::io::Error::new(std::io::ErrorKind::InvalidData, e.to_string()),
        })
}
