//! The final separation pass: after the breadth-first sweep, objects that still miss a
//! post-condition on the exact fields are settled again against *every* other object (not only
//! those placed before them), with the dense check samples the post-conditions use, so that
//! "resolved" means resolved by the same test. Siblings that the sweep wedged into each other
//! (a book between two books, boxes along a rack level) make room in turn; a child that
//! collides with its parent moves, not the parent. A resting object whose centre of mass is
//! not over the part of its footprint that its support holds (a photo frame whose kickstand
//! hangs over a shelf's back edge) is moved inward until it is. A held object that no small
//! move frees from its holder (turned across a shelf's front lip, wedged between the lip and
//! a crate) tries its holder's square turns, in place and a few centimetres inward.

use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::Instant;

use nalgebra::{Point2, Vector2};
use scenethesis_correspondence::shape::turned;
use scenethesis_scene_graph::{convex_hull, yaw_distance, Pose, SceneObject};
use scenethesis_sdf::SignedDistance;

use crate::memo::ContactMemo;
use crate::objective::{LossSettings, ObjectProblem, RoomBounds, Stage};
use crate::obstacles::Obstacles;
use crate::optimizer::Optimizer;
use crate::prepare::PreparedAsset;
use crate::report::Issue;
use crate::support::{Support, SupportPlane};
use crate::verify::{verify, Placed, Tolerances, Verdict};
use scenethesis_correspondence::deadline::past;
use scenethesis_correspondence::params::world_point;

/// Rounds of the pass at most.
const ROUNDS: usize = 8;
/// Bottom samples this close to the asset's lowest point (asset frame) count as feet, metres.
const FOOT_BAND: f64 = 0.003;
/// The centre of mass must lie this far inside the supported feet's hull, metres.
const REST_MARGIN: f64 = 0.004;
/// How far (metres) a held object still pressed into something is moved toward the middle of
/// its support surface for another try.
const HELD_STEPS: [f64; 3] = [0.0, 0.03, 0.08];
/// Inward steps a toppling object takes at most.
const REST_STEPS: usize = 6;
/// Physics iterations a further start (shifted, or turned to its holder's square) may take:
/// a start that frees the object does so within a few (3 to 6 in the vision benchmark's
/// scenes), while one that does not would run the optimizer's whole budget in vain.
const PROBE_ITERATIONS: usize = 12;

/// Everything the pass reads besides the poses it changes.
pub(crate) struct FinishInput<'a> {
    /// Objects in breadth-first order.
    pub order: &'a [&'a SceneObject],
    /// Prepared asset per object, in `order`.
    pub assets: &'a [Arc<PreparedAsset>],
    /// The architecture's fields.
    pub architecture: &'a [(String, Arc<dyn SignedDistance>, Pose)],
    /// The rectangle each object must stay inside, in `order`.
    pub rooms: &'a [RoomBounds],
    /// Loss settings.
    pub losses: &'a LossSettings,
    /// Post-condition tolerances.
    pub tolerances: Tolerances,
    /// Whether resting objects are settled on their support (the optimizer's stability term).
    pub settle: bool,
    /// The stage's deadline: no round, and no object of a round, starts after it.
    pub deadline: Option<Instant>,
}

/// The slack of [`Resettle::acceptable`]'s comparison of scores.
const SCORE_SLACK: f64 = 1e-6;

/// Whether score `s` is better than `was`: no deeper into a holder, and lower in one part by
/// more than [`SCORE_SLACK`].
fn improves(was: Score, s: Score) -> bool {
    s.0 <= was.0 + SCORE_SLACK && (s.0 < was.0 - SCORE_SLACK || s.1 < was.1 - SCORE_SLACK)
}

/// Whether any score [`improves`] on `was` (scores are never negative).
fn could_improve(was: Score) -> bool {
    was.0 > SCORE_SLACK || was.1 > SCORE_SLACK
}

/// What the pass needs to re-resolve an object's support after its parent moved.
pub(crate) type ResolveSupport<'a> = dyn Fn(usize, &Pose, &[Pose]) -> Support + 'a;

/// Runs the pass over `poses` and `supports` (in `input.order`); returns the physics
/// iterations spent per object and, when the last check was made on the final poses, its
/// verdicts (so that the driver need not check again).
pub(crate) fn finish(
    input: &FinishInput<'_>,
    optimizer: &dyn Optimizer,
    resolve: &ResolveSupport<'_>,
    poses: &mut [Pose],
    supports: &mut [Support],
) -> (Vec<usize>, Option<Vec<Verdict>>) {
    let n = input.order.len();
    let mut iterations = vec![0usize; n];
    let tree = Tree::of(input.order);
    let is_ancestor = |a: usize, b: usize| tree.is_ancestor(a, b);
    // The check (and the obstacles' samples) use each asset's dense check points as they
    // are; only an object settled again needs them as its collision samples too.
    let dense = input.assets;
    let mut densified: BTreeMap<usize, Arc<PreparedAsset>> = BTreeMap::new();
    let tol = input.tolerances;
    let mut last = None;
    for _ in 0..ROUNDS {
        if past(input.deadline) {
            break;
        }
        let (todo, verdicts) = pending(
            input,
            dense,
            poses,
            supports,
            &tol,
            &tree.index_of,
            &is_ancestor,
        );
        if todo.is_empty() {
            last = Some(verdicts);
            break;
        }
        let mut moved_any = false;
        for (i, topples) in todo {
            if past(input.deadline) {
                break;
            }
            let others = obstacles_without(input, dense, poses, i, true);
            let asset = densified
                .entry(Arc::as_ptr(&dense[i]) as usize)
                .or_insert_with(|| Arc::new(dense[i].densified()))
                .clone();
            let support = supports[i].clone();
            let memo = ContactMemo::new();
            let problem = ObjectProblem {
                room: Some(input.rooms[i]),
                deadline: input.deadline,
                memo: Some(&memo),
                ..ObjectProblem::new(&input.order[i].id, &asset, &others, &support, input.losses)
            };
            let resettle = Resettle {
                input,
                optimizer,
                tree: &tree,
                problem,
                dense: &dense[i],
                i,
                topples,
            };
            let before = poses[i];
            let (after, spent) = resettle.run(before, poses);
            iterations[i] += spent;
            let Some(after) = after.filter(|after| *after != before) else {
                continue;
            };
            moved_any = true;
            poses[i] = after;
            // Children move with it, and rest on its surfaces where they now are.
            let carried: Vec<usize> = (0..n).filter(|&d| d != i && is_ancestor(i, d)).collect();
            for &d in &carried {
                poses[d] = crate::carry::carry(&before, &after, &poses[d]);
            }
            for &d in &carried {
                supports[d] = resolve(d, &poses[d], poses);
            }
        }
        if !moved_any {
            last = Some(verdicts);
            break;
        }
    }
    (iterations, last)
}

/// The objects' hierarchy, by position in the breadth-first order.
struct Tree<'a> {
    index_of: BTreeMap<&'a str, usize>,
    parent_of: Vec<Option<usize>>,
}

impl<'a> Tree<'a> {
    fn of(order: &'a [&'a SceneObject]) -> Self {
        let index_of: BTreeMap<&str, usize> = order
            .iter()
            .enumerate()
            .map(|(i, o)| (o.id.as_str(), i))
            .collect();
        let parent_of: Vec<Option<usize>> = order
            .iter()
            .map(|o| o.parent.object_id().and_then(|p| index_of.get(p).copied()))
            .collect();
        Self {
            index_of,
            parent_of,
        }
    }

    /// Whether `a` holds `b`, directly or through others.
    fn is_ancestor(&self, a: usize, mut b: usize) -> bool {
        while let Some(p) = self.parent_of[b] {
            if p == a {
                return true;
            }
            b = p;
        }
        false
    }
}

/// A collision score: the deepest contact with what cannot make room (the architecture, the
/// object's holders) and with what can (anything else, moved in its own turn).
type Score = (f64, f64);

/// One object settled again against every other: the starts it tries and the best pose
/// found.
struct Resettle<'a> {
    input: &'a FinishInput<'a>,
    optimizer: &'a dyn Optimizer,
    tree: &'a Tree<'a>,
    problem: ObjectProblem<'a>,
    /// The object's asset with its dense check samples as they are.
    dense: &'a PreparedAsset,
    /// The object's position in the breadth-first order.
    i: usize,
    /// Whether it topples (rather than collides).
    topples: bool,
}

/// The state of one object's attempts: the score and stability it started from, the best
/// pose so far and the physics iterations spent on further starts.
struct Attempts {
    was: Score,
    was_stable: bool,
    best: Option<(Pose, Score)>,
    spent: usize,
    /// Whether a toppling object reached a stable pose clear of its holders (pressing only
    /// into siblings, which make room in their turn).
    rests_clear: bool,
}

impl Resettle<'_> {
    /// Settles the object again from `before`; returns the pose to move it to (if any) and
    /// the physics iterations spent. `poses`: everyone's current poses.
    fn run(&self, before: Pose, poses: &[Pose]) -> (Option<Pose>, usize) {
        let input = self.input;
        let tol = input.tolerances;
        let start = match (self.problem.support, self.topples && input.settle) {
            (Support::Surface(plane), true) => rest_inward(self.dense, plane, &before),
            _ => before,
        };
        let mut attempts = Attempts {
            was: self.score(&before),
            was_stable: self.stable(&before),
            best: None,
            spent: 0,
            rests_clear: false,
        };
        let settles_a_topple = self.topples && input.settle;
        if !(settles_a_topple || could_improve(attempts.was)) {
            // Its own samples touch nothing (the check saw another object's samples in it):
            // no pose can score better, so none would be taken. The other moves in its turn.
            return (None, 0);
        }
        let outcome = self
            .optimizer
            .optimize(&self.problem, Stage::Physics, start);
        let first = self.score(&outcome.pose);
        self.consider(&mut attempts, outcome.pose, first);
        if !self.resolved(first) {
            self.try_shifted_starts(&mut attempts, start, &before);
        }
        // Clear of its holder and pressing only into siblings, it waits for them to make
        // room (next round); still pressed into its holder, it turns.
        if !attempts.rests_clear && !attempts.best.is_some_and(|(_, b)| b.0 <= tol.penetration) {
            if let Some(j) = self.tree.parent_of[self.i] {
                self.try_holder_turns(&mut attempts, start, poses[j].yaw);
            }
        }
        let spent = outcome.iterations + attempts.spent;
        let mut after = attempts.best.map(|(p, _)| p);
        if after.is_none()
            && self.topples
            && input.settle
            && self.stable(&start)
            && start != before
            && only_movable_contacts(&self.problem, &start, &|j| {
                self.tree
                    .index_of
                    .get(j)
                    .is_some_and(|&j| !self.tree.is_ancestor(j, self.i))
            })
        {
            // Resting stably, it presses into a sibling that is free to make room: take
            // the stable pose, and let the sibling move next round.
            after = Some(start);
        }
        (after, spent)
    }

    /// The object's contacts at `p`: (deepest with what holds it, deepest with the rest).
    fn score(&self, p: &Pose) -> Score {
        let others = self.problem.obstacles;
        let (mut fixed, mut movable) = (0.0f64, 0.0f64);
        for c in self
            .problem
            .contacts(p)
            .contacts
            .iter()
            .filter(|c| c.violation > 0.0)
        {
            let id = others.id(c.obstacle);
            let holds = others.is_architecture(c.obstacle)
                || self
                    .tree
                    .index_of
                    .get(id)
                    .is_none_or(|&j| self.tree.is_ancestor(j, self.i));
            if holds {
                fixed = fixed.max(c.violation);
            } else {
                movable = movable.max(c.violation);
            }
        }
        (fixed, movable)
    }

    fn resolved(&self, s: Score) -> bool {
        s.0.max(s.1) <= self.input.tolerances.penetration
    }

    fn stable(&self, p: &Pose) -> bool {
        !self.input.settle
            || self
                .problem
                .support
                .plane()
                .is_none_or(|plane| rests_stably(self.dense, plane, p))
    }

    /// Whether pose `p` scoring `s` may replace the start (for an object that does not
    /// topple, only a score [`could_improve`] on).
    fn acceptable(&self, attempts: &Attempts, p: &Pose, s: Score) -> bool {
        if self.topples && self.input.settle {
            self.stable(p) && self.resolved(s)
        } else {
            // Never trade a collision for a topple, nor press harder into a holder.
            (!attempts.was_stable || self.stable(p)) && improves(attempts.was, s)
        }
    }

    /// Keeps `p` (scoring `s`) when acceptable and better than the best so far.
    fn consider(&self, attempts: &mut Attempts, p: Pose, s: Score) {
        if self.topples && s.0 <= self.input.tolerances.penetration && self.stable(&p) {
            attempts.rests_clear = true;
        }
        if self.acceptable(attempts, &p, s)
            && attempts.best.is_none_or(|(_, b)| {
                (self.resolved(s), -s.0, -s.1) > (self.resolved(b), -b.0, -b.1)
            })
        {
            attempts.best = Some((p, s));
        }
    }

    /// Another start, settled from it for at most [`PROBE_ITERATIONS`], kept if better;
    /// whether the best so far resolves.
    fn settle_from(&self, attempts: &mut Attempts, from: Pose) -> bool {
        let probe = ObjectProblem {
            iteration_limit: Some(PROBE_ITERATIONS),
            ..self.problem
        };
        let o = self.optimizer.optimize(&probe, Stage::Physics, from);
        attempts.spent += o.iterations;
        let s = self.score(&o.pose);
        self.consider(attempts, o.pose, s);
        attempts.best.is_some_and(|(_, b)| self.resolved(b))
    }

    /// The smallest move is blocked: try starts shifted along the object's own axes and the
    /// world's by about the penetration.
    fn try_shifted_starts(&self, attempts: &mut Attempts, start: Pose, before: &Pose) {
        let step = attempts.was.0.max(attempts.was.1) + 0.005;
        let (sin, cos) = before.yaw.sin_cos();
        let axes = [
            Vector2::new(cos, -sin),
            Vector2::new(sin, cos),
            Vector2::new(1.0, 0.0),
            Vector2::new(0.0, 1.0),
        ];
        for axis in axes {
            for sign in [1.0, -1.0] {
                let mut shifted = start;
                shifted.translation.x += sign * step * axis.x;
                shifted.translation.z += sign * step * axis.y;
                if self.settle_from(attempts, shifted) {
                    return;
                }
            }
        }
    }

    /// Still pressed into its holder (or a wall): held things line up with their holder (a
    /// magazine in its pocket, a toy car along a shelf level) and sit inside its surface, not
    /// on its rim. Try the holder's four square turns (the holder turned to `holder_yaw`; the
    /// nearest first) about the object's centre, there and moved a few centimetres toward the
    /// middle of the surface.
    fn try_holder_turns(&self, attempts: &mut Attempts, start: Pose, holder_yaw: f64) {
        let pivot = self.dense.bounds().center();
        let centre = start.transform_point(&pivot);
        let mut yaws: Vec<f64> = (0..4)
            .map(|k| holder_yaw + k as f64 * std::f64::consts::FRAC_PI_2)
            .collect();
        yaws.sort_by(|a, b| yaw_distance(*a, start.yaw).total_cmp(&yaw_distance(*b, start.yaw)));
        yaws.insert(0, start.yaw);
        let inward = self
            .problem
            .support
            .plane()
            .and_then(region_centre)
            .map(|m| m - Vector2::new(centre.x, centre.z))
            .filter(|t| t.norm() > 1e-9)
            .map(|t| t / t.norm());
        let steps: &[f64] = if inward.is_some() {
            &HELD_STEPS
        } else {
            &HELD_STEPS[..1]
        };
        for &step in steps {
            for (k, &yaw) in yaws.iter().enumerate() {
                if step == 0.0 && k == 0 {
                    continue; // the start itself, tried above
                }
                let toward = inward.unwrap_or_else(Vector2::zeros) * step;
                let mut turned = turned(&start, &pivot, yaw);
                turned.translation.x += toward.x;
                turned.translation.z += toward.y;
                // Clear of the holder but pressing into a sibling, the start itself
                // will do: the sibling makes room in its turn.
                let here = self.score(&turned);
                if here.0 <= self.input.tolerances.penetration {
                    self.consider(attempts, turned, here);
                }
                if self.settle_from(attempts, turned) {
                    return;
                }
            }
        }
    }
}

/// The objects that still miss a post-condition the pass can act on, in order, each with
/// whether it is a toppling (rather than colliding) case: colliding objects (of a pair where
/// one holds the other, only the held one), objects whose centre of mass is off their support
/// region, and objects whose centre of mass is not over their supported feet.
fn pending(
    input: &FinishInput<'_>,
    dense: &[Arc<PreparedAsset>],
    poses: &[Pose],
    supports: &[Support],
    tol: &Tolerances,
    index_of: &BTreeMap<&str, usize>,
    is_ancestor: &dyn Fn(usize, usize) -> bool,
) -> (Vec<(usize, bool)>, Vec<Verdict>) {
    // The check reads only the fields, not the obstacles' samples.
    let all = obstacles_without(input, dense, poses, usize::MAX, false);
    let placed: Vec<Placed<'_>> = input
        .order
        .iter()
        .enumerate()
        .map(|(i, o)| Placed {
            id: &o.id,
            asset: &dense[i],
            pose: poses[i],
            support: &supports[i],
            room: input.rooms[i],
        })
        .collect();
    let verdicts = verify(&placed, &all, tol);
    let mut out = Vec::new();
    for (i, v) in verdicts.iter().enumerate() {
        let collides = v.issues.iter().any(|issue| match issue {
            Issue::Collision { with, .. } => match index_of.get(with.as_str()) {
                // The parent (or any holder) stays; the held object moves.
                Some(&j) => !is_ancestor(i, j),
                None => true,
            },
            _ => false,
        });
        let off = input.settle
            && v.issues
                .iter()
                .any(|issue| matches!(issue, Issue::OffSupport { .. }));
        let topples = input.settle
            && !input.order[i].fixed_to_world()
            && supports[i]
                .plane()
                .is_some_and(|plane| !rests_stably(&dense[i], plane, &poses[i]));
        if collides || off || topples {
            out.push((i, (off || topples) && !collides));
        }
    }
    (out, verdicts)
}

/// Whether every contact of the object at `pose` is with an obstacle `movable` accepts (by id).
fn only_movable_contacts(
    problem: &ObjectProblem<'_>,
    pose: &Pose,
    movable: &dyn Fn(&str) -> bool,
) -> bool {
    problem
        .contacts(pose)
        .contacts
        .iter()
        .filter(|c| c.violation > 0.0)
        .all(|c| {
            !problem.obstacles.is_architecture(c.obstacle)
                && movable(problem.obstacles.id(c.obstacle))
        })
}

/// Obstacles of the architecture and every object but `skip`, exact fields with (when
/// `samples`) their dense samples.
fn obstacles_without(
    input: &FinishInput<'_>,
    dense: &[Arc<PreparedAsset>],
    poses: &[Pose],
    skip: usize,
    samples: bool,
) -> Obstacles {
    let mut obstacles = Obstacles::new(true);
    for (id, field, pose) in input.architecture {
        obstacles.insert(id, field.clone(), *pose, true, &[]);
    }
    for (i, object) in input.order.iter().enumerate() {
        if i != skip {
            let asset = &dense[i];
            obstacles.insert(
                &object.id,
                asset.exact_field(),
                poses[i],
                false,
                if samples { asset.check_points() } else { &[] },
            );
        }
    }
    obstacles
}

/// The feet of `asset` at `pose` (its samples within [`FOOT_BAND`] of its lowest point), world
/// (x, z).
fn feet(asset: &PreparedAsset, pose: &Pose) -> Vec<Point2<f64>> {
    let low = asset.bounds().min.y + FOOT_BAND;
    asset
        .check_points()
        .iter()
        .filter(|p| p.y <= low)
        .map(|p| {
            let w = world_point(pose, p);
            Point2::new(w.x, w.z)
        })
        .collect()
}

/// Whether the object's centre of mass is over the hull of the feet its support region holds,
/// with [`REST_MARGIN`]. An asset whose centre of mass is not over its own feet at all is left
/// alone (moving it cannot help).
pub(crate) fn rests_stably(asset: &PreparedAsset, plane: &SupportPlane, pose: &Pose) -> bool {
    let c = world_point(pose, &asset.centroid());
    let c = Point2::new(c.x, c.z);
    let all = feet(asset, pose);
    if plane.region.is_none() || !inside_hull(&all, &c, REST_MARGIN) {
        return true;
    }
    let held: Vec<Point2<f64>> = all
        .into_iter()
        .filter(|f| plane.contains(f.x, f.y))
        .collect();
    inside_hull(&held, &c, REST_MARGIN)
}

/// `pose` moved horizontally, in small steps, so that more of the feet stand on the region,
/// until the object rests stably (or [`REST_STEPS`] are spent).
fn rest_inward(asset: &PreparedAsset, plane: &SupportPlane, pose: &Pose) -> Pose {
    let mut p = *pose;
    for _ in 0..REST_STEPS {
        if rests_stably(asset, plane, &p) {
            break;
        }
        // The foot farthest off the region, brought back onto it (plus the margin).
        let worst = feet(asset, &p)
            .into_iter()
            .map(|f| plane.clamp(f.x, f.y) - f)
            .max_by(|a, b| a.norm().total_cmp(&b.norm()));
        let Some(shift) = worst.filter(|s| s.norm() > 1e-9) else {
            // Every foot is on the region: move the centre of mass inward instead.
            let c = world_point(&p, &asset.centroid());
            let toward = region_centre(plane).map(|m| m - Vector2::new(c.x, c.z));
            let Some(t) = toward.filter(|t| t.norm() > 1e-9) else {
                break;
            };
            p.translation.x += t.x / t.norm() * REST_MARGIN;
            p.translation.z += t.y / t.norm() * REST_MARGIN;
            continue;
        };
        let shift = shift * (1.0 + REST_MARGIN / shift.norm());
        p.translation.x += shift.x;
        p.translation.z += shift.y;
    }
    p
}

/// The mean of the region's corners.
fn region_centre(plane: &SupportPlane) -> Option<Vector2<f64>> {
    let poly = plane.region.as_ref()?;
    if poly.is_empty() {
        return None;
    }
    Some(poly.iter().fold(Vector2::zeros(), |a, p| a + p.coords) / poly.len() as f64)
}

/// Whether `c` lies inside the convex hull of `points` at least `margin` from its border.
fn inside_hull(points: &[Point2<f64>], c: &Point2<f64>, margin: f64) -> bool {
    let hull = convex_hull(points);
    if hull.len() < 3 {
        return false;
    }
    (0..hull.len()).all(|k| {
        let (a, b) = (hull[k], hull[(k + 1) % hull.len()]);
        let e = b - a;
        let len = e.norm();
        len < 1e-12 || (e.x * (c.y - a.y) - e.y * (c.x - a.x)) / len >= margin
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_score_improves_on_one_that_could_not_be_improved() {
        let values = [0.0, 1e-7, 5e-7, 1e-6, 1.5e-6, 2e-6, 1e-3, 0.02];
        for &a in &values {
            for &b in &values {
                for &c in &values {
                    for &d in &values {
                        if improves((a, b), (c, d)) {
                            assert!(could_improve((a, b)), "({a}, {b}) improved by ({c}, {d})");
                        }
                    }
                }
            }
        }
        assert!(!could_improve((0.0, 1e-6)) && could_improve((0.0, 2e-6)));
    }

    #[test]
    fn hull_contains_with_margin() {
        let sq = [
            Point2::new(0.0, 0.0),
            Point2::new(1.0, 0.0),
            Point2::new(1.0, 1.0),
            Point2::new(0.0, 1.0),
            Point2::new(0.5, 0.5),
        ];
        assert_eq!(convex_hull(&sq).len(), 4);
        assert!(inside_hull(&sq, &Point2::new(0.5, 0.5), 0.1));
        assert!(!inside_hull(&sq, &Point2::new(0.95, 0.5), 0.1));
        assert!(!inside_hull(&sq, &Point2::new(1.5, 0.5), 0.0));
        // A line of feet holds nothing.
        let line = [Point2::new(0.0, 0.0), Point2::new(1.0, 0.0)];
        assert!(!inside_hull(&line, &Point2::new(0.5, 0.0), 0.0));
    }
}
