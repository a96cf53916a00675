//! The floor-plan types: rooms, doors and windows, as a generated plan holds them and as a
//! user's `plan.json` gives them. All coordinates are (x, z) on the floor plane in metres.

use nalgebra::Point2;
use serde::{Deserialize, Serialize};

/// The name a door uses for the outside of the building in its `rooms`.
pub const EXTERIOR: &str = "exterior";

/// A floor plan: rooms tiling the footprint, the doors joining them and their windows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FloorPlan {
    /// The rooms, each a simple axis-aligned polygon.
    pub rooms: Vec<Room>,
    /// Doors and open passages between two rooms or a room and the exterior.
    #[serde(default)]
    pub doors: Vec<Door>,
    /// Windows in the exterior walls.
    #[serde(default)]
    pub windows: Vec<Window>,
}

/// One room of a plan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Room {
    /// Stable id, unique in the plan (e.g. `bedroom_1`); never `exterior`.
    pub id: String,
    /// The room type, one of the knowledge's (e.g. `bedroom`, `kitchen`).
    #[serde(rename = "type")]
    pub room_type: String,
    /// The floor outline in (x, z), m: at least four corners, every edge parallel to x or z,
    /// not crossing itself (rectangles and L-shapes), in either winding.
    pub polygon: Vec<Point2<f64>>,
}

/// How a door opening is filled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum DoorKind {
    /// One leaf, 0.8-0.9 m wide.
    #[default]
    Single,
    /// Two leaves, 1.4-1.6 m wide.
    Double,
    /// An open passage: no leaf, wider than a door.
    Passage,
}

/// The hinge side of a door's leaf, seen from inside the room it opens into, facing the door.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Hinge {
    /// Hinged on the left edge.
    Left,
    /// Hinged on the right edge.
    Right,
    /// Two leaves, hinged on both edges (a double door).
    Both,
}

/// Which way a door's leaf swings.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Swing {
    /// Id of the room the leaf opens into (one of the door's rooms, never `exterior`).
    pub into: String,
    /// The hinge side seen from that room.
    pub hinge: Hinge,
}

/// A door or open passage in a wall.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Door {
    /// Stable id, unique in the plan (e.g. `door_0`).
    pub id: String,
    /// The two room ids it joins; one may be [`EXTERIOR`] (an entrance).
    pub rooms: [String; 2],
    /// Centre of the opening on the wall's line, (x, z) in m.
    pub centre: Point2<f64>,
    /// Width of the opening along the wall, m.
    pub width: f64,
    /// Height of the opening above the floor, m.
    pub height: f64,
    /// Single, double or open passage.
    #[serde(default)]
    pub kind: DoorKind,
    /// How the leaf swings; `None` for an open passage (or when not given).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub swing: Option<Swing>,
}

impl Door {
    /// Whether the door leads outside (an entrance).
    pub fn is_exterior(&self) -> bool {
        self.rooms.iter().any(|r| r == EXTERIOR)
    }

    /// The room on the other side from `room`, if the door touches `room`.
    pub fn other(&self, room: &str) -> Option<&str> {
        match (&self.rooms[0], &self.rooms[1]) {
            (a, b) if a == room => Some(b),
            (a, b) if b == room => Some(a),
            _ => None,
        }
    }
}

/// A window in an exterior wall.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Window {
    /// Stable id, unique in the plan (e.g. `window_0`).
    pub id: String,
    /// Id of the room it lights.
    pub room: String,
    /// Centre of the opening on the wall's line, (x, z) in m.
    pub centre: Point2<f64>,
    /// Width of the opening along the wall, m.
    pub width: f64,
    /// Height of the opening, m.
    pub height: f64,
    /// Height of the opening's bottom above the floor, m.
    pub sill: f64,
}

impl FloorPlan {
    /// The room with this id.
    pub fn room(&self, id: &str) -> Option<&Room> {
        self.rooms.iter().find(|r| r.id == id)
    }

    /// The doors touching a room.
    pub fn doors_of<'a>(&'a self, room: &'a str) -> impl Iterator<Item = &'a Door> + 'a {
        self.doors.iter().filter(move |d| d.other(room).is_some())
    }

    /// The entrance doors (doors to the exterior).
    pub fn entrances(&self) -> impl Iterator<Item = &Door> {
        self.doors.iter().filter(|d| d.is_exterior())
    }
}
