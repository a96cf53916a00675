//! Whether a scene holds what its prompt asked for: every requested object present, and every
//! stated relation holding, checked with [`relation_holds`] (the judge's relation code).

use scenethesis_scene_graph::{Relation, RelationKind, Scene, GROUND_ID};
use serde::{Deserialize, Serialize};

use crate::plan::{ConstraintTarget, Plan, PlanConstraint};
use scenethesis_scene_graph::relation_holds;

/// A requested object some of whose instances are not in the scene.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct MissingObject {
    /// The prompt's words for it.
    pub words: String,
    /// The planned category.
    pub category: String,
    /// How many the prompt asked for.
    pub requested: u32,
    /// How many are in the scene.
    pub present: u32,
    /// The planned ids missing from the scene.
    pub missing_ids: Vec<String>,
}

/// A stated relation that does not hold in the scene.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct BrokenRelation {
    /// The subject's id.
    pub subject: String,
    /// The relation kind.
    pub kind: RelationKind,
    /// The target: an object or wall id, `ground` for any wall, `corner` for a corner.
    pub target: String,
    /// The prompt words that stated it.
    pub phrase: String,
    /// Why it does not hold ("does not hold", "`x` is not in the scene").
    pub reason: String,
}

/// How far a scene honours its prompt; part of `report.json`.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct PromptCheck {
    /// Instances of objects the prompt names that the library can provide.
    pub requested: u32,
    /// Of those, instances in the scene.
    pub present: u32,
    /// Requested objects with instances missing from the scene.
    pub missing: Vec<MissingObject>,
    /// Nouns the prompt names that the library has nothing close to.
    pub unavailable: Vec<String>,
    /// Relations the prompt states.
    pub relations_stated: u32,
    /// Of those, relations that hold in the scene.
    pub relations_held: u32,
    /// Stated relations that do not hold.
    pub broken: Vec<BrokenRelation>,
}

impl PromptCheck {
    /// Whether every requested object is present and every stated relation holds.
    pub fn complete(&self) -> bool {
        self.present == self.requested && self.relations_held == self.relations_stated
    }
}

/// Checks `scene` against what `plan`'s prompt asked for: its requested objects (by planned
/// id) and its stated relations (the plan's constraints). Use the first plan of a run, before
/// any re-plan dropped objects.
pub fn check_prompt(plan: &Plan, scene: &Scene) -> PromptCheck {
    let mut check = PromptCheck::default();
    for r in &plan.requested {
        let Some(category) = &r.category else {
            check.unavailable.push(r.words.clone());
            continue;
        };
        if r.count == 0 {
            continue;
        }
        let present = r.ids.iter().filter(|id| scene.object(id).is_some()).count() as u32;
        check.requested += r.count;
        check.present += present.min(r.count);
        if present < r.count {
            check.missing.push(MissingObject {
                words: r.words.clone(),
                category: category.clone(),
                requested: r.count,
                present,
                missing_ids: r
                    .ids
                    .iter()
                    .filter(|id| scene.object(id).is_none())
                    .cloned()
                    .collect(),
            });
        }
    }
    for c in &plan.constraints {
        check.relations_stated += 1;
        match constraint_holds(scene, c) {
            Ok(()) => check.relations_held += 1,
            Err(reason) => check.broken.push(BrokenRelation {
                subject: c.subject.clone(),
                kind: c.kind,
                target: target_name(&c.target),
                phrase: c.phrase.clone(),
                reason,
            }),
        }
    }
    check
}

fn target_name(target: &ConstraintTarget) -> String {
    match target {
        ConstraintTarget::Object(id) | ConstraintTarget::Wall(id) => id.clone(),
        ConstraintTarget::AnyWall => GROUND_ID.to_owned(),
        ConstraintTarget::Corner => "corner".to_owned(),
    }
}

/// Whether one stated relation holds; the error says why not.
pub fn constraint_holds(scene: &Scene, c: &PlanConstraint) -> Result<(), String> {
    if scene.object(&c.subject).is_none() {
        return Err(format!("`{}` is not in the scene", c.subject));
    }
    let holds = |relation: Relation| relation_holds(scene, &c.subject, &relation);
    let held = match &c.target {
        ConstraintTarget::Object(t) => {
            if scene.object(t).is_none() {
                return Err(format!("`{t}` is not in the scene"));
            }
            holds(Relation::new(c.kind, t.clone()))
        }
        ConstraintTarget::Wall(w) => holds(Relation::new(RelationKind::AgainstWall, w.clone())),
        ConstraintTarget::AnyWall => holds(Relation::new(RelationKind::AgainstWall, GROUND_ID)),
        ConstraintTarget::Corner => {
            // Against two walls at once.
            let against = scene
                .architecture
                .walls
                .iter()
                .filter(|w| {
                    relation_holds(
                        scene,
                        &c.subject,
                        &Relation::new(RelationKind::AgainstWall, w.id.clone()),
                    ) == Some(true)
                })
                .count();
            Some(against >= 2)
        }
    };
    match held {
        Some(true) => Ok(()),
        Some(false) => Err("does not hold".to_owned()),
        None => Err(format!(
            "`{}` is not a wall of the room",
            target_name(&c.target)
        )),
    }
}
