//! Whether a scene holds what its prompt asked for: every requested object present, and every
//! stated relation holding, checked with [`relation_holds`] (the judge's relation code).

use scenethesis_scene_graph::{Relation, RelationKind, Scene, WornMaterial, GROUND_ID};
use serde::{Deserialize, Serialize};

use crate::plan::{Attribute, AttributeKind, ConstraintTarget, Plan, PlanConstraint, StyleSource};
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
    /// Colours, materials and a style the prompt asks for (on objects of the plan, on the
    /// room's surfaces, of the room).
    #[serde(default)]
    pub attributes_requested: u32,
    /// Of those, attributes the scene's recorded materials show.
    #[serde(default)]
    pub attributes_honoured: u32,
    /// Requested attributes the scene does not show, and why.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub attributes_missed: Vec<MissedAttribute>,
    /// Look words the library cannot do, as `words (target)`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub attributes_unavailable: Vec<String>,
}

/// A requested colour, material or style the scene does not show.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct MissedAttribute {
    /// The object id, the surface (`floor`, `walls`, `ceiling`) or `room` for the style.
    pub target: String,
    /// The prompt's words for it.
    pub words: String,
    /// What the scene shows instead.
    pub reason: String,
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
    check_looks(plan, scene, &mut check);
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

/// The largest difference, per sRGB channel, between a requested colour and a worn one that
/// still honours it (rounding and the look's own conversions stay well inside it).
const COLOR_TOLERANCE: u8 = 6;

/// Counts the plan's requested attributes and those the scene's recorded looks honour: an
/// object's from the materials its asset wears (`scene.look.objects`, recorded from the
/// meshes), a surface's from its material, the style from the scene's style.
fn check_looks(plan: &Plan, scene: &Scene, check: &mut PromptCheck) {
    let Some(look) = &plan.look else { return };
    check.attributes_unavailable = look
        .unavailable
        .iter()
        .map(|u| format!("{} ({})", u.words, u.target))
        .collect();
    let mut tally = |target: &str, words: &str, verdict: Result<(), String>| {
        check.attributes_requested += 1;
        match verdict {
            Ok(()) => check.attributes_honoured += 1,
            Err(reason) => check.attributes_missed.push(MissedAttribute {
                target: target.to_owned(),
                words: words.to_owned(),
                reason,
            }),
        }
    };
    if look.style_source == StyleSource::Prompt {
        let words = look
            .style_words
            .clone()
            .unwrap_or_else(|| look.style.clone());
        let verdict = match &scene.look.style {
            Some(s) if *s == look.style => Ok(()),
            Some(s) => Err(format!("the room's style is `{s}`")),
            None => Err("the scene records no style".to_owned()),
        };
        tally("room", &words, verdict);
    }
    for object in &plan.objects {
        for a in &object.attributes {
            let verdict = match (scene.object(&object.id), scene.look.objects.get(&object.id)) {
                (None, _) => Err("the object is not in the scene".to_owned()),
                (Some(_), None) => Err("the scene records no materials for it".to_owned()),
                (Some(_), Some(worn)) => worn_honours(worn, a),
            };
            tally(&object.id, &a.words, verdict);
        }
    }
    for (name, surface) in &look.surfaces {
        for a in &surface.attributes {
            let verdict = match scene.look.surfaces.get(name) {
                None => Err("the scene records no material for it".to_owned()),
                Some(m) => worn_honours(&[WornMaterial::new(m, vec![name.clone()])], a),
            };
            tally(name, &a.words, verdict);
        }
    }
}

/// Whether some worn material shows the attribute: a material by its name (the entry, or a
/// coloured material of the entry's kind: `red_leather` for `brown_leather`), a colour by
/// its base colour.
fn worn_honours(worn: &[WornMaterial], attribute: &Attribute) -> Result<(), String> {
    let look = &attribute.look;
    let material_ok = |w: &WornMaterial| match &look.material {
        None => true,
        Some(m) => {
            let token = m.rsplit('_').next().unwrap_or(m);
            w.name == *m || w.name.ends_with(&format!("_{token}"))
        }
    };
    let colour_ok = |w: &WornMaterial| {
        look.color
            .is_none_or(|c| c.distance(w.color) <= COLOR_TOLERANCE)
    };
    if worn.iter().any(|w| match attribute.kind {
        AttributeKind::Material => material_ok(w),
        AttributeKind::Color => colour_ok(w),
    }) {
        return Ok(());
    }
    let names: Vec<String> = worn
        .iter()
        .map(|w| format!("{} {}", w.name, w.color))
        .collect();
    Err(format!("it wears {}", names.join(", ")))
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
