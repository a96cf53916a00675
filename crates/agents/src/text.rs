//! Prompt text handling: normalisation, tokens and plural folding.

/// One token of a normalised prompt.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Token {
    /// A word, folded to its singular form, with whether it looked plural.
    Word {
        /// The singular form used for matching.
        stem: String,
        /// Whether the written form was a plural.
        plural: bool,
    },
    /// A clause break: comma, period, semicolon, colon.
    Break,
}

impl Token {
    /// The word's stem, or `None` for a break.
    pub(crate) fn stem(&self) -> Option<&str> {
        match self {
            Token::Word { stem, .. } => Some(stem),
            Token::Break => None,
        }
    }
}

/// Lower-cases, folds accents and possessives, splits hyphenated words and turns punctuation
/// into clause breaks.
pub(crate) fn tokenize(text: &str) -> Vec<Token> {
    let mut tokens = Vec::new();
    let mut word = String::new();
    let flush = |word: &mut String, tokens: &mut Vec<Token>| {
        if !word.is_empty() {
            let w = std::mem::take(word);
            let w = w.strip_suffix("'s").unwrap_or(&w).replace('\'', "");
            if !w.is_empty() {
                let (stem, plural) = singular(&w);
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

/// The words of a knowledge phrase, each folded to its singular form.
pub(crate) fn phrase_stems(phrase: &str) -> Vec<String> {
    tokenize(phrase)
        .into_iter()
        .filter_map(|t| t.stem().map(str::to_owned))
        .collect()
}

/// Folds an English plural to its singular, returning whether the word was plural.
pub(crate) fn singular(word: &str) -> (String, bool) {
    const IRREGULAR: &[(&str, &str)] = &[
        ("children", "child"),
        ("people", "person"),
        ("shelves", "shelf"),
        ("knives", "knife"),
        ("leaves", "leaf"),
        ("mice", "mouse"),
        ("feet", "foot"),
        ("men", "man"),
        ("women", "woman"),
        ("teeth", "tooth"),
        ("loaves", "loaf"),
        ("halves", "half"),
        ("wolves", "wolf"),
        ("series", "series"),
        ("species", "species"),
        ("cacti", "cactus"),
    ];
    if let Some((_, s)) = IRREGULAR.iter().find(|(p, _)| *p == word) {
        return ((*s).to_owned(), *s != word);
    }
    let n = word.len();
    if n <= 3 || !word.is_ascii() || word.chars().all(|c| c.is_ascii_digit()) {
        return (word.to_owned(), false);
    }
    for keep in ["ss", "us", "is", "as", "os"] {
        if word.ends_with(keep) {
            return (word.to_owned(), false);
        }
    }
    if let Some(stem) = word.strip_suffix("ies") {
        return (format!("{stem}y"), true);
    }
    for suffix in ["ches", "shes", "sses", "xes", "zes"] {
        if word.ends_with(suffix) {
            return (word[..n - 2].to_owned(), true);
        }
    }
    if let Some(stem) = word.strip_suffix('s') {
        return (stem.to_owned(), true);
    }
    (word.to_owned(), false)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plurals_fold_to_singular() {
        for (p, s) in [
            ("books", "book"),
            ("shelves", "shelf"),
            ("benches", "bench"),
            ("boxes", "box"),
            ("armchairs", "armchair"),
            ("glass", "glass"),
            ("bodies", "body"),
            ("children", "child"),
        ] {
            assert_eq!(singular(p).0, s, "{p}");
        }
        assert!(!singular("glass").1);
        assert!(singular("mugs").1);
    }

    #[test]
    fn tokenize_splits_hyphens_possessives_and_breaks() {
        let t = tokenize("A children's three-seat Sofa, café.");
        let stems: Vec<_> = t.iter().map(|t| t.stem().unwrap_or("|")).collect();
        assert_eq!(
            stems,
            ["a", "child", "three", "seat", "sofa", "|", "cafe", "|"]
        );
    }
}
