//! Materials of the generated assets: the palettes (families of plausible materials an
//! asset picks from per seed) and fixed materials. Their names are what the texture library
//! (`scenethesis-materials`) resolves into patterns at export and render time; the tests here
//! and in `tests/catalog.rs` keep every name resolvable.

#[cfg(test)]
mod library_names;
mod palette;

pub use palette::{fixed_material, pick_material, Palette};
