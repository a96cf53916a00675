//! Materials of the generated assets. Today the palettes (families of plausible materials an
//! asset picks from per seed) and fixed materials; a material library belongs here beside them.

mod palette;

pub use palette::{fixed_material, pick_material, Palette};
