//! The judge stage of scenethesis as its own crate, below both the pipeline that calls it and
//! any provider crate that implements it (a vision-language judge, say).
//!
//! - [`Judge`] is the seam: it looks at a [`JudgeInput`] (plan, optimized scene, meshes) and
//!   returns a [`Verdict`] whose [`Failure`]s name the objects at fault, so the pipeline can
//!   re-plan.
//! - [`GeometricJudge`] is the offline default: collisions, stability, relations, walkway and
//!   reachability, measured by `scenethesis-eval`.
//! - [`AcceptAll`] measures the same metrics but accepts every scene (no re-planning): the
//!   second implementation that proves the seam, and a way to see a first attempt unjudged.

#![warn(missing_docs)]

mod accept;
mod judge;

pub use accept::AcceptAll;
pub use judge::{
    Failure, FailureKind, GeometricJudge, Judge, JudgeError, JudgeInput, JudgeTimings, Verdict,
};
