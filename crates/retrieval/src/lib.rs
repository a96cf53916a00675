//! Asset retrieval: an index over built-in and user-supplied assets that ranks candidates for a
//! text query by category, synonyms and semantic similarity.
//!
//! Ranking stages, best first:
//! 1. the query names a category exactly (`"coffee table"`, `"coffee_tables"`);
//! 2. the query is a synonym: the category's own synonyms, the imported asset's synonyms, or the
//!    words of the one category table that the planner reads too
//!    ([`scenethesis_procedural::catalog::words`]: couch → sofa, bookcase → bookshelf, TV →
//!    television, …);
//! 3. fuzzy word match: overlap of the query's words with a name's words, tolerant of typos
//!    (edit distance), and with single aliased words replaced (`"big tv"` → `big television`);
//! 4. when a [`TextEmbedder`] is attached, cosine similarity of embeddings lifts candidates the
//!    lexical stages missed (`"somewhere to sleep"` → bed).
//!
//! Every query is normalised first (case, `_`/`-`, plurals). Candidates that score the same are
//! ordered by the search seed, and a built-in category's candidate carries the search seed as
//! its procedural seed, so different seeds give varied but reproducible scenes.
//!
//! ```
//! use scenethesis_retrieval::{AssetIndex, AssetQuery, AssetSource, MatchReason, RetrievalSource};
//!
//! let index = AssetIndex::builtin();
//! let best = &index.search("couch", 1, 0)[0];
//! assert_eq!(best.category, "sofa");
//! assert!(matches!(best.reason, MatchReason::Synonym(_)));
//! // The same query and seed always rank the same way.
//! assert_eq!(index.search("couch", 3, 7), index.search("couch", 3, 7));
//!
//! // The pipeline's asset source: one asset per planned object.
//! let source = RetrievalSource::default();
//! let asset = source.retrieve(&AssetQuery::new("sofa_0", "sofa"), 0)?;
//! assert_eq!(asset.info.category, "sofa");
//! assert!(asset.mesh.triangle_count() > 0);
//! # Ok::<(), scenethesis_retrieval::AssetError>(())
//! ```

#![warn(missing_docs)]

mod index;
mod source;
pub mod text;

pub use index::{AssetIndex, Candidate, EmbedError, MatchReason};
/// The embedding seam retrieval ranks by meaning with: the one trait of `scenethesis-models`.
pub use scenethesis_models::TextEmbedder;
/// The generator seed of an object at a variant: the one rule, owned by the procedural
/// catalog, that the sources here and the guide's catalog metadata share.
pub use scenethesis_procedural::catalog::object_seed;
pub use source::{AssetError, AssetQuery, AssetSource, CatalogSource, RetrievalSource};
