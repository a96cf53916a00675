//! The preview set of an output folder: which views, at what size, under which file names.

use std::collections::BTreeMap;

use scenethesis_imagery::encode_png;
use scenethesis_scene_graph::{Mesh, Scene};

use crate::{render_checked, RendererError, SceneRenderer, ViewKind, ViewRequest};

/// The preview images an output folder may hold, in the order they are drawn and written.
pub const PREVIEW_FILES: [&str; 2] = ["preview.png", "preview_top.png"];

/// Previews are drawn at this many times their size per side and averaged down.
pub const PREVIEW_SUPERSAMPLE: u32 = 2;

/// The views of [`PREVIEW_FILES`] for a preview size `[w, h]`: the photo view at `w × h` and
/// the top view at `h × h` (a square that shows the whole floor plan), both supersampled.
pub fn preview_views(size: [u32; 2]) -> [ViewRequest; 2] {
    let [_, h] = size;
    [
        ViewRequest::new(ViewKind::Photo, size).supersampled(PREVIEW_SUPERSAMPLE),
        ViewRequest::new(ViewKind::Top, [h, h]).supersampled(PREVIEW_SUPERSAMPLE),
    ]
}

/// Draws the previews of `scene` at `size` ([`preview_views`]) with `renderer` and encodes
/// them: file name ([`PREVIEW_FILES`]) and PNG bytes, in that order.
pub fn render_previews(
    renderer: &dyn SceneRenderer,
    scene: &Scene,
    meshes: &BTreeMap<String, Mesh>,
    size: [u32; 2],
) -> Result<Vec<(String, Vec<u8>)>, RendererError> {
    let images = render_checked(renderer, scene, meshes, &preview_views(size))?;
    PREVIEW_FILES
        .iter()
        .zip(images)
        .map(|(file, image)| {
            let png = encode_png(&image.color).map_err(|source| RendererError::Png {
                file: (*file).to_owned(),
                source,
            })?;
            Ok(((*file).to_owned(), png))
        })
        .collect()
}
