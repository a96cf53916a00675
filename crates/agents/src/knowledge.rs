//! The planner's knowledge: scene archetypes, category priors and prompt vocabulary, read from
//! TOML files embedded at build time or supplied by the caller. Category names, words,
//! placement and priors come from the one category table of the asset library
//! ([`scenethesis_procedural::catalog::CATEGORIES_TOML`]), which retrieval reads too; archetypes and
//! vocabulary are this crate's `knowledge/*.toml`.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::OnceLock;

use scenethesis_scene_graph::{Environment, RelationKind};
use serde::Deserialize;

use crate::text::phrase_stems;

/// The embedded archetype file.
pub const ARCHETYPES_TOML: &str = include_str!("../knowledge/archetypes.toml");
/// The embedded category table (names, words, placement, size ranges and planner priors),
/// shared with the asset library and retrieval.
pub const CATEGORIES_TOML: &str = scenethesis_procedural::catalog::CATEGORIES_TOML;
/// The embedded vocabulary file.
pub const VOCABULARY_TOML: &str = include_str!("../knowledge/vocabulary.toml");

/// A knowledge file that cannot be read, naming the file and the entry at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum KnowledgeError {
    /// The TOML does not parse or does not match the schema.
    #[error("{file}: {message}")]
    Parse {
        /// Which file.
        file: &'static str,
        /// The parser's message.
        message: String,
    },
    /// An entry is inconsistent.
    #[error("{file}: {entry}: {message}")]
    Invalid {
        /// Which file.
        file: &'static str,
        /// Which archetype, category or phrase.
        entry: String,
        /// What is wrong and what was expected.
        message: String,
    },
}

/// How things rest on a category, used for nominal support surfaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum NominalShape {
    /// A seat: a top at seat height over the front part of the footprint.
    Seat,
    /// A table: a top at full height and free floor underneath.
    Table,
    /// Shelf levels enclosed above (`shelves` of them).
    Shelves,
    /// Shelf levels inside plus a top.
    Cabinet,
    /// An open container: an interior floor.
    Container,
    /// A solid block with a usable top.
    Solid,
    /// A bed or lounger: a top at full height.
    Bed,
    /// Nothing rests on it.
    None,
}

/// Where a category normally goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Mount {
    /// Stands on the floor.
    #[default]
    Floor,
    /// Hangs on a wall.
    Wall,
    /// Rests on or in another object.
    Surface,
    /// Hangs from the ceiling.
    Ceiling,
}

/// What a category's prior says about it.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CategoryPrior {
    /// Nominal extent [x, y, z] in metres.
    pub size: [f64; 3],
    /// How things rest on it.
    pub shape: NominalShape,
    /// Shelf levels for `shelves` and `cabinet` shapes.
    #[serde(default)]
    pub shelves: u32,
    /// Extra words and phrases for the category.
    #[serde(default)]
    pub words: Vec<String>,
    /// Where a small item goes when the prompt does not say (`on` or `inside`).
    #[serde(default)]
    pub rests: Option<ItemRest>,
    /// Where the category is mounted.
    #[serde(default)]
    pub mount: Mount,
    /// A surface-sized stand-in for when the prompt puts this floor category on or inside
    /// something.
    #[serde(default)]
    pub small: Option<String>,
}

/// Where a small item goes by default.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ItemRest {
    /// On a top surface.
    On,
    /// Inside a shelf compartment or container.
    Inside,
}

/// Where an archetype's anchor stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum AnchorPlace {
    /// Back against the back wall, facing into the room.
    Wall,
    /// In the middle of the room.
    Center,
}

/// The placement template of an archetype's object group.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Place {
    /// The anchor.
    Anchor,
    /// Back against a wall.
    Wall,
    /// In a corner.
    Corner,
    /// Near the middle of the room.
    Center,
    /// In a grid of rows in the middle of the room.
    Rows,
    /// Anywhere with clearance.
    Free,
    /// Hanging on a wall above free floor.
    WallMounted,
    /// Related to instances of a category on the floor (in-front-of, behind, beside, facing,
    /// around).
    Relative(RelationKind, String),
    /// Against the wall opposite an instance of a category, facing it.
    Opposite(String),
    /// Supported by instances of a category (on, inside, under).
    Support(RelationKind, String),
}

impl Place {
    /// Parses a place of the archetype file (`wall`, `in-front-of:sofa`, `on:coffee_table`).
    pub fn parse(text: &str) -> Option<Place> {
        let (head, arg) = match text.split_once(':') {
            Some((h, a)) => (h, Some(a.to_owned())),
            None => (text, None),
        };
        Some(match (head, arg) {
            ("anchor", None) => Place::Anchor,
            ("wall", None) => Place::Wall,
            ("corner", None) => Place::Corner,
            ("center", None) => Place::Center,
            ("rows", None) => Place::Rows,
            ("free", None) => Place::Free,
            ("wall-mounted", None) => Place::WallMounted,
            ("opposite", Some(c)) => Place::Opposite(c),
            ("in-front-of", Some(c)) => Place::Relative(RelationKind::InFrontOf, c),
            ("behind", Some(c)) => Place::Relative(RelationKind::Behind, c),
            ("beside", Some(c)) => Place::Relative(RelationKind::Beside, c),
            ("facing", Some(c)) => Place::Relative(RelationKind::Facing, c),
            ("around", Some(c)) => Place::Relative(RelationKind::Around, c),
            ("on", Some(c)) => Place::Support(RelationKind::On, c),
            ("inside", Some(c)) => Place::Support(RelationKind::Inside, c),
            ("under", Some(c)) => Place::Support(RelationKind::Under, c),
            _ => return None,
        })
    }

    /// The category this place refers to, if any.
    pub fn target(&self) -> Option<&str> {
        match self {
            Place::Relative(_, c) | Place::Opposite(c) | Place::Support(_, c) => Some(c),
            _ => None,
        }
    }
}

/// One group of objects of an archetype.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectGroup {
    /// Category name.
    pub category: String,
    /// Fewest objects (per supporting instance for `Support` places).
    pub min: u32,
    /// Most objects (per supporting instance for `Support` places).
    pub max: u32,
    /// Where they go.
    pub place: Place,
}

/// A scene archetype: what a kind of scene holds and how it is arranged.
#[derive(Debug, Clone, PartialEq)]
pub struct Archetype {
    /// Stable name, e.g. `living_room`.
    pub name: String,
    /// Names and phrases a prompt may use, as singular word stems.
    pub phrases: Vec<Vec<String>>,
    /// Indoor room or outdoor ground.
    pub environment: Environment,
    /// What the open ground of an outdoor archetype is made of: a library material id
    /// (`sand`, `grass`, `paving`, …); `None` indoors.
    pub ground: Option<String>,
    /// Size range [x_min, x_max, z_min, z_max] in metres.
    pub size: [f64; 4],
    /// The anchor category.
    pub anchor: String,
    /// Where the anchor stands.
    pub anchor_place: AnchorPlace,
    /// Minimum walkway width in metres.
    pub aisle: f64,
    /// Free depth in front of the door in metres.
    pub door_clearance: f64,
    /// The object groups, in planning order.
    pub objects: Vec<ObjectGroup>,
    /// What real rooms of this type hold: categories every generated scene of the type should
    /// contain (each has a group with a minimum count of at least one). Groups with a minimum
    /// of zero are the optional extras drawn per seed.
    pub core: Vec<String>,
    /// Where the core comes from.
    pub source: Option<String>,
}

/// The prompt vocabulary.
#[derive(Debug, Clone, PartialEq)]
pub struct Vocabulary {
    /// Count words.
    pub counts: BTreeMap<String, u32>,
    /// Generic nouns and the categories they stand for.
    pub generic: BTreeMap<String, Vec<String>>,
    /// Words without object or scene meaning.
    pub filler: BTreeSet<String>,
    /// Words that make a prompt a scene description.
    pub scene_words: BTreeSet<String>,
    /// The archetype a bare scene description falls back to.
    pub default_archetype: String,
    /// Spatial phrases (as word stems) and what they state.
    pub relations: Vec<(Vec<String>, RelationPhrase)>,
    /// Words that end a prompt's place phrase ("a kitchen *with* a table").
    pub phrase_ends: BTreeSet<String>,
    /// Head nouns that name no kind of place by themselves ("a music *room*").
    pub generic_heads: BTreeSet<String>,
    /// Category words that are also adjectives ("a *safe* room"): read as the object only after
    /// an article, a count or "the", and not before another meaningful word.
    pub adjective_nouns: BTreeSet<String>,
    /// Words of a place phrase that ask for a sparse room ("a *minimalist* bedroom", "an
    /// *empty* warehouse"), as stems, and how sparse.
    pub sparse: BTreeMap<String, Sparsity>,
}

/// How sparse a prompt asks its room to be (`[sparse]` of `knowledge/vocabulary.toml`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Sparsity {
    /// The place's core only, each at its least count, and no optional extras.
    Core,
    /// Nearly nothing: the anchor (a fixed item such as a warehouse's rack) alone.
    Empty,
}

impl Sparsity {
    /// What the planner keeps, in words (recorded in the plan's assumptions).
    pub fn keeps(self) -> &'static str {
        match self {
            Sparsity::Core => "only the place's core contents, at their least counts, no extras",
            Sparsity::Empty => "only the room and its anchor",
        }
    }
}

/// What a spatial phrase states.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RelationPhrase {
    /// The relation kind (`AgainstWall` also for corners).
    pub kind: RelationKind,
    /// The phrase places its subject in a corner.
    pub corner: bool,
    /// The target is the clause's head object, not a following noun.
    pub head: bool,
    /// The subjects go to both sides of the target.
    pub split: bool,
    /// A particular wall (`wall_0` … `wall_3`), or `Some("")` for any wall.
    pub wall: Option<String>,
}

/// All knowledge of the offline planner.
#[derive(Debug, Clone, PartialEq)]
pub struct Knowledge {
    /// Scene archetypes.
    pub archetypes: Vec<Archetype>,
    /// Category priors by category name.
    pub categories: BTreeMap<String, CategoryPrior>,
    /// Prompt vocabulary.
    pub vocabulary: Vocabulary,
    /// Category phrases as word stems, longest first (derived from `categories`).
    phrases: Vec<(Vec<String>, String)>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ArchetypesFile {
    archetype: Vec<RawArchetype>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawArchetype {
    name: String,
    words: Vec<String>,
    environment: Environment,
    #[serde(default)]
    ground: Option<String>,
    size: [f64; 4],
    anchor: String,
    anchor_place: AnchorPlace,
    #[serde(default)]
    aisle: Option<f64>,
    #[serde(default)]
    door_clearance: Option<f64>,
    objects: Vec<(String, u32, u32, String)>,
    #[serde(default)]
    core: Vec<String>,
    #[serde(default)]
    source: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CategoriesFile {
    category: BTreeMap<String, RawCategory>,
}

/// A row of the category table (see `crates/procedural/data/categories.toml`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCategory {
    placement: Mount,
    /// Checked by the asset library; the planner sizes rooms from `plan.size`.
    #[allow(dead_code)]
    size_range: [[f64; 2]; 3],
    #[serde(default)]
    words: Vec<String>,
    plan: RawPrior,
}

/// The `plan` prior of a table row.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPrior {
    size: [f64; 3],
    shape: NominalShape,
    #[serde(default)]
    shelves: u32,
    #[serde(default)]
    rests: Option<ItemRest>,
    #[serde(default)]
    small: Option<String>,
    /// Only where the planner places the category differently from `placement`.
    #[serde(default)]
    mount: Option<Mount>,
}

impl RawCategory {
    fn prior(self) -> CategoryPrior {
        CategoryPrior {
            size: self.plan.size,
            shape: self.plan.shape,
            shelves: self.plan.shelves,
            words: self.words,
            rests: self.plan.rests,
            mount: self.plan.mount.unwrap_or(self.placement),
            small: self.plan.small,
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct VocabularyFile {
    counts: BTreeMap<String, u32>,
    generic: BTreeMap<String, Vec<String>>,
    filler: WordList,
    scene_words: SceneWords,
    place_phrase: PlacePhraseWords,
    sparse: SparseWords,
    relations: BTreeMap<String, String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SparseWords {
    core: Vec<String>,
    empty: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PlacePhraseWords {
    ends: Vec<String>,
    generic_heads: Vec<String>,
    adjective_nouns: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct WordList {
    words: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneWords {
    default_archetype: String,
    words: Vec<String>,
}

const ARCHETYPES_FILE: &str = "knowledge/archetypes.toml";
const CATEGORIES_FILE: &str = "crates/procedural/data/categories.toml";
const VOCABULARY_FILE: &str = "knowledge/vocabulary.toml";

fn relation_kind(name: &str) -> Option<RelationKind> {
    RelationKind::ALL.into_iter().find(|k| k.as_str() == name)
}

impl Knowledge {
    /// The knowledge embedded in this build (parsed once).
    ///
    /// # Panics
    /// Never in a released build: the embedded files are checked by this crate's tests.
    pub fn builtin() -> &'static Knowledge {
        static BUILTIN: OnceLock<Knowledge> = OnceLock::new();
        BUILTIN.get_or_init(|| {
            Knowledge::from_toml(ARCHETYPES_TOML, CATEGORIES_TOML, VOCABULARY_TOML)
                .unwrap_or_else(|e| panic!("embedded knowledge is broken: {e}"))
        })
    }

    /// Reads and checks knowledge from the text of the three files.
    pub fn from_toml(
        archetypes: &str,
        categories: &str,
        vocabulary: &str,
    ) -> Result<Knowledge, KnowledgeError> {
        let parse_err = |file: &'static str| {
            move |e: toml::de::Error| KnowledgeError::Parse {
                file,
                message: e.to_string(),
            }
        };
        let raw: CategoriesFile = toml::from_str(categories).map_err(parse_err(CATEGORIES_FILE))?;
        let priors: BTreeMap<String, CategoryPrior> = raw
            .category
            .into_iter()
            .map(|(name, row)| (name, row.prior()))
            .collect();
        let arch: ArchetypesFile =
            toml::from_str(archetypes).map_err(parse_err(ARCHETYPES_FILE))?;
        let voc: VocabularyFile = toml::from_str(vocabulary).map_err(parse_err(VOCABULARY_FILE))?;

        check_priors(&priors)?;
        let known = |c: &str| priors.contains_key(c);
        let mut archetypes = Vec::new();
        let mut names = BTreeSet::new();
        for raw in arch.archetype {
            if !names.insert(raw.name.clone()) {
                return Err(invalid(
                    ARCHETYPES_FILE,
                    &raw.name,
                    "archetype name used twice".into(),
                ));
            }
            archetypes.push(read_archetype(raw, &known)?);
        }
        check_vocabulary(&voc, &archetypes, &known)?;
        let relations = read_relation_phrases(&voc.relations)?;

        let phrases = category_phrases_of(&priors);
        Ok(Knowledge {
            phrases,
            archetypes,
            categories: priors,
            vocabulary: Vocabulary {
                counts: voc.counts,
                generic: voc.generic,
                filler: voc.filler.words.into_iter().collect(),
                scene_words: voc
                    .scene_words
                    .words
                    .iter()
                    .flat_map(|w| phrase_stems(w))
                    .collect(),
                default_archetype: voc.scene_words.default_archetype,
                relations,
                phrase_ends: voc
                    .place_phrase
                    .ends
                    .iter()
                    .flat_map(|w| phrase_stems(w))
                    .collect(),
                generic_heads: voc
                    .place_phrase
                    .generic_heads
                    .iter()
                    .flat_map(|w| phrase_stems(w))
                    .collect(),
                adjective_nouns: voc
                    .place_phrase
                    .adjective_nouns
                    .iter()
                    .flat_map(|w| phrase_stems(w))
                    .collect(),
                sparse: sparse_words(&voc.sparse),
            },
        })
    }

    /// The archetype with this name.
    pub fn archetype(&self, name: &str) -> Option<&Archetype> {
        self.archetypes.iter().find(|a| a.name == name)
    }

    /// The prior of a category.
    pub fn prior(&self, category: &str) -> Option<&CategoryPrior> {
        self.categories.get(category)
    }

    /// Every category named by the knowledge files.
    pub fn category_names(&self) -> impl Iterator<Item = &str> {
        self.categories.keys().map(String::as_str)
    }

    /// The category a whole phrase names (`"couch"` → `sofa`), matched on word stems against the
    /// category names and words, as the planner reads prompts.
    pub fn category_of_phrase(&self, phrase: &str) -> Option<&str> {
        let rows = self.phrases.iter().map(|(p, c)| (p.as_slice(), c.as_str()));
        scenethesis_words::category_of_phrase(&phrase_stems(phrase), rows)
    }

    /// The phrases (as word stems) that name each category, its name and its words, longest
    /// first.
    pub fn category_phrases(&self) -> &[(Vec<String>, String)] {
        &self.phrases
    }
}

/// The error for an invalid `entry` of `file`.
fn invalid(file: &'static str, entry: &str, message: String) -> KnowledgeError {
    KnowledgeError::Invalid {
        file,
        entry: entry.to_owned(),
        message,
    }
}

/// Checks the category priors: positive sizes, shelves for shelf and cabinet shapes, and
/// `small` naming a known category.
fn check_priors(priors: &BTreeMap<String, CategoryPrior>) -> Result<(), KnowledgeError> {
    for (name, prior) in priors {
        if prior.size.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
            return Err(invalid(
                CATEGORIES_FILE,
                name,
                "size must be three positive numbers".into(),
            ));
        }
        if matches!(prior.shape, NominalShape::Shelves | NominalShape::Cabinet)
            && prior.shelves == 0
        {
            return Err(invalid(
                CATEGORIES_FILE,
                name,
                "shape needs `shelves` ≥ 1".into(),
            ));
        }
    }
    for (name, prior) in priors {
        if let Some(small) = prior.small.as_deref().filter(|s| !priors.contains_key(*s)) {
            return Err(invalid(
                CATEGORIES_FILE,
                name,
                format!("`small` names unknown category `{small}`"),
            ));
        }
    }
    Ok(())
}

/// The sparse words as stems with their sparsity (a word listed under both reads as empty).
fn sparse_words(words: &SparseWords) -> BTreeMap<String, Sparsity> {
    let levels = [
        (&words.core, Sparsity::Core),
        (&words.empty, Sparsity::Empty),
    ];
    levels
        .into_iter()
        .flat_map(|(list, level)| {
            list.iter()
                .flat_map(|w| phrase_stems(w))
                .map(move |w| (w, level))
        })
        .collect()
}

/// Checks a `ground` of `entry` in `file`: only outdoors, and naming a material of the
/// procedural library (`scenethesis_materials::by_id`).
pub(crate) fn check_ground(
    file: &'static str,
    entry: &str,
    environment: Environment,
    ground: Option<&str>,
) -> Result<(), KnowledgeError> {
    let Some(ground) = ground else {
        return Ok(());
    };
    if environment != Environment::Outdoor {
        return Err(invalid(
            file,
            entry,
            format!("`ground = \"{ground}\"`: only outdoor places have open ground"),
        ));
    }
    if scenethesis_materials::by_id(ground).is_none() {
        return Err(invalid(
            file,
            entry,
            format!("`ground = \"{ground}\"` is not a material of the library"),
        ));
    }
    Ok(())
}

/// Reads and checks one archetype: its size range, object groups, anchor and core.
fn read_archetype(
    raw: RawArchetype,
    known: &dyn Fn(&str) -> bool,
) -> Result<Archetype, KnowledgeError> {
    let entry = raw.name.clone();
    let [x0, x1, z0, z1] = raw.size;
    if !(x0 > 0.0 && x0 <= x1 && z0 > 0.0 && z0 <= z1) {
        return Err(invalid(
            ARCHETYPES_FILE,
            &entry,
            "size must be [x_min, x_max, z_min, z_max] with 0 < min ≤ max".into(),
        ));
    }
    check_ground(
        ARCHETYPES_FILE,
        &entry,
        raw.environment,
        raw.ground.as_deref(),
    )?;
    if raw.environment == Environment::Outdoor && raw.ground.is_none() {
        return Err(invalid(
            ARCHETYPES_FILE,
            &entry,
            "an outdoor archetype needs a `ground` (a library material id)".into(),
        ));
    }
    let objects = read_object_groups(&entry, raw.objects, known)?;
    if !objects
        .iter()
        .any(|g| g.place == Place::Anchor && g.category == raw.anchor)
    {
        return Err(invalid(
            ARCHETYPES_FILE,
            &entry,
            format!("anchor `{}` has no group with place `anchor`", raw.anchor),
        ));
    }
    for c in &raw.core {
        if !objects.iter().any(|g| g.category == *c && g.min >= 1) {
            return Err(invalid(
                ARCHETYPES_FILE,
                &entry,
                format!(
                    "core category `{c}` needs an object group with a minimum count of at least 1"
                ),
            ));
        }
    }
    if !raw.core.is_empty() && raw.source.as_deref().is_none_or(str::is_empty) {
        return Err(invalid(
            ARCHETYPES_FILE,
            &entry,
            "a `core` needs a `source` saying where it comes from".into(),
        ));
    }
    Ok(Archetype {
        phrases: raw
            .words
            .iter()
            .chain(std::iter::once(&raw.name.replace('_', " ")))
            .map(|w| phrase_stems(w))
            .filter(|p| !p.is_empty())
            .collect(),
        name: raw.name,
        environment: raw.environment,
        ground: raw.ground,
        size: raw.size,
        anchor: raw.anchor,
        anchor_place: raw.anchor_place,
        aisle: raw.aisle.unwrap_or(0.6).max(0.6),
        door_clearance: raw.door_clearance.unwrap_or(1.0).max(0.6),
        objects,
        core: raw.core,
        source: raw.source,
    })
}

/// Reads archetype `entry`'s object groups (category, min, max, place), checking each
/// category, count range and place target (planned earlier in the list).
fn read_object_groups(
    entry: &str,
    rows: Vec<(String, u32, u32, String)>,
    known: &dyn Fn(&str) -> bool,
) -> Result<Vec<ObjectGroup>, KnowledgeError> {
    let mut seen: BTreeSet<String> = BTreeSet::new();
    let mut objects = Vec::new();
    for (category, min, max, place_text) in rows {
        let place = Place::parse(&place_text).ok_or_else(|| {
            invalid(
                ARCHETYPES_FILE,
                entry,
                format!("object `{category}`: unknown place `{place_text}`"),
            )
        })?;
        if !known(&category) {
            return Err(invalid(
                ARCHETYPES_FILE,
                entry,
                format!("unknown category `{category}` (not in {CATEGORIES_FILE})"),
            ));
        }
        if min > max {
            return Err(invalid(
                ARCHETYPES_FILE,
                entry,
                format!("object `{category}`: min count {min} > max {max}"),
            ));
        }
        if let Some(target) = place.target() {
            if !seen.contains(target) {
                return Err(invalid(ARCHETYPES_FILE, entry, format!("object `{category}`: place `{place_text}` refers to `{target}`, which is not planned earlier in the list")));
            }
        }
        seen.insert(category.clone());
        objects.push(ObjectGroup {
            category,
            min,
            max,
            place,
        });
    }
    Ok(objects)
}

/// Checks the vocabulary against the categories and archetypes: generic nouns list known
/// categories, and the default archetype exists.
fn check_vocabulary(
    voc: &VocabularyFile,
    archetypes: &[Archetype],
    known: &dyn Fn(&str) -> bool,
) -> Result<(), KnowledgeError> {
    for (word, list) in &voc.generic {
        if let Some(bad) = list.iter().find(|c| !known(c)) {
            return Err(invalid(
                VOCABULARY_FILE,
                word,
                format!("generic noun lists unknown category `{bad}`"),
            ));
        }
    }
    if !archetypes
        .iter()
        .any(|a| a.name == voc.scene_words.default_archetype)
    {
        return Err(invalid(
            VOCABULARY_FILE,
            "scene_words",
            format!(
                "default_archetype `{}` is not an archetype",
                voc.scene_words.default_archetype
            ),
        ));
    }
    Ok(())
}

/// Reads the relation phrases (`phrase = "kind"` or `"kind/modifier"`), longest phrases
/// first, so "in front of" wins over "in".
fn read_relation_phrases(
    table: &BTreeMap<String, String>,
) -> Result<Vec<(Vec<String>, RelationPhrase)>, KnowledgeError> {
    let mut relations = Vec::new();
    for (phrase, value) in table {
        relations.push((phrase_stems(phrase), read_relation_phrase(phrase, value)?));
    }
    relations.sort_by(|a, b| b.0.len().cmp(&a.0.len()).then(a.0.cmp(&b.0)));
    Ok(relations)
}

/// Reads the value of relation `phrase`: a relation kind (or `corner`), with an optional
/// modifier (`head`, `split`, `any` or a wall).
fn read_relation_phrase(phrase: &str, value: &str) -> Result<RelationPhrase, KnowledgeError> {
    let (kind_text, modifier) = match value.split_once('/') {
        Some((k, m)) => (k, Some(m)),
        None => (value, None),
    };
    let corner = kind_text == "corner";
    let kind = if corner {
        Some(RelationKind::AgainstWall)
    } else {
        relation_kind(kind_text)
    };
    let kind = kind.ok_or_else(|| {
        invalid(
            VOCABULARY_FILE,
            phrase,
            format!("unknown relation kind `{kind_text}`"),
        )
    })?;
    let mut rp = RelationPhrase {
        kind,
        corner,
        head: false,
        split: false,
        wall: None,
    };
    match modifier {
        None => {}
        Some("head") => rp.head = true,
        Some("split") => rp.split = true,
        Some("any") => rp.wall = Some(String::new()),
        Some(w) if w.starts_with("wall_") => rp.wall = Some(w.to_owned()),
        Some(other) => {
            return Err(invalid(
                VOCABULARY_FILE,
                phrase,
                format!("unknown modifier `{other}`"),
            ))
        }
    }
    Ok(rp)
}

fn category_phrases_of(categories: &BTreeMap<String, CategoryPrior>) -> Vec<(Vec<String>, String)> {
    let mut out = Vec::new();
    for (name, prior) in categories {
        out.push((phrase_stems(&name.replace('_', " ")), name.clone()));
        for w in &prior.words {
            out.push((phrase_stems(w), name.clone()));
        }
    }
    out.retain(|(p, _)| !p.is_empty());
    out.sort_by(|a, b| b.0.len().cmp(&a.0.len()).then(a.cmp(b)));
    out
}
