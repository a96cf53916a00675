//! Built-in outdoor generators.

use crate::catalog::Category;

/// The outdoor categories of the registry.
pub(crate) const CATEGORIES: &[Category] = &[];
