//! Floor-plan generation: the program's rooms as rectangles (and L-shapes) in two rows along a
//! corridor, or two rows facing each other when no corridor is needed, optionally with a large
//! public room across the whole depth at one end; then doors, windows and walls.
//!
//! Every attempt tiles its rectangular footprint exactly; attempts whose areas leave the
//! knowledge's ranges by more than [`AREA_TOLERANCE`], or that cannot join every room to the
//! entrance, are dropped, and the attempt closest to the target areas is kept.

use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use crate::doors::{leaf_clash, place_doors, service_entries, DoorRules};
use crate::geometry::{union_outline, Rect};
use crate::knowledge::{DwellingKind, Knowledge, HALLWAY};
use crate::plan::{FloorPlan, Room};
use crate::program::Program;
use crate::validate::{check_privacy, validate};
use crate::walls::{walls, Wall};
use crate::windows::place_windows;

/// How far (as a fraction) a generated room's area may leave its knowledge range.
pub const AREA_TOLERANCE: f64 = 0.2;

/// Layout attempts per plan at most.
const ATTEMPTS: usize = 48;

/// Valid attempts compared before the best is kept (few, so that seeds vary the plan).
const CANDIDATES: usize = 8;

/// A generated floor plan with its walls and how its areas compare with the knowledge.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Generated {
    /// The plan: rooms, doors and windows.
    pub plan: FloorPlan,
    /// Its walls, each interior wall once, with their openings.
    pub walls: Vec<Wall>,
    /// The footprint rectangle `[min_x, min_z, max_x, max_z]`, m.
    pub footprint: [f64; 4],
    /// Each room's area against its range.
    pub areas: Vec<AreaNote>,
    /// Whether a hallway (corridor) was made.
    pub hallway: bool,
}

/// One room's area against the knowledge's range.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AreaNote {
    /// The room id.
    pub room: String,
    /// Its floor area, m².
    pub area: f64,
    /// The knowledge's `[min, max]` for its type in this dwelling kind, m².
    pub range: [f64; 2],
    /// Whether the area lies inside the range (otherwise it lies within [`AREA_TOLERANCE`]).
    pub within: bool,
}

/// A program no layout could be found for.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LayoutError {
    /// The program's kind is not in the knowledge.
    #[error("unknown dwelling kind `{0}`")]
    UnknownKind(String),
    /// The program holds no room.
    #[error("the program of `{0}` has no rooms")]
    Empty(String),
    /// No attempt met the rules.
    #[error("no floor plan for `{kind}` met the area and door rules in {attempts} attempts (seed {seed}; failures: {failures})")]
    NoLayout {
        /// The dwelling kind.
        kind: String,
        /// Attempts made.
        attempts: usize,
        /// The seed.
        seed: u64,
        /// Why the attempts failed, with counts.
        failures: String,
    },
}

/// One room to place.
#[derive(Debug, Clone)]
pub(crate) struct Spec {
    pub id: String,
    pub room_type: String,
    pub target: f64,
    pub range: [f64; 3],
    pub min_width: f64,
    pub private: bool,
    pub ensuite_of: Option<usize>,
}

/// Generates the floor plan of a program, deterministically for a seed.
///
/// ```
/// use scenethesis_floorplan::{generate, validate, Knowledge, Program};
/// let k = Knowledge::builtin();
/// let program = Program::from_words(k, "a two-bedroom apartment").unwrap();
/// let house = generate(k, &program, 7).unwrap();
/// assert_eq!(house.plan.rooms.iter().filter(|r| r.room_type == "bedroom").count(), 2);
/// assert_eq!(house.plan.entrances().count(), 1);
/// validate(&house.plan, k).unwrap();
/// ```
pub fn generate(
    knowledge: &Knowledge,
    program: &Program,
    seed: u64,
) -> Result<Generated, LayoutError> {
    let dwelling = knowledge
        .dwelling(&program.kind)
        .ok_or_else(|| LayoutError::UnknownKind(program.kind.clone()))?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let specs = specs(knowledge, dwelling, program, &mut rng);
    if specs.is_empty() {
        return Err(LayoutError::Empty(program.kind.clone()));
    }
    let wants_hallway = program.count(HALLWAY) > 0 || private_units(&specs) > 2;
    let mut best: Option<(bool, f64, Generated)> = None;
    let mut failures: std::collections::BTreeMap<&str, usize> = Default::default();
    let mut valid = 0;
    for attempt in 0..ATTEMPTS {
        // Without a required hallway, the first half of the attempts try without one.
        let corridor = wants_hallway || attempt >= ATTEMPTS / 2;
        if valid >= CANDIDATES || (corridor && best.as_ref().is_some_and(|(c, _, _)| !c)) {
            break;
        }
        let (score, plan) = match attempt_plan(knowledge, dwelling, &specs, corridor, &mut rng) {
            Ok(found) => {
                valid += 1;
                found
            }
            Err(why) => {
                *failures.entry(why).or_default() += 1;
                continue;
            }
        };
        if best
            .as_ref()
            .is_none_or(|(c, s, _)| (*c && !corridor) || (*c == corridor && score < *s))
        {
            best = Some((corridor, score, plan));
        }
    }
    best.map(|(_, _, plan)| plan)
        .ok_or_else(|| LayoutError::NoLayout {
            kind: program.kind.clone(),
            attempts: ATTEMPTS,
            seed,
            failures: failures
                .iter()
                .map(|(k, n)| format!("{k} {n}"))
                .collect::<Vec<_>>()
                .join(", "),
        })
}

/// The program's rooms (a hallway in the program is left to the corridor), with target areas
/// drawn inside their ranges and en-suites attached to hosts.
fn specs(
    knowledge: &Knowledge,
    dwelling: &DwellingKind,
    program: &Program,
    rng: &mut ChaCha8Rng,
) -> Vec<Spec> {
    let mut out = Vec::new();
    for rc in program.rooms.iter().filter(|r| r.room_type != HALLWAY) {
        let Some(kind) = knowledge.room(&rc.room_type) else {
            continue;
        };
        let range = knowledge.area(dwelling, &rc.room_type).unwrap_or(kind.area);
        for n in 0..rc.count {
            let id = if rc.count == 1 {
                rc.room_type.clone()
            } else {
                format!("{}_{}", rc.room_type, n + 1)
            };
            let lo = (range[0] + range[1]) / 2.0;
            let hi = (range[1] + range[2]) / 2.0;
            out.push(Spec {
                id,
                room_type: rc.room_type.clone(),
                target: rng.random_range(lo..=hi),
                range,
                min_width: kind.min_width,
                private: knowledge.is_private(&rc.room_type),
                ensuite_of: None,
            });
        }
    }
    attach_ensuites(knowledge, &mut out);
    out
}

/// The second and later rooms of an en-suite type become en-suites of the hosts, in order.
fn attach_ensuites(knowledge: &Knowledge, specs: &mut [Spec]) {
    let types: Vec<String> = specs.iter().map(|s| s.room_type.clone()).collect();
    let mut taken = vec![false; specs.len()];
    for i in 0..specs.len() {
        let Some(host_type) = knowledge.room(&types[i]).and_then(|r| r.ensuite_of.clone()) else {
            continue;
        };
        let first = types.iter().position(|t| *t == types[i]) == Some(i);
        if first {
            continue;
        }
        if let Some(host) = (0..specs.len()).find(|&h| types[h] == host_type && !taken[h]) {
            taken[host] = true;
            specs[i].ensuite_of = Some(host);
        }
    }
}

fn private_units(specs: &[Spec]) -> usize {
    specs
        .iter()
        .filter(|s| s.private && s.ensuite_of.is_none())
        .count()
}

/// Groups of rooms placed side by side in a row: a host with its en-suite, a chain of public
/// rooms joined by passages or double doors (kitchen, living, dining), the rest alone.
fn units(knowledge: &Knowledge, specs: &[Spec], rng: &mut ChaCha8Rng) -> Vec<Vec<usize>> {
    let mut used = vec![false; specs.len()];
    let mut out = Vec::new();
    for (i, s) in specs.iter().enumerate() {
        if let Some(host) = s.ensuite_of {
            used[i] = true;
            used[host] = true;
            let mut pair = vec![host, i];
            pair.shuffle(rng);
            out.push(pair);
        }
    }
    // Mostly, rooms joined by a passage or double door stand side by side; sometimes not
    // (they may still meet across the rows).
    let chains = rng.random_bool(0.7);
    for start in 0..specs.len() {
        if used[start] || specs[start].private {
            continue;
        }
        used[start] = true;
        let mut chain = vec![start];
        while let Some(next) = (0..specs.len()).find(|&j| {
            let last = &specs[*chain.last().unwrap_or(&start)];
            chains
                && !used[j]
                && !specs[j].private
                && knowledge.join_kind(&last.room_type, &specs[j].room_type)
                    != crate::plan::DoorKind::Single
        }) {
            used[next] = true;
            chain.push(next);
        }
        if rng.random_bool(0.5) {
            chain.reverse();
        }
        out.push(chain);
    }
    out.extend((0..specs.len()).filter(|&i| !used[i]).map(|i| vec![i]));
    out.shuffle(rng);
    out
}

/// One room of a row: its spec, its width, and for a small room the depth it takes from the
/// row's front (the rest behind it is a leg of a neighbour).
#[derive(Debug, Clone)]
struct Item {
    spec: usize,
    width: f64,
    front_depth: Option<f64>,
    leg_to: Option<usize>,
}

/// The widths of a row of depth `depth`: small rooms keep a compact shape at the front and
/// hand the strip behind them to a neighbour (which becomes an L), whose width shrinks by the
/// strip's area.
fn row_items(specs: &[Spec], order: &[usize], depth: f64) -> Vec<Item> {
    let mut items: Vec<Item> = order
        .iter()
        .map(|&s| Item {
            spec: s,
            width: (specs[s].target / depth).max(specs[s].min_width),
            front_depth: None,
            leg_to: None,
        })
        .collect();
    for k in 0..items.len() {
        let spec = &specs[items[k].spec];
        let natural = spec.target / depth;
        if natural >= spec.min_width.max(depth / 2.2) {
            continue;
        }
        let width = spec.min_width.max((spec.target / 1.4).sqrt());
        let front = spec.target / width;
        let Some(to) = leg_neighbour(specs, &items, k) else {
            continue;
        };
        if depth - front < 1.0 {
            continue;
        }
        items[k] = Item {
            spec: items[k].spec,
            width,
            front_depth: Some(front),
            leg_to: Some(to),
        };
    }
    for k in 0..items.len() {
        if items[k].front_depth.is_some() {
            continue;
        }
        let legs: f64 = items
            .iter()
            .filter(|it| it.leg_to == Some(k))
            .map(|it| it.width * (depth - it.front_depth.unwrap_or(depth)))
            .sum();
        let spec = &specs[items[k].spec];
        items[k].width = ((spec.target - legs) / depth).max(spec.min_width);
    }
    items
}

/// The row neighbour a small room at `k` hands its back strip to: its host when it is an
/// en-suite, else the larger full-depth neighbour.
fn leg_neighbour(specs: &[Spec], items: &[Item], k: usize) -> Option<usize> {
    let candidates = [k.checked_sub(1), (k + 1 < items.len()).then_some(k + 1)];
    let full = |j: &usize| items[*j].front_depth.is_none() && specs[items[*j].spec].target >= 6.0;
    let mut around: Vec<usize> = candidates.into_iter().flatten().filter(full).collect();
    if let Some(host) = specs[items[k].spec].ensuite_of {
        if let Some(&j) = around.iter().find(|&&j| items[j].spec == host) {
            return Some(j);
        }
    }
    around.sort_by(|a, b| {
        specs[items[*b].spec]
            .target
            .total_cmp(&specs[items[*a].spec].target)
    });
    around.first().copied()
}

fn row_length(items: &[Item]) -> f64 {
    items.iter().map(|it| it.width).sum()
}

/// Widens the full-depth rooms of a row so the row is `length` long, each by its share of
/// the room left below its maximum area.
fn stretch(specs: &[Spec], items: &mut [Item], depth: f64, length: f64) {
    let extra = length - row_length(items);
    if extra <= 1e-9 {
        return;
    }
    let slack = |it: &Item| {
        let s = &specs[it.spec];
        if it.front_depth.is_some() {
            0.0
        } else {
            (s.range[2] / depth - it.width).max(0.0) + 0.05
        }
    };
    let total: f64 = items.iter().map(slack).sum();
    if total <= 0.0 {
        return;
    }
    let shares: Vec<f64> = items.iter().map(|it| slack(it) / total).collect();
    for (it, share) in items.iter_mut().zip(shares) {
        it.width += extra * share;
    }
}

fn round_cm(v: f64) -> f64 {
    (v * 100.0).round() / 100.0
}

/// A row's rooms as rectangles: x from `x0`, the row spanning `far..front` in z (either
/// order); each small room at the front, its back strip added to its neighbour's parts.
fn realize_row(items: &[Item], x0: f64, far: f64, front: f64, parts: &mut [Vec<Rect>]) {
    let mut x = x0;
    let mut spans = Vec::new();
    for it in items {
        let next = round_cm(x + it.width);
        spans.push((x, next));
        x = next;
    }
    let dir = (front - far).signum();
    for (k, it) in items.iter().enumerate() {
        let (a, b) = spans[k];
        match it.front_depth {
            Some(d) => {
                let cut = round_cm(front - dir * d);
                parts[it.spec].push(Rect::new(a, cut, b, front));
                if let Some(to) = it.leg_to {
                    parts[items[to].spec].push(Rect::new(a, far, b, cut));
                }
            }
            None => parts[it.spec].push(Rect::new(a, far, b, front)),
        }
    }
}

/// Drops the x end of the last room to `end` (the rounding of a row's last boundary).
fn close_row(items: &[Item], end: f64, parts: &mut [Vec<Rect>]) {
    let Some(last) = items.last() else { return };
    let touch = |r: &mut Rect, old: f64| {
        if (r.max.x - old).abs() < 0.02 {
            r.max.x = end;
        }
    };
    let old = parts[last.spec]
        .iter()
        .map(|r| r.max.x)
        .fold(f64::MIN, f64::max);
    for r in parts[last.spec].iter_mut() {
        touch(r, old);
    }
    if let Some(to) = last.leg_to {
        for r in parts[items[to].spec].iter_mut() {
            touch(r, old);
        }
    }
}

/// The shape of one attempt: which rooms go in which row, the end room and the depths.
struct Sketch {
    north: Vec<usize>,
    south: Vec<usize>,
    hub: Option<(usize, bool)>,
    corridor: f64,
    depth_sum: f64,
}

fn sketch(
    knowledge: &Knowledge,
    dwelling: &DwellingKind,
    specs: &[Spec],
    corridor: bool,
    rng: &mut ChaCha8Rng,
) -> Sketch {
    let mut units = units(knowledge, specs, rng);
    let hub = pick_hub(specs, &mut units, rng);
    let unit_area = |u: &Vec<usize>| u.iter().map(|&i| specs[i].target).sum::<f64>();
    units.sort_by(|a, b| unit_area(b).total_cmp(&unit_area(a)));
    let (mut north, mut south, mut an, mut asouth) = (Vec::new(), Vec::new(), 0.0, 0.0);
    for unit in units {
        let to_north = an < asouth || (an == asouth && rng.random_bool(0.5));
        if to_north {
            an += unit_area(&unit);
            north.push(unit);
        } else {
            asouth += unit_area(&unit);
            south.push(unit);
        }
    }
    // Rows of very different areas cannot share a length: one row instead.
    let few = north.len() + south.len() <= 3;
    if an.min(asouth) * 3.0 < an.max(asouth) || (few && rng.random_bool(0.2)) {
        north.append(&mut south);
    }
    for row in [&mut north, &mut south] {
        row.shuffle(rng);
        if let Some((h, _)) = hub {
            if let Some(k) = row.iter().position(|u| unit_joins(knowledge, specs, h, u)) {
                let unit = row.remove(k);
                row.insert(0, unit);
            }
        }
    }
    let [cmin, cmax] = dwelling.corridor_width;
    let west = hub.is_none_or(|(_, west)| west);
    let flatten = |rows: Vec<Vec<usize>>| -> Vec<usize> {
        let mut flat: Vec<usize> = rows.into_iter().flatten().collect();
        if !west {
            flat.reverse();
        }
        flat
    };
    Sketch {
        north: flatten(north),
        south: flatten(south),
        hub,
        corridor: if corridor {
            round_cm(rng.random_range(cmin..=cmax))
        } else {
            0.0
        },
        depth_sum: rng.random_range(if corridor { 6.5..9.5 } else { 5.5..8.5 }),
    }
}

fn unit_joins(knowledge: &Knowledge, specs: &[Spec], hub: usize, unit: &[usize]) -> bool {
    unit.iter().any(|&i| {
        knowledge.join_kind(&specs[hub].room_type, &specs[i].room_type)
            != crate::plan::DoorKind::Single
    })
}

/// Sometimes the largest public room spans the whole depth at the west or east end.
fn pick_hub(
    specs: &[Spec],
    units: &mut Vec<Vec<usize>>,
    rng: &mut ChaCha8Rng,
) -> Option<(usize, bool)> {
    if units.len() < 3 || !rng.random_bool(0.4) {
        return None;
    }
    let hub = (0..specs.len())
        .filter(|&i| !specs[i].private && specs[i].ensuite_of.is_none())
        .max_by(|&a, &b| specs[a].target.total_cmp(&specs[b].target))?;
    for unit in units.iter_mut() {
        unit.retain(|&i| i != hub);
    }
    units.retain(|u| !u.is_empty());
    Some((hub, rng.random_bool(0.5)))
}

/// One attempt: rooms, doors, windows and walls, with its score (lower is closer to the
/// targets); the rule it breaks otherwise.
fn attempt_plan(
    knowledge: &Knowledge,
    dwelling: &DwellingKind,
    specs: &[Spec],
    corridor: bool,
    rng: &mut ChaCha8Rng,
) -> Result<(f64, Generated), &'static str> {
    let sketch = sketch(knowledge, dwelling, specs, corridor, rng);
    let (rooms, footprint) = rooms_of(specs, &sketch).ok_or("room outline")?;
    let mut plan = FloorPlan {
        rooms,
        doors: Vec::new(),
        windows: Vec::new(),
    };
    let bare = walls(&plan);
    let ensuites = specs
        .iter()
        .filter_map(|s| s.ensuite_of.map(|h| (s.id.clone(), specs[h].id.clone())))
        .collect();
    let rules = DoorRules {
        knowledge,
        dwelling,
        ensuites,
    };
    let areas = area_notes(specs, &plan).ok_or("areas")?;
    plan.doors = place_doors(&rules, &plan, &bare, rng).ok_or("doors")?;
    plan.windows = place_windows(knowledge, &plan, &bare);
    let score = score(specs, &plan) + 0.5 * service_entries(knowledge, &plan) as f64;
    let walls = validate(&plan, knowledge).map_err(|_| "validation")?;
    if leaf_clash(&plan, &walls).is_some() {
        return Err("door leaves clash");
    }
    check_privacy(&plan, knowledge).map_err(|_| "privacy")?;
    let hallway = plan.rooms.iter().any(|r| r.room_type == HALLWAY);
    Ok((
        score,
        Generated {
            plan,
            walls,
            footprint,
            areas,
            hallway,
        },
    ))
}

/// The rooms of a sketch and the footprint `[min_x, min_z, max_x, max_z]`.
fn rooms_of(specs: &[Spec], sketch: &Sketch) -> Option<(Vec<Room>, [f64; 4])> {
    let area = |row: &[usize]| row.iter().map(|&i| specs[i].target).sum::<f64>();
    let (an, asouth) = (area(&sketch.north), area(&sketch.south));
    let rows = usize::from(an > 0.0) + usize::from(asouth > 0.0);
    let guess = (an + asouth) / (sketch.depth_sum * rows as f64 / 2.0).max(1.0);
    let depth = |a: f64| {
        if a > 0.0 {
            round_cm((a / guess).clamp(2.4, 7.5))
        } else {
            0.0
        }
    };
    let (dn, ds) = (depth(an), depth(asouth));
    let mut north = row_items(specs, &sketch.north, dn);
    let mut south = row_items(specs, &sketch.south, ds);
    let length = round_cm(row_length(&north).max(row_length(&south)));
    stretch(specs, &mut north, dn, length);
    stretch(specs, &mut south, ds, length);
    let total_depth = dn + sketch.corridor + ds;
    let hub_width = sketch.hub.map_or(0.0, |(h, _)| {
        round_cm((specs[h].target / total_depth).max(specs[h].min_width))
    });
    let west = sketch.hub.is_none_or(|(_, w)| w);
    let x0 = if west { hub_width } else { 0.0 };
    let mut parts = vec![Vec::new(); specs.len()];
    realize_row(&north, x0, 0.0, dn, &mut parts);
    close_row(&north, x0 + length, &mut parts);
    let s0 = dn + sketch.corridor;
    realize_row(&south, x0, total_depth, s0, &mut parts);
    close_row(&south, x0 + length, &mut parts);
    if let Some((h, _)) = sketch.hub {
        let hx = if west { 0.0 } else { length };
        parts[h].push(Rect::new(hx, 0.0, hx + hub_width, total_depth));
    }
    let mut rooms = Vec::new();
    for (spec, p) in specs.iter().zip(&parts) {
        rooms.push(Room {
            id: spec.id.clone(),
            room_type: spec.room_type.clone(),
            polygon: union_outline(p)?,
        });
    }
    if sketch.corridor > 0.0 {
        let hall = Rect::new(x0, dn, x0 + length, s0);
        rooms.push(Room {
            id: HALLWAY.into(),
            room_type: HALLWAY.into(),
            polygon: hall.polygon(),
        });
    }
    Some((rooms, [0.0, 0.0, length + hub_width, total_depth]))
}

/// Each room's area against its range; `None` if one leaves it by more than the tolerance.
fn area_notes(specs: &[Spec], plan: &FloorPlan) -> Option<Vec<AreaNote>> {
    let mut notes = Vec::new();
    for spec in specs {
        let room = plan.room(&spec.id)?;
        let area = crate::geometry::area(&room.polygon);
        let [min, _, max] = spec.range;
        let loose = min * (1.0 - AREA_TOLERANCE) <= area && area <= max * (1.0 + AREA_TOLERANCE);
        if !loose {
            return None;
        }
        let within = min - 1e-6 <= area && area <= max + 1e-6;
        notes.push(AreaNote {
            room: spec.id.clone(),
            area,
            range: [min, max],
            within,
        });
    }
    Some(notes)
}

/// How far an attempt is from the targets: relative area misses plus stretched shapes (the
/// caller adds half a point per private room entered from a kitchen or dining room).
fn score(specs: &[Spec], plan: &FloorPlan) -> f64 {
    specs
        .iter()
        .filter_map(|s| plan.room(&s.id).map(|r| (s, r)))
        .map(|(s, r)| {
            let area = crate::geometry::area(&r.polygon);
            let (w, d) = extent(&r.polygon);
            let aspect = w.max(d) / w.min(d).max(0.1);
            (area - s.target).abs() / s.target + (aspect - 2.0).max(0.0)
        })
        .sum()
}

fn extent(polygon: &[nalgebra::Point2<f64>]) -> (f64, f64) {
    let xs = polygon.iter().map(|p| p.x);
    let zs = polygon.iter().map(|p| p.y);
    let span = |v: Vec<f64>| {
        v.iter().copied().fold(f64::MIN, f64::max) - v.iter().copied().fold(f64::MAX, f64::min)
    };
    (span(xs.collect()), span(zs.collect()))
}
