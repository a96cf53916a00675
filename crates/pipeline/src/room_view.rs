//! The empty room of a plan rendered from the photo view (feature `render`): what the vision
//! guide asks an image model to furnish, and whose camera it then lifts the objects with.

use scenethesis_correspondence::RgbImage;
use scenethesis_render::{views, RenderError, RenderScene, Renderer};
use scenethesis_scene_graph::Architecture;
use scenethesis_vision_guide::{RoomRenderer, RoomView};

/// Renders a plan's empty room (floor, walls, door) with the headless wgpu renderer, from the
/// same photo view as `preview.png` and `render DIR --guidance`.
#[derive(Debug)]
pub struct WgpuRoomRenderer {
    renderer: Renderer,
}

impl WgpuRoomRenderer {
    /// Opens a renderer on the backend `WGPU_BACKEND` names (or the best available one).
    pub fn from_env() -> Result<Self, RenderError> {
        Ok(Self {
            renderer: Renderer::from_env()?,
        })
    }
}

impl RoomRenderer for WgpuRoomRenderer {
    fn name(&self) -> String {
        format!("room render ({})", self.renderer.adapter_description())
    }

    fn render_room(&self, architecture: &Architecture, size: [u32; 2]) -> Result<RoomView, String> {
        let scene = RenderScene::with_architecture(Vec::new(), architecture.clone());
        let camera = views::photo_view(&scene, size[0], size[1]);
        let prepared = self.renderer.prepare(&scene).map_err(|e| e.to_string())?;
        let frame = self
            .renderer
            .render_prepared(&prepared, &camera)
            .map_err(|e| e.to_string())?;
        let rgb: Vec<u8> = frame
            .color
            .pixels()
            .flat_map(|p| [p.0[0], p.0[1], p.0[2]])
            .collect();
        let image = RgbImage::new(frame.width(), frame.height(), rgb).map_err(|e| e.to_string())?;
        Ok(RoomView { camera, image })
    }
}
