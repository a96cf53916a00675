//! The renderer seam: what the stages that look at a scene ask of a renderer, with no GPU
//! dependency.
//!
//! [`SceneRenderer`] draws a [`Scene`]'s objects (each with its asset-frame [`Mesh`], by object
//! id) inside its architecture, from standard views ([`ViewKind`]) at a requested size, and
//! hands back each image with the [`Camera`] it was taken with. Failures are
//! [`RendererError`]s naming the renderer and the view at fault.
//!
//! `scenethesis-render` implements it with headless wgpu. Its users sit on floors of their own:
//! the pipeline's previews, the vision guide's empty-room render, the VLM judge of
//! `scenethesis-language` and the Python package. The trait lives in this small crate, below all
//! of them and beside the GPU crate rather than in it, so that none of its users compiles wgpu to
//! name it (the language crate in particular sits below the pipeline and stays free of it), and
//! so that tests hand any stage a CPU renderer of their own.
//!
//! The preview set of an output folder — [`PREVIEW_FILES`], their views and supersampling —
//! is defined once here too ([`render_previews`]), because both the pipeline and the VLM judge
//! draw it.
//!
//! ```
//! use std::collections::BTreeMap;
//! use scenethesis_render_api::{render_view, RendererError, SceneRenderer, ViewImage, ViewKind, ViewRequest};
//! use scenethesis_imagery::{Camera, Intrinsics};
//! use scenethesis_scene_graph::{Architecture, Mesh, Scene};
//!
//! /// Draws every view as one flat grey, from a camera two metres up.
//! struct Grey;
//!
//! impl SceneRenderer for Grey {
//!     fn name(&self) -> String {
//!         "grey".into()
//!     }
//!     fn render_views(
//!         &self,
//!         _: &Scene,
//!         _: &BTreeMap<String, Mesh>,
//!         views: &[ViewRequest],
//!     ) -> Result<Vec<ViewImage>, RendererError> {
//!         Ok(views
//!             .iter()
//!             .map(|v| {
//!                 let [w, h] = v.size;
//!                 let k = Intrinsics::from_vertical_fov(w, h, 0.9);
//!                 let camera = Camera::look_at(
//!                     k,
//!                     [0.0, 2.0, 3.0].into(),
//!                     [0.0, 0.0, 0.0].into(),
//!                     nalgebra::Vector3::y(),
//!                 );
//!                 let color = image::RgbaImage::from_pixel(w, h, image::Rgba([128, 128, 128, 255]));
//!                 ViewImage { camera, color }
//!             })
//!             .collect())
//!     }
//! }
//!
//! let room = Scene::new(Architecture::rectangular_room(4.0, 3.0, 2.5, 0.9));
//! let view = render_view(&Grey, &room, &BTreeMap::new(), ViewRequest::new(ViewKind::Photo, [64, 48]))?;
//! assert_eq!(view.color.dimensions(), (64, 48));
//! # Ok::<(), RendererError>(())
//! ```
#![warn(missing_docs)]

mod error;
mod previews;

use std::collections::BTreeMap;
use std::fmt;

use scenethesis_imagery::Camera;
use scenethesis_scene_graph::{Mesh, Scene};

pub use error::RendererError;
pub use previews::{preview_views, render_previews, PREVIEW_FILES, PREVIEW_SUPERSAMPLE};

/// A standard view of a scene; the renderer places the camera from the scene's extent, so
/// every renderer frames a scene the same way for the same kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ViewKind {
    /// The three-quarter "photo" view, like an interior photograph from the front right and
    /// above (the view of `preview.png` and of the vision guide's empty room).
    Photo,
    /// Straight down onto the scene, the back (−Z) at the top of the image.
    Top,
}

impl fmt::Display for ViewKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Photo => "photo",
            Self::Top => "top",
        })
    }
}

/// One image asked of a renderer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ViewRequest {
    /// Where the camera stands.
    pub kind: ViewKind,
    /// Width and height of the image in pixels.
    pub size: [u32; 2],
    /// Draw at this many times the size per side and average down (anti-aliasing); `1` is a
    /// plain render.
    pub supersample: u32,
}

impl ViewRequest {
    /// A plain (not supersampled) view of `kind` at `size` pixels.
    pub fn new(kind: ViewKind, size: [u32; 2]) -> Self {
        Self {
            kind,
            size,
            supersample: 1,
        }
    }

    /// The same view drawn at `factor` × its size per side and averaged down.
    pub fn supersampled(self, factor: u32) -> Self {
        Self {
            supersample: factor,
            ..self
        }
    }
}

/// One rendered view: the image and the camera it was taken with.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewImage {
    /// The camera, its intrinsics the requested size.
    pub camera: Camera,
    /// sRGB colour, opaque, the requested size.
    pub color: image::RgbaImage,
}

/// Renders scenes: a scene's objects, each with its asset-frame mesh, inside its architecture
/// (floor, walls, door openings), from standard views.
pub trait SceneRenderer: Send + Sync {
    /// A short name (e.g. the graphics adapter) for reports and errors.
    fn name(&self) -> String;

    /// Draws `scene` once per request, in the order asked. `meshes` holds each object's mesh
    /// in its asset frame by object id; an object without one is not drawn. Callers go through
    /// [`render_view`] or [`render_previews`], which check the answer's count and sizes.
    fn render_views(
        &self,
        scene: &Scene,
        meshes: &BTreeMap<String, Mesh>,
        views: &[ViewRequest],
    ) -> Result<Vec<ViewImage>, RendererError>;
}

/// Draws `views` with `renderer` and checks that every requested view came back at its size.
pub fn render_checked(
    renderer: &dyn SceneRenderer,
    scene: &Scene,
    meshes: &BTreeMap<String, Mesh>,
    views: &[ViewRequest],
) -> Result<Vec<ViewImage>, RendererError> {
    let images = renderer.render_views(scene, meshes, views)?;
    if images.len() != views.len() {
        return Err(RendererError::ViewCount {
            renderer: renderer.name(),
            asked: views.len(),
            drawn: images.len(),
        });
    }
    for (request, image) in views.iter().zip(&images) {
        let drawn = [image.color.width(), image.color.height()];
        let k = image.camera.intrinsics;
        if drawn != request.size || [k.width, k.height] != request.size {
            return Err(RendererError::ViewSize {
                renderer: renderer.name(),
                view: request.kind,
                asked: request.size,
                drawn,
            });
        }
    }
    Ok(images)
}

/// Draws one view of `scene` with `renderer`, checked like [`render_checked`].
pub fn render_view(
    renderer: &dyn SceneRenderer,
    scene: &Scene,
    meshes: &BTreeMap<String, Mesh>,
    request: ViewRequest,
) -> Result<ViewImage, RendererError> {
    let mut images = render_checked(renderer, scene, meshes, &[request])?;
    Ok(images.remove(0))
}
