//! Phase 1, interpret: read the prompt and choose the archetypes the scene draws on.
//!
//! No non-empty prompt is refused. The place is read from the prompt's place phrase and its
//! head noun ([`super::head`]), in order, from: an archetype or a place of the thesaurus
//! (`knowledge/places.toml`: "a pharmacy" is a shop selling medicine) whose phrase is on the
//! head (then the longest; an archetype named as the head's modifier blends in: "an alchemy
//! workshop"; a modifier that spells a phrase with the head across other words names one
//! kind of a head many places share: "a *radio* station *studio*" is a radio studio), or
//! elsewhere in the place phrase when the head is a noun we do not know, or
//! after the contents ("chairs and a table in a kitchen"); the generic room of the head
//! noun's place family ("a haunted castle" → fantasy); archetypes sharing the head's words;
//! the archetypes holding the objects the prompt names; the default archetype. A word that
//! only modifies a known head never decides ("a music *practice* room" is not an office).
//! Every reading carries a confidence ([`PlaceReading`]); everything but a named archetype
//! is also recorded as an assumption of the plan.

use std::collections::BTreeSet;

use crate::knowledge::{Archetype, Sparsity, Vocabulary};
use crate::places::Family;
use crate::plan::{cut_prompt, PlaceReading, PlanError, PlanRequest, ReadingSource};
use crate::prompt::{analyze, Analysis};
use crate::text::tokenize;

use super::head::{phrase_hits, setting_compound, spread_hits, Named, PhraseHit, PlacePhrase};
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
    /// The place read, how sure the reading is and why.
    pub place: PlaceReading,
    /// Whether the second archetype is named by a modifier of the head ("an *alchemy*
    /// workshop"): its anchor then belongs in the scene too.
    pub modifier_blend: bool,
    /// How sparse the place phrase asks the room to be ("a *minimalist* bedroom"), with the
    /// word that asks; `None` for a room as full as lived-in rooms.
    pub sparsity: Option<(Sparsity, String)>,
}

/// Which tokens of `prompt` name its place (not read as objects: "a *fire station*" holds no
/// campfire), as [`interpret`] reads them.
pub(super) fn naming_tokens(planner: &KnowledgePlanner, prompt: &str) -> Vec<bool> {
    let tokens = tokenize(prompt);
    let stems: Vec<Option<&str>> = tokens.iter().map(|t| t.stem()).collect();
    let phrase = PlacePhrase::read(&stems, &planner.knowledge.vocabulary);
    let hits = place_hits(planner, &stems, phrase.as_ref());
    let no_analysis = Analysis::default();
    let namer = Chooser {
        planner,
        analysis: &no_analysis,
        stems: &stems,
        phrase: phrase.as_ref(),
    };
    namer.naming_tokens(&hits)
}

/// Every phrase of an archetype or a place in `stems`: whole ones, and those the place
/// phrase's modifiers spell with its head across other words ([`spread_hits`]).
fn place_hits(
    planner: &KnowledgePlanner,
    stems: &[Option<&str>],
    phrase: Option<&PlacePhrase>,
) -> Vec<PhraseHit> {
    let (knowledge, thesaurus) = (&planner.knowledge, &planner.thesaurus);
    let mut hits = phrase_hits(stems, knowledge, thesaurus);
    if let Some(phrase) = phrase {
        hits.extend(spread_hits(stems, phrase, knowledge, thesaurus));
    }
    hits
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
    let tokens = tokenize(prompt);
    let stems: Vec<Option<&str>> = tokens.iter().map(|t| t.stem()).collect();
    let phrase = PlacePhrase::read(&stems, &knowledge.vocabulary);
    let hits = place_hits(planner, &stems, phrase.as_ref());
    let no_analysis = Analysis::default();
    let namer = Chooser {
        planner,
        analysis: &no_analysis,
        stems: &stems,
        phrase: phrase.as_ref(),
    };
    let naming = namer.naming_tokens(&hits);
    let analysis = analyze(
        prompt,
        knowledge,
        &planner.thesaurus.nouns,
        &request.available_categories,
        &naming,
    );
    let chooser = Chooser {
        analysis: &analysis,
        ..namer
    };
    let choice = choose_archetypes(&chooser, &hits);
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
    let place = PlaceReading {
        place: choice.archetypes[0].name.clone(),
        confidence: (choice.confidence * 100.0).round() / 100.0,
        basis: choice.basis,
        source: ReadingSource::Knowledge,
    };
    let sparsity = phrase
        .as_ref()
        .and_then(|p| sparsity_of(&stems[p.span.clone()], &knowledge.vocabulary));
    let mut assumptions: Vec<String> = choice.assumption.into_iter().collect();
    if let Some((level, word)) = &sparsity {
        assumptions.push(format!(
            "\"{word}\" asks for a sparse room: {}",
            level.keeps()
        ));
    }
    Ok(Reading {
        prompt: prompt.to_owned(),
        analysis,
        archetypes: choice.archetypes,
        scene_type,
        assumptions,
        limits,
        place,
        modifier_blend: choice.modifier_blend,
        sparsity,
    })
}

/// The sparsest level a sparse word of the place phrase (`stems`) asks for, with its word.
fn sparsity_of(stems: &[Option<&str>], voc: &Vocabulary) -> Option<(Sparsity, String)> {
    stems
        .iter()
        .flatten()
        .filter_map(|w| voc.sparse.get(*w).map(|level| (*level, (*w).to_owned())))
        .max_by_key(|(level, _)| *level)
}

/// The archetypes chosen for a prompt, how sure the choice is and why.
struct Choice {
    archetypes: Vec<Archetype>,
    blended: bool,
    assumption: Option<String>,
    /// From 0 (a guess) to 1 (the prompt names the place).
    confidence: f64,
    /// What the choice rests on, in words.
    basis: String,
    /// Whether a modifier of the head names the second archetype.
    modifier_blend: bool,
}

/// How sure a reading is when the prompt's head names the place outright.
const NAMED: f64 = 0.95;
/// … when a modifier and the head spell its phrase with other words between ("a *radio*
/// station *studio*": a radio studio).
const NAMED_ACROSS_WORDS: f64 = 0.85;
/// … when a compound of the setting and the head names it ("a bar in a hotel": a hotel bar).
const NAMED_IN_SETTING: f64 = 0.9;
/// … when a generic head's modifier names it ("a *music* practice room").
const NAMED_BY_MODIFIER: f64 = 0.75;
/// … when the head modifies a place the prompt also names ("an *alchemy* workshop").
const NAMED_AND_BLENDED: f64 = 0.8;
/// … when a word of the place phrase names it but the head is a noun we do not know.
const NAMED_BESIDE_HEAD: f64 = 0.65;
/// … when the prompt names the place after its contents ("chairs and a table in a kitchen").
const NAMED_LATER: f64 = 0.7;
/// … when only the head noun's family is known ("a haunted castle" → fantasy).
const FAMILY_HEAD: f64 = 0.45;
/// … when only a word after the head's "of" has a family ("the keep of the *goblin* king").
const FAMILY_CONTEXT: f64 = 0.35;
/// … when archetypes share the words of the head but none is named.
const SHARED_HEAD_WORDS: f64 = 0.5;
/// … when nothing names a place (plus up to 0.3 for the share of objects held).
const HOLDING_MENTIONS: f64 = 0.3;
/// … for the default room.
const DEFAULT_ROOM: f64 = 0.1;

/// The archetypes best matching the analysis (best first), whether they blend, and what was
/// assumed: the sources of the module's list, tried in order.
fn choose_archetypes(chooser: &Chooser<'_>, hits: &[PhraseHit]) -> Choice {
    if let Some(choice) = chooser.named(hits) {
        return choice;
    }
    let family = chooser.head_family();
    // A family's head noun ("a city bus") tells more than a word shared with an archetype
    // phrase ("city park"), unless the prompt names objects.
    if chooser.analysis.mentions.is_empty() {
        if let Some(f) = family.clone().filter(|f| f.on_head) {
            return chooser.family_room(f);
        }
    }
    chooser
        .sharing_head_words()
        .or_else(|| chooser.holding_mentions())
        .or_else(|| family.map(|f| chooser.family_room(f)))
        .unwrap_or_else(|| chooser.default_room())
}

/// "a" or "an" before `word`.
fn article(word: &str) -> &'static str {
    if word.starts_with(['a', 'e', 'i', 'o', 'u']) {
        "an"
    } else {
        "a"
    }
}

/// A place family found through a word of the place phrase.
#[derive(Clone)]
struct FamilyHit<'a> {
    family: &'a Family,
    /// The word, as a stem.
    word: String,
    /// The family's generic room.
    room: Archetype,
    /// Whether the word is the head noun (else it is in the head's complement).
    on_head: bool,
}

/// How a whole phrase of the knowledge stands to the prompt's place phrase.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Standing {
    /// After the place phrase, among the contents.
    Later,
    /// In the place phrase, beside a head noun we do not know.
    BesideHead,
    /// On the head.
    Head,
}

/// The planner's knowledge and the prompt's analysis, asked in turn by each source of a
/// [`Choice`].
struct Chooser<'a> {
    planner: &'a KnowledgePlanner,
    analysis: &'a Analysis,
    stems: &'a [Option<&'a str>],
    phrase: Option<&'a PlacePhrase>,
}

impl Chooser<'_> {
    /// The (at most) two archetypes of highest positive `score`, best first (ties in file
    /// order).
    fn best_two(&self, score: impl Fn(&Archetype) -> usize) -> Vec<usize> {
        let mut ranked: Vec<(usize, usize)> = self
            .planner
            .knowledge
            .archetypes
            .iter()
            .enumerate()
            .map(|(i, a)| (score(a), i))
            .filter(|(n, _)| *n > 0)
            .collect();
        ranked.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
        ranked.iter().take(2).map(|r| r.1).collect()
    }

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

    /// The prompt's words in `range`, joined.
    fn words(&self, range: std::ops::Range<usize>) -> String {
        self.stems[range]
            .iter()
            .flatten()
            .copied()
            .collect::<Vec<_>>()
            .join(" ")
    }

    /// Where `hit` stands, or `None` when it cannot name the place: a word of the contents
    /// that names an object ("a room with a *piano*") names no place.
    fn standing(&self, hit: &PhraseHit) -> Option<Standing> {
        let phrase = self.phrase?;
        if phrase.covers_head(hit.start, hit.len) {
            return Some(Standing::Head);
        }
        if phrase.holds(hit.start, hit.len) {
            return Some(Standing::BesideHead);
        }
        let words = self.words(hit.start..hit.start + hit.len);
        let object = self.planner.knowledge.category_of_phrase(&words).is_some();
        (hit.start >= phrase.span.end && !object).then_some(Standing::Later)
    }

    /// The place a whole phrase of the prompt names: the phrase on the head first, then the
    /// longest, an archetype before a place of equal length. A second archetype named as a
    /// modifier of the head ("an *alchemy* workshop") blends in.
    fn named(&self, hits: &[PhraseHit]) -> Option<Choice> {
        if let Some((hit, words)) = self.setting_hit() {
            return self.named_choice(hit.named, words, NAMED_IN_SETTING, None);
        }
        let (standing, best) = self.best_hit(hits)?;
        if let Some(special) = self.specialized(hits, standing, &best) {
            let words = self.words(special.start..special.start + special.len);
            return self.named_choice(special.named, words, NAMED, None);
        }
        let words = self.words(best.start..best.start + best.len);
        let confidence = match standing {
            Standing::Head => {
                let phrase = self.phrase?;
                let on_head_word =
                    best.start <= phrase.head_word && phrase.head_word < best.start + best.len;
                if best.spread {
                    NAMED_ACROSS_WORDS
                } else if on_head_word {
                    NAMED
                } else {
                    NAMED_BY_MODIFIER
                }
            }
            Standing::BesideHead => NAMED_BESIDE_HEAD,
            Standing::Later => NAMED_LATER,
        };
        let modifier = (standing == Standing::Head)
            .then(|| self.modifier_archetype(hits, &best))
            .flatten();
        self.named_choice(best.named, words, confidence, modifier)
    }

    /// The choice of the place `named` names (by the prompt's `words`), sure to `confidence`,
    /// blended with the archetype `modifier` names.
    fn named_choice(
        &self,
        named: Named,
        words: String,
        confidence: f64,
        modifier: Option<usize>,
    ) -> Option<Choice> {
        let i = match named {
            Named::Archetype(i) => i,
            Named::Place(p) => return self.place_choice(p, words, confidence),
        };
        let chosen: Vec<usize> = std::iter::once(i).chain(modifier).collect();
        let blend = chosen.len() > 1;
        Some(Choice {
            assumption: blend.then(|| {
                format!(
                    "the prompt names {} together; blended them",
                    self.names(&chosen)
                )
            }),
            archetypes: self.by_index(&chosen),
            blended: blend,
            confidence: if blend { NAMED_AND_BLENDED } else { confidence },
            basis: format!("\"{words}\" names {}", self.names(&chosen[..1])),
            modifier_blend: blend,
        })
    }

    /// The choice of place `p` of the thesaurus.
    fn place_choice(&self, p: usize, words: String, confidence: f64) -> Option<Choice> {
        let place = &self.planner.thesaurus.places[p];
        let archetype = self
            .planner
            .thesaurus
            .archetype(&place.name, &self.planner.knowledge)?;
        let name = place.name.replace('_', " ");
        let assumption = format!(
            "read as {} {name}: {} (like `{}`, family {})",
            article(&name),
            place.gloss,
            place.like,
            place.family
        );
        Some(Choice {
            archetypes: vec![archetype],
            blended: false,
            assumption: Some(assumption),
            confidence,
            basis: format!("\"{words}\" names the place `{}`", place.name),
            modifier_blend: false,
        })
    }

    /// The place a compound of the setting and the head names ("a bar in a hotel" → "hotel
    /// bar"), with the compound's words: a phrase across the setting's last word and the
    /// head's first.
    fn setting_hit(&self) -> Option<(PhraseHit, String)> {
        let phrase = self.phrase?;
        let knowledge = &self.planner.knowledge;
        let (compound, junction) = setting_compound(self.stems, phrase, &knowledge.vocabulary)?;
        let hit = phrase_hits(&compound, knowledge, &self.planner.thesaurus)
            .into_iter()
            .filter(|h| h.start < junction && junction < h.start + h.len)
            .max_by_key(|h| (h.len, matches!(h.named, Named::Archetype(_))))?;
        let words = compound[hit.start..hit.start + hit.len]
            .iter()
            .flatten()
            .copied()
            .collect::<Vec<_>>()
            .join(" ");
        Some((hit, words))
    }

    /// A place of the thesaurus named beside the head that is a kind of what the head names
    /// ("a *ski lodge* lounge": a ski lodge is a kind of living room, which "lounge" names).
    fn specialized(
        &self,
        hits: &[PhraseHit],
        standing: Standing,
        best: &PhraseHit,
    ) -> Option<PhraseHit> {
        let phrase = self.phrase?;
        let thesaurus = &self.planner.thesaurus;
        let base = match best.named {
            Named::Archetype(i) => &self.planner.knowledge.archetypes[i].name,
            Named::Place(p) => &thesaurus.places[p].name,
        };
        let kind_of_base = |p: usize| {
            let mut like = &thesaurus.places[p].like;
            for _ in 0..8 {
                if like == base {
                    return true;
                }
                match thesaurus.place(like) {
                    Some(next) => like = &next.like,
                    None => return false,
                }
            }
            false
        };
        (standing == Standing::Head)
            .then(|| {
                hits.iter()
                    .filter(|h| phrase.holds(h.start, h.len))
                    .filter(|h| h.start + h.len <= best.start || h.start >= best.start + best.len)
                    .filter(|h| matches!(h.named, Named::Place(p) if kind_of_base(p)))
                    .max_by_key(|h| (h.words, !h.spread))
                    .copied()
            })
            .flatten()
    }

    /// The whole phrase that names the place, with where it stands: the phrase on the head
    /// first, then the longest (by its own words; of equal length, one whose words stand
    /// together before one spread across other words), an archetype before a place of equal
    /// length.
    fn best_hit(&self, hits: &[PhraseHit]) -> Option<(Standing, PhraseHit)> {
        // A phrase beside the head counts only when the head is a noun we do not know.
        let head_known = hits
            .iter()
            .any(|o| self.standing(o) == Some(Standing::Head));
        hits.iter()
            .filter_map(|h| {
                let standing = self.standing(h)?;
                if standing == Standing::BesideHead && head_known {
                    return None;
                }
                let archetype = matches!(h.named, Named::Archetype(_));
                let key = (standing, h.words, !h.spread, archetype);
                Some(((key, std::cmp::Reverse(h.start)), *h))
            })
            .max_by_key(|(k, _)| *k)
            .map(|(k, h)| (k.0 .0, h))
    }

    /// Which tokens name the place (the best phrase and a blended modifier's): they are not
    /// read as objects ("a *fire station*" holds no campfire). All `false` when no phrase
    /// names the place.
    fn naming_tokens(&self, hits: &[PhraseHit]) -> Vec<bool> {
        let mut naming = vec![false; self.stems.len()];
        if let (Some(phrase), Some(_)) = (self.phrase, self.setting_hit()) {
            naming[phrase.head.clone()].fill(true);
            naming[phrase.setting.clone()].fill(true);
            return naming;
        }
        if let Some((standing, best)) = self.best_hit(hits) {
            let modifier = (standing == Standing::Head
                && matches!(best.named, Named::Archetype(_)))
            .then(|| self.modifier_hit(hits, &best))
            .flatten();
            for h in std::iter::once(best).chain(modifier) {
                naming[h.start..h.start + h.len].fill(true);
            }
        }
        naming
    }

    /// Another archetype whose phrase sits in the place phrase apart from `best`'s.
    fn modifier_archetype(&self, hits: &[PhraseHit], best: &PhraseHit) -> Option<usize> {
        match self.modifier_hit(hits, best)?.named {
            Named::Archetype(i) => Some(i),
            Named::Place(_) => None,
        }
    }

    /// The longest phrase of another archetype in the place phrase apart from `best`'s.
    fn modifier_hit(&self, hits: &[PhraseHit], best: &PhraseHit) -> Option<PhraseHit> {
        let phrase = self.phrase?;
        hits.iter()
            .filter(|h| phrase.holds(h.start, h.len))
            .filter(|h| h.start + h.len <= best.start || h.start >= best.start + best.len)
            .filter(|h| matches!(h.named, Named::Archetype(_)) && h.named != best.named)
            .max_by_key(|h| (h.words, !h.spread, std::cmp::Reverse(h.named)))
            .copied()
    }

    /// The family whose word is the head noun ("a haunted *castle*"), else the last word of
    /// the head's complement ("the keep of the *goblin* king"), with that word, the family's
    /// generic room and whether the word was the head. A word that only modifies the head
    /// ("a music *practice* room") never counts.
    fn head_family(&self) -> Option<FamilyHit<'_>> {
        let phrase = self.phrase?;
        let thesaurus = &self.planner.thesaurus;
        let words = std::iter::once(phrase.head_word).chain(phrase.complement.clone().rev());
        let (i, word, family) =
            words
                .filter_map(|i| Some((i, self.stems[i]?)))
                .find_map(|(i, w)| {
                    let f = thesaurus.families.iter().find(|f| f.words.contains(w))?;
                    Some((i, w, f))
                })?;
        let room = thesaurus.archetype(&family.room, &self.planner.knowledge)?;
        Some(FamilyHit {
            family,
            word: word.to_owned(),
            room,
            on_head: i == phrase.head_word,
        })
    }

    /// The generic room of the family of `hit`'s word.
    fn family_room(&self, hit: FamilyHit<'_>) -> Choice {
        let FamilyHit {
            family,
            word,
            room,
            on_head,
        } = hit;
        let held = !self.analysis.mentions.is_empty();
        let (confidence, role) = if on_head {
            (FAMILY_HEAD, "the head noun")
        } else {
            (FAMILY_CONTEXT, "a word after the head's \"of\"")
        };
        Choice {
            assumption: Some(format!(
                "\"{word}\" is a {} place; assumed the family's generic room (`{}`)",
                family.name, family.room
            )),
            archetypes: vec![room],
            blended: held,
            confidence,
            basis: format!(
                "no place is named; only {role} \"{word}\" is known, as a {} place",
                family.name
            ),
            modifier_blend: false,
        }
    }

    /// The two archetypes sharing most of the head's words, blended ("a *music* practice
    /// room"); words that only modify a known head never count.
    fn sharing_head_words(&self) -> Option<Choice> {
        let phrase = self.phrase?;
        let voc = &self.planner.knowledge.vocabulary;
        let head: Vec<&str> = self.stems[phrase.head.clone()]
            .iter()
            .flatten()
            .copied()
            .filter(|w| !voc.filler.contains(*w) && !voc.generic_heads.contains(*w))
            .collect();
        let chosen = self.best_two(|a| {
            head.iter()
                .filter(|w| a.phrases.iter().flatten().any(|p| p == *w))
                .count()
        });
        let first = *chosen.first()?;
        let shared: Vec<&str> = head
            .iter()
            .copied()
            .filter(|w| {
                self.planner.knowledge.archetypes[first]
                    .phrases
                    .iter()
                    .flatten()
                    .any(|p| p == w)
            })
            .collect();
        Some(Choice {
            assumption: Some(format!(
                "no known scene type is named; blended {}, which share the prompt's words",
                self.names(&chosen)
            )),
            archetypes: self.by_index(&chosen),
            blended: true,
            confidence: SHARED_HEAD_WORDS,
            basis: format!(
                "no place is named; \"{}\" is a word of {}",
                shared.join(" "),
                self.names(&chosen[..1])
            ),
            modifier_blend: false,
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
        let chosen = self.best_two(|a| {
            let held = a
                .objects
                .iter()
                .filter(|g| mentioned.contains(g.category.as_str()))
                .map(|g| &g.category)
                .collect::<BTreeSet<_>>()
                .len();
            // An archetype anchored on a mentioned object fits best.
            let anchored = held > 0 && mentioned.contains(a.anchor.as_str());
            2 * held + usize::from(anchored)
        });
        if chosen.is_empty() {
            return None;
        }
        let held = self.planner.knowledge.archetypes[chosen[0]]
            .objects
            .iter()
            .filter(|g| mentioned.contains(g.category.as_str()))
            .map(|g| g.category.as_str())
            .collect::<BTreeSet<_>>();
        let share = held.len() as f64 / mentioned.len() as f64;
        Some(Choice {
            assumption: Some(format!(
                "no scene type is named; chose {}, which hold the objects the prompt names",
                self.names(&chosen)
            )),
            archetypes: self.by_index(&chosen),
            blended: true,
            confidence: HOLDING_MENTIONS * (1.0 + share),
            basis: format!(
                "no place is named; {} holds {} of the {} objects named",
                self.names(&chosen[..1]),
                held.len(),
                mentioned.len()
            ),
            modifier_blend: false,
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
            confidence: DEFAULT_ROOM,
            basis: why.to_owned(),
            modifier_blend: false,
        }
    }
}
