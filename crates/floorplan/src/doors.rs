//! Doors of a generated plan: one entrance on an exterior wall of the dwelling's entrance room,
//! public rooms joined to it (open passages and double doors where the knowledge says, else
//! single doors), each private room joined to one public room (the hallway first) and each
//! en-suite to its host.

use std::collections::BTreeSet;

use nalgebra::{Point2, Vector2};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

use crate::geometry::Rect;
use crate::knowledge::{DwellingKind, Knowledge, HALLWAY};
use crate::plan::{Door, DoorKind, FloorPlan, Hinge, Swing, EXTERIOR};
use crate::walls::Wall;

/// Free wall kept between a door's edge and the wall's end (a corner or a crossing wall), m.
pub const CORNER_CLEARANCE: f64 = 0.1;
/// Height of doors and passages, m.
pub const DOOR_HEIGHT: f64 = 2.1;
/// Width of a single entrance door, m.
pub const ENTRANCE_WIDTH: f64 = 0.9;
/// Narrowest open passage, m.
pub const PASSAGE_MIN: f64 = 1.2;
/// Widest open passage, m.
pub const PASSAGE_MAX: f64 = 2.4;
/// Wall kept at each end of an open passage where the wall is long enough, m: a kitchen
/// run's depth (0.6 m) and the 0.1 m the approach before the passage reaches past its edge,
/// so that the walls beside a passage can still hold counters up to the corner.
pub const PASSAGE_SIDE_WALL: f64 = 0.75;
/// Double door widths, m.
pub const DOUBLE_WIDTHS: [f64; 3] = [1.4, 1.5, 1.6];

/// Public rooms a private room is entered from only when no hallway or living space is next
/// to it (a bathroom off a kitchen is a last resort).
pub const SERVICE_ROOMS: &[&str] = &["kitchen", "kitchenette", "dining_room"];

/// Private rooms entered from a service room ([`SERVICE_ROOMS`]): a cost for layout scoring.
pub(crate) fn service_entries(knowledge: &Knowledge, plan: &FloorPlan) -> usize {
    let ty = |id: &str| plan.room(id).map_or("", |r| r.room_type.as_str());
    plan.doors
        .iter()
        .filter(|d| {
            let [a, b] = [ty(&d.rooms[0]), ty(&d.rooms[1])];
            (SERVICE_ROOMS.contains(&a) && knowledge.is_private(b))
                || (SERVICE_ROOMS.contains(&b) && knowledge.is_private(a))
        })
        .count()
}

/// What door placement needs to know.
pub(crate) struct DoorRules<'a> {
    pub knowledge: &'a Knowledge,
    pub dwelling: &'a DwellingKind,
    /// `(en-suite id, host id)` pairs.
    pub ensuites: Vec<(String, String)>,
}

/// The doors of a plan whose walls are `walls`; `None` when some room cannot be joined.
pub(crate) fn place_doors(
    rules: &DoorRules,
    plan: &FloorPlan,
    walls: &[Wall],
    rng: &mut ChaCha8Rng,
) -> Option<Vec<Door>> {
    let mut placer = Placer {
        rules,
        plan,
        walls,
        doors: Vec::new(),
        rng,
    };
    let entrance = placer.entrance()?;
    let mut reached = BTreeSet::from([entrance.clone()]);
    placer.join_public(&mut reached);
    placer.add_passages(&reached);
    for room in &plan.rooms {
        if reached.contains(&room.id) || placer.host_of(&room.id).is_some() {
            continue;
        }
        if !placer.is_private(&room.id) {
            return None;
        }
        placer.join_private(&room.id, &reached)?;
    }
    for room in &plan.rooms {
        if let Some(host) = placer.host_of(&room.id) {
            let wall = placer.shared(&host, &room.id)?;
            placer.add(&wall, [host, room.id.clone()], DoorKind::Single, &room.id)?;
        }
    }
    Some(placer.doors)
}

struct Placer<'a, 'r> {
    rules: &'a DoorRules<'a>,
    plan: &'a FloorPlan,
    walls: &'a [Wall],
    doors: Vec<Door>,
    rng: &'r mut ChaCha8Rng,
}

impl Placer<'_, '_> {
    fn room_type(&self, id: &str) -> &str {
        self.plan.room(id).map_or("", |r| r.room_type.as_str())
    }

    fn is_private(&self, id: &str) -> bool {
        self.rules.knowledge.is_private(self.room_type(id))
    }

    /// The room an en-suite is reached through, if `id` is an en-suite.
    fn host_of(&self, id: &str) -> Option<String> {
        self.rules
            .ensuites
            .iter()
            .find(|(e, _)| e == id)
            .map(|(_, h)| h.clone())
    }

    /// The longest wall two rooms share.
    fn shared(&self, a: &str, b: &str) -> Option<Wall> {
        self.walls
            .iter()
            .filter(|w| w.joins(a, b))
            .max_by(|x, y| x.length().total_cmp(&y.length()))
            .cloned()
    }

    /// The entrance door into the first entrance room type the plan has.
    fn entrance(&mut self) -> Option<String> {
        let kind = self.rules.dwelling.entrance_door;
        let width = ENTRANCE_WIDTH;
        for ty in &self.rules.dwelling.entrance {
            let rooms: Vec<String> = self
                .plan
                .rooms
                .iter()
                .filter(|r| &r.room_type == ty)
                .map(|r| r.id.clone())
                .collect();
            for room in rooms {
                let wall = self
                    .walls
                    .iter()
                    .filter(|w| {
                        w.rooms[0] == room
                            && w.is_exterior()
                            && w.length() >= width + 2.0 * CORNER_CLEARANCE
                    })
                    .max_by(|a, b| a.length().total_cmp(&b.length()))
                    .cloned();
                if let Some(wall) = wall {
                    self.add(&wall, [room.clone(), EXTERIOR.into()], kind, &room)?;
                    return Some(room);
                }
            }
        }
        None
    }

    /// Joins every public room it can reach to the entrance, best joins first: passages, then
    /// double doors, then single doors from the hallway, then other single doors.
    fn join_public(&mut self, reached: &mut BTreeSet<String>) {
        loop {
            let mut best: Option<(u8, Wall, String, String)> = None;
            for p in reached.iter().filter(|p| !self.is_private(p)) {
                for q in self.plan.rooms.iter().map(|r| &r.id) {
                    if reached.contains(q) || self.is_private(q) {
                        continue;
                    }
                    let Some(wall) = self
                        .shared(p, q)
                        .filter(|w| w.length() >= 0.8 + 2.0 * CORNER_CLEARANCE)
                    else {
                        continue;
                    };
                    let rank = match self
                        .rules
                        .knowledge
                        .join_kind(self.room_type(p), self.room_type(q))
                    {
                        DoorKind::Passage => 0,
                        DoorKind::Double => 1,
                        DoorKind::Single if self.room_type(p) == HALLWAY => 2,
                        DoorKind::Single => 3,
                    };
                    if best.as_ref().is_none_or(|(r, ..)| rank < *r) {
                        best = Some((rank, wall, p.clone(), q.clone()));
                    }
                }
            }
            let Some((_, wall, p, q)) = best else { return };
            let kind = self
                .rules
                .knowledge
                .join_kind(self.room_type(&p), self.room_type(&q));
            // Doors open into rooms, not into corridors.
            let into = if self.room_type(&q) == HALLWAY {
                p.clone()
            } else {
                q.clone()
            };
            if self
                .add(&wall, [p.clone(), q.clone()], kind, &into)
                .is_none()
            {
                return;
            }
            reached.insert(q);
        }
    }

    /// Open passages between reached public rooms the knowledge joins that way (a kitchen open
    /// to the living room), where they share a long enough wall and have no door yet.
    fn add_passages(&mut self, reached: &BTreeSet<String>) {
        let ids: Vec<&String> = reached.iter().collect();
        for (i, a) in ids.iter().enumerate() {
            for b in &ids[i + 1..] {
                let open = self
                    .rules
                    .knowledge
                    .join_kind(self.room_type(a), self.room_type(b))
                    == DoorKind::Passage;
                let joined = self.doors.iter().any(|d| d.other(a) == Some(b.as_str()));
                let wall = self
                    .shared(a, b)
                    .filter(|w| w.length() >= PASSAGE_MIN + 2.0 * 0.3);
                if let (true, false, Some(wall)) = (open, joined, wall) {
                    self.add(&wall, [(*a).clone(), (*b).clone()], DoorKind::Passage, b);
                }
            }
        }
    }

    /// A single door from the best reached public neighbour into a private room: the hallway,
    /// then living spaces, then kitchens and dining rooms, the longer wall first.
    fn join_private(&mut self, room: &str, reached: &BTreeSet<String>) -> Option<()> {
        let rank = |ty: &str| match ty {
            HALLWAY => 0,
            ty if SERVICE_ROOMS.contains(&ty) => 2,
            _ => 1,
        };
        let need = self.width(DoorKind::Single, room, 0.0) + 2.0 * CORNER_CLEARANCE;
        let best = reached
            .iter()
            .filter(|p| !self.is_private(p))
            .filter_map(|p| {
                self.shared(p, room)
                    .filter(|w| w.length() >= need)
                    .map(|w| (p.clone(), w))
            })
            .min_by(|(a, wa), (b, wb)| {
                rank(self.room_type(a))
                    .cmp(&rank(self.room_type(b)))
                    .then(wb.length().total_cmp(&wa.length()))
            })?;
        self.add(&best.1, [best.0, room.to_owned()], DoorKind::Single, room)
    }

    /// The width of a door of `kind` into `room` on a wall `length` long (0: not yet known).
    fn width(&mut self, kind: DoorKind, room: &str, length: f64) -> f64 {
        match kind {
            DoorKind::Single if room.is_empty() => ENTRANCE_WIDTH,
            DoorKind::Single => self
                .rules
                .knowledge
                .room(self.room_type(room))
                .map_or(0.9, |r| r.door_width),
            DoorKind::Double => DOUBLE_WIDTHS[self.rng.random_range(0..DOUBLE_WIDTHS.len())],
            DoorKind::Passage => (length - 2.0 * PASSAGE_SIDE_WALL).clamp(PASSAGE_MIN, PASSAGE_MAX),
        }
    }

    /// Adds a door of `kind` (a single door when the wall is too short for it) on `wall`,
    /// opening into `into`.
    fn add(&mut self, wall: &Wall, rooms: [String; 2], kind: DoorKind, into: &str) -> Option<()> {
        let into_room = if rooms[1] == EXTERIOR {
            rooms[0].clone()
        } else {
            into.to_owned()
        };
        let exterior = rooms[1] == EXTERIOR;
        let mut kind = kind;
        let mut width = self.width(kind, if exterior { "" } else { &into_room }, wall.length());
        if wall.length() < width + 2.0 * CORNER_CLEARANCE && kind != DoorKind::Single {
            kind = DoorKind::Single;
            width = self.width(kind, if exterior { "" } else { &into_room }, wall.length());
        }
        let (centre, hinge_at) = self.position(wall, width, kind == DoorKind::Passage)?;
        let swing = swing(wall, centre, hinge_at, &into_room, kind);
        let id = format!("door_{}", self.doors.len());
        self.doors.push(Door {
            id,
            rooms,
            centre,
            width,
            height: DOOR_HEIGHT,
            kind,
            swing,
        });
        Some(())
    }

    /// The door's centre on the wall and its hinge end: near one corner, or anywhere between;
    /// passages centred.
    fn position(
        &mut self,
        wall: &Wall,
        width: f64,
        centred: bool,
    ) -> Option<(Point2<f64>, Point2<f64>)> {
        let seg = wall.segment();
        let (lo, hi) = (
            seg.lo + CORNER_CLEARANCE + width / 2.0,
            seg.hi - CORNER_CLEARANCE - width / 2.0,
        );
        if hi < lo - 1e-9 {
            return None;
        }
        let t = if centred {
            (lo + hi) / 2.0
        } else {
            match self.rng.random_range(0..3) {
                0 => lo,
                1 => hi,
                _ => self.rng.random_range(lo..=hi.max(lo)),
            }
        };
        let t = ((t * 100.0).round() / 100.0).clamp(lo, hi.max(lo));
        let hinge = if t - seg.lo <= seg.hi - t {
            t - width / 2.0
        } else {
            t + width / 2.0
        };
        Some((seg.point(t), seg.point(hinge)))
    }
}

/// The swing of a door opening into `into`: hinged at `hinge_at`, named Left or Right seen
/// from inside `into` facing the door; both sides for a double door; none for a passage.
fn swing(
    wall: &Wall,
    centre: Point2<f64>,
    hinge_at: Point2<f64>,
    into: &str,
    kind: DoorKind,
) -> Option<Swing> {
    let hinge = match kind {
        DoorKind::Passage => return None,
        DoorKind::Double => Hinge::Both,
        DoorKind::Single => {
            let n = if wall.rooms[0] == into {
                wall.inward_normal()
            } else {
                -wall.inward_normal()
            };
            let view = -n;
            let right = Vector2::new(-view.y, view.x);
            if (hinge_at - centre).dot(&right) > 0.0 {
                Hinge::Right
            } else {
                Hinge::Left
            }
        }
    };
    Some(Swing {
        into: into.to_owned(),
        hinge,
    })
}

/// The floor square each door leaf sweeps as it opens, `(door id, square)`: a leaf of width
/// `w` hinged at one end of the opening sweeps a quarter disc inside the w × w square beside
/// it, on the side of the room it opens into; a double door's two leaves sweep the opening's
/// width by half of it. Passages and doors without a swing or off every wall sweep nothing.
pub fn leaf_squares(plan: &FloorPlan, walls: &[Wall]) -> Vec<(String, Rect)> {
    let mut out = Vec::new();
    for door in &plan.doors {
        let Some(swing) = &door.swing else { continue };
        let Some(wall) = walls.iter().find(|w| w.openings.contains(&door.id)) else {
            continue;
        };
        let n = if wall.rooms[0] == swing.into {
            wall.inward_normal()
        } else {
            -wall.inward_normal()
        };
        let along = (wall.end - wall.start).normalize() * (door.width / 2.0);
        let (a, b) = (door.centre - along, door.centre + along);
        let reach = if swing.hinge == Hinge::Both {
            door.width / 2.0
        } else {
            door.width
        };
        let (c, d) = (a + n * reach, b + n * reach);
        let xs = [a.x, b.x, c.x, d.x];
        let zs = [a.y, b.y, c.y, d.y];
        let min = |v: [f64; 4]| v.into_iter().fold(f64::MAX, f64::min);
        let max = |v: [f64; 4]| v.into_iter().fold(f64::MIN, f64::max);
        out.push((
            door.id.clone(),
            Rect::new(min(xs), min(zs), max(xs), max(zs)),
        ));
    }
    out
}

/// The first two doors whose leaves would sweep the same floor (their [`leaf_squares`]
/// overlap by more than 1 cm²).
pub fn leaf_clash(plan: &FloorPlan, walls: &[Wall]) -> Option<(String, String)> {
    let squares = leaf_squares(plan, walls);
    for (i, (a, ra)) in squares.iter().enumerate() {
        for (b, rb) in &squares[i + 1..] {
            if ra.overlap_area(rb) > 1e-4 {
                return Some((a.clone(), b.clone()));
            }
        }
    }
    None
}
