//! The house's architecture from its floor plan: the plan's centre-line walls as [`Wall`]s
//! (each turned so that the leaves of its doors swing to its inward side), its doors and
//! windows as openings in them, and every room's floor outline.

use nalgebra::{Point2, Vector2};
use scenethesis_floorplan::{walls, DoorKind, FloorPlan, Room, Wall as PlanWall};
use scenethesis_scene_graph::{
    Architecture, DoorOpening, Environment, Floor, RoomArea, Wall, WindowOpening,
};

use super::frame::{leaf_of, WALL_HEIGHT, WALL_THICKNESS};

/// The architecture of `plan`, whose footprint is `footprint` (`[min x, min z, max x, max z]`
/// of the wall centre lines): the floor inside the exterior walls, every wall, door and
/// window, and the rooms' floors (each outline inset by half a wall).
pub(crate) fn house_architecture(plan: &FloorPlan, footprint: [f64; 4]) -> Architecture {
    let half = WALL_THICKNESS / 2.0;
    let plan_walls: Vec<PlanWall> = walls(plan).into_iter().map(|w| turned(plan, w)).collect();
    let doors = plan
        .doors
        .iter()
        .filter_map(|door| {
            let wall = plan_walls.iter().find(|w| w.openings.contains(&door.id))?;
            let swings = door.kind != DoorKind::Passage;
            Some(DoorOpening {
                id: door.id.clone(),
                wall: wall.id.clone(),
                offset: (door.centre - wall.start).norm(),
                width: door.width,
                height: door.height.min(WALL_HEIGHT),
                leaf: door
                    .swing
                    .as_ref()
                    .filter(|_| swings)
                    .map(|s| leaf_of(s.hinge)),
                joins: Some(door.rooms.clone()),
            })
        })
        .collect();
    let windows = plan
        .windows
        .iter()
        .filter_map(|window| {
            let wall = plan_walls
                .iter()
                .find(|w| w.openings.contains(&window.id))?;
            Some(WindowOpening {
                id: window.id.clone(),
                wall: wall.id.clone(),
                offset: (window.centre - wall.start).norm(),
                width: window.width,
                height: window.height,
                sill: window.sill,
                room: Some(window.room.clone()),
            })
        })
        .collect();
    Architecture {
        environment: Environment::Indoor,
        floor: Floor {
            id: "floor".into(),
            min: Point2::new(footprint[0] + half, footprint[1] + half),
            max: Point2::new(footprint[2] - half, footprint[3] - half),
        },
        walls: plan_walls
            .iter()
            .map(|w| Wall {
                id: w.id.clone(),
                start: w.start,
                end: w.end,
                height: WALL_HEIGHT,
                thickness: WALL_THICKNESS,
            })
            .collect(),
        doors,
        windows,
        rooms: plan.rooms.iter().map(room_area).collect(),
    }
}

/// `wall` turned end for end when the leaf of a door in it swings into the room on its right
/// (a door leaf swings to its wall's inward side, `rooms[0]`). Exterior walls keep their
/// room on the left, as no leaf swings outside.
fn turned(plan: &FloorPlan, mut wall: PlanWall) -> PlanWall {
    let swings_right = plan
        .doors
        .iter()
        .filter(|d| wall.openings.contains(&d.id) && d.kind != DoorKind::Passage)
        .filter_map(|d| d.swing.as_ref())
        .any(|s| s.into == wall.rooms[1]);
    if swings_right && !wall.is_exterior() {
        std::mem::swap(&mut wall.start, &mut wall.end);
        wall.rooms.swap(0, 1);
    }
    wall
}

/// The floor of a plan room: its outline inset by half a wall (the walls' inner faces), in the
/// winding scene-graph's walls use (the room on the left of each edge).
pub(crate) fn room_area(room: &Room) -> RoomArea {
    let mut polygon = room.polygon.clone();
    if signed_area(&polygon) > 0.0 {
        polygon.reverse();
    }
    RoomArea {
        id: room.id.clone(),
        room_type: room.room_type.clone(),
        polygon: inset(&polygon, WALL_THICKNESS / 2.0),
    }
}

/// Twice the signed area of a polygon in (x, z) (shoelace); negative when each edge has the
/// inside on its left as scene-graph's walls do.
fn signed_area(polygon: &[Point2<f64>]) -> f64 {
    (0..polygon.len())
        .map(|i| {
            let (a, b) = (polygon[i], polygon[(i + 1) % polygon.len()]);
            a.x * b.y - b.x * a.y
        })
        .sum()
}

/// An axis-aligned polygon with the inside on the left of each edge, every edge moved `by`
/// towards the inside.
fn inset(polygon: &[Point2<f64>], by: f64) -> Vec<Point2<f64>> {
    let n = polygon.len();
    let inward = |i: usize| -> Vector2<f64> {
        let d = (polygon[(i + 1) % n] - polygon[i]).normalize();
        Vector2::new(d.y, -d.x)
    };
    (0..n)
        .map(|i| polygon[i] + (inward((i + n - 1) % n) + inward(i)) * by)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_inset_l_keeps_its_shape_half_a_wall_in() {
        let room = Room {
            id: "living_room".into(),
            room_type: "living_room".into(),
            polygon: vec![
                Point2::new(0.0, 0.0),
                Point2::new(4.0, 0.0),
                Point2::new(4.0, 2.0),
                Point2::new(1.5, 2.0),
                Point2::new(1.5, 5.0),
                Point2::new(0.0, 5.0),
            ],
        };
        let area = room_area(&room);
        assert!(signed_area(&area.polygon) < 0.0);
        // 4 × 5 minus the 2.5 × 3 notch, each outline edge 5 cm in.
        let expected = 3.9 * 1.9 + 1.4 * 3.0;
        assert!((area.area() - expected).abs() < 1e-9, "{}", area.area());
        assert!(area.contains_xz(0.1, 4.9));
        assert!(!area.contains_xz(0.02, 4.0));
        assert!(!area.contains_xz(3.0, 3.0));
    }
}
