//! Built-in furniture generators.

use crate::catalog::Category;

/// The furniture categories of the registry.
pub(crate) const CATEGORIES: &[Category] = &[];
