//! Prompt text handling: the tokens, singular forms and phrase words of the one text vocabulary
//! (`scenethesis-words`), which retrieval and the language planner share.

pub(crate) use scenethesis_words::{tokenize, Token};

/// The words of a knowledge phrase, each folded to its singular form.
pub(crate) fn phrase_stems(phrase: &str) -> Vec<String> {
    scenethesis_words::words(phrase)
}
