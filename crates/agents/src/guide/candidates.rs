//! Where a floor object could go: spots along the walls, in corners, in the middle, in rows,
//! anywhere free, and relative to another object, each with the yaw it faces; and whether a
//! wall-mounted object may hang at a spot.

use std::f64::consts::{FRAC_PI_2, PI};

use nalgebra::Point3;
use rand::seq::SliceRandom;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use scenethesis_scene_graph::RelationKind;
use scenethesis_scene_graph::{aabb_floor_gap, Aabb, AssetInfo};

use super::geometry::Footprint;
use super::room::Side;
use super::shared::{positional_target, Placed, WALL_MOUNT_HEIGHT};
use super::walkway::FloorState;
use crate::arrangement::ArrangementRules;
use crate::knowledge::{Knowledge, NominalShape};
use crate::plan::{PlannedObject, Zone};

/// A spot an object could take: its footprint and the wall it backs onto, if any.
#[derive(Debug, Clone)]
pub(super) struct Candidate {
    pub(super) fp: Footprint,
    pub(super) wall: Option<String>,
}

fn seat_like(category: &str) -> bool {
    Knowledge::builtin()
        .prior(category)
        .is_some_and(|p| p.shape == NominalShape::Seat)
        || [
            "chair",
            "stool",
            "bench",
            "bean_bag",
            "ottoman",
            "wheelchair",
        ]
        .iter()
        .any(|w| category.contains(w))
}

fn yaw_toward(from: [f64; 2], to: [f64; 2]) -> f64 {
    (to[0] - from[0]).atan2(to[1] - from[1])
}

/// Whether mounted object `p` may hang where it is: over no other mounted object, clear of
/// the doors of the floor and hung objects around it (and theirs of it), outside the areas
/// the plan keeps clear (a house room's doorways; below a window's cover height in front of
/// it), free floor in front.
pub(super) fn mount_ok(state: &FloorState<'_>, p: &Placed) -> bool {
    let fp = &p.fp;
    if state
        .placed
        .iter()
        .filter(|p| p.mounted)
        .any(|p| p.fp.overlaps(fp, 0.1))
        || state.in_a_swing(fp, WALL_MOUNT_HEIGHT - 0.5)
        || state.in_a_hung_swing(p)
        || state.hangs_in_keep_clear(p)
    {
        return false;
    }
    let front = fp.to_world(0.0, fp.hz + 0.35);
    let band = Footprint {
        cx: front[0],
        cz: front[1],
        yaw: fp.yaw,
        hx: fp.hx,
        hz: 0.35,
    };
    !state
        .placed
        .iter()
        .filter(|p| !p.mounted)
        .any(|p| p.fp.overlaps(&band, 0.0))
        && !state.door_zone.is_some_and(|d| d.overlaps(&band, 0.0))
}

pub(super) fn candidates(
    state: &FloorState<'_>,
    o: &PlannedObject,
    info: &AssetInfo,
    sides: &[Side],
    infos: &[AssetInfo],
    rng: &mut ChaCha8Rng,
) -> Vec<Candidate> {
    let (hx, hz) = (info.size[0] as f64 / 2.0, info.size[2] as f64 / 2.0);
    let plan = state.plan;
    let is_anchor = o.id == plan.anchor;
    let mut out = Vec::new();
    if is_anchor && matches!(o.zone, Zone::Wall { .. }) {
        out.extend(anchor_wall_candidates(o, sides, hx, hz, rng));
        return out;
    }
    match &o.zone {
        Zone::Wall { wall: Some(w) } => {
            if let Some(side) = sides.iter().find(|s| s.id.as_deref() == Some(w)) {
                out.extend(wall_candidates(side, hx, hz, rng));
            }
        }
        Zone::Wall { wall: None } => out.extend(any_wall_candidates(state, o, sides, hx, hz, rng)),
        Zone::Corner => out.extend(corner_candidates(sides, hx, hz, rng)),
        Zone::Center => out.extend(center_candidates(state, hx, hz, rng, is_anchor)),
        Zone::Rows => out.extend(row_candidates(state, hx, hz, seat_like(&o.category))),
        Zone::Free => {}
        Zone::WallMounted => {
            let mut order: Vec<usize> = (0..sides.len()).collect();
            order.shuffle(rng);
            for k in order {
                out.extend(wall_candidates(
                    &sides[k],
                    hx,
                    (info.size[2] as f64 / 2.0).max(0.005),
                    rng,
                ));
            }
        }
        Zone::Relative => out.extend(relative_candidates(state, o, hx, hz, infos, rng)),
        Zone::Supported => {}
    }
    if (matches!(o.zone, Zone::Free | Zone::Center | Zone::Rows)
        || (o.zone == Zone::Relative && !must_flank_target(state, o))
        || (is_anchor && out.is_empty()))
    {
        add_free_candidates(state, o, info, rng, &mut out);
    }
    order_by_service(state, o, &mut out);
    out
}

/// Whether `o` must stand at a side of its positional target (a nightstand by its bed, a
/// judged `flanks` rule) in a room whose walls are given ([`crate::Plan::room_is_fixed`]: a house
/// room): no spot elsewhere on the floor serves it there. A room sized to its plan keeps the
/// fallback spots (before the foot, elsewhere on the floor): its flanks are rarely taken, the
/// judge re-plans the layout when it is, and its layouts (the seeded spot draws) stay those
/// the single-room measurements and fixtures were made with.
fn must_flank_target(state: &FloorState<'_>, o: &PlannedObject) -> bool {
    if !state.plan.room_is_fixed() {
        return false;
    }
    positional_target(o)
        .and_then(|t| state.index_of(t))
        .is_some_and(|t| {
            ArrangementRules::builtin().must_flank(&o.category, &state.plan.objects[t].category)
        })
}

/// Spots along any wall: with a target to face, the wall facing it first (nearest the
/// target's line first), then the other walls in a random order, those from which the object
/// would not face its target last.
fn any_wall_candidates(
    state: &FloorState<'_>,
    o: &PlannedObject,
    sides: &[Side],
    hx: f64,
    hz: f64,
    rng: &mut ChaCha8Rng,
) -> Vec<Candidate> {
    let mut out = Vec::new();
    // Opposite a target: the wall facing it first.
    let facing = o
        .relations
        .iter()
        .find(|r| r.kind == RelationKind::Facing)
        .and_then(|r| state.index_of(&r.target))
        .and_then(|t| state.placed_of(t));
    let mut order: Vec<usize> = (0..sides.len()).collect();
    order.shuffle(rng);
    if let Some(t) = facing {
        let (_, f) = t.fp.axes();
        order.sort_by(|&a, &b| {
            let da = sides[a].normal[0] * f[0] + sides[a].normal[1] * f[1];
            let db = sides[b].normal[0] * f[0] + sides[b].normal[1] * f[1];
            da.total_cmp(&db)
        });
        let side = &sides[order[0]];
        let s_t =
            (t.fp.cx - side.face[0]) * side.along[0] + (t.fp.cz - side.face[1]) * side.along[1];
        let lim = side.limit(hx);
        if lim > 0.0 {
            let mut ss: Vec<f64> = (0..=(2.0 * lim / 0.1) as usize)
                .map(|k| -lim + k as f64 * 0.1)
                .collect();
            ss.sort_by(|a, b| (a - s_t).abs().total_cmp(&(b - s_t).abs()));
            out.extend(ss.into_iter().map(|s| Candidate {
                fp: side.footprint_at(s, hx, hz),
                wall: side.id.clone(),
            }));
        }
        order.remove(0);
    }
    for k in order {
        out.extend(wall_candidates(&sides[k], hx, hz, rng));
    }
    if let Some(t) = facing {
        // Places on the other walls from which the object would not face its target
        // (a television on a side wall, turned away from the sofa) come last.
        let faces = |c: &Candidate| {
            let d = [t.fp.cx - c.fp.cx, t.fp.cz - c.fp.cz];
            let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
            len > 1e-9
                && (c.fp.yaw.sin() * d[0] + c.fp.yaw.cos() * d[1]) / len >= 50f64.to_radians().cos()
        };
        out.sort_by_key(|c| !faces(c));
    }
    out
}

/// Appends free spots on the floor (a seat turned toward the anchor); a desk of the rows
/// turns like the rows.
fn add_free_candidates(
    state: &FloorState<'_>,
    o: &PlannedObject,
    info: &AssetInfo,
    rng: &mut ChaCha8Rng,
    out: &mut Vec<Candidate>,
) {
    let anchor_toward = state
        .index_of(&state.plan.anchor)
        .and_then(|a| state.placed_of(a))
        .map(|p| [p.fp.cx, p.fp.cz]);
    let seat = seat_like(&o.category);
    let facing = seat.then_some(anchor_toward).flatten();
    let from = out.len();
    out.extend(free_candidates(state, info, rng, facing));
    if o.zone == Zone::Rows {
        // A desk or seat of the rows that finds no row spot still turns like the rows (a pew
        // faces the altar squarely, not at an angle toward its centre).
        for c in &mut out[from..] {
            c.fp.yaw = row_yaw(seat);
        }
    }
}

/// The yaw of the rows: seats face the back wall, where the anchor stands (the altar, the
/// screen, the teacher's desk); desks turn their fronts to the seats drawn up behind them.
fn row_yaw(seat: bool) -> f64 {
    if seat {
        PI
    } else {
        0.0
    }
}

/// Orders `out` so that spots breaking the object's `faces` and `served by` rules come last.
fn order_by_service(state: &FloorState<'_>, o: &PlannedObject, out: &mut [Candidate]) {
    let serves = ArrangementRules::builtin().faces_of(&o.category);
    if !serves.is_empty() {
        // Spots from which the object would stand by a table (screen, …) of its `faces` rule
        // without facing any such table come last: a chair of the rows beside a desk it does
        // not serve.
        out.sort_by_key(|c| breaks_faces(state, &c.fp, &serves));
    }
    let served = ArrangementRules::builtin().served_by(&o.category);
    if !served.is_empty() && o.zone != Zone::Rows {
        // A table (desk, …) placed after its seats: spots that would stand it within reach of
        // a placed seat that does not face it come last. Desks of the rows keep the rows'
        // order: their seats are drawn up to them afterwards.
        out.sort_by_key(|c| strands_a_seat(state, &c.fp, &served));
    }
}

/// Whether a subject at `subject` faces a target at `target`: its front within 50° of the
/// target's centre, or squarely before the target's front.
fn faces_footprint(subject: &Footprint, target: &Footprint) -> bool {
    let cos50 = 50f64.to_radians().cos();
    let (_, f) = subject.axes();
    let d = [target.cx - subject.cx, target.cz - subject.cz];
    let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
    let (_, tf) = target.axes();
    let toward = len > 1e-9 && (f[0] * d[0] + f[1] * d[1]) / len >= cos50;
    let square = -(f[0] * tf[0] + f[1] * tf[1]) >= cos50 && -(d[0] * tf[0] + d[1] * tf[1]) > 0.0;
    toward || square
}

/// Whether a target of `served`'s rules at `fp` would have a placed subject within reach that
/// does not face it.
fn strands_a_seat(state: &FloorState<'_>, fp: &Footprint, served: &[(&[String], f64)]) -> bool {
    served.iter().any(|(subjects, within)| {
        state
            .placed
            .iter()
            .filter(|p| !p.mounted)
            .filter(|p| subjects.contains(&state.plan.objects[p.plan_index].category))
            .any(|p| p.fp.overlaps(fp, 2.0 * within) && !faces_footprint(&p.fp, fp))
    })
}

/// Whether an object at `fp` would have one of `serves`' targets within reach and face none of
/// them (the judge's `faces` rule, on footprints: within reach by the gap of the world boxes,
/// as the judge measures it, so facing a table the judge deems out of reach does not count;
/// facing: front within 50° of the target's centre, or squarely before its front).
fn breaks_faces(state: &FloorState<'_>, fp: &Footprint, serves: &[(&[String], f64)]) -> bool {
    let boxed = |f: &Footprint| {
        let [x0, z0, x1, z1] = f.bounds(0.0);
        Aabb::new(Point3::new(x0, 0.0, z0), Point3::new(x1, 0.0, z1))
    };
    let here = boxed(fp);
    serves.iter().any(|(targets, within)| {
        let mut near = state
            .placed
            .iter()
            .filter(|p| !p.mounted)
            .filter(|p| targets.contains(&state.plan.objects[p.plan_index].category))
            .filter(|p| aabb_floor_gap(&boxed(&p.fp), &here) <= *within)
            .peekable();
        near.peek().is_some() && !near.any(|t| faces_footprint(fp, &t.fp))
    })
}

fn anchor_wall_candidates(
    o: &PlannedObject,
    sides: &[Side],
    hx: f64,
    hz: f64,
    rng: &mut ChaCha8Rng,
) -> Vec<Candidate> {
    let wall = match &o.zone {
        Zone::Wall { wall: Some(w) } => w.clone(),
        _ => "wall_0".to_owned(),
    };
    let mut out = Vec::new();
    let mut order: Vec<&Side> = sides
        .iter()
        .filter(|s| s.id.as_deref() == Some(wall.as_str()))
        .collect();
    if o.relations
        .iter()
        .all(|r| r.kind != RelationKind::AgainstWall)
    {
        order.extend(
            sides
                .iter()
                .filter(|s| s.id.as_deref() != Some(wall.as_str())),
        );
    }
    for side in order {
        let lim = side.limit(hx);
        if lim < 0.0 {
            continue;
        }
        let jitter = rng.random_range(-0.25..=0.25) * lim.min(1.2);
        let mut ss: Vec<f64> = vec![jitter];
        let mut k = 1.0;
        while k * 0.1 <= 2.0 * lim {
            ss.push(jitter + k * 0.1);
            ss.push(jitter - k * 0.1);
            k += 1.0;
        }
        out.extend(
            ss.into_iter()
                .filter(|s| s.abs() <= lim)
                .map(|s| Candidate {
                    fp: side.footprint_at(s, hx, hz),
                    wall: side.id.clone(),
                }),
        );
    }
    out
}

fn wall_candidates(side: &Side, hx: f64, hz: f64, rng: &mut ChaCha8Rng) -> Vec<Candidate> {
    let lim = side.limit(hx);
    if lim < 0.0 {
        return Vec::new();
    }
    let steps = (2.0 * lim / 0.1).floor() as usize;
    let mut ss: Vec<f64> = (0..=steps).map(|k| -lim + k as f64 * 0.1).collect();
    ss.push(lim);
    if rng.random_bool(0.5) {
        ss.reverse();
    }
    ss.into_iter()
        .map(|s| Candidate {
            fp: side.footprint_at(s, hx, hz),
            wall: side.id.clone(),
        })
        .collect()
}

fn corner_candidates(sides: &[Side], hx: f64, hz: f64, rng: &mut ChaCha8Rng) -> Vec<Candidate> {
    let mut out = Vec::new();
    let mut options: Vec<(usize, f64)> = (0..sides.len())
        .flat_map(|k| [(k, -1.0), (k, 1.0)])
        .collect();
    options.shuffle(rng);
    for (k, sign) in options {
        let side = &sides[k];
        let lim = side.limit(hx);
        if lim < 0.0 {
            continue;
        }
        for back in [0.0, 0.1, 0.2] {
            out.push(Candidate {
                fp: side.footprint_at(sign * (lim - back), hx, hz),
                wall: side.id.clone(),
            });
        }
    }
    out
}

fn center_candidates(
    state: &FloorState<'_>,
    hx: f64,
    hz: f64,
    rng: &mut ChaCha8Rng,
    anchor: bool,
) -> Vec<Candidate> {
    let [x0, z0, x1, z1] = state.floor;
    let (w, d) = (x1 - x0, z1 - z0);
    // Long side along the room's long side; flipped at random for variety.
    let base = if (hx >= hz) == (w >= d) {
        0.0
    } else {
        FRAC_PI_2
    };
    let yaw = if rng.random_bool(0.5) {
        base
    } else {
        base + PI
    };
    let (cx, cz) = (
        (x0 + x1) / 2.0 + rng.random_range(-0.2..=0.2),
        (z0 + z1) / 2.0 - if anchor { 0.1 * d } else { 0.0 } + rng.random_range(-0.2..=0.2),
    );
    let mut out = vec![];
    for ring in 0..16 {
        let radius = ring as f64 * 0.15;
        let n = if ring == 0 { 1 } else { 8 + ring * 2 };
        let phase = rng.random_range(0.0..(2.0 * PI));
        for k in 0..n {
            let a = phase + k as f64 / n as f64 * 2.0 * PI;
            for y in [yaw, yaw + FRAC_PI_2] {
                out.push(Candidate {
                    fp: Footprint {
                        cx: cx + radius * a.cos(),
                        cz: cz + radius * a.sin(),
                        yaw: y,
                        hx,
                        hz,
                    },
                    wall: None,
                });
            }
        }
    }
    out
}

/// Spots on a grid of rows before the room's front (the wall at minimum z, where the anchor
/// stands). A desk of the rows is turned like the anchor, so whoever sits at its front looks to
/// the room's front; a seat of the rows faces the front.
fn row_candidates(state: &FloorState<'_>, hx: f64, hz: f64, seat: bool) -> Vec<Candidate> {
    let [x0, z0, x1, z1] = state.floor;
    // Rows of desks leave room for the seats drawn up to them; rows of seats (pews, a
    // cinema's recliners) only a walkway between one row's back and the next one's front.
    let (sx, sz) = (2.0 * hx + 1.0, 2.0 * hz + if seat { 1.0 } else { 1.5 });
    let (ax0, ax1) = (x0 + 0.9 + hx, x1 - 0.9 - hx);
    let (az0, az1) = (z0 + 1.9 + hz, z1 - 1.3 - hz);
    let mut out = Vec::new();
    if ax1 < ax0 || az1 < az0 {
        return out;
    }
    let cols = ((ax1 - ax0) / sx).floor() as usize + 1;
    let rows = ((az1 - az0) / sz).floor() as usize + 1;
    let off_x = (ax1 - ax0 - (cols - 1) as f64 * sx) / 2.0;
    for r in 0..rows {
        for c in 0..cols {
            let fp = Footprint {
                cx: ax0 + off_x + c as f64 * sx,
                cz: az0 + r as f64 * sz,
                yaw: row_yaw(seat),
                hx,
                hz,
            };
            out.push(Candidate { fp, wall: None });
        }
    }
    out
}

pub(super) fn free_candidates(
    state: &FloorState<'_>,
    info: &AssetInfo,
    rng: &mut ChaCha8Rng,
    face: Option<[f64; 2]>,
) -> Vec<Candidate> {
    let (hx, hz) = (info.size[0] as f64 / 2.0, info.size[2] as f64 / 2.0);
    let [x0, z0, x1, z1] = state.floor;
    let r = hx.max(hz) + 0.05;
    let mut out = Vec::new();
    if x1 - x0 <= 2.0 * r || z1 - z0 <= 2.0 * r {
        return out;
    }
    for _ in 0..240 {
        let x = rng.random_range(x0 + r..=x1 - r);
        let z = rng.random_range(z0 + r..=z1 - r);
        let yaw = match face {
            Some(t) => yaw_toward([x, z], t),
            None => rng.random_range(0..4) as f64 * FRAC_PI_2,
        };
        out.push(Candidate {
            fp: Footprint {
                cx: x,
                cz: z,
                yaw,
                hx,
                hz,
            },
            wall: None,
        });
    }
    out
}

fn relative_candidates(
    state: &FloorState<'_>,
    o: &PlannedObject,
    hx: f64,
    hz: f64,
    infos: &[AssetInfo],
    rng: &mut ChaCha8Rng,
) -> Vec<Candidate> {
    let _ = infos;
    let Some(target_id) = positional_target(o) else {
        return Vec::new();
    };
    let Some(ti) = state.index_of(target_id) else {
        return Vec::new();
    };
    let Some(t) = state.placed_of(ti) else {
        return Vec::new();
    };
    let kind = o
        .relations
        .iter()
        .find(|r| {
            r.target == target_id
                && !matches!(
                    r.kind,
                    RelationKind::AgainstWall | RelationKind::LeftOf | RelationKind::RightOf
                )
        })
        .map(|r| r.kind)
        .unwrap_or(RelationKind::Beside);
    let side_rel = o
        .relations
        .iter()
        .find(|r| matches!(r.kind, RelationKind::LeftOf | RelationKind::RightOf))
        .map(|r| r.kind);
    let facing = o
        .relations
        .iter()
        .find(|r| r.kind == RelationKind::Facing && r.target != target_id)
        .or_else(|| o.relations.iter().find(|r| r.kind == RelationKind::Facing))
        .and_then(|r| state.index_of(&r.target))
        .and_then(|i| state.placed_of(i))
        .map(|p| [p.fp.cx, p.fp.cz]);
    let (r_t, f_t) = t.fp.axes();
    // Which of the objects sharing this relation to the target this one is.
    let peers: Vec<&PlannedObject> = state
        .plan
        .objects
        .iter()
        .filter(|p| {
            p.zone == Zone::Relative
                && positional_target(p) == Some(target_id)
                && p.relations
                    .iter()
                    .any(|r| r.kind == kind && r.target == target_id)
        })
        .collect();
    let near = NearTarget {
        target: t.fp,
        tc: [t.fp.cx, t.fp.cz],
        r_t,
        f_t,
        hx,
        hz,
        k: peers.iter().position(|p| p.id == o.id).unwrap_or(0),
        n: peers.len().max(1),
        seat: seat_like(&o.category),
        facing,
    };
    match kind {
        RelationKind::InFrontOf | RelationKind::Behind => near.in_front_or_behind(kind, rng),
        RelationKind::Beside | RelationKind::LeftOf | RelationKind::RightOf => {
            near.beside(side_rel, kind, must_flank_target(state, o), rng)
        }
        RelationKind::Facing => near.facing(rng),
        RelationKind::Around => near.around(),
        _ => Vec::new(),
    }
}

/// `a + s·b`.
fn add(a: [f64; 2], s: f64, b: [f64; 2]) -> [f64; 2] {
    [a[0] + s * b[0], a[1] + s * b[1]]
}

/// An object placed relative to a target already on the floor: the target's footprint,
/// centre and axes, the object's half extents, and which of its peers (objects in the same
/// relation to the target) it is.
struct NearTarget {
    target: Footprint,
    /// The target's centre.
    tc: [f64; 2],
    /// The target's right and front axes.
    r_t: [f64; 2],
    f_t: [f64; 2],
    hx: f64,
    hz: f64,
    /// This object's index among its `n` peers.
    k: usize,
    n: usize,
    seat: bool,
    /// Where the object it should face stands, if any.
    facing: Option<[f64; 2]>,
}

impl NearTarget {
    /// A candidate centred at `c` turned to `yaw`.
    fn at(&self, c: [f64; 2], yaw: f64) -> Candidate {
        Candidate {
            fp: Footprint {
                cx: c[0],
                cz: c[1],
                yaw,
                hx: self.hx,
                hz: self.hz,
            },
            wall: None,
        }
    }

    /// Half extent along `dir` of this object's footprint turned to `yaw`.
    fn extent_at(&self, yaw: f64, dir: [f64; 2]) -> f64 {
        Footprint {
            cx: 0.0,
            cz: 0.0,
            yaw,
            hx: self.hx,
            hz: self.hz,
        }
        .extent_along(dir)
    }

    /// In front of or behind the target: rows of gaps along its front axis, spread
    /// sideways among the peers.
    fn in_front_or_behind(&self, kind: RelationKind, rng: &mut ChaCha8Rng) -> Vec<Candidate> {
        let (t, tc, r_t, f_t) = (&self.target, self.tc, self.r_t, self.f_t);
        let mut out = Vec::new();
        let dir = if kind == RelationKind::InFrontOf {
            1.0
        } else {
            -1.0
        };
        let yaw = match self.facing {
            Some(_) => None,
            None if self.seat && kind == RelationKind::InFrontOf => Some(t.yaw + PI),
            None => Some(t.yaw),
        };
        let base_gap = if self.seat { 0.06 } else { 0.45 };
        let lateral = if self.n > 1 {
            ((self.k as f64 + 0.5) / self.n as f64 * 2.0 - 1.0) * t.hx
        } else {
            rng.random_range(-0.05..=0.05)
        };
        for gap in [
            base_gap,
            base_gap + 0.1,
            base_gap + 0.25,
            base_gap + 0.45,
            base_gap + 0.7,
        ] {
            for dl in [0.0, 0.2, -0.2, 0.4, -0.4] {
                let probe = add(
                    add(tc, dir * (t.hz + gap + self.hz), f_t),
                    lateral + dl,
                    r_t,
                );
                let y = yaw.unwrap_or_else(|| yaw_toward(probe, self.facing.unwrap_or(tc)));
                let e = self.extent_at(y, f_t);
                let c = add(add(tc, dir * (t.hz + gap + e), f_t), lateral + dl, r_t);
                out.push(self.at(c, y));
            }
        }
        out
    }

    /// Beside the target (or on the side `side_rel` names): both flanks at growing gaps,
    /// then, when no side is stated and the object need not flank the target
    /// (`flanks_only`, a nightstand by its bed), in front, behind and diagonally.
    fn beside(
        &self,
        side_rel: Option<RelationKind>,
        kind: RelationKind,
        flanks_only: bool,
        rng: &mut ChaCha8Rng,
    ) -> Vec<Candidate> {
        let (t, tc, r_t, f_t) = (&self.target, self.tc, self.r_t, self.f_t);
        let mut out = Vec::new();
        let sides: Vec<f64> = match side_rel.unwrap_or(kind) {
            RelationKind::LeftOf => vec![-1.0],
            RelationKind::RightOf => vec![1.0],
            _ => {
                let first = if (self.k % 2 == 0) == rng.random_bool(0.5) {
                    1.0
                } else {
                    -1.0
                };
                vec![first, -first]
            }
        };
        for side in sides {
            for gap in [0.05, 0.12, 0.25, 0.4, 0.6, 0.9, 1.3] {
                let y = match self.facing {
                    Some(f) => {
                        let probe = add(tc, side * (t.hx + gap + self.hx), r_t);
                        yaw_toward(probe, f)
                    }
                    None => t.yaw,
                };
                let e_r = self.extent_at(y, r_t);
                let e_f = self.extent_at(y, f_t);
                let along_f = if self.facing.is_some() {
                    0.0
                } else {
                    e_f - t.hz
                };
                let c = add(add(tc, side * (t.hx + gap + e_r), r_t), along_f, f_t);
                out.push(self.at(c, y));
            }
        }
        if side_rel.is_none() && !flanks_only {
            self.around_flanks(&mut out);
        }
        out
    }

    /// Both flanks taken (a corner, a wall, a neighbour): "beside" also holds in front,
    /// behind or diagonally, as long as the gap stays under a metre.
    fn around_flanks(&self, out: &mut Vec<Candidate>) {
        let (t, tc, r_t, f_t) = (&self.target, self.tc, self.r_t, self.f_t);
        for gap in [0.08, 0.25, 0.45, 0.7] {
            for (a, b) in [
                (0.0, 1.0),
                (1.0, 1.0),
                (-1.0, 1.0),
                (0.0, -1.0),
                (1.0, -1.0),
                (-1.0, -1.0),
            ] {
                let dir = [a * r_t[0] + b * f_t[0], a * r_t[1] + b * f_t[1]];
                let len = (dir[0] * dir[0] + dir[1] * dir[1]).sqrt();
                let dir = [dir[0] / len, dir[1] / len];
                let probe = add(tc, t.extent_along(dir) + gap + self.hx.max(self.hz), dir);
                let y = match self.facing {
                    Some(f) => yaw_toward(probe, f),
                    None => t.yaw,
                };
                let dist = t.extent_along(dir) + gap + self.extent_at(y, dir);
                out.push(self.at(add(tc, dist, dir), y));
            }
        }
    }

    /// Facing the target: a fan of angles about its front, alternating sides among the
    /// peers, at growing distances, each turned toward the target.
    fn facing(&self, rng: &mut ChaCha8Rng) -> Vec<Candidate> {
        let (t, tc, r_t, f_t) = (&self.target, self.tc, self.r_t, self.f_t);
        let mut out = Vec::new();
        let mut angles: Vec<f64> = vec![];
        for a in [60.0f64, 72.0, 48.0, 84.0, 36.0, 24.0, 96.0, 12.0, 0.0] {
            let s = if (self.k % 2 == 0) == rng.random_bool(0.5) {
                1.0
            } else {
                -1.0
            };
            angles.push(s * a.to_radians());
            if a != 0.0 {
                angles.push(-s * a.to_radians());
            }
        }
        for extra in [0.9, 1.2, 0.7, 1.6, 2.1] {
            for &a in &angles {
                let (sa, ca) = a.sin_cos();
                let dir = [f_t[0] * ca + r_t[0] * sa, f_t[1] * ca + r_t[1] * sa];
                let dist = t.extent_along(dir) + self.hx.max(self.hz) + extra;
                let c = add(tc, dist, dir);
                out.push(self.at(c, yaw_toward(c, tc)));
            }
        }
        out
    }

    /// Around the target (chairs around a table): slots along its long sides, and its ends
    /// when wide enough, each object starting at its own slot, turned toward the target.
    fn around(&self) -> Vec<Candidate> {
        let (t, hx, hz) = (&self.target, self.hx, self.hz);
        let mut out = Vec::new();
        let long_x = t.hx >= t.hz;
        let mut slots: Vec<([f64; 2], f64)> = Vec::new(); // (local normal, along offset)
        let along_len = if long_x { t.hx } else { t.hz };
        let per_side = (((2.0 * along_len) / (2.0 * hx + 0.12)).floor() as usize).max(1);
        let long_normals: [[f64; 2]; 2] = if long_x {
            [[0.0, 1.0], [0.0, -1.0]]
        } else {
            [[1.0, 0.0], [-1.0, 0.0]]
        };
        for m in 0..per_side {
            let off = ((m as f64 + 0.5) / per_side as f64 * 2.0 - 1.0) * along_len;
            for nrm in long_normals {
                slots.push((nrm, off));
            }
        }
        let short_len = if long_x { t.hz } else { t.hx };
        if 2.0 * short_len >= 2.0 * hx * 0.8 {
            let ends: [[f64; 2]; 2] = if long_x {
                [[1.0, 0.0], [-1.0, 0.0]]
            } else {
                [[0.0, 1.0], [0.0, -1.0]]
            };
            for nrm in ends {
                slots.push((nrm, 0.0));
            }
        }
        // Spread: reorder so consecutive chairs alternate sides.
        let start = self.k % slots.len().max(1);
        let ordered: Vec<([f64; 2], f64)> = slots
            .iter()
            .cycle()
            .skip(start)
            .take(slots.len())
            .copied()
            .collect();
        for gap in [0.04, 0.12, 0.25] {
            for (nrm, off) in &ordered {
                let (lx, lz) = (nrm[0], nrm[1]);
                let half_n = if lx != 0.0 { t.hx } else { t.hz };
                let (ox, oz) = if lx != 0.0 {
                    (lx * (half_n + gap + hz), *off)
                } else {
                    (*off, lz * (half_n + gap + hz))
                };
                let c = t.to_world(ox, oz);
                let toward = t.to_world(
                    if lx != 0.0 { 0.0 } else { ox },
                    if lx != 0.0 { oz } else { 0.0 },
                );
                out.push(self.at(c, yaw_toward(c, toward)));
            }
        }
        out
    }
}
