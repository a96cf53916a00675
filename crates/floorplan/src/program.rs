//! House programs: which rooms (type and count) a dwelling is built with, from a dwelling kind
//! and the counts a caller names, or read from a prompt's words.

use std::collections::BTreeMap;

use scenethesis_words::{tokenize, words, Token};
use serde::{Deserialize, Serialize};

use crate::knowledge::Knowledge;

/// The most rooms of one type a program may hold.
pub const MAX_PER_TYPE: u32 = 10;
/// The most rooms a program may hold in all.
pub const MAX_ROOMS: u32 = 16;

/// A room type and how many rooms of it to build.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoomCount {
    /// The room type (a knowledge room type, e.g. `bedroom`).
    #[serde(rename = "type")]
    pub room_type: String,
    /// How many (at least 1).
    pub count: u32,
}

/// The rooms to build for one dwelling.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Program {
    /// The dwelling kind (a knowledge dwelling, e.g. `house`).
    pub kind: String,
    /// The rooms, in the knowledge's room order.
    pub rooms: Vec<RoomCount>,
}

/// A program that cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ProgramError {
    /// The dwelling kind is not in the knowledge.
    #[error("unknown dwelling kind `{kind}` (known: {known})")]
    UnknownKind {
        /// The kind asked for.
        kind: String,
        /// The known kinds.
        known: String,
    },
    /// A counted room type is not in the knowledge.
    #[error("unknown room type `{room_type}` (known: {known})")]
    UnknownRoomType {
        /// The type asked for.
        room_type: String,
        /// The known types.
        known: String,
    },
    /// Too many rooms.
    #[error("{what}: {count} rooms asked, at most {max}")]
    TooMany {
        /// Which count (`bedroom`, or `all rooms`).
        what: String,
        /// The count asked.
        count: u32,
        /// The limit.
        max: u32,
    },
}

impl Program {
    /// The program of a dwelling `kind` with the `counts` the caller names: a named count
    /// replaces the kind's default, and the kind's required rooms are always there (at least
    /// their required count). A count of 0 drops a default room that is not required.
    ///
    /// ```
    /// use scenethesis_floorplan::{Knowledge, Program};
    /// let k = Knowledge::builtin();
    /// let p = Program::new(k, "house", &[("bedroom", 3), ("bathroom", 2)]).unwrap();
    /// assert_eq!((p.count("bedroom"), p.count("bathroom"), p.count("kitchen")), (3, 2, 1));
    /// ```
    pub fn new(
        knowledge: &Knowledge,
        kind: &str,
        counts: &[(&str, u32)],
    ) -> Result<Program, ProgramError> {
        let dwelling = knowledge
            .dwelling(kind)
            .ok_or_else(|| ProgramError::UnknownKind {
                kind: kind.to_owned(),
                known: knowledge
                    .dwellings
                    .iter()
                    .map(|d| d.kind.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
            })?;
        let mut named: BTreeMap<&str, u32> = BTreeMap::new();
        for (room_type, count) in counts {
            if knowledge.room(room_type).is_none() {
                return Err(ProgramError::UnknownRoomType {
                    room_type: (*room_type).to_owned(),
                    known: knowledge.room_names(),
                });
            }
            check_limit(room_type, *count, MAX_PER_TYPE)?;
            named.insert(room_type, *count);
        }
        let rooms: Vec<RoomCount> = knowledge
            .rooms
            .iter()
            .map(|r| {
                let required = dwelling.required.get(&r.name).copied().unwrap_or(0);
                let wanted = named.get(r.name.as_str()).copied();
                let count = wanted.unwrap_or_else(|| dwelling.default_count(&r.name));
                RoomCount {
                    room_type: r.name.clone(),
                    count: count.max(required),
                }
            })
            .filter(|r| r.count > 0)
            .collect();
        let program = Program {
            kind: kind.to_owned(),
            rooms,
        };
        check_limit("all rooms", program.total(), MAX_ROOMS)?;
        Ok(program)
    }

    /// How many rooms of a type the program has.
    pub fn count(&self, room_type: &str) -> u32 {
        self.rooms
            .iter()
            .find(|r| r.room_type == room_type)
            .map_or(0, |r| r.count)
    }

    /// How many rooms in all.
    pub fn total(&self) -> u32 {
        self.rooms.iter().map(|r| r.count).sum()
    }

    /// Reads a prompt's dwelling phrase and room counts with the knowledge's words: "a
    /// two-bedroom apartment", "a family house with three bedrooms and two bathrooms", "an
    /// office suite with a meeting room, a kitchenette and four offices". Counts are number
    /// words (one to ten, "a", "single"), digits or a plural (at least two). Returns `None`
    /// when the text names no dwelling and fewer than two room types (a single-room prompt);
    /// with no dwelling but several room types, the kind that fits the named rooms best.
    /// Named counts above [`MAX_PER_TYPE`] are capped.
    ///
    /// ```
    /// use scenethesis_floorplan::{Knowledge, Program};
    /// let p = Program::from_words(Knowledge::builtin(), "a two-bedroom apartment").unwrap();
    /// assert_eq!((p.kind.as_str(), p.count("bedroom")), ("apartment", 2));
    /// assert!(Program::from_words(Knowledge::builtin(), "a cosy bedroom").is_none());
    /// ```
    pub fn from_words(knowledge: &Knowledge, text: &str) -> Option<Program> {
        let mentions = read_mentions(knowledge, &tokenize(text));
        let kind = mentions.iter().find_map(|m| match &m.target {
            Target::Dwelling(kind) => Some(kind.clone()),
            Target::Room(_) => None,
        });
        let mut counts: BTreeMap<String, Option<u32>> = BTreeMap::new();
        for m in &mentions {
            if let Target::Room(room_type) = &m.target {
                let entry = counts.entry(room_type.clone()).or_insert(Some(0));
                *entry = match (*entry, m.count) {
                    (Some(sum), Some(n)) => Some(sum + n),
                    _ => None,
                };
            }
        }
        let kind = match kind {
            Some(kind) => kind,
            None if counts.len() >= 2 => best_kind(knowledge, counts.keys())?,
            None => return None,
        };
        let dwelling = knowledge.dwelling(&kind)?;
        let named: Vec<(&str, u32)> = counts
            .iter()
            .map(|(t, n)| {
                let plural = dwelling.default_count(t).max(2);
                (t.as_str(), n.unwrap_or(plural).clamp(1, MAX_PER_TYPE))
            })
            .collect();
        Program::new(knowledge, &kind, &named).ok()
    }
}

fn check_limit(what: &str, count: u32, max: u32) -> Result<(), ProgramError> {
    if count > max {
        return Err(ProgramError::TooMany {
            what: what.to_owned(),
            count,
            max,
        });
    }
    Ok(())
}

/// The dwelling kind that mentions most of the named room types (the first on a tie).
fn best_kind<'a>(
    knowledge: &Knowledge,
    named: impl Iterator<Item = &'a String> + Clone,
) -> Option<String> {
    let score =
        |d: &crate::knowledge::DwellingKind| named.clone().filter(|t| d.mentions(t)).count();
    let best = knowledge.dwellings.iter().map(score).max()?;
    knowledge
        .dwellings
        .iter()
        .find(|d| score(d) == best)
        .map(|d| d.kind.clone())
}

/// What a phrase names.
#[derive(Debug, Clone, PartialEq)]
enum Target {
    Dwelling(String),
    Room(String),
}

/// One phrase found in the prompt, with its count (`None`: a plural without a number).
#[derive(Debug, Clone, PartialEq)]
struct Mention {
    target: Target,
    count: Option<u32>,
}

/// Words that may follow a room or dwelling phrase without making it a modifier of another
/// noun ("a kitchen table" names no kitchen).
const FOLLOWERS: &[&str] = &[
    "and",
    "with",
    "or",
    "in",
    "on",
    "at",
    "for",
    "of",
    "to",
    "that",
    "which",
    "where",
    "plus",
    "next",
    "off",
    "opening",
    "each",
    "by",
    "near",
    "beside",
    "facing",
    "having",
    "has",
    "have",
    "containing",
    "including",
    "is",
    "are",
    "a",
    "an",
    "the",
    "upstairs",
    "downstairs",
    "all",
    "both",
    "but",
    "as",
    "from",
    "into",
    "onto",
    "sharing",
    "connected",
    "overlooking",
];

/// Number words and what they count.
const NUMBERS: &[(&str, u32)] = &[
    ("a", 1),
    ("an", 1),
    ("one", 1),
    ("single", 1),
    ("two", 2),
    ("three", 3),
    ("four", 4),
    ("five", 5),
    ("six", 6),
    ("seven", 7),
    ("eight", 8),
    ("nine", 9),
    ("ten", 10),
];

fn number(word: &str) -> Option<u32> {
    NUMBERS
        .iter()
        .find(|(w, _)| *w == word)
        .map(|(_, n)| *n)
        .or_else(|| word.parse().ok())
}

/// Every phrase of the knowledge as words, longest first.
fn phrases(knowledge: &Knowledge) -> Vec<(Vec<String>, Target)> {
    let dwellings = knowledge.dwellings.iter().flat_map(|d| {
        d.words
            .iter()
            .map(|w| (words(w), Target::Dwelling(d.kind.clone())))
    });
    let rooms = knowledge.rooms.iter().flat_map(|r| {
        r.words
            .iter()
            .map(|w| (words(w), Target::Room(r.name.clone())))
    });
    let mut all: Vec<(Vec<String>, Target)> = dwellings.chain(rooms).collect();
    all.sort_by_key(|(w, _)| std::cmp::Reverse(w.len()));
    all
}

/// The longest phrase starting at token `at`, with its length.
fn phrase_at<'a>(
    table: &'a [(Vec<String>, Target)],
    tokens: &[Token],
    at: usize,
) -> Option<(&'a Target, usize)> {
    table.iter().find_map(|(words, target)| {
        let fits = tokens.len() >= at + words.len()
            && words
                .iter()
                .zip(&tokens[at..])
                .all(|(w, t)| t.stem() == Some(w.as_str()));
        fits.then_some((target, words.len()))
    })
}

fn read_mentions(knowledge: &Knowledge, tokens: &[Token]) -> Vec<Mention> {
    let table = phrases(knowledge);
    let mut out = Vec::new();
    let mut at = 0;
    while at < tokens.len() {
        let Some((target, len)) = phrase_at(&table, tokens, at) else {
            at += 1;
            continue;
        };
        let end = at + len;
        if names_itself(&table, tokens, end) {
            let plural = matches!(tokens[end - 1], Token::Word { plural: true, .. });
            let count = count_before(tokens, at).or(if plural { None } else { Some(1) });
            out.push(Mention {
                target: target.clone(),
                count,
            });
        }
        at = end;
    }
    out
}

/// Whether the phrase ending before token `end` names a room or dwelling rather than modifying
/// the next noun: it ends the text or a clause, or a follower word or another phrase comes next.
fn names_itself(table: &[(Vec<String>, Target)], tokens: &[Token], end: usize) -> bool {
    match tokens.get(end) {
        None | Some(Token::Break) => true,
        Some(Token::Word { stem, .. }) => {
            FOLLOWERS.contains(&stem.as_str())
                || number(stem).is_some()
                || phrase_at(table, tokens, end).is_some()
        }
    }
}

/// The count written just before the phrase at `at` ("three bedrooms", "a two-bedroom",
/// "four small offices": one adjective may stand between).
fn count_before(tokens: &[Token], at: usize) -> Option<u32> {
    for back in 1..=2 {
        let word = at.checked_sub(back).and_then(|i| tokens[i].stem())?;
        if let Some(n) = number(word) {
            return Some(n);
        }
        if FOLLOWERS.contains(&word) {
            return None;
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Program {
        Program::from_words(Knowledge::builtin(), text).unwrap_or_else(|| panic!("{text}"))
    }

    #[test]
    fn the_five_prompts_of_issue_26() {
        let p = read("a two-bedroom apartment");
        assert_eq!(p.kind, "apartment");
        assert_eq!(
            (p.count("bedroom"), p.count("kitchen"), p.count("bathroom")),
            (2, 1, 1)
        );
        assert_eq!(p.count("living_room"), 1);

        let p = read("a studio flat");
        assert_eq!(p.kind, "studio");
        assert_eq!(
            (
                p.count("bedroom"),
                p.count("kitchenette"),
                p.count("bathroom")
            ),
            (0, 1, 1)
        );

        let p = read("a family house with three bedrooms and two bathrooms");
        assert_eq!(p.kind, "house");
        assert_eq!(
            (p.count("bedroom"), p.count("bathroom"), p.count("kitchen")),
            (3, 2, 1)
        );

        let p = read("an office suite with a meeting room, a kitchenette and four offices");
        assert_eq!(p.kind, "office_suite");
        assert_eq!(
            (
                p.count("office"),
                p.count("meeting_room"),
                p.count("kitchenette")
            ),
            (4, 1, 1)
        );
        assert_eq!((p.count("reception"), p.count("toilet")), (1, 1));

        let p = read("a clinic with a waiting room and two exam rooms");
        assert_eq!(p.kind, "clinic");
        assert_eq!(
            (
                p.count("waiting_room"),
                p.count("exam_room"),
                p.count("toilet")
            ),
            (1, 2, 1)
        );
    }

    #[test]
    fn digits_plurals_and_modifiers() {
        let p = read("a house with 4 bedrooms");
        assert_eq!(p.count("bedroom"), 4);
        let p = read("an apartment with bedrooms");
        assert_eq!(p.count("bedroom"), 2);
        let p = read("a flat with a kitchen table and two bedrooms");
        assert_eq!((p.count("kitchen"), p.count("bedroom")), (1, 2));
        let p = read("a shop with a store room");
        assert_eq!((p.kind.as_str(), p.count("storeroom")), ("shop", 1));
        assert!(Program::from_words(Knowledge::builtin(), "a kitchen with a big table").is_none());
        assert!(
            Program::from_words(Knowledge::builtin(), "a bathroom sink and a bedroom").is_none()
        );
    }

    #[test]
    fn several_rooms_without_a_dwelling_pick_the_kind_that_fits() {
        let p = read("a reception and three offices");
        assert_eq!((p.kind.as_str(), p.count("office")), ("office_suite", 3));
        let p = read("a bedroom, a kitchen and a living room");
        assert_eq!(p.kind, "apartment");
    }

    #[test]
    fn counts_override_defaults_but_not_requirements() {
        let k = Knowledge::builtin();
        let p = Program::new(k, "house", &[("bathroom", 0), ("dining_room", 0)]).unwrap();
        assert_eq!(
            (
                p.count("bathroom"),
                p.count("dining_room"),
                p.count("bedroom")
            ),
            (1, 0, 3)
        );
        assert!(matches!(
            Program::new(k, "castle", &[]),
            Err(ProgramError::UnknownKind { .. })
        ));
        assert!(matches!(
            Program::new(k, "house", &[("dungeon", 1)]),
            Err(ProgramError::UnknownRoomType { .. })
        ));
        assert!(matches!(
            Program::new(k, "house", &[("bedroom", 11)]),
            Err(ProgramError::TooMany { .. })
        ));
    }
}
