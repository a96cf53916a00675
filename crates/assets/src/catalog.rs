//! The registry of built-in procedural categories.

use rand_chacha::ChaCha8Rng;

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
    /// Builds one asset; all randomness comes from the seeded generator passed in.
    pub generate: fn(&mut ChaCha8Rng) -> Asset,
}
