//! What each house room is asked for: the single-room prompt of its type, plus what the
//! house prompt says about rooms of that type ("a kitchen with an island").

use scenethesis_floorplan::Knowledge;

/// The single-room prompt the planner reads for each floor-plan room type: the archetype (or
/// place) the planner knows that furnishes such a room.
const ROOM_PROMPTS: &[(&str, &str)] = &[
    ("living_room", "a living room"),
    ("kitchen", "a kitchen"),
    ("kitchenette", "a small kitchen"),
    ("dining_room", "a dining room"),
    ("bedroom", "a bedroom"),
    ("bathroom", "a bathroom"),
    ("toilet", "a small bathroom with a toilet"),
    ("hallway", "a hallway"),
    ("office", "an office"),
    ("meeting_room", "a conference room"),
    ("reception", "a reception with a desk"),
    ("waiting_room", "a waiting room"),
    ("exam_room", "a doctor's examination room"),
    ("storeroom", "a storage room"),
    ("shop_floor", "a convenience store"),
    ("classroom", "a classroom"),
    ("staff_room", "a break room"),
    ("utility_room", "a laundry room"),
];

/// Dwelling words that also name one room the single-room planner furnishes ("an art studio",
/// "a toy store", "a cafe", "a cozy home", "a witch's cottage"): alone they leave a prompt one
/// room, as before
/// houses; with a room type named ("a cafe with a kitchen and a dining room") they make a
/// house.
const ONE_ROOM_AS_WELL: &[&str] = &[
    "studio",
    "shop",
    "store",
    "boutique",
    "corner shop",
    "grocery",
    "restaurant",
    "bistro",
    "diner",
    "cafe",
    "eatery",
    "school",
    "home",
    "cottage",
];

/// Whether `prompt`, which the floor-plan knowledge reads as a house program, asks for a house
/// rather than one room: it names a dwelling unambiguously ("apartment", "studio flat",
/// "office suite"), an ambiguous dwelling word ([`ONE_ROOM_AS_WELL`]) with a room type besides
/// ("a shop with a store room"), or two room types apart ("a kitchen and a living room").
/// Ambiguous dwelling words alone stay one room, and so do room words that only form one
/// compound name ("a town hall reception": the hall is the town hall's).
pub(crate) fn asks_for_house(knowledge: &Knowledge, prompt: &str) -> bool {
    let tokens = tokens(prompt);
    let dwelling = |ambiguous: bool| {
        knowledge.dwellings.iter().any(|d| {
            d.words
                .iter()
                .any(|w| ONE_ROOM_AS_WELL.contains(&w.as_str()) == ambiguous && names(&tokens, w))
        })
    };
    let rooms: Vec<(usize, usize)> = knowledge
        .rooms
        .iter()
        .flat_map(|r| r.words.iter().flat_map(|w| spans(&tokens, w)))
        .collect();
    let apart = rooms.iter().any(|a| rooms.iter().any(|b| b.0 > a.1));
    dwelling(false) || (dwelling(true) && !rooms.is_empty()) || apart
}

/// Where `tokens` hold the phrase `words` (its last word also as a plural): each match's first
/// token and the token after its last.
fn spans(tokens: &[String], words: &str) -> Vec<(usize, usize)> {
    let n = self::tokens(words).len();
    (0..tokens.len().saturating_sub(n.max(1) - 1))
        .filter(|&i| n > 0 && names(&tokens[i..i + n], words))
        .map(|i| (i, i + n))
        .collect()
}

/// The prompt's lower-case words (letters and digits; "two-bedroom" is two words).
fn tokens(prompt: &str) -> Vec<String> {
    prompt
        .to_lowercase()
        .split(|c: char| !c.is_alphanumeric())
        .filter(|t| !t.is_empty())
        .map(str::to_owned)
        .collect()
}

/// Whether `tokens` hold the phrase `words` (its last word also as a plural).
fn names(tokens: &[String], words: &str) -> bool {
    let phrase = self::tokens(words);
    let n = phrase.len();
    n > 0
        && tokens.windows(n).any(|w| {
            w[..n - 1] == phrase[..n - 1]
                && (w[n - 1] == phrase[n - 1]
                    || w[n - 1] == format!("{}s", phrase[n - 1])
                    || w[n - 1] == format!("{}es", phrase[n - 1]))
        })
}

/// The prompt a room of `room_type` is planned from: its type's single-room prompt, with what
/// `house_prompt` asks of rooms of that type ("… a kitchen with an island" → "a kitchen with
/// an island"). Counts ("three bedrooms") are the floor plan's, never the room's.
pub(crate) fn room_prompt(knowledge: &Knowledge, house_prompt: &str, room_type: &str) -> String {
    let base = ROOM_PROMPTS
        .iter()
        .find(|(t, _)| *t == room_type)
        .map_or_else(
            || format!("a {}", room_type.replace('_', " ")),
            |(_, p)| (*p).to_owned(),
        );
    match details(knowledge, house_prompt, room_type) {
        Some(extra) if base.contains(" with ") => format!("{base} and {extra}"),
        Some(extra) => format!("{base} with {extra}"),
        None => base,
    }
}

/// What a clause of `prompt` naming `room_type` asks for after "with": `a kitchen with an
/// island` gives `an island`. Clauses are split at commas, semicolons and "and".
fn details(knowledge: &Knowledge, prompt: &str, room_type: &str) -> Option<String> {
    let kind = knowledge.room(room_type)?;
    let lower = prompt.to_lowercase();
    lower
        .split([',', ';', '.'])
        .flat_map(|part| part.split(" and "))
        .find_map(|clause| {
            let (head, tail) = clause.split_once(" with ")?;
            let head = head.trim_end();
            let names = kind
                .words
                .iter()
                .any(|w| head.ends_with(w.as_str()) || head.ends_with(&format!("{w}s")));
            let tail = tail.trim();
            (names && !tail.is_empty()).then(|| tail.to_owned())
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_room_gets_its_types_prompt_and_only_its_own_details() {
        let k = Knowledge::builtin();
        let prompt =
            "a family house with three bedrooms, a kitchen with an island and two bathrooms";
        assert_eq!(room_prompt(k, prompt, "bedroom"), "a bedroom");
        assert_eq!(
            room_prompt(k, prompt, "kitchen"),
            "a kitchen with an island"
        );
        assert_eq!(room_prompt(k, prompt, "bathroom"), "a bathroom");
        let desks = "an office suite with a meeting room and four offices with standing desks";
        assert_eq!(
            room_prompt(k, desks, "office"),
            "an office with standing desks"
        );
        assert_eq!(room_prompt(k, desks, "meeting_room"), "a conference room");
    }

    #[test]
    fn ambiguous_dwelling_words_alone_stay_one_room() {
        let k = Knowledge::builtin();
        for prompt in [
            "a two-bedroom apartment",
            "a studio flat",
            "a shop with a store room",
        ] {
            assert!(asks_for_house(k, prompt), "{prompt}");
        }
        for prompt in [
            "a convenience store",
            "an art studio",
            "a cafe with two bar stools",
            "a witch's cottage",
        ] {
            assert!(!asks_for_house(k, prompt), "{prompt}");
        }
    }

    #[test]
    fn room_words_apart_make_a_house_and_one_compound_name_does_not() {
        let k = Knowledge::builtin();
        assert!(asks_for_house(k, "a kitchen and a living room"));
        assert!(asks_for_house(k, "a bedroom with a bathroom"));
        assert!(!asks_for_house(k, "a town hall reception"));
        assert_eq!(
            spans(&tokens("a living room, a kitchen"), "living room"),
            [(1, 3)]
        );
        assert_eq!(spans(&tokens("two kitchens"), "kitchen"), [(1, 2)]);
    }
}
