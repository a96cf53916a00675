use thiserror::Error;

/// Everything that can go wrong while setting up the GPU or rendering a frame.
#[derive(Debug, Error)]
pub enum RenderError {
    /// No graphics adapter could be opened for the requested backends.
    #[error(
        "no graphics adapter available for backends {backends} ({reason}); install a GPU driver, \
         or Mesa's software drivers for headless rendering (Debian: `libegl1 libegl-mesa0 \
         libgl1-mesa-dri libgbm1` for GL llvmpipe, `libvulkan1 mesa-vulkan-drivers` for Vulkan \
         lavapipe)"
    )]
    NoAdapter {
        /// The backends that were searched, e.g. `gl, vulkan`.
        backends: String,
        /// Why nothing was found.
        reason: String,
    },
    /// The adapter was found but refused to open a device.
    #[error("the {adapter} adapter could not open a device: {source}")]
    Device {
        /// Name and backend of the adapter.
        adapter: String,
        /// The error from wgpu.
        #[source]
        source: wgpu::RequestDeviceError,
    },
    /// A backend name that is not `gl`, `vulkan`, `auto` (or another wgpu backend list).
    #[error("unknown graphics backend `{0}`: expected `auto`, `gl` or `vulkan`")]
    UnknownBackend(String),
    /// The camera's image size is zero or larger than the adapter allows.
    #[error(
        "cannot render a {width}×{height} image: each side must be between 1 and {max} pixels"
    )]
    InvalidSize {
        /// Requested width in pixels.
        width: u32,
        /// Requested height in pixels.
        height: u32,
        /// The adapter's largest texture side.
        max: u32,
    },
    /// The camera has a non-finite position, rotation or intrinsics.
    #[error("the camera has non-finite numbers: {0}")]
    InvalidCamera(String),
    /// An instance carries a non-finite or non-positive pose.
    #[error("instance `{id}` has an invalid pose (scale must be positive, numbers finite)")]
    InvalidPose {
        /// Id of the instance at fault.
        id: String,
    },
    /// Two instances share one id, so the instance image could not tell them apart.
    #[error("two instances share the id `{0}`")]
    DuplicateId(String),
    /// The scene has no object with a mesh, so there is no guidance to render.
    #[error("the scene has no object with a mesh to render guidance of")]
    NoObjects,
    /// Mapping the read-back buffer failed.
    #[error("reading the rendered images back from the GPU failed: {0}")]
    Readback(String),
    /// Encoding an image (PNG) failed.
    #[error("encoding the image failed: {0}")]
    Encode(#[from] image::ImageError),
}
