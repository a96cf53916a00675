//! The words of a prompt that name its place, and which of them lead.
//!
//! "a cozy music practice room with a piano" names its place in "cozy music practice room":
//! the phrase runs from the start to the first word that turns to contents ("with", a comma,
//! …). Its head noun is the last word, "room". "room" names no kind of place by itself, so the
//! words before it say what kind; a head like "cinema" or "kitchen" says it alone, and the
//! words before it only modify it ("home cinema"). A reading rests on the head: a word that
//! only modifies ("practice") never decides the place on its own.

use std::ops::Range;

use crate::knowledge::{Knowledge, Vocabulary};
use crate::places::Thesaurus;

/// The phrase of a prompt that names its place.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct PlacePhrase {
    /// Token range of the whole phrase (articles and counts included).
    pub span: Range<usize>,
    /// Token range that decides the place: the head noun alone, or the head noun and every
    /// word before it in the phrase when the head is generic ("music practice room").
    pub head: Range<usize>,
    /// Index of the head noun.
    pub head_word: usize,
    /// Whether the head noun names no kind of place by itself ("room", "space").
    pub generic: bool,
    /// Token range of the head's complement after "of" ("the keep *of the goblin king*"),
    /// empty when there is none.
    pub complement: Range<usize>,
    /// Token range of the setting after the phrase ("a bar *in a hotel*", "a classroom *for
    /// toddlers*"): the words up to the next clause break or phrase end, empty when there is
    /// none.
    pub setting: Range<usize>,
}

impl PlacePhrase {
    /// Reads the place phrase of `stems` (one entry per token, `None` for a clause break), or
    /// `None` when no word before the first clause break carries meaning.
    pub(super) fn read(stems: &[Option<&str>], voc: &Vocabulary) -> Option<PlacePhrase> {
        // A sparse word ("a *sparsely* furnished office") says how full the place is, not
        // what it is: it is never the head.
        let content = |w: &str| {
            !voc.filler.contains(w) && !voc.counts.contains_key(w) && !voc.sparse.contains_key(w)
        };
        let mut end = 0;
        let mut head = None;
        let mut of = None;
        for (i, stem) in stems.iter().enumerate() {
            let Some(w) = stem else { break };
            if head.is_some() && voc.phrase_ends.contains(*w) {
                break;
            }
            end = i + 1;
            if *w == "of" && head.is_some() && of.is_none() {
                of = Some(i);
            } else if content(w) && of.is_none() {
                head = Some(i);
            }
        }
        let head_word = head?;
        let generic = stems[head_word].is_some_and(|w| voc.generic_heads.contains(w));
        let first = if generic { 0 } else { head_word };
        Some(PlacePhrase {
            span: 0..end,
            head: first..head_word + 1,
            head_word,
            generic,
            complement: of.map_or(end..end, |o| o + 1..end),
            setting: setting_after(stems, end, voc),
        })
    }

    /// Whether the token range `start..start + len` reaches into the head.
    pub(super) fn covers_head(&self, start: usize, len: usize) -> bool {
        start < self.head.end && self.head.start < start + len
    }

    /// Whether the token range `start..start + len` lies inside the phrase.
    pub(super) fn holds(&self, start: usize, len: usize) -> bool {
        start >= self.span.start && start + len <= self.span.end
    }
}

/// The words that set a phrase ending at `end` in a larger place: after "in", "at", "for",
/// "inside" or "of", up to the next clause break or phrase end.
fn setting_after(stems: &[Option<&str>], end: usize, voc: &Vocabulary) -> Range<usize> {
    const SETTING: [&str; 5] = ["in", "at", "for", "inside", "of"];
    if !stems
        .get(end)
        .copied()
        .flatten()
        .is_some_and(|w| SETTING.contains(&w))
    {
        return end..end;
    }
    let start = end + 1;
    let mut stop = start;
    while let Some(Some(w)) = stems.get(stop) {
        if stop > start && voc.phrase_ends.contains(*w) {
            break;
        }
        stop += 1;
    }
    start..stop
}

/// The words of a compound read from a setting: the setting's meaningful words, then the
/// head's ("a bar in a hotel" → "hotel bar", "a classroom for toddlers" → "toddler
/// classroom"), with the index of the head's first word; `None` without a setting.
pub(super) fn setting_compound<'a>(
    stems: &[Option<&'a str>],
    phrase: &PlacePhrase,
    voc: &Vocabulary,
) -> Option<(Vec<Option<&'a str>>, usize)> {
    let content = |w: &&&str| !voc.filler.contains(**w) && !voc.counts.contains_key(**w);
    let setting: Vec<Option<&str>> = stems[phrase.setting.clone()]
        .iter()
        .flatten()
        .filter(content)
        .map(|w| Some(*w))
        .collect();
    if setting.is_empty() {
        return None;
    }
    let junction = setting.len();
    let head = stems[phrase.head.clone()].iter().flatten().filter(content);
    let words = setting.into_iter().chain(head.map(|w| Some(*w))).collect();
    Some((words, junction))
}

/// What a whole phrase of the knowledge names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum Named {
    /// An archetype, by index into `Knowledge::archetypes`.
    Archetype(usize),
    /// A place of the thesaurus, by index into `Thesaurus::places`.
    Place(usize),
}

/// A whole phrase of an archetype or a place, found in the prompt.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct PhraseHit {
    /// What the phrase names.
    pub named: Named,
    /// Index of its first token.
    pub start: usize,
    /// Its token count, from its first word to its last (other words between included when
    /// it is `spread`).
    pub len: usize,
    /// The phrase's own word count: `len` unless other words stand between its words.
    pub words: usize,
    /// Whether other words of the prompt stand between the phrase's words ("a *radio*
    /// station *studio*").
    pub spread: bool,
}

/// Every whole phrase of an archetype or a place in `stems`.
pub(super) fn phrase_hits(
    stems: &[Option<&str>],
    knowledge: &Knowledge,
    thesaurus: &Thesaurus,
) -> Vec<PhraseHit> {
    let archetypes = knowledge
        .archetypes
        .iter()
        .enumerate()
        .map(|(i, a)| (Named::Archetype(i), &a.phrases));
    let places = thesaurus
        .places
        .iter()
        .enumerate()
        .map(|(i, p)| (Named::Place(i), &p.phrases));
    let mut hits = Vec::new();
    for (named, phrases) in archetypes.chain(places) {
        for phrase in phrases {
            for start in 0..stems.len() {
                if spells(stems, start, phrase) {
                    hits.push(PhraseHit {
                        named,
                        start,
                        len: phrase.len(),
                        words: phrase.len(),
                        spread: false,
                    });
                }
            }
        }
    }
    hits
}

/// Every phrase of an archetype or a place that the head noun of `place` ends and whose other
/// words its modifiers spell in order with other words between them: "a *radio* station
/// *studio*" names the radio studio (a recording studio), not the art studio that "studio"
/// alone names. A modifier that names one kind of a head many places share decides which.
/// Each phrase is matched to the modifiers nearest the head.
pub(super) fn spread_hits(
    stems: &[Option<&str>],
    place: &PlacePhrase,
    knowledge: &Knowledge,
    thesaurus: &Thesaurus,
) -> Vec<PhraseHit> {
    let head = place.head_word;
    let Some(head_stem) = stems[head] else {
        return Vec::new();
    };
    let archetypes =
        (knowledge.archetypes.iter().enumerate()).map(|(i, a)| (Named::Archetype(i), &a.phrases));
    let places = (thesaurus.places.iter().enumerate()).map(|(i, p)| (Named::Place(i), &p.phrases));
    let mut hits = Vec::new();
    for (named, phrases) in archetypes.chain(places) {
        for phrase in phrases.iter().filter(|p| p.len() >= 2) {
            let Some((last, modifiers)) = phrase.split_last() else {
                continue;
            };
            if last != head_stem {
                continue;
            }
            // The modifiers from the last back, each at the nearest place before the next.
            let mut end = head;
            let mut start = Some(head);
            for m in modifiers.iter().rev() {
                start = (place.span.start..end)
                    .rev()
                    .find(|&i| stems[i] == Some(m.as_str()));
                match start {
                    Some(i) => end = i,
                    None => break,
                }
            }
            if let Some(start) = start.filter(|&s| head + 1 - s > phrase.len()) {
                hits.push(PhraseHit {
                    named,
                    start,
                    len: head + 1 - start,
                    words: phrase.len(),
                    spread: true,
                });
            }
        }
    }
    hits
}

/// Whether the stems from `start` on spell `phrase`.
fn spells(stems: &[Option<&str>], start: usize, phrase: &[String]) -> bool {
    !phrase.is_empty()
        && phrase.len() <= stems.len() - start
        && phrase
            .iter()
            .enumerate()
            .all(|(k, w)| stems[start + k] == Some(w.as_str()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::text::tokenize;

    fn phrase(prompt: &str) -> Option<(String, String, bool)> {
        let voc = &Knowledge::builtin().vocabulary;
        let tokens = tokenize(prompt);
        let stems: Vec<Option<&str>> = tokens.iter().map(|t| t.stem()).collect();
        let p = PlacePhrase::read(&stems, voc)?;
        let words = |r: Range<usize>| {
            stems[r]
                .iter()
                .flatten()
                .copied()
                .collect::<Vec<_>>()
                .join(" ")
        };
        Some((words(p.span.clone()), words(p.head.clone()), p.generic))
    }

    #[test]
    fn the_head_is_the_last_word_before_the_contents() {
        assert_eq!(
            phrase("a cozy music practice room with a piano"),
            Some((
                "a cozy music practice room".into(),
                "a cozy music practice room".into(),
                true
            ))
        );
        assert_eq!(
            phrase("a home cinema, big screen"),
            Some(("a home cinema".into(), "cinema".into(), false))
        );
        assert_eq!(
            phrase("a kitchen in a castle"),
            Some(("a kitchen".into(), "kitchen".into(), false))
        );
        assert_eq!(
            phrase("a gloomy keep of the goblin king"),
            Some((
                "a gloomy keep of the goblin king".into(),
                "keep".into(),
                false
            ))
        );
        let voc = &Knowledge::builtin().vocabulary;
        let tokens = tokenize("a bar in a small hotel, warm light");
        let stems: Vec<Option<&str>> = tokens.iter().map(|t| t.stem()).collect();
        let p = PlacePhrase::read(&stems, voc).unwrap();
        assert_eq!(
            setting_compound(&stems, &p, voc),
            Some((vec![Some("small"), Some("hotel"), Some("bar")], 2))
        );
        assert_eq!(
            phrase("with a sofa"),
            Some(("with a sofa".into(), "sofa".into(), false))
        );
    }
}
