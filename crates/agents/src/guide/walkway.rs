//! The walkway the guide keeps open while it places floor objects: an aisle from the door to
//! every object's access side and one connected free floor, checked on the guide's raster and,
//! at the end, by the Walk metric's own raster rules.

use nalgebra::{Point2, Point3};
use scenethesis_eval::raster::{
    free_floor, grown_cells, metric_grid, FloorRect, WALK_HEIGHT_LIMIT,
};
#[cfg(test)]
use scenethesis_scene_graph::OpensTo;
use scenethesis_scene_graph::{Aabb, Architecture, Components, Floor, RelationKind, ROBOT_RADIUS};

use super::geometry::{Footprint, Raster, RasterExt};
use super::room::Room;
use super::shared::{Placed, DOOR_WIDTH};
use super::DroppedObject;
use crate::plan::Plan;

/// How far the guide grows footprints for its own walk check: the robot radius plus half a
/// raster cell and a centimetre, so that slivers the metric raster may close never count as
/// passages.
pub(super) fn walk_grow(cell: f64) -> f64 {
    ROBOT_RADIUS + cell / 2.0 + 0.01
}
/// The guide's footprint of a plan's keep-clear area, with its height limit.
fn keep_clear_zone(area: &crate::plan::KeepClear) -> (Footprint, Option<f64>) {
    let zone = Footprint {
        cx: (area.min[0] + area.max[0]) / 2.0,
        cz: (area.min[1] + area.max[1]) / 2.0,
        yaw: 0.0,
        hx: (area.max[0] - area.min[0]).abs() / 2.0,
        hz: (area.max[1] - area.min[1]).abs() / 2.0,
    };
    (zone, area.below)
}

/// Minimum share of the free floor the largest walkable component must hold.
pub(super) const MIN_WALK: f64 = 0.995;

/// The floor objects placed so far and the walkway rasters they leave.
pub(super) struct FloorState<'a> {
    /// The guide's raster over the floor.
    pub(super) raster: Raster,
    /// Half the aisle width (at least 0.3 m): how far the aisle keeps from footprints.
    pub(super) aisle_radius: f64,
    /// Free cells of the aisle raster with every placed floor object stamped in.
    pub(super) aisle_base: Vec<bool>,
    /// Free cells of the walk raster with every placed floor object stamped in.
    pub(super) walk_base: Vec<bool>,
    /// The aisle cell just inside the door (indoors).
    pub(super) door_aisle: Option<usize>,
    /// The walk cell just inside the door (indoors).
    pub(super) door_walk: Option<usize>,
    /// The clearance in front of the door that no floor object may take (indoors).
    pub(super) door_zone: Option<Footprint>,
    /// The plan's keep-clear areas and the height an object may reach in each
    /// ([`crate::plan::KeepClear`]).
    pub(super) keep_clear: Vec<(Footprint, Option<f64>)>,
    /// The floor rectangle [min x, min z, max x, max z].
    pub(super) floor: [f64; 4],
    /// The room's architecture when it has windows, whose fronts tall floor objects keep
    /// clear of ([`Architecture::window_covered_by`]).
    pub(super) windowed: Option<Architecture>,
    /// The objects placed so far (floor and wall-mounted), in placement order.
    pub(super) placed: Vec<Placed>,
    /// The Walk metric's raster of the floor with the placed objects stamped in.
    pub(super) metric: MetricFloor,
    /// The plan being laid out.
    pub(super) plan: &'a Plan,
}

impl<'a> FloorState<'a> {
    /// The empty floor of `room` on a raster of `cell` metres, with the door's clearance kept
    /// free and the door cells marked walkable.
    pub(super) fn new(plan: &'a Plan, room: &Room, cell: f64) -> Self {
        let [hw, hd] = room.half;
        let indoor = room.indoor;
        let aisle_radius = (plan.aisle / 2.0).max(0.3);
        let raster = Raster::new(-hw, -hd, hw, hd, cell);
        let mut aisle_base = raster.floor_mask(aisle_radius);
        let mut walk_base = raster.floor_mask(walk_grow(cell));
        // A house room is entered by a door of its front wall that need not lie at its
        // middle: the area that door keeps clear is the room's door clearance.
        let entrance = plan
            .keep_clear
            .iter()
            .find(|k| k.entrance)
            .map(|k| keep_clear_zone(k).0);
        let door_x = entrance.map_or(0.0, |zone| zone.cx);
        let door_zone = indoor.then(|| {
            if let Some(zone) = entrance {
                return zone;
            }
            let clear = plan.door_clearance.max(0.6);
            let zone = Footprint {
                cx: 0.0,
                cz: hd - clear / 2.0,
                yaw: 0.0,
                hx: DOOR_WIDTH / 2.0 + 0.2,
                hz: clear / 2.0,
            };
            let arch = &room.architecture;
            let swing = arch.doors.first().and_then(|d| arch.door_swing(d));
            swing.map_or(zone, |swing| covering(zone, &swing, [-hw, -hd, hw, hd]))
        });
        let door_cell = |r: f64| {
            if indoor {
                raster
                    .cell_of(door_x, hd - r - cell * 1.5)
                    .map(|(i, j)| j * raster.nx + i)
            } else {
                None
            }
        };
        let (door_aisle, door_walk) = (door_cell(aisle_radius), door_cell(walk_grow(cell)));
        if let (Some(a), Some(w)) = (door_aisle, door_walk) {
            aisle_base[a] = true;
            walk_base[w] = true;
        }
        FloorState {
            raster,
            aisle_radius,
            aisle_base,
            walk_base,
            door_aisle,
            door_walk,
            door_zone,
            keep_clear: plan.keep_clear.iter().map(keep_clear_zone).collect(),
            floor: [-hw, -hd, hw, hd],
            windowed: (!room.architecture.windows.is_empty()).then(|| room.architecture.clone()),
            placed: Vec::new(),
            metric: MetricFloor::new([-hw, -hd, hw, hd]),
            plan,
        }
    }
}

impl FloorState<'_> {
    pub(super) fn inside_floor(&self, fp: &Footprint, margin: f64) -> bool {
        fp.corners().iter().all(|c| {
            c[0] >= self.floor[0] + margin - 1e-9
                && c[0] <= self.floor[2] - margin + 1e-9
                && c[1] >= self.floor[1] + margin - 1e-9
                && c[1] <= self.floor[3] - margin + 1e-9
        })
    }

    /// Whether a body at `fp` would overlap (within `gap`) a placed floor object, the room
    /// door's zone or an area the plan keeps wholly clear.
    pub(super) fn collides(&self, fp: &Footprint, gap: f64) -> bool {
        self.placed
            .iter()
            .filter(|p| !p.mounted)
            .any(|p| p.fp.overlaps(fp, gap))
            || self.in_door_ways(fp)
    }

    /// Whether `fp` overlaps the room door's zone or an area the plan keeps wholly clear (a
    /// house room's other doors' swings and approaches).
    pub(super) fn in_door_ways(&self, fp: &Footprint) -> bool {
        self.door_zone.is_some_and(|d| d.overlaps(fp, 0.0)) || self.in_wholly_clear(fp)
    }

    /// Whether `fp` overlaps an area the plan keeps wholly clear (one without a height limit).
    fn in_wholly_clear(&self, fp: &Footprint) -> bool {
        self.keep_clear
            .iter()
            .any(|(zone, below)| below.is_none() && zone.overlaps(fp, 0.0))
    }

    /// Whether hung object `p` would hang in an area the plan keeps wholly clear (a house
    /// door's opening and approach) or reach above the height limit of one it hangs in (in
    /// front of a window).
    pub(super) fn hangs_in_keep_clear(&self, p: &Placed) -> bool {
        self.in_wholly_clear(&p.fp) || self.too_tall_for_keep_clear(p)
    }

    /// Whether `p` reaches above the height limit of a keep-clear area it stands in (a tall
    /// piece, or anything hung, in front of a window).
    fn too_tall_for_keep_clear(&self, p: &Placed) -> bool {
        let top = if p.mounted {
            p.mounted_bottom() + p.height
        } else {
            p.height
        };
        self.keep_clear
            .iter()
            .any(|(zone, below)| below.is_some_and(|h| top > h) && zone.overlaps(&p.fp, 0.0))
    }

    /// Whether `p` fits: its footprint inside the floor and clear of the others (within
    /// `gap`) and of the floor their doors and drawers open into, the floor its own open
    /// into inside the room and clear of every placed body, hung ones lower than its top
    /// included (other openings may share it: one opens at a time), and, if its top rises
    /// above a window's sill, not in front of that window. An object placed against
    /// another (a chair at its desk) may stand in that one's opening: it is moved aside to
    /// open it.
    pub(super) fn fits(&self, p: &Placed, gap: f64) -> bool {
        self.inside_floor(&p.fp, 0.0)
            && !self.collides(&p.fp, gap)
            && !self.too_tall_for_keep_clear(p)
            && self.clear_of_openings(p)
            && !self.covers_a_window(p)
    }

    /// Whether floor object `p` would stand in front of a window with its top above the sill.
    fn covers_a_window(&self, p: &Placed) -> bool {
        let Some(arch) = self.windowed.as_ref().filter(|_| !p.mounted) else {
            return false;
        };
        let corners = p.fp.corners();
        let (lo, hi) = corners[1..]
            .iter()
            .fold((corners[0], corners[0]), |(lo, hi), c| {
                (
                    [lo[0].min(c[0]), lo[1].min(c[1])],
                    [hi[0].max(c[0]), hi[1].max(c[1])],
                )
            });
        let bounds = Aabb::new(
            Point3::new(lo[0], 0.0, lo[1]),
            Point3::new(hi[0], p.height, hi[1]),
        );
        arch.window_covered_by(&bounds).is_some()
    }

    /// Whether `p` stands in no placed floor object's opening and its own opening lies inside
    /// the room, clear of every placed body (see [`Self::fits`]).
    fn clear_of_openings(&self, p: &Placed) -> bool {
        !self
            .placed
            .iter()
            .filter(|q| !q.mounted && !self.related(p, q))
            .any(|q| q.opening.is_some_and(|o| o.overlaps(&p.fp, 0.0)))
            && p.opening.is_none_or(|o| {
                self.inside_floor(&o, 0.0)
                    && !self
                        .placed
                        .iter()
                        .filter(|q| !q.mounted || q.mounted_bottom() < p.height)
                        .filter(|q| !self.related(p, q))
                        .any(|q| q.fp.overlaps(&o, 0.0))
            })
    }

    /// Whether one of `a` and `b` is placed in front of the other, facing it or around it (a
    /// chair at its desk): such a pair may stand in each other's openings. Pieces beside each
    /// other (a stove next to a counter) may not.
    fn related(&self, a: &Placed, b: &Placed) -> bool {
        let objects = &self.plan.objects;
        let target = |x: &Placed, y: &Placed| {
            let (x, y) = (&objects[x.plan_index], &objects[y.plan_index]);
            x.relations.iter().any(|r| {
                r.target == y.id
                    && matches!(
                        r.kind,
                        RelationKind::InFrontOf | RelationKind::Facing | RelationKind::Around
                    )
            })
        };
        target(a, b) || target(b, a)
    }

    /// Whether an object hung at `fp` with its bottom at `bottom` would hang where the doors
    /// of a placed floor object taller than that bottom open.
    pub(super) fn in_a_swing(&self, fp: &Footprint, bottom: f64) -> bool {
        self.placed
            .iter()
            .filter(|p| !p.mounted && p.height > bottom)
            .any(|p| p.opening.is_some_and(|o| o.overlaps(fp, 0.0)))
    }

    /// Whether hung object `p` would hang where the doors of another hung object open, or its
    /// own doors would open into one (a wall cabinet beside a wall shelf). Hung objects share
    /// the height band above the counters, so their heights are not compared.
    pub(super) fn in_a_hung_swing(&self, p: &Placed) -> bool {
        self.placed.iter().filter(|q| q.mounted).any(|q| {
            q.opening.is_some_and(|o| o.overlaps(&p.fp, 0.0))
                || p.opening.is_some_and(|o| o.overlaps(&q.fp, 0.0))
        })
    }

    /// Walkway evaluation with an optional extra object: (accepted, walk ratio, door reachable,
    /// unreachable plan indices). An extra object is accepted only if it cuts no more floor
    /// off the walkway on the Walk metric's raster ([`MetricFloor::cut_off_by`]) than is cut
    /// off already.
    pub(super) fn evaluate(&self, extra: Option<&Placed>) -> (bool, f64, bool, Vec<usize>) {
        let r = &self.raster;
        let mut aisle = self.aisle_base.clone();
        let mut walk = self.walk_base.clone();
        if let Some(p) = extra.filter(|p| !p.mounted) {
            r.stamp(&mut aisle, &p.fp, self.aisle_radius);
            // Tall objects too: the Reach raster counts every object as an obstacle.
            r.stamp(&mut walk, &p.fp, walk_grow(r.cell));
        }
        let scenethesis_scene_graph::Components {
            labels: alabels,
            sizes: asizes,
        } = r.components4(&aisle);
        let main = match self.door_aisle {
            Some(d) => alabels[d],
            None => (1..asizes.len())
                .max_by_key(|&l| (asizes[l], usize::MAX - l))
                .unwrap_or(0) as u32,
        };
        let door_ok = main != 0;
        let mut unreachable = Vec::new();
        for p in self.placed.iter().chain(extra) {
            if main == 0 || !self.reachable(p, &alabels, main) {
                unreachable.push(p.plan_index);
            }
        }
        let scenethesis_scene_graph::Components {
            labels: wlabels,
            sizes: wsizes,
        } = r.components4(&walk);
        let total: usize = wsizes.iter().sum();
        let largest = (1..wsizes.len())
            .max_by_key(|&l| (wsizes[l], usize::MAX - l))
            .unwrap_or(0);
        let ratio = if total == 0 {
            0.0
        } else {
            wsizes[largest] as f64 / total as f64
        };
        let door_walk = self
            .door_walk
            .is_none_or(|d| wlabels[d] == largest as u32 && largest != 0);
        // Last (the dearest): the metric's own raster keeps every cell of floor on the walkway.
        let ok = door_ok
            && unreachable.is_empty()
            && ratio >= MIN_WALK
            && door_walk
            && extra.is_none_or(|p| !self.metric.cut_off_by(p));
        (ok, ratio, door_ok, unreachable)
    }

    pub(super) fn reachable(&self, p: &Placed, labels: &[u32], main: u32) -> bool {
        let r = &self.raster;
        let reach = self.aisle_radius + 1.5 * r.cell;
        let zone = if p.front_access {
            let depth = reach + r.cell;
            let centre = p.fp.to_world(0.0, p.fp.hz + depth / 2.0);
            Footprint {
                cx: centre[0],
                cz: centre[1],
                yaw: p.fp.yaw,
                hx: (p.fp.hx * 0.8).max(r.cell),
                hz: depth / 2.0,
            }
        } else {
            Footprint {
                hx: p.fp.hx + reach,
                hz: p.fp.hz + reach,
                ..p.fp
            }
        };
        let mut found = false;
        r.for_cells_in(&zone, 0.0, |idx| found |= labels[idx] == main);
        found
    }

    /// Recomputes the walkway rasters from the placed objects.
    pub(super) fn rebuild(&mut self) {
        let grow = walk_grow(self.raster.cell);
        self.aisle_base = self.raster.floor_mask(self.aisle_radius);
        self.walk_base = self.raster.floor_mask(grow);
        for (door, mask) in [
            (self.door_aisle, &mut self.aisle_base),
            (self.door_walk, &mut self.walk_base),
        ] {
            if let Some(d) = door {
                mask[d] = true;
            }
        }
        self.metric = MetricFloor::new(self.floor);
        let placed = std::mem::take(&mut self.placed);
        for p in placed {
            self.commit(p);
        }
    }

    pub(super) fn commit(&mut self, p: Placed) {
        if !p.mounted {
            self.raster
                .stamp(&mut self.aisle_base, &p.fp, self.aisle_radius);
            self.raster
                .stamp(&mut self.walk_base, &p.fp, walk_grow(self.raster.cell));
            self.metric.stamp(&p);
        }
        self.placed.push(p);
    }

    pub(super) fn placed_of(&self, plan_index: usize) -> Option<&Placed> {
        self.placed.iter().find(|p| p.plan_index == plan_index)
    }

    pub(super) fn index_of(&self, id: &str) -> Option<usize> {
        self.plan.objects.iter().position(|o| o.id == id)
    }
}

/// The axis-aligned `zone` grown to cover the part of the box `swing` (a door leaf's) over
/// the `floor` [min x, min z, max x, max z], unchanged when it already does.
fn covering(zone: Footprint, swing: &Aabb, floor: [f64; 4]) -> Footprint {
    let (x0, x1) = (zone.cx - zone.hx, zone.cx + zone.hx);
    let (z0, z1) = (zone.cz - zone.hz, zone.cz + zone.hz);
    let lo = Point3::new(swing.min.x.max(floor[0]), 0.0, swing.min.z.max(floor[1]));
    let hi = Point3::new(swing.max.x.min(floor[2]), 0.0, swing.max.z.min(floor[3]));
    let swing = Aabb::new(lo, hi);
    if swing.min.x >= x0 && swing.max.x <= x1 && swing.min.z >= z0 && swing.max.z <= z1 {
        return zone;
    }
    let (x0, x1) = (x0.min(swing.min.x), x1.max(swing.max.x));
    let (z0, z1) = (z0.min(swing.min.z), z1.max(swing.max.z));
    Footprint {
        cx: (x0 + x1) / 2.0,
        cz: (z0 + z1) / 2.0,
        yaw: 0.0,
        hx: (x1 - x0) / 2.0,
        hz: (z1 - z0) / 2.0,
    }
}

/// An obstacle's footprint as the Walk metric's floor rectangle.
fn metric_rect(fp: &Footprint) -> FloorRect {
    FloorRect {
        center: [fp.cx, fp.cz],
        axis: fp.axes().0,
        half: [fp.hx, fp.hz],
    }
}

/// The Walk metric's raster of the floor ([`metric_grid`], [`free_floor`]) with every placed
/// floor object that counts for Walk stamped in by the metric's rules ([`grown_cells`]): the
/// guide keeps it in one piece, so that no pocket of floor is cut off from the walkway.
pub(super) struct MetricFloor {
    grid: Raster,
    /// Walkable cells.
    free: Vec<bool>,
    /// Walkable cells off the largest component.
    pocket_cells: usize,
}

impl MetricFloor {
    /// The empty floor [min x, min z, max x, max z] on the metric's raster.
    fn new(floor: [f64; 4]) -> Self {
        let floor = Floor {
            id: "floor".into(),
            min: Point2::new(floor[0], floor[1]),
            max: Point2::new(floor[2], floor[3]),
        };
        let grid = metric_grid(&floor);
        let free = free_floor(&grid, &floor, &[]);
        MetricFloor {
            grid,
            free,
            pocket_cells: 0,
        }
    }

    /// The cells `p` takes from the walkable floor: none for a hung object or one whose box
    /// centre (at half its height) is at or above [`WALK_HEIGHT_LIMIT`].
    fn cells_of(&self, p: &Placed) -> Vec<usize> {
        if p.mounted || p.height / 2.0 >= WALK_HEIGHT_LIMIT {
            return Vec::new();
        }
        grown_cells(&self.grid, &metric_rect(&p.fp))
    }

    /// The walkable cells off the largest component of `free`.
    fn pockets_of(&self, free: &[bool]) -> usize {
        let sizes = self.grid.components8(free).sizes;
        let largest = sizes.iter().skip(1).max().copied().unwrap_or(0);
        sizes.iter().skip(1).sum::<usize>() - largest
    }

    /// Stamps `p` in. The pockets are counted again only when `p` may have cut some floor
    /// off; so the count may stay above the truth when `p` covers part of a pocket, and only
    /// [`drop_pocket_closers`] counts afresh.
    fn stamp(&mut self, p: &Placed) {
        let taken: Vec<usize> = (self.cells_of(p).into_iter())
            .filter(|&c| self.free[c])
            .collect();
        let bypassed = self.bypassed(&taken);
        for &c in &taken {
            self.free[c] = false;
        }
        if !bypassed {
            self.pocket_cells = self.pockets_of(&self.free);
        }
    }

    /// Whether placing `p` would cut more of the floor off the walkway than is cut off now.
    /// Decided locally when it can be: if the free cells bordering what `p` takes stay
    /// connected to each other around it, every path through it still has a way round.
    pub(super) fn cut_off_by(&self, p: &Placed) -> bool {
        let taken: Vec<usize> = (self.cells_of(p).into_iter())
            .filter(|&c| self.free[c])
            .collect();
        if self.bypassed(&taken) {
            return false;
        }
        let mut free = self.free.clone();
        for c in taken {
            free[c] = false;
        }
        self.pockets_of(&free) > self.pocket_cells
    }

    /// Whether the free cells 8-adjacent to the cells `taken` are all connected to each
    /// other through free cells, not taken, of the box around `taken` grown by two cells
    /// (so taking them cuts nothing off); true when nothing is taken.
    fn bypassed(&self, taken: &[usize]) -> bool {
        if taken.is_empty() {
            return true;
        }
        let (nx, nz) = (self.grid.nx, self.grid.nz);
        let (mut i0, mut j0, mut i1, mut j1) = (usize::MAX, usize::MAX, 0, 0);
        for &c in taken {
            let (i, j) = (c % nx, c / nx);
            (i0, j0, i1, j1) = (i0.min(i), j0.min(j), i1.max(i), j1.max(j));
        }
        let (i0, j0) = (i0.saturating_sub(2), j0.saturating_sub(2));
        let (i1, j1) = ((i1 + 2).min(nx - 1), (j1 + 2).min(nz - 1));
        let w = i1 - i0 + 1;
        let local = |c: usize| (c / nx - j0) * w + (c % nx - i0);
        // 0 blocked, 1 taken, 2 free.
        let mut cell = vec![0u8; w * (j1 - j0 + 1)];
        for j in j0..=j1 {
            for i in i0..=i1 {
                cell[(j - j0) * w + (i - i0)] = 2 * u8::from(self.free[j * nx + i]);
            }
        }
        for &c in taken {
            cell[local(c)] = 1;
        }
        let neighbours = |k: usize| {
            let (i, j) = ((k % w) as isize, (k / w) as isize);
            let h = (cell.len() / w) as isize;
            (-1..=1)
                .flat_map(move |dj| (-1..=1).map(move |di| (i + di, j + dj)))
                .filter(move |&(a, b)| {
                    (a, b) != (i, j) && a >= 0 && b >= 0 && a < w as isize && b < h
                })
                .map(move |(a, b)| b as usize * w + a as usize)
        };
        let border: Vec<usize> = (0..cell.len())
            .filter(|&k| cell[k] == 2 && neighbours(k).any(|n| cell[n] == 1))
            .collect();
        let Some(&first) = border.first() else {
            return true;
        };
        let mut seen = vec![false; cell.len()];
        let mut stack = vec![first];
        seen[first] = true;
        while let Some(k) = stack.pop() {
            for n in neighbours(k) {
                if cell[n] == 2 && !seen[n] {
                    seen[n] = true;
                    stack.push(n);
                }
            }
        }
        border.iter().all(|&k| seen[k])
    }
}

/// The final check by the metric's own raster rules: no pocket of floor may stay cut off
/// from the walkway (Walk = 1). Objects bordering a pocket are dropped (at most eight),
/// newest and softest first, and reported in `dropped`.
pub(super) fn drop_pocket_closers(state: &mut FloorState<'_>, dropped: &mut Vec<DroppedObject>) {
    let plan = state.plan;
    for _ in 0..8 {
        let raster = &state.metric.grid;
        let Components { labels, sizes } = raster.components8(&state.metric.free);
        let main = (1..sizes.len()).max_by_key(|&l| sizes[l]).unwrap_or(0);
        if sizes.iter().skip(1).sum::<usize>() == sizes.get(main).copied().unwrap_or(0) {
            break;
        }
        let culprit = (state.placed.iter().enumerate())
            .filter(|(_, p)| !p.mounted && plan.objects[p.plan_index].id != plan.anchor)
            .filter(|(_, p)| {
                let mut touches_pocket = false;
                raster.for_cells_in(&p.fp, ROBOT_RADIUS + 1.5 * raster.cell, |idx| {
                    touches_pocket |= labels[idx] != 0 && labels[idx] as usize != main;
                });
                touches_pocket
            })
            .max_by_key(|(k, p)| (!plan.objects[p.plan_index].hard, *k))
            .map(|(k, _)| k);
        let Some(k) = culprit else { break };
        let p = state.placed.remove(k);
        dropped.push(DroppedObject {
            id: plan.objects[p.plan_index].id.clone(),
            reason: "it closed off a pocket of floor from the walkway".into(),
        });
        state.rebuild();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{KnowledgePlanner, PlanRequest, Planner};

    /// A floor object taller than a window's sill does not fit in front of the window; a low
    /// one does, and so does the tall one beside it.
    #[test]
    fn tall_furniture_keeps_clear_of_a_window() {
        let available: Vec<String> = scenethesis_procedural::catalog::categories()
            .map(|c| c.name.to_owned())
            .collect();
        let plan = KnowledgePlanner::new()
            .plan(&PlanRequest::new("a bedroom", available, 0))
            .unwrap();
        let mut room = Room::of(&plan).unwrap();
        let back = room.architecture.walls[0].clone();
        room.architecture
            .windows
            .push(scenethesis_scene_graph::WindowOpening {
                id: "window_0".into(),
                wall: back.id.clone(),
                offset: back.length() / 2.0,
                width: 1.0,
                height: 1.2,
                sill: 0.9,
                room: None,
            });
        let state = FloorState::new(&plan, &room, 0.05);
        let inner = state.floor[1];
        let at = |cx: f64, height: f64| Placed {
            plan_index: 0,
            fp: Footprint {
                cx,
                cz: inner + 0.3,
                yaw: 0.0,
                hx: 0.45,
                hz: 0.3,
            },
            height,
            front_access: true,
            wall: Some(back.id.clone()),
            mounted: false,
            bottom: None,
            opening: None,
        };
        assert!(
            !state.fits(&at(0.0, 2.0), 0.0),
            "a wardrobe in front of the window"
        );
        assert!(state.fits(&at(0.0, 0.6), 0.0), "a chest below the sill");
        let beside = room.architecture.floor.max.x - 0.5;
        assert!(
            state.fits(&at(beside, 2.0), 0.0),
            "a wardrobe beside the window"
        );
    }

    /// The door zone keeps the leaf's whole swing free: the quarter disc of radius the door's
    /// width about the hinge on the room side, whichever side the hinge is on, even when the
    /// plan asks for the shallowest clearance.
    #[test]
    fn door_zone_covers_the_leafs_swing() {
        let available: Vec<String> = scenethesis_procedural::catalog::categories()
            .map(|c| c.name.to_owned())
            .collect();
        let mut plan = KnowledgePlanner::new()
            .plan(&PlanRequest::new("a bedroom", available, 0))
            .unwrap();
        plan.door_clearance = 0.6;
        for side in [OpensTo::Left, OpensTo::Right] {
            let mut room = Room::of(&plan).unwrap();
            room.architecture.doors[0].leaf.as_mut().unwrap().opens_to = side;
            let state = FloorState::new(&plan, &room, 0.05);
            let zone = state.door_zone.unwrap();
            let arch = &room.architecture;
            let door = &arch.doors[0];
            let joint = arch.door_leaf(door).unwrap().joint.joint;
            let (hinge, inward) = (joint.anchor, arch.door_position(door).unwrap().1);
            let (free, _) = arch.door_position(door).unwrap();
            let out = (free.x - f64::from(hinge[0])).signum();
            for i in 0..=20 {
                let a = std::f64::consts::FRAC_PI_2 * f64::from(i) / 20.0;
                for r in [0.3, 0.6, door.width] {
                    // From the hinge toward the free edge, turning into the room.
                    let x = f64::from(hinge[0]) + r * (a.cos() * out + a.sin() * inward.x);
                    let z = f64::from(hinge[2]) + r * a.sin() * inward.y;
                    assert!(
                        zone.contains(x, z, 1e-6),
                        "{side:?}: ({x:.3}, {z:.3}) of the swing lies outside {zone:?}"
                    );
                }
            }
        }
    }
}
