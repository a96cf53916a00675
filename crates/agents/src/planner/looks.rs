//! Phase 7, looks: the room's style (the prompt's style word, else one drawn with the seed),
//! one palette entry per material family and per surface so that woods and fabrics agree in
//! the room, and the prompt's colours and materials on the objects and surfaces they qualify
//! (`knowledge/looks.toml`).

use std::collections::BTreeMap;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use scenethesis_scene_graph::{Environment, LookAttribute, LookScope};

use crate::looks::{LookTarget, LookWord, Looks, ReadWord, Style, SURFACES};
use crate::plan::{
    Attribute, AttributeKind, PlannedObject, RoomLook, StyleSource, SurfaceLook,
    UnavailableAttribute,
};

use super::interpret::Reading;
use super::Drafting;

/// Salt of the looks' own generator: drawing a style never changes the plan's other draws.
const LOOK_SALT: u64 = 0x100c_5a17_0000_0007;

/// The room's look, with each requested object's attributes set on its planned instances.
pub(super) fn room_look(
    reading: &Reading,
    drafting: &Drafting,
    ids: &[String],
    objects: &mut [PlannedObject],
    seed: u64,
    environment: Environment,
) -> RoomLook {
    let looks = Looks::builtin();
    let read = &reading.analysis.looks;
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ LOOK_SALT);
    let (style, style_source, style_words) = match &read.style {
        Some((name, words)) => (
            looks.style_named(name).unwrap_or(&looks.styles[0]),
            StyleSource::Prompt,
            Some(words.clone()),
        ),
        None => (
            &looks.styles[rng.random_range(0..looks.styles.len())],
            StyleSource::Seed,
            None,
        ),
    };
    let families: BTreeMap<String, String> = style
        .families
        .iter()
        .map(|(family, entries)| (family.clone(), pick(&mut rng, entries)))
        .collect();
    let mut look = RoomLook {
        style: style.name.clone(),
        style_source,
        style_words,
        surfaces: surfaces(looks, style, &mut rng, environment),
        families,
        unavailable: Vec::new(),
    };
    let mut by_target: BTreeMap<&LookTarget, Vec<&ReadWord>> = BTreeMap::new();
    for (target, word) in &read.attributes {
        by_target.entry(target).or_default().push(word);
    }
    for (target, words) in by_target {
        let name = target_name(reading, target);
        let attributes = resolve(&look, &words);
        let unavailable: Vec<UnavailableAttribute> = words
            .iter()
            .filter(|w| w.word == LookWord::Unavailable)
            .map(|w| UnavailableAttribute {
                words: w.words.clone(),
                target: name.clone(),
            })
            .collect();
        look.unavailable.extend(unavailable);
        match target {
            LookTarget::Mention(m) => {
                let planned = drafting.mention_drafts.get(*m).into_iter().flatten();
                for &d in planned {
                    if let Some(o) = objects.iter_mut().find(|o| o.id == ids[d]) {
                        o.attributes.extend(attributes.iter().cloned());
                    }
                }
            }
            LookTarget::Surface(s) => {
                if let Some(surface) = look.surfaces.get_mut(s) {
                    surface.attributes.extend(attributes);
                } else {
                    look.unavailable
                        .extend(attributes.iter().map(|a| UnavailableAttribute {
                            words: a.words.clone(),
                            target: format!("{s} (an outdoor scene has none)"),
                        }));
                }
            }
        }
    }
    look
}

/// One entry of a non-empty list, drawn with the looks' generator.
fn pick(rng: &mut ChaCha8Rng, entries: &[String]) -> String {
    entries[rng.random_range(0..entries.len())].clone()
}

/// The room surfaces of an indoor room: the style's entry for each, else the default.
fn surfaces(
    looks: &Looks,
    style: &Style,
    rng: &mut ChaCha8Rng,
    environment: Environment,
) -> BTreeMap<String, SurfaceLook> {
    if environment != Environment::Indoor {
        return BTreeMap::new();
    }
    SURFACES
        .iter()
        .filter_map(|s| {
            let base = match style.surfaces.get(*s) {
                Some(entries) => pick(rng, entries),
                None => looks.surface_defaults.get(*s)?.clone(),
            };
            Some((
                s.to_string(),
                SurfaceLook {
                    base,
                    attributes: Vec::new(),
                },
            ))
        })
        .collect()
}

/// The words naming a target in reports.
fn target_name(reading: &Reading, target: &LookTarget) -> String {
    match target {
        LookTarget::Mention(m) => reading
            .analysis
            .mentions
            .get(*m)
            .map_or_else(String::new, |m| m.words.clone()),
        LookTarget::Surface(s) => s.clone(),
    }
}

/// The attributes of one target's look words: materials resolved to a palette entry (the
/// room's choice for a family word) or a fabric token, colours scoped like the target's
/// material when it has one.
fn resolve(look: &RoomLook, words: &[&ReadWord]) -> Vec<Attribute> {
    let material_scope = words.iter().find_map(|w| match &w.word {
        LookWord::Material(m) => Some(m.scope),
        _ => None,
    });
    words
        .iter()
        .filter_map(|w| match &w.word {
            LookWord::Material(m) => {
                let material = m
                    .entry
                    .clone()
                    .or_else(|| {
                        m.family
                            .as_ref()
                            .and_then(|f| look.families.get(f).cloned())
                    })
                    .or_else(|| m.default.clone())
                    .or_else(|| m.token.clone());
                Some(Attribute {
                    words: w.words.clone(),
                    kind: AttributeKind::Material,
                    look: LookAttribute {
                        scope: m.scope,
                        material,
                        color: None,
                        color_name: None,
                    },
                })
            }
            LookWord::Color(colour, name) => Some(Attribute {
                words: w.words.clone(),
                kind: AttributeKind::Color,
                look: LookAttribute {
                    scope: material_scope.unwrap_or(LookScope::Main),
                    material: None,
                    color: Some(*colour),
                    color_name: Some(name.clone()),
                },
            }),
            LookWord::Unavailable => None,
        })
        .collect()
}
