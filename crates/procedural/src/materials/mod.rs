//! Materials of the generated assets: the palettes (families of plausible materials an asset
//! picks from per seed), fixed materials, and looks (a room style's material per family and an
//! object's requested colours and materials, applied after generation). Their names are what
//! the texture library (`scenethesis-materials`) resolves into patterns at export and render
//! time; the tests here and in `tests/catalog.rs` keep every name resolvable.

#[cfg(test)]
mod library_names;
mod look;
mod palette;

pub use look::{apply_look, family_of, surface_material};
pub use palette::{fixed_material, named_material, pick_material, Palette};
