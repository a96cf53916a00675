//! The dwelling knowledge (`knowledge/dwellings.toml`): room types with their areas, privacy,
//! doors and windows, which room pairs join by an open passage or a double door, and the
//! dwelling kinds with the rooms each has.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::OnceLock;

use serde::Deserialize;

use crate::plan::DoorKind;

/// The built-in knowledge file.
pub const DWELLINGS_TOML: &str = include_str!("../knowledge/dwellings.toml");

/// A knowledge file that cannot be used, naming the entry at fault.
#[derive(Debug, thiserror::Error)]
pub enum KnowledgeError {
    /// The text is not the expected TOML.
    #[error("dwelling knowledge: {0}")]
    Toml(#[from] toml::de::Error),
    /// One entry breaks a rule.
    #[error("dwelling knowledge, {entry}: {reason}")]
    Entry {
        /// The entry at fault, e.g. `room "bedroom"` or `dwelling "house"`.
        entry: String,
        /// What is wrong with it.
        reason: String,
    },
}

/// Whether a room may be a passage to other rooms.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Privacy {
    /// Never a passage (a bedroom may lead only to its own en-suite bathroom).
    Private,
    /// May lead to other rooms (living room, kitchen, hallway, reception).
    Public,
}

/// The window a room type gets on an exterior wall.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WindowSpec {
    /// Height of the window's bottom above the floor, m.
    pub sill: f64,
    /// Width of the opening, m.
    pub width: f64,
    /// Height of the opening, m.
    pub height: f64,
}

/// One room type of the knowledge.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoomKind {
    /// The type's name, e.g. `bedroom` (what plans name in a room's `type`).
    #[serde(rename = "type")]
    pub name: String,
    /// Phrases a prompt uses for the type, e.g. `living room`, `lounge`.
    pub words: Vec<String>,
    /// Floor area `[min, typical, max]` in m².
    pub area: [f64; 3],
    /// Narrowest side a room of this type may have, m.
    pub min_width: f64,
    /// Whether the room may be a passage.
    pub privacy: Privacy,
    /// Width of a single door into such a room, m.
    pub door_width: f64,
    /// The room type a room of this type may be an en-suite of (reached only through that
    /// room, as a bathroom off a bedroom); generation makes the second and later rooms of the
    /// type en-suites when the program has such hosts.
    #[serde(default)]
    pub ensuite_of: Option<String>,
    /// The window such a room gets, if any.
    #[serde(default)]
    pub window: Option<WindowSpec>,
    /// Where the numbers come from (our summary).
    pub source: String,
}

/// Two room types and the note saying why they join that way.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoomPair {
    /// The two room types.
    pub rooms: [String; 2],
    /// Where the rule comes from (our summary).
    pub source: String,
}

/// One dwelling kind of the knowledge.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DwellingKind {
    /// The kind's name, e.g. `house`.
    pub kind: String,
    /// Phrases a prompt uses for the kind, e.g. `family house`.
    pub words: Vec<String>,
    /// Rooms every dwelling of the kind has, with their minimum counts.
    pub required: BTreeMap<String, u32>,
    /// Counts used when the caller names none (on top of `required`).
    #[serde(default)]
    pub defaults: BTreeMap<String, u32>,
    /// Further room types that suit the kind.
    #[serde(default)]
    pub optional: Vec<String>,
    /// Room types the entrance door may lead into, in order of preference.
    pub entrance: Vec<String>,
    /// The entrance door's kind (single or double).
    pub entrance_door: DoorKind,
    /// Width range `[min, max]` of a corridor in this kind, m.
    #[serde(default = "default_corridor")]
    pub corridor_width: [f64; 2],
    /// Area ranges `[min, typical, max]` that replace the room type's for this kind.
    #[serde(default)]
    pub areas: BTreeMap<String, [f64; 3]>,
    /// Where the composition comes from (our summary).
    pub source: String,
}

impl DwellingKind {
    /// The default count of a room type for this kind: its `defaults` entry, else its
    /// `required` minimum, else 0.
    pub fn default_count(&self, room_type: &str) -> u32 {
        let required = self.required.get(room_type).copied().unwrap_or(0);
        self.defaults
            .get(room_type)
            .copied()
            .unwrap_or(0)
            .max(required)
    }

    /// Whether the kind has, may have or defaults to this room type.
    pub fn mentions(&self, room_type: &str) -> bool {
        self.required.contains_key(room_type)
            || self.defaults.contains_key(room_type)
            || self.optional.iter().any(|t| t == room_type)
    }
}

/// The whole knowledge file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Knowledge {
    /// Room types.
    #[serde(rename = "room")]
    pub rooms: Vec<RoomKind>,
    /// Pairs joined by an open passage.
    #[serde(rename = "open_pair", default)]
    pub open_pairs: Vec<RoomPair>,
    /// Pairs joined by a double door.
    #[serde(rename = "double_pair", default)]
    pub double_pairs: Vec<RoomPair>,
    /// Dwelling kinds.
    #[serde(rename = "dwelling")]
    pub dwellings: Vec<DwellingKind>,
}

/// The room type that circulation spaces (corridors, entrance halls) have.
pub const HALLWAY: &str = "hallway";

impl Knowledge {
    /// The built-in knowledge (`knowledge/dwellings.toml`), read and checked once.
    ///
    /// # Panics
    /// Never in a released build: the built-in file is checked by this crate's tests.
    pub fn builtin() -> &'static Knowledge {
        static BUILTIN: OnceLock<Knowledge> = OnceLock::new();
        BUILTIN.get_or_init(|| {
            Knowledge::from_toml(DWELLINGS_TOML).expect("built-in dwellings.toml is checked")
        })
    }

    /// Reads and checks a knowledge file.
    pub fn from_toml(text: &str) -> Result<Knowledge, KnowledgeError> {
        let knowledge: Knowledge = toml::from_str(text)?;
        knowledge.check()?;
        Ok(knowledge)
    }

    /// The room type with this name.
    pub fn room(&self, name: &str) -> Option<&RoomKind> {
        self.rooms.iter().find(|r| r.name == name)
    }

    /// The dwelling kind with this name.
    pub fn dwelling(&self, kind: &str) -> Option<&DwellingKind> {
        self.dwellings.iter().find(|d| d.kind == kind)
    }

    /// The area range `[min, typical, max]` of a room type in a dwelling kind.
    pub fn area(&self, kind: &DwellingKind, room_type: &str) -> Option<[f64; 3]> {
        kind.areas
            .get(room_type)
            .copied()
            .or_else(|| self.room(room_type).map(|r| r.area))
    }

    /// Whether the room type may be a passage.
    pub fn is_private(&self, room_type: &str) -> bool {
        self.room(room_type)
            .is_some_and(|r| r.privacy == Privacy::Private)
    }

    /// How two room types sharing a wall are joined when they are joined directly: an open
    /// passage, a double door or a single door.
    pub fn join_kind(&self, a: &str, b: &str) -> DoorKind {
        let has = |pairs: &[RoomPair]| {
            pairs.iter().any(|p| {
                (p.rooms[0] == a && p.rooms[1] == b) || (p.rooms[0] == b && p.rooms[1] == a)
            })
        };
        if has(&self.open_pairs) {
            DoorKind::Passage
        } else if has(&self.double_pairs) {
            DoorKind::Double
        } else {
            DoorKind::Single
        }
    }

    /// Whether a room of this type may be an en-suite of a private room.
    pub fn may_be_ensuite(&self, room_type: &str) -> bool {
        self.room(room_type).is_some_and(|r| r.ensuite_of.is_some())
    }

    /// The names of all room types, comma-separated (for error messages).
    pub fn room_names(&self) -> String {
        let names: Vec<&str> = self.rooms.iter().map(|r| r.name.as_str()).collect();
        names.join(", ")
    }

    fn check(&self) -> Result<(), KnowledgeError> {
        if self.room(HALLWAY).is_none() {
            return Err(entry_error("room list", "has no `hallway` room type"));
        }
        let mut names = BTreeSet::new();
        for room in &self.rooms {
            if !names.insert(room.name.as_str()) {
                return Err(entry_error(&room_entry(room), "is listed twice"));
            }
            check_room(room)?;
        }
        for room in &self.rooms {
            if let Some(host) = room
                .ensuite_of
                .as_deref()
                .filter(|h| self.room(h).is_none())
            {
                let reason = format!("ensuite_of names unknown room type `{host}`");
                return Err(entry_error(&room_entry(room), &reason));
            }
        }
        for (list, pairs) in [
            ("open_pair", &self.open_pairs),
            ("double_pair", &self.double_pairs),
        ] {
            for pair in pairs {
                self.check_pair(list, pair)?;
            }
        }
        let mut kinds = BTreeSet::new();
        for dwelling in &self.dwellings {
            if !kinds.insert(dwelling.kind.as_str()) {
                return Err(entry_error(&dwelling_entry(dwelling), "is listed twice"));
            }
            self.check_dwelling(dwelling)?;
        }
        Ok(())
    }

    fn check_pair(&self, list: &str, pair: &RoomPair) -> Result<(), KnowledgeError> {
        for name in &pair.rooms {
            if self.room(name).is_none() {
                let entry = format!("{list} {:?}", pair.rooms);
                return Err(entry_error(&entry, &format!("unknown room type `{name}`")));
            }
        }
        Ok(())
    }

    fn check_dwelling(&self, dwelling: &DwellingKind) -> Result<(), KnowledgeError> {
        let entry = dwelling_entry(dwelling);
        if dwelling.words.is_empty() || dwelling.required.is_empty() {
            return Err(entry_error(&entry, "needs `words` and `required` rooms"));
        }
        let named = dwelling
            .required
            .keys()
            .chain(dwelling.defaults.keys())
            .chain(&dwelling.optional)
            .chain(&dwelling.entrance)
            .chain(dwelling.areas.keys());
        for name in named {
            if self.room(name).is_none() {
                return Err(entry_error(&entry, &format!("unknown room type `{name}`")));
            }
        }
        if !matches!(dwelling.entrance_door, DoorKind::Single | DoorKind::Double) {
            return Err(entry_error(
                &entry,
                "entrance_door must be single or double",
            ));
        }
        let [lo, hi] = dwelling.corridor_width;
        if !(1.0..=4.0).contains(&lo) || hi < lo || hi > 4.0 {
            return Err(entry_error(
                &entry,
                "corridor_width must be [min, max] within 1-4 m",
            ));
        }
        for (name, area) in &dwelling.areas {
            check_area(&format!("{entry}, areas.{name}"), *area)?;
        }
        Ok(())
    }
}

fn default_corridor() -> [f64; 2] {
    [1.2, 1.5]
}

fn check_room(room: &RoomKind) -> Result<(), KnowledgeError> {
    let entry = room_entry(room);
    if room.words.is_empty() || room.source.trim().is_empty() {
        return Err(entry_error(&entry, "needs `words` and a `source` note"));
    }
    check_area(&entry, room.area)?;
    if room.ensuite_of.as_deref() == Some(room.name.as_str()) {
        return Err(entry_error(&entry, "cannot be an en-suite of itself"));
    }
    let door_ok = (0.7..=1.0).contains(&room.door_width) && room.door_width < room.min_width;
    if !door_ok || room.min_width <= 0.0 {
        return Err(entry_error(
            &entry,
            "door_width must be 0.7-1.0 m and less than min_width",
        ));
    }
    if let Some(w) = room.window {
        let fits = w.sill >= 0.0 && w.width > 0.0 && w.height > 0.0 && w.sill + w.height <= 2.4;
        if !fits {
            return Err(entry_error(
                &entry,
                "window needs sill >= 0, a positive size and its top at most 2.4 m",
            ));
        }
    }
    Ok(())
}

fn check_area(entry: &str, [min, typical, max]: [f64; 3]) -> Result<(), KnowledgeError> {
    if 0.0 < min && min <= typical && typical <= max {
        Ok(())
    } else {
        Err(entry_error(
            entry,
            "area must be [min, typical, max] with 0 < min <= typical <= max",
        ))
    }
}

fn room_entry(room: &RoomKind) -> String {
    format!("room {:?}", room.name)
}

fn dwelling_entry(dwelling: &DwellingKind) -> String {
    format!("dwelling {:?}", dwelling.kind)
}

fn entry_error(entry: &str, reason: &str) -> KnowledgeError {
    KnowledgeError::Entry {
        entry: entry.to_owned(),
        reason: reason.to_owned(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_loads_with_the_kinds_the_issue_names() {
        let k = Knowledge::from_toml(DWELLINGS_TOML).unwrap();
        for kind in [
            "apartment",
            "studio",
            "house",
            "office_suite",
            "clinic",
            "shop",
            "restaurant",
            "school_wing",
        ] {
            assert!(k.dwelling(kind).is_some(), "{kind}");
        }
        let house = k.dwelling("house").unwrap();
        for room in ["kitchen", "bathroom", "living_room"] {
            assert!(house.required.contains_key(room), "{room}");
        }
        assert_eq!(k.join_kind("living_room", "kitchen"), DoorKind::Passage);
        assert_eq!(k.join_kind("dining_room", "living_room"), DoorKind::Double);
        assert_eq!(k.join_kind("bedroom", "hallway"), DoorKind::Single);
        assert!(k.is_private("bedroom") && !k.is_private("hallway"));
        assert!(k.room("bathroom").unwrap().window.unwrap().sill >= 1.4);
    }

    fn with(old: &str, new: &str) -> String {
        assert!(DWELLINGS_TOML.contains(old), "{old}");
        DWELLINGS_TOML.replacen(old, new, 1)
    }

    #[test]
    fn bad_entries_are_named() {
        let cases = [
            (
                with("area = [5.5, 9.0, 16.0]", "area = [9.0, 5.5, 16.0]"),
                "room \"kitchen\"",
            ),
            (
                with(
                    "defaults = { bedroom = 3, dining_room = 1 }",
                    "defaults = { bedrom = 3 }",
                ),
                "`bedrom`",
            ),
            (
                with(
                    "rooms = [\"kitchen\", \"living_room\"]",
                    "rooms = [\"kitchen\", \"lounge\"]",
                ),
                "open_pair",
            ),
            (
                with("entrance_door = \"double\"", "entrance_door = \"passage\""),
                "dwelling \"clinic\"",
            ),
            (
                with(
                    "window = { sill = 1.5, width = 0.6, height = 0.6 }",
                    "window = { sill = 2.0, width = 0.6, height = 0.6 }",
                ),
                "room \"bathroom\"",
            ),
        ];
        for (text, needle) in cases {
            let err = Knowledge::from_toml(&text).unwrap_err().to_string();
            assert!(err.contains(needle), "{err} lacks {needle}");
        }
        let unknown = with(
            "min_width = 3.0\nprivacy",
            "min_width = 3.0\nfloor = 1\nprivacy",
        );
        assert!(Knowledge::from_toml(&unknown).is_err());
    }
}
