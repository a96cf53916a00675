//! Built-in items generators.

use crate::catalog::Category;

/// The items categories of the registry.
pub(crate) const CATEGORIES: &[Category] = &[];
