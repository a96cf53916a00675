//! A generated or loaded scene, held natively; Python reads it through JSON and byte buffers.

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::path::PathBuf;

use pyo3::exceptions::PyKeyError;
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use scenethesis_pipeline::{export_file, GeneratedScene, OutputDir, Report, SavedScene};
use scenethesis_scene_graph::{Mesh, Scene};
use serde::Serialize;

use crate::errors::Failure;

/// Where a scene came from: a run of the pipeline, or an output folder read back.
enum Held {
    Generated(Box<GeneratedScene>),
    Saved(Box<SavedScene>),
}

/// A scene: its graph, meshes, previews and report.
#[pyclass(module = "scenethesis._native")]
pub struct NativeScene {
    held: Held,
}

impl NativeScene {
    /// A scene the pipeline generated.
    pub fn generated(scene: GeneratedScene) -> Self {
        Self {
            held: Held::Generated(Box::new(scene)),
        }
    }

    /// A scene read from an output folder.
    pub fn saved(scene: SavedScene) -> Self {
        Self {
            held: Held::Saved(Box::new(scene)),
        }
    }

    fn scene(&self) -> &Scene {
        match &self.held {
            Held::Generated(g) => &g.scene,
            Held::Saved(s) => &s.scene,
        }
    }

    fn meshes(&self) -> &BTreeMap<String, Mesh> {
        match &self.held {
            Held::Generated(g) => &g.meshes,
            Held::Saved(s) => &s.meshes,
        }
    }

    fn previews(&self) -> &[(String, Vec<u8>)] {
        match &self.held {
            Held::Generated(g) => &g.previews,
            Held::Saved(s) => &s.previews,
        }
    }

    fn report(&self) -> Option<&Report> {
        match &self.held {
            Held::Generated(g) => Some(&g.report),
            Held::Saved(s) => s.report.as_ref(),
        }
    }
}

/// One object as Python sees it.
#[derive(Serialize)]
struct ObjectView<'a> {
    id: &'a str,
    category: &'a str,
    parent: &'a str,
    support: &'a str,
    relations: Vec<(&'a str, &'a str)>,
    /// Row-major 4×4 asset-to-world transform.
    pose: [f64; 16],
    /// World-space axis-aligned bounds: [min, max].
    bounds: [[f64; 3]; 2],
    asset: String,
}

#[pymethods]
impl NativeScene {
    /// The scene graph as the JSON of `scene.json`.
    fn scene_json(&self) -> String {
        self.scene().to_json_string()
    }

    /// The report as the JSON of `report.json`, if the scene has one.
    fn report_json(&self) -> Option<String> {
        self.report()
            .map(|r| serde_json::to_string_pretty(r).expect("report serializes"))
    }

    /// Whether the judge accepted the scene (`None` when there is no report).
    fn accepted(&self) -> Option<bool> {
        self.report().map(|r| r.accepted)
    }

    /// The report's one-line summary, as the CLI prints it.
    fn summary_line(&self) -> Option<String> {
        self.report().map(Report::summary_line)
    }

    /// Why the judge rejected the scene (empty when accepted or unknown).
    fn rejection_reasons(&self) -> String {
        self.report()
            .filter(|r| !r.accepted)
            .map(|r| r.verdict.reasons())
            .unwrap_or_default()
    }

    /// The objects, as JSON: id, category, parent, support, relations, pose (row-major 4×4),
    /// world bounds and asset.
    fn objects_json(&self) -> String {
        let views: Vec<ObjectView<'_>> = self
            .scene()
            .objects
            .iter()
            .map(|o| {
                let m = o.pose.to_matrix();
                let mut pose = [0.0; 16];
                for (r, row) in pose.chunks_mut(4).enumerate() {
                    for (c, v) in row.iter_mut().enumerate() {
                        *v = m[(r, c)];
                    }
                }
                let b = o.world_aabb();
                ObjectView {
                    id: &o.id,
                    category: &o.category,
                    parent: o.parent.as_str(),
                    support: o.support.as_str(),
                    relations: o
                        .relations
                        .iter()
                        .map(|r| (r.kind.as_str(), r.target.as_str()))
                        .collect(),
                    pose,
                    bounds: [[b.min.x, b.min.y, b.min.z], [b.max.x, b.max.y, b.max.z]],
                    asset: o.asset.to_string(),
                }
            })
            .collect();
        serde_json::to_string(&views).expect("objects serialize")
    }

    /// The names of the preview images the scene holds.
    fn preview_names(&self) -> Vec<String> {
        self.previews().iter().map(|(n, _)| n.clone()).collect()
    }

    /// A preview image as `(rgba_bytes, width, height)`, rendered now at `size` when the scene
    /// holds none of that name (needs a renderer: a GPU or Mesa).
    #[pyo3(signature = (name, size=(1024, 768)))]
    fn preview_rgba<'py>(
        &self,
        py: Python<'py>,
        name: &str,
        size: (u32, u32),
    ) -> PyResult<(Bound<'py, PyBytes>, u32, u32)> {
        let held = self.previews().iter().find(|(n, _)| n == name);
        let png: Cow<'_, [u8]> = match held {
            Some((_, bytes)) => Cow::Borrowed(bytes),
            None => Cow::Owned(self.render(py, name, size)?),
        };
        let decoded = py.detach(|| image::load_from_memory(&png).map(|i| i.to_rgba8()));
        let image = decoded
            .map_err(|e| Failure::other(&e, format!("decoding the preview {name}")).into_py())?;
        let (w, h) = image.dimensions();
        Ok((PyBytes::new(py, image.as_raw()), w, h))
    }

    /// Writes the output folder as `generate --out` does (atomically; an existing folder is
    /// replaced only when it holds an earlier scenethesis output, or with `force`). Returns the
    /// absolute path written.
    #[pyo3(signature = (folder, force=false))]
    fn save(&mut self, py: Python<'_>, folder: PathBuf, force: bool) -> PyResult<String> {
        let held = &mut self.held;
        let outcome = py.detach(|| -> Result<PathBuf, Failure> {
            let context = || format!("saving {}", folder.display());
            let out =
                OutputDir::prepare(&folder, force).map_err(|e| Failure::pipeline(&e, context()))?;
            match held {
                Held::Generated(g) => g.write_to(&out),
                Held::Saved(s) => s.write_to(&out),
            }
            .map_err(|e| Failure::pipeline(&e, context()))
        });
        let path = outcome.map_err(Failure::into_py)?;
        Ok(path.to_string_lossy().into_owned())
    }

    /// Writes the scene to `path` in the format its suffix names (.glb, .usda, .xml for MJCF,
    /// .urdf); returns the files written.
    fn export(&self, py: Python<'_>, path: PathBuf) -> PyResult<Vec<String>> {
        let (scene, meshes) = (self.scene(), self.meshes());
        let outcome = py.detach(|| {
            export_file(scene, meshes, &path)
                .map_err(|e| Failure::pipeline(&e, format!("exporting {}", path.display())))
        });
        let written = outcome.map_err(Failure::into_py)?;
        Ok(written
            .iter()
            .map(|p| p.to_string_lossy().into_owned())
            .collect())
    }

    /// The metrics of `scenethesis eval --json` for this scene, as JSON.
    fn evaluate(&self, py: Python<'_>) -> PyResult<String> {
        let (scene, meshes) = (self.scene(), self.meshes());
        let outcome = py.detach(|| {
            let eval = scenethesis_eval::EvalScene::from_scene(scene, |o| {
                Ok(meshes.get(&o.id).cloned().unwrap_or_default())
            })
            .and_then(|s| s.check_limits().map(|()| s))
            .map_err(|e| Failure::input(&e, "evaluating the scene".into()))?;
            let metrics = scenethesis_eval::evaluate(&eval);
            Ok(serde_json::to_string(&metrics).expect("metrics serialize"))
        });
        outcome.map_err(Failure::into_py)
    }
}

impl NativeScene {
    /// Renders the previews now and returns the one called `name`.
    fn render(&self, py: Python<'_>, name: &str, size: (u32, u32)) -> PyResult<Vec<u8>> {
        let (scene, meshes) = (self.scene(), self.meshes());
        let rendered = py.detach(|| -> Result<_, String> {
            let renderer = scenethesis_render::Renderer::from_env().map_err(|e| e.to_string())?;
            scenethesis_render_api::render_previews(&renderer, scene, meshes, [size.0, size.1])
                .map_err(|e| e.to_string())
        });
        let images = rendered.map_err(|e| {
            crate::errors::ScenethesisError::new_err(format!("rendering the previews: {e}"))
        })?;
        images
            .into_iter()
            .find(|(n, _)| n == name)
            .map(|(_, png)| png)
            .ok_or_else(|| PyKeyError::new_err(format!("no preview called {name}")))
    }
}
