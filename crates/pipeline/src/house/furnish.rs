//! Every room of a floor plan furnished by the single-room stages (plan, retrieve, guide,
//! optimize, judge and its re-plans) inside its own shell, in parallel and deterministically.

use std::collections::{BTreeMap, VecDeque};
use std::time::Instant;

use rayon::prelude::*;
use scenethesis_floorplan::{FloorPlan, Knowledge, Room, EXTERIOR};
use scenethesis_scene_graph::{fnv1a64, mix64, Mesh, Scene};

use super::frame::RoomShell;
use super::words::room_prompt;
use crate::pipeline::{GenerateOptions, GeneratedScene, Pipeline};
use crate::stage::NoProgress;
use crate::PipelineError;

/// One furnished room, in its own frame.
pub(crate) struct RoomRun {
    /// The room's shell (frame, size, doors, windows).
    pub(crate) shell: RoomShell,
    /// The room of the plan.
    pub(crate) room: Room,
    /// The single-room prompt it was planned from.
    pub(crate) prompt: String,
    /// The room's run, or `None` when it was left empty.
    pub(crate) generated: Option<GeneratedScene>,
    /// The empty shell's scene when the room was left empty.
    pub(crate) empty: Scene,
    /// Why it was left empty.
    pub(crate) notes: Vec<String>,
}

impl RoomRun {
    /// The room's scene (room frame).
    pub(crate) fn scene(&self) -> &Scene {
        self.generated.as_ref().map_or(&self.empty, |g| &g.scene)
    }

    /// Its objects' meshes.
    pub(crate) fn meshes(&self) -> Option<&BTreeMap<String, Mesh>> {
        self.generated.as_ref().map(|g| &g.meshes)
    }
}

/// For every room, the door it is first reached by walking in from the entrance (breadth
/// first over the plan's doors, in plan order).
pub(crate) fn entry_doors(plan: &FloorPlan) -> BTreeMap<String, String> {
    let mut entry = BTreeMap::new();
    let mut queue = VecDeque::from([EXTERIOR.to_owned()]);
    while let Some(room) = queue.pop_front() {
        for door in plan.doors_of(&room) {
            let Some(next) = door.other(&room) else {
                continue;
            };
            if next != EXTERIOR && !entry.contains_key(next) {
                entry.insert(next.to_owned(), door.id.clone());
                queue.push_back(next.to_owned());
            }
        }
    }
    entry
}

/// The seed of a room's run: the house seed mixed with the room's id.
fn room_seed(seed: u64, room: &str) -> u64 {
    mix64(seed ^ fnv1a64(room.as_bytes()))
}

impl Pipeline {
    /// Furnishes every room of `plan` (in parallel; the result is in plan order and the same
    /// for the same seed). A room whose run fails for a reason other than time or a stop
    /// request is left empty with a note.
    pub(crate) fn furnish_rooms(
        &self,
        plan: &FloorPlan,
        house_prompt: &str,
        seed: u64,
        options: &GenerateOptions,
        started: Instant,
    ) -> Result<Vec<RoomRun>, PipelineError> {
        let knowledge = Knowledge::builtin();
        let entries = entry_doors(plan);
        let mut room_options = options.clone();
        room_options.time_limit = options
            .time_limit
            .map(|limit| limit.saturating_sub(started.elapsed()));
        plan.rooms
            .par_iter()
            .map(|room| {
                let shell = RoomShell::of(plan, room, entries.get(&room.id).map(String::as_str));
                let prompt = room_prompt(knowledge, house_prompt, &room.room_type);
                self.furnish_room(
                    shell,
                    room,
                    prompt,
                    room_seed(seed, &room.id),
                    &room_options,
                )
            })
            .collect()
    }

    /// One room's run in its shell.
    fn furnish_room(
        &self,
        shell: RoomShell,
        room: &Room,
        prompt: String,
        seed: u64,
        options: &GenerateOptions,
    ) -> Result<RoomRun, PipelineError> {
        let empty = Scene::new(shell.architecture.clone());
        let (result, used) = scenethesis_models::metered(|| {
            self.run_room(&prompt, seed, options, &mut NoProgress, Some(&shell))
        });
        let (generated, notes) = match result {
            Ok(mut generated) => {
                generated.report.providers = used;
                (Some(generated), Vec::new())
            }
            Err(e @ (PipelineError::OutOfTime { .. } | PipelineError::Stopped { .. })) => {
                return Err(e)
            }
            Err(e) => (None, vec![format!("left empty: {e}")]),
        };
        Ok(RoomRun {
            shell,
            room: room.clone(),
            prompt,
            generated,
            empty,
            notes,
        })
    }
}
