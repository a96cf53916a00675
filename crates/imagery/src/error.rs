//! The error of inconsistent image data: buffer sizes, image sizes against the camera, depth values.

/// Why guidance data is inconsistent.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GuidanceError {
    /// A buffer's length does not match its stated size.
    #[error("{what}: {len} values for a {width} × {height} image (expected {expected})")]
    BufferSize {
        /// Which buffer ("image", "depth", "mask of `sofa_0`", …).
        what: String,
        /// Stated width in pixels.
        width: u32,
        /// Stated height in pixels.
        height: u32,
        /// Values given.
        len: usize,
        /// Values expected.
        expected: usize,
    },
    /// An image's size differs from the camera's.
    #[error(
        "{what} is {width} × {height} but the camera's image is {camera_width} × {camera_height}"
    )]
    SizeMismatch {
        /// Which image.
        what: String,
        /// Its width.
        width: u32,
        /// Its height.
        height: u32,
        /// The camera's width.
        camera_width: u32,
        /// The camera's height.
        camera_height: u32,
    },
    /// A depth value is negative or infinite (unknown depth is `NaN` or `0`).
    #[error("depth at pixel ({x}, {y}) is {value}: expected a finite distance ≥ 0 in metres (NaN or 0 = unknown)")]
    BadDepth {
        /// Column.
        x: u32,
        /// Row.
        y: u32,
        /// The offending value.
        value: f32,
    },
}
