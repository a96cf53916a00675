//! A faster solver for the same objective: Levenberg–Marquardt on the alignment residuals, and
//! for physics a projected Gauss–Newton iteration that settles the object on its support in one
//! step and resolves penetration with the minimum-norm translation satisfying the linearized
//! contact constraints, shrinking the object only when those constraints contradict each other.

use nalgebra::Vector3;
use scenethesis_scene_graph::Pose;
use serde::{Deserialize, Serialize};

use crate::contact::CollisionState;
use crate::objective::{ObjectProblem, Stage};
use crate::optimizer::{lowest_residual, Optimizer, StageOutcome};
use crate::support::{horizontal, Support};
use scenethesis_correspondence::damped::{damped_step, take, NormalEquations};

/// Projected Gauss–Newton / Levenberg–Marquardt solver.
///
/// Physics stage, per iteration:
/// 1. stability: a Gauss–Newton step on the stability residuals along +Y (exact for a flat
///    support surface, where it puts the bottom at the support plus the clearance);
/// 2. collision: every penetrating surface point gives a linear constraint `n·δ ≥ margin − d`
///    on the translation `δ`, with `n` the obstacle's outward gradient (or, where that points
///    away from the object's centroid because the point is deep inside a thin part, the
///    paper's point-to-centroid direction). Resting objects move only horizontally; the
///    minimum-norm `δ` comes from Hildreth's dual coordinate ascent;
/// 3. scale: when the constraints cannot all be met (the penetration forms clusters on
///    opposite sides, or something presses down from above), the object shrinks by the paper's
///    target factor `(‖u‖ − |d|)/‖u‖`, keeping its centroid, within its scale range;
/// 4. projection onto the feasible set (scale range, support region, room).
///
/// Yaw is never changed by physics; only the alignment stage turns objects.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ProjectedGaussNewton {
    /// Iteration budget of the alignment stage.
    pub alignment_iterations: usize,
    /// Iteration budget of the physics stage.
    pub physics_iterations: usize,
    /// Initial Levenberg–Marquardt damping.
    pub damping: f64,
    /// Extra distance added to every contact constraint so that one step clears it, metres.
    pub overshoot: f64,
    /// Contacts whose obstacle normal has a horizontal part shorter than this are treated as
    /// vertical (resolved by settling or shrinking, not by sliding).
    pub min_horizontal_normal: f64,
    /// The physics stage stops when the object is collision-free and its lowest bottom point
    /// is within this of the target clearance, metres.
    pub resting_tolerance: f64,
    /// Settle objects on their support (the stability loss). Off, the physics stage only
    /// resolves collisions, every object by its smallest move (resting objects too may move
    /// vertically): the "+collision" row of the alignment ablation.
    #[serde(default = "yes")]
    pub stability: bool,
}

fn yes() -> bool {
    true
}

impl Default for ProjectedGaussNewton {
    fn default() -> Self {
        Self {
            alignment_iterations: 50,
            physics_iterations: 40,
            damping: 1e-3,
            overshoot: 2.5e-4,
            min_horizontal_normal: 0.3,
            resting_tolerance: 2.5e-4,
            stability: true,
        }
    }
}

impl Optimizer for ProjectedGaussNewton {
    fn name(&self) -> &str {
        "projected-gauss-newton"
    }

    fn settles(&self) -> bool {
        self.stability
    }

    fn optimize(&self, problem: &ObjectProblem<'_>, stage: Stage, initial: Pose) -> StageOutcome {
        let (pose, iterations) = match stage {
            Stage::Alignment => self.align(problem, initial),
            Stage::Physics => self.settle(problem, initial),
        };
        StageOutcome {
            pose,
            iterations,
            losses: problem.losses(&pose, stage),
        }
    }
}

/// A linear constraint `normal · δ ≥ depth` on a translation `δ`.
#[derive(Debug, Clone, Copy)]
struct Constraint {
    normal: Vector3<f64>,
    depth: f64,
}

impl ProjectedGaussNewton {
    /// Levenberg–Marquardt on the pose-alignment residuals.
    fn align(&self, problem: &ObjectProblem<'_>, initial: Pose) -> (Pose, usize) {
        let mut pose = problem.project(&initial);
        let Some(alignment) = problem.alignment else {
            return (pose, 0);
        };
        let mut lambda = self.damping;
        let mut jac = Vec::new();
        let mut iterations = 0;
        let mut cost: f64 = alignment.residuals(&pose, None).iter().map(|r| r * r).sum();
        let budget = problem.iteration_budget(self.alignment_iterations);
        while iterations < budget && !problem.out_of_time() {
            iterations += 1;
            let r = alignment.residuals(&pose, Some(&mut jac));
            let normal = NormalEquations::of(&r, &jac, None);
            let project = |p: Pose| problem.project(&p);
            let cost_of = |p: &Pose| alignment.residuals(p, None).iter().map(|r| r * r).sum();
            let step = damped_step(&normal, &pose, cost, &mut lambda, 12, project, cost_of);
            if !take(step, &mut pose, &mut cost) {
                break;
            }
        }
        (pose, iterations)
    }

    /// The physics iteration described on the type.
    fn settle(&self, problem: &ObjectProblem<'_>, initial: Pose) -> (Pose, usize) {
        let mut pose = problem.project(&initial);
        let resting = !matches!(problem.support, Support::Free);
        let mut iterations = 0;
        let mut started = RecentPoses::default();
        let budget = problem.iteration_budget(self.physics_iterations);
        while iterations < budget && !problem.out_of_time() {
            iterations += 1;
            let left = budget - iterations;
            if let Some(end) = started.cycle_end(&pose, left) {
                return (end, iterations);
            }
            started.push(pose);
            if self.stability {
                pose = self.settle_vertically(problem, pose);
            }
            // Clustered only when the constraints contradict each other (below).
            let mut state = problem.contacts(&pose);
            if state.is_free() && !self.stability {
                break;
            }
            if state.is_free() {
                let rest = lowest_residual(&problem.stability_residuals(&pose));
                if rest.is_none_or(|r| r.abs() <= self.resting_tolerance) {
                    break;
                }
                continue;
            }
            let (constraints, pressing_down) = self.constraints(problem, &pose, &state, resting);
            let (delta, feasible) = solve_min_norm(&constraints);
            let contradictory = !feasible && {
                problem.cluster(&mut state);
                state.clusters.len() > 1
            };
            if contradictory || (constraints.is_empty() && pressing_down.is_some()) {
                let factor = if contradictory {
                    paper_scale_factor(problem, &pose, &state)
                } else {
                    pressing_down.unwrap_or(1.0)
                };
                if let Some(shrunk) = shrink(problem, &pose, factor) {
                    pose = shrunk;
                    continue;
                }
            }
            let step = clamp_norm(delta, 0.5);
            let mut next = pose;
            next.translation += step;
            pose = problem.project(&next);
        }
        (pose, iterations)
    }

    /// One Gauss–Newton step on the stability residuals along +Y (weights `exp(−(r/σ)²)` make
    /// it the step for the paper's `1 − exp(−r²)` loss).
    fn settle_vertically(&self, problem: &ObjectProblem<'_>, mut pose: Pose) -> Pose {
        if let Some(height) = problem.resting_height(&pose) {
            pose.translation.y = height;
            return pose;
        }
        let residuals = problem.stability_residuals(&pose);
        if residuals.is_empty() {
            return pose;
        }
        // Rest on the lowest point: the step that brings it to the target clearance.
        let sigma2 = problem.settings.stability_length.powi(2);
        let (mut num, mut den) = (0.0, 0.0);
        let lowest = lowest_residual(&residuals).unwrap_or(0.0);
        for (r, dr) in &residuals {
            if (r - lowest).abs() > 0.01 {
                continue;
            }
            let w = (-(r * r) / sigma2).exp();
            num += w * r * dr;
            den += w * dr * dr;
        }
        if den > 1e-12 {
            pose.translation.y -= (num / den).clamp(-0.5, 0.5);
        }
        pose
    }

    /// The linearized contact constraints, and for a resting object the scale factor needed
    /// to clear contacts pressing down from above (if any).
    fn constraints(
        &self,
        problem: &ObjectProblem<'_>,
        pose: &Pose,
        state: &CollisionState,
        resting: bool,
    ) -> (Vec<Constraint>, Option<f64>) {
        let centroid = problem.world_centroid(pose);
        let base_y = pose.translation.y + pose.scale * problem.asset.bounds().min.y;
        let mut constraints = Vec::with_capacity(state.contacts.len());
        let mut pressing_down: Option<f64> = None;
        for c in &state.contacts {
            let mut n = c.push;
            let toward_centroid = centroid - c.world;
            if toward_centroid.norm() > 1e-9 && n.dot(&toward_centroid.normalize()) < -0.2 {
                n = toward_centroid.normalize();
            }
            let depth = c.violation + self.overshoot;
            // Without the stability term nothing settles a resting object vertically, so
            // collisions are resolved by the smallest move in any direction (out of the floor
            // or the parent's top is up, not sideways).
            if !resting || !self.stability {
                constraints.push(Constraint { normal: n, depth });
                continue;
            }
            let h = horizontal(&n);
            if h.norm() >= self.min_horizontal_normal {
                constraints.push(Constraint { normal: h, depth });
            } else if n.y < 0.0 {
                let height = (c.world.y - base_y).max(1e-6);
                let factor = ((height - depth) / height).max(0.0);
                pressing_down = Some(pressing_down.map_or(factor, |f: f64| f.min(factor)));
            }
        }
        (constraints, pressing_down)
    }
}

/// The smallest of the paper's per-point target scale factors `(‖u‖ − |d|)/‖u‖`.
fn paper_scale_factor(problem: &ObjectProblem<'_>, pose: &Pose, state: &CollisionState) -> f64 {
    let centroid = problem.world_centroid(pose);
    state
        .contacts
        .iter()
        .map(|c| {
            let arm = horizontal(&(centroid - c.world)).norm().max(1e-6);
            ((arm - c.violation - 2.5e-4) / arm).max(0.0)
        })
        .fold(1.0, f64::min)
}

/// The pose scaled by `factor` about its centroid's vertical axis (the bottom stays on the
/// support), within the scale range; `None` when the scale cannot shrink any further.
fn shrink(problem: &ObjectProblem<'_>, pose: &Pose, factor: f64) -> Option<Pose> {
    let [lo, _] = problem.scale_range();
    let scale = (pose.scale * factor).max(lo);
    if scale >= pose.scale - 1e-9 {
        return None;
    }
    let before = problem.world_centroid(pose);
    let mut next = *pose;
    next.scale = scale;
    let after = problem.world_centroid(&next);
    next.translation.x += before.x - after.x;
    next.translation.z += before.z - after.z;
    Some(problem.project(&next))
}

/// The minimum-norm `δ` with `nᵢ·δ ≥ dᵢ` for every constraint (Hildreth's dual coordinate
/// ascent), and whether the constraints were all met.
fn solve_min_norm(constraints: &[Constraint]) -> (Vector3<f64>, bool) {
    let mut delta = Vector3::zeros();
    if constraints.is_empty() {
        return (delta, true);
    }
    let mut lambda = vec![0.0f64; constraints.len()];
    for _ in 0..200 {
        let mut change = 0.0f64;
        for (c, l) in constraints.iter().zip(lambda.iter_mut()) {
            let nn = c.normal.norm_squared();
            if nn < 1e-12 {
                continue;
            }
            let step = (c.depth - c.normal.dot(&delta)) / nn;
            let next = (*l + step).max(0.0);
            let d = next - *l;
            if d != 0.0 {
                delta += c.normal * d;
                *l = next;
                change = change.max(d.abs() * nn.sqrt());
            }
        }
        if change < 1e-7 {
            break;
        }
    }
    let feasible = constraints
        .iter()
        .all(|c| c.normal.dot(&delta) >= c.depth - 5e-5 || c.normal.norm_squared() < 1e-12);
    (delta, feasible)
}

/// `v` shortened to at most `limit`.
fn clamp_norm(v: Vector3<f64>, limit: f64) -> Vector3<f64> {
    let n = v.norm();
    if n > limit {
        v * (limit / n)
    } else {
        v
    }
}

/// The longest cycle of poses the settle loop recognises.
const LONGEST_CYCLE: usize = 8;

/// The poses that started the settle loop's latest iterations, newest first.
#[derive(Default)]
struct RecentPoses {
    newest_first: std::collections::VecDeque<Pose>,
}

impl RecentPoses {
    /// Remembers the pose that starts an iteration, forgetting what no cycle can reach.
    fn push(&mut self, pose: Pose) {
        self.newest_first.push_front(pose);
        self.newest_first.truncate(LONGEST_CYCLE);
    }

    /// Where the loop ends when `pose`, starting an iteration with `left` more to run after it,
    /// repeats (bit for bit) the pose that started the iteration `p` ago, `p` ≤
    /// [`LONGEST_CYCLE`]. An iteration is a function of the pose that starts it, so from there
    /// on the loop goes round the same `p` poses and would end, `left + 1` steps on, on the one
    /// the remainder of `left + 1` by `p` selects. `None` when `pose` repeats none.
    fn cycle_end(&self, pose: &Pose, left: usize) -> Option<Pose> {
        let key = pose.to_bits();
        let back = self.newest_first.iter().position(|p| p.to_bits() == key)?;
        let period = back + 1;
        // Step `m` (0..period) of the cycle from `pose` is the pose that started the
        // iteration `period − m` ago: newest_first[period − m − 1], and `pose` itself at m = 0.
        let m = (left + 1) % period;
        Some(if m == 0 {
            *pose
        } else {
            self.newest_first[period - m - 1]
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A pose standing for state `k` of a made-up iteration.
    fn state(k: usize) -> Pose {
        Pose::new(1.0, 0.0, Vector3::new(k as f64 * 0.01, 0.0, 0.0))
    }

    /// The last pose of `iterations` steps of `step` from `start`, run out in full or ended
    /// early by [`RecentPoses::cycle_end`], as `settle` does.
    fn run(step: impl Fn(usize) -> usize, iterations: usize, early: bool) -> (Pose, usize) {
        let mut k = 0;
        let mut recent = RecentPoses::default();
        for i in 1..=iterations {
            if early {
                if let Some(end) = recent.cycle_end(&state(k), iterations - i) {
                    return (end, i);
                }
                recent.push(state(k));
            }
            k = step(k);
        }
        (state(k), iterations)
    }

    #[test]
    fn a_cycle_ends_the_settle_loop_on_the_pose_it_would_have_reached() {
        for tail in 0..4 {
            for period in 1..=LONGEST_CYCLE + 2 {
                // States 0..tail lead into the cycle tail..tail + period.
                let step = |k: usize| {
                    if k + 1 < tail + period {
                        k + 1
                    } else {
                        tail
                    }
                };
                for iterations in 1..40 {
                    let (full, _) = run(step, iterations, false);
                    let (early, spent) = run(step, iterations, true);
                    assert_eq!(
                        full, early,
                        "tail {tail}, period {period}, {iterations} iterations"
                    );
                    if period <= LONGEST_CYCLE && iterations > tail + period + 1 {
                        assert!(spent <= tail + period + 1, "spent {spent} of {iterations}");
                    }
                    if period > LONGEST_CYCLE {
                        assert_eq!(spent, iterations);
                    }
                }
            }
        }
    }

    #[test]
    fn min_norm_step_meets_every_constraint_or_reports_contradiction() {
        let cs = [
            Constraint {
                normal: Vector3::x(),
                depth: 0.1,
            },
            Constraint {
                normal: Vector3::new(1.0, 0.0, 1.0).normalize(),
                depth: 0.1,
            },
        ];
        let (d, ok) = solve_min_norm(&cs);
        assert!(ok);
        assert!(
            d.x >= 0.1 - 1e-6 && (d.x + d.z) / 2f64.sqrt() >= 0.1 - 1e-6,
            "{d:?}"
        );
        assert!(d.norm() < 0.1 * 1.1, "not minimal: {d:?}");
        let opposed = [
            Constraint {
                normal: Vector3::x(),
                depth: 0.05,
            },
            Constraint {
                normal: -Vector3::x(),
                depth: 0.05,
            },
        ];
        assert!(!solve_min_norm(&opposed).1);
    }
}
