//! The place thesaurus: kinds of places the archetypes do not name (a pharmacy, an airport
//! gate, a throne room), each read as a kind of a known archetype, and the families places
//! belong to (home, shop, office, public space, workshop, outdoor, vehicle interior, fantasy),
//! read from `knowledge/places.toml`. Every place documents its `core` (what any real room of
//! its type holds, checked at load against the groups it derives) and the `source` of it.

use std::collections::BTreeSet;
use std::sync::OnceLock;

use serde::Deserialize;

use crate::knowledge::{
    check_ground, AnchorPlace, Archetype, Knowledge, KnowledgeError, ObjectGroup, Place,
};
use crate::plan::Zone;
use crate::text::phrase_stems;

/// The embedded place thesaurus.
pub const PLACES_TOML: &str = include_str!("../knowledge/places.toml");
/// The embedded table of nouns the library lacks.
pub const NOUNS_TOML: &str = include_str!("../knowledge/nouns.toml");

const PLACES_FILE: &str = "knowledge/places.toml";
const NOUNS_FILE: &str = "knowledge/nouns.toml";

/// How many `like` links a place may follow before it must reach an archetype.
const MAX_LIKE_DEPTH: usize = 8;

/// A family of places and its generic room.
#[derive(Debug, Clone, PartialEq)]
pub struct Family {
    /// The family's name (`home`, `shop`, `office`, `public`, `workshop`, `outdoor`, `vehicle`,
    /// `fantasy`).
    pub name: String,
    /// The family's generic room: an archetype or a place name.
    pub room: String,
    /// Head nouns (word stems) that make a prompt a place of the family.
    pub words: BTreeSet<String>,
}

/// A kind of place, read as a kind of a known archetype or of another place.
#[derive(Debug, Clone, PartialEq)]
pub struct PlaceKind {
    /// Stable name, used as the plan's scene type.
    pub name: String,
    /// Names and phrases a prompt may use, as singular word stems.
    pub phrases: Vec<Vec<String>>,
    /// The family the place belongs to.
    pub family: String,
    /// What the place is, in words ("a shop selling medicine").
    pub gloss: String,
    /// The archetype or earlier place it is a kind of.
    pub like: String,
    /// Categories whose inherited groups are left out.
    pub without: Vec<String>,
    /// Object groups added after (or replacing) the inherited ones.
    pub add: Vec<ObjectGroup>,
    /// A new anchor category and where it stands.
    pub anchor: Option<(String, AnchorPlace)>,
    /// What the open ground is made of when it differs from the ground of the place it is
    /// like (outdoor places only): a library material id.
    pub ground: Option<String>,
    /// What any real room of this type holds: categories every plan of the place contains
    /// (each is the derived anchor or has a derived group with a minimum count of at least 1).
    pub core: Vec<String>,
    /// Where the core comes from (for most places our summary of common practice, not a
    /// measured survey).
    pub source: String,
}

/// A noun the library has no category for: its nearest category, or none.
#[derive(Debug, Clone, PartialEq)]
pub struct NounAlias {
    /// The noun's phrase as singular word stems.
    pub phrase: Vec<String>,
    /// The nearest category, or `None` when nothing is close (reported as unavailable).
    pub category: Option<String>,
    /// Where the stand-in goes when the prompt does not say.
    pub zone: Option<Zone>,
    /// The mapping applies only when the scene's archetypes plan this category.
    pub only_with: Option<String>,
}

/// The place thesaurus: places, families and the nouns the library lacks.
#[derive(Debug, Clone, PartialEq)]
pub struct Thesaurus {
    /// The families, in file order.
    pub families: Vec<Family>,
    /// The places, in file order.
    pub places: Vec<PlaceKind>,
    /// Nouns the library lacks, longest phrase first.
    pub nouns: Vec<NounAlias>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct NounsFile {
    noun: Vec<RawNoun>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawNoun {
    words: Vec<String>,
    #[serde(default)]
    category: Option<String>,
    #[serde(default)]
    zone: Option<String>,
    #[serde(default)]
    only_with: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PlacesFile {
    family: Vec<RawFamily>,
    place: Vec<RawPlace>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFamily {
    name: String,
    room: String,
    words: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPlace {
    name: String,
    words: Vec<String>,
    family: String,
    gloss: String,
    like: String,
    #[serde(default)]
    without: Vec<String>,
    #[serde(default)]
    add: Vec<(String, u32, u32, String)>,
    #[serde(default)]
    anchor: Option<(String, AnchorPlace)>,
    #[serde(default)]
    ground: Option<String>,
    core: Vec<String>,
    source: String,
}

fn invalid(entry: &str, message: String) -> KnowledgeError {
    KnowledgeError::Invalid {
        file: PLACES_FILE,
        entry: entry.to_owned(),
        message,
    }
}

impl Thesaurus {
    /// The thesaurus embedded in this build, checked against the built-in knowledge (parsed
    /// once).
    ///
    /// # Panics
    /// Never in a released build: the embedded file is checked by this crate's tests.
    pub fn builtin() -> &'static Thesaurus {
        static BUILTIN: OnceLock<Thesaurus> = OnceLock::new();
        BUILTIN.get_or_init(|| {
            Thesaurus::from_toml(PLACES_TOML, NOUNS_TOML, Knowledge::builtin())
                .unwrap_or_else(|e| panic!("embedded place thesaurus is broken: {e}"))
        })
    }

    /// Reads the thesaurus from the text of `places.toml` and `nouns.toml` and checks it
    /// against `knowledge`: unique names, known families, `like` reaching an archetype, known
    /// categories, places and zones, phrases no archetype or earlier place uses, a `source`,
    /// and a `core` every category of which the derived place plans (as its anchor or in a
    /// group with a minimum count of at least 1).
    pub fn from_toml(
        text: &str,
        nouns: &str,
        knowledge: &Knowledge,
    ) -> Result<Thesaurus, KnowledgeError> {
        let file: PlacesFile = toml::from_str(text).map_err(|e| KnowledgeError::Parse {
            file: PLACES_FILE,
            message: e.to_string(),
        })?;
        let families: Vec<Family> = file
            .family
            .into_iter()
            .map(|f| Family {
                name: f.name,
                room: f.room,
                words: f.words.iter().flat_map(|w| phrase_stems(w)).collect(),
            })
            .collect();
        let mut places: Vec<PlaceKind> = Vec::new();
        for raw in file.place {
            let entry = raw.name.clone();
            if places.iter().any(|p| p.name == raw.name) || knowledge.archetype(&raw.name).is_some()
            {
                return Err(invalid(
                    &entry,
                    "place name used twice (or already an archetype name)".into(),
                ));
            }
            if !families.iter().any(|f| f.name == raw.family) {
                return Err(invalid(&entry, format!("unknown family `{}`", raw.family)));
            }
            if knowledge.archetype(&raw.like).is_none()
                && !places.iter().any(|p| p.name == raw.like)
            {
                return Err(invalid(
                    &entry,
                    format!(
                        "`like` names `{}`, which is neither an archetype nor an earlier place",
                        raw.like
                    ),
                ));
            }
            let known = |c: &str| knowledge.prior(c).is_some();
            for c in raw.without.iter().chain(raw.anchor.iter().map(|a| &a.0)) {
                if !known(c) {
                    return Err(invalid(&entry, format!("unknown category `{c}`")));
                }
            }
            let mut add = Vec::new();
            for (category, min, max, place_text) in raw.add {
                if !known(&category) {
                    return Err(invalid(&entry, format!("unknown category `{category}`")));
                }
                let place = Place::parse(&place_text).filter(|p| *p != Place::Anchor);
                let Some(place) = place else {
                    return Err(invalid(
                        &entry,
                        format!("object `{category}`: unknown place `{place_text}`"),
                    ));
                };
                if min > max {
                    return Err(invalid(
                        &entry,
                        format!("object `{category}`: min {min} is above max {max}"),
                    ));
                }
                add.push(ObjectGroup {
                    category,
                    min,
                    max,
                    place,
                });
            }
            let phrases: Vec<Vec<String>> = raw
                .words
                .iter()
                .map(|w| phrase_stems(w))
                .filter(|p| !p.is_empty())
                .collect();
            if phrases.is_empty() {
                return Err(invalid(&entry, "`words` must name the place".into()));
            }
            if raw.gloss.trim().is_empty() {
                return Err(invalid(&entry, "`gloss` must say what the place is".into()));
            }
            if raw.source.trim().is_empty() {
                return Err(invalid(
                    &entry,
                    "`source` must say where the place's contents come from".into(),
                ));
            }
            if raw.core.is_empty() {
                return Err(invalid(
                    &entry,
                    "`core` must list what every room of the place holds".into(),
                ));
            }
            for c in &raw.core {
                if !known(c) {
                    return Err(invalid(&entry, format!("core: unknown category `{c}`")));
                }
            }
            for phrase in &phrases {
                let words = phrase.join(" ");
                if let Some(a) = knowledge
                    .archetypes
                    .iter()
                    .find(|a| a.phrases.contains(phrase))
                {
                    return Err(invalid(
                        &entry,
                        format!("words: `{words}` already names the archetype `{}`", a.name),
                    ));
                }
                if let Some(p) = places.iter().find(|p| p.phrases.contains(phrase)) {
                    return Err(invalid(
                        &entry,
                        format!("words: `{words}` already names the place `{}`", p.name),
                    ));
                }
            }
            places.push(PlaceKind {
                name: raw.name,
                phrases,
                family: raw.family,
                gloss: raw.gloss,
                like: raw.like,
                without: raw.without,
                add,
                anchor: raw.anchor,
                ground: raw.ground,
                core: raw.core,
                source: raw.source,
            });
        }
        let nouns = read_nouns(nouns, knowledge)?;
        let thesaurus = Thesaurus {
            families,
            places,
            nouns,
        };
        for p in &thesaurus.places {
            let Some(derived) = thesaurus.archetype(&p.name, knowledge) else {
                return Err(invalid(
                    &p.name,
                    "the place has no anchor group once `without` applies; give it an `anchor`"
                        .into(),
                ));
            };
            check_ground(
                PLACES_FILE,
                &p.name,
                derived.environment,
                p.ground.as_deref(),
            )?;
            for c in &p.core {
                let held = *c == derived.anchor
                    || derived
                        .objects
                        .iter()
                        .any(|g| g.category == *c && g.min >= 1);
                if !held {
                    return Err(invalid(
                        &p.name,
                        format!(
                            "core category `{c}` is neither the anchor nor in an object group \
                             with a minimum count of at least 1 (inherited from `{}` or added)",
                            p.like
                        ),
                    ));
                }
            }
        }
        for f in &thesaurus.families {
            thesaurus
                .archetype(&f.room, knowledge)
                .ok_or_else(|| invalid(&f.name, format!("unknown room `{}`", f.room)))?;
        }
        Ok(thesaurus)
    }

    /// The place with this name.
    pub fn place(&self, name: &str) -> Option<&PlaceKind> {
        self.places.iter().find(|p| p.name == name)
    }

    /// The family with this name.
    pub fn family(&self, name: &str) -> Option<&Family> {
        self.families.iter().find(|f| f.name == name)
    }

    /// The archetype `name` stands for: a knowledge archetype itself, or a place derived from
    /// the archetype it is (transitively) like. `None` if the name is unknown.
    pub fn archetype(&self, name: &str, knowledge: &Knowledge) -> Option<Archetype> {
        self.derive(name, knowledge, 0)
    }

    fn derive(&self, name: &str, knowledge: &Knowledge, depth: usize) -> Option<Archetype> {
        if let Some(a) = knowledge.archetype(name) {
            return Some(a.clone());
        }
        if depth > MAX_LIKE_DEPTH {
            return None;
        }
        let place = self.place(name)?;
        let mut a = self.derive(&place.like, knowledge, depth + 1)?;
        a.name = place.name.clone();
        a.phrases = place.phrases.clone();
        a.core = place.core.clone();
        a.source = Some(place.source.clone());
        if place.ground.is_some() {
            a.ground = place.ground.clone();
        }
        a.objects.retain(|g| !place.without.contains(&g.category));
        if let Some((category, anchor_place)) = &place.anchor {
            for g in &mut a.objects {
                if g.place == Place::Anchor {
                    g.place = Place::Wall;
                }
            }
            a.objects.insert(
                0,
                ObjectGroup {
                    category: category.clone(),
                    min: 1,
                    max: 1,
                    place: Place::Anchor,
                },
            );
            a.anchor = category.clone();
            a.anchor_place = *anchor_place;
        }
        for g in &place.add {
            match a
                .objects
                .iter()
                .position(|x| x.category == g.category && x.place != Place::Anchor)
            {
                // A group placed relative to a category moves to the end, after every group
                // it may be relative to: the open office's chairs are drawn up to the rows of
                // desks its own `add` brings, not all to the office's one desk.
                Some(i) if g.place.target().is_some() => {
                    a.objects.remove(i);
                    a.objects.push(g.clone());
                }
                Some(i) => a.objects[i] = g.clone(),
                None => a.objects.push(g.clone()),
            }
        }
        // Groups placed relative to a category no earlier group provides are left out.
        let mut have: BTreeSet<String> = BTreeSet::new();
        a.objects.retain(|g| {
            let keep = g.place.target().is_none_or(|t| have.contains(t));
            if keep {
                have.insert(g.category.clone());
            }
            keep
        });
        if !a.objects.iter().any(|g| g.place == Place::Anchor) {
            return None;
        }
        Some(a)
    }
}

/// Reads and checks `nouns.toml`.
fn read_nouns(text: &str, knowledge: &Knowledge) -> Result<Vec<NounAlias>, KnowledgeError> {
    let file: NounsFile = toml::from_str(text).map_err(|e| KnowledgeError::Parse {
        file: NOUNS_FILE,
        message: e.to_string(),
    })?;
    let invalid = |entry: &str, message: String| KnowledgeError::Invalid {
        file: NOUNS_FILE,
        entry: entry.to_owned(),
        message,
    };
    let mut nouns = Vec::new();
    for raw in file.noun {
        let entry = raw.words.first().cloned().unwrap_or_default();
        for c in raw.category.iter().chain(&raw.only_with) {
            if knowledge.prior(c).is_none() {
                return Err(invalid(&entry, format!("unknown category `{c}`")));
            }
        }
        let zone = match raw.zone.as_deref() {
            None => None,
            Some("center") => Some(Zone::Center),
            Some("wall") => Some(Zone::Wall { wall: None }),
            Some("corner") => Some(Zone::Corner),
            Some("free") => Some(Zone::Free),
            Some("wall-mounted") => Some(Zone::WallMounted),
            Some(other) => {
                return Err(invalid(
                    &entry,
                    format!(
                    "unknown zone `{other}`; expected center, wall, corner, free or wall-mounted"
                ),
                ))
            }
        };
        for words in &raw.words {
            let phrase = phrase_stems(words);
            if phrase.is_empty() {
                return Err(invalid(&entry, "an empty phrase in `words`".into()));
            }
            nouns.push(NounAlias {
                phrase,
                category: raw.category.clone(),
                zone: zone.clone(),
                only_with: raw.only_with.clone(),
            });
        }
    }
    // Longest phrase first, so that "dresser mirror" is tried before "mirror".
    nouns.sort_by_key(|n| std::cmp::Reverse(n.phrase.len()));
    Ok(nouns)
}
