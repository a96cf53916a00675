//! One house room in its own frame: the rectangle the single-room stages furnish (the whole
//! room, or the largest rectangle of an L-shaped one), turned so that the door it is entered
//! by lies in its front wall (+z), with its real doors and windows and the floor they keep
//! clear.

use nalgebra::{Point2, Vector2, Vector3};
use scenethesis_agents::{KeepClear, Plan, Zone, BACK_WALL};
use scenethesis_floorplan::geometry::{contains, Rect};
use scenethesis_floorplan::{DoorKind, FloorPlan, Hinge, Room};
use scenethesis_scene_graph::{
    wrap_yaw, Architecture, DoorLeaf, DoorOpening, Environment, OpensTo, Pose, RelationKind,
    WindowOpening, WINDOW_CLEARANCE,
};

/// Wall thickness of a house (m), centred on the plan's wall lines, as a single room's.
pub(crate) const WALL_THICKNESS: f64 = 0.1;

/// Wall height of a house (m).
pub(crate) const WALL_HEIGHT: f64 = 2.7;

/// The free floor kept in front of every door on both sides (m), beyond its leaf's swing.
pub(crate) const DOOR_APPROACH: f64 = 0.6;

/// Height (m) of the opening left between the furnished rectangle of an L-shaped room and the
/// rest of it.
const OPEN_SIDE_HEIGHT: f64 = 2.1;

/// The index of a shell's front wall (+z), the one its entrance lies in.
const FRONT: usize = 2;

/// Distance (m) under which a point counts as lying on a line.
const ON_LINE: f64 = 1e-6;

/// A room's own frame: a house point is `rotate(yaw) · local + centre` in (x, z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct RoomFrame {
    /// The furnished rectangle's centre in the house, (x, z).
    pub(crate) centre: [f64; 2],
    /// The turn about +Y from the room's frame into the house (a multiple of 90°).
    pub(crate) yaw: f64,
}

impl RoomFrame {
    /// The house (x, z) of a point given in the room's frame.
    pub(crate) fn house_point(&self, x: f64, z: f64) -> [f64; 2] {
        let (s, c) = self.yaw.sin_cos();
        [
            self.centre[0] + c * x + s * z,
            self.centre[1] - s * x + c * z,
        ]
    }

    /// The room-frame (x, z) of a house point.
    pub(crate) fn local_point(&self, x: f64, z: f64) -> [f64; 2] {
        let (s, c) = self.yaw.sin_cos();
        let (dx, dz) = (x - self.centre[0], z - self.centre[1]);
        [c * dx - s * dz, s * dx + c * dz]
    }

    /// A pose of the room's frame moved into the house.
    pub(crate) fn pose_to_house(&self, pose: &Pose) -> Pose {
        let t = pose.translation;
        let [x, z] = self.house_point(t.x, t.z);
        Pose {
            scale: pose.scale,
            yaw: wrap_yaw(pose.yaw + self.yaw),
            translation: Vector3::new(x, t.y, z),
        }
    }

    /// A direction of the room's frame turned into the house.
    pub(crate) fn direction_to_house(&self, d: Vector2<f64>) -> Vector2<f64> {
        let (s, c) = self.yaw.sin_cos();
        Vector2::new(c * d.x + s * d.y, -s * d.x + c * d.y)
    }
}

/// A side of an axis-aligned rectangle, seen from above.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Side {
    /// z = max (+z).
    South,
    /// z = min (−z).
    North,
    /// x = max (+x).
    East,
    /// x = min (−x).
    West,
}

impl Side {
    const ALL: [Side; 4] = [Side::South, Side::North, Side::East, Side::West];

    /// The turn that brings the room frame's front (+z) onto this side.
    fn yaw(self) -> f64 {
        use std::f64::consts::FRAC_PI_2;
        match self {
            Side::South => 0.0,
            Side::North => std::f64::consts::PI,
            Side::East => FRAC_PI_2,
            Side::West => -FRAC_PI_2,
        }
    }

    /// Whether the (x, z) point lies on this side of `r` (within its span).
    fn holds(self, r: &Rect, p: Point2<f64>) -> bool {
        let within_x = (r.min.x - ON_LINE..=r.max.x + ON_LINE).contains(&p.x);
        let within_z = (r.min.y - ON_LINE..=r.max.y + ON_LINE).contains(&p.y);
        match self {
            Side::South => (p.y - r.max.y).abs() < ON_LINE && within_x,
            Side::North => (p.y - r.min.y).abs() < ON_LINE && within_x,
            Side::East => (p.x - r.max.x).abs() < ON_LINE && within_z,
            Side::West => (p.x - r.min.x).abs() < ON_LINE && within_z,
        }
    }

    /// The part of this side of `r` that is open to the rest of `polygon` (an L-shaped
    /// room's other arm), as (lo, hi) along the side, if any.
    fn open_span(self, r: &Rect, polygon: &[Point2<f64>]) -> Option<(f64, f64)> {
        let probe = 0.05;
        let (lo, hi) = match self {
            Side::South | Side::North => (r.min.x, r.max.x),
            Side::East | Side::West => (r.min.y, r.max.y),
        };
        let point = |t: f64| match self {
            Side::South => Point2::new(t, r.max.y + probe),
            Side::North => Point2::new(t, r.min.y - probe),
            Side::East => Point2::new(r.max.x + probe, t),
            Side::West => Point2::new(r.min.x - probe, t),
        };
        let steps = ((hi - lo) / 0.05).ceil().max(1.0) as usize;
        let open: Vec<f64> = (0..steps)
            .map(|k| lo + (hi - lo) * (k as f64 + 0.5) / steps as f64)
            .filter(|&t| contains(polygon, point(t)))
            .collect();
        let (first, last) = (*open.first()?, *open.last()?);
        let half = (hi - lo) / steps as f64 / 2.0;
        Some((first - half, last + half))
    }
}

/// The largest rectangle inside a rectilinear polygon whose corners lie on the polygon's
/// corner coordinates (the whole room for a rectangle, an arm of an L).
pub(crate) fn largest_rectangle(polygon: &[Point2<f64>]) -> Rect {
    let coords = |f: fn(&Point2<f64>) -> f64| {
        let mut v: Vec<f64> = polygon.iter().map(f).collect();
        v.sort_by(f64::total_cmp);
        v.dedup_by(|a, b| (*a - *b).abs() < ON_LINE);
        v
    };
    let (xs, zs) = (coords(|p| p.x), coords(|p| p.y));
    let cell_inside = |i: usize, j: usize| {
        let mid = Point2::new((xs[i] + xs[i + 1]) / 2.0, (zs[j] + zs[j + 1]) / 2.0);
        contains(polygon, mid)
    };
    let mut best = Rect::new(xs[0], zs[0], xs[0], zs[0]);
    for i0 in 0..xs.len() - 1 {
        for i1 in i0 + 1..xs.len() {
            for j0 in 0..zs.len() - 1 {
                for j1 in j0 + 1..zs.len() {
                    let all = (i0..i1).all(|i| (j0..j1).all(|j| cell_inside(i, j)));
                    let r = Rect::new(xs[i0], zs[j0], xs[i1], zs[j1]);
                    if all && r.area() > best.area() + ON_LINE {
                        best = r;
                    }
                }
            }
        }
    }
    best
}

/// A house room as the single-room stages see it: its frame, its floor size and its shell.
#[derive(Debug, Clone)]
pub(crate) struct RoomShell {
    /// The room's id in the floor plan.
    pub(crate) id: String,
    /// Where the room's frame sits in the house.
    pub(crate) frame: RoomFrame,
    /// The furnished floor, width (x) × depth (z) in the room's frame, m.
    pub(crate) size: [f64; 2],
    /// Walls, doors and windows in the room's frame.
    pub(crate) architecture: Architecture,
    /// The floor the doors and windows keep clear, in the room's frame.
    pub(crate) keep_clear: Vec<KeepClear>,
}

impl RoomShell {
    /// The shell of `room` of `plan`, entered by the door `entry` (its id).
    pub(crate) fn of(plan: &FloorPlan, room: &Room, entry: Option<&str>) -> Self {
        let rect = largest_rectangle(&room.polygon);
        let entry_centre = entry
            .and_then(|id| plan.doors.iter().find(|d| d.id == id))
            .map(|d| d.centre);
        let front = Side::ALL
            .into_iter()
            .find(|s| entry_centre.is_some_and(|c| s.holds(&rect, c)))
            .or_else(|| {
                Side::ALL
                    .into_iter()
                    .find(|s| s.open_span(&rect, &room.polygon).is_some())
            })
            .unwrap_or(Side::South);
        let frame = RoomFrame {
            centre: [
                (rect.min.x + rect.max.x) / 2.0,
                (rect.min.y + rect.max.y) / 2.0,
            ],
            yaw: front.yaw(),
        };
        let (w, d) = (rect.width() - WALL_THICKNESS, rect.depth() - WALL_THICKNESS);
        let size = if matches!(front, Side::East | Side::West) {
            [d, w]
        } else {
            [w, d]
        };
        let mut shell = Self {
            id: room.id.clone(),
            frame,
            size,
            architecture: Architecture::rectangular_room(size[0], size[1], WALL_HEIGHT, 0.9),
            keep_clear: Vec::new(),
        };
        shell.architecture.doors.clear();
        shell.add_doors(plan, room, &rect, entry);
        shell.add_open_sides(room, &rect);
        shell.add_windows(plan, room, &rect);
        shell
    }

    /// The wall of the shell (its index) holding the room-frame point `p` on a wall's centre
    /// line, and the offset of `p` along it.
    fn wall_at(&self, p: [f64; 2]) -> Option<(usize, f64)> {
        let (ox, oz) = (
            (self.size[0] + WALL_THICKNESS) / 2.0,
            (self.size[1] + WALL_THICKNESS) / 2.0,
        );
        let near = |a: f64, b: f64| (a - b).abs() < 1e-4;
        if near(p[1], -oz) {
            Some((0, ox - p[0]))
        } else if near(p[0], -ox) {
            Some((1, p[1] + oz))
        } else if near(p[1], oz) {
            Some((2, p[0] + ox))
        } else if near(p[0], ox) {
            Some((3, oz - p[1]))
        } else {
            None
        }
    }

    /// A keep-clear rectangle `depth` m deep into the room in front of the opening at
    /// `offset` (width `width`) of wall `wall`.
    fn zone_before(
        &self,
        wall: usize,
        offset: f64,
        width: f64,
        depth: f64,
    ) -> ([f64; 2], [f64; 2]) {
        let w = &self.architecture.walls[wall];
        let dir = w.direction();
        let n = w.inward_normal();
        let face = w.start + dir * offset + n * (WALL_THICKNESS / 2.0);
        let a = face - dir * (width / 2.0);
        let b = face + dir * (width / 2.0) + n * depth;
        ([a.x.min(b.x), a.y.min(b.y)], [a.x.max(b.x), a.y.max(b.y)])
    }

    /// The plan's doors on the furnished rectangle, as openings of the shell with the floor
    /// their leaves sweep and their approach kept clear; the area of the door `entry` (in the
    /// front wall) is the room's entrance.
    fn add_doors(&mut self, plan: &FloorPlan, room: &Room, rect: &Rect, entry: Option<&str>) {
        for door in plan.doors_of(&room.id) {
            if !Side::ALL.iter().any(|s| s.holds(rect, door.centre)) {
                continue;
            }
            let local = self.frame.local_point(door.centre.x, door.centre.y);
            let Some((wall, offset)) = self.wall_at(local) else {
                continue;
            };
            let swings_in = door.swing.as_ref().is_some_and(|s| s.into == room.id);
            let leaf = door
                .swing
                .as_ref()
                .filter(|_| swings_in && door.kind != DoorKind::Passage)
                .map(|s| leaf_of(s.hinge));
            let sweep = match (swings_in, door.kind) {
                (true, DoorKind::Single) => door.width,
                (true, DoorKind::Double) => door.width / 2.0,
                _ => 0.0,
            };
            let (min, max) =
                self.zone_before(wall, offset, door.width + 0.2, sweep.max(DOOR_APPROACH));
            self.keep_clear.push(KeepClear {
                why: format!("{} swing and approach", door.id),
                min,
                max,
                below: None,
                entrance: wall == FRONT && entry == Some(door.id.as_str()),
            });
            let wall_id = self.architecture.walls[wall].id.clone();
            self.architecture.doors.push(DoorOpening {
                id: door.id.clone(),
                wall: wall_id,
                offset,
                width: door.width,
                height: door.height.min(WALL_HEIGHT),
                leaf,
                joins: Some(door.rooms.clone()),
            });
        }
    }

    /// The sides of the furnished rectangle open to the rest of an L-shaped room: an opening
    /// in the shell's wall there, with a walkway kept clear along it.
    fn add_open_sides(&mut self, room: &Room, rect: &Rect) {
        for side in Side::ALL {
            let Some((lo, hi)) = side.open_span(rect, &room.polygon) else {
                continue;
            };
            let (lo, hi) = (lo + 0.1, hi - 0.1);
            if hi - lo < 0.6 {
                continue;
            }
            let mid = (lo + hi) / 2.0;
            let centre = match side {
                Side::South => [mid, rect.max.y],
                Side::North => [mid, rect.min.y],
                Side::East => [rect.max.x, mid],
                Side::West => [rect.min.x, mid],
            };
            let local = self.frame.local_point(centre[0], centre[1]);
            let Some((wall, offset)) = self.wall_at(local) else {
                continue;
            };
            let (min, max) = self.zone_before(wall, offset, hi - lo, DOOR_APPROACH);
            let id = format!("{}_open_{}", room.id, self.architecture.doors.len());
            self.keep_clear.push(KeepClear {
                why: format!("{id}: the way into the rest of the room"),
                min,
                max,
                below: None,
                // The way in when the room is entered through its other part.
                entrance: wall == FRONT && !self.keep_clear.iter().any(|k| k.entrance),
            });
            self.architecture.doors.push(DoorOpening {
                id,
                wall: self.architecture.walls[wall].id.clone(),
                offset,
                width: hi - lo,
                height: OPEN_SIDE_HEIGHT,
                leaf: None,
                joins: Some([room.id.clone(), room.id.clone()]),
            });
        }
    }

    /// The plan's windows on the furnished rectangle, with the floor before them kept free of
    /// anything that would cover them ([`WindowOpening::cover_height`]).
    fn add_windows(&mut self, plan: &FloorPlan, room: &Room, rect: &Rect) {
        for window in plan.windows.iter().filter(|w| w.room == room.id) {
            if !Side::ALL.iter().any(|s| s.holds(rect, window.centre)) {
                continue;
            }
            let local = self.frame.local_point(window.centre.x, window.centre.y);
            let Some((wall, offset)) = self.wall_at(local) else {
                continue;
            };
            let (min, max) = self.zone_before(wall, offset, window.width, WINDOW_CLEARANCE);
            let opening = WindowOpening {
                id: window.id.clone(),
                wall: self.architecture.walls[wall].id.clone(),
                offset,
                width: window.width,
                height: window.height,
                sill: window.sill,
                room: None,
            };
            self.keep_clear.push(KeepClear {
                why: window.id.clone(),
                min,
                max,
                below: Some(opening.cover_height()),
                entrance: false,
            });
            self.architecture.windows.push(opening);
        }
    }

    /// Fits a plan to this shell: its room size, wall height and the floor kept clear, and
    /// the anchor free to stand against any wall ([`any_wall_anchor`]).
    pub(crate) fn fit_plan(&self, plan: &mut Plan) {
        plan.environment = Environment::Indoor;
        plan.room_size = self.size;
        plan.wall_height = WALL_HEIGHT;
        plan.keep_clear = self.keep_clear.clone();
        any_wall_anchor(plan);
    }
}

/// Lets a wall anchor the planner put on the back wall by default (a bedroom's bed) stand
/// against any wall: in a house room's fixed walls the back wall may be all doorway and
/// window, and a bed on a side wall beats a bedroom without one. The guide still tries the
/// back wall first ([`Zone::Wall`] without a wall); an anchor the prompt puts on another wall
/// keeps it.
fn any_wall_anchor(plan: &mut Plan) {
    let anchor = plan.anchor.clone();
    let Some(o) = plan.objects.iter_mut().find(|o| o.id == anchor) else {
        return;
    };
    if o.zone
        == (Zone::Wall {
            wall: Some(BACK_WALL.to_owned()),
        })
    {
        o.zone = Zone::Wall { wall: None };
        o.relations
            .retain(|r| !(r.kind == RelationKind::AgainstWall && r.target == BACK_WALL));
    }
}

/// The scene-graph leaf of a plan door hinged on `hinge` (seen from the room it opens into, as
/// [`DoorLeaf::opens_to`] is): two mirrored leaves for a double door ([`Hinge::Both`]).
pub(crate) fn leaf_of(hinge: Hinge) -> DoorLeaf {
    DoorLeaf {
        opens_to: match hinge {
            Hinge::Right => OpensTo::Right,
            Hinge::Left | Hinge::Both => OpensTo::Left,
        },
        double: hinge == Hinge::Both,
        ..DoorLeaf::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_round_trips_and_turns_front_onto_its_side() {
        for side in Side::ALL {
            let frame = RoomFrame {
                centre: [3.0, 2.0],
                yaw: side.yaw(),
            };
            let [x, z] = frame.house_point(0.4, -1.3);
            let back = frame.local_point(x, z);
            assert!((back[0] - 0.4).abs() < 1e-9 && (back[1] + 1.3).abs() < 1e-9);
            let front = frame.direction_to_house(Vector2::new(0.0, 1.0));
            let expected = match side {
                Side::South => [0.0, 1.0],
                Side::North => [0.0, -1.0],
                Side::East => [1.0, 0.0],
                Side::West => [-1.0, 0.0],
            };
            assert!((front.x - expected[0]).abs() < 1e-9, "{side:?}");
            assert!((front.y - expected[1]).abs() < 1e-9, "{side:?}");
        }
    }

    #[test]
    fn largest_rectangle_of_an_l_is_its_bigger_arm() {
        let l = [
            Point2::new(0.0, 0.0),
            Point2::new(4.0, 0.0),
            Point2::new(4.0, 2.0),
            Point2::new(1.5, 2.0),
            Point2::new(1.5, 5.0),
            Point2::new(0.0, 5.0),
        ];
        let r = largest_rectangle(&l);
        assert_eq!((r.min.x, r.min.y, r.max.x, r.max.y), (0.0, 0.0, 4.0, 2.0));
        let side = Side::South.open_span(&r, &l).unwrap();
        assert!(
            (side.0 - 0.0).abs() < 0.06 && (side.1 - 1.5).abs() < 0.06,
            "{side:?}"
        );
        assert!(Side::East.open_span(&r, &l).is_none());
    }
}
