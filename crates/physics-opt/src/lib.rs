//! Physics-aware pose optimization: refines each object's 5-DoF pose (uniform scale, yaw about
//! +Y, translation) in scene-graph breadth-first order against pose-alignment, SDF collision and
//! stability losses, behind an [`Optimizer`] seam so that solvers can be swapped.
//!
//! For every object — the anchor first, then parents, then children — [`optimize_scene`] runs
//! two stages against a [`scenethesis_sdf::SceneSdf`] of the objects already placed plus the
//! architecture (floor slab and walls):
//!
//! 1. **pose alignment** to the guidance image: 2D pixel and 3D point distances of
//!    [`Correspondence`](scenethesis_correspondence::Correspondence)s under the guide's pinhole
//!    camera ([`PoseAlignment`](scenethesis_correspondence::PoseAlignment): the correspond
//!    stage's loss, which `scenethesis-correspondence` holds with the pose parameters and the
//!    damped least-squares step both stages take); an object the image placed off its surface
//!    support then rests on it by a change of scale that keeps its top where the image shows
//!    it ([`ObjectProblem::rest_by_scale`]);
//! 2. **physics**: the paper's translation collision loss (penetrating surface points push the
//!    object along point → centroid by their depth), scale collision loss (only when the
//!    penetration forms two or more separate clusters, pulling the scale toward
//!    `(‖u‖ − |d|)/‖u‖` within the asset's scale range) and stability loss
//!    (`Σ 1 − exp(−d²)` over bottom points against the parent's support surface).
//!
//! Two optimizers implement [`Optimizer`]: [`Sgd`], the paper's gradient descent, and
//! [`ProjectedGaussNewton`], which settles objects on their support in one step and resolves
//! penetration with minimum-norm translations (Levenberg–Marquardt for the alignment, the
//! step of [`scenethesis_correspondence::damped`]).
//!
//! Inner loops use baked grid fields; afterwards every object is polished and checked against
//! the exact mesh fields: no pair penetrates more than 1 mm, every resting object's bottom is
//! within 2 mm of its support, every object is inside the room. An object that cannot be made to
//! fit is reported with the reason ([`Issue`]) — which object it collides with and how deep, how
//! far it floats, how far it sticks out — so the judge can re-plan.

#![warn(missing_docs)]

mod carry;
mod contact;
mod driver;
mod finish;
mod footprint;
mod memo;
mod objective;
mod obstacles;
mod optimizer;
mod prepare;
mod projected;
mod report;
pub mod support;
mod verify;

pub use contact::{cluster_contacts, CollisionState, Contact};
pub use driver::{
    architecture_fields, optimize_scene, OptimizeSettings, SceneProblem,
    DEFAULT_OPTIMIZE_BUDGET_SECS,
};
pub use memo::ContactMemo;
pub use objective::{
    LossSettings, Losses, ObjectProblem, RoomBounds, Stage, REST_BY_SCALE_GAP, REST_BY_SCALE_LIMIT,
};
pub use obstacles::Obstacles;
pub use optimizer::{LearningRates, Optimizer, Sgd, StageOutcome};
pub use prepare::{PrepareSettings, PreparedAsset};
pub use projected::ProjectedGaussNewton;
pub use report::{Issue, ObjectReport, OptimizeTimings, Placement};
pub use support::{Support, SupportPlane};
pub use verify::Tolerances;

use scenethesis_scene_graph::{Pose, ValidationError};

/// Errors setting up an optimization. (Objects that cannot be placed are not errors: they are
/// reported in the [`Placement`].)
#[derive(Debug, thiserror::Error)]
pub enum PhysicsOptError {
    /// The scene graph cannot be ordered (unknown parent or a parent cycle).
    #[error("scene graph: {0}")]
    Graph(#[from] ValidationError),
    /// An object has no prepared asset.
    #[error("object `{id}`: no prepared asset was given for it")]
    MissingAsset {
        /// The object.
        id: String,
    },
    /// An object's starting pose is not finite or has a non-positive scale.
    #[error("object `{id}`: starting pose must be finite with positive scale, got {pose:?}")]
    InvalidPose {
        /// The object.
        id: String,
        /// The rejected pose.
        pose: Pose,
    },
    /// An asset's mesh has no vertices or no area to sample.
    #[error("asset `{asset}`: mesh is empty, expected triangles with area")]
    EmptyMesh {
        /// The asset.
        asset: String,
    },
    /// An asset's scale range is not a positive interval.
    #[error("asset `{asset}`: scale range {range:?} must satisfy 0 < min <= max")]
    InvalidScaleRange {
        /// The asset.
        asset: String,
        /// The rejected range.
        range: [f64; 2],
    },
    /// An asset's signed distance field could not be built.
    #[error("asset `{asset}`: {source}")]
    Sdf {
        /// The asset.
        asset: String,
        /// The cause.
        source: scenethesis_sdf::SdfError,
    },
}
