//! 2D/3D correspondences between a rendered object and a guidance image (the
//! [`Guidance`](scenethesis_imagery::Guidance) of `scenethesis-imagery`, which holds the image
//! types): how the pose optimizer pairs an asset with what the guide saw.
//!
//! - [`Correspondence`]: one matched pair (asset point ↔ target pixel ↔ optional target 3D
//!   point), the unit the pose-alignment loss of `scenethesis-physics-opt` consumes.
//! - [`Matcher`]: the seam that pairs an asset rendered at its current pose ([`RenderedView`])
//!   with its object's guidance region ([`TargetRegion`]); [`lift`] turns the pixel pairs into
//!   [`Correspondence`]s. [`ShapeMatcher`] is the default: silhouette and depth agreement, so
//!   it works when the asset does not look like the photographed object.
//! - [`rasterize`]: a small CPU depth rasterizer of an asset's mesh in a window of the guidance
//!   camera, cheap enough to render every yaw hypothesis of every object.
//!
//! This crate has no GPU, HTTP or model-runtime dependency: renders and model outputs arrive
//! as plain buffers.
//!
//! ```
//! use scenethesis_correspondence::{Correspondence, PairKind};
//! use scenethesis_imagery::nalgebra::{Point2, Point3};
//!
//! let pair = Correspondence {
//!     asset_point: Point3::new(0.1, 0.4, 0.0),
//!     target_pixel: Point2::new(320.5, 200.5),
//!     target_point: Some(Point3::new(1.0, 0.4, -2.0)),
//!     confidence: 0.9,
//!     kind: PairKind::Depth,
//! };
//! assert_eq!(pair.kind, PairKind::Depth);
//! ```

#![warn(missing_docs)]

mod matcher;
mod pair;
mod raster;
pub mod shape;

pub use matcher::{lift, MatchKind, Matcher, PixelMatch, TargetRegion};
pub use pair::{Correspondence, PairKind};
pub use raster::{projected_bbox, rasterize, rasterize_coarse, RenderedView, Window};
pub use shape::{ShapeMatcher, ShapeScore};
