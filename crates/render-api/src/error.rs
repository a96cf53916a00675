//! What can go wrong behind the renderer seam.

use crate::ViewKind;

/// A cause a renderer reports, of whatever type its backend has.
pub type Cause = Box<dyn std::error::Error + Send + Sync>;

/// Why a [`SceneRenderer`](crate::SceneRenderer) drew no image, naming the renderer and the
/// view at fault.
#[derive(Debug, thiserror::Error)]
pub enum RendererError {
    /// The renderer could not take the scene (e.g. a pose or geometry it refuses, or a device
    /// it lost while uploading).
    #[error("renderer `{renderer}` cannot take the scene: {source}")]
    Scene {
        /// The renderer's name.
        renderer: String,
        /// The backend's error.
        #[source]
        source: Cause,
    },
    /// One view failed.
    #[error("renderer `{renderer}` cannot draw the {view} view at {}×{} pixels: {source}", .size[0], .size[1])]
    View {
        /// The renderer's name.
        renderer: String,
        /// The view asked for.
        view: ViewKind,
        /// Its size in pixels.
        size: [u32; 2],
        /// The backend's error.
        #[source]
        source: Cause,
    },
    /// The renderer answered with another number of images than views were asked for.
    #[error("renderer `{renderer}` drew {drawn} image(s) for {asked} requested view(s)")]
    ViewCount {
        /// The renderer's name.
        renderer: String,
        /// Views asked for.
        asked: usize,
        /// Images drawn.
        drawn: usize,
    },
    /// An image (or its camera) came back at another size than asked.
    #[error("renderer `{renderer}` drew the {view} view at {}×{} pixels; {}×{} were asked for", .drawn[0], .drawn[1], .asked[0], .asked[1])]
    ViewSize {
        /// The renderer's name.
        renderer: String,
        /// The view.
        view: ViewKind,
        /// The size asked for.
        asked: [u32; 2],
        /// The size of the image drawn.
        drawn: [u32; 2],
    },
    /// A rendered image could not be encoded as PNG.
    #[error("cannot encode {file} as PNG: {source}")]
    Png {
        /// The file name of the image.
        file: String,
        /// The encoder's error.
        #[source]
        source: image::ImageError,
    },
}
