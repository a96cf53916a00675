//! The one text vocabulary of scenethesis: how a word folds to its singular form, how text
//! splits into words, and which category a phrase names. The offline planner (reading prompts),
//! retrieval (matching queries to catalog names) and the language planner (mapping a model's
//! category names onto the library) all fold and match words here, so a word means the same
//! thing to all three.
//!
//! ```
//! use scenethesis_words::{category_of_phrase, nearest_category, singular, words};
//!
//! assert_eq!(singular("bookshelves"), "bookshelf");
//! assert_eq!(words("Two Coffee_Tables, café"), ["two", "coffee", "table", "cafe"]);
//! let rows = [(words("coffee table"), "coffee_table"), (words("couch"), "sofa")];
//! let rows = || rows.iter().map(|(w, c)| (w.as_slice(), *c));
//! assert_eq!(category_of_phrase(&words("couches"), rows()), Some("sofa"));
//! assert_eq!(nearest_category(&words("small coffee tables"), rows()), Some("coffee_table"));
//! ```

#![warn(missing_docs)]

/// Plurals that do not follow the endings [`singular`] folds, with their singulars.
const IRREGULAR: &[(&str, &str)] = &[
    ("children", "child"),
    ("people", "person"),
    ("shelves", "shelf"),
    ("bookshelves", "bookshelf"),
    ("knives", "knife"),
    ("leaves", "leaf"),
    ("loaves", "loaf"),
    ("halves", "half"),
    ("wolves", "wolf"),
    ("mice", "mouse"),
    ("feet", "foot"),
    ("men", "man"),
    ("women", "woman"),
    ("teeth", "tooth"),
    ("geese", "goose"),
    ("dice", "die"),
    ("cacti", "cactus"),
];

/// Words that end like a plural but are singular, or have no singular of their own.
const INVARIANT: &[&str] = &[
    "series",
    "species",
    "glass",
    "grass",
    "bus",
    "cactus",
    "canvas",
    "chess",
    "dress",
    "gas",
    "lens",
    "mattress",
    "news",
    "stairs",
    "tennis",
    "chassis",
    "compass",
    "pants",
    "jeans",
    "scissors",
    "trousers",
    "shorts",
    "goods",
    "this",
    "plus",
    "bonus",
    "thermos",
    "atlas",
    "chaos",
    "cosmos",
    "christmas",
];

/// The singular form of a lower-case English word (`shelves` → `shelf`, `boxes` → `box`,
/// `bodies` → `body`, `chairs` → `chair`, `sofas` → `sofa`); words that only look plural
/// (`glass`, `cactus`, `scissors`), short words (three letters or fewer), numbers and words with
/// letters outside ASCII are kept. A word was plural exactly when its singular differs from it.
pub fn singular(word: &str) -> String {
    if let Some((_, s)) = IRREGULAR.iter().find(|(p, _)| *p == word) {
        return (*s).to_owned();
    }
    let keep = word.len() <= 3
        || !word.is_ascii()
        || word.chars().all(|c| c.is_ascii_digit())
        || INVARIANT.contains(&word)
        || ["ss", "us", "is"].iter().any(|k| word.ends_with(k));
    if keep {
        return word.to_owned();
    }
    if let Some(stem) = word.strip_suffix("ies") {
        return format!("{stem}y");
    }
    for suffix in ["ches", "shes", "sses", "xes", "zzes"] {
        if word.ends_with(suffix) {
            return word[..word.len() - 2].to_owned();
        }
    }
    match word.strip_suffix('s') {
        Some(stem) => stem.to_owned(),
        None => word.to_owned(),
    }
}

/// One token of a text read by [`tokenize`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Token {
    /// A word, folded to its singular form, with whether it looked plural.
    Word {
        /// The singular form used for matching.
        stem: String,
        /// Whether the written form was a plural.
        plural: bool,
    },
    /// A clause break: comma, period, semicolon, colon, `!`, `?` or a line break.
    Break,
}

impl Token {
    /// The word's stem, or `None` for a break.
    pub fn stem(&self) -> Option<&str> {
        match self {
            Token::Word { stem, .. } => Some(stem),
            Token::Break => None,
        }
    }
}

/// Lower-cases, folds accents and possessives, splits hyphenated and `_`-joined words, folds
/// every word to its [`singular`] and turns punctuation into clause breaks.
pub fn tokenize(text: &str) -> Vec<Token> {
    let mut tokens = Vec::new();
    let mut word = String::new();
    let flush = |word: &mut String, tokens: &mut Vec<Token>| {
        if !word.is_empty() {
            let w = std::mem::take(word);
            let w = w.strip_suffix("'s").unwrap_or(&w).replace('\'', "");
            if !w.is_empty() {
                let stem = singular(&w);
                let plural = stem != w;
                tokens.push(Token::Word { stem, plural });
            }
        }
    };
    for ch in text.chars().flat_map(char::to_lowercase) {
        let ch = match ch {
            'é' | 'è' | 'ê' | 'ë' => 'e',
            'á' | 'à' | 'â' | 'ä' => 'a',
            'í' | 'ì' | 'î' | 'ï' => 'i',
            'ó' | 'ò' | 'ô' | 'ö' => 'o',
            'ú' | 'ù' | 'û' | 'ü' => 'u',
            'ç' => 'c',
            'ñ' => 'n',
            '’' | '‘' => '\'',
            c => c,
        };
        if ch.is_alphanumeric() || ch == '\'' {
            word.push(ch);
        } else {
            flush(&mut word, &mut tokens);
            if matches!(ch, ',' | '.' | ';' | ':' | '!' | '?' | '\n')
                && tokens.last() != Some(&Token::Break)
            {
                tokens.push(Token::Break);
            }
        }
    }
    flush(&mut word, &mut tokens);
    tokens
}

/// The words of `text` as [`tokenize`] reads them, each in its singular form, without the
/// clause breaks: `"Coffee_Tables!"` → `["coffee", "table"]`.
pub fn words(text: &str) -> Vec<String> {
    tokenize(text)
        .into_iter()
        .filter_map(|t| match t {
            Token::Word { stem, .. } => Some(stem),
            Token::Break => None,
        })
        .collect()
}

/// The category a phrase names: the first of `rows` (each a naming phrase as [`words`] and its
/// category) whose words are exactly `phrase`'s (`couches` → `sofa` when a row says `couch`).
pub fn category_of_phrase<'a, C>(
    phrase: &[String],
    rows: impl IntoIterator<Item = (&'a [String], C)>,
) -> Option<C> {
    rows.into_iter()
        .find(|(w, _)| *w == phrase)
        .map(|(_, category)| category)
}

/// The category nearest to a phrase: the first row whose words are exactly `phrase`'s (as
/// [`category_of_phrase`]), else the row with the most words that all occur in the phrase
/// (`pharmacy shelf` → `shelf`; among equals the first).
pub fn nearest_category<'a, C>(
    phrase: &[String],
    rows: impl IntoIterator<Item = (&'a [String], C)>,
) -> Option<C> {
    if phrase.is_empty() {
        return None;
    }
    let mut best: Option<(usize, C)> = None;
    for (w, category) in rows {
        if w == phrase {
            return Some(category);
        }
        let contained = !w.is_empty() && w.iter().all(|x| phrase.contains(x));
        if contained && best.as_ref().is_none_or(|(n, _)| w.len() > *n) {
            best = Some((w.len(), category));
        }
    }
    best.map(|(_, category)| category)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plurals_fold_to_singular() {
        for (p, s) in [
            ("books", "book"),
            ("shelves", "shelf"),
            ("bookshelves", "bookshelf"),
            ("benches", "bench"),
            ("boxes", "box"),
            ("armchairs", "armchair"),
            ("glass", "glass"),
            ("glasses", "glass"),
            ("bodies", "body"),
            ("batteries", "battery"),
            ("children", "child"),
            ("sofas", "sofa"),
            ("pianos", "piano"),
            ("buzzes", "buzz"),
            ("sizes", "size"),
            ("cactus", "cactus"),
            ("scissors", "scissors"),
            ("canvas", "canvas"),
            ("tv", "tv"),
            ("1990s", "1990"),
            ("café", "café"),
        ] {
            assert_eq!(singular(p), s, "{p}");
        }
    }

    #[test]
    fn tokenize_splits_hyphens_possessives_and_breaks() {
        let t = tokenize("A children's three-seat Sofa, café.");
        let stems: Vec<_> = t.iter().map(|t| t.stem().unwrap_or("|")).collect();
        assert_eq!(
            stems,
            ["a", "child", "three", "seat", "sofa", "|", "cafe", "|"]
        );
        assert_eq!(
            tokenize("mugs")[0],
            Token::Word {
                stem: "mug".into(),
                plural: true
            }
        );
        assert_eq!(words("BOXES  of  Toys"), ["box", "of", "toy"]);
        assert_eq!(words("book-shelves"), ["book", "shelf"]);
    }

    #[test]
    fn categories_by_exact_words_then_by_the_most_words_contained() {
        let names = [
            "shelf",
            "bookshelf",
            "coffee_table",
            "table",
            "potted_plant",
        ];
        let rows: Vec<(Vec<String>, &str)> = names.iter().map(|c| (words(c), *c)).collect();
        let rows = || rows.iter().map(|(w, c)| (w.as_slice(), *c));
        let nearest = |p: &str| nearest_category(&words(p), rows());
        assert_eq!(nearest("Shelves"), Some("shelf"));
        assert_eq!(nearest("coffee tables"), Some("coffee_table"));
        assert_eq!(nearest("pharmacy shelf"), Some("shelf"));
        assert_eq!(nearest("small coffee table"), Some("coffee_table"));
        assert_eq!(nearest("potted plants"), Some("potted_plant"));
        assert_eq!(nearest("x-ray machine"), None);
        assert_eq!(
            category_of_phrase(&words("small coffee table"), rows()),
            None
        );
        assert_eq!(category_of_phrase(&words("tables"), rows()), Some("table"));
    }
}
