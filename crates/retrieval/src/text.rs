//! Text normalisation and fuzzy word matching. Words and singular forms are those of the one
//! text vocabulary, `scenethesis-words`, which the offline and language planners share.

pub use scenethesis_words::{singular, words};

/// The words of `text` joined by single spaces (see [`words`]).
pub fn normalise(text: &str) -> String {
    words(text).join(" ")
}

/// Levenshtein distance between two words, counted in characters.
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let above = row[j + 1];
            row[j + 1] = (above + 1)
                .min(row[j] + 1)
                .min(diagonal + usize::from(ca != cb));
            diagonal = above;
        }
    }
    row[b.len()]
}

/// Similarity of two words in [0, 1]: 1 when equal, `1 − distance / longer length` when that is
/// at least 0.75 (a typo or two in a long word), else 0.
pub fn word_similarity(a: &str, b: &str) -> f32 {
    if a == b {
        return 1.0;
    }
    let (la, lb) = (a.chars().count(), b.chars().count());
    let longer = la.max(lb);
    // The distance is at least the length difference: skip pairs that cannot reach 0.75.
    if longer < 4 || la.abs_diff(lb) * 4 > longer {
        return 0.0;
    }
    let s = 1.0 - edit_distance(a, b) as f32 / longer as f32;
    if s >= 0.75 {
        s
    } else {
        0.0
    }
}

/// How well a query's words cover a name's words: 0.7 × the name's words found in the query plus
/// 0.3 × the query's words found in the name, each word matched by [`word_similarity`].
pub fn overlap_score(query: &[String], name: &[String]) -> f32 {
    if query.is_empty() || name.is_empty() {
        return 0.0;
    }
    let best = |w: &String, others: &[String]| {
        others
            .iter()
            .map(|o| word_similarity(w, o))
            .fold(0.0f32, f32::max)
    };
    let recall = name.iter().map(|w| best(w, query)).sum::<f32>() / name.len() as f32;
    let precision = query.iter().map(|w| best(w, name)).sum::<f32>() / query.len() as f32;
    0.7 * recall + 0.3 * precision
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_are_lowercase_singular_and_split_on_separators() {
        assert_eq!(words("Coffee_Tables!"), vec!["coffee", "table"]);
        assert_eq!(words("book-shelves"), vec!["book", "shelf"]);
        assert_eq!(words("two wine glasses"), vec!["two", "wine", "glass"]);
        assert_eq!(words("children's chair"), vec!["child", "chair"]);
        assert_eq!(normalise("BOXES  of  Toys"), "box of toy");
        assert_eq!(singular("bodies"), "body");
        assert_eq!(singular("benches"), "bench");
        assert_eq!(singular("glass"), "glass");
        assert_eq!(singular("cactus"), "cactus");
        assert_eq!(singular("tv"), "tv");
    }

    #[test]
    fn edit_distance_and_similarity() {
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(word_similarity("bookshelf", "bookshelf"), 1.0);
        assert!(word_similarity("bookshelf", "bookshelv") > 0.85);
        assert_eq!(word_similarity("chair", "armchair"), 0.0);
        assert_eq!(
            word_similarity("cat", "car"),
            0.0,
            "short words need an exact match"
        );
    }

    #[test]
    fn overlap_prefers_the_name_the_query_covers() {
        let q = words("red wooden chair");
        let chair = overlap_score(&q, &words("chair"));
        let dining = overlap_score(&q, &words("dining chair"));
        assert!(chair > dining, "{chair} vs {dining}");
        assert_eq!(overlap_score(&q, &words("lamp")), 0.0);
    }
}
