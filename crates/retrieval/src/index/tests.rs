use super::*;
use scenethesis_models::ProviderErrorKind;

/// An index with a handful of categories, independent of what the built-in library holds.
fn small_index() -> AssetIndex {
    let mut index = AssetIndex::empty();
    for (category, synonyms, placement) in [
        ("sofa", vec!["couch"], Placement::Floor),
        ("bookshelf", vec![], Placement::Floor),
        ("television", vec!["flat screen"], Placement::Surface),
        ("refrigerator", vec![], Placement::Floor),
        ("chair", vec![], Placement::Floor),
        ("dining_chair", vec![], Placement::Floor),
        ("office_chair", vec![], Placement::Floor),
        ("coffee_table", vec![], Placement::Floor),
        ("table_lamp", vec![], Placement::Surface),
        ("bed", vec![], Placement::Floor),
        ("mug", vec!["coffee mug"], Placement::Surface),
    ] {
        index.add_imported(&info(
            category,
            &synonyms,
            placement,
            &format!("{category}_a"),
        ));
    }
    index
}

fn info(category: &str, synonyms: &[&str], placement: Placement, id: &str) -> AssetInfo {
    AssetInfo {
        source: AssetRef::Imported {
            id: id.into(),
            path: format!("lib/{id}.glb"),
        },
        category: category.into(),
        synonyms: synonyms.iter().map(|s| s.to_string()).collect(),
        size: [1.0; 3],
        placement,
        front: [0.0, 0.0, 1.0],
        support_surfaces: Vec::new(),
        scale_range: [0.9, 1.1],
        joints: Vec::new(),
        opening_bounds: None,
    }
}

fn top(index: &AssetIndex, query: &str) -> Candidate {
    index
        .search(query, 5, 0)
        .into_iter()
        .next()
        .unwrap_or_else(|| panic!("no candidate for {query:?}"))
}

#[test]
fn exact_category_plural_and_separator_forms_match_first() {
    let index = small_index();
    for q in ["coffee_table", "Coffee Tables", "coffee-table"] {
        let c = top(&index, q);
        assert_eq!(c.category, "coffee_table", "{q}");
        assert_eq!(c.reason, MatchReason::ExactCategory, "{q}");
    }
    assert_eq!(top(&index, "mugs").category, "mug");
}

#[test]
fn synonyms_and_aliases_map_to_their_category() {
    let index = small_index();
    for (q, category) in [
        ("couch", "sofa"),
        ("settee", "sofa"),
        ("bookcase", "bookshelf"),
        ("book cases", "bookshelf"),
        ("TV", "television"),
        ("fridge", "refrigerator"),
        ("flat screen", "television"),
    ] {
        let c = top(&index, q);
        assert_eq!(c.category, category, "{q}");
        assert!(
            matches!(c.reason, MatchReason::Synonym(_)),
            "{q}: {:?}",
            c.reason
        );
    }
}

#[test]
fn fuzzy_word_match_handles_extra_words_typos_and_aliased_words() {
    let index = small_index();
    let c = top(&index, "red wooden chair");
    assert_eq!(c.category, "chair");
    assert!(matches!(c.reason, MatchReason::Fuzzy(_)));
    assert_eq!(top(&index, "bookshelv").category, "bookshelf");
    assert_eq!(top(&index, "a big tv").category, "television");
    assert_eq!(top(&index, "comfy old couch").category, "sofa");
    assert!(
        index.search("xylophone", 5, 0).is_empty(),
        "no match below the threshold"
    );
    let ranked = index.search("office chair", 3, 0);
    assert_eq!(ranked[0].category, "office_chair");
    assert!(ranked[0].score > ranked[1].score);
}

#[test]
fn equally_good_candidates_are_ordered_by_the_seed() {
    let mut index = AssetIndex::empty();
    for k in 0..6 {
        index.add_imported(&info("vase", &[], Placement::Surface, &format!("vase_{k}")));
    }
    let firsts: std::collections::BTreeSet<String> = (0..32)
        .map(|seed| index.search("vase", 1, seed)[0].asset.to_string())
        .collect();
    assert!(firsts.len() >= 3, "seeds pick different vases: {firsts:?}");
    assert_eq!(
        index.search("vase", 6, 7),
        index.search("vase", 6, 7),
        "same seed, same order"
    );
    assert_eq!(index.search("vase", 6, 7).len(), 6);
}

#[test]
fn builtin_index_gives_procedural_candidates_with_seed_dependent_variants() {
    let index = AssetIndex::builtin();
    assert_eq!(
        index.len(),
        scenethesis_procedural::catalog::categories().count()
    );
    let c = top(&index, "mug");
    assert_eq!(c.category, "mug");
    let seeds: std::collections::BTreeSet<u64> = (0..8)
        .map(|s| match &index.search("mug", 1, s)[0].asset {
            AssetRef::Procedural {
                generator, seed, ..
            } => {
                assert_eq!(generator, "mug");
                *seed
            }
            other => panic!("unexpected {other:?}"),
        })
        .collect();
    assert_eq!(seeds.len(), 8, "each search seed gives another variant");
    assert_eq!(top(&index, "rucksack").category, "backpack");
    for (q, category) in [
        ("couch", "sofa"),
        ("settee", "sofa"),
        ("bookcase", "bookshelf"),
        ("TV", "television"),
        ("fridge", "refrigerator"),
        ("coffee tables", "coffee_table"),
        ("garbage can", "trash_can"),
    ] {
        assert_eq!(top(&index, q).category, category, "{q}");
    }
    assert_eq!(top(&index, "beach umbrellas").category, "beach_umbrella");
}

#[test]
fn imported_assets_rank_next_to_and_just_above_the_builtin_generator() {
    let mine = info("mug", &["my favourite cup"], Placement::Surface, "blue_mug");
    let index = AssetIndex::with_imported([&mine]);
    // An exact category match scores 1 for both (the bonus is capped); the import still wins,
    // whatever the seed.
    for seed in 0..16 {
        let ranked = index.search("mug", 2, seed);
        assert_eq!(ranked[0].asset, mine.source, "seed {seed}");
        assert!(matches!(ranked[1].asset, AssetRef::Procedural { .. }));
    }
    assert_eq!(top(&index, "my favourite cup").category, "mug");
}

/// A deterministic test double for the embedding seam: bag-of-letter-trigram vectors with a
/// few hand-made concept words, so "somewhere to sleep" lands near "bed".
struct TrigramEmbedder;

impl TextEmbedder for TrigramEmbedder {
    fn name(&self) -> String {
        "test/trigram".into()
    }

    fn embed(&self, texts: &[&str]) -> Result<Vec<Vec<f32>>, ProviderError> {
        Ok(texts
            .iter()
            .map(|t| {
                let t = t.to_lowercase();
                let mut v = vec![0.0f32; 64];
                // Whole words, so that "bedside lamp" is not about sleeping.
                let has = |concept: &str| {
                    t.split(|c: char| !c.is_alphanumeric())
                        .any(|w| w == concept)
                };
                for concept in ["sleep", "bed", "rest", "night"] {
                    if has(concept) {
                        v[0] += 1.0;
                    }
                }
                for concept in ["drink", "coffee", "mug", "tea"] {
                    if has(concept) {
                        v[1] += 1.0;
                    }
                }
                let bytes = t.as_bytes();
                for w in bytes.windows(3) {
                    let h = (w[0] as usize * 31 + w[1] as usize * 7 + w[2] as usize) % 62;
                    v[2 + h] += 0.05;
                }
                v
            })
            .collect())
    }
}

struct FailingEmbedder;

impl TextEmbedder for FailingEmbedder {
    fn name(&self) -> String {
        "test/failing".into()
    }

    fn embed(&self, texts: &[&str]) -> Result<Vec<Vec<f32>>, ProviderError> {
        if texts.len() == 1 {
            let kind = ProviderErrorKind::Unreachable {
                message: "model unavailable".into(),
                source: None,
            };
            Err(ProviderError::new("test", "failing", kind))
        } else {
            Ok(texts.iter().map(|_| vec![1.0, 0.0]).collect())
        }
    }
}

#[test]
fn an_embedder_adds_a_semantic_stage_without_overriding_exact_matches() {
    let mut index = small_index();
    assert!(index.search("somewhere to sleep at night", 3, 0).is_empty());
    index.set_embedder(Box::new(TrigramEmbedder)).unwrap();
    let c = top(&index, "somewhere to sleep at night");
    assert_eq!(c.category, "bed");
    assert!(
        matches!(c.reason, MatchReason::Semantic(s) if s > 0.5),
        "{:?}",
        c.reason
    );
    let c = top(&index, "couch");
    assert_eq!(
        (c.category.as_str(), c.reason.clone()),
        ("sofa", MatchReason::Synonym("couch".into()))
    );
}

#[test]
fn a_failing_embedder_is_reported_or_falls_back_to_lexical_ranking() {
    let mut index = small_index();
    index.set_embedder(Box::new(FailingEmbedder)).unwrap();
    assert!(index.try_search("couch", 3, 0).is_err());
    assert_eq!(top(&index, "couch").category, "sofa");
    struct Short;
    impl TextEmbedder for Short {
        fn name(&self) -> String {
            "test/short".into()
        }

        fn embed(&self, _: &[&str]) -> Result<Vec<Vec<f32>>, ProviderError> {
            Ok(vec![vec![1.0]])
        }
    }
    let e = small_index().set_embedder(Box::new(Short)).unwrap_err();
    assert!(e.to_string().contains("1 vectors for 11 texts"), "{e}");
}
