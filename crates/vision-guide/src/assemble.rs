//! Lifted boxes become the scene graph: ground → anchor → parents → children, with initial
//! 5-DoF poses (scale, yaw, translation) of the retrieved assets.
//!
//! - **Parent**: the lifted support (on, inside or under another recovered object) when there
//!   is one; a box standing on the floor is a ground object. A box nothing holds up is hung on
//!   the nearest wall when its asset mounts on walls, goes to its planned parent when that was
//!   recovered, and otherwise stands on the floor below where it was seen.
//! - **Pose**: translation = the box's bottom centre (the asset frame's origin), scale = the
//!   box height over the asset's, clamped to the asset's scale range, yaw = the box's yaw, or
//!   the half turn of it toward the box of what it faces, else away from a wall the box backs
//!   onto (within 15 cm), else toward the camera: a box alone cannot tell front from back. What it faces is what the plan says, or for seating the nearest recovered
//!   table, desk or counter it serves (an arrangement `faces` rule, within the rule's reach):
//!   that becomes a `facing` relation, so the correspond stage's yaw search and the judge
//!   hold it to it. A square box facing something may also turn a quarter.
//! - **Against a wall**: a ground object whose box backs onto a wall within 15 cm.

use std::collections::{BTreeMap, BTreeSet};
use std::f64::consts::{FRAC_1_SQRT_2, PI};

use nalgebra::{Point3, Vector2, Vector3};
use scenethesis_agents::arrangement::ArrangementRules;
use scenethesis_agents::{Plan, PlannedObject};
use scenethesis_scene_graph::{
    aabb_floor_gap, wrap_yaw, Aabb, Architecture, ParentRef, Pose, Relation, RelationKind, Scene,
    SceneObject, GROUND_ID,
};
use scenethesis_scene_graph::{is_square_footprint, AssetInfo, Placement};
use scenethesis_vision::{LiftedBox, SupportGuess, SupportKind};

/// Largest gap between a box's back and a wall that still counts as backing onto it.
pub const WALL_GAP: f64 = 0.15;
/// The same for an object the plan puts against a wall: seen only at the image's edge (a
/// standing mirror on the wall behind the camera), its box comes out farther off.
const PLANNED_WALL_GAP: f64 = 0.35;

/// How far (metres) from a wall `object`'s box may back onto it: [`PLANNED_WALL_GAP`] when the
/// plan puts it against a wall, else [`WALL_GAP`].
fn wall_reach(object: &PlannedObject) -> f64 {
    if object.support == RelationKind::AgainstWall
        || object
            .relations
            .iter()
            .any(|r| r.kind == RelationKind::AgainstWall)
    {
        PLANNED_WALL_GAP
    } else {
        WALL_GAP
    }
}
/// Walls whose gaps to a box differ by at most this (metres) are a corner it stands in.
const CORNER_TIE: f64 = 0.03;
/// A box more than this (metres) inside a wall was lifted a quarter turn off.
const WALL_DEEP: f64 = 0.1;

/// The wall a footprint backs onto: `(wall id, inward normal)` of the nearest wall whose inner
/// face is within `reach` of the box ([`wall_reach`]). In a corner (gaps within [`CORNER_TIE`]), an
/// oblong asset (`size`, its front +Z) backs onto the wall its back lines: a shelving unit
/// whose end touches the side wall still backs onto the wall behind it, a bed onto the wall
/// at its head. A box more than [`WALL_DEEP`] inside a wall backs onto that one.
fn backing_wall(
    architecture: &Architecture,
    b: &LiftedBox,
    size: [f32; 3],
    reach: f64,
) -> Option<(String, Vector2<f64>)> {
    let floor = &architecture.floor;
    let footprint = b.footprint();
    let corners = footprint.corners();
    let depth_axis = back_axis(b, size);
    // (gap, wall, inward normal, whether its back lines it) of the walls within reach.
    let mut near: Vec<(f64, String, Vector2<f64>, bool)> = Vec::new();
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
        if gap <= reach {
            let along = depth_axis.is_none_or(|a| a.dot(&normal).abs() >= FRAC_1_SQRT_2);
            near.push((gap, wall.id.clone(), normal, along));
        }
    }
    let nearest = near.iter().map(|w| w.0).fold(f64::INFINITY, f64::min);
    // A box deep in a wall is a quarter turn off (the lift read its length as its depth): it
    // backs onto that wall. Else walls about as near (a corner) go by which one its back lines.
    let tied = |gap: f64| nearest >= -WALL_DEEP && gap <= nearest.max(0.0) + CORNER_TIE;
    near.into_iter()
        .filter(|w| w.0 == nearest || tied(w.0))
        .max_by(|a, b| a.3.cmp(&b.3).then(b.0.total_cmp(&a.0)))
        .map(|(_, id, n, _)| (id, n))
}

/// The box axis (world x, z) along which the asset of `size` (x, y, z) turned to the box's
/// footprint looks front to back, when the asset is oblong: the box side that matches the
/// asset's width runs along its back.
fn back_axis(b: &LiftedBox, size: [f32; 3]) -> Option<Vector2<f64>> {
    let (sx, sz) = (f64::from(size[0]), f64::from(size[2]));
    if is_square_footprint(sx, sz) {
        return None;
    }
    let (w, d) = (b.half_extents.x, b.half_extents.z);
    let footprint = b.footprint();
    Some(if (w >= d) == (sx >= sz) {
        footprint.axis_z()
    } else {
        footprint.axis_x()
    })
}

/// The yaw among the box's turns (`b.yaw` and `b.yaw + π`; for a square box facing a target,
/// every quarter turn) whose front (+Z turned by yaw) points most along `toward`.
fn facing(b: &LiftedBox, toward: Vector2<f64>, quarter: bool) -> f64 {
    let front = |yaw: f64| Vector2::new(yaw.sin(), yaw.cos());
    let turns: &[f64] = if quarter && is_square_footprint(b.half_extents.x, b.half_extents.z) {
        &[0.0, PI / 2.0, PI, -PI / 2.0]
    } else {
        &[0.0, PI]
    };
    let best = turns
        .iter()
        .map(|t| b.yaw + t)
        .max_by(|a, c| front(*a).dot(&toward).total_cmp(&front(*c).dot(&toward)))
        .unwrap_or(b.yaw);
    wrap_yaw(best)
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
        let faced = faced(plan, &placed, object, b, &by_id);
        let built = scene_object(
            &scene,
            object,
            b,
            info,
            placed[id].clone(),
            &done,
            Heading {
                faced,
                camera: Vector2::new(eye.x - b.center.x, eye.z - b.center.z),
            },
        );
        scene.objects.push(built);
    }
    scene.anchor = anchor(&scene, plan);
    scene
}

/// What box `b` of `object` faces, when it was recovered: the target of a planned `facing`
/// relation, else (for a floor object an arrangement `faces` rule makes face a table, desk or
/// counter it serves) the nearest floor box of a target category within the rule's reach.
/// Returns the target's id, whether the plan named it, and the direction (x, z) to it.
fn faced(
    plan: &Plan,
    placed: &BTreeMap<String, Placed>,
    object: &PlannedObject,
    b: &LiftedBox,
    by_id: &BTreeMap<&str, &LiftedBox>,
) -> Option<Faced> {
    let toward = |t: &LiftedBox| {
        Some(Vector2::new(
            t.center.x - b.center.x,
            t.center.z - b.center.z,
        ))
        .filter(|d| d.norm() > 1e-6)
    };
    let planned = object
        .relations
        .iter()
        .filter(|r| r.kind == RelationKind::Facing)
        .find_map(|r| Some((r.target.clone(), toward(by_id.get(r.target.as_str())?)?)));
    if let Some((target, direction)) = planned {
        return Some(Faced {
            target,
            planned: true,
            direction,
        });
    }
    let on_floor = |id: &str| placed.get(id).is_some_and(|p| p.0 == ParentRef::Ground);
    if !on_floor(&object.id) {
        return None;
    }
    let mine = floor_box(b);
    let mut best: Option<(f64, &LiftedBox)> = None;
    for (targets, within) in ArrangementRules::builtin().faces_of(&object.category) {
        for (id, t) in by_id {
            let category = plan.object(id).map(|o| o.category.as_str());
            if *id == object.id
                || !on_floor(id)
                || !category.is_some_and(|c| targets.iter().any(|x| x == c))
            {
                continue;
            }
            let gap = aabb_floor_gap(&mine, &floor_box(t));
            if gap <= within && best.is_none_or(|(g, _)| gap < g) {
                best = Some((gap, t));
            }
        }
    }
    let (_, t) = best?;
    Some(Faced {
        target: t.id.clone(),
        planned: false,
        direction: toward(t)?,
    })
}

/// The world box of `b`'s footprint (flat, at the floor), as the judge's floor gaps measure.
fn floor_box(b: &LiftedBox) -> Aabb {
    let corners = b.footprint().corners();
    let (xs, zs) = (corners.map(|c| c.x), corners.map(|c| c.y));
    let lo = |v: [f64; 4]| v.into_iter().fold(f64::INFINITY, f64::min);
    let hi = |v: [f64; 4]| v.into_iter().fold(f64::NEG_INFINITY, f64::max);
    Aabb::new(
        Point3::new(lo(xs), 0.0, lo(zs)),
        Point3::new(hi(xs), 0.0, hi(zs)),
    )
}

/// What a recovered object faces (see [`faced`]).
struct Faced {
    /// The target's id.
    target: String,
    /// Whether the plan has the `facing` relation (else the scene gains it).
    planned: bool,
    /// The direction (x, z) from the object's box to the target's.
    direction: Vector2<f64>,
}

/// What turns a box that backs onto no wall: what it faces, else the camera.
struct Heading {
    /// What it faces, when anything.
    faced: Option<Faced>,
    /// The direction (x, z) from the box to the camera.
    camera: Vector2<f64>,
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
    // Without its asset (never in a planned scene), the box's own sides decide nothing.
    let size = infos.get(&object.id).map_or([1.0; 3], |i| i.size);
    let wall = backing_wall(architecture, b, size, wall_reach(object));
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
/// to face out of its wall (else by its `heading`: what it faces, else the camera), standing
/// on the floor or at the box's bottom, with the planned relations whose targets exist (`done`, the walls, the
/// ground) and the wall it stands against.
fn scene_object(
    scene: &Scene,
    object: &PlannedObject,
    b: &LiftedBox,
    info: &AssetInfo,
    (parent, support_kind, wall): Placed,
    done: &BTreeSet<String>,
    heading: Heading,
) -> SceneObject {
    let Heading { faced, camera } = heading;
    let [sx, sy, sz] = info.size.map(f64::from);
    let [lo, hi] = info.scale_range.map(f64::from);
    let scale = (b.size().y / sy.max(1e-6)).clamp(lo.min(hi), hi.max(lo));
    // What it faces decides before the wall behind it: a desk chair beside the side wall
    // still faces its desk.
    let backing = backing_wall(&scene.architecture, b, info.size, wall_reach(object));
    let yaw = match (&faced, backing) {
        (Some(f), _) => facing(b, f.direction, true),
        (None, Some((_, inward))) => facing(b, inward, false),
        (None, None) => facing(b, camera, false),
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
    if let Some(f) = faced.filter(|f| !f.planned && done.contains(&f.target)) {
        relations.push(Relation::new(RelationKind::Facing, f.target));
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

#[cfg(test)]
mod tests {
    use super::*;
    use scenethesis_scene_graph::yaw_distance;

    /// A room 4 m × 6 m (x from −2 to 2, z from −3 to 3) and the wall whose inward normal is
    /// `normal`.
    fn room_and_wall(normal: Vector2<f64>) -> (Architecture, String) {
        let room = Architecture::rectangular_room(4.0, 6.0, 2.6, 0.9);
        let id = room
            .walls
            .iter()
            .find(|w| (w.inward_normal() - normal).norm() < 1e-6)
            .expect("a wall with that normal")
            .id
            .clone();
        (room, id)
    }

    #[test]
    fn a_box_the_plan_puts_against_a_wall_backs_onto_it_from_farther() {
        // A standing mirror seen at the image's edge: its box 26 cm off the front wall.
        let (room, front) = room_and_wall(Vector2::new(0.0, -1.0));
        let mirror = LiftedBox::axis_aligned("mirror", [1.0, 0.85, 2.49], [0.38, 0.85, 0.25]);
        let size = [0.77, 1.69, 0.5];
        assert_eq!(backing_wall(&room, &mirror, size, WALL_GAP), None);
        let found = backing_wall(&room, &mirror, size, PLANNED_WALL_GAP);
        assert_eq!(found.map(|w| w.0), Some(front));
    }

    #[test]
    fn in_a_corner_an_oblong_asset_backs_onto_the_wall_along_its_back() {
        let shelf = [1.0, 1.8, 0.4];
        // A shelving unit in the back-right corner, its end 1 cm into the side wall.
        let b = LiftedBox::axis_aligned("shelf", [1.51, 0.9, -2.8], [0.5, 0.9, 0.2]);
        let (room, back) = room_and_wall(Vector2::new(0.0, 1.0));
        assert_eq!(
            backing_wall(&room, &b, shelf, WALL_GAP).map(|w| w.0),
            Some(back)
        );
        // A bed (long in its own z) in the same corner, its head against the side wall.
        let bed = LiftedBox::axis_aligned("bed", [0.99, 0.3, -2.2], [1.0, 0.3, 0.8]);
        let (_, side) = room_and_wall(Vector2::new(-1.0, 0.0));
        assert_eq!(
            backing_wall(&room, &bed, [1.6, 0.6, 2.0], WALL_GAP).map(|w| w.0),
            Some(side)
        );
    }

    #[test]
    fn a_box_deep_in_a_wall_backs_onto_it() {
        // Lifted a quarter turn off: its length pokes 30 cm into the side wall.
        let b = LiftedBox::axis_aligned("shelf", [1.8, 0.9, -2.7], [0.5, 0.9, 0.25]);
        let (room, side) = room_and_wall(Vector2::new(-1.0, 0.0));
        assert_eq!(
            backing_wall(&room, &b, [1.0, 1.8, 0.5], WALL_GAP).map(|w| w.0),
            Some(side)
        );
    }

    #[test]
    fn seating_faces_the_table_it_serves_even_turned_a_quarter() {
        // A square stool's box cannot tell a quarter turn: facing a target picks the turn.
        let stool = LiftedBox::axis_aligned("bar_stool_0", [0.0, 0.35, 0.0], [0.2, 0.35, 0.2]);
        let yaw = facing(&stool, Vector2::new(-1.0, 0.0), true);
        assert!(yaw_distance(yaw, -PI / 2.0) < 1e-9, "{yaw}");
        // Without a target only the half turn is free.
        let yaw = facing(&stool, Vector2::new(-1.0, 0.1), false);
        assert!(yaw_distance(yaw, 0.0) < 1e-9 || yaw_distance(yaw, PI) < 1e-9);
    }
}
