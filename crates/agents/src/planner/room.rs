//! Phase 5, room: the room's size (grown when the floor objects need more), wall height,
//! walkway width and door clearance.

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use scenethesis_scene_graph::ParentRef;

use crate::knowledge::{Archetype, Knowledge};
use crate::plan::{PlannedObject, Zone};

/// The room a plan asks for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Room {
    /// Size [x, z] in metres, rounded to centimetres.
    pub size: [f64; 2],
    /// Wall height in metres.
    pub wall_height: f64,
    /// Minimum walkway width in metres.
    pub aisle: f64,
    /// Free depth in front of the door in metres.
    pub door_clearance: f64,
}

/// Sizes the room for `objects` within the archetypes' ranges.
pub(super) fn size_room(
    knowledge: &Knowledge,
    archetypes: &[Archetype],
    objects: &[PlannedObject],
    rng: &mut ChaCha8Rng,
) -> Room {
    let primary = &archetypes[0];
    // Room size: the archetype's range, grown when the floor objects need more room.
    let size_range = archetypes.iter().fold(primary.size, |acc, a| {
        [
            acc[0].max(a.size[0]),
            acc[1].max(a.size[1]),
            acc[2].max(a.size[2]),
            acc[3].max(a.size[3]),
        ]
    });
    let mut x = rng.random_range(size_range[0]..=size_range[1]);
    let mut z = rng.random_range(size_range[2]..=size_range[3]);
    let need: f64 = objects
        .iter()
        .filter(|o| o.parent == ParentRef::Ground && o.zone != Zone::WallMounted)
        .map(|o| footprint(knowledge, &o.category) * 2.4)
        .sum::<f64>()
        + 5.0;
    if x * z < need {
        let grow = (need / (x * z)).sqrt().min(1.5);
        x *= grow;
        z *= grow;
    }
    let tallest = objects
        .iter()
        .filter_map(|o| knowledge.prior(&o.category))
        .map(|p| p.size[1])
        .filter(|h| *h < 4.0)
        .fold(0.0, f64::max);
    let wall_height = if tallest > 2.3 { 3.4 } else { 2.8 };
    let aisle = archetypes.iter().map(|a| a.aisle).fold(0.6, f64::max);
    let door_clearance = archetypes
        .iter()
        .map(|a| a.door_clearance)
        .fold(0.6, f64::max);
    Room {
        size: [round_cm(x), round_cm(z)],
        wall_height,
        aisle,
        door_clearance,
    }
}

/// The nominal floor footprint of a category in square metres.
pub(super) fn footprint(knowledge: &Knowledge, category: &str) -> f64 {
    knowledge
        .prior(category)
        .map(|p| p.size[0] * p.size[2])
        .unwrap_or(0.25)
}

/// `v` rounded to centimetres.
fn round_cm(v: f64) -> f64 {
    (v * 100.0).round() / 100.0
}
