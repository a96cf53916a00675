//! The registry of built-in procedural categories.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use scenethesis_scene_graph::AssetRef;

use crate::{Asset, Placement};

/// One built-in category: its names, placement and generator.
#[derive(Debug, Clone, Copy)]
pub struct Category {
    /// Canonical name (see `docs/asset-categories.md`).
    pub name: &'static str,
    /// Other names retrieval should match (`bookcase` for `bookshelf`).
    pub synonyms: &'static [&'static str],
    /// Where the category is normally placed.
    pub placement: Placement,
    /// Documented extent of the generated assets in metres, as `[min, max]` along x (width),
    /// y (height) and z (depth), over all seeds at scale 1. Crate tests check that every
    /// generated asset's [`crate::AssetInfo::size`] lies inside it.
    pub size_range: [[f32; 2]; 3],
    /// Builds one asset; all randomness comes from the seeded generator passed in. The
    /// registry fills in [`crate::AssetInfo::source`], `category` and `synonyms` afterwards.
    pub generate: fn(&mut ChaCha8Rng) -> Asset,
}

/// Every built-in category, furniture first, in a stable order.
pub fn categories() -> impl Iterator<Item = &'static Category> {
    crate::furniture::CATEGORIES
        .iter()
        .chain(crate::items::CATEGORIES)
        .chain(crate::outdoor::CATEGORIES)
}

/// The built-in category with this canonical name.
pub fn category(name: &str) -> Option<&'static Category> {
    categories().find(|c| c.name == name)
}

/// Generates the asset of `category` for `seed`: the same pair always gives the same asset.
pub fn generate(category: &Category, seed: u64) -> Asset {
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ name_hash(category.name));
    let mut asset = (category.generate)(&mut rng);
    asset.info.source = AssetRef::Procedural {
        generator: category.name.to_owned(),
        seed,
    };
    asset.info.category = category.name.to_owned();
    asset.info.synonyms = category.synonyms.iter().map(|s| s.to_string()).collect();
    asset
}

/// A stable hash of a name (the project's FNV-1a), so categories sharing a seed still differ.
fn name_hash(name: &str) -> u64 {
    scenethesis_scene_graph::fnv1a64(name.as_bytes())
}
