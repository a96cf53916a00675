//! What the optimization produced: the poses and, per object, what was done and whether it
//! meets the physical post-conditions — and if not, which object or surface is at fault.

use std::fmt;

use scenethesis_scene_graph::{Pose, Scene};
use serde::{Deserialize, Serialize};

use crate::support::Support;

/// A post-condition an object misses after optimization (checked on exact distance fields).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Issue {
    /// The object penetrates another object or the architecture by more than the tolerance.
    Collision {
        /// Id of the other object, wall or floor.
        with: String,
        /// Penetration depth in metres.
        depth: f64,
    },
    /// The object's bottom hangs above its support by more than the tolerance.
    Floating {
        /// Id of what it should rest on.
        support: String,
        /// The gap in metres.
        gap: f64,
    },
    /// The object's centre of mass is not over its support region, so it would topple.
    OffSupport {
        /// Id of what it should rest on.
        support: String,
        /// Horizontal distance from the centroid to the region, metres.
        distance: f64,
    },
    /// Part of the object lies outside the floor rectangle.
    OutsideRoom {
        /// How far it sticks out, metres.
        overhang: f64,
    },
}

impl fmt::Display for Issue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Issue::Collision { with, depth } => {
                write!(f, "penetrates `{with}` by {:.1} mm", depth * 1000.0)
            }
            Issue::Floating { support, gap } => {
                write!(f, "floats {:.1} mm above `{support}`", gap * 1000.0)
            }
            Issue::OffSupport { support, distance } => write!(
                f,
                "centre of mass {:.1} mm outside the support region of `{support}`",
                distance * 1000.0
            ),
            Issue::OutsideRoom { overhang } => {
                write!(f, "sticks {:.1} mm out of the room", overhang * 1000.0)
            }
        }
    }
}

/// The outcome for one object.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ObjectReport {
    /// The object's id.
    pub id: String,
    /// Its pose before optimization (as given by the guide).
    pub initial_pose: Pose,
    /// Its optimized pose.
    pub pose: Pose,
    /// What it rests on.
    pub support: Support,
    /// Iterations of the alignment stage.
    pub alignment_iterations: usize,
    /// Iterations of the physics stage (including the exact-field polish, if it ran).
    pub physics_iterations: usize,
    /// Whether a polish against the exact distance fields was needed after the grid stage.
    pub polished: bool,
    /// The deepest penetration into or by any other object or the architecture, metres.
    pub penetration: f64,
    /// The gap between its bottom and its support (negative when sunk), if it rests on one.
    pub support_gap: Option<f64>,
    /// Missed post-conditions; empty when the object is placed correctly.
    pub issues: Vec<Issue>,
}

impl ObjectReport {
    /// Whether every post-condition holds.
    pub fn is_ok(&self) -> bool {
        self.issues.is_empty()
    }
}

impl fmt::Display for ObjectReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.issues.is_empty() {
            return write!(f, "`{}`: ok", self.id);
        }
        write!(f, "`{}`: ", self.id)?;
        for (i, issue) in self.issues.iter().enumerate() {
            if i > 0 {
                f.write_str("; ")?;
            }
            write!(f, "{issue}")?;
        }
        Ok(())
    }
}

/// The optimized layout of a scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Placement {
    /// Name of the optimizer used.
    pub optimizer: String,
    /// One report per object, in placement (breadth-first) order.
    pub objects: Vec<ObjectReport>,
    /// Whether the stage's time budget ([`crate::OptimizeSettings::time_budget`]) ran out
    /// before its work was done: objects not reached kept their starting poses, the others
    /// the poses reached, and the post-conditions were checked on those (absent when false).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub out_of_time: bool,
    /// How long the parts of the optimization took. Wall-clock, so the one non-deterministic
    /// part of a placement: never serialized.
    #[serde(skip)]
    pub timings: OptimizeTimings,
}

/// Wall-clock seconds the parts of [`crate::optimize_scene`] took.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct OptimizeTimings {
    /// The breadth-first sweep: every object aligned, settled and polished in turn.
    pub sweep: f64,
    /// The final separation pass over the objects that still missed a post-condition
    /// (0 when skipped).
    pub final_pass: f64,
    /// The post-condition check on the exact fields, when the final pass did not already make
    /// it on the final poses.
    pub check: f64,
}

impl OptimizeTimings {
    /// Every part as `(name, seconds)`, in the order `report.json` lists them.
    pub fn parts(&self) -> [(&'static str, f64); 3] {
        [
            ("sweep", self.sweep),
            ("final-pass", self.final_pass),
            ("check", self.check),
        ]
    }
}

impl Placement {
    /// The report of object `id`.
    pub fn object(&self, id: &str) -> Option<&ObjectReport> {
        self.objects.iter().find(|o| o.id == id)
    }

    /// The optimized pose of object `id`.
    pub fn pose(&self, id: &str) -> Option<&Pose> {
        self.object(id).map(|o| &o.pose)
    }

    /// Whether every object meets every post-condition.
    pub fn is_ok(&self) -> bool {
        self.objects.iter().all(ObjectReport::is_ok)
    }

    /// The objects that miss a post-condition (for the judge to re-plan).
    pub fn failures(&self) -> impl Iterator<Item = &ObjectReport> + '_ {
        self.objects.iter().filter(|o| !o.is_ok())
    }

    /// Writes the optimized poses into `scene` (objects it does not know are left alone).
    pub fn apply_to(&self, scene: &mut Scene) {
        for report in &self.objects {
            if let Some(object) = scene.object_mut(&report.id) {
                object.pose = report.pose;
            }
        }
    }
}
