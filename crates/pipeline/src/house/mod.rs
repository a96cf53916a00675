//! Houses (issue #26): a prompt naming a dwelling or several rooms ("a two-bedroom
//! apartment") gets a floor plan (`scenethesis-floorplan`), every room furnished by the
//! single-room stages inside its own shell ([`frame`], [`furnish`]), and one house scene
//! assembled in the plan's coordinates ([`architecture`], [`assemble`]), measured over the
//! whole house ([`measure`]) and reported room by room ([`report`], [`summary`]).

mod architecture;
mod assemble;
mod frame;
mod furnish;
mod measure;
mod plan_file;
mod report;
mod summary;
mod words;

use std::time::Instant;

use scenethesis_floorplan::{generate, FloorPlan, Knowledge, Program};
use scenethesis_render_api::render_previews;

pub(crate) use frame::RoomShell;
pub use plan_file::HousePlanFile;
pub use report::{HouseReport, RoomReport};

use crate::pipeline::{GenerateOptions, GeneratedScene, Pipeline};
use crate::stage::{Progress, Stage};
use crate::PipelineError;
use architecture::house_architecture;
use assemble::{assemble, FurnishedRoom};
use furnish::RoomRun;

/// The house program a prompt names, or `None` for a single-room prompt (which also covers
/// a dwelling word that names one room as well, alone: "a convenience store").
pub(crate) fn program_of(prompt: &str) -> Option<Program> {
    let knowledge = Knowledge::builtin();
    Program::from_words(knowledge, prompt).filter(|_| words::asks_for_house(knowledge, prompt))
}

/// A floor plan to furnish and what is known of where it came from.
pub(crate) struct HousePlan<'a> {
    /// Rooms, doors and windows.
    pub(crate) plan: &'a FloorPlan,
    /// The footprint of the wall centre lines, `[min x, min z, max x, max z]`.
    pub(crate) footprint: [f64; 4],
    /// The dwelling kind, or `plan` for a user's plan.
    pub(crate) kind: String,
    /// Whether the plan has a hallway.
    pub(crate) hallway: bool,
}

impl Pipeline {
    /// Generates the house `program` names: its floor plan for `seed`, then every room.
    pub(crate) fn run_house(
        &self,
        prompt: &str,
        seed: u64,
        options: &GenerateOptions,
        progress: &mut dyn Progress,
        program: &Program,
    ) -> Result<GeneratedScene, PipelineError> {
        let started = Instant::now();
        if progress.stop_requested() {
            return Err(PipelineError::Stopped {
                stage: Stage::Plan,
                round: 0,
            });
        }
        progress.stage_started(Stage::Plan, 0);
        let house = generate(Knowledge::builtin(), program, seed)?;
        progress.stage_finished(
            Stage::Plan,
            0,
            started.elapsed(),
            &format!("{} ({} rooms)", program.kind, house.plan.rooms.len()),
        );
        let plan = HousePlan {
            plan: &house.plan,
            footprint: house.footprint,
            kind: program.kind.clone(),
            hallway: house.hallway,
        };
        self.furnish_house(&plan, prompt, seed, options, progress, started)
    }

    /// Furnishes a floor plan room by room and assembles, measures and renders the house.
    pub(crate) fn furnish_house(
        &self,
        house: &HousePlan<'_>,
        prompt: &str,
        seed: u64,
        options: &GenerateOptions,
        progress: &mut dyn Progress,
        started: Instant,
    ) -> Result<GeneratedScene, PipelineError> {
        let furnishing = Instant::now();
        progress.stage_started(Stage::Guide, 0);
        let rooms = self.furnish_rooms(house.plan, prompt, seed, options, started)?;
        progress.stage_finished(
            Stage::Guide,
            0,
            furnishing.elapsed(),
            &format!("{} rooms furnished", rooms.len()),
        );
        let furnished: Vec<FurnishedRoom<'_>> = rooms
            .iter()
            .filter_map(|r| {
                Some(FurnishedRoom {
                    shell: &r.shell,
                    scene: r.scene(),
                    meshes: r.meshes()?,
                })
            })
            .collect();
        let architecture = house_architecture(house.plan, house.footprint);
        let (scene, meshes) = assemble(architecture, &furnished, prompt, seed);
        let judging = Instant::now();
        progress.stage_started(Stage::Judge, 0);
        let measured = measure::measure(&scene, &meshes)?;
        progress.stage_finished(Stage::Judge, 0, judging.elapsed(), "house measured");
        let rendering = Instant::now();
        let (previews, notes) = self.house_previews(&scene, &meshes, &rooms, options);
        let render_seconds = rendering.elapsed().as_secs_f64();
        let report = summary::house_report(
            summary::HouseRun {
                house,
                prompt,
                seed,
                options_digest: options.digest(self.assets().name()),
                rooms: &rooms,
                measured: &measured,
                scene: &scene,
                notes,
                render_seconds,
                total_seconds: started.elapsed().as_secs_f64(),
            },
            self,
        );
        let plan = rooms
            .iter()
            .find_map(|r| r.generated.as_ref().map(|g| g.plan.clone()))
            .ok_or_else(|| PipelineError::Inconsistent {
                detail: "no room of the house could be furnished".into(),
            })?;
        Ok(GeneratedScene {
            scene,
            meshes,
            plan,
            previews,
            report,
            guidance: None,
        })
    }

    /// The house's previews (the whole plan from above and in perspective) followed by each
    /// room's own view (`preview_<room>.png`), with notes on what was skipped.
    fn house_previews(
        &self,
        scene: &scenethesis_scene_graph::Scene,
        meshes: &std::collections::BTreeMap<String, scenethesis_scene_graph::Mesh>,
        rooms: &[RoomRun],
        options: &GenerateOptions,
    ) -> (Vec<(String, Vec<u8>)>, Vec<String>) {
        if !options.previews {
            return (Vec::new(), Vec::new());
        }
        let Some(renderer) = self.renderer() else {
            return (
                Vec::new(),
                vec!["previews skipped: no renderer configured".into()],
            );
        };
        let mut previews = match render_previews(renderer, scene, meshes, options.preview_size) {
            Ok(images) => images,
            Err(e) => return (Vec::new(), vec![format!("previews skipped: {e}")]),
        };
        for room in rooms {
            let view = room
                .generated
                .as_ref()
                .and_then(|g| g.previews.iter().find(|(name, _)| name == "preview.png"));
            if let Some((_, png)) = view {
                previews.push((format!("preview_{}.png", room.shell.id), png.clone()));
            }
        }
        (previews, Vec::new())
    }
}
