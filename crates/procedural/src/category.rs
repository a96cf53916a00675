//! The type of one built-in category and of its generator, below both the registry
//! ([`crate::catalog`]) and the generator tables (furniture, items, outdoor) that fill it.

use rand_chacha::ChaCha8Rng;

use scenethesis_scene_graph::{Asset, Placement};

/// A builder of one asset from the seeded generator it is given.
pub type Generator = fn(&mut ChaCha8Rng) -> Asset;

/// One built-in category: its names, placement and generator.
#[derive(Debug, Clone, Copy)]
pub struct Category {
    /// Canonical name (see `docs/asset-categories.md`).
    pub name: &'static str,
    /// Other names people use for the category (`bookcase` for `bookshelf`): the `words` of its
    /// row in [`crate::catalog::CATEGORIES_TOML`], which retrieval and the planner both resolve to it.
    pub synonyms: &'static [&'static str],
    /// Where the category is normally placed.
    pub placement: Placement,
    /// Documented extent of the generated assets in metres, as `[min, max]` along x (width),
    /// y (height) and z (depth), over all seeds at scale 1. Crate tests check that every
    /// generated asset's [`scenethesis_scene_graph::AssetInfo::size`] lies inside it.
    pub size_range: [[f32; 2]; 3],
    /// Builds one asset; all randomness comes from the seeded generator passed in. The
    /// registry fills in [`scenethesis_scene_graph::AssetInfo::source`], `category` and `synonyms` afterwards.
    pub generate: Generator,
}
