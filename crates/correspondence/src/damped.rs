//! One damped least-squares (Levenberg–Marquardt) step over the five pose parameters: the
//! step both the alignment fit ([`crate::PoseAlignment::fit`], robust reweighting) and the
//! alignment stage of the physics optimizer (`scenethesis_physics_opt::ProjectedGaussNewton`)
//! take, each with its own residuals, projection and number of tries. It lives here, with the
//! alignment loss, because the optimizer sits above this crate and imports it.

use nalgebra::Matrix5;
use scenethesis_scene_graph::Pose;

use crate::params::{from_vector, to_vector, PoseVector};

/// The normal equations of one linearisation: `JᵀWJ` and `JᵀWr`.
pub struct NormalEquations {
    /// `JᵀWJ`.
    pub jtj: Matrix5<f64>,
    /// `JᵀWr`.
    pub jtr: PoseVector,
}

impl NormalEquations {
    /// Sums the rows of `jacobian` against `residuals`, each weighted by `weights` when given.
    pub fn of(residuals: &[f64], jacobian: &[PoseVector], weights: Option<&[f64]>) -> Self {
        let mut jtj = Matrix5::<f64>::zeros();
        let mut jtr = PoseVector::zeros();
        match weights {
            Some(weights) => {
                for ((ri, row), w) in residuals.iter().zip(jacobian).zip(weights) {
                    jtj += row * row.transpose() * *w;
                    jtr += row * (*ri * *w);
                }
            }
            None => {
                for (ri, row) in residuals.iter().zip(jacobian) {
                    jtj += row * row.transpose();
                    jtr += row * *ri;
                }
            }
        }
        Self { jtj, jtr }
    }
}

/// An accepted step: the new pose, its cost, and whether it moved at all (by more than 1e-9
/// in some parameter).
pub struct Step {
    /// The new pose.
    pub pose: Pose,
    /// Its cost.
    pub cost: f64,
    /// Whether it moved by more than 1e-9 in some parameter.
    pub moved: bool,
}

/// Solves the damped normal equations from `pose` (of cost `cost`) up to `tries` times,
/// raising the damping `lambda` until a step, once `project`ed, lowers `cost_of`; lowers the
/// damping again after a success. `None` when no try lowered the cost.
pub fn damped_step(
    normal: &NormalEquations,
    pose: &Pose,
    cost: f64,
    lambda: &mut f64,
    tries: usize,
    project: impl Fn(Pose) -> Pose,
    cost_of: impl Fn(&Pose) -> f64,
) -> Option<Step> {
    for _ in 0..tries {
        let mut a = normal.jtj;
        for k in 0..5 {
            a[(k, k)] += *lambda * normal.jtj[(k, k)].max(1e-9) + 1e-12;
        }
        let Some(chol) = a.cholesky() else {
            *lambda *= 10.0;
            continue;
        };
        let step = chol.solve(&(-normal.jtr));
        let candidate = project(from_vector(&(to_vector(pose) + step)));
        let c = cost_of(&candidate);
        if c < cost {
            let moved = (to_vector(&candidate) - to_vector(pose)).amax() > 1e-9;
            *lambda = (*lambda / 3.0).max(1e-9);
            return Some(Step {
                pose: candidate,
                cost: c,
                moved,
            });
        }
        *lambda *= 4.0;
    }
    None
}

/// Moves `pose` and `cost` to an accepted `step`; whether the iteration goes on (a step was
/// accepted and it moved).
pub fn take(step: Option<Step>, pose: &mut Pose, cost: &mut f64) -> bool {
    match step {
        Some(step) => {
            *pose = step.pose;
            *cost = step.cost;
            step.moved
        }
        None => false,
    }
}
