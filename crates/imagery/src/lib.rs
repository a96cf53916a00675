//! The image vocabulary every scenethesis stage shares, at the bottom of the crate graph: the
//! pinhole [`Camera`] with its [`Intrinsics`] (f64, pixels), the colour [`RgbImage`], metric
//! [`DepthMap`]s (metres, in the single precision depth sensors, depth models and the GPU
//! give), binary [`Mask`]s, the [`Guidance`] a guide hands the optimizer
//! (camera, image, optional depth, one mask per object), the one PNG encoder
//! ([`encode_png`]) and the default field of view ([`DEFAULT_VERTICAL_FOV`]).
//!
//! Renderers, model providers (segmenters, depth estimators), the vision lift, the
//! correspondence matchers and the pipeline all speak these types, so an image, depth map or
//! mask crosses a crate boundary as it is, never through a converter. This crate depends on
//! no other scenethesis crate and has no GPU, HTTP or model-runtime dependency.
//!
//! Conventions: pixel (0, 0) is the top-left corner, the centre of the top-left pixel is
//! (0.5, 0.5), `u` grows right and `v` down; the camera frame follows glTF (+X right, +Y up,
//! looking along −Z) and depth is the distance along the optical axis in metres.
//!
//! ```
//! use scenethesis_imagery::nalgebra::{Point3, Vector3};
//! use scenethesis_imagery::{
//!     Camera, DepthMap, Guidance, Intrinsics, Mask, RgbImage, DEFAULT_VERTICAL_FOV,
//! };
//! use std::collections::BTreeMap;
//!
//! let k = Intrinsics::from_vertical_fov(4, 3, DEFAULT_VERTICAL_FOV);
//! let camera = Camera::look_at(k, Point3::new(0.0, 1.5, 3.0), Point3::origin(), Vector3::y());
//!
//! let mut mask = Mask::new(4, 3);
//! mask.set(1, 1, true);
//! mask.set(2, 1, true);
//! assert_eq!(mask.area(), 2);
//! assert_eq!(mask.bounding_box(), Some((1, 1, 3, 2)));
//!
//! let depth = DepthMap::from_fn(4, 3, |x, _| if x == 0 { f32::NAN } else { 2.0 });
//! assert_eq!(depth.get(0, 0), None);
//! assert_eq!(depth.get(1, 2), Some(2.0));
//!
//! let image = RgbImage::new(4, 3, vec![128; 4 * 3 * 3])?;
//! assert_eq!(&image.to_png()[1..4], b"PNG");
//! let masks = BTreeMap::from([("sofa_0".to_owned(), mask)]);
//! let guidance = Guidance::new(camera, image, Some(depth), masks)?;
//!
//! // The pixel a depth sample was read at lifts back to the world point it saw.
//! let seen = guidance.camera.unproject(&nalgebra::Point2::new(1.5, 1.5), 2.0);
//! let back = guidance.camera.project(&seen).unwrap();
//! assert!((back.pixel.x - 1.5).abs() < 1e-9 && (back.depth - 2.0).abs() < 1e-9);
//! # Ok::<(), scenethesis_imagery::GuidanceError>(())
//! ```

#![warn(missing_docs)]

mod camera;
mod error;
mod guidance;
mod mask;
mod png;

pub use camera::{Camera, Intrinsics, Projection, DEFAULT_VERTICAL_FOV};
pub use error::GuidanceError;
pub use guidance::{DepthMap, Guidance, RgbImage};
pub use mask::Mask;
pub use png::encode_png;

/// Re-export of the linear-algebra crate used in this crate's public types.
pub use nalgebra;
