//! The offline planner: archetype knowledge plus prompt reading, no model and no network.
//!
//! [`KnowledgePlanner::plan`] runs one function per phase, each in its own file: `interpret`
//! (read the prompt's place from its head noun, with `head`; choose archetypes), `select`
//! (which objects, how many, roughly where), `needs` (what serves what: a table for dining
//! chairs), `constrain` (the prompt's stated relations become hard constraints), `hierarchy` (anchor,
//! support tree, ids, layers) and `room` (room size and walkways), then `describe` words the
//! plan's layers.

mod constrain;
mod describe;
mod head;
mod hierarchy;
mod interpret;
mod looks;
mod needs;
mod requested;
mod room;
mod select;

use std::collections::{BTreeMap, BTreeSet};

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use scenethesis_scene_graph::RelationKind;

use crate::knowledge::Knowledge;
use crate::places::Thesaurus;
use crate::plan::*;

/// Plans scenes from the embedded (or a supplied) archetype knowledge, with no API key.
///
/// A prompt is matched to scene archetypes by their names and synonyms (whole phrases first,
/// then shared words); an unknown scene type blends the nearest archetypes, and every object
/// the prompt mentions joins the plan with its count. Spatial phrases of a detailed prompt
/// ("on", "inside", "under", "in front of", "facing", "beside", "left of", "against the back
/// wall", "in the corner") become hard constraints.
#[derive(Debug, Clone)]
pub struct KnowledgePlanner {
    knowledge: Knowledge,
    thesaurus: Thesaurus,
}

impl Default for KnowledgePlanner {
    fn default() -> Self {
        Self::new()
    }
}

impl KnowledgePlanner {
    /// A planner over the embedded knowledge files.
    pub fn new() -> Self {
        Self {
            knowledge: Knowledge::builtin().clone(),
            thesaurus: Thesaurus::builtin().clone(),
        }
    }

    /// A planner over caller-supplied knowledge (and the embedded place thesaurus; places
    /// whose archetypes the knowledge lacks are not used).
    pub fn with_knowledge(knowledge: Knowledge) -> Self {
        Self {
            knowledge,
            thesaurus: Thesaurus::builtin().clone(),
        }
    }

    /// The planner's place thesaurus.
    pub fn thesaurus(&self) -> &Thesaurus {
        &self.thesaurus
    }

    /// The planner's knowledge.
    pub fn knowledge(&self) -> &Knowledge {
        &self.knowledge
    }

    /// The core contents of a place (an archetype or a place of the thesaurus, by name):
    /// what any real room of the kind holds; empty for an unknown name.
    ///
    /// ```
    /// let planner = scenethesis_agents::KnowledgePlanner::new();
    /// assert!(planner.core_of("bathroom").contains(&"toilet".to_owned()));
    /// assert!(planner.core_of("no such place").is_empty());
    /// ```
    pub fn core_of(&self, place: &str) -> Vec<String> {
        self.thesaurus
            .archetype(place, &self.knowledge)
            .map(|a| a.core)
            .unwrap_or_default()
    }

    /// Every category the knowledge files name (the built-in library's categories).
    pub fn known_categories(&self) -> BTreeSet<String> {
        self.knowledge.category_names().map(str::to_owned).collect()
    }

    /// A category usable under `available`: itself, or the first available category of a
    /// generic noun's list that contains it.
    fn substitute(&self, category: &str, available: &BTreeSet<String>) -> Option<String> {
        if available.contains(category) {
            return Some(category.to_owned());
        }
        let shape = self.knowledge.prior(category).map(|p| p.shape);
        self.knowledge
            .vocabulary
            .generic
            .values()
            .filter(|list| list.iter().any(|c| c == category))
            .flatten()
            .find(|c| available.contains(*c) && self.knowledge.prior(c).map(|p| p.shape) == shape)
            .cloned()
    }
}

impl Planner for KnowledgePlanner {
    fn name(&self) -> &str {
        "knowledge"
    }

    fn plan(&self, request: &PlanRequest) -> Result<Plan, PlanError> {
        let reading = interpret::interpret(self, request)?;
        let mut rng = ChaCha8Rng::seed_from_u64(request.seed ^ 0x5ce7_e515_9a11_0001);
        let mut drafting = select::select(self, &reading, &request.available_categories, &mut rng);
        constrain::apply_stated(self, &reading, &request.available_categories, &mut drafting);
        let drafts = std::mem::take(&mut drafting.drafts);
        let mut tree = hierarchy::build(self, &reading, request, drafts)?;
        let (requested, limits) = requested::requested(&reading, &drafting, &tree.ids);
        let environment = reading.archetypes[0].environment;
        let look = looks::room_look(
            &reading,
            &drafting,
            &tree.ids,
            &mut tree.objects,
            request.seed,
            environment,
        );
        let room = room::size_room(
            &self.knowledge,
            &reading.archetypes,
            &tree.objects,
            &mut rng,
        );
        let description = describe::describe(&tree.objects, &tree.anchor);
        Ok(Plan {
            prompt: reading.prompt,
            scene_type: reading.scene_type,
            archetypes: reading.archetypes.iter().map(|a| a.name.clone()).collect(),
            environment,
            ground: reading.archetypes[0].ground.clone(),
            room_size: room.size,
            wall_height: room.wall_height,
            aisle: room.aisle,
            door_clearance: room.door_clearance,
            anchor: tree.anchor,
            objects: tree.objects,
            constraints: tree.constraints,
            description,
            notes: drafting.notes,
            assumptions: reading.assumptions,
            reading: Some(reading.place),
            limits: reading.limits.into_iter().chain(limits).collect(),
            requested,
            look: Some(look),
            keep_clear: Vec::new(),
        })
    }
}

/// One object instance being drafted.
#[derive(Debug, Clone)]
struct Draft {
    category: String,
    place: DraftPlace,
    hard: bool,
    /// Extra relations: kind and target draft.
    extra: Vec<(RelationKind, usize)>,
    /// Relations to walls (kind against-wall) stated by the prompt.
    wall: Option<String>,
    /// Hard constraints: (kind, target, phrase).
    constraints: Vec<(RelationKind, ConstraintTarget, String)>,
}

/// Where a draft goes, relative to other drafts by index.
#[derive(Debug, Clone, PartialEq)]
enum DraftPlace {
    Anchor,
    Zone(Zone),
    Relative(RelationKind, usize),
    Opposite(usize),
    Support(RelationKind, usize),
}

/// The drafts of a plan being made, with what the phases share about them.
#[derive(Debug, Clone, Default)]
struct Drafting {
    /// Every drafted object instance, in drafting order.
    drafts: Vec<Draft>,
    /// Draft indices by category.
    by_category: BTreeMap<String, Vec<usize>>,
    /// The drafts made for each mention of the prompt.
    mention_drafts: Vec<Vec<usize>>,
    /// The category planned for each mention (`None`: not available).
    mention_category: Vec<Option<String>>,
    /// What the planner substituted or left out, and why.
    notes: Vec<String>,
    /// Planned objects still reserved for the prompt's mentions.
    reserve: usize,
    /// Instances left out by [`MAX_PLANNED_OBJECTS`], by category.
    cut: BTreeMap<String, u32>,
}

impl Drafting {
    /// Adds a draft of `category` at `place` and returns its index, or `None` when the plan
    /// is full ([`MAX_PLANNED_OBJECTS`]; an archetype's own objects leave room for the
    /// objects the prompt names, `requested`).
    fn add(
        &mut self,
        category: &str,
        place: DraftPlace,
        hard: bool,
        requested: bool,
    ) -> Option<usize> {
        let room = if requested {
            self.reserve = self.reserve.saturating_sub(1);
            MAX_PLANNED_OBJECTS
        } else {
            MAX_PLANNED_OBJECTS.saturating_sub(self.reserve)
        };
        if self.drafts.len() >= room {
            *self.cut.entry(category.to_owned()).or_default() += 1;
            return None;
        }
        let idx = self.drafts.len();
        self.drafts.push(Draft {
            category: category.to_owned(),
            place,
            hard,
            extra: Vec::new(),
            wall: None,
            constraints: Vec::new(),
        });
        self.by_category
            .entry(category.to_owned())
            .or_default()
            .push(idx);
        Some(idx)
    }

    /// Removes the drafts at `gone` and every draft they carry, renumbering the rest (only
    /// before the prompt's stated relations are applied: those name drafts by index).
    fn remove(&mut self, gone: &[usize]) {
        let n = self.drafts.len();
        let mut dropped = vec![false; n];
        for &d in gone {
            dropped[d] = true;
        }
        // Carried drafts go with their carrier (parents may come after children).
        let mut changed = true;
        while changed {
            changed = false;
            for d in 0..n {
                if let DraftPlace::Support(_, p) = self.drafts[d].place {
                    if dropped[p] && !dropped[d] {
                        dropped[d] = true;
                        changed = true;
                    }
                }
            }
        }
        let mut new_index = vec![None; n];
        let mut next = 0;
        for d in 0..n {
            if !dropped[d] {
                new_index[d] = Some(next);
                next += 1;
            }
        }
        let drafts = std::mem::take(&mut self.drafts);
        for (d, mut draft) in drafts.into_iter().enumerate() {
            if dropped[d] {
                continue;
            }
            draft.place = match draft.place {
                DraftPlace::Relative(k, t) => new_index[t]
                    .map_or(DraftPlace::Zone(Zone::Free), |t| DraftPlace::Relative(k, t)),
                DraftPlace::Opposite(t) => {
                    new_index[t].map_or(DraftPlace::Zone(Zone::Free), DraftPlace::Opposite)
                }
                DraftPlace::Support(k, p) => DraftPlace::Support(k, new_index[p].unwrap_or(p)),
                other => other,
            };
            draft.extra = draft
                .extra
                .iter()
                .filter_map(|&(k, t)| new_index[t].map(|t| (k, t)))
                .collect();
            self.drafts.push(draft);
        }
        let renumber = |list: &mut Vec<usize>| {
            *list = list.iter().filter_map(|&d| new_index[d]).collect();
        };
        self.by_category.values_mut().for_each(renumber);
        self.by_category.retain(|_, v| !v.is_empty());
        self.mention_drafts.iter_mut().for_each(renumber);
    }
}
