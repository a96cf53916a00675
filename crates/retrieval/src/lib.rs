//! Asset retrieval: an index over built-in and user-supplied assets that ranks candidates for a
//! text query by category, synonyms and semantic similarity.
