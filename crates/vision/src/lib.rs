//! Lifting a guidance image to 3D: the geometric core of the vision guide.
//!
//! Given the camera a guidance image was taken with, an instance mask per object and either a
//! metric depth map or nothing at all, this crate recovers for every object a gravity-aligned
//! 3D box (centre, size and yaw) and a guess of what supports it. The phases are one module each:
//!
//! 1. [`points`]: mask pixels with valid depth → world points; the largest spatial cluster is
//!    kept and depth outliers are dropped.
//! 2. [`metrology`]: without depth, single-view metrology: an object stands where its mask meets
//!    the floor under the known camera, and its height follows from its top edge.
//! 3. [`footprint`]: the minimum-area rectangle of the points' floor projection gives yaw and
//!    horizontal extent.
//! 4. [`boxes`]: the gravity-aligned box per object ([`LiftedBox`]).
//! 5. [`support`]: support relations, lowest first, from footprint overlap and height gaps;
//!    [`cross_check`](mod@cross_check) reconciles them with the relations a vision-language model states.
//!
//! Everything here is deterministic and free of GPU, HTTP and model runtimes; the model-backed
//! pieces (segmentation, monocular depth) produce the [`Guidance`](scenethesis_imagery::Guidance) this crate reads.
//!
//! ```
//! use nalgebra::{Point3, Vector3};
//! use scenethesis_imagery::{Camera, DepthMap, Guidance, Intrinsics, Mask, RgbImage};
//! use scenethesis_vision::{lift_scene, LiftOptions};
//! use std::collections::BTreeMap;
//!
//! // A camera 1.6 m up, looking at the floor point (0, 0, -3).
//! let k = Intrinsics::from_vertical_fov(64, 48, 1.0);
//! let camera = Camera::look_at(k, Point3::new(0.0, 1.6, 0.0), Point3::new(0.0, 0.0, -3.0), Vector3::y());
//! // Depth of the floor plane y = 0 at every pixel; the mask covers the bottom-centre pixels.
//! let depth = DepthMap::from_fn(64, 48, |u, v| {
//!     let ray = camera.unproject(&nalgebra::Point2::new(u as f64 + 0.5, v as f64 + 0.5), 1.0);
//!     let dy = ray.y - 1.6;
//!     if dy < 0.0 { (1.6 / -dy) as f32 } else { f32::NAN }
//! });
//! let mut mask = Mask::new(64, 48);
//! for v in 36..48 { for u in 24..40 { mask.set(u, v, true); } }
//! let image = RgbImage::new(64, 48, vec![128; 64 * 48 * 3]).unwrap();
//! let guidance = Guidance::new(camera, image, Some(depth), BTreeMap::from([("rug_0".to_string(), mask)])).unwrap();
//! let lifted = lift_scene(&guidance, &LiftOptions::default()).unwrap();
//! let rug = &lifted.boxes[0];
//! assert_eq!(rug.id, "rug_0");
//! assert!(rug.center.y.abs() < 0.05, "a patch of floor lifts to a flat box on the floor");
//! ```
#![warn(missing_docs)]

pub mod boxes;
pub mod cross_check;
mod error;
pub mod files;
pub mod footprint;
mod lifted_box;
pub mod metrology;
pub mod points;
pub mod support;

pub use boxes::{lift_scene, LiftOptions, LiftedBox, LiftedScene};
pub use cross_check::{cross_check, Decision, Evidence, SupportCheck};
pub use error::LiftError;
pub use footprint::{min_area_rectangle, FloorRectangle};
pub use support::{
    infer_supports, infer_supports_within, mount_on_walls, prefer_tiers, SupportGuess, SupportKind,
    MOUNT_MIN_BOTTOM, MOUNT_WALL_REACH,
};
