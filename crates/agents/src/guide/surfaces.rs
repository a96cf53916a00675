//! Children on, in and under their parents' support surfaces.

use std::collections::BTreeMap;
use std::f64::consts::FRAC_PI_2;

use nalgebra::Point3;
use rand::seq::SliceRandom;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use scenethesis_scene_graph::{AssetInfo, SupportSurface, SurfaceKind};
use scenethesis_scene_graph::{ParentRef, Pose, RelationKind, LOW_SHELF_SHARE};

use super::DroppedObject;
use crate::plan::Plan;

/// Gap between neighbours on one surface, in metres.
const GAP: f64 = 0.015;

/// The share of a surface's extent a child may span.
pub(super) const FIT_SHARE: f64 = 0.98;

/// Free height kept between a child's top and the underside of what is above it, in metres.
pub(super) const HEADROOM: f64 = 0.01;

/// An axis-aligned rectangle in the parent's asset frame (x0, z0, x1, z1).
type Rect = [f64; 4];

fn rects_overlap(a: &Rect, b: &Rect) -> bool {
    a[0] < b[2] + GAP && b[0] < a[2] + GAP && a[1] < b[3] + GAP && b[1] < a[3] + GAP
}

fn rect_inside(surface: &SupportSurface, r: &Rect) -> bool {
    [[r[0], r[1]], [r[0], r[3]], [r[2], r[1]], [r[2], r[3]]]
        .iter()
        .all(|c| surface.contains(c[0] as f32, c[1] as f32))
}

fn surface_bounds(surface: &SupportSurface) -> Rect {
    surface
        .polygon
        .iter()
        .fold([f64::MAX, f64::MAX, f64::MIN, f64::MIN], |b, p| {
            [
                b[0].min(p[0] as f64),
                b[1].min(p[1] as f64),
                b[2].max(p[0] as f64),
                b[3].max(p[1] as f64),
            ]
        })
}

/// Places every supported object of `plan` whose parent has a pose, adding its pose to
/// `poses`; returns the objects that found no room.
pub(crate) fn place_children(
    plan: &Plan,
    infos: &[AssetInfo],
    poses: &mut BTreeMap<usize, Pose>,
    rng: &mut ChaCha8Rng,
) -> Vec<DroppedObject> {
    let index: BTreeMap<&str, usize> = plan
        .objects
        .iter()
        .enumerate()
        .map(|(i, o)| (o.id.as_str(), i))
        .collect();
    let mut packer = Packer::default();
    let mut dropped = Vec::new();
    let mut done = vec![false; plan.objects.len()];
    let order = fill_order(plan, infos);
    loop {
        let mut progress = false;
        for &i in &order {
            let o = &plan.objects[i];
            let ParentRef::Object(parent_id) = &o.parent else {
                continue;
            };
            if done[i] {
                continue;
            }
            let Some(&p) = index.get(parent_id.as_str()) else {
                done[i] = true;
                dropped.push(DroppedObject {
                    id: o.id.clone(),
                    reason: format!("parent `{parent_id}` is not planned"),
                });
                continue;
            };
            if !done[p] && plan.objects[p].parent != ParentRef::Ground {
                continue; // the parent is itself waiting
            }
            done[i] = true;
            progress = true;
            let Some(parent_pose) = poses.get(&p).copied() else {
                dropped.push(DroppedObject {
                    id: o.id.clone(),
                    reason: format!("parent `{parent_id}` was not placed"),
                });
                continue;
            };
            let kinds = SurfaceKind::for_support(o.support);
            let surfaces = packer.surfaces(o.support, &infos[p], p, rng);
            match packer.place(&infos[p], &infos[i], p, parent_pose, surfaces, rng) {
                Some(pose) => {
                    poses.insert(i, pose);
                }
                None => dropped.push(DroppedObject {
                    id: o.id.clone(),
                    reason: format!(
                        "no room {} `{parent_id}` (its {} surfaces are full or too small)",
                        o.support,
                        kinds
                            .iter()
                            .map(|k| format!("{k:?}").to_lowercase())
                            .collect::<Vec<_>>()
                            .join("/")
                    ),
                }),
            }
        }
        if !progress {
            break;
        }
    }
    for (i, o) in plan.objects.iter().enumerate() {
        if !done[i] && o.parent != ParentRef::Ground {
            dropped.push(DroppedObject {
                id: o.id.clone(),
                reason: "its parent chain does not reach the ground".into(),
            });
        }
    }
    dropped
}

/// The order children are placed in: what the prompt asked for first (a crowded top drops an
/// extra, never the stated mug), then largest first, so a small item never blocks a big one
/// on a shared surface.
fn fill_order(plan: &Plan, infos: &[AssetInfo]) -> Vec<usize> {
    let area = |i: usize| -(infos[i].size[0] as f64 * infos[i].size[2] as f64);
    let mut order: Vec<usize> = (0..plan.objects.len()).collect();
    order.sort_by(|&a, &b| {
        asked(plan, b)
            .cmp(&asked(plan, a))
            .then(area(a).total_cmp(&area(b)))
            .then(a.cmp(&b))
    });
    order
}

/// Whether the prompt asked for object `i` of `plan` (its support or relations were stated,
/// or it is one of the objects a request named).
pub(super) fn asked(plan: &Plan, i: usize) -> bool {
    let o = &plan.objects[i];
    o.hard || plan.requested.iter().any(|r| r.ids.contains(&o.id))
}

/// What the children placed so far take up on their parents' surfaces.
#[derive(Debug, Default)]
struct Packer {
    /// Occupied rectangles per (parent, surface index).
    occupied: BTreeMap<(usize, usize), Vec<Rect>>,
    /// The shelf each parent fills next, chosen at random once.
    next_shelf: BTreeMap<usize, usize>,
}

impl Packer {
    /// The surfaces of `parent` (plan index `p`) a child held by `support` may use, best kind
    /// first; shelves from the one the parent fills next onward, so items cluster.
    fn surfaces(
        &mut self,
        support: RelationKind,
        parent: &AssetInfo,
        p: usize,
        rng: &mut ChaCha8Rng,
    ) -> Vec<usize> {
        let mut surfaces: Vec<usize> = Vec::new();
        for kind in SurfaceKind::for_support(support) {
            let mut of_kind: Vec<usize> = parent
                .support_surfaces
                .iter()
                .enumerate()
                .filter(|(_, s)| s.kind == *kind && !on_a_lid(parent, s))
                .map(|(k, _)| k)
                .collect();
            if support == RelationKind::Under && *kind == SurfaceKind::Under {
                // A low shelf beneath a table top is "under" it too (measured against the
                // asset's height).
                let low = parent.size[1] * LOW_SHELF_SHARE as f32;
                of_kind.extend(
                    parent
                        .support_surfaces
                        .iter()
                        .enumerate()
                        .filter(|(_, s)| {
                            s.kind == SurfaceKind::Shelf
                                && s.height <= low
                                && parent
                                    .support_surfaces
                                    .iter()
                                    .any(|t| t.kind == SurfaceKind::Top && t.height > s.height)
                        })
                        .map(|(k, _)| k),
                );
            }
            if *kind == SurfaceKind::Shelf && !of_kind.is_empty() {
                // Fill shelves from a random one onward, so items cluster.
                let start = *self
                    .next_shelf
                    .entry(p)
                    .or_insert_with(|| rng.random_range(0..of_kind.len()));
                let n = of_kind.len();
                of_kind.rotate_left(start % n);
            }
            surfaces.extend(of_kind);
        }
        surfaces
    }

    /// The pose of `child` on the first of `surfaces` of `parent` (plan index `p`, at
    /// `parent_pose`) with room for it: square to the parent or turned a quarter, at its
    /// natural size or a little smaller within its scale range. `None` when none has room.
    fn place(
        &mut self,
        parent: &AssetInfo,
        child: &AssetInfo,
        p: usize,
        parent_pose: Pose,
        surfaces: Vec<usize>,
        rng: &mut ChaCha8Rng,
    ) -> Option<Pose> {
        for sk in surfaces {
            let surface = &parent.support_surfaces[sk];
            let occ = self.occupied.entry((p, sk)).or_default();
            let (cw, ch, cd) = (
                child.size[0] as f64,
                child.size[1] as f64,
                child.size[2] as f64,
            );
            let mut scale = 1.0f64;
            if let Some(clear) = surface.clearance {
                scale = scale.min((clear as f64 - HEADROOM) / ch);
            }
            let b = surface_bounds(surface);
            for rel_yaw in [0.0, FRAC_PI_2] {
                let (w, d) = if rel_yaw == 0.0 { (cw, cd) } else { (cd, cw) };
                let fit = ((b[2] - b[0]) * FIT_SHARE / w).min((b[3] - b[1]) * FIT_SHARE / d);
                let largest = scale.min(fit).min(1.0);
                let smallest = child.scale_range[0] as f64;
                // The natural size first, then a little smaller within the scale range.
                let tries = [largest, largest * 0.92, largest * 0.85];
                for s in tries.into_iter().filter(|s| *s >= smallest && *s > 0.0) {
                    let (hw, hd) = (w * s / 2.0, d * s / 2.0);
                    let round = (w - d).abs() <= 0.15 * w.max(d);
                    let margins = swept_margins(child, s, rel_yaw);
                    let spot = find_spot(surface, &b, occ, [hw, hd], margins, round, rng);
                    if let Some((x, z)) = spot {
                        occ.push([x - hw, z - hd, x + hw, z + hd]);
                        if let Some(zone) = opening_zone(child, s, [x, z], [hw, hd], rel_yaw) {
                            occ.push(zone);
                        }
                        let local = Point3::new(x, surface.height as f64, z);
                        let world = parent_pose.transform_point(&local);
                        let yaw = parent_pose.yaw + rel_yaw;
                        // Keep filling this shelf next time.
                        if surface.kind == SurfaceKind::Shelf {
                            let shelves: Vec<usize> = parent
                                .support_surfaces
                                .iter()
                                .enumerate()
                                .filter(|(_, s)| s.kind == SurfaceKind::Shelf)
                                .map(|(k, _)| k)
                                .collect();
                            if let Some(pos) = shelves.iter().position(|&k| k == sk) {
                                self.next_shelf.insert(p, pos);
                            }
                        }
                        return Some(Pose::new(s * parent_pose.scale, yaw, world.coords));
                    }
                }
            }
        }
        None
    }
}

/// Whether `surface` of `parent` is the top of a part that swings up when it opens (a
/// cooler's or a toy box's lid): its centre lies inside the box the moving parts sweep
/// ([`AssetInfo::opening_bounds`]) at a height that box spans. A thing left there would stop
/// the lid opening, so nothing is placed on it; a cabinet's top, beside its doors' sweep, stays
/// usable.
fn on_a_lid(parent: &AssetInfo, surface: &SupportSurface) -> bool {
    let Some(swept) = parent.opening_bounds.as_ref() else {
        return false;
    };
    let b = surface_bounds(surface);
    let (x, z, y) = (
        (b[0] + b[2]) / 2.0,
        (b[1] + b[3]) / 2.0,
        surface.height as f64,
    );
    (swept.min.x..=swept.max.x).contains(&x)
        && (swept.min.z..=swept.max.z).contains(&z)
        && (swept.min.y..=swept.max.y).contains(&y)
}

/// The part of a surface in front of a child placed at `centre` (half extents `half` on the
/// surface, turned by `rel_yaw` 0 or π/2 from its parent) that its doors sweep while opening
/// ([`AssetInfo::opening_bounds`] at scale `s`), kept free of later children: a mug never
/// stands where the microwave's door opens.
fn opening_zone(
    child: &AssetInfo,
    s: f64,
    [x, z]: [f64; 2],
    [hw, hd]: [f64; 2],
    rel_yaw: f64,
) -> Option<Rect> {
    let swept = child.opening_bounds.as_ref()?;
    let front = child.size[2] as f64 * s / 2.0;
    let reach = swept.max.z * s - front;
    if reach <= 0.01 {
        return None;
    }
    // The child's front is +z on the surface, or +x once turned by π/2.
    Some(if rel_yaw == 0.0 {
        [x - hw, z + hd, x + hw, z + hd + reach]
    } else {
        [x + hw, z - hd, x + hw + reach, z + hd]
    })
}

/// How far past a child's body (half extents `w·s/2 × d·s/2` about its origin) its moving
/// parts sweep behind it and to its sides while opening ([`AssetInfo::opening_bounds`] at
/// scale `s`), on the surface's axes once the child is turned by `rel_yaw` (0 or π/2): the
/// margins [−x, −z, +x, +z] that must stay on the surface too, so a laptop's screen leaning
/// back never meets the wall or the sofa behind its table. The front is left out: a door
/// swinging out past a counter's edge opens into the room, and [`opening_zone`] keeps that
/// part clear of the surface's other children. Zero for a child with no moving parts.
fn swept_margins(child: &AssetInfo, s: f64, rel_yaw: f64) -> [f64; 4] {
    let Some(swept) = child.opening_bounds.as_ref() else {
        return [0.0; 4];
    };
    let (hw, hd) = (
        child.size[0] as f64 * s / 2.0,
        child.size[2] as f64 * s / 2.0,
    );
    let side = (swept.max.x.max(-swept.min.x) * s - hw).max(0.0);
    let back = (-swept.min.z * s - hd).max(0.0);
    // The child's front is +z on the surface, or +x once turned by π/2.
    if rel_yaw == 0.0 {
        [side, back, side, 0.0]
    } else {
        [back, side, 0.0, side]
    }
}

/// A free centre for a rectangle of half extents `half` on the surface, whose margins
/// `margins` ([`swept_margins`]) also stay on it: packed left to right on shelves and in
/// containers, spread out on tops, centred underneath. The spots tried (and the random draws
/// made) do not depend on the margins, which only rule spots out, so a child with moving parts
/// changes where nothing else goes but on its own surface.
fn find_spot(
    surface: &SupportSurface,
    b: &Rect,
    occ: &[Rect],
    [hw, hd]: [f64; 2],
    margins: [f64; 4],
    round: bool,
    rng: &mut ChaCha8Rng,
) -> Option<(f64, f64)> {
    // A round item (about as wide as deep) in a container only needs its inscribed circle
    // on the container's floor.
    let circle_inside = |x: f64, z: f64| {
        let radius = hw.max(hd);
        (0..12).all(|k| {
            let a = k as f64 * std::f64::consts::PI / 6.0;
            surface.contains((x + radius * a.cos()) as f32, (z + radius * a.sin()) as f32)
        })
    };
    let [ml, mn, mr, mf] = margins;
    let ok = |x: f64, z: f64| {
        let r = [x - hw, z - hd, x + hw, z + hd];
        let reach = [r[0] - ml, r[1] - mn, r[2] + mr, r[3] + mf];
        let inside = if round && surface.kind == SurfaceKind::Interior {
            circle_inside(x, z) && (margins == [0.0; 4] || rect_inside(surface, &reach))
        } else {
            rect_inside(surface, &reach)
        };
        inside && !occ.iter().any(|o| rects_overlap(o, &r))
    };
    let step = 0.01;
    let xs: Vec<f64> = {
        let (lo, hi) = (b[0] + hw, b[2] - hw);
        if hi < lo {
            return None;
        }
        let mut v: Vec<f64> = (0..=((hi - lo) / step) as usize)
            .map(|k| lo + k as f64 * step)
            .collect();
        v.push((lo + hi) / 2.0);
        v.sort_by(f64::total_cmp);
        v
    };
    let zs: Vec<f64> = {
        let (lo, hi) = (b[1] + hd, b[3] - hd);
        if hi < lo {
            return None;
        }
        let mid = (lo + hi) / 2.0;
        let mut v: Vec<f64> = (0..=((hi - lo) / step) as usize)
            .map(|k| lo + k as f64 * step)
            .collect();
        v.push(mid);
        v.sort_by(|a, c| (a - mid).abs().total_cmp(&(c - mid).abs()));
        v
    };
    match surface.kind {
        SurfaceKind::Shelf | SurfaceKind::Interior => {
            // Front-to-back rows nearest the middle first, left to right within a row.
            let from_right = rng.random_bool(0.5);
            for &z in zs.iter().step_by(2) {
                let iter: Box<dyn Iterator<Item = &f64>> = if from_right {
                    Box::new(xs.iter().rev())
                } else {
                    Box::new(xs.iter())
                };
                for &x in iter {
                    if ok(x, z) {
                        return Some((x, z));
                    }
                }
            }
            None
        }
        SurfaceKind::Under => {
            let cx = (b[0] + b[2]) / 2.0;
            let mut xs = xs;
            xs.sort_by(|a, c| (a - cx).abs().total_cmp(&(c - cx).abs()));
            for &z in zs.iter().step_by(2) {
                for &x in xs.iter().step_by(2) {
                    if ok(x, z) {
                        return Some((x, z));
                    }
                }
            }
            None
        }
        SurfaceKind::Top => {
            // Random samples; keep the one farthest from what is already there.
            let mut grid: Vec<(f64, f64)> = xs
                .iter()
                .step_by(2)
                .flat_map(|&x| zs.iter().step_by(2).map(move |&z| (x, z)))
                .collect();
            grid.shuffle(rng);
            let mut best: Option<((f64, f64), f64)> = None;
            let mut seen = 0;
            for (x, z) in grid {
                if !ok(x, z) {
                    continue;
                }
                let clearance = occ
                    .iter()
                    .map(|o| {
                        let (ox, oz) = ((o[0] + o[2]) / 2.0, (o[1] + o[3]) / 2.0);
                        ((ox - x).powi(2) + (oz - z).powi(2)).sqrt()
                    })
                    .fold(f64::MAX, f64::min);
                if best.is_none_or(|(_, c)| clearance > c) {
                    best = Some(((x, z), clearance));
                }
                seen += 1;
                if seen >= 24 {
                    break;
                }
            }
            best.map(|(p, _)| p)
        }
    }
}
