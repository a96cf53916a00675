//! Guidance rendered from a scene: what the vision path reads from a photo (colour, metric
//! depth, one mask per object and the camera), drawn from the scene itself, for `render
//! --guidance` and for the round-trip experiments that measure the vision path against
//! ground truth.

use std::collections::BTreeMap;

use scenethesis_imagery::{Camera, Guidance, Mask, RgbImage};
use scenethesis_render_api::ViewKind;
use scenethesis_scene_graph::{Mesh, Scene};

use crate::{view_camera, Frame, RenderError, RenderScene, Renderer};

impl Renderer {
    /// Renders the photo view of `scene` at `size` as guidance: the colour image, metric depth
    /// (architecture included, `0` for background) and one visible mask per object, keyed by
    /// object id (an object hidden from the view gets an empty mask).
    pub fn render_guidance(
        &self,
        scene: &Scene,
        meshes: &BTreeMap<String, Mesh>,
        size: [u32; 2],
    ) -> Result<Guidance, RenderError> {
        let rs = RenderScene::from_scene(scene, meshes);
        if rs.instances.is_empty() {
            return Err(RenderError::NoObjects);
        }
        let camera = view_camera(&rs, ViewKind::Photo, size);
        let prepared = self.prepare(&rs)?;
        let frame = self.render_prepared(&prepared, &camera)?;
        Ok(guidance_from_frame(scene, &frame, camera))
    }
}

/// The guidance a rendered frame holds: its colour, its depth and each object's mask.
fn guidance_from_frame(scene: &Scene, frame: &Frame, camera: Camera) -> Guidance {
    let (w, h) = (frame.width(), frame.height());
    let image = RgbImage::from_rgba(&frame.color);
    let depth = frame.depth.clone();
    let mut masks = BTreeMap::new();
    for object in &scene.objects {
        let mut mask = Mask::new(w, h);
        if let Some(index) = frame.index_of(&object.id) {
            for (i, &v) in frame.instance.iter().enumerate() {
                if v == index {
                    mask.set(i as u32 % w, i as u32 / w, true);
                }
            }
        }
        masks.insert(object.id.clone(), mask);
    }
    Guidance::new(camera, image, Some(depth), masks).expect("all images share the frame size")
}
