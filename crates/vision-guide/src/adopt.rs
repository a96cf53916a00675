//! The image leads: every labelled object the guidance shows becomes an object of the plan.
//!
//! A label matched to a planned object of its category guides that object; a label no planned
//! object is left for is *adopted*: a new planned object of the label's category (the label's
//! own id when it is free, else the category's next free `category_N`), with the support
//! relation the lift of the image gives it — on, inside or under the object it rests on, hung
//! on a wall, or on the floor. The pipeline appends the adopted objects to the plan before
//! retrieval, so they are retrieved, laid out, optimized and judged like planned ones.

use std::collections::{BTreeMap, BTreeSet};

use scenethesis_agents::{
    Knowledge, Layer, Plan, PlannedObject, Zone, BACK_WALL, FRONT_WALL, LEFT_WALL,
    MAX_PLANNED_OBJECTS, MAX_ROOM_SIDE, MIN_ROOM_SIDE, RIGHT_WALL,
};
use scenethesis_imagery::{Guidance, Mask};
use scenethesis_scene_graph::{is_printable_id, limits::MAX_ID_BYTES, ParentRef, RelationKind};
use scenethesis_scene_graph::{Architecture, GROUND_ID};
use scenethesis_vision::files::Labels;
use scenethesis_vision::{lift_scene, LiftOptions, SupportGuess, SupportKind};

use crate::detect::assign_labels;

/// A label to adopt: its id, the planned id it gets and its category.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NewObject {
    /// The label's id in `labels.json`.
    pub label: String,
    /// The id of the new planned object.
    pub id: String,
    /// Its category (the library's).
    pub category: String,
}

/// The labels of `labels` no planned object of `plan` is left for, each with the id its new
/// object gets; the notes say which labels the plan's object limit left out.
pub fn new_objects(
    plan: &Plan,
    masks: &BTreeMap<String, Mask>,
    labels: &Labels,
) -> (Vec<NewObject>, Vec<String>) {
    let matched = assign_labels(plan, masks, labels);
    let mut used: BTreeSet<String> = plan.objects.iter().map(|o| o.id.clone()).collect();
    let room = MAX_PLANNED_OBJECTS.saturating_sub(plan.objects.len());
    let mut out = Vec::new();
    let mut notes = Vec::new();
    for (label, category) in matched.unplanned {
        if out.len() == room {
            notes.push(format!(
                "label `{label}` ({category}) is not adopted: the plan holds its limit of \
                 {MAX_PLANNED_OBJECTS} objects"
            ));
            continue;
        }
        let id = if usable_id(&label) && !used.contains(&label) {
            label.clone()
        } else {
            (0..)
                .map(|n| format!("{category}_{n}"))
                .find(|id| !used.contains(id))
                .expect("a free id")
        };
        used.insert(id.clone());
        out.push(NewObject {
            label,
            id,
            category,
        });
    }
    (out, notes)
}

/// Whether a label's id can name a planned object: printable, short, and not the ground's or
/// a wall's.
fn usable_id(id: &str) -> bool {
    is_printable_id(id)
        && id.len() <= MAX_ID_BYTES
        && id != GROUND_ID
        && ![BACK_WALL, LEFT_WALL, FRONT_WALL, RIGHT_WALL].contains(&id)
}

/// What the lift of every labelled mask gives the adoption: the new objects as planned
/// objects (parents before children) and the size of every object's box, by id.
pub type Adopted = (Vec<PlannedObject>, BTreeMap<String, [f64; 3]>);

/// The planned objects of `new`, with the supports the lift of `view` gives them (every mask
/// of `labels`, the planned objects' under their planned ids, so an adopted cushion can rest on
/// a planned sofa), parents before children; and every lifted box's size
/// (`[long side, height, short side]` of its footprint), by object id.
pub fn adopted_objects(
    plan: &Plan,
    new: &[NewObject],
    view: &Guidance,
    labels: &Labels,
    architecture: &Architecture,
    options: &LiftOptions,
) -> Result<Adopted, String> {
    let matched = assign_labels(plan, &view.masks, labels);
    let mut masks: BTreeMap<String, Mask> = BTreeMap::new();
    let mut categories: BTreeMap<String, String> = BTreeMap::new();
    for (label, id) in &matched.assigned {
        masks.insert(id.clone(), view.masks[label].clone());
        let o = plan.object(id).expect("assigned to a planned object");
        categories.insert(id.clone(), o.category.clone());
    }
    for n in new {
        masks.insert(n.id.clone(), view.masks[&n.label].clone());
        categories.insert(n.id.clone(), n.category.clone());
    }
    let guidance = Guidance::new(view.camera, view.image.clone(), view.depth.clone(), masks)
        .map_err(|e| e.to_string())?;
    let knowledge = Knowledge::builtin();
    let mut options = options.clone();
    options.priors = categories
        .iter()
        .filter_map(|(id, c)| {
            let [x, y, z] = knowledge.prior(c)?.size;
            Some((id.clone(), nalgebra::Vector3::new(x, y, z)))
        })
        .collect();
    options.walls = architecture.walls.clone();
    let lifted = lift_scene(&guidance, &options).map_err(|e| e.to_string())?;
    let supports: BTreeMap<&str, &SupportGuess> =
        lifted.supports.iter().map(|s| (s.id.as_str(), s)).collect();
    let layers: BTreeMap<&str, Layer> = plan
        .objects
        .iter()
        .map(|o| (o.id.as_str(), o.layer))
        .collect();
    let objects = new
        .iter()
        .map(|n| {
            let wall_asset = knowledge
                .prior(&n.category)
                .is_some_and(|p| p.mount == scenethesis_agents::knowledge::Mount::Wall);
            let guess = supports.get(n.id.as_str()).copied();
            planned(n, guess, wall_asset, &layers)
        })
        .collect();
    // The height the image shows, not the prior-blended one: the category's prior must not
    // pick the asset variant that then becomes the object's prior.
    let sizes = lifted
        .boxes
        .iter()
        .map(|b| {
            let s = b.size();
            (b.id.clone(), [s.x.max(s.z), b.seen_height, s.x.min(s.z)])
        })
        .collect();
    Ok((parents_first(objects), sizes))
}

/// The planned object of `n` resting as `guess` says (none: the lift could not place it, and
/// the layout will say so); `wall_asset` when its category hangs on walls.
fn planned(
    n: &NewObject,
    guess: Option<&SupportGuess>,
    wall_asset: bool,
    layers: &BTreeMap<&str, Layer>,
) -> PlannedObject {
    let on_wall = (
        Zone::WallMounted,
        RelationKind::AgainstWall,
        ParentRef::Ground,
    );
    let on_floor = (Zone::Free, RelationKind::OnFloor, ParentRef::Ground);
    let (zone, support, parent) = match guess.map(|g| (g.kind, g.parent.clone())) {
        Some((SupportKind::On, Some(p))) => {
            (Zone::Supported, RelationKind::On, ParentRef::Object(p))
        }
        Some((SupportKind::Inside, Some(p))) => {
            (Zone::Supported, RelationKind::Inside, ParentRef::Object(p))
        }
        Some((SupportKind::Under, Some(p))) => {
            (Zone::Supported, RelationKind::Under, ParentRef::Object(p))
        }
        Some((SupportKind::Mounted, _)) => on_wall,
        Some((SupportKind::Unsupported, _)) if wall_asset => on_wall,
        _ => on_floor,
    };
    let layer = match (&parent, &zone) {
        (ParentRef::Object(p), _) => match layers.get(p.as_str()) {
            Some(Layer::Background) => Layer::Background,
            _ => Layer::Foreground,
        },
        (_, Zone::WallMounted) => Layer::Background,
        _ => Layer::Foreground,
    };
    PlannedObject {
        id: n.id.clone(),
        category: n.category.clone(),
        layer,
        support,
        parent,
        zone,
        relations: Vec::new(),
        hard: false,
        attributes: Vec::new(),
    }
}

/// `objects` with every one whose parent is among them after that parent (the lift's parents
/// are strictly lower, so no cycle; any left over keeps its place at the end).
fn parents_first(objects: Vec<PlannedObject>) -> Vec<PlannedObject> {
    let ids: BTreeSet<String> = objects.iter().map(|o| o.id.clone()).collect();
    let mut done: BTreeSet<String> = BTreeSet::new();
    let mut out: Vec<PlannedObject> = Vec::new();
    let mut pending = objects;
    loop {
        let before = pending.len();
        let (ready, wait): (Vec<_>, Vec<_>) = pending.into_iter().partition(|o| {
            o.parent
                .object_id()
                .is_none_or(|p| !ids.contains(p) || done.contains(p))
        });
        for o in ready {
            done.insert(o.id.clone());
            out.push(o);
        }
        pending = wait;
        if pending.is_empty() || pending.len() == before {
            break;
        }
    }
    out.extend(pending);
    out
}

/// Pixels sampled per row and column when measuring the room's walls.
const WALL_STRIDE: u32 = 2;
/// Wall points are taken this far above the floor and below this height (metres): clear of
/// the floor, skirting and most furniture tops, and below the ceiling of any room.
const WALL_BAND: (f64, f64) = (0.3, 2.0);
/// A wall counts as seen when at least this share of the wall points lie within
/// [`WALL_SLAB`] of its plane.
const WALL_SHARE: f64 = 0.03;
/// Half-thickness of the slab of points that make up a seen wall (metres).
const WALL_SLAB: f64 = 0.03;

/// The room's half extents `[x, z]` as the walls the image shows them: depth pixels outside
/// every mask, between [`WALL_BAND`]'s heights, lifted to the world; on each axis, the outermost
/// plane of |x| or |z| that holds a wall's share ([`WALL_SHARE`]) of them. `None` on an axis with no wall seen (the back wall alone says nothing about the
/// side walls), and without depth. The room is centred on the origin (the guidance files'
/// convention).
pub fn room_from_walls(view: &Guidance) -> [Option<f64>; 2] {
    let Some(depth) = &view.depth else {
        return [None, None];
    };
    let (w, h) = (view.camera.intrinsics.width, view.camera.intrinsics.height);
    let mut xs = Vec::new();
    let mut zs = Vec::new();
    for v in (0..h).step_by(WALL_STRIDE as usize) {
        for u in (0..w).step_by(WALL_STRIDE as usize) {
            let Some(d) = depth.get(u, v).filter(|d| *d > 0.0) else {
                continue;
            };
            if view.masks.values().any(|m| m.contains(u, v)) {
                continue;
            }
            let pixel = nalgebra::Point2::new(u as f64 + 0.5, v as f64 + 0.5);
            let p = view.camera.unproject(&pixel, d as f64);
            if p.y > WALL_BAND.0 && p.y < WALL_BAND.1 {
                xs.push(p.x.abs());
                zs.push(p.z.abs());
            }
        }
    }
    [wall_plane(xs), wall_plane(zs)]
}

/// How far (metres) beyond a wall's inner face its outer face, top edge or cut end may show.
const WALL_DEPTH: f64 = 0.3;

/// The plane of `distances` (from the room's centre) that a wall's inner face makes: scanning
/// inward from the farthest point, the first slab [`WALL_SLAB`] thick that holds
/// [`WALL_SHARE`] of them marks the wall; of the slabs within [`WALL_DEPTH`] inside it, the
/// one holding the most points is its inner face, at its median. A wall's outer face, top and
/// cut ends, seen from a camera outside a cut-away room, can hold a wall's share too, but far
/// fewer points than the inner face.
fn wall_plane(mut distances: Vec<f64>) -> Option<f64> {
    if distances.len() < 100 {
        return None;
    }
    distances.sort_by(f64::total_cmp);
    let needed = (WALL_SHARE * distances.len() as f64).ceil() as usize;
    let mut lo = distances.len();
    let mut outermost: Option<f64> = None;
    let mut best: Option<(usize, f64)> = None;
    for hi in (0..distances.len()).rev() {
        if outermost.is_some_and(|d| distances[hi] < d - WALL_DEPTH) {
            break;
        }
        while lo > 0 && distances[hi] - distances[lo - 1] <= 2.0 * WALL_SLAB {
            lo -= 1;
        }
        let count = hi + 1 - lo;
        if count >= needed {
            outermost.get_or_insert(distances[hi]);
            if best.is_none_or(|(c, _)| count > c) {
                best = Some((count, distances[(lo + hi) / 2]));
            }
        }
    }
    best.map(|(_, plane)| plane)
}

/// The plan's room resized to the walls `view` shows ([`room_from_walls`]), rounded to the
/// centimetre; `None` when no wall is seen or the plan's room already fits them within 2 cm.
pub fn room_size(plan: &Plan, view: &Guidance) -> Option<[f64; 2]> {
    let seen = room_from_walls(view);
    let mut size = plan.room_size;
    for (side, half) in size.iter_mut().zip(seen) {
        if let Some(half) = half {
            *side = ((2.0 * half * 100.0).round() / 100.0).clamp(MIN_ROOM_SIDE, MAX_ROOM_SIDE);
        }
    }
    let changed = size
        .iter()
        .zip(plan.room_size)
        .any(|(a, b)| (a - b).abs() > 0.02);
    changed.then_some(size)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_wall_plane_is_the_outermost_slab_holding_a_walls_share() {
        // 900 points on a back wall's inner face at 2.75 m, 20 on its outer face and top,
        // the rest spread over the room.
        let mut d: Vec<f64> = (0..900).map(|i| 2.75 + (i % 3) as f64 * 0.001).collect();
        d.extend((0..20).map(|i| 2.85 + i as f64 * 0.001));
        d.extend((0..2000).map(|i| i as f64 * 0.001));
        let plane = wall_plane(d.clone()).unwrap();
        assert!((plane - 2.751).abs() < 0.002, "{plane}");
        // A wall's cut ends 10 cm beyond its inner face hold a wall's share as well, but
        // fewer points than the face.
        let mut ends = d.clone();
        ends.extend((0..150).map(|i| 2.85 + (i % 5) as f64 * 0.002));
        let plane = wall_plane(ends).unwrap();
        assert!((plane - 2.751).abs() < 0.002, "{plane}");
        // No wall: points spread evenly hold no slab's share.
        assert_eq!(
            wall_plane((0..3000).map(|i| i as f64 * 0.001).collect()),
            None
        );
    }
}
