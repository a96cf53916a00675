//! Phase 1, interpret: read the prompt and choose the archetypes the scene draws on.
//!
//! No non-empty prompt is refused. The scene type comes, in order, from: an archetype the
//! prompt names; a place of the thesaurus (`knowledge/places.toml`: "a pharmacy" is a shop
//! selling medicine) when its phrase is longer than any archetype phrase found; archetypes
//! sharing the prompt's words; the archetypes holding the objects the prompt names; the
//! generic room of a place family ("a haunted castle" → fantasy); the default archetype.
//! Everything but the first is recorded as an assumption of the plan.

use std::collections::BTreeSet;

use crate::knowledge::Archetype;
use crate::places::{Family, PlaceKind};
use crate::plan::{cut_prompt, PlanError, PlanRequest};
use crate::prompt::{analyze, Analysis};
use crate::text::tokenize;

use super::KnowledgePlanner;

/// What the planner made of a prompt before drafting any object.
#[derive(Debug, Clone)]
pub(super) struct Reading {
    /// The prompt, trimmed (and cut to [`crate::MAX_PROMPT_CHARS`]).
    pub prompt: String,
    /// Mentions, stated relations and archetype matches.
    pub analysis: Analysis,
    /// The archetypes the plan draws on, primary first (places of the thesaurus derived).
    pub archetypes: Vec<Archetype>,
    /// The plan's scene type: the primary archetype's name, or `custom` for a blend.
    pub scene_type: String,
    /// What was assumed to read the prompt (empty when it names a known scene type).
    pub assumptions: Vec<String>,
    /// Limits applied to the prompt (its length).
    pub limits: Vec<String>,
}

/// Reads `request.prompt` and chooses its archetypes.
pub(super) fn interpret(
    planner: &KnowledgePlanner,
    request: &PlanRequest,
) -> Result<Reading, PlanError> {
    let prompt = request.prompt.trim();
    let knowledge = &planner.knowledge;
    if !prompt.chars().any(char::is_alphanumeric) {
        return Err(PlanError::EmptyPrompt);
    }
    let (prompt, cut) = cut_prompt(prompt);
    let limits: Vec<String> = cut.into_iter().collect();
    let analysis = analyze(
        prompt,
        knowledge,
        &planner.thesaurus.nouns,
        &request.available_categories,
    );
    let choice = choose_archetypes(planner, &analysis, prompt);
    if choice.archetypes.is_empty() {
        // Only knowledge without archetypes gets here.
        return Err(PlanError::Unintelligible {
            prompt: prompt.to_owned(),
        });
    }
    let scene_type = if choice.blended {
        "custom".to_owned()
    } else {
        choice.archetypes[0].name.clone()
    };
    Ok(Reading {
        prompt: prompt.to_owned(),
        analysis,
        archetypes: choice.archetypes,
        scene_type,
        assumptions: choice.assumption.into_iter().collect(),
        limits,
    })
}

/// The archetypes chosen for a prompt.
struct Choice {
    archetypes: Vec<Archetype>,
    blended: bool,
    assumption: Option<String>,
}

/// The archetypes best matching the analysis (best first), whether they blend, and what was
/// assumed: the sources of the module's list, tried in order.
fn choose_archetypes(planner: &KnowledgePlanner, analysis: &Analysis, prompt: &str) -> Choice {
    let tokens = tokenize(prompt);
    let stems: Vec<Option<&str>> = tokens.iter().map(|t| t.stem()).collect();
    let chooser = Chooser { planner, analysis };
    // A place of the thesaurus that derives, with its phrase length.
    let place = planner.thesaurus.find_place(&stems).and_then(|(p, len)| {
        planner
            .thesaurus
            .archetype(&p.name, &planner.knowledge)
            .map(|a| (p, a, len))
    });
    if let Some(choice) = chooser.named(place.as_ref().map(|(_, _, len)| *len)) {
        return choice;
    }
    if let Some((place, archetype, _)) = place {
        return read_as_place(place, archetype);
    }
    let family = planner.thesaurus.find_family(&stems).and_then(|(f, word)| {
        planner
            .thesaurus
            .archetype(&f.room, &planner.knowledge)
            .map(|a| (f, word, a))
    });
    // A family's head noun ("a city bus") tells more than a word shared with an archetype
    // phrase ("city park"), unless the prompt names objects.
    if analysis.mentions.is_empty() {
        if let Some(f) = family.clone() {
            return chooser.family_room(f);
        }
    }
    chooser
        .sharing_words()
        .or_else(|| chooser.holding_mentions())
        .or_else(|| family.map(|f| chooser.family_room(f)))
        .unwrap_or_else(|| chooser.default_room())
}

/// The choice read from a place of the thesaurus.
fn read_as_place(place: &PlaceKind, archetype: Archetype) -> Choice {
    let name = place.name.replace('_', " ");
    let article = if name.starts_with(['a', 'e', 'i', 'o', 'u']) {
        "an"
    } else {
        "a"
    };
    Choice {
        assumption: Some(format!(
            "read as {article} {name}: {} (like `{}`, family {})",
            place.gloss, place.like, place.family
        )),
        archetypes: vec![archetype],
        blended: false,
    }
}

/// The planner's knowledge and the prompt's analysis, asked in turn by each source of a
/// [`Choice`].
struct Chooser<'a> {
    planner: &'a KnowledgePlanner,
    analysis: &'a Analysis,
}

impl Chooser<'_> {
    /// The archetypes at `chosen` indices.
    fn by_index(&self, chosen: &[usize]) -> Vec<Archetype> {
        chosen
            .iter()
            .map(|&i| self.planner.knowledge.archetypes[i].clone())
            .collect()
    }

    /// The archetypes at `chosen` indices, quoted and joined with "and".
    fn names(&self, chosen: &[usize]) -> String {
        chosen
            .iter()
            .map(|&i| format!("`{}`", self.planner.knowledge.archetypes[i].name))
            .collect::<Vec<_>>()
            .join(" and ")
    }

    /// An archetype the prompt names by a phrase at least as long as the place phrase found
    /// (`place_len`, when one was); two named equally strongly blend.
    fn named(&self, place_len: Option<usize>) -> Option<Choice> {
        let scenes = &self.analysis.scenes;
        let best = scenes
            .first()
            .filter(|best| best.phrase)
            .filter(|best| place_len.is_none_or(|len| len <= best.phrase_len))?;
        let ties = scenes
            .iter()
            .take_while(|m| (m.score - best.score).abs() < 1e-9)
            .count();
        // Two archetypes named equally strongly ("an alchemy workshop") blend.
        let rival = scenes
            .get(1)
            .is_some_and(|m| m.phrase && m.phrase_len == best.phrase_len);
        if ties == 1 && !rival {
            return Some(Choice {
                archetypes: self.by_index(&[best.archetype]),
                blended: false,
                assumption: None,
            });
        }
        let mut chosen: Vec<usize> = scenes.iter().take(2).map(|m| m.archetype).collect();
        chosen.dedup();
        Some(Choice {
            assumption: Some(format!(
                "the prompt names {} equally; blended them",
                self.names(&chosen)
            )),
            archetypes: self.by_index(&chosen),
            blended: true,
        })
    }

    /// The generic room of the family whose head noun is `word`.
    fn family_room(&self, (family, word, archetype): (&Family, &str, Archetype)) -> Choice {
        Choice {
            assumption: Some(format!(
                "\"{word}\" is a {} place; assumed the family's generic room (`{}`)",
                family.name, family.room
            )),
            archetypes: vec![archetype],
            blended: !self.analysis.mentions.is_empty(),
        }
    }

    /// The two archetypes sharing most of the prompt's words, blended.
    fn sharing_words(&self) -> Option<Choice> {
        let scenes = &self.analysis.scenes;
        if scenes.is_empty() {
            return None;
        }
        let mut chosen: Vec<usize> = scenes.iter().take(2).map(|m| m.archetype).collect();
        chosen.dedup();
        Some(Choice {
            assumption: Some(format!(
                "no known scene type is named; blended {}, which share the prompt's words",
                self.names(&chosen)
            )),
            archetypes: self.by_index(&chosen),
            blended: true,
        })
    }

    /// No scene words: the two archetypes holding most of the mentioned categories (anchored
    /// on one of them first), blended.
    fn holding_mentions(&self) -> Option<Choice> {
        let mentioned: BTreeSet<&str> = self
            .analysis
            .mentions
            .iter()
            .filter(|m| m.count > 0)
            .map(|m| m.category.as_str())
            .collect();
        if mentioned.is_empty() {
            return None;
        }
        let mut ranked: Vec<(usize, usize)> = self
            .planner
            .knowledge
            .archetypes
            .iter()
            .enumerate()
            .map(|(i, a)| {
                let held = a
                    .objects
                    .iter()
                    .filter(|g| mentioned.contains(g.category.as_str()))
                    .map(|g| &g.category)
                    .collect::<BTreeSet<_>>()
                    .len();
                // An archetype anchored on a mentioned object fits best.
                let anchored = held > 0 && mentioned.contains(a.anchor.as_str());
                (2 * held + usize::from(anchored), i)
            })
            .filter(|(n, _)| *n > 0)
            .collect();
        ranked.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
        if ranked.is_empty() {
            return None;
        }
        let chosen: Vec<usize> = ranked.iter().take(2).map(|r| r.1).collect();
        Some(Choice {
            assumption: Some(format!(
                "no scene type is named; chose {}, which hold the objects the prompt names",
                self.names(&chosen)
            )),
            archetypes: self.by_index(&chosen),
            blended: true,
        })
    }

    /// The knowledge's default archetype, as a generic room.
    fn default_room(&self) -> Choice {
        let knowledge = &self.planner.knowledge;
        let default = knowledge
            .archetype(&knowledge.vocabulary.default_archetype)
            .or(knowledge.archetypes.first());
        let why = if self.analysis.scene_words || !self.analysis.mentions.is_empty() {
            "no scene type is named"
        } else {
            "no word of the prompt names a place, an object or a setting the planner knows"
        };
        Choice {
            assumption: Some(format!(
                "{why}; assumed a generic room (`{}`)",
                default.map_or("", |a| a.name.as_str())
            )),
            archetypes: default.cloned().into_iter().collect(),
            blended: !self.analysis.mentions.is_empty(),
        }
    }
}
