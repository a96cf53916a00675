//! The `house` part of `report.json`: the floor plan's rooms, each room's verdict, Walk and
//! Reach, and the whole house measured at once.

use serde::{Deserialize, Serialize};

/// What a house run measured: the whole house and every room.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HouseReport {
    /// The dwelling kind (`apartment`, `house`, `office_suite`, …; `plan` for a user's plan).
    pub kind: String,
    /// The footprint of the wall centre lines, `[min x, min z, max x, max z]`, m.
    pub footprint: [f64; 4],
    /// Whether the plan has a hallway.
    pub hallway: bool,
    /// Walk over the whole house (`metrics.md`; interior walls block, door openings pass).
    pub walk: f64,
    /// Reach of the floor objects over the whole house (`metrics.md`).
    pub reach: Option<f64>,
    /// The smallest share, over the rooms, of a room's free floor that a 0.3 m-radius robot
    /// reaches from the entrance (1 when it reaches every room everywhere).
    pub entrance_reach: Option<f64>,
    /// How many rooms the judge accepted.
    pub rooms_accepted: usize,
    /// Every room, in plan order.
    pub rooms: Vec<RoomReport>,
}

/// One room of a house run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RoomReport {
    /// The room's id (every object in it is named `<id>.<object>`).
    pub id: String,
    /// The room type.
    #[serde(rename = "type")]
    pub room_type: String,
    /// The single-room prompt it was planned from.
    pub prompt: String,
    /// Its floor area (inside the walls), m².
    pub area: f64,
    /// The furnished rectangle, width × depth in the room's own frame, m (the whole room, or
    /// the largest rectangle of an L-shaped one).
    pub furnished_size: [f64; 2],
    /// Whether the judge accepted the room (a room left empty counts as accepted).
    pub accepted: bool,
    /// Objects in it.
    pub objects: usize,
    /// Attempts the room's judge made (1 without re-plans).
    pub attempts: usize,
    /// Walk of the room alone, as its judge measured it.
    pub walk: f64,
    /// Reach of the room alone, as its judge measured it.
    pub reach: Option<f64>,
    /// The share of its free floor a 0.3 m-radius robot reaches from the house's entrance.
    pub entrance_reach: Option<f64>,
    /// The room judge's failures (empty when accepted).
    pub failures: Vec<String>,
    /// Why the room was left empty, or other notes.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
}

impl HouseReport {
    /// The summary line's house part.
    pub fn summary(&self) -> String {
        format!(
            "house: {} rooms ({} accepted), Walk {:.2} Reach {} entrance reach {}",
            self.rooms.len(),
            self.rooms_accepted,
            self.walk,
            self.reach.map_or("n/a".to_owned(), |r| format!("{r:.2}")),
            self.entrance_reach
                .map_or("n/a".to_owned(), |r| format!("{r:.2}")),
        )
    }
}
