//! A user's own floor plan in `plan.json` (docs/plan.md): the prompt and the rooms, doors and
//! windows of `scenethesis-floorplan`'s `FloorPlan`, checked by its `validate` before anything
//! is built.

use std::path::Path;
use std::time::Instant;

use scenethesis_floorplan::{validate, Door, FloorPlan, Knowledge, Room, Window, HALLWAY};
use serde::{Deserialize, Serialize};

use super::HousePlan;
use crate::pipeline::{GenerateOptions, GeneratedScene, Pipeline};
use crate::stage::Progress;
use crate::PipelineError;

/// A house plan file: a prompt (optional; it becomes the scene's) and a floor plan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HousePlanFile {
    /// The scene's prompt (what each room's words are read from).
    #[serde(default)]
    pub prompt: String,
    /// The rooms: id, type (a floor-plan room type) and floor polygon on the wall centre lines.
    pub rooms: Vec<Room>,
    /// Doors and open passages between two rooms or a room and `exterior`.
    #[serde(default)]
    pub doors: Vec<Door>,
    /// Windows in exterior walls.
    #[serde(default)]
    pub windows: Vec<Window>,
}

impl HousePlanFile {
    /// The floor plan it holds.
    pub fn floor_plan(&self) -> FloorPlan {
        FloorPlan {
            rooms: self.rooms.clone(),
            doors: self.doors.clone(),
            windows: self.windows.clone(),
        }
    }

    /// Reads `path` as a house plan: `Ok(None)` when the file's JSON has no `rooms` (a
    /// single-room plan, read by `FixedPlanner`); an error naming the file and the field, or
    /// the room, door or window at fault, when it is not a valid house plan.
    pub fn from_file(path: &Path) -> Result<Option<Self>, PipelineError> {
        let read = |source| PipelineError::Read {
            path: path.to_owned(),
            source,
        };
        let text = std::fs::read_to_string(path).map_err(read)?;
        let syntax = |message: String| PipelineError::PlanSyntax {
            path: path.to_owned(),
            message,
        };
        let value: serde_json::Value =
            serde_json::from_str(&text).map_err(|e| syntax(e.to_string()))?;
        if value.get("rooms").is_none() {
            return Ok(None);
        }
        let file: Self = serde_json::from_value(value).map_err(|e| syntax(e.to_string()))?;
        validate(&file.floor_plan(), Knowledge::builtin())?;
        Ok(Some(file))
    }
}

/// The footprint `[min x, min z, max x, max z]` of a plan's room outlines.
fn footprint(plan: &FloorPlan) -> [f64; 4] {
    plan.rooms.iter().flat_map(|r| r.polygon.iter()).fold(
        [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ],
        |[a, b, c, d], p| [a.min(p.x), b.min(p.y), c.max(p.x), d.max(p.y)],
    )
}

impl Pipeline {
    /// Furnishes a user's floor plan (checked again with `validate`; a bad plan is an error
    /// naming the room, door or window at fault). Deterministic for the same file and seed.
    pub fn generate_house(
        &self,
        file: &HousePlanFile,
        seed: u64,
        options: &GenerateOptions,
        progress: &mut dyn Progress,
    ) -> Result<GeneratedScene, PipelineError> {
        let started = Instant::now();
        let plan = file.floor_plan();
        validate(&plan, Knowledge::builtin())?;
        let house = HousePlan {
            plan: &plan,
            footprint: footprint(&plan),
            kind: "plan".into(),
            hallway: plan.rooms.iter().any(|r| r.room_type == HALLWAY),
        };
        self.furnish_house(&house, &file.prompt, seed, options, progress, started)
    }
}
