//! 2D/3D correspondences between a rendered object and a guidance image, and the guidance data
//! itself: the exchange types between a guide that reads an image (the vision guide) and the
//! pose optimizer that aligns assets to it.
//!
//! - [`Correspondence`]: one matched pair (asset point ↔ target pixel ↔ optional target 3D
//!   point), the unit the pose-alignment loss of `scenethesis-physics-opt` consumes.
//! - [`Guidance`]: what a guide saw — the [`Camera`](scenethesis_scene_graph::Camera), the
//!   colour image ([`RgbImage`]), an optional metric [`DepthMap`] and one [`Mask`] per object id.
//! - [`Matcher`]: the seam that pairs an asset rendered at its current pose ([`RenderedView`])
//!   with its object's guidance region ([`TargetRegion`]); [`lift`] turns the pixel pairs into
//!   [`Correspondence`]s. [`ShapeMatcher`] is the default: silhouette and depth agreement, so
//!   it works when the asset does not look like the photographed object.
//! - [`rasterize`]: a small CPU depth rasterizer of an asset's mesh in a window of the guidance
//!   camera, cheap enough to render every yaw hypothesis of every object.
//!
//! - [`encode_png`]: the one PNG encoder of the workspace, next to the image types.
//!
//! This crate has no GPU, HTTP or model-runtime dependency: renders and model outputs arrive
//! as plain buffers.
//!
//! ```
//! use scenethesis_correspondence::{DepthMap, Mask};
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
//! ```

#![warn(missing_docs)]

mod error;
mod guidance;
mod mask;
mod matcher;
mod pair;
mod png;
mod raster;
pub mod shape;

pub use error::GuidanceError;
pub use guidance::{DepthMap, Guidance, RgbImage};
pub use mask::Mask;
pub use matcher::{lift, MatchKind, Matcher, PixelMatch, TargetRegion};
pub use pair::{Correspondence, PairKind};
pub use png::encode_png;
pub use raster::{projected_bbox, rasterize, rasterize_coarse, RenderedView, Window};
pub use shape::{ShapeMatcher, ShapeScore};
