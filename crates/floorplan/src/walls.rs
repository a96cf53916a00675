//! Wall segments derived from a plan's rooms: every stretch of room outline becomes a wall
//! between the two rooms on its sides (or a room and the exterior), each interior wall listed
//! once, with the doors and windows cut into it.

use std::collections::BTreeMap;

use nalgebra::{Point2, Vector2};
use serde::{Deserialize, Serialize};

use crate::geometry::{sided_edges, Axis, Segment, EPS};
use crate::plan::{FloorPlan, EXTERIOR};

/// A straight wall between two rooms, or a room and the exterior.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Wall {
    /// Stable id (`wall_0`, ...), in a fixed order.
    pub id: String,
    /// Start of the centre line in (x, z), m.
    pub start: Point2<f64>,
    /// End of the centre line in (x, z), m.
    pub end: Point2<f64>,
    /// The rooms on its two sides: `rooms[0]` on the left walking from `start` to `end`
    /// (the side [`Wall::inward_normal`] points to, as in scene-graph's `Wall`), `rooms[1]` on
    /// the right, [`EXTERIOR`] for outside (always `rooms[1]`).
    pub rooms: [String; 2],
    /// Ids of the doors and windows in this wall.
    #[serde(default)]
    pub openings: Vec<String>,
}

impl Wall {
    /// Whether one side is the exterior.
    pub fn is_exterior(&self) -> bool {
        self.rooms[1] == EXTERIOR
    }

    /// Length of the centre line, m.
    pub fn length(&self) -> f64 {
        (self.end - self.start).norm()
    }

    /// Unit normal pointing into `rooms[0]`: for direction (dx, dz) it is (dz, -dx).
    pub fn inward_normal(&self) -> Vector2<f64> {
        let d = (self.end - self.start).normalize();
        Vector2::new(d.y, -d.x)
    }

    /// The wall as an axis-aligned segment.
    pub fn segment(&self) -> Segment {
        if (self.start.y - self.end.y).abs() < EPS {
            Segment {
                axis: Axis::X,
                at: self.start.y,
                lo: self.start.x.min(self.end.x),
                hi: self.start.x.max(self.end.x),
            }
        } else {
            Segment {
                axis: Axis::Z,
                at: self.start.x,
                lo: self.start.y.min(self.end.y),
                hi: self.start.y.max(self.end.y),
            }
        }
    }

    /// Whether the wall has `room` on one side.
    pub fn touches(&self, room: &str) -> bool {
        self.rooms.iter().any(|r| r == room)
    }

    /// Whether the wall joins exactly these two rooms (in either order).
    pub fn joins(&self, a: &str, b: &str) -> bool {
        (self.rooms[0] == a && self.rooms[1] == b) || (self.rooms[0] == b && self.rooms[1] == a)
    }
}

/// One room edge on a line: its interval, its room and the side the room is on.
struct EdgeRun {
    lo: f64,
    hi: f64,
    room: usize,
    positive: bool,
}

/// The walls of a plan, derived from its room polygons (assumed valid and not overlapping),
/// with each door and window listed in the wall it sits on.
pub fn walls(plan: &FloorPlan) -> Vec<Wall> {
    let mut lines: BTreeMap<(Axis, i64), Vec<EdgeRun>> = BTreeMap::new();
    for (index, room) in plan.rooms.iter().enumerate() {
        for (seg, side) in sided_edges(&room.polygon) {
            let key = (seg.axis, (seg.at * 1e4).round() as i64);
            lines.entry(key).or_default().push(EdgeRun {
                lo: seg.lo,
                hi: seg.hi,
                room: index,
                positive: side > 0.0,
            });
        }
    }
    let mut out = Vec::new();
    for ((axis, at), runs) in &lines {
        for (lo, hi, neg, pos) in pieces(runs) {
            let seg = Segment {
                axis: *axis,
                at: *at as f64 / 1e4,
                lo,
                hi,
            };
            let name =
                |r: Option<usize>| r.map_or(EXTERIOR.to_owned(), |i| plan.rooms[i].id.clone());
            out.push(oriented(
                seg,
                name(neg),
                name(pos),
                neg.is_some(),
                out.len(),
            ));
        }
    }
    for wall in &mut out {
        wall.openings = openings_on(plan, wall);
    }
    out
}

/// The maximal stretches of a line with the same room on each side: `(lo, hi, negative-side
/// room, positive-side room)`.
fn pieces(runs: &[EdgeRun]) -> Vec<(f64, f64, Option<usize>, Option<usize>)> {
    let mut cuts: Vec<f64> = runs.iter().flat_map(|r| [r.lo, r.hi]).collect();
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|a, b| (*a - *b).abs() < EPS);
    let mut out: Vec<(f64, f64, Option<usize>, Option<usize>)> = Vec::new();
    for w in cuts.windows(2) {
        let mid = (w[0] + w[1]) / 2.0;
        let on = |positive: bool| {
            runs.iter()
                .find(|r| r.positive == positive && r.lo < mid && mid < r.hi)
                .map(|r| r.room)
        };
        // The room at smaller coordinates has its inside on the negative side of the line.
        let (neg, pos) = (on(false), on(true));
        if neg.is_none() && pos.is_none() {
            continue;
        }
        match out.last_mut() {
            Some(last) if (last.1 - w[0]).abs() < EPS && last.2 == neg && last.3 == pos => {
                last.1 = w[1];
            }
            _ => out.push((w[0], w[1], neg, pos)),
        }
    }
    out
}

/// A wall on `seg` with `neg` at smaller and `pos` at larger coordinates, oriented so that a
/// room is on its left (`rooms[0]`) and the exterior, if any, on its right.
fn oriented(seg: Segment, neg: String, pos: String, neg_is_room: bool, index: usize) -> Wall {
    let (a, b) = seg.ends();
    // Walking +x the left (inward normal (0, -1)) is at smaller z; walking +z the left
    // (normal (1, 0)) is at larger x.
    let left_is_neg_forward = seg.axis == Axis::X;
    let keep_forward = if neg_is_room {
        left_is_neg_forward
    } else {
        !left_is_neg_forward
    };
    let (start, end) = if keep_forward { (a, b) } else { (b, a) };
    let left_is_neg = keep_forward == left_is_neg_forward;
    let rooms = if left_is_neg { [neg, pos] } else { [pos, neg] };
    Wall {
        id: format!("wall_{index}"),
        start,
        end,
        rooms,
        openings: Vec::new(),
    }
}

fn openings_on(plan: &FloorPlan, wall: &Wall) -> Vec<String> {
    let seg = wall.segment();
    let doors = plan
        .doors
        .iter()
        .filter(|d| seg.holds(&d.centre, d.width / 2.0) && wall.joins(&d.rooms[0], &d.rooms[1]))
        .map(|d| d.id.clone());
    let windows = plan
        .windows
        .iter()
        .filter(|w| seg.holds(&w.centre, w.width / 2.0) && wall.touches(&w.room))
        .map(|w| w.id.clone());
    doors.chain(windows).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Rect;
    use crate::plan::Room;

    fn room(id: &str, r: Rect) -> Room {
        Room {
            id: id.into(),
            room_type: "bedroom".into(),
            polygon: r.polygon(),
        }
    }

    #[test]
    fn two_rooms_share_one_interior_wall_and_face_inward() {
        let plan = FloorPlan {
            rooms: vec![
                room("a", Rect::new(0.0, 0.0, 3.0, 4.0)),
                room("b", Rect::new(3.0, 0.0, 5.0, 2.0)),
                room("c", Rect::new(3.0, 2.0, 5.0, 4.0)),
            ],
            doors: vec![],
            windows: vec![],
        };
        let walls = walls(&plan);
        let interior: Vec<&Wall> = walls.iter().filter(|w| !w.is_exterior()).collect();
        assert_eq!(interior.len(), 3, "{walls:#?}");
        assert!(interior
            .iter()
            .any(|w| w.joins("a", "b") && (w.length() - 2.0).abs() < 1e-9));
        let exterior: f64 = walls
            .iter()
            .filter(|w| w.is_exterior())
            .map(Wall::length)
            .sum();
        assert!((exterior - 18.0).abs() < 1e-9, "perimeter {exterior}");
        for wall in &walls {
            let mid = nalgebra::center(&wall.start, &wall.end) + wall.inward_normal() * 0.1;
            let left = plan.room(&wall.rooms[0]).unwrap();
            assert!(crate::geometry::contains(&left.polygon, mid), "{wall:?}");
        }
    }
}
