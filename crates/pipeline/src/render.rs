//! Preview images with the headless wgpu renderer (feature `render`).

use std::collections::BTreeMap;
use std::io::Cursor;
use std::sync::Arc;

use scenethesis_render::{views, Instance, RenderError, RenderScene, Renderer};
use scenethesis_scene_graph::{Mesh, Scene};

use crate::pipeline::PreviewRenderer;

/// Renders `preview.png` (a photo view from above the door side) and `preview_top.png` (a
/// top-down view), anti-aliased by 2× supersampling, with `scenethesis-render`.
#[derive(Debug)]
pub struct WgpuPreviews {
    renderer: Renderer,
}

impl WgpuPreviews {
    /// Opens a renderer on the backend `WGPU_BACKEND` names (or the best available one); fails
    /// when no adapter exists, e.g. on a machine without GPU or Mesa drivers.
    pub fn from_env() -> Result<Self, RenderError> {
        Ok(Self {
            renderer: Renderer::from_env()?,
        })
    }

    /// Wraps an open renderer.
    pub fn new(renderer: Renderer) -> Self {
        Self { renderer }
    }
}

fn png(image: &image::RgbaImage) -> Result<Vec<u8>, String> {
    let mut bytes = Vec::new();
    image
        .write_to(&mut Cursor::new(&mut bytes), image::ImageFormat::Png)
        .map_err(|e| format!("PNG encoding failed: {e}"))?;
    Ok(bytes)
}

impl PreviewRenderer for WgpuPreviews {
    fn name(&self) -> String {
        self.renderer.adapter_description()
    }

    fn render(
        &self,
        scene: &Scene,
        meshes: &BTreeMap<String, Mesh>,
        size: [u32; 2],
    ) -> Result<Vec<(String, Vec<u8>)>, String> {
        let instances = scene
            .objects
            .iter()
            .filter_map(|o| {
                let mesh = meshes.get(&o.id)?;
                Some(Instance::new(o.id.clone(), Arc::new(mesh.clone()), o.pose))
            })
            .collect();
        let render_scene = RenderScene::with_architecture(instances, scene.architecture.clone());
        let prepared = self
            .renderer
            .prepare(&render_scene)
            .map_err(|e| e.to_string())?;
        let [w, h] = size;
        let mut out = Vec::new();
        for (name, camera) in [
            ("preview.png", views::photo_view(&render_scene, w, h)),
            ("preview_top.png", views::top_view(&render_scene, h, h)),
        ] {
            let image = self
                .renderer
                .render_color_supersampled(&prepared, &camera, 2)
                .map_err(|e| e.to_string())?;
            out.push((name.to_owned(), png(&image)?));
        }
        Ok(out)
    }
}
