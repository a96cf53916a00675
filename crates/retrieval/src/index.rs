//! The asset index and its ranking.

use std::collections::BTreeMap;
use std::fmt;

use scenethesis_models::{ProviderError, TextEmbedder};
use scenethesis_procedural::catalog;
use scenethesis_scene_graph::AssetRef;
use scenethesis_scene_graph::{AssetInfo, Placement};

use crate::text::{normalise, word_similarity, words};

/// Why a candidate matched.
#[derive(Debug, Clone, PartialEq)]
pub enum MatchReason {
    /// The query is the category name.
    ExactCategory,
    /// The query is this synonym or alias of the category.
    Synonym(String),
    /// The query's words overlap this name's words (after typo-tolerant matching).
    Fuzzy(String),
    /// The attached embedder found the query close to the category (cosine similarity).
    Semantic(f32),
}

impl fmt::Display for MatchReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MatchReason::ExactCategory => write!(f, "exact category"),
            MatchReason::Synonym(s) => write!(f, "synonym \"{s}\""),
            MatchReason::Fuzzy(s) => write!(f, "word match with \"{s}\""),
            MatchReason::Semantic(c) => write!(f, "semantic similarity {c:.3}"),
        }
    }
}

/// One ranked result of [`AssetIndex::search`].
#[derive(Debug, Clone, PartialEq)]
pub struct Candidate {
    /// The asset to use: a procedural generator with a seed, or an imported file.
    pub asset: AssetRef,
    /// Its category.
    pub category: String,
    /// Where it is normally placed.
    pub placement: Placement,
    /// Score in [0, 1]; higher is better.
    pub score: f32,
    /// Why it matched.
    pub reason: MatchReason,
}

/// Why an embedder failed.
#[derive(Debug, thiserror::Error)]
pub enum EmbedError {
    /// The embedding model or service failed.
    #[error("text embedding failed: {0}")]
    Failed(#[from] ProviderError),
    /// The embedder returned the wrong number of vectors.
    #[error("embedder returned {got} vectors for {expected} texts")]
    Count {
        /// Texts sent.
        expected: usize,
        /// Vectors received.
        got: usize,
    },
}

/// A group of assets sharing one category, with the names it answers to.
#[derive(Debug, Clone)]
struct Entry {
    category: String,
    placement: Placement,
    /// Normalised names: the category first, then synonyms and aliases, each with its words as
    /// ids into [`AssetIndex::vocabulary`].
    names: Vec<(String, Vec<u32>)>,
    /// Whether a built-in generator exists for the category.
    builtin: bool,
    /// Imported assets of this category.
    imported: Vec<AssetRef>,
}

/// Index over the built-in categories and imported assets; answers text queries with ranked
/// [`Candidate`]s.
pub struct AssetIndex {
    entries: Vec<Entry>,
    by_category: BTreeMap<String, usize>,
    embedder: Option<Box<dyn TextEmbedder>>,
    entry_vectors: Vec<Vec<f32>>,
    /// The words of the category table ([`catalog::words`]), as [`words`], with their categories.
    aliases: Vec<(Vec<String>, &'static str)>,
    /// Every distinct word of every name, so a query word is compared with each only once.
    vocabulary: Vec<String>,
    word_ids: BTreeMap<String, u32>,
}

impl fmt::Debug for AssetIndex {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("AssetIndex")
            .field("categories", &self.entries.len())
            .field("semantic", &self.embedder.is_some())
            .finish()
    }
}

/// Scores of the ranking stages.
const EXACT: f32 = 1.0;
const SYNONYM: f32 = 0.95;
const FUZZY_WEIGHT: f32 = 0.85;
const ALIASED_FUZZY_WEIGHT: f32 = 0.8;
const SEMANTIC_WEIGHT: f32 = 0.85;
/// Candidates scoring below this are not returned.
const MIN_SCORE: f32 = 0.3;
/// Imported assets rank just above the built-in generator of the same category: the user
/// brought them for a reason. (Scores are capped at 1, so an exact match ties with the
/// generator; ties put imported assets first.)
const IMPORTED_BONUS: f32 = 0.01;

impl AssetIndex {
    /// An index of every built-in category.
    pub fn builtin() -> Self {
        let mut index = Self::empty();
        for c in scenethesis_procedural::catalog::categories() {
            let i = index.entry(c.name, c.placement);
            index.entries[i].builtin = true;
            for s in c.synonyms {
                index.add_name(i, s);
            }
        }
        index
    }

    /// An index of built-in categories plus the given imported assets.
    pub fn with_imported<'a>(assets: impl IntoIterator<Item = &'a AssetInfo>) -> Self {
        let mut index = Self::builtin();
        for info in assets {
            index.add_imported(info);
        }
        index
    }

    /// An index with nothing in it.
    pub fn empty() -> Self {
        Self {
            entries: Vec::new(),
            by_category: BTreeMap::new(),
            embedder: None,
            entry_vectors: Vec::new(),
            aliases: catalog::words().map(|(a, c)| (words(a), c)).collect(),
            vocabulary: Vec::new(),
            word_ids: BTreeMap::new(),
        }
    }

    /// Adds an imported asset (its `source`, category and synonyms are used). Call
    /// [`AssetIndex::set_embedder`] again afterwards if one is attached, to embed new categories.
    pub fn add_imported(&mut self, info: &AssetInfo) {
        let i = self.entry(&info.category, info.placement);
        for s in &info.synonyms {
            self.add_name(i, s);
        }
        self.entries[i].imported.push(info.source.clone());
    }

    /// Number of categories in the index.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether the index holds no category.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The categories in the index, in insertion order.
    pub fn categories(&self) -> impl Iterator<Item = &str> {
        self.entries.iter().map(|e| e.category.as_str())
    }

    /// Attaches a semantic embedder and embeds every category's description once
    /// (`"sofa: couch, settee"`). Later searches re-rank by cosine similarity to the query.
    pub fn set_embedder(&mut self, embedder: Box<dyn TextEmbedder>) -> Result<(), EmbedError> {
        let texts: Vec<String> = self.entries.iter().map(describe).collect();
        let refs: Vec<&str> = texts.iter().map(String::as_str).collect();
        let vectors = embedder.embed(&refs)?;
        if vectors.len() != refs.len() {
            return Err(EmbedError::Count {
                expected: refs.len(),
                got: vectors.len(),
            });
        }
        self.entry_vectors = vectors;
        self.embedder = Some(embedder);
        Ok(())
    }

    /// The best `limit` candidates for `query`, best first. Equal scores are ordered by `seed`,
    /// and built-in candidates carry it as their procedural seed (so a search seeded with
    /// [`scenethesis_procedural::catalog::object_seed`] yields the object's own asset). If an attached
    /// embedder fails on the query, the lexical ranking is returned (and a warning logged).
    pub fn search(&self, query: &str, limit: usize, seed: u64) -> Vec<Candidate> {
        match self.try_search(query, limit, seed) {
            Ok(c) => c,
            Err(e) => {
                tracing::warn!("semantic stage skipped for {query:?}: {e}");
                self.rank(query, limit, seed, None)
            }
        }
    }

    /// Like [`AssetIndex::search`], but reports an embedder failure instead of falling back.
    pub fn try_search(
        &self,
        query: &str,
        limit: usize,
        seed: u64,
    ) -> Result<Vec<Candidate>, EmbedError> {
        let semantic = match &self.embedder {
            Some(embedder) if !self.entry_vectors.is_empty() => {
                let v = embedder.embed(&[query])?;
                let q = v.into_iter().next().ok_or(EmbedError::Count {
                    expected: 1,
                    got: 0,
                })?;
                Some(
                    self.entry_vectors
                        .iter()
                        .map(|e| cosine(&q, e))
                        .collect::<Vec<f32>>(),
                )
            }
            _ => None,
        };
        Ok(self.rank(query, limit, seed, semantic.as_deref()))
    }

    fn rank(
        &self,
        query: &str,
        limit: usize,
        seed: u64,
        semantic: Option<&[f32]>,
    ) -> Vec<Candidate> {
        let q = normalise(query);
        let q_words = words(query);
        // Each query word that is an alias, replaced by its category's words.
        let aliased: Vec<String> = q_words
            .iter()
            .flat_map(|w| match self.alias_of(w) {
                Some(category) => words(category),
                None => vec![w.clone()],
            })
            .collect();
        let direct = self.similarities(&q_words);
        let via_alias = if aliased == q_words {
            None
        } else {
            Some(self.similarities(&aliased))
        };
        let mut scored: Vec<(f32, MatchReason, usize)> = Vec::new();
        for (i, entry) in self.entries.iter().enumerate() {
            let (mut score, mut reason) = lexical(entry, &q, &direct, via_alias.as_deref());
            if let Some(sims) = semantic {
                let s = sims.get(i).copied().unwrap_or(0.0);
                if score < SYNONYM && SEMANTIC_WEIGHT * s > score {
                    score = SEMANTIC_WEIGHT * s;
                    reason = MatchReason::Semantic(s);
                }
            }
            if score >= MIN_SCORE {
                scored.push((score, reason, i));
            }
        }
        // (candidate, rank among equal scores: imported before built-in, then the seeded tie).
        let mut candidates: Vec<(Candidate, (bool, u64))> = Vec::new();
        for (score, reason, i) in scored {
            let entry = &self.entries[i];
            if entry.builtin {
                candidates.push((
                    Candidate {
                        asset: AssetRef::Procedural {
                            generator: entry.category.clone(),
                            seed,
                            look: None,
                        },
                        category: entry.category.clone(),
                        placement: entry.placement,
                        score,
                        reason: reason.clone(),
                    },
                    (true, mix(seed ^ fnv(&entry.category))),
                ));
            }
            for asset in &entry.imported {
                let tie = mix(seed ^ fnv(&asset.to_string()));
                candidates.push((
                    Candidate {
                        asset: asset.clone(),
                        category: entry.category.clone(),
                        placement: entry.placement,
                        score: (score + IMPORTED_BONUS).min(1.0),
                        reason: reason.clone(),
                    },
                    (false, tie),
                ));
            }
        }
        candidates.sort_by(|(a, ta), (b, tb)| b.score.total_cmp(&a.score).then(ta.cmp(tb)));
        candidates.truncate(limit);
        candidates.into_iter().map(|(c, _)| c).collect()
    }

    /// The entry for `category`, created if new.
    fn entry(&mut self, category: &str, placement: Placement) -> usize {
        if let Some(&i) = self.by_category.get(category) {
            return i;
        }
        self.entries.push(Entry {
            category: category.to_owned(),
            placement,
            names: Vec::new(),
            builtin: false,
            imported: Vec::new(),
        });
        let i = self.entries.len() - 1;
        self.by_category.insert(category.to_owned(), i);
        self.add_name(i, category);
        // An imported category named like a built-in one answers to the table's words too.
        for (word, target) in catalog::words() {
            if target == category {
                self.add_name(i, word);
            }
        }
        i
    }

    /// The category a normalised alias stands for.
    fn alias_of(&self, word: &str) -> Option<&'static str> {
        let rows = self.aliases.iter().map(|(alias, c)| (alias.as_slice(), *c));
        scenethesis_words::category_of_phrase(&[word.to_owned()], rows)
    }

    fn add_name(&mut self, i: usize, name: &str) {
        let n = normalise(name);
        if !n.is_empty() && !self.entries[i].names.iter().any(|(m, _)| *m == n) {
            let ids = words(&n)
                .into_iter()
                .map(|w| match self.word_ids.get(&w) {
                    Some(&id) => id,
                    None => {
                        let id = self.vocabulary.len() as u32;
                        self.word_ids.insert(w.clone(), id);
                        self.vocabulary.push(w);
                        id
                    }
                })
                .collect();
            self.entries[i].names.push((n, ids));
        }
    }

    /// For each query word, its similarity to every vocabulary word.
    fn similarities(&self, query: &[String]) -> Vec<Vec<f32>> {
        query
            .iter()
            .map(|q| {
                self.vocabulary
                    .iter()
                    .map(|w| word_similarity(q, w))
                    .collect()
            })
            .collect()
    }
}

/// The lexical score of one entry: exact, synonym, fuzzy or aliased fuzzy. `direct[j][w]` is
/// the similarity of query word `j` to vocabulary word `w`; `via_alias` the same for the query
/// with aliased words replaced.
fn lexical(
    entry: &Entry,
    q: &str,
    direct: &[Vec<f32>],
    via_alias: Option<&[Vec<f32>]>,
) -> (f32, MatchReason) {
    let mut best = (0.0f32, MatchReason::Fuzzy(String::new()));
    for (k, (name, ids)) in entry.names.iter().enumerate() {
        if name == q {
            return if k == 0 {
                (EXACT, MatchReason::ExactCategory)
            } else {
                (SYNONYM, MatchReason::Synonym(name.clone()))
            };
        }
        let mut s = FUZZY_WEIGHT * overlap(direct, ids);
        if let Some(aliased) = via_alias {
            s = s.max(ALIASED_FUZZY_WEIGHT * overlap(aliased, ids));
        }
        if s > best.0 {
            best = (s, MatchReason::Fuzzy(name.clone()));
        }
    }
    best
}

/// [`crate::text::overlap_score`] over precomputed word similarities.
fn overlap(sims: &[Vec<f32>], name: &[u32]) -> f32 {
    if sims.is_empty() || name.is_empty() {
        return 0.0;
    }
    let recall = name
        .iter()
        .map(|&w| {
            sims.iter()
                .map(|row| row[w as usize])
                .fold(0.0f32, f32::max)
        })
        .sum::<f32>()
        / name.len() as f32;
    let precision = sims
        .iter()
        .map(|row| name.iter().map(|&w| row[w as usize]).fold(0.0f32, f32::max))
        .sum::<f32>()
        / sims.len() as f32;
    0.7 * recall + 0.3 * precision
}

/// The text embedded for an entry: its category and names.
fn describe(entry: &Entry) -> String {
    let names: Vec<&str> = entry
        .names
        .iter()
        .skip(1)
        .map(|(n, _)| n.as_str())
        .collect();
    if names.is_empty() {
        normalise(&entry.category)
    } else {
        format!("{}: {}", normalise(&entry.category), names.join(", "))
    }
}

fn cosine(a: &[f32], b: &[f32]) -> f32 {
    let n = a.len().min(b.len());
    let dot: f32 = (0..n).map(|i| a[i] * b[i]).sum();
    let na = a.iter().map(|x| x * x).sum::<f32>().sqrt();
    let nb = b.iter().map(|x| x * x).sum::<f32>().sqrt();
    if na == 0.0 || nb == 0.0 {
        0.0
    } else {
        (dot / (na * nb)).clamp(-1.0, 1.0)
    }
}

/// The project's FNV-1a hash of a string (stable across platforms and runs).
fn fnv(s: &str) -> u64 {
    scenethesis_scene_graph::fnv1a64(s.as_bytes())
}

/// One SplitMix64 step: spreads nearby seeds over the whole range.
fn mix(z: u64) -> u64 {
    scenethesis_scene_graph::mix64(z.wrapping_add(scenethesis_scene_graph::GOLDEN_GAMMA))
}

#[cfg(test)]
mod tests;
