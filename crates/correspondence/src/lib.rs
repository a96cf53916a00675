//! The correspond stage (method step 4a): every retrieved asset aligned to the guidance image
//! (the [`Guidance`](scenethesis_imagery::Guidance) of `scenethesis-imagery`, which holds the
//! image types) through 2D/3D correspondences, and a 5-DoF pose (scale, yaw, translation)
//! fitted per object. The whole stage lives here, one module per concept:
//!
//! - [`Correspondence`] (`pair`): one matched pair (asset point ↔ target pixel ↔ optional
//!   target 3D point), the unit the pose-alignment loss consumes.
//! - [`Matcher`] (`matcher`): the seam that pairs an asset rendered at its current pose
//!   ([`RenderedView`]) with its object's guidance region ([`TargetRegion`]); [`lift`] turns
//!   the pixel pairs into [`Correspondence`]s. [`ShapeMatcher`] ([`shape`]) is the default:
//!   silhouette and depth agreement, so it works when the asset does not look like the
//!   photographed object.
//! - [`rasterize`] (`raster`): a small CPU depth rasterizer of an asset's mesh in a window of
//!   the guidance camera, cheap enough to render every yaw hypothesis of every object.
//! - [`PoseAlignment`] (`alignment`): the alignment loss (2D pixel and 3D point distances
//!   under the guide's pinhole camera) and its robust fit, over the five pose parameters of
//!   [`params`], by the one damped least-squares step of [`damped`]. The physics optimizer of
//!   `scenethesis-physics-opt` takes the same loss as its alignment stage and the same step,
//!   the same parameters and the same [`deadline`]s, from here.
//! - [`align_to_guidance`] (`guided`): one object — yaw hypotheses ranked by shape, then
//!   rounds of render → match → lift → fit, within a time budget ([`GuidedSettings`]); the
//!   fitted pose replaces the starting one (the raw lift) only when it agrees with the image
//!   at least as well by the stage's own measures (shape score, match residual), else the
//!   start is kept with the reason ([`GuidedPose::kept_start`], [`KeptLift`]).
//! - [`correspond`] (`stage`): every object of a scene, in parallel, with the plan's facing
//!   hints ([`facing_hint`]).
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

mod alignment;
pub mod damped;
pub mod deadline;
mod guided;
mod matcher;
mod pair;
pub mod params;
mod raster;
pub mod shape;
mod stage;

pub use alignment::{FitOptions, PoseAlignment, ScalePrior};
pub use guided::{align_to_guidance, GuidedPose, GuidedSettings, DEFAULT_TIME_BUDGET_SECS};
pub use matcher::{lift, MatchKind, Matcher, PixelMatch, TargetRegion};
pub use pair::{Correspondence, PairKind};
pub use raster::{
    projected_bbox, rasterize, rasterize_coarse, rasterized_guidance, RenderedView, Window,
};
pub use shape::{ShapeMatcher, ShapeScore};
pub use stage::{correspond, facing_hint, kept_lift, KeptLift};
