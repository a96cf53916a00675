//! Lifted boxes become the scene graph: ground → anchor → parents → children, with initial
//! 5-DoF poses (scale, yaw, translation) of the retrieved assets.
//!
//! - **Parent**: the lifted support (on, inside or under another recovered object) when there
//!   is one; a box standing on the floor is a ground object. A box nothing holds up is hung on
//!   the nearest wall when its asset mounts on walls, goes to its planned parent when that was
//!   recovered, and otherwise stands on the floor below where it was seen.
//! - **Pose**: translation = the box's bottom centre (the asset frame's origin), scale = the
//!   box height over the asset's, clamped to the asset's scale range, yaw = the box's yaw, or
//!   the half turn of it that faces away from a wall the box backs onto (within 15 cm), else
//!   toward the box of what the plan has it face, else toward the camera: a box alone cannot
//!   tell front from back.
//! - **Against a wall**: a ground object whose box backs onto a wall within 15 cm.

use std::collections::{BTreeMap, BTreeSet};
use std::f64::consts::PI;

use nalgebra::{Point3, Vector2, Vector3};
use scenethesis_agents::{Plan, PlannedObject};
use scenethesis_scene_graph::{
    wrap_yaw, Aabb, Architecture, ParentRef, Pose, Relation, RelationKind, Scene, SceneObject,
    GROUND_ID,
};
use scenethesis_scene_graph::{AssetInfo, Placement};
use scenethesis_vision::{LiftedBox, SupportGuess, SupportKind};

/// Largest gap between a box's back and a wall that still counts as backing onto it.
pub const WALL_GAP: f64 = 0.15;

/// The wall a footprint backs onto: `(wall id, inward normal)` of the nearest wall whose inner
/// face is within [`WALL_GAP`] of the box.
fn backing_wall(architecture: &Architecture, b: &LiftedBox) -> Option<(String, Vector2<f64>)> {
    let floor = &architecture.floor;
    let corners = b.footprint().corners();
    let mut best: Option<(f64, String, Vector2<f64>)> = None;
    for wall in &architecture.walls {
        // Rectangular rooms: each wall lines one side of the floor rectangle.
        let mid = nalgebra::center(&wall.start, &wall.end);
        let sides = [
            (mid.y - floor.min.y, Vector2::new(0.0, 1.0), floor.min.y, 1),
            (floor.max.y - mid.y, Vector2::new(0.0, -1.0), floor.max.y, 1),
            (mid.x - floor.min.x, Vector2::new(1.0, 0.0), floor.min.x, 0),
            (floor.max.x - mid.x, Vector2::new(-1.0, 0.0), floor.max.x, 0),
        ];
        let Some(&(_, normal, face, axis)) = sides
            .iter()
            .filter(|s| s.0.abs() < 0.3)
            .min_by(|a, b| a.0.abs().total_cmp(&b.0.abs()))
        else {
            continue;
        };
        let gap = corners
            .iter()
            .map(|c| (c[axis] - face) * normal[axis])
            .fold(f64::INFINITY, f64::min);
        if gap <= WALL_GAP && best.as_ref().is_none_or(|(g, _, _)| gap < *g) {
            best = Some((gap, wall.id.clone(), normal));
        }
    }
    best.map(|(_, id, n)| (id, n))
}

/// The yaw among `b.yaw` and `b.yaw + π` whose front (+Z turned by yaw) points most along
/// `toward`.
fn facing(b: &LiftedBox, toward: Vector2<f64>) -> f64 {
    let front = |yaw: f64| Vector2::new(yaw.sin(), yaw.cos());
    if front(b.yaw).dot(&toward) >= front(b.yaw + PI).dot(&toward) {
        wrap_yaw(b.yaw)
    } else {
        wrap_yaw(b.yaw + PI)
    }
}

/// The scene of the recovered boxes. `infos` are the assets by planned id, `supports` the
/// lifted supports, `eye` the camera centre. Returns the scene; every box id must be planned.
pub fn build_scene(
    plan: &Plan,
    seed: u64,
    architecture: Architecture,
    infos: &BTreeMap<String, AssetInfo>,
    boxes: &[LiftedBox],
    supports: &[SupportGuess],
    eye: Point3<f64>,
) -> Scene {
    let by_id: BTreeMap<&str, &LiftedBox> = boxes.iter().map(|b| (b.id.as_str(), b)).collect();
    let support: BTreeMap<&str, &SupportGuess> =
        supports.iter().map(|s| (s.id.as_str(), s)).collect();
    let mut placed: BTreeMap<String, Placed> = BTreeMap::new();
    for b in boxes {
        let Some(object) = plan.object(&b.id) else {
            continue;
        };
        let guess = support.get(b.id.as_str()).copied();
        let entry = placement(&architecture, infos, &by_id, object, b, guess);
        placed.insert(b.id.clone(), entry);
    }
    let (order, done) = parents_first(plan, &mut placed);
    let mut scene = Scene::new(architecture);
    scene.prompt = plan.prompt.clone();
    scene.seed = seed;
    for id in &order {
        let (object, b, info) = (
            plan.object(id).expect("planned"),
            by_id[id.as_str()],
            &infos[id],
        );
        let toward = facing_target(object, b, &by_id)
            .unwrap_or(Vector2::new(eye.x - b.center.x, eye.z - b.center.z));
        let built = scene_object(&scene, object, b, info, placed[id].clone(), &done, toward);
        scene.objects.push(built);
    }
    scene.anchor = anchor(&scene, plan);
    scene
}

/// The direction (x, z) from box `b` to the box of what `object` is planned to face, when
/// that was recovered.
fn facing_target(
    object: &PlannedObject,
    b: &LiftedBox,
    by_id: &BTreeMap<&str, &LiftedBox>,
) -> Option<Vector2<f64>> {
    object
        .relations
        .iter()
        .filter(|r| r.kind == RelationKind::Facing)
        .find_map(|r| by_id.get(r.target.as_str()))
        .map(|t| Vector2::new(t.center.x - b.center.x, t.center.z - b.center.z))
        .filter(|d| d.norm() > 1e-6)
}

/// An object's parent, support kind and, for one standing against a wall, that wall.
type Placed = (ParentRef, RelationKind, Option<String>);

/// Where the recovered box `b` of `object` hangs or stands: on, inside or under the lifted
/// support's parent; on a wall (a wall asset with a wall behind it, or a mounted guess); on its
/// planned parent when the lift found no support; else on the floor, against the wall behind
/// it when there is one.
fn placement(
    architecture: &Architecture,
    infos: &BTreeMap<String, AssetInfo>,
    by_id: &BTreeMap<&str, &LiftedBox>,
    object: &PlannedObject,
    b: &LiftedBox,
    guess: Option<&SupportGuess>,
) -> Placed {
    let wall = backing_wall(architecture, b);
    match guess.map(|g| (g.kind, g.parent.clone())) {
        Some((SupportKind::On, Some(p))) => (ParentRef::Object(p), RelationKind::On, None),
        Some((SupportKind::Inside, Some(p))) => (ParentRef::Object(p), RelationKind::Inside, None),
        Some((SupportKind::Under, Some(p))) => (ParentRef::Object(p), RelationKind::Under, None),
        Some((SupportKind::Mounted, Some(w))) if architecture.wall(&w).is_some() => {
            (ParentRef::Wall(w), RelationKind::Mounted, None)
        }
        Some((SupportKind::Unsupported | SupportKind::Mounted, _)) => {
            let planned_parent = object
                .parent
                .object_id()
                .filter(|p| by_id.contains_key(p))
                .map(str::to_owned);
            let mounts = infos
                .get(&b.id)
                .is_some_and(|i| i.placement == Placement::Wall);
            match (planned_parent, mounts) {
                // A wall asset with a wall behind it hangs on that wall.
                (_, true) => match &wall {
                    Some((w, _)) => (ParentRef::Wall(w.clone()), RelationKind::Mounted, None),
                    None => (ParentRef::Ground, RelationKind::AgainstWall, None),
                },
                (Some(p), false) => (ParentRef::Object(p), object.support, None),
                (None, false) => (ParentRef::Ground, RelationKind::OnFloor, None),
            }
        }
        _ => match &wall {
            Some((w, _)) => (
                ParentRef::Ground,
                RelationKind::AgainstWall,
                Some(w.clone()),
            ),
            None => (ParentRef::Ground, RelationKind::OnFloor, None),
        },
    }
}

/// The placed objects in plan order with parents before children (lifted parents are
/// strictly lower, planned ones acyclic; any object left in a cycle goes to the floor), and
/// the set of them.
fn parents_first(
    plan: &Plan,
    placed: &mut BTreeMap<String, Placed>,
) -> (Vec<String>, BTreeSet<String>) {
    let mut order: Vec<String> = Vec::new();
    let mut done: BTreeSet<String> = BTreeSet::new();
    loop {
        let before = order.len();
        for o in &plan.objects {
            let Some((parent, _, _)) = placed.get(&o.id) else {
                continue;
            };
            if done.contains(&o.id) {
                continue;
            }
            let ready = match parent {
                ParentRef::Ground | ParentRef::Wall(_) => true,
                ParentRef::Object(p) => done.contains(p),
            };
            if ready {
                done.insert(o.id.clone());
                order.push(o.id.clone());
            }
        }
        if order.len() == before {
            break;
        }
    }
    for o in &plan.objects {
        if placed.contains_key(&o.id) && !done.contains(&o.id) {
            let entry = placed.get_mut(&o.id).expect("present");
            *entry = (ParentRef::Ground, RelationKind::OnFloor, None);
            done.insert(o.id.clone());
            order.push(o.id.clone());
        }
    }
    (order, done)
}

/// The scene object of box `b`: scaled to the box's height within the asset's range, turned
/// to face out of its wall (or along `toward`: what it faces, else the camera), standing on the floor or at the
/// box's bottom, with the planned relations whose targets exist (`done`, the walls, the
/// ground) and the wall it stands against.
fn scene_object(
    scene: &Scene,
    object: &PlannedObject,
    b: &LiftedBox,
    info: &AssetInfo,
    (parent, support_kind, wall): Placed,
    done: &BTreeSet<String>,
    toward: Vector2<f64>,
) -> SceneObject {
    let [sx, sy, sz] = info.size.map(f64::from);
    let [lo, hi] = info.scale_range.map(f64::from);
    let scale = (b.size().y / sy.max(1e-6)).clamp(lo.min(hi), hi.max(lo));
    let yaw = match backing_wall(&scene.architecture, b) {
        Some((_, inward)) => facing(b, inward),
        None => facing(b, toward),
    };
    let on_floor = parent == ParentRef::Ground
        && (support_kind != RelationKind::AgainstWall || b.bottom() < 0.1);
    let y = if on_floor { 0.0 } else { b.bottom().max(0.0) };
    let mut relations: Vec<Relation> = object
        .relations
        .iter()
        .filter(|r| {
            r.kind != RelationKind::AgainstWall
                && (done.contains(&r.target)
                    || scene.architecture.wall(&r.target).is_some()
                    || r.target == GROUND_ID)
        })
        .cloned()
        .collect();
    if let Some(w) = wall {
        relations.insert(0, Relation::new(RelationKind::AgainstWall, w));
    }
    let support_kind = if support_kind == RelationKind::AgainstWall
        && !relations
            .iter()
            .any(|r| r.kind == RelationKind::AgainstWall)
    {
        RelationKind::OnFloor
    } else {
        support_kind
    };
    SceneObject {
        id: object.id.clone(),
        category: object.category.clone(),
        asset: info.source.clone(),
        pose: Pose::new(scale, yaw, Vector3::new(b.center.x, y, b.center.z)),
        parent,
        support: support_kind,
        relations,
        local_bounds: Aabb::new(
            Point3::new(-sx / 2.0, 0.0, -sz / 2.0),
            Point3::new(sx / 2.0, sy, sz / 2.0),
        ),
        joints: scenethesis_scene_graph::JointState::all_closed(&info.joints),
        parent_link: None,
        room: None,
    }
}

/// The plan's anchor when it stands on the ground, else the first ground object.
fn anchor(scene: &Scene, plan: &Plan) -> Option<String> {
    let is_ground = |id: &str| {
        scene
            .objects
            .iter()
            .any(|o| o.id == id && o.parent == ParentRef::Ground)
    };
    if is_ground(&plan.anchor) {
        Some(plan.anchor.clone())
    } else {
        scene
            .objects
            .iter()
            .find(|o| o.parent == ParentRef::Ground)
            .map(|o| o.id.clone())
    }
}
