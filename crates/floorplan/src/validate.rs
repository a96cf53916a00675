//! Validation of a floor plan, generated or given by a user: one clear error naming the room,
//! door or window at fault.

use std::collections::{BTreeMap, BTreeSet, VecDeque};

use crate::geometry::{polygon_problem, rectangles, Rect};
use crate::knowledge::Knowledge;
use crate::plan::{FloorPlan, Window, EXTERIOR};
use crate::walls::{walls, Wall};

/// Room outlines this crate supports, for error messages.
pub const SUPPORTED_OUTLINES: &str =
    "simple axis-aligned polygons (rectangles, L-shapes and other outlines whose edges run along x or z), with at least 4 corners and no repeated or collinear corners";

/// Overlaps smaller than this (m²) are rounding, not overlap.
const OVERLAP_TOLERANCE: f64 = 1e-4;

/// What is wrong with a floor plan.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlanError {
    /// The plan has no room.
    #[error("the floor plan has no rooms")]
    NoRooms,
    /// Two rooms, doors or windows share an id.
    #[error("id `{id}` is used twice (room, door and window ids must be unique)")]
    DuplicateId {
        /// The repeated id.
        id: String,
    },
    /// A room is called `exterior`, the name doors use for outside.
    #[error("room id `{room}` is reserved for the outside")]
    ReservedId {
        /// The room.
        room: String,
    },
    /// A room's type is not in the knowledge.
    #[error("room `{room}` has unknown type `{room_type}` (known: {known})")]
    UnknownRoomType {
        /// The room.
        room: String,
        /// Its type.
        room_type: String,
        /// The known types.
        known: String,
    },
    /// A room's outline is not supported.
    #[error("room `{room}`: polygon {reason}; supported are {SUPPORTED_OUTLINES}")]
    BadPolygon {
        /// The room.
        room: String,
        /// What is wrong.
        reason: String,
    },
    /// Two rooms overlap.
    #[error("rooms `{a}` and `{b}` overlap by {area:.2} m²")]
    Overlap {
        /// One room.
        a: String,
        /// The other.
        b: String,
        /// Overlapping area, m².
        area: f64,
    },
    /// A door names a room the plan does not have, or names the same side twice.
    #[error("door `{door}` joins `{a}` and `{b}`: {reason}")]
    DoorRooms {
        /// The door.
        door: String,
        /// Its first room.
        a: String,
        /// Its second room.
        b: String,
        /// What is wrong.
        reason: String,
    },
    /// A door or window has a size that is not positive and finite.
    #[error("{item} `{id}`: {field} must be a positive number, got {value}")]
    BadSize {
        /// `door` or `window`.
        item: &'static str,
        /// Its id.
        id: String,
        /// The field.
        field: &'static str,
        /// The value given.
        value: f64,
    },
    /// A door between two rooms is not on a wall they share.
    #[error("door `{door}` (width {width} m) is not on a wall shared by `{a}` and `{b}`")]
    DoorNotOnSharedWall {
        /// The door.
        door: String,
        /// One room.
        a: String,
        /// The other.
        b: String,
        /// The door's width.
        width: f64,
    },
    /// An entrance door is not on an exterior wall of its room.
    #[error(
        "door `{door}` (width {width} m) leads outside but is not on an exterior wall of `{room}`"
    )]
    DoorNotOnExteriorWall {
        /// The door.
        door: String,
        /// Its room.
        room: String,
        /// The door's width.
        width: f64,
    },
    /// A door's swing names a room the door does not join.
    #[error("door `{door}` swings into `{into}`, which is not one of its rooms")]
    BadSwing {
        /// The door.
        door: String,
        /// The room named.
        into: String,
    },
    /// Two doors overlap on a wall.
    #[error("doors `{a}` and `{b}` overlap")]
    DoorsOverlap {
        /// One door.
        a: String,
        /// The other.
        b: String,
    },
    /// No door leads outside.
    #[error("the floor plan has no entrance (a door whose rooms include \"exterior\")")]
    NoEntrance,
    /// A room cannot be reached from an entrance through doors.
    #[error("room `{room}` cannot be reached from the entrance through doors")]
    Unreachable {
        /// The room.
        room: String,
    },
    /// A window names a room the plan does not have.
    #[error("window `{window}` names unknown room `{room}`")]
    WindowUnknownRoom {
        /// The window.
        window: String,
        /// The room named.
        room: String,
    },
    /// A window is not on any wall of its room.
    #[error("window `{window}` is not on a wall of room `{room}`")]
    WindowNotOnRoomWall {
        /// The window.
        window: String,
        /// Its room.
        room: String,
    },
    /// A window is on a wall between two rooms.
    #[error("window `{window}` of room `{room}` is on an interior wall (shared with `{other}`); windows go in exterior walls")]
    WindowOnInteriorWall {
        /// The window.
        window: String,
        /// Its room.
        room: String,
        /// The room on the wall's other side.
        other: String,
    },
    /// A window overlaps a door on the same wall.
    #[error("window `{window}` overlaps door `{door}`")]
    WindowOverlapsDoor {
        /// The window.
        window: String,
        /// The door.
        door: String,
    },
    /// A private room is a passage to other rooms.
    #[error("private room `{room}` is a passage: its doors lead to {neighbours}")]
    PrivatePassage {
        /// The room.
        room: String,
        /// The rooms its doors lead to.
        neighbours: String,
    },
}

/// Checks a plan against the knowledge's room types; on success returns its walls.
///
/// Checks, in order: ids, room types, outlines, overlaps, doors (rooms, size, on a shared or
/// exterior wall, swing, overlaps), windows (room, size, on an exterior wall of their room,
/// clear of doors), the entrance and that every room is reachable from it.
pub fn validate(plan: &FloorPlan, knowledge: &Knowledge) -> Result<Vec<Wall>, PlanError> {
    if plan.rooms.is_empty() {
        return Err(PlanError::NoRooms);
    }
    check_ids(plan)?;
    check_rooms(plan, knowledge)?;
    check_overlaps(plan)?;
    let walls = walls(plan);
    check_doors(plan, &walls)?;
    check_windows(plan, &walls)?;
    check_reachable(plan)?;
    Ok(walls)
}

fn check_ids(plan: &FloorPlan) -> Result<(), PlanError> {
    if let Some(room) = plan.rooms.iter().find(|r| r.id == EXTERIOR) {
        return Err(PlanError::ReservedId {
            room: room.id.clone(),
        });
    }
    let ids = plan
        .rooms
        .iter()
        .map(|r| &r.id)
        .chain(plan.doors.iter().map(|d| &d.id))
        .chain(plan.windows.iter().map(|w| &w.id));
    let mut seen = BTreeSet::new();
    for id in ids {
        if !seen.insert(id) {
            return Err(PlanError::DuplicateId { id: id.clone() });
        }
    }
    Ok(())
}

fn check_rooms(plan: &FloorPlan, knowledge: &Knowledge) -> Result<(), PlanError> {
    for room in &plan.rooms {
        if knowledge.room(&room.room_type).is_none() {
            return Err(PlanError::UnknownRoomType {
                room: room.id.clone(),
                room_type: room.room_type.clone(),
                known: knowledge.room_names(),
            });
        }
        if let Some(reason) = polygon_problem(&room.polygon) {
            return Err(PlanError::BadPolygon {
                room: room.id.clone(),
                reason,
            });
        }
    }
    Ok(())
}

fn check_overlaps(plan: &FloorPlan) -> Result<(), PlanError> {
    let pieces: Vec<Vec<Rect>> = plan.rooms.iter().map(|r| rectangles(&r.polygon)).collect();
    for i in 0..pieces.len() {
        for j in i + 1..pieces.len() {
            let area: f64 = pieces[i]
                .iter()
                .flat_map(|a| pieces[j].iter().map(move |b| a.overlap_area(b)))
                .sum();
            if area > OVERLAP_TOLERANCE {
                let (a, b) = (plan.rooms[i].id.clone(), plan.rooms[j].id.clone());
                return Err(PlanError::Overlap { a, b, area });
            }
        }
    }
    Ok(())
}

fn check_size(
    item: &'static str,
    id: &str,
    field: &'static str,
    value: f64,
) -> Result<(), PlanError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(PlanError::BadSize {
            item,
            id: id.to_owned(),
            field,
            value,
        })
    }
}

fn check_doors(plan: &FloorPlan, walls: &[Wall]) -> Result<(), PlanError> {
    for door in &plan.doors {
        check_door_rooms(plan, &door.id, &door.rooms)?;
        check_size("door", &door.id, "width", door.width)?;
        check_size("door", &door.id, "height", door.height)?;
        let [a, b] = &door.rooms;
        let on_wall = walls
            .iter()
            .any(|w| w.joins(a, b) && w.segment().holds(&door.centre, door.width / 2.0));
        if !on_wall {
            return Err(match door.other(EXTERIOR) {
                Some(room) => PlanError::DoorNotOnExteriorWall {
                    door: door.id.clone(),
                    room: room.to_owned(),
                    width: door.width,
                },
                None => PlanError::DoorNotOnSharedWall {
                    door: door.id.clone(),
                    a: a.clone(),
                    b: b.clone(),
                    width: door.width,
                },
            });
        }
        if let Some(swing) = &door.swing {
            if swing.into == EXTERIOR || door.other(&swing.into).is_none() {
                return Err(PlanError::BadSwing {
                    door: door.id.clone(),
                    into: swing.into.clone(),
                });
            }
        }
    }
    check_door_overlaps(plan, walls)
}

fn check_door_rooms(plan: &FloorPlan, door: &str, rooms: &[String; 2]) -> Result<(), PlanError> {
    let error = |reason: &str| PlanError::DoorRooms {
        door: door.to_owned(),
        a: rooms[0].clone(),
        b: rooms[1].clone(),
        reason: reason.to_owned(),
    };
    if rooms[0] == rooms[1] {
        return Err(error("a door joins two different sides"));
    }
    for room in rooms {
        if room != EXTERIOR && plan.room(room).is_none() {
            return Err(error(&format!("the plan has no room `{room}`")));
        }
    }
    Ok(())
}

/// The interval `(lo, hi)` an opening of `width` centred at `centre` covers on the wall, if it
/// sits on it.
fn interval_on(wall: &Wall, centre: &nalgebra::Point2<f64>, width: f64) -> Option<(f64, f64)> {
    let seg = wall.segment();
    seg.holds(centre, width / 2.0)
        .then(|| seg.along(centre))
        .flatten()
        .map(|t| (t - width / 2.0, t + width / 2.0))
}

fn overlaps(a: (f64, f64), b: (f64, f64)) -> bool {
    a.0 < b.1 - 1e-3 && b.0 < a.1 - 1e-3
}

fn check_door_overlaps(plan: &FloorPlan, walls: &[Wall]) -> Result<(), PlanError> {
    for wall in walls {
        let on: Vec<(&str, (f64, f64))> = plan
            .doors
            .iter()
            .filter_map(|d| interval_on(wall, &d.centre, d.width).map(|iv| (d.id.as_str(), iv)))
            .collect();
        for (i, (a, ia)) in on.iter().enumerate() {
            if let Some((b, _)) = on[i + 1..].iter().find(|(_, ib)| overlaps(*ia, *ib)) {
                return Err(PlanError::DoorsOverlap {
                    a: (*a).to_owned(),
                    b: (*b).to_owned(),
                });
            }
        }
    }
    Ok(())
}

fn check_windows(plan: &FloorPlan, walls: &[Wall]) -> Result<(), PlanError> {
    for window in &plan.windows {
        if plan.room(&window.room).is_none() {
            return Err(PlanError::WindowUnknownRoom {
                window: window.id.clone(),
                room: window.room.clone(),
            });
        }
        check_size("window", &window.id, "width", window.width)?;
        check_size("window", &window.id, "height", window.height)?;
        if !(window.sill.is_finite() && window.sill >= 0.0) {
            return Err(PlanError::BadSize {
                item: "window",
                id: window.id.clone(),
                field: "sill",
                value: window.sill,
            });
        }
        check_window_wall(plan, walls, window)?;
    }
    Ok(())
}

fn check_window_wall(plan: &FloorPlan, walls: &[Wall], window: &Window) -> Result<(), PlanError> {
    let wall = walls.iter().find(|w| {
        w.touches(&window.room) && interval_on(w, &window.centre, window.width).is_some()
    });
    let Some(wall) = wall else {
        return Err(PlanError::WindowNotOnRoomWall {
            window: window.id.clone(),
            room: window.room.clone(),
        });
    };
    if !wall.is_exterior() {
        let other = if wall.rooms[0] == window.room {
            &wall.rooms[1]
        } else {
            &wall.rooms[0]
        };
        return Err(PlanError::WindowOnInteriorWall {
            window: window.id.clone(),
            room: window.room.clone(),
            other: other.clone(),
        });
    }
    let span = interval_on(wall, &window.centre, window.width).unwrap_or_default();
    let seg = wall.segment();
    for door in &plan.doors {
        if let Some(t) = seg.along(&door.centre) {
            if overlaps(span, (t - door.width / 2.0, t + door.width / 2.0)) {
                return Err(PlanError::WindowOverlapsDoor {
                    window: window.id.clone(),
                    door: door.id.clone(),
                });
            }
        }
    }
    Ok(())
}

/// The rooms each room's doors lead to (the outside as [`EXTERIOR`]).
pub fn neighbours(plan: &FloorPlan) -> BTreeMap<&str, Vec<&str>> {
    let mut graph: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for door in &plan.doors {
        let [a, b] = &door.rooms;
        graph.entry(a).or_default().push(b);
        graph.entry(b).or_default().push(a);
    }
    graph
}

fn check_reachable(plan: &FloorPlan) -> Result<(), PlanError> {
    if plan.entrances().next().is_none() {
        return Err(PlanError::NoEntrance);
    }
    let graph = neighbours(plan);
    let mut seen = BTreeSet::from([EXTERIOR]);
    let mut queue = VecDeque::from([EXTERIOR]);
    while let Some(at) = queue.pop_front() {
        for next in graph.get(at).into_iter().flatten() {
            if seen.insert(next) {
                queue.push_back(next);
            }
        }
    }
    match plan.rooms.iter().find(|r| !seen.contains(r.id.as_str())) {
        Some(room) => Err(PlanError::Unreachable {
            room: room.id.clone(),
        }),
        None => Ok(()),
    }
}

/// Checks that no private room (bedroom, bathroom, office...) is a passage: each has doors to
/// at most one room (or the outside), not counting its own en-suites (private rooms whose only
/// door leads into it).
pub fn check_privacy(plan: &FloorPlan, knowledge: &Knowledge) -> Result<(), PlanError> {
    let graph = neighbours(plan);
    let private = |id: &str| {
        plan.room(id)
            .is_some_and(|r| knowledge.is_private(&r.room_type))
    };
    for room in plan.rooms.iter().filter(|r| private(&r.id)) {
        let around = graph.get(room.id.as_str()).cloned().unwrap_or_default();
        let ensuite = |n: &str| {
            plan.room(n)
                .is_some_and(|r| knowledge.may_be_ensuite(&r.room_type))
                && graph
                    .get(n)
                    .is_some_and(|m| m.iter().all(|x| *x == room.id))
        };
        let through: BTreeSet<&str> = around.iter().copied().filter(|n| !ensuite(n)).collect();
        if through.len() > 1 {
            let neighbours = through.into_iter().collect::<Vec<_>>().join(", ");
            return Err(PlanError::PrivatePassage {
                room: room.id.clone(),
                neighbours,
            });
        }
    }
    Ok(())
}
