use nalgebra::{Point2, Point3, Vector2};
use serde::{Deserialize, Serialize};

use crate::{Aabb, DoorLeaf};

/// Whether the scene is a closed room or open ground.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Environment {
    /// A room with walls and at least one door opening.
    #[default]
    Indoor,
    /// Open ground (beach, park, campsite): a floor area and no walls.
    Outdoor,
}

/// The static parts of a scene: floor, walls and door openings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct Architecture {
    /// Indoor room or outdoor ground.
    pub environment: Environment,
    /// The walkable ground rectangle at y = 0.
    pub floor: Floor,
    /// Wall segments standing on the floor.
    #[serde(default)]
    pub walls: Vec<Wall>,
    /// Openings cut into walls.
    #[serde(default)]
    pub doors: Vec<DoorOpening>,
    /// Windows cut into walls (none in scenes written before windows existed).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub windows: Vec<WindowOpening>,
    /// The rooms of a house, each with its floor outline; empty for a single-room scene, whose
    /// one room is the whole [`Floor`].
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub rooms: Vec<RoomArea>,
}

/// The name a door's [`DoorOpening::joins`] uses for the outside of the building.
pub const EXTERIOR: &str = "exterior";

/// One room of a house: its id, its type and its floor outline at y = 0.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RoomArea {
    /// Stable id, unique in the scene (e.g. `bedroom_1`); the `room` every object in it names.
    pub id: String,
    /// The room type (e.g. `bedroom`, `kitchen`), as the dwelling knowledge names it.
    #[serde(rename = "type")]
    pub room_type: String,
    /// The floor outline in (x, z), m: the walls' inner faces, every edge parallel to x or z
    /// (rectangles and L-shapes), counter-clockwise seen from above.
    pub polygon: Vec<Point2<f64>>,
}

impl RoomArea {
    /// A rectangular room from its floor's corners `min` and `max` in (x, z), m, its outline
    /// counter-clockwise seen from above.
    ///
    /// ```
    /// use scenethesis_scene_graph::RoomArea;
    /// let bath = RoomArea::rectangle("bath_0", "bathroom", [0.0, -2.0], [3.0, 2.0]);
    /// assert!(bath.contains_xz(1.0, 0.5) && !bath.contains_xz(3.5, 0.5));
    /// assert_eq!(bath.polygon.len(), 4);
    /// ```
    pub fn rectangle(id: &str, room_type: &str, min: [f64; 2], max: [f64; 2]) -> Self {
        let corners = [
            (min[0], min[1]),
            (max[0], min[1]),
            (max[0], max[1]),
            (min[0], max[1]),
        ];
        Self {
            id: id.into(),
            room_type: room_type.into(),
            polygon: corners.iter().map(|&(x, z)| Point2::new(x, z)).collect(),
        }
    }

    /// Whether the (x, z) point lies inside the outline (even-odd rule; a point on an edge
    /// may count either way).
    pub fn contains_xz(&self, x: f64, z: f64) -> bool {
        let poly = &self.polygon;
        let mut inside = false;
        for i in 0..poly.len() {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            if (a.y > z) != (b.y > z) && x < a.x + (z - a.y) / (b.y - a.y) * (b.x - a.x) {
                inside = !inside;
            }
        }
        inside
    }

    /// The corners `(min, max)` in (x, z) of the outline's bounding box; `None` for an empty
    /// outline.
    ///
    /// ```
    /// use scenethesis_scene_graph::RoomArea;
    /// let bath = RoomArea::rectangle("bath_0", "bathroom", [0.0, -2.0], [3.0, 2.0]);
    /// let (min, max) = bath.bounds().unwrap();
    /// assert_eq!((min.x, min.y, max.x, max.y), (0.0, -2.0, 3.0, 2.0));
    /// ```
    pub fn bounds(&self) -> Option<(Point2<f64>, Point2<f64>)> {
        let first = *self.polygon.first()?;
        Some(
            self.polygon
                .iter()
                .fold((first, first), |(lo, hi), p| (lo.inf(p), hi.sup(p))),
        )
    }

    /// The outline's area in m² (shoelace formula; positive for either winding).
    pub fn area(&self) -> f64 {
        let poly = &self.polygon;
        let twice: f64 = (0..poly.len())
            .map(|i| {
                let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
                a.x * b.y - b.x * a.y
            })
            .sum();
        twice.abs() / 2.0
    }
}

/// A window cut into a wall: an opening from `sill` to `sill + height` above the floor, glazed
/// with a pane.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WindowOpening {
    /// Stable id (e.g. `window_0`), also the glTF node name of its pane.
    pub id: String,
    /// Id of the wall holding the opening.
    pub wall: String,
    /// Distance along the wall from its `start` to the opening's centre, in metres.
    pub offset: f64,
    /// Opening width along the wall in metres.
    pub width: f64,
    /// Opening height in metres.
    pub height: f64,
    /// Height of the opening's bottom above the floor in metres.
    pub sill: f64,
    /// Id of the room it lights ([`RoomArea::id`]); `None` in a single-room scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub room: Option<String>,
}

/// The floor: an axis-aligned rectangle on the plane y = 0, given in (x, z).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Floor {
    /// Stable id, also the glTF node name (usually `floor`).
    pub id: String,
    /// Corner with the smallest x and z.
    pub min: Point2<f64>,
    /// Corner with the largest x and z.
    pub max: Point2<f64>,
}

impl Default for Floor {
    fn default() -> Self {
        Self {
            id: "floor".into(),
            min: Point2::new(-2.0, -2.0),
            max: Point2::new(2.0, 2.0),
        }
    }
}

impl Floor {
    /// Width along x and depth along z.
    pub fn extent(&self) -> Vector2<f64> {
        self.max - self.min
    }

    /// Whether the (x, z) point lies on the floor rectangle.
    pub fn contains_xz(&self, x: f64, z: f64) -> bool {
        self.min.x <= x && x <= self.max.x && self.min.y <= z && z <= self.max.y
    }
}

/// A straight wall segment standing on the floor, its centre line running from `start` to `end`
/// in (x, z). The side facing the room is to the left when walking from `start` to `end`
/// (so walls listed counter-clockwise seen from above enclose the room).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Wall {
    /// Stable id, also the glTF node name (e.g. `wall_0`).
    pub id: String,
    /// Start of the centre line in (x, z).
    pub start: Point2<f64>,
    /// End of the centre line in (x, z).
    pub end: Point2<f64>,
    /// Height above the floor in metres.
    pub height: f64,
    /// Thickness in metres, centred on the centre line.
    pub thickness: f64,
}

/// How high (m) the bottom of an object with nothing beneath it must be for it to hang on a
/// wall rather than be a floor object lifted wrongly.
pub const MOUNT_MIN_BOTTOM: f64 = 0.3;

/// How far (m) an object's back may be from a wall's face, either side, and still hang on it:
/// lifted boxes are a few centimetres off, and a frame sits proud of the wall.
pub const MOUNT_WALL_REACH: f64 = 0.12;

/// Whether an object with nothing beneath it hangs on a wall: its bottom, `bottom` m above the
/// floor, is above [`MOUNT_MIN_BOTTOM`], and its back, `gap` m in front of the wall's face
/// (negative: behind it), is within [`MOUNT_WALL_REACH`] of that face. The one rule behind
/// wall mounting in the vision reader and in the evaluation of foreign scenes.
pub fn hangs_on_wall(bottom: f64, gap: f64) -> bool {
    bottom > MOUNT_MIN_BOTTOM && gap.abs() <= MOUNT_WALL_REACH
}

impl Wall {
    /// Length of the centre line.
    pub fn length(&self) -> f64 {
        (self.end - self.start).norm()
    }

    /// Unit direction from `start` to `end` in (x, z).
    pub fn direction(&self) -> Vector2<f64> {
        (self.end - self.start).normalize()
    }

    /// Unit normal in (x, z) pointing into the room (left of the direction of travel, seen
    /// from above with +Y up: for direction (dx, dz) the left side is (dz, -dx)).
    pub fn inward_normal(&self) -> Vector2<f64> {
        let d = self.direction();
        Vector2::new(d.y, -d.x)
    }

    /// The wall's world-space box (exact for axis-aligned walls).
    pub fn aabb(&self) -> Aabb {
        let half = self.thickness / 2.0;
        let n = self.inward_normal() * half;
        let d = self.direction() * half;
        let pts = [
            self.start - d + n,
            self.start - d - n,
            self.end + d + n,
            self.end + d - n,
        ];
        let lo = pts
            .iter()
            .fold(Point2::new(f64::MAX, f64::MAX), |a, p| a.inf(p));
        let hi = pts
            .iter()
            .fold(Point2::new(f64::MIN, f64::MIN), |a, p| a.sup(p));
        Aabb::new(
            Point3::new(lo.x, 0.0, lo.y),
            Point3::new(hi.x, self.height, hi.y),
        )
    }
}

/// A door opening cut into a wall, from the floor up to `height`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DoorOpening {
    /// Stable id (e.g. `door_0`).
    pub id: String,
    /// Id of the wall holding the opening.
    pub wall: String,
    /// Distance along the wall from its `start` to the opening's centre, in metres.
    pub offset: f64,
    /// Opening width in metres.
    pub width: f64,
    /// Opening height in metres.
    pub height: f64,
    /// The leaf hung in the opening, or `None` for an empty opening (scenes written before
    /// leaves existed read as such).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub leaf: Option<DoorLeaf>,
    /// The two rooms it joins ([`RoomArea::id`]s, one may be [`EXTERIOR`]) in a house; `None`
    /// in a single-room scene, whose doors lead outside. A leaf swings into the room on its
    /// wall's inward side.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub joins: Option<[String; 2]>,
}

impl Architecture {
    /// A closed rectangular room of the given size centred on the origin, with four walls
    /// (`wall_0` … `wall_3`, counter-clockwise from the back wall at −z) and one door opening
    /// `door_0` of the given width in the middle of the front wall (+z), its leaf
    /// ([`DoorLeaf::default`]) closed, hinged on the left seen from the room.
    pub fn rectangular_room(width_x: f64, depth_z: f64, wall_height: f64, door_width: f64) -> Self {
        let (hx, hz) = (width_x / 2.0, depth_z / 2.0);
        let t = 0.1;
        // Centre lines sit half a thickness outside the floor so the inner faces bound it.
        let (ox, oz) = (hx + t / 2.0, hz + t / 2.0);
        let corners = [
            Point2::new(ox, -oz),
            Point2::new(-ox, -oz),
            Point2::new(-ox, oz),
            Point2::new(ox, oz),
        ];
        let walls: Vec<Wall> = (0..4)
            .map(|i| Wall {
                id: format!("wall_{i}"),
                start: corners[i],
                end: corners[(i + 1) % 4],
                height: wall_height,
                thickness: t,
            })
            .collect();
        let front = &walls[2];
        let doors = vec![DoorOpening {
            id: "door_0".into(),
            wall: front.id.clone(),
            offset: front.length() / 2.0,
            width: door_width,
            height: 2.1_f64.min(wall_height),
            leaf: Some(DoorLeaf::default()),
            joins: None,
        }];
        Self {
            environment: Environment::Indoor,
            floor: Floor {
                id: "floor".into(),
                min: Point2::new(-hx, -hz),
                max: Point2::new(hx, hz),
            },
            walls,
            doors,
            windows: Vec::new(),
            rooms: Vec::new(),
        }
    }

    /// Open ground of the given size centred on the origin, with no walls.
    pub fn open_ground(width_x: f64, depth_z: f64) -> Self {
        Self {
            environment: Environment::Outdoor,
            floor: Floor {
                id: "ground_plane".into(),
                min: Point2::new(-width_x / 2.0, -depth_z / 2.0),
                max: Point2::new(width_x / 2.0, depth_z / 2.0),
            },
            walls: Vec::new(),
            doors: Vec::new(),
            windows: Vec::new(),
            rooms: Vec::new(),
        }
    }

    /// The wall with this id.
    pub fn wall(&self, id: &str) -> Option<&Wall> {
        self.walls.iter().find(|w| w.id == id)
    }

    /// Every architecture id: floor, walls, doors, windows and rooms.
    pub fn ids(&self) -> impl Iterator<Item = &str> {
        std::iter::once(self.floor.id.as_str())
            .chain(self.walls.iter().map(|w| w.id.as_str()))
            .chain(self.doors.iter().map(|d| d.id.as_str()))
            .chain(self.windows.iter().map(|w| w.id.as_str()))
            .chain(self.rooms.iter().map(|r| r.id.as_str()))
    }

    /// The room with this id.
    pub fn room(&self, id: &str) -> Option<&RoomArea> {
        self.rooms.iter().find(|r| r.id == id)
    }

    /// The room whose outline holds the (x, z) point, if the scene is a house.
    pub fn room_at(&self, x: f64, z: f64) -> Option<&RoomArea> {
        self.rooms.iter().find(|r| r.contains_xz(x, z))
    }

    /// World (x, z) centre of a window opening on the floor plane, and the unit inward normal
    /// of its wall; `None` if the window's wall is unknown.
    pub fn window_position(&self, window: &WindowOpening) -> Option<(Point2<f64>, Vector2<f64>)> {
        let wall = self.wall(&window.wall)?;
        Some((
            wall.start + wall.direction() * window.offset,
            wall.inward_normal(),
        ))
    }

    /// World (x, z) centre of a door opening on the floor, and the unit inward normal of its
    /// wall; `None` if the door's wall is unknown.
    pub fn door_position(&self, door: &DoorOpening) -> Option<(Point2<f64>, Vector2<f64>)> {
        let wall = self.wall(&door.wall)?;
        Some((
            wall.start + wall.direction() * door.offset,
            wall.inward_normal(),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rectangular_room_walls_face_inward() {
        let room = Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9);
        for wall in &room.walls {
            let mid = nalgebra::center(&wall.start, &wall.end);
            let inside = mid + wall.inward_normal() * 0.5;
            assert!(
                room.floor.contains_xz(inside.x, inside.y),
                "{} faces out",
                wall.id
            );
        }
        let (door, normal) = room.door_position(&room.doors[0]).unwrap();
        assert!(
            (door.y - 2.05).abs() < 1e-9 && door.x.abs() < 1e-9,
            "{door:?}"
        );
        assert!((normal.y + 1.0).abs() < 1e-9);
    }

    #[test]
    fn l_shaped_room_contains_and_measures() {
        let corners = [
            (0.0, 0.0),
            (4.0, 0.0),
            (4.0, 2.0),
            (2.0, 2.0),
            (2.0, 4.0),
            (0.0, 4.0),
        ];
        let room = RoomArea {
            id: "living_room".into(),
            room_type: "living room".into(),
            polygon: corners.iter().map(|&(x, z)| Point2::new(x, z)).collect(),
        };
        assert!((room.area() - 12.0).abs() < 1e-9);
        assert!(room.contains_xz(1.0, 3.0) && room.contains_xz(3.0, 1.0));
        assert!(!room.contains_xz(3.0, 3.0), "the L's missing corner");
        let mut arch = Architecture::rectangular_room(4.0, 4.0, 2.8, 0.9);
        arch.rooms.push(room);
        assert_eq!(
            arch.room_at(0.5, 0.5).map(|r| r.id.as_str()),
            Some("living_room")
        );
        assert!(arch.ids().any(|id| id == "living_room"));
    }

    #[test]
    fn wall_box_covers_thickness() {
        let room = Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9);
        let b = room.walls[0].aabb();
        assert!(
            (b.min.z - -2.1).abs() < 1e-9 && (b.max.z - -2.0).abs() < 1e-9,
            "{b:?}"
        );
    }
}
