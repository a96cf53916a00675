//! The registry of built-in procedural categories.
//!
//! Everything known about a category — its name, the words people use for it, where it is
//! placed, its documented size range and the planner's prior — lives in one table,
//! `data/categories.toml` ([`CATEGORIES_TOML`]), which this crate, retrieval and the planner all
//! read. The generators live next to their geometry code and are joined to their rows by name.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::OnceLock;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use scenethesis_scene_graph::AssetRef;
use serde::Deserialize;

use scenethesis_scene_graph::{Asset, Placement};

/// The embedded category table (`crates/procedural/data/categories.toml`).
pub const CATEGORIES_TOML: &str = include_str!("../data/categories.toml");

/// The path of the table in the source tree, for messages.
const TABLE_FILE: &str = "crates/procedural/data/categories.toml";

pub use crate::category::{Category, Generator};

/// A category table that cannot be used, naming the row and field at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TableError {
    /// The TOML does not parse or a row does not match the schema.
    #[error("{TABLE_FILE}: {0}")]
    Parse(String),
    /// A row is inconsistent.
    #[error("{TABLE_FILE}: category `{category}`: {message}")]
    Invalid {
        /// Which row.
        category: String,
        /// What is wrong and what was expected.
        message: String,
    },
}

/// One row of the category table, as far as the asset library is concerned (the planner's
/// `plan` prior is read by `scenethesis-agents`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CategoryRow {
    /// Where the category is normally placed.
    pub placement: Placement,
    /// Documented size range, as in [`Category::size_range`].
    pub size_range: [[f32; 2]; 3],
    /// Other names people use for the category.
    #[serde(default)]
    pub words: Vec<String>,
    /// The planner's prior, kept as TOML for `scenethesis-agents` to read.
    pub plan: toml::Table,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TableFile {
    category: BTreeMap<String, CategoryRow>,
}

/// A word folded for comparison: lower case, `_` and `-` as spaces, single spaces.
pub fn fold_word(word: &str) -> String {
    word.to_lowercase()
        .replace(['_', '-'], " ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// Parses and checks a category table: sizes are ordered and positive, and no word names two
/// categories or another category's name.
pub fn parse_table(text: &str) -> Result<BTreeMap<String, CategoryRow>, TableError> {
    let file: TableFile = toml::from_str(text).map_err(|e| TableError::Parse(e.to_string()))?;
    let invalid = |category: &str, message: String| TableError::Invalid {
        category: category.to_owned(),
        message,
    };
    let names: BTreeMap<String, &str> = file
        .category
        .keys()
        .map(|n| (fold_word(n), n.as_str()))
        .collect();
    let mut owner: BTreeMap<String, &str> = BTreeMap::new();
    for (name, row) in &file.category {
        for (axis, [lo, hi]) in row.size_range.iter().enumerate() {
            if !(lo.is_finite() && hi.is_finite() && *lo > 0.0 && lo <= hi) {
                return Err(invalid(
                    name,
                    format!("size_range[{axis}] = [{lo}, {hi}]: expected 0 < min <= max"),
                ));
            }
        }
        for word in &row.words {
            let key = fold_word(word);
            if key.is_empty() {
                return Err(invalid(name, "an empty word".into()));
            }
            if let Some(other) = names.get(&key) {
                return Err(invalid(
                    name,
                    format!("word `{word}` is the name of category `{other}`"),
                ));
            }
            if let Some(other) = owner.insert(key, name) {
                return Err(invalid(
                    name,
                    format!("word `{word}` also belongs to category `{other}`"),
                ));
            }
        }
    }
    Ok(file.category)
}

/// The embedded table, parsed once.
///
/// # Panics
/// Never in a released build: the embedded table is checked by this crate's tests.
pub fn table() -> &'static BTreeMap<String, CategoryRow> {
    static TABLE: OnceLock<BTreeMap<String, CategoryRow>> = OnceLock::new();
    TABLE.get_or_init(|| {
        parse_table(CATEGORIES_TOML).unwrap_or_else(|e| panic!("embedded table is broken: {e}"))
    })
}

/// Every built-in generator by category name, furniture first, in a stable order.
fn generators() -> impl Iterator<Item = &'static (&'static str, Generator)> {
    crate::furniture::GENERATORS
        .iter()
        .chain(crate::items::GENERATORS)
        .chain(crate::outdoor::GENERATORS)
}

/// Joins the generators to their rows. Each generator needs exactly one row and each row one
/// generator.
fn join() -> Result<Vec<Category>, TableError> {
    let rows = table();
    let mut seen = BTreeSet::new();
    let mut out = Vec::new();
    for &(name, generate) in generators() {
        if !seen.insert(name) {
            return Err(TableError::Invalid {
                category: name.to_owned(),
                message: "two generators share this name".into(),
            });
        }
        let row = rows.get(name).ok_or_else(|| TableError::Invalid {
            category: name.to_owned(),
            message: "has a generator but no row".into(),
        })?;
        // Leaked once per process: the registry lives for the whole program.
        let synonyms: Vec<&'static str> = row
            .words
            .iter()
            .map(|w| &*Box::leak(w.clone().into_boxed_str()))
            .collect();
        out.push(Category {
            name,
            synonyms: Box::leak(synonyms.into_boxed_slice()),
            placement: row.placement,
            size_range: row.size_range,
            generate,
        });
    }
    if let Some(orphan) = rows.keys().find(|n| !seen.contains(n.as_str())) {
        return Err(TableError::Invalid {
            category: orphan.clone(),
            message: "has a row but no generator".into(),
        });
    }
    Ok(out)
}

/// Checks that every generator has exactly one row of the embedded table and every row a
/// generator.
pub fn check_registry() -> Result<(), TableError> {
    join().map(|_| ())
}

/// Every built-in category, furniture first, in a stable order.
pub fn categories() -> impl Iterator<Item = &'static Category> {
    static REGISTRY: OnceLock<Vec<Category>> = OnceLock::new();
    REGISTRY
        .get_or_init(|| join().unwrap_or_else(|e| panic!("category registry is broken: {e}")))
        .iter()
}

/// The built-in category with this canonical name.
pub fn category(name: &str) -> Option<&'static Category> {
    categories().find(|c| c.name == name)
}

/// Every word of the table with the category it names (not the names themselves), in table
/// order: the aliases retrieval matches and the planner's category words.
pub fn words() -> impl Iterator<Item = (&'static str, &'static str)> {
    categories().flat_map(|c| c.synonyms.iter().map(move |w| (*w, c.name)))
}

/// Generates the asset of `category` for `seed`: the same pair always gives the same asset.
pub fn generate(category: &Category, seed: u64) -> Asset {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ name_hash(category.name));
    let mut asset = (category.generate)(&mut rng);
    asset.info.source = AssetRef::Procedural {
        generator: category.name.to_owned(),
        seed,
        look: None,
    };
    asset.info.category = category.name.to_owned();
    asset.info.synonyms = category.synonyms.iter().map(|s| s.to_string()).collect();
    asset
}

/// Generates the asset of `category` for `seed` wearing `look` (see [`crate::looks`]): the
/// geometry of [`generate`] with the look's materials, and the look recorded in its source so
/// the reference regenerates the same asset. A plain look is no look.
pub fn generate_with_look(
    category: &Category,
    seed: u64,
    look: Option<&scenethesis_scene_graph::AssetLook>,
) -> Asset {
    let mut asset = generate(category, seed);
    if let Some(look) = look.filter(|l| !l.is_plain()) {
        crate::materials::apply_look(&mut asset, look);
        asset.info.source = AssetRef::Procedural {
            generator: category.name.to_owned(),
            seed,
            look: Some(look.clone()),
        };
    }
    asset
}

/// The generator seed of object `id` at `variant`: the one rule for which seed an object's
/// built-in asset is generated with, read by everyone who generates or sizes it — the
/// guide's catalog metadata (`scenethesis_agents::CatalogAssets`, variant = the scene seed) and
/// retrieval's sources (variant = the run's seed plus the re-plan variant) — so the asset a
/// layout is planned with is the asset retrieval delivers. The project's FNV-1a of the id,
/// mixed with the variant by the SplitMix64 output function so neighbouring variants give
/// unrelated seeds. The category is not part of it: [`generate`] mixes that in itself.
///
/// ```
/// use scenethesis_procedural::catalog::{category, generate, object_seed};
///
/// assert_eq!(object_seed("mug_0", 3), object_seed("mug_0", 3));
/// assert_ne!(object_seed("mug_0", 3), object_seed("mug_0", 4));
/// assert_ne!(object_seed("mug_0", 3), object_seed("mug_1", 3));
/// let mug = generate(category("mug").unwrap(), object_seed("mug_0", 3));
/// assert_eq!(mug.info.source.to_string(), format!("mug#{}", object_seed("mug_0", 3)));
/// ```
pub fn object_seed(id: &str, variant: u64) -> u64 {
    use scenethesis_scene_graph::{fnv1a64, mix64, GOLDEN_GAMMA};
    mix64(fnv1a64(id.as_bytes()) ^ variant.wrapping_mul(GOLDEN_GAMMA))
}

/// A stable hash of a name (the project's FNV-1a), so categories sharing a seed still differ.
fn name_hash(name: &str) -> u64 {
    scenethesis_scene_graph::fnv1a64(name.as_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_generator_has_exactly_one_row_and_every_row_a_generator() {
        check_registry().unwrap();
        assert_eq!(categories().count(), table().len());
    }

    #[test]
    fn the_table_rejects_shared_words_and_bad_ranges() {
        let row = |words: &str, range: &str| {
            format!(
                "placement = \"floor\"\nsize_range = {range}\nwords = [{words}]\nplan = {{ size = [1.0, 1.0, 1.0], shape = \"none\" }}\n"
            )
        };
        let ok = "[[0.1, 0.2], [0.1, 0.2], [0.1, 0.2]]";
        let shared = format!(
            "[category.a]\n{}[category.b]\n{}",
            row("\"thing\"", ok),
            row("\"Thing\"", ok)
        );
        let e = parse_table(&shared).unwrap_err().to_string();
        assert!(e.contains("`Thing` also belongs to category `a`"), "{e}");
        let named = format!("[category.big_box]\n{}", row("\"big box\"", ok));
        let e = parse_table(&named).unwrap_err().to_string();
        assert!(e.contains("is the name of category `big_box`"), "{e}");
        let bad = format!(
            "[category.a]\n{}",
            row("", "[[0.3, 0.2], [0.1, 0.2], [0.1, 0.2]]")
        );
        let e = parse_table(&bad).unwrap_err().to_string();
        assert!(e.contains("category `a`: size_range[0]"), "{e}");
        let unknown = "[category.a]\nplacement = \"floor\"\nsize = 1\n";
        assert!(parse_table(unknown).is_err());
    }
}
