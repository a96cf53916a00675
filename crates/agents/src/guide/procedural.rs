//! The offline procedural guide: rule-based floor layout with a walkway check, then children
//! packed onto their parents' support surfaces.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use scenethesis_scene_graph::{AssetInfo, ParentRef};

use super::assemble::{build_scene, ground_poses};
use super::grow::{layout_scales, scaled};
use super::place_floor::{place_floor_objects, placement_order};
use super::room::{asset_infos, Room};
use super::runs::place_runs;
use super::surfaces::place_children;
use super::walkway::{drop_pocket_closers, FloorState};
use super::{AssetLookup, Guide, GuideError, GuidedLayout, WalkwayReport};
use crate::plan::Plan;

/// Lays out plans by rules: the anchor against its wall or in the middle, storage against the
/// walls facing into the room, seats facing the anchor, tables in front of it, chairs around
/// tables, then every floor object accepted only while one connected walkway (at least the
/// plan's aisle width, ≥ 0.6 m) still reaches the door and the access side of every floor
/// object, and the robot-radius free floor stays one region. Children are packed onto their
/// parents' support surfaces (several per shelf when they fit, never overlapping); a floor
/// object too small for a child the prompt puts on, in or under it is first grown within its
/// scale range until that child fits at its smallest scale. What does not fit is dropped and
/// reported.
#[derive(Debug, Clone)]
pub struct ProceduralGuide {
    cell: f64,
}

impl Default for ProceduralGuide {
    fn default() -> Self {
        Self { cell: 0.05 }
    }
}

impl ProceduralGuide {
    /// A guide checking walkways on a raster of `cell` metres (0.05 by default).
    pub fn with_cell(cell: f64) -> Self {
        Self {
            cell: cell.clamp(0.02, 0.2),
        }
    }
}

impl Guide for ProceduralGuide {
    fn name(&self) -> &str {
        "procedural"
    }

    /// Lays the plan out; when the anchor, a stated (hard) object or a parent of other objects
    /// finds no room, the room grows by 12 % and the layout is redone (at most twice).
    fn layout(
        &self,
        plan: &Plan,
        assets: &dyn AssetLookup,
        seed: u64,
    ) -> Result<GuidedLayout, GuideError> {
        let mut room = plan.clone();
        for attempt in 0..3 {
            let result = self.layout_once(&room, assets, seed)?;
            let important = |id: &str| {
                room.object(id).is_some_and(|o| {
                    o.parent == ParentRef::Ground
                        && (o.id == room.anchor
                            || o.hard
                            || room
                                .objects
                                .iter()
                                .any(|c| c.parent.object_id() == Some(id)))
                })
            };
            if attempt == 2 || !result.dropped.iter().any(|d| important(&d.id)) {
                return Ok(result);
            }
            room.room_size = room.room_size.map(|v| (v * 1.12 * 100.0).round() / 100.0);
        }
        unreachable!("the last attempt returns")
    }
}

impl ProceduralGuide {
    /// One layout of the plan in its room, phase by phase: the room and the assets, the floor
    /// objects placed while the walkway stays open, the final walkway check by the metric's
    /// rules, the children on their parents, and the scene.
    fn layout_once(
        &self,
        plan: &Plan,
        assets: &dyn AssetLookup,
        seed: u64,
    ) -> Result<GuidedLayout, GuideError> {
        let room = Room::of(plan)?;
        let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x9e37_79b9_7f4a_7c15);
        let infos = asset_infos(plan, assets)?;
        // Everything is placed at its layout scale; the scene keeps the assets' own metadata
        // and carries the scale in the poses.
        let scales = layout_scales(plan, &infos);
        let laid: Vec<AssetInfo> = infos
            .iter()
            .zip(&scales)
            .map(|(i, &k)| scaled(i, k))
            .collect();
        let mut state = FloorState::new(plan, &room, self.cell);
        let runs = place_runs(&mut state, &laid, &room.sides, seed);
        let order: Vec<usize> = placement_order(plan)
            .into_iter()
            .filter(|&i| state.placed_of(i).is_none())
            .collect();
        let mut dropped = place_floor_objects(
            &mut state,
            order,
            &laid,
            &room.sides,
            runs.as_ref(),
            &mut rng,
        );
        if state.placed.iter().all(|p| p.mounted) {
            let [width, depth] = plan.room_size;
            return Err(GuideError::NothingFits { width, depth });
        }
        drop_pocket_closers(&mut state, &mut dropped);
        let (mut poses, walls) = ground_poses(&state);
        dropped.extend(place_children(plan, &laid, &mut poses, &mut rng));
        for (i, pose) in poses.iter_mut() {
            pose.scale *= scales[*i];
        }
        let (_, ratio, door_ok, unreachable) = state.evaluate(None);
        let scene = build_scene(plan, seed, room, &infos, &poses, &walls);
        Ok(GuidedLayout {
            scene,
            dropped,
            walkway: WalkwayReport {
                walk_ratio: ratio,
                door_reachable: door_ok,
                unreachable: unreachable
                    .into_iter()
                    .map(|i| plan.objects[i].id.clone())
                    .collect(),
            },
            guidance: None,
            notes: Vec::new(),
        })
    }
}
