//! The scene driver: places every object in breadth-first order (anchor, parents, children)
//! with an [`Optimizer`], stage 1 (pose alignment) then stage 2 (physics), against a scene of
//! the objects already placed plus the architecture, and checks the post-conditions on the
//! exact fields.

use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::Instant;

use nalgebra::{Point3, Vector3};
use scenethesis_correspondence::deadline::{deadline_after, past};
use scenethesis_correspondence::PoseAlignment;
use scenethesis_scene_graph::{
    Architecture, ParentRef, Pose, RelationKind, Scene, SceneObject, SupportSurface,
};
use scenethesis_sdf::{BoxSdf, SignedDistance};
use serde::{Deserialize, Serialize};

use crate::carry::carry;
use crate::finish::{finish, FinishInput};
use crate::objective::{LossSettings, ObjectProblem, RoomBounds, Stage};
use crate::obstacles::Obstacles;
use crate::optimizer::Optimizer;
use crate::prepare::PreparedAsset;
use crate::report::{ObjectReport, OptimizeTimings, Placement};
use crate::support::{choose_surface, Support, SupportPlane};
use crate::verify::{verify, Placed, Tolerances, Verdict};
use crate::PhysicsOptError;

/// A scene to optimize: the scene graph with the guide's initial poses, each object's prepared
/// asset, and the correspondences of the objects the vision path matched.
pub struct SceneProblem {
    /// The scene graph; its poses are the starting poses.
    pub scene: Scene,
    /// Prepared geometry per object id (objects may share one asset).
    pub assets: BTreeMap<String, Arc<PreparedAsset>>,
    /// Pose-alignment correspondences per object id.
    pub alignments: BTreeMap<String, PoseAlignment>,
}

impl SceneProblem {
    /// A problem over `scene` with no assets or correspondences yet.
    pub fn new(scene: Scene) -> Self {
        Self {
            scene,
            assets: BTreeMap::new(),
            alignments: BTreeMap::new(),
        }
    }

    /// Sets the prepared asset of object `id`.
    pub fn set_asset(&mut self, id: &str, asset: Arc<PreparedAsset>) {
        self.assets.insert(id.to_owned(), asset);
    }

    /// Sets the correspondences of object `id`.
    pub fn set_alignment(&mut self, id: &str, alignment: PoseAlignment) {
        self.alignments.insert(id.to_owned(), alignment);
    }
}

/// Settings of a scene optimization.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OptimizeSettings {
    /// Loss tolerances and weights.
    pub losses: LossSettings,
    /// Post-condition tolerances.
    pub tolerances: Tolerances,
    /// Skip the second physics pass against the exact fields (only the baked grids are used;
    /// faster, but grid error near edges may leave sub-millimetre penetrations).
    pub skip_exact_polish: bool,
    /// Do not move children along when their parent moves (by default a child keeps its pose
    /// relative to its parent's displacement before it is optimized).
    pub keep_children_in_place: bool,
    /// Skip the final separation pass (by default objects that still miss a post-condition
    /// after the breadth-first sweep are settled again against every other object, with the
    /// dense samples the post-conditions use; see [`optimize_scene`]).
    #[serde(default)]
    pub skip_finish: bool,
    /// Wall-clock budget of [`optimize_scene`], in seconds (default
    /// [`DEFAULT_OPTIMIZE_BUDGET_SECS`]; infinite: none). It is checked before every object,
    /// every optimizer iteration and every round of the final pass; once spent, the objects not
    /// reached keep their starting poses, the others the poses reached, the post-conditions are
    /// checked as usual and [`Placement::out_of_time`] is set. Objects not reached are only
    /// brought into their scale range, support region and the room. The clock is only compared
    /// with the deadline, so a budget that is not reached changes nothing. Not serialized (like
    /// the run's time limit it is not part of the options' digest).
    #[serde(skip, default = "default_budget")]
    pub time_budget: f64,
    /// An instant the optimization must also end by, as if its budget ran out then (the
    /// pipeline sets the end of the run's time limit); never serialized.
    #[serde(skip)]
    pub deadline: Option<Instant>,
}

/// Default [`OptimizeSettings::time_budget`], seconds. Optimizing a benchmark scene takes a few
/// seconds in a release build, so the budget only ends runaway work (thousands of objects, a
/// degenerate scene); the pipeline also ends it with the run's time limit
/// ([`OptimizeSettings::deadline`]).
pub const DEFAULT_OPTIMIZE_BUDGET_SECS: f64 = 120.0;

fn default_budget() -> f64 {
    DEFAULT_OPTIMIZE_BUDGET_SECS
}

impl Default for OptimizeSettings {
    fn default() -> Self {
        Self {
            losses: LossSettings::default(),
            tolerances: Tolerances::default(),
            skip_exact_polish: false,
            keep_children_in_place: false,
            skip_finish: false,
            time_budget: default_budget(),
            deadline: None,
        }
    }
}

/// Optimizes every object of `problem` with `optimizer` and reports per object whether the
/// post-conditions hold. Objects that cannot be placed are reported with the reason (which
/// object or surface they collide with, how far they float, how far they stick out); they are
/// never silently left colliding.
///
/// After the breadth-first sweep, a final separation pass settles the objects that still miss
/// a post-condition again, this time against every other object (siblings placed after them
/// included) and with the dense samples of the post-condition check: siblings wedged into each
/// other make room in turn, a child colliding with its parent moves (the parent stays), and a
/// resting object whose centre of mass is not over the feet its support holds moves inward.
/// Children move with a parent the pass moves.
pub fn optimize_scene(
    problem: &SceneProblem,
    optimizer: &dyn Optimizer,
    settings: &OptimizeSettings,
) -> Result<Placement, PhysicsOptError> {
    let scene = &problem.scene;
    let order = scene.bfs_order()?;
    check_objects(problem, &order)?;
    let deadline = match (deadline_after(settings.time_budget), settings.deadline) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    };
    let rooms: Vec<RoomBounds> = order
        .iter()
        .map(|o| RoomBounds::of_room(&scene.architecture, o.room.as_deref()))
        .collect();
    let mut timings = OptimizeTimings::default();
    let mut clock = Instant::now();
    let mut sweep = Sweep::new(&scene.architecture, order.len());
    for (object, &room) in order.iter().zip(&rooms) {
        sweep.place(problem, optimizer, settings, object, room, deadline);
    }
    timings.sweep = lap(&mut clock);
    let Sweep {
        mut exact,
        mut reports,
        mut supports,
        ..
    } = sweep;
    let mut checked = None;
    if !settings.skip_finish {
        let mut finished = Finished {
            reports: &mut reports,
            supports: &mut supports,
            exact: &mut exact,
        };
        let scope = FinishScope {
            order: &order,
            rooms: &rooms,
            deadline,
        };
        checked = finish_pass(problem, optimizer, settings, &scope, &mut finished);
    }
    timings.final_pass = lap(&mut clock);
    let out_of_time = past(deadline);
    let placed: Vec<Placed<'_>> = order
        .iter()
        .zip(&reports)
        .zip(&supports)
        .zip(&rooms)
        .map(|(((object, report), support), &room)| Placed {
            id: &object.id,
            asset: &problem.assets[&object.id],
            pose: report.pose,
            support,
            room,
        })
        .collect();
    let verdicts = checked.unwrap_or_else(|| verify(&placed, &exact, &settings.tolerances));
    for (report, verdict) in reports.iter_mut().zip(verdicts) {
        report.penetration = verdict.penetration;
        report.support_gap = verdict.support_gap;
        report.issues = verdict.issues;
    }
    timings.check = lap(&mut clock);
    Ok(Placement {
        optimizer: optimizer.name().to_owned(),
        objects: reports,
        out_of_time,
        timings,
    })
}

/// The seconds since `clock`, which is moved on to now.
fn lap(clock: &mut Instant) -> f64 {
    let now = Instant::now();
    let seconds = now.duration_since(*clock).as_secs_f64();
    *clock = now;
    seconds
}

/// Every object of `order` has a prepared asset and a finite pose of positive scale.
fn check_objects(problem: &SceneProblem, order: &[&SceneObject]) -> Result<(), PhysicsOptError> {
    for object in order {
        if !problem.assets.contains_key(&object.id) {
            return Err(PhysicsOptError::MissingAsset {
                id: object.id.clone(),
            });
        }
        if !object.pose.is_finite() || object.pose.scale <= 0.0 {
            return Err(PhysicsOptError::InvalidPose {
                id: object.id.clone(),
                pose: object.pose,
            });
        }
    }
    Ok(())
}

/// The breadth-first sweep: the obstacles placed so far (baked grids and exact fields), the
/// final poses by id, and each placed object's report and support.
struct Sweep<'a> {
    grid: Obstacles,
    exact: Obstacles,
    finals: BTreeMap<&'a str, Pose>,
    reports: Vec<ObjectReport>,
    supports: Vec<Support>,
}

impl<'a> Sweep<'a> {
    /// A sweep over `objects` objects, with the architecture as the first obstacles.
    fn new(architecture: &Architecture, objects: usize) -> Self {
        let mut grid = Obstacles::new(false);
        let mut exact = Obstacles::new(true);
        for (id, field, pose) in architecture_fields(architecture) {
            grid.insert(&id, field.clone(), pose, true, &[]);
            exact.insert(&id, field, pose, true, &[]);
        }
        Self {
            grid,
            exact,
            finals: BTreeMap::new(),
            reports: Vec::with_capacity(objects),
            supports: Vec::with_capacity(objects),
        }
    }

    /// Places `object`: moved with its parent, aligned, settled, polished against the exact
    /// fields when it still collides, then added to the obstacles. Past `deadline` it keeps
    /// its starting pose (brought into its scale range, support region and the room).
    fn place(
        &mut self,
        problem: &SceneProblem,
        optimizer: &dyn Optimizer,
        settings: &OptimizeSettings,
        object: &'a SceneObject,
        room: RoomBounds,
        deadline: Option<Instant>,
    ) {
        let scene = &problem.scene;
        let asset = &problem.assets[&object.id];
        let start = match object.parent.object_id() {
            Some(parent) if !settings.keep_children_in_place => {
                let before = scene.object(parent).map(|p| p.pose);
                match (before, self.finals.get(parent)) {
                    (Some(before), Some(after)) => carry(&before, after, &object.pose),
                    _ => object.pose,
                }
            }
            _ => object.pose,
        };
        let support = resolve_support(problem, object, &start, &self.finals);
        let alignment = problem.alignments.get(&object.id);
        let mut object_problem = ObjectProblem {
            room: Some(room),
            alignment,
            deadline,
            ..ObjectProblem::new(&object.id, asset, &self.grid, &support, &settings.losses)
        };
        let (mut pose, alignment_iterations, mut physics_iterations) = if past(deadline) {
            // Out of time: not reached, it keeps its starting pose.
            (object_problem.project(&start), 0, 0)
        } else {
            let aligned = optimizer.optimize(&object_problem, Stage::Alignment, start);
            let rested = rested_by_scale(&object_problem, optimizer.settles(), aligned.pose);
            let settled = optimizer.optimize(&object_problem, Stage::Physics, rested);
            (settled.pose, aligned.iterations, settled.iterations)
        };
        let mut polished = false;
        if !settings.skip_exact_polish && !past(deadline) {
            object_problem.obstacles = &self.exact;
            if !object_problem.contacts(&pose).is_free() {
                let polish = optimizer.optimize(&object_problem, Stage::Physics, pose);
                pose = polish.pose;
                physics_iterations += polish.iterations;
                polished = true;
            }
        }
        let samples = asset.surface_points();
        self.grid
            .insert(&object.id, asset.grid_field(), pose, false, samples);
        self.exact
            .insert(&object.id, asset.exact_field(), pose, false, samples);
        self.finals.insert(&object.id, pose);
        self.reports.push(ObjectReport {
            id: object.id.clone(),
            initial_pose: object.pose,
            pose,
            support: support.clone(),
            alignment_iterations,
            physics_iterations,
            polished,
            penetration: 0.0,
            support_gap: None,
            issues: Vec::new(),
        });
        self.supports.push(support);
    }
}

/// The alignment stage's `pose` of an object the image placed, rested on its support by a
/// change of scale ([`ObjectProblem::rest_by_scale`]) when the optimizer `settles` it: a
/// shrink always, a growth only when the grown object touches nothing placed so far (grown
/// into a neighbour, the physics stage would push it off the place the image shows).
fn rested_by_scale(problem: &ObjectProblem<'_>, settles: bool, pose: Pose) -> Pose {
    if problem.alignment.is_none() || !settles {
        return pose;
    }
    match problem.rest_by_scale(&pose) {
        Some(rested) if rested.scale <= pose.scale || problem.contacts(&rested).is_free() => rested,
        _ => pose,
    }
}

/// What the final separation pass updates: the reports, the supports and the exact fields.
struct Finished<'r> {
    reports: &'r mut Vec<ObjectReport>,
    supports: &'r mut Vec<Support>,
    exact: &'r mut Obstacles,
}

/// What the final separation pass works over: the objects in sweep order, the rectangle each
/// must stay inside and the instant it must end by.
struct FinishScope<'s, 'o> {
    order: &'s [&'o SceneObject],
    rooms: &'s [RoomBounds],
    deadline: Option<Instant>,
}

/// The final separation pass ([`finish`]) over the swept objects; when it moved any, the
/// exact fields are rebuilt at the new poses. Returns the pass's last check, when it was
/// made on the final poses.
fn finish_pass(
    problem: &SceneProblem,
    optimizer: &dyn Optimizer,
    settings: &OptimizeSettings,
    scope: &FinishScope<'_, '_>,
    finished: &mut Finished<'_>,
) -> Option<Vec<Verdict>> {
    let scene = &problem.scene;
    let order = scope.order;
    let assets: Vec<Arc<PreparedAsset>> = order
        .iter()
        .map(|o| problem.assets[&o.id].clone())
        .collect();
    let architecture = architecture_fields(&scene.architecture);
    let input = FinishInput {
        order,
        assets: &assets,
        architecture: &architecture,
        rooms: scope.rooms,
        losses: &settings.losses,
        tolerances: settings.tolerances,
        settle: optimizer.settles(),
        deadline: scope.deadline,
    };
    let mut poses: Vec<Pose> = finished.reports.iter().map(|r| r.pose).collect();
    let resolve = |i: usize, pose: &Pose, poses: &[Pose]| {
        let finals: BTreeMap<&str, Pose> = order
            .iter()
            .zip(poses)
            .map(|(o, p)| (o.id.as_str(), *p))
            .collect();
        resolve_support(problem, order[i], pose, &finals)
    };
    let (spent, verdicts) = finish(&input, optimizer, &resolve, &mut poses, finished.supports);
    if poses
        .iter()
        .zip(finished.reports.iter())
        .any(|(p, r)| *p != r.pose)
    {
        let mut exact = Obstacles::new(true);
        for (id, field, pose) in architecture {
            exact.insert(&id, field, pose, true, &[]);
        }
        for ((object, report), pose) in order.iter().zip(finished.reports.iter_mut()).zip(&poses) {
            let asset = &problem.assets[&object.id];
            exact.insert(
                &object.id,
                asset.exact_field(),
                *pose,
                false,
                asset.surface_points(),
            );
            report.pose = *pose;
        }
        *finished.exact = exact;
    }
    for (report, (support, spent)) in finished
        .reports
        .iter_mut()
        .zip(finished.supports.iter().zip(spent))
    {
        report.support = support.clone();
        report.physics_iterations += spent;
    }
    verdicts
}

/// Head room an object needs under a compartment's clearance beyond its own height, metres
/// (the support clearance and the collision margin above and below, rounded up).
const FIT_SPARE: f64 = 0.004;

/// What `object` rests on, given the final poses of the objects placed before it: nothing for
/// an object fixed to the world ([`SceneObject::fixed_to_world`]: mounted on a wall, so no
/// stability term pulls it down; collisions still push it), the floor for ground objects and
/// for `on-floor` / `against-wall` objects linked to another object, else the parent's support
/// surface of the fitting kind nearest to the object's foot (or the parent's geometry when it
/// has none).
fn resolve_support(
    problem: &SceneProblem,
    object: &SceneObject,
    start: &Pose,
    finals: &BTreeMap<&str, Pose>,
) -> Support {
    if object.fixed_to_world() {
        return Support::Free;
    }
    let on_floor = matches!(
        object.support,
        RelationKind::OnFloor | RelationKind::AgainstWall
    );
    match &object.parent {
        _ if on_floor => Support::Surface(SupportPlane::floor(&problem.scene.architecture)),
        ParentRef::Ground | ParentRef::Wall(_) => {
            Support::Surface(SupportPlane::floor(&problem.scene.architecture))
        }
        ParentRef::Object(parent) => {
            let (Some(parent_pose), Some(parent_asset)) =
                (finals.get(parent.as_str()), problem.assets.get(parent))
            else {
                return Support::ParentGeometry {
                    parent: parent.clone(),
                };
            };
            let foot = Point3::from(start.translation);
            let all = parent_asset.support_surfaces();
            // A compartment too low for the object even at its smallest scale cannot hold it:
            // choose among the surfaces it fits under first.
            let fitting: Vec<SupportSurface> = problem
                .assets
                .get(&object.id)
                .map(|asset| {
                    let height = asset.bounds().max.y.max(1e-6) * asset.scale_range()[0];
                    all.iter()
                        .filter(|s| {
                            s.clearance
                                .is_none_or(|c| c as f64 * parent_pose.scale >= height + FIT_SPARE)
                        })
                        .cloned()
                        .collect()
                })
                .unwrap_or_default();
            let fits = |surfaces: &[SupportSurface]| {
                choose_surface(parent, parent_pose, surfaces, object.support, &foot)
            };
            (if fitting.len() < all.len() {
                fits(&fitting).or_else(|| fits(all))
            } else {
                fits(all)
            })
            .map_or_else(
                || Support::ParentGeometry {
                    parent: parent.clone(),
                },
                Support::Surface,
            )
        }
    }
}

/// The architecture as posed box fields: a floor slab under the floor rectangle (reaching a
/// metre beyond it) and one box per wall along its centre line, lengthened by its thickness so
/// that corners close. Door openings are kept solid: nothing should stand in a doorway.
pub fn architecture_fields(
    architecture: &Architecture,
) -> Vec<(String, Arc<dyn SignedDistance>, Pose)> {
    let floor = &architecture.floor;
    let extent = floor.extent();
    let centre = nalgebra::center(&floor.min, &floor.max);
    let slab = 0.5;
    let mut out: Vec<(String, Arc<dyn SignedDistance>, Pose)> = vec![(
        floor.id.clone(),
        Arc::new(BoxSdf::new(Vector3::new(
            (extent.x / 2.0 + 1.0) as f32,
            (slab / 2.0) as f32,
            (extent.y / 2.0 + 1.0) as f32,
        ))),
        Pose::new(1.0, 0.0, Vector3::new(centre.x, -slab / 2.0, centre.y)),
    )];
    for wall in &architecture.walls {
        let length = wall.length();
        if length <= 0.0 || wall.height <= 0.0 || wall.thickness <= 0.0 {
            continue;
        }
        let d = wall.direction();
        let mid = nalgebra::center(&wall.start, &wall.end);
        // R_y(yaw)·x̂ = (cos yaw, 0, −sin yaw) must equal the wall direction (dx, 0, dz).
        let yaw = (-d.y).atan2(d.x);
        out.push((
            wall.id.clone(),
            Arc::new(BoxSdf::new(Vector3::new(
                ((length + wall.thickness) / 2.0) as f32,
                (wall.height / 2.0) as f32,
                (wall.thickness / 2.0) as f32,
            ))),
            Pose::new(1.0, yaw, Vector3::new(mid.x, wall.height / 2.0, mid.y)),
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wall_boxes_cover_the_walls() {
        let arch = Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9);
        let fields = architecture_fields(&arch);
        assert_eq!(fields.len(), 5);
        for ((_, field, pose), wall) in fields[1..].iter().zip(&arch.walls) {
            let mid = nalgebra::center(&wall.start, &wall.end);
            let inner = mid + wall.inward_normal() * (wall.thickness / 2.0 + 0.01);
            let outer = mid + wall.inward_normal() * (wall.thickness / 2.0 - 0.01);
            let d = |x: f64, z: f64| {
                let p = pose.inverse_transform_point(&Point3::new(x, 1.0, z));
                field.distance(&p.cast::<f32>())
            };
            assert!((d(inner.x, inner.y) - 0.01).abs() < 1e-4, "{}", wall.id);
            assert!((d(outer.x, outer.y) + 0.01).abs() < 1e-4, "{}", wall.id);
        }
    }
}
