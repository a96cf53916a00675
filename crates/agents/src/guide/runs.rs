//! Runs: the members of a `[[runs]]` arrangement rule (kitchen counters, cabinets, sink, stove,
//! fridge) placed edge to edge along the walls before any other floor object — along one wall,
//! two (an L), three (a U) or two facing walls (a galley), the shape drawn per seed unless the
//! prompt names one — then an island free in front of the run, facing it, and, later, wall
//! cabinets hung above it.
//!
//! The main run always stands on the back wall (`wall_0`, where the planner puts a wall anchor);
//! legs run from its corners along the side walls; a galley's second run stands on the door wall
//! beside the door. At a corner one piece owns the corner: either the main run's end piece
//! reaches into it and the leg starts in front of that piece, or the leg's first piece stands in
//! the corner and the main run starts beside it. The piece in the corner is then blind (the other
//! stands in front of its end), so a layout is kept only when the blind piece has nothing that
//! opens there (a sink's open bay) and no piece stands in another's opening: with doors and
//! drawers on most pieces, most kitchens get one wall or a galley. Neighbours keep [`RUN_GAP`]
//! apart, so their boxes touch within the rule's gap and never interpenetrate.

use std::f64::consts::PI;

use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use scenethesis_scene_graph::AssetInfo;
use scenethesis_scene_graph::{ParentRef, RelationKind};

use super::geometry::Footprint;
use super::room::Side;
use super::shared::Placed;
use super::walkway::FloorState;
use crate::arrangement::{ArrangementRules, RunsRule};
use crate::plan::Zone;

/// Gap between neighbouring pieces of a run, in metres.
pub(super) const RUN_GAP: f64 = 0.02;
/// Bottom height of cabinets hung above a run (a worktop at ≈ 0.9 m plus 0.55 m).
pub(super) const ABOVE_RUN_BOTTOM: f64 = 1.45;
/// Clearance kept between a piece under a hung cabinet and the cabinet (items on the worktop).
const ABOVE_RUN_CLEARANCE: f64 = 0.25;
/// Distance from a wall's face to a backed piece (as [`Side::footprint_at`] keeps it).
const WALL_GAP: f64 = 0.01;
/// Extra slack at the free end of a leg (before the door wall), in metres.
const LEG_END: f64 = 0.05;

/// The shape of the runs of a room.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum RunShape {
    /// One run along the back wall.
    OneWall,
    /// The back wall and the left wall.
    LLeft,
    /// The back wall and the right wall.
    LRight,
    /// The back wall and both side walls.
    U,
    /// The back wall and, facing it, the door wall beside the door.
    Galley,
}

impl RunShape {
    /// The name prompts and reports use (`one-wall`, `l-shaped`, `u-shaped`, `galley`).
    pub(crate) fn name(self) -> &'static str {
        match self {
            RunShape::OneWall => "one-wall",
            RunShape::LLeft | RunShape::LRight => "l-shaped",
            RunShape::U => "u-shaped",
            RunShape::Galley => "galley",
        }
    }
}

/// The runs placed in a room: which rule, its shape and members.
#[derive(Debug, Clone)]
pub(super) struct PlacedRuns {
    /// The rule the runs follow.
    pub(super) rule: &'static RunsRule,
    /// The members placed, by plan index.
    pub(super) members: Vec<usize>,
    /// Members left out so that the others form the runs within a room's fixed walls
    /// ([`crate::Plan::room_is_fixed`]), by plan index.
    pub(super) left_out: Vec<usize>,
}

/// One piece to lay: plan index, width along the wall, depth off it.
#[derive(Debug, Clone, Copy)]
struct Piece {
    index: usize,
    w: f64,
    d: f64,
}

/// The plan's run members for `rule`: ground objects of a member category that stand against a
/// wall (wall, corner or anchor zone) or beside another member; `None` when the rule does not
/// apply to the plan.
fn members(state: &FloorState<'_>, rule: &RunsRule) -> Option<Vec<usize>> {
    let plan = state.plan;
    let floor: Vec<usize> = (0..plan.objects.len())
        .filter(|&i| plan.objects[i].parent == ParentRef::Ground)
        .collect();
    if !rule.applies(floor.iter().map(|&i| plan.objects[i].category.as_str())) {
        return None;
    }
    let is_member = |i: usize| rule.members.contains(&plan.objects[i].category);
    let out: Vec<usize> = floor
        .iter()
        .copied()
        .filter(|&i| is_member(i))
        .filter(|&i| {
            let o = &plan.objects[i];
            match &o.zone {
                Zone::Wall { wall } => wall.as_deref().is_none_or(|w| w == "wall_0"),
                Zone::Corner => true,
                Zone::Relative => o.relations.iter().all(|r| {
                    matches!(r.kind, RelationKind::Beside | RelationKind::AgainstWall)
                        && state.index_of(&r.target).is_some_and(is_member)
                }),
                _ => false,
            }
        })
        .collect();
    (out.len() >= 2).then_some(out)
}

/// The order of the pieces along a run: the `ends` first (one end), then cabinets, the sink,
/// the dishwasher (next to the sink, as it is plumbed), counters and the stove, each member
/// that is beside another member moved next to it.
fn sequence(state: &FloorState<'_>, rule: &RunsRule, members: &[usize]) -> Vec<usize> {
    let plan = state.plan;
    let role = |i: usize| -> u8 {
        let c = plan.objects[i].category.as_str();
        if rule.ends.iter().any(|e| e == c) {
            0
        } else {
            match c {
                "cabinet" => 1,
                "sink" => 2,
                "dishwasher" => 3,
                "kitchen_counter" => 4,
                "stove" => 5,
                _ => 6,
            }
        }
    };
    let mut seq: Vec<usize> = members.to_vec();
    seq.sort_by_key(|&i| (role(i), i));
    for &i in members {
        let target = plan.objects[i]
            .relations
            .iter()
            .find(|r| r.kind == RelationKind::Beside)
            .and_then(|r| state.index_of(&r.target))
            .filter(|t| members.contains(t));
        let Some(t) = target else { continue };
        let (pi, pt) = (
            seq.iter().position(|&x| x == i).expect("member"),
            seq.iter().position(|&x| x == t).expect("member"),
        );
        if pi.abs_diff(pt) == 1 {
            continue;
        }
        seq.remove(pi);
        let pt = seq.iter().position(|&x| x == t).expect("member");
        seq.insert(pt + 1, i);
    }
    seq
}

/// The shape the prompt names, if any.
fn named_shape(rule: &RunsRule, prompt: &str) -> Option<&'static str> {
    let prompt = prompt.to_lowercase();
    for (name, words) in &rule.shapes {
        if words.iter().any(|w| prompt.contains(&w.to_lowercase())) {
            return ["one-wall", "l-shaped", "u-shaped", "galley"]
                .into_iter()
                .find(|n| n == name);
        }
    }
    None
}

/// Places the runs of the first applicable `[[runs]]` rule (and its island) before the other
/// floor objects; the shape is drawn from `seed` among those that fit, keep the walkway open
/// and leave the door free. Returns `None` (and places nothing) when no rule applies or no
/// shape fits.
pub(super) fn place_runs(
    state: &mut FloorState<'_>,
    infos: &[AssetInfo],
    sides: &[Side],
    seed: u64,
) -> Option<PlacedRuns> {
    if sides.len() != 4 || sides.iter().any(|s| s.id.is_none()) {
        return None;
    }
    let rules = ArrangementRules::builtin();
    let (rule, members) = rules
        .runs
        .iter()
        .find_map(|r| members(state, r).map(|m| (r, m)))?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x7275_6e73_5f6b_6974);
    let piece = |i: usize| Piece {
        index: i,
        w: infos[i].size[0] as f64,
        d: infos[i].size[2] as f64,
    };
    let mut seq: Vec<Piece> = sequence(state, rule, &members)
        .into_iter()
        .map(piece)
        .collect();
    let mut left_out = Vec::new();
    loop {
        if let Some(mut placed) = lay_shapes(state, rule, infos, sides, &seq, &mut rng) {
            placed.left_out = left_out;
            return Some(placed);
        }
        // Fixed walls cannot grow around the runs: the runs go along another wall, or are
        // laid without a spare piece.
        if !state.plan.room_is_fixed() {
            return None;
        }
        if let Some(mut placed) = lay_along_another_wall(state, rule, infos, sides, &seq, &mut rng)
        {
            placed.left_out = left_out;
            return Some(placed);
        }
        let k = spare_piece(state, rule, &seq)?;
        left_out.push(seq.remove(k).index);
        if seq.len() < 2 {
            return None;
        }
    }
}

/// The piece of `seq` the runs can best do without: not asked for, not a sink, not the last
/// of the rule's `with` pieces; a dishwasher before a cabinet before a refrigerator before a
/// counter before the rest, the last such first; `None` when every piece is needed.
fn spare_piece(state: &FloorState<'_>, rule: &RunsRule, seq: &[Piece]) -> Option<usize> {
    let plan = state.plan;
    let category = |k: usize| plan.objects[seq[k].index].category.as_str();
    let rank = |c: &str| match c {
        "dishwasher" => 0,
        "cabinet" => 1,
        "refrigerator" => 2,
        "kitchen_counter" => 3,
        _ => 4,
    };
    let with = |k: usize| rule.with.iter().any(|w| w == category(k));
    let withs = (0..seq.len()).filter(|&k| with(k)).count();
    (0..seq.len())
        .filter(|&k| {
            !plan.objects[seq[k].index].hard && category(k) != "sink" && (!with(k) || withs > 1)
        })
        .min_by_key(|&k| (rank(category(k)), usize::MAX - k))
}

/// Lays `seq` as one run along a side wall or the door wall, the first that fits and keeps
/// the walkway open (a house kitchen whose back wall is mostly a passage), without islands.
fn lay_along_another_wall(
    state: &mut FloorState<'_>,
    rule: &'static RunsRule,
    infos: &[AssetInfo],
    sides: &[Side],
    seq: &[Piece],
    rng: &mut ChaCha8Rng,
) -> Option<PlacedRuns> {
    for turn in [1, 3, 2] {
        // The sides turned so that wall `turn` is the main run's.
        let turned: Vec<Side> = (0..4).map(|k| sides[(k + turn) % 4].clone()).collect();
        for order in [seq.to_vec(), seq.iter().rev().copied().collect()] {
            let split = (0, order.len(), 0);
            let Some(spots) = lay_split(RunShape::OneWall, split, &order, state, &turned, rng)
            else {
                continue;
            };
            let spots: Vec<(usize, Footprint, usize)> = spots
                .into_iter()
                .map(|(i, fp, k)| (i, fp, (k + turn) % 4))
                .collect();
            if commit_all(state, &spots, infos) {
                return Some(PlacedRuns {
                    rule,
                    members: spots.iter().map(|(i, _, _)| *i).collect(),
                    left_out: Vec::new(),
                });
            }
        }
    }
    None
}

/// Lays `seq` as the first shape (drawn from `rng`, the prompt's named one first) that fits,
/// keeps the walkway open and leaves the door free, with the rule's islands.
fn lay_shapes(
    state: &mut FloorState<'_>,
    rule: &'static RunsRule,
    infos: &[AssetInfo],
    sides: &[Side],
    seq: &[Piece],
    rng: &mut ChaCha8Rng,
) -> Option<PlacedRuns> {
    let mut shapes = vec![
        RunShape::OneWall,
        RunShape::LLeft,
        RunShape::LRight,
        RunShape::U,
        RunShape::Galley,
    ];
    shapes.shuffle(rng);
    if let Some(name) = named_shape(rule, &state.plan.prompt) {
        shapes.sort_by_key(|s| s.name() != name);
    }
    for shape in shapes {
        let mut orders = [seq.to_vec(), seq.iter().rev().copied().collect()];
        if rng.random_bool(0.5) {
            orders.swap(0, 1);
        }
        for order in &orders {
            let Some(spots) = lay(shape, order, state, sides, rng) else {
                continue;
            };
            if commit_all(state, &spots, infos) {
                let placed = PlacedRuns {
                    rule,
                    members: spots.iter().map(|(i, _, _)| *i).collect(),
                    left_out: Vec::new(),
                };
                place_islands(state, rule, infos, &placed, rng);
                return Some(placed);
            }
        }
    }
    None
}

/// Commits the spots one by one while each fits the floor, misses the others and the door and
/// keeps the walkway open; on any failure undoes them all and returns false.
fn commit_all(
    state: &mut FloorState<'_>,
    spots: &[(usize, Footprint, usize)],
    infos: &[AssetInfo],
) -> bool {
    let before = state.placed.len();
    for (i, fp, side) in spots {
        let p = Placed::standing(*i, *fp, &infos[*i]).against_wall(format!("wall_{side}"));
        // At a corner one piece stands in front of the other's end (a blind corner): that
        // one must have nothing opening there (a sink's open bay), or the layout is refused.
        if !state.fits(&p, RUN_GAP * 0.5) || !state.evaluate(Some(&p)).0 {
            state.placed.truncate(before);
            state.rebuild();
            return false;
        }
        state.commit(p);
    }
    true
}

/// The footprints of `order` laid out as `shape` (plan index, footprint, side index), or `None`
/// when it does not fit the walls.
fn lay(
    shape: RunShape,
    order: &[Piece],
    state: &FloorState<'_>,
    sides: &[Side],
    rng: &mut ChaCha8Rng,
) -> Option<Vec<(usize, Footprint, usize)>> {
    let mut splits = candidate_splits(shape, order.len());
    // Balanced splits first, then by the seed.
    splits.shuffle(rng);
    splits.sort_by(|a, b| {
        let spread = |s: &(usize, usize, usize)| s.1.abs_diff(s.0.max(s.2));
        spread(a).cmp(&spread(b))
    });
    splits
        .into_iter()
        .find_map(|split| lay_split(shape, split, order, state, sides, rng))
}

/// The start along `side` nearest `pick` within `lo..=hi` (in 5 cm steps) from which the
/// `main` run stays clear of the door's clearance and the areas the plan keeps clear (a house
/// room's other doors, whose walls the room cannot grow past); `None` when there is none.
fn clear_start(
    state: &FloorState<'_>,
    side: &Side,
    main: &[Piece],
    lo: f64,
    hi: f64,
    pick: f64,
) -> Option<f64> {
    let steps = ((hi - lo) / 0.05).floor() as usize;
    let mut starts: Vec<f64> = (0..=steps).map(|k| lo + k as f64 * 0.05).collect();
    starts.push(pick);
    starts.sort_by(|a, b| (a - pick).abs().total_cmp(&(b - pick).abs()));
    starts.into_iter().find(|&x0| {
        let mut x = x0;
        main.iter().all(|p| {
            let fp = side.footprint_at(x + p.w / 2.0, p.w / 2.0, p.d / 2.0);
            x += p.w + RUN_GAP;
            !state.in_door_ways(&fp)
        })
    })
}

/// Length of a run of `pieces`, gaps included.
fn run_length(pieces: &[Piece]) -> f64 {
    pieces.iter().map(|x| x.w).sum::<f64>() + RUN_GAP * pieces.len().saturating_sub(1) as f64
}

/// Candidate splits of `n` pieces for `shape`: (left leg, main, right leg / galley) as
/// counts.
fn candidate_splits(shape: RunShape, n: usize) -> Vec<(usize, usize, usize)> {
    let mut splits: Vec<(usize, usize, usize)> = Vec::new();
    match shape {
        RunShape::OneWall => splits.push((0, n, 0)),
        RunShape::LLeft => splits.extend((1..n).map(|k| (k, n - k, 0))),
        RunShape::LRight => splits.extend((1..n).map(|k| (0, n - k, k))),
        RunShape::U => {
            for a in 1..n {
                for b in 1..n.saturating_sub(a) {
                    splits.push((a, n - a - b, b));
                }
            }
        }
        RunShape::Galley => {
            if n >= 4 {
                splits.extend((2..=n - 2).map(|k| (0, n - k, k)));
            }
        }
    }
    splits
}

/// `order` laid out as `shape` with the split (left leg, main, right leg / galley), or `None`
/// when it does not fit or puts a member off the wall the plan gives it.
fn lay_split(
    shape: RunShape,
    (a, m, b): (usize, usize, usize),
    order: &[Piece],
    state: &FloorState<'_>,
    sides: &[Side],
    rng: &mut ChaCha8Rng,
) -> Option<Vec<(usize, Footprint, usize)>> {
    let n = order.len();
    let hw = sides[0].half_len;
    let hd = sides[1].half_len;
    let left = &order[..a];
    let main = &order[a..a + m];
    let right = &order[a + m..];
    let galley = shape == RunShape::Galley;
    let (own_l, own_r, lo, hi) = main_start_range(hw, left, main, right, galley)?;
    // Flush against a corner when there is a leg; anywhere (by the seed) otherwise.
    let x0 = if a > 0 {
        lo
    } else if b > 0 && !galley {
        hi
    } else {
        let pick = rng.random_range(lo..=hi.max(lo));
        if state.plan.room_is_fixed() {
            clear_start(state, &sides[0], main, lo, hi.max(lo), pick)?
        } else {
            pick
        }
    };
    let mut out = Vec::with_capacity(n);
    let mut x = x0;
    for p in main {
        out.push((
            p.index,
            sides[0].footprint_at(x + p.w / 2.0, p.w / 2.0, p.d / 2.0),
            0,
        ));
        x += p.w + RUN_GAP;
    }
    let back = -hd + WALL_GAP;
    if a > 0 {
        let start = if own_l {
            back + main[0].d + RUN_GAP
        } else {
            back
        };
        if !lay_leg(&mut left.iter().rev(), sides, 1, start, &mut out) {
            return None;
        }
    }
    if b > 0 && !galley {
        let start = if own_r {
            back + main.last().expect("main").d + RUN_GAP
        } else {
            back
        };
        if !lay_leg(&mut right.iter(), sides, 3, start, &mut out) {
            return None;
        }
    }
    if galley && !lay_galley(right, state, sides, rng, &mut out) {
        return None;
    }
    // A member the plan puts against a particular wall stays on it.
    let on_its_wall = out.iter().all(|(i, _, side)| {
        let o = &state.plan.objects[*i];
        o.relations
            .iter()
            .filter(|r| r.kind == RelationKind::AgainstWall)
            .all(|r| sides[*side].id.as_deref() == Some(r.target.as_str()))
    });
    on_its_wall.then_some(out)
}

/// The interval of the main run's start x0 (the run spans [x0, x0 + its length]) along a
/// back wall of half length `hw`, with which corners the main run's end pieces own (whether
/// they reach into the legs' depth), the first ownership that fits: (owns left, owns right,
/// lowest x0, highest x0).
fn main_start_range(
    hw: f64,
    left: &[Piece],
    main: &[Piece],
    right: &[Piece],
    galley: bool,
) -> Option<(bool, bool, f64, f64)> {
    let (a, b) = (left.len(), right.len());
    let lm = run_length(main);
    let (lo, hi) = (-hw + WALL_GAP, hw - WALL_GAP - lm);
    if hi < lo {
        return None;
    }
    // Corner ownership: per leg, whether the main run's end piece takes the corner.
    let owners: Vec<(bool, bool)> = match (a > 0, b > 0 && !galley) {
        (false, false) => vec![(true, true)],
        (true, false) => vec![(true, true), (false, true)],
        (false, true) => vec![(true, true), (true, false)],
        (true, true) => vec![(true, true), (true, false), (false, true), (false, false)],
    };
    for (main_owns_left, main_owns_right) in owners {
        let (mut l, mut h) = (lo, hi);
        if a > 0 {
            let d_leg = left.last().expect("leg").d;
            let corner = -hw + WALL_GAP;
            if main_owns_left {
                // The main run's first piece reaches into the leg's depth.
                h = h.min(corner + d_leg - 0.05);
                l = l.max(corner);
            } else {
                l = l.max(corner + d_leg + RUN_GAP);
                h = h.min(corner + d_leg + 0.045);
            }
        }
        if b > 0 && !galley {
            let d_leg = right[0].d;
            let corner = hw - WALL_GAP;
            if main_owns_right {
                l = l.max(corner - d_leg + 0.05 - lm);
                h = h.min(corner - lm);
            } else {
                h = h.min(corner - d_leg - RUN_GAP - lm);
                l = l.max(corner - d_leg - 0.045 - lm);
            }
        }
        if l <= h + 1e-9 {
            return Some((main_owns_left, main_owns_right, l, h));
        }
    }
    None
}

/// Lays a leg along `sides[side]`: legs run along +z from the back corner, from `start`, the
/// piece nearest the corner first. Whether it fits before the wall's end.
fn lay_leg(
    pieces: &mut dyn Iterator<Item = &Piece>,
    sides: &[Side],
    side: usize,
    start: f64,
    out: &mut Vec<(usize, Footprint, usize)>,
) -> bool {
    let hd = sides[1].half_len;
    let mut z = start;
    for p in pieces {
        if z + p.w > hd - WALL_GAP - LEG_END {
            return false;
        }
        out.push((
            p.index,
            sides[side].footprint_at(z + p.w / 2.0, p.w / 2.0, p.d / 2.0),
            side,
        ));
        z += p.w + RUN_GAP;
    }
    true
}

/// Lays the galley's second run beside the door on the door wall, flush in one of its
/// corners (by the seed). Whether it fits beside the door.
fn lay_galley(
    pieces: &[Piece],
    state: &FloorState<'_>,
    sides: &[Side],
    rng: &mut ChaCha8Rng,
    out: &mut Vec<(usize, Footprint, usize)>,
) -> bool {
    let hw = sides[0].half_len;
    let door_half = state.door_zone.map_or(0.0, |d| d.hx);
    let lg = run_length(pieces);
    let room = hw - WALL_GAP - door_half - 0.05;
    if lg > room {
        return false;
    }
    let side = &sides[2];
    let mut x = if rng.random_bool(0.5) {
        -hw + WALL_GAP
    } else {
        hw - WALL_GAP - lg
    };
    for p in pieces {
        out.push((
            p.index,
            side.footprint_at(x + p.w / 2.0, p.w / 2.0, p.d / 2.0),
            2,
        ));
        x += p.w + RUN_GAP;
    }
    true
}

/// Places the plan's islands (ground objects of the rule's `island` categories) in front of
/// the main run, facing it, with an aisle of about a metre between; what does not fit is left
/// to the other placement rules.
fn place_islands(
    state: &mut FloorState<'_>,
    rule: &RunsRule,
    infos: &[AssetInfo],
    runs: &PlacedRuns,
    rng: &mut ChaCha8Rng,
) {
    let plan = state.plan;
    let islands: Vec<usize> = (0..plan.objects.len())
        .filter(|&i| {
            let o = &plan.objects[i];
            o.parent == ParentRef::Ground
                && rule.island.contains(&o.category)
                && matches!(o.zone, Zone::Center | Zone::Free)
        })
        .collect();
    let main: Vec<Footprint> = state
        .placed
        .iter()
        .filter(|p| runs.members.contains(&p.plan_index) && p.wall.as_deref() == Some("wall_0"))
        .map(|p| p.fp)
        .collect();
    if main.is_empty() {
        return;
    }
    let front = main.iter().map(|f| f.cz + f.hz).fold(f64::MIN, f64::max);
    let (x_min, x_max) = main.iter().fold((f64::MAX, f64::MIN), |(a, b), f| {
        (a.min(f.cx - f.hx), b.max(f.cx + f.hx))
    });
    // 1.5 m from either side wall; a floor narrower than 3 m (a house's kitchenette) has only
    // its middle.
    let (lo, hi) = (state.floor[0] + 1.5, state.floor[2] - 1.5);
    let mid = if lo <= hi {
        ((x_min + x_max) / 2.0).clamp(lo, hi)
    } else {
        (state.floor[0] + state.floor[2]) / 2.0
    };
    for i in islands {
        let (hx, hz) = (infos[i].size[0] as f64 / 2.0, infos[i].size[2] as f64 / 2.0);
        let jitter = rng.random_range(-0.2..=0.2);
        let mut placed = false;
        'search: for aisle in [1.1, 1.0, 1.2, 1.35, 0.95, 1.5, 1.7] {
            for dx in [0.0, 0.3, -0.3, 0.6, -0.6, 0.9, -0.9, 1.2, -1.2] {
                let fp = Footprint {
                    cx: mid + jitter + dx,
                    cz: front + aisle + hz,
                    // Its front toward the run (−z).
                    yaw: PI,
                    hx,
                    hz,
                };
                let p = Placed::standing(i, fp, &infos[i]);
                if !state.fits(&p, 0.02) {
                    continue;
                }
                if state.evaluate(Some(&p)).0 {
                    state.commit(p);
                    placed = true;
                    break 'search;
                }
            }
        }
        let _ = placed;
    }
}

/// Spots above the run for a wall-mounted object of one of the rule's `above` categories: on
/// the wall of a run piece, 10 cm past the piece's outer edge at a free end of the run, hung at
/// [`ABOVE_RUN_BOTTOM`]; only where every floor object beneath is a run member low enough to
/// leave room for what stands on it, and where free floor beside the run's end lets one reach
/// the cabinet (the Reach metric counts a hung object as reachable only from floor next to it).
pub(super) fn above_run_spots(
    state: &FloorState<'_>,
    runs: &PlacedRuns,
    category: &str,
    size: [f64; 3],
    sides: &[Side],
    rng: &mut ChaCha8Rng,
) -> Vec<(Footprint, String)> {
    if !runs.rule.above.iter().any(|c| c == category) {
        return Vec::new();
    }
    let (hx, hz) = (size[0] / 2.0, (size[2] / 2.0).max(0.005));
    let mut pieces: Vec<&Placed> = state
        .placed
        .iter()
        .filter(|p| !p.mounted && runs.members.contains(&p.plan_index))
        .collect();
    pieces.shuffle(rng);
    let limit = ABOVE_RUN_BOTTOM - ABOVE_RUN_CLEARANCE;
    let mut out = Vec::new();
    for p in pieces {
        let Some(side) = sides.iter().find(|s| s.id == p.wall) else {
            continue;
        };
        let s = (p.fp.cx - side.face[0]) * side.along[0] + (p.fp.cz - side.face[1]) * side.along[1];
        let lim = side.limit(hx);
        if lim < 0.0 {
            continue;
        }
        for sign in [-1.0, 1.0] {
            // The cabinet's outer edge 10 cm past the piece's edge, over the free floor.
            let outer = s + sign * (p.fp.hx + 0.1);
            let centre = outer - sign * hx;
            if centre.abs() > lim {
                continue;
            }
            let fp = side.footprint_at(centre, hx, hz);
            let beneath: Vec<&Placed> = state
                .placed
                .iter()
                .filter(|q| !q.mounted && q.fp.overlaps(&fp, 0.0))
                .collect();
            let low_run = !beneath.is_empty()
                && beneath
                    .iter()
                    .all(|q| runs.members.contains(&q.plan_index) && q.height <= limit);
            // Free floor beside the run's end, in front of the wall.
            let probe = side.footprint_at(outer + sign * 0.15, 0.25, hz + 0.3);
            let free_beside = state.inside_floor(&probe, 0.0) && !state.collides(&probe, 0.0);
            if low_run && free_beside {
                out.push((fp, side.id.clone().expect("indoor side")));
            }
        }
    }
    out
}
