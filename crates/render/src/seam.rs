//! The renderer seam of `scenethesis-render-api`, implemented by the wgpu [`Renderer`].

use std::collections::BTreeMap;

use scenethesis_imagery::Camera;
use scenethesis_render_api::{RendererError, SceneRenderer, ViewImage, ViewKind, ViewRequest};
use scenethesis_scene_graph::{Mesh, Scene};

use crate::{labels, views, RenderScene, Renderer};

/// The camera of a standard view of `scene` at `size`.
pub fn view_camera(scene: &RenderScene, kind: ViewKind, size: [u32; 2]) -> Camera {
    let [w, h] = size;
    match kind {
        ViewKind::Photo => views::photo_view(scene, w, h),
        ViewKind::Top => views::top_view(scene, w, h),
    }
}

impl SceneRenderer for Renderer {
    /// The graphics adapter's description.
    fn name(&self) -> String {
        self.adapter_description()
    }

    /// Uploads the scene once ([`RenderScene::from_scene`]), then draws each view from its
    /// preset camera ([`views`]), supersampled as asked; a house's top view is labelled with
    /// its rooms' ids ([`labels::label_rooms`]), a plan of it.
    fn render_views(
        &self,
        scene: &Scene,
        meshes: &BTreeMap<String, Mesh>,
        requests: &[ViewRequest],
    ) -> Result<Vec<ViewImage>, RendererError> {
        let render_scene = RenderScene::from_scene(scene, meshes);
        let prepared = self
            .prepare(&render_scene)
            .map_err(|e| RendererError::Scene {
                renderer: self.name(),
                source: Box::new(e),
            })?;
        requests
            .iter()
            .map(|request| {
                let camera = view_camera(&render_scene, request.kind, request.size);
                let mut color = self
                    .render_color_supersampled(&prepared, &camera, request.supersample)
                    .map_err(|e| RendererError::View {
                        renderer: self.name(),
                        view: request.kind,
                        size: request.size,
                        source: Box::new(e),
                    })?;
                if request.kind == ViewKind::Top {
                    labels::label_rooms(&mut color, &camera, &scene.architecture);
                }
                Ok(ViewImage { camera, color })
            })
            .collect()
    }
}
