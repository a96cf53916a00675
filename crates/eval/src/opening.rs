//! Opening clearance: whether every door, drawer and lid of a scene opens to
//! [`OPEN_SHARE`] of its range without running into another object, the floor or a wall.
//!
//! Each joint's moving part (with the parts nested under it) is swept from closed to
//! [`OPEN_SHARE`] of its upper limit in small steps; at every step its surface points are
//! tested against the exact distance fields of the objects whose boxes it reaches and against
//! the walls and floor. The object's own parts never block it, and neither does an object the
//! part carries (`parent_link`): a sock in a drawer rides out with it.

use nalgebra::{Isometry3, Point3, Translation3, Unit, UnitQuaternion, Vector3};
use rayon::prelude::*;
use scenethesis_scene_graph::{
    carried_by, Aabb, Joint, JointKind, JointState, Mesh, MeshPart, OPEN_SHARE,
};
use serde::{Deserialize, Serialize};

use crate::collision::{
    penetration, piece_depth, surface_area, PartField, SceneFields, PENETRATION_TOLERANCE,
};
use crate::raster::{wall_pieces, WallPiece};
use crate::scene::{EvalObject, EvalScene};

/// The largest turn (radians) between two tested states of a revolute joint.
pub const MAX_TURN_STEP: f32 = 0.15;
/// The largest slide (metres) between two tested states of a prismatic joint.
pub const MAX_SLIDE_STEP: f32 = 0.04;

/// How far one joint opens before it hits something.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OpeningClearance {
    /// The object the joint belongs to.
    pub object: String,
    /// The joint's name.
    pub joint: String,
    /// Whether it opens to at least [`OPEN_SHARE`] of its range unobstructed.
    pub held: bool,
    /// The largest share of its range tested free, from closed (1 × [`OPEN_SHARE`] when
    /// held).
    pub free_share: f64,
    /// What stopped it first: an object id, a wall id or the floor's id.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub blocked_by: Option<String>,
}

/// Every joint of the scene, in scene order and joint order.
pub fn opening_clearances(scene: &EvalScene) -> Vec<OpeningClearance> {
    opening_clearances_with(scene, &SceneFields::new(scene))
}

/// [`opening_clearances`] with the part fields of `fields` (shared with other tests of the
/// scene).
pub(crate) fn opening_clearances_with(
    scene: &EvalScene,
    fields: &SceneFields<'_>,
) -> Vec<OpeningClearance> {
    let jobs: Vec<(usize, usize)> = scene
        .objects
        .iter()
        .enumerate()
        .flat_map(|(i, o)| (0..o.joints.len()).map(move |j| (i, j)))
        .collect();
    if jobs.is_empty() {
        return Vec::new();
    }
    let walls = wall_pieces(scene);
    jobs.par_iter()
        .map(|&(i, j)| sweep(scene, &walls, fields, i, j))
        .collect()
}

/// The parts of `object`'s mesh that move when joint `j` does: its own link and every link
/// nested under it.
fn moving_parts(object: &EvalObject, j: usize) -> Vec<&MeshPart> {
    let name = &object.joints[j].joint.name;
    let joints = object.joints.iter().map(|k| &k.joint);
    let carried = |part: &MeshPart| carried_by(part.joint.as_deref(), name, joints.clone());
    object.mesh.parts.iter().filter(|p| carried(p)).collect()
}

/// The joint's axis line where it is now: its world anchor and axis moved by the current
/// states of the joints it hangs from.
fn current_axis(object: &EvalObject, j: usize) -> JointState {
    let mut placed = object.joints[j].clone();
    let mut parent = placed.joint.parent.clone();
    for _ in 0..object.joints.len() {
        let Some(p) = parent.and_then(|n| object.joints.iter().find(|k| k.joint.name == n)) else {
            break;
        };
        let a = placed.joint.anchor;
        let tip = std::array::from_fn(|k| a[k] + placed.joint.axis[k]);
        let (a2, tip2) = (
            p.joint.moved_point(p.state, a),
            p.joint.moved_point(p.state, tip),
        );
        placed.joint.anchor = a2;
        placed.joint.axis = std::array::from_fn(|k| tip2[k] - a2[k]);
        parent = p.joint.parent.clone();
    }
    placed
}

/// The states from closed to [`OPEN_SHARE`] of the upper limit, at most one step apart.
fn sweep_states(placed: &JointState) -> Vec<f32> {
    let target = OPEN_SHARE * placed.joint.limits[1];
    let step = match placed.joint.kind {
        JointKind::Revolute => MAX_TURN_STEP,
        JointKind::Prismatic => MAX_SLIDE_STEP,
    };
    let n = (target / step).ceil().max(1.0) as usize;
    (1..=n).map(|k| target * k as f32 / n as f32).collect()
}

/// Sweeps joint `j` of object `i` and reports how far it opens.
fn sweep(
    scene: &EvalScene,
    walls: &[WallPiece],
    fields: &SceneFields<'_>,
    i: usize,
    j: usize,
) -> OpeningClearance {
    let object = &scene.objects[i];
    let axis = current_axis(object, j);
    let link = Mesh {
        parts: moving_parts(object, j).into_iter().cloned().collect(),
        materials: Vec::new(),
    };
    let points = sweep_points(&link, 0x0be7_0000 + (i * 64 + j) as u64);
    let states = sweep_states(&axis);
    // Each state's points, moved from where the part is now (`axis.state`).
    let posed: Vec<Vec<Point3<f32>>> = states
        .iter()
        .map(|&s| {
            let motion = motion(&axis.joint, s - axis.state);
            points.iter().map(|p| motion * p).collect()
        })
        .collect();
    let swept = Aabb::from_points(
        posed
            .iter()
            .flatten()
            .map(|p| p.cast::<f64>())
            .collect::<Vec<_>>()
            .iter(),
    );
    let obstacles = obstacles(scene, fields, i, &axis.joint.name, swept);
    let floor = scene.architecture.floor.id.clone();
    let share = |k: usize| OPEN_SHARE as f64 * k as f64 / states.len() as f64;
    for (k, pts) in posed.iter().enumerate() {
        if let Some(blocker) = first_blocker(pts, &obstacles, walls, &floor) {
            return OpeningClearance {
                object: object.id.clone(),
                joint: axis.joint.name.clone(),
                held: false,
                free_share: share(k),
                blocked_by: Some(blocker),
            };
        }
    }
    OpeningClearance {
        object: object.id.clone(),
        joint: axis.joint.name.clone(),
        held: true,
        free_share: share(states.len()),
        blocked_by: None,
    }
}

/// Surface samples per square metre of a moving part (one per 4 cm², a quarter of the
/// collision check's density: a part sweeping into another is caught long before it is
/// 1 cm deep).
const SWEEP_SAMPLES_PER_M2: f64 = 2_500.0;

/// The points a moving part is tested by: its vertices and area-uniform surface samples.
fn sweep_points(link: &Mesh, seed: u64) -> Vec<Point3<f32>> {
    let mut points: Vec<Point3<f32>> = link
        .parts
        .iter()
        .flat_map(|p| p.positions.iter().map(|&v| Point3::from(v)))
        .collect();
    if link.triangle_count() > 0 {
        let count = (surface_area(link) * SWEEP_SAMPLES_PER_M2).ceil() as usize;
        points.extend(scenethesis_sdf::sampling::surface_points(
            link,
            count.max(200),
            seed,
        ));
    }
    points
}

/// The rigid motion of a joint's part by `delta` (radians about the axis through the anchor,
/// or metres along the axis).
fn motion(joint: &Joint, delta: f32) -> Isometry3<f32> {
    let axis = Vector3::from(joint.axis);
    let Some(unit) = Unit::try_new(axis, 1e-9) else {
        return Isometry3::identity();
    };
    match joint.kind {
        JointKind::Prismatic => {
            Isometry3::translation(0.0, 0.0, 0.0) * Translation3::from(unit.into_inner() * delta)
        }
        JointKind::Revolute => {
            let anchor = Vector3::from(joint.anchor);
            Translation3::from(anchor)
                * UnitQuaternion::from_axis_angle(&unit, delta)
                * Translation3::from(-anchor)
        }
    }
}

/// An object a sweep may hit, with its box and exact part fields.
struct Obstacle<'a, 's> {
    id: &'a str,
    bounds: Aabb,
    fields: &'a [PartField<'s>],
}

/// The objects other than object `i` and what joint `joint` carries whose boxes meet the
/// swept box, with their part fields (built once per object for all sweeps).
fn obstacles<'a, 's>(
    scene: &'a EvalScene,
    fields: &'a SceneFields<'s>,
    i: usize,
    joint: &str,
    swept: Option<Aabb>,
) -> Vec<Obstacle<'a, 's>> {
    let Some(swept) = swept else {
        return Vec::new();
    };
    let owner = &scene.objects[i].id;
    scene
        .objects
        .iter()
        .enumerate()
        .filter(|&(k, o)| {
            k != i
                && !(o.parent.as_deref() == Some(owner.as_str())
                    && o.parent_link.as_deref() == Some(joint))
        })
        .filter_map(|(k, o)| {
            let bounds = o.mesh.bounds()?;
            touches(&bounds, &swept).then(|| Obstacle {
                id: &o.id,
                bounds,
                fields: fields.of(k),
            })
        })
        .collect()
}

fn touches(a: &Aabb, b: &Aabb) -> bool {
    (0..3).all(|k| a.min[k] <= b.max[k] && b.min[k] <= a.max[k])
}

/// The first thing `points` penetrate deeper than [`PENETRATION_TOLERANCE`]: an obstacle,
/// a wall or the floor.
fn first_blocker(
    points: &[Point3<f32>],
    obstacles: &[Obstacle<'_, '_>],
    walls: &[WallPiece],
    floor: &str,
) -> Option<String> {
    if points.iter().any(|p| -(p.y as f64) > PENETRATION_TOLERANCE) {
        return Some(floor.to_owned());
    }
    for o in obstacles {
        if penetration(points, &o.bounds, o.fields) > PENETRATION_TOLERANCE {
            return Some(o.id.to_owned());
        }
    }
    walls
        .iter()
        .find(|w| piece_depth(w, points) > PENETRATION_TOLERANCE)
        .map(|w| w.wall.clone())
}
