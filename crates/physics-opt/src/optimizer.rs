//! The optimizer seam and the paper's optimizer: plain (projected) stochastic gradient descent
//! on the weighted losses.

use scenethesis_scene_graph::Pose;
use serde::{Deserialize, Serialize};

use crate::objective::{Losses, ObjectProblem, Stage};
use scenethesis_correspondence::params::{from_vector, to_vector, PoseVector};

/// What one stage of optimizing one object produced.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StageOutcome {
    /// The optimized pose.
    pub pose: Pose,
    /// Iterations used.
    pub iterations: usize,
    /// The loss terms at `pose`.
    pub losses: Losses,
}

/// A solver for one object's 5-DoF pose. The scene driver ([`crate::optimize_scene`]) calls it
/// once per stage and object in breadth-first order; an implementation only sees the object's
/// [`ObjectProblem`] (its geometry, the obstacles placed before it, its support, the room and
/// its correspondences) and must return a pose that respects [`ObjectProblem::project`].
///
/// An optimizer of its own that runs [`Sgd`] and then snaps the yaw to the nearest quarter
/// turn (projected again, so the pose stays feasible), and only separates collisions at the
/// end:
///
/// ```
/// use scenethesis_physics_opt::{ObjectProblem, Optimizer, Sgd, Stage, StageOutcome};
/// use scenethesis_scene_graph::Pose;
///
/// struct QuarterTurns(Sgd);
///
/// impl Optimizer for QuarterTurns {
///     fn name(&self) -> &str {
///         "sgd-quarter-turns"
///     }
///     fn optimize(&self, problem: &ObjectProblem<'_>, stage: Stage, initial: Pose) -> StageOutcome {
///         let mut outcome = self.0.optimize(problem, stage, initial);
///         let quarter = std::f64::consts::FRAC_PI_2;
///         outcome.pose.yaw = (outcome.pose.yaw / quarter).round() * quarter;
///         outcome.pose = problem.project(&outcome.pose);
///         outcome.losses = problem.losses(&outcome.pose, stage);
///         outcome
///     }
///     fn settles(&self) -> bool {
///         false
///     }
/// }
///
/// let optimizer: &dyn Optimizer = &QuarterTurns(Sgd::default());
/// assert_eq!(optimizer.name(), "sgd-quarter-turns");
/// assert!(!optimizer.settles() && Sgd::default().settles());
/// ```
pub trait Optimizer: Send + Sync {
    /// A short name for reports and benchmarks.
    fn name(&self) -> &str;

    /// Runs `stage` for one object from `initial`.
    fn optimize(&self, problem: &ObjectProblem<'_>, stage: Stage, initial: Pose) -> StageOutcome;

    /// Whether the physics stage settles resting objects on their support (the stability
    /// loss); when it does not, the scene driver's final pass only separates collisions.
    fn settles(&self) -> bool {
        true
    }
}

/// Learning rates of the five parameters (scale, yaw, translation).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LearningRates {
    /// Learning rate of the scale.
    pub scale: f64,
    /// Learning rate of the yaw.
    pub yaw: f64,
    /// Learning rate of the translation.
    pub translation: f64,
}

impl LearningRates {
    fn as_vector(&self) -> PoseVector {
        PoseVector::new(
            self.scale,
            self.yaw,
            self.translation,
            self.translation,
            self.translation,
        )
    }
}

/// The paper's optimizer: gradient descent with per-parameter learning rates (optionally with
/// momentum), each step projected back onto the feasible set (scale range, support region,
/// room). Stops early once the object is collision-free and resting within tolerance.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sgd {
    /// Learning rates of stage 1 (pose alignment).
    pub alignment_rates: LearningRates,
    /// Learning rates of stage 2 (collision and stability).
    pub physics_rates: LearningRates,
    /// Momentum factor in [0, 1); the paper uses plain SGD (0).
    pub momentum: f64,
    /// Iteration budget of stage 1.
    pub alignment_iterations: usize,
    /// Iteration budget of stage 2.
    pub physics_iterations: usize,
    /// Stage 1 stops when the step's largest component falls below this.
    pub alignment_tolerance: f64,
    /// Stage 2 stops when the object is collision-free and every stability residual is below
    /// this, in metres.
    pub resting_tolerance: f64,
}

impl Default for Sgd {
    fn default() -> Self {
        Self {
            alignment_rates: LearningRates {
                scale: 0.3,
                yaw: 0.3,
                translation: 0.3,
            },
            physics_rates: LearningRates {
                scale: 0.5,
                yaw: 0.0,
                translation: 0.5,
            },
            momentum: 0.0,
            alignment_iterations: 400,
            physics_iterations: 300,
            alignment_tolerance: 1e-6,
            resting_tolerance: 2.5e-4,
        }
    }
}

impl Optimizer for Sgd {
    fn name(&self) -> &str {
        "sgd"
    }

    fn optimize(&self, problem: &ObjectProblem<'_>, stage: Stage, initial: Pose) -> StageOutcome {
        let (rates, budget) = match stage {
            Stage::Alignment => (self.alignment_rates, self.alignment_iterations),
            Stage::Physics => (self.physics_rates, self.physics_iterations),
        };
        let budget = problem.iteration_budget(budget);
        let rates = rates.as_vector();
        let mut pose = problem.project(&initial);
        let mut velocity = PoseVector::zeros();
        let mut iterations = 0;
        if stage == Stage::Alignment && problem.alignment.is_none() {
            let losses = problem.losses(&pose, stage);
            return StageOutcome {
                pose,
                iterations,
                losses,
            };
        }
        while iterations < budget && !problem.out_of_time() {
            let (_, grad, state) = problem.losses_gradient_and_state(&pose, stage);
            let settled = state.is_some_and(|s| s.is_free())
                && lowest_residual(&problem.stability_residuals(&pose))
                    .is_none_or(|r| r.abs() <= self.resting_tolerance);
            if stage == Stage::Physics && settled {
                break;
            }
            iterations += 1;
            velocity = velocity * self.momentum - rates.component_mul(&grad);
            let next = problem.project(&from_vector(&(to_vector(&pose) + velocity)));
            let moved = (to_vector(&next) - to_vector(&pose)).amax();
            pose = next;
            if stage == Stage::Alignment && moved < self.alignment_tolerance {
                break;
            }
        }
        StageOutcome {
            pose,
            iterations,
            losses: problem.losses(&pose, stage),
        }
    }
}

/// The smallest stability residual (the lowest bottom point's gap minus the clearance), if any.
pub(crate) fn lowest_residual(residuals: &[(f64, f64)]) -> Option<f64> {
    residuals.iter().map(|(r, _)| *r).reduce(f64::min)
}
