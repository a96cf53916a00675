//! Geometric checks of scene relations, for tests, the judge and reports.

use crate::{Aabb, Relation, RelationKind, Scene, SceneObject, GROUND_ID, LOW_SHELF_SHARE};
use nalgebra::Vector2;

/// Tolerance for resting contact, in metres.
const CONTACT: f64 = 0.02;

/// The centre of `o`'s world box on the floor plane (x, z).
pub fn floor_centre(o: &SceneObject) -> Vector2<f64> {
    let c = o.world_aabb().center();
    Vector2::new(c.x, c.z)
}

/// `o`'s front (its local +Z) on the floor plane (x, z), a unit vector.
pub fn front_dir(o: &SceneObject) -> Vector2<f64> {
    Vector2::new(o.pose.yaw.sin(), o.pose.yaw.cos())
}

/// `o`'s right-hand side (its local +X) on the floor plane (x, z), a unit vector.
pub fn right_dir(o: &SceneObject) -> Vector2<f64> {
    Vector2::new(o.pose.yaw.cos(), -o.pose.yaw.sin())
}

fn within_xz(o: &SceneObject, t: &SceneObject) -> bool {
    let (c, b) = (floor_centre(o), t.world_aabb());
    b.min.x - CONTACT <= c.x
        && c.x <= b.max.x + CONTACT
        && b.min.z - CONTACT <= c.y
        && c.y <= b.max.z + CONTACT
}

/// The gap between the world boxes of `a` and `b` on the floor plane (x, z), in metres: 0 when
/// their footprints touch or overlap. *Beside* and *around* are bounds on it.
pub fn floor_gap(a: &SceneObject, b: &SceneObject) -> f64 {
    aabb_floor_gap(&a.world_aabb(), &b.world_aabb())
}

/// The gap between two world boxes on the floor plane (x, z), in metres: 0 when they touch or
/// overlap there. [`floor_gap`] of two objects is this of their world boxes; a layout step that
/// has only boxes measures with it what the relation checks will measure.
pub fn aabb_floor_gap(a: &Aabb, b: &Aabb) -> f64 {
    let dx = (b.min.x - a.max.x).max(a.min.x - b.max.x).max(0.0);
    let dz = (b.min.z - a.max.z).max(a.min.z - b.max.z).max(0.0);
    (dx * dx + dz * dz).sqrt()
}

/// How far (radians) an object's front may turn from the direction to what it faces and
/// still face it: 50°.
pub const FACING_TOLERANCE: f64 = 50.0 * std::f64::consts::PI / 180.0;

fn faces(o: &SceneObject, t: &SceneObject) -> bool {
    let d = floor_centre(t) - floor_centre(o);
    d.norm() > 1e-9 && front_dir(o).dot(&d.normalize()) >= FACING_TOLERANCE.cos()
}

/// How much further toward `direction` (a unit floor vector) the box of `o` reaches than the
/// ellipse inscribed in it: 0 for a box square to `direction`, up to 41 % of the half extent
/// for a square box turned by 45°. The relation checks see only boxes, and a turned round
/// object (a plant pot, a barrel) touching a wall has its box's corners in the wall; they are
/// not the object's (the collision metrics check its real geometry).
fn turned_corner_reach(o: &SceneObject, direction: &Vector2<f64>) -> f64 {
    let half = o.local_bounds.size() * o.pose.scale / 2.0;
    let (along, across) = (
        front_dir(o).dot(direction).abs(),
        right_dir(o).dot(direction).abs(),
    );
    let boxed = half.z * along + half.x * across;
    let inscribed = ((half.z * along).powi(2) + (half.x * across).powi(2)).sqrt();
    (boxed - inscribed).max(0.0)
}

/// Whether `relation` of object `subject` holds in `scene`'s geometry (world boxes and
/// poses), or `None` if the subject or target does not exist.
///
/// Conventions: *on* rests above the target's bottom and at most at its top; *inside* starts
/// below the target's top; *under* stays below the top and starts in the lowest 35 % of the
/// target's height ([`LOW_SHELF_SHARE`]) (the floor beneath a table or its low shelf); all three need the subject's
/// centre over the target's box. *Left of* / *right of* are seen facing the target's front
/// (left = the target's local −X); *facing* allows 50° of yaw error; *beside* and *around*
/// need the boxes within 1 m and 0.6 m; *against-wall* needs the back within 0.1 m of the
/// wall's inner face and not more than 2 cm into it beyond where a turned box's corners reach
/// past its inscribed outline (target `ground` means any wall); *mounted* needs the same of the
/// target wall and the bottom off the floor (more than the 2 cm contact tolerance above it).
pub fn relation_holds(scene: &Scene, subject: &str, relation: &Relation) -> Option<bool> {
    let o = scene.object(subject)?;
    let ob = o.world_aabb();
    if relation.kind == RelationKind::OnFloor {
        return Some(ob.min.y.abs() <= CONTACT);
    }
    if matches!(
        relation.kind,
        RelationKind::AgainstWall | RelationKind::Mounted
    ) {
        let walls: Vec<_> = if relation.target == GROUND_ID {
            scene.architecture.walls.iter().collect()
        } else {
            vec![scene.architecture.wall(&relation.target)?]
        };
        let backed = walls.iter().any(|w| {
            let n = w.inward_normal();
            let face = w.start + n * (w.thickness / 2.0);
            let nearest = ob
                .corners()
                .iter()
                .map(|c| (Vector2::new(c.x, c.z) - face.coords).dot(&n))
                .fold(f64::MAX, f64::min);
            (-CONTACT - turned_corner_reach(o, &n)..=0.1).contains(&nearest)
        });
        let off_floor = relation.kind == RelationKind::AgainstWall || ob.min.y > CONTACT;
        return Some(backed && off_floor);
    }
    let t = scene.object(&relation.target)?;
    let tb = t.world_aabb();
    let d = floor_centre(o) - floor_centre(t);
    let t_half = |dir: Vector2<f64>| {
        let s = t.local_bounds.size() * t.pose.scale / 2.0;
        s.x * right_dir(t).dot(&dir).abs() + s.z * front_dir(t).dot(&dir).abs()
    };
    Some(match relation.kind {
        RelationKind::On => {
            within_xz(o, t) && ob.min.y > tb.min.y + 1e-3 && ob.min.y <= tb.max.y + CONTACT
        }
        RelationKind::Inside => {
            within_xz(o, t) && ob.min.y >= tb.min.y - CONTACT && ob.min.y < tb.max.y - CONTACT
        }
        RelationKind::Under => {
            within_xz(o, t)
                && ob.max.y <= tb.max.y + CONTACT
                && ob.min.y <= tb.min.y + LOW_SHELF_SHARE * (tb.max.y - tb.min.y)
        }
        RelationKind::InFrontOf => {
            d.dot(&front_dir(t)) > 0.0 && d.dot(&right_dir(t)).abs() <= t_half(right_dir(t)) + 0.5
        }
        RelationKind::Behind => {
            d.dot(&front_dir(t)) < 0.0 && d.dot(&right_dir(t)).abs() <= t_half(right_dir(t)) + 0.5
        }
        RelationKind::Beside => floor_gap(o, t) <= 1.0,
        RelationKind::LeftOf => d.dot(&right_dir(t)) < 0.0,
        RelationKind::RightOf => d.dot(&right_dir(t)) > 0.0,
        RelationKind::Facing => faces(o, t),
        RelationKind::Around => floor_gap(o, t) <= 0.6 && faces(o, t),
        RelationKind::OnFloor | RelationKind::AgainstWall | RelationKind::Mounted => {
            unreachable!("handled above")
        }
    })
}
