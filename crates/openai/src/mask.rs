//! Masking an API key in text a server or model sent back, also when it comes reshaped: split by
//! spaces, newlines or hyphens, re-cased, or only in part.
//!
//! Two passes. The first replaces every exact occurrence of the key by `***`. The second
//! compares the text and the key on their ASCII letters and digits only, case-folded (every
//! other character counts as a separator and is skipped on both sides), and replaces every run
//! of the text that spells at least [`min_masked_run`] consecutive letters and digits of the key
//! (with at most 8 separators between two of them) by `***`, together with the separators
//! inside the run. Keys with fewer than
//! [`MIN_RESHAPED_KEY_CHARS`] letters and digits are masked by the first pass only: a shorter
//! piece would match ordinary words.

use std::borrow::Cow;

/// Keys with fewer ASCII letters and digits than this are masked only where they appear whole.
pub const MIN_RESHAPED_KEY_CHARS: usize = 8;

/// The longest run of key characters a reshaped echo must show to be masked.
const MAX_MASKED_RUN: usize = 12;

/// Most other characters between two letters or digits of a reshaped echo (a wider gap ends
/// the run, which bounds the work per position).
const MAX_GAP: usize = 8;

/// How many consecutive letters and digits of a key (of `key_chars` letters and digits) a piece
/// of text must spell to be masked: half the key, at least [`MIN_RESHAPED_KEY_CHARS`] and at
/// most 12.
pub fn min_masked_run(key_chars: usize) -> usize {
    key_chars
        .div_ceil(2)
        .clamp(MIN_RESHAPED_KEY_CHARS, MAX_MASKED_RUN)
}

/// `text` with `key` masked (see the module documentation).
pub(crate) fn mask_key<'a>(key: &str, text: &'a str) -> Cow<'a, str> {
    if key.is_empty() {
        return Cow::Borrowed(text);
    }
    let exact = if text.contains(key) {
        Cow::Owned(text.replace(key, "***"))
    } else {
        Cow::Borrowed(text)
    };
    let key_chars: Vec<u8> = key
        .bytes()
        .filter(u8::is_ascii_alphanumeric)
        .map(|b| b.to_ascii_lowercase())
        .collect();
    if key_chars.len() < MIN_RESHAPED_KEY_CHARS {
        return exact;
    }
    let spans = reshaped_spans(&key_chars, &exact);
    if spans.is_empty() {
        return exact;
    }
    let mut out = String::with_capacity(exact.len());
    let mut at = 0;
    for (start, end) in spans {
        out.push_str(&exact[at..start]);
        out.push_str("***");
        at = end;
    }
    out.push_str(&exact[at..]);
    Cow::Owned(out)
}

/// The byte ranges of `text` (merged, in order) that spell at least [`min_masked_run`]
/// consecutive characters of `key` (ASCII letters and digits, lower-cased) when only the
/// letters and digits of the text are read, case-folded. One pass over the text, with no
/// allocation per character (answers may be tens of megabytes).
fn reshaped_spans(key: &[u8], text: &str) -> Vec<(usize, usize)> {
    let run = min_masked_run(key.len());
    let bytes = text.as_bytes();
    // Where each character occurs in the key.
    let mut positions: Vec<Vec<usize>> = vec![Vec::new(); 128];
    for (j, &k) in key.iter().enumerate() {
        positions[usize::from(k)].push(j);
    }
    let mut spans: Vec<(usize, usize)> = Vec::new();
    // Letters and digits still inside a match already found, not worth starting from.
    let mut skip = 0usize;
    for (at, &b) in bytes.iter().enumerate() {
        if !b.is_ascii_alphanumeric() {
            continue;
        }
        if skip > 0 {
            skip -= 1;
            continue;
        }
        let (len, end) = positions[usize::from(b.to_ascii_lowercase())]
            .iter()
            .map(|&j| spelled(&key[j..], &bytes[at..]))
            .max()
            .unwrap_or((0, 0));
        if len < run {
            continue;
        }
        let (start, end) = (at, at + end);
        match spans.last_mut() {
            Some(last) if start <= last.1 => last.1 = last.1.max(end),
            _ => spans.push((start, end)),
        }
        // Every longer match starting inside this one reaches past it by a whole run.
        skip = len - run;
    }
    spans
}

/// How many leading characters of `key` the letters and digits at the start of `text` spell
/// (case-folded, other bytes skipped), and the byte offset just past the last one.
fn spelled(key: &[u8], text: &[u8]) -> (usize, usize) {
    let (mut matched, mut end) = (0, 0);
    for (i, &b) in text.iter().enumerate() {
        if matched == key.len() || i - end > MAX_GAP {
            break;
        }
        if !b.is_ascii_alphanumeric() {
            continue;
        }
        if b.to_ascii_lowercase() != key[matched] {
            break;
        }
        matched += 1;
        end = i + 1;
    }
    (matched, end)
}

#[cfg(test)]
mod tests {
    use super::*;

    const KEY: &str = "sk-proj-Ab12Cd34Ef56Gh78";

    #[test]
    fn exact_and_reshaped_echoes_are_masked() {
        assert_eq!(mask_key(KEY, &format!("key {KEY}.")), "key ***.");
        for echo in [
            "sk-proj-Ab12 Cd34Ef56Gh78",
            "sk-proj-Ab12\nCd34-Ef56\r\nGh78",
            "SK-PROJ-AB12CD34EF56GH78",
            "s k - p r o j - A b 1 2 C d 3 4 E f 5 6 G h 7 8",
        ] {
            let text = format!("said <{echo}> then");
            assert_eq!(mask_key(KEY, &text), "said <***> then", "{echo:?}");
        }
        // A long-enough piece of the key (12 of its 20 letters and digits) is masked ...
        assert_eq!(mask_key(KEY, "tail Cd34Ef56Gh78!"), "tail ***!");
        assert_eq!(mask_key(KEY, "head sk-proj-Ab12Cd"), "head ***");
        // ... a shorter one, or ordinary text, is left alone.
        assert_eq!(
            mask_key(KEY, "Ef56Gh78 and sk-proj"),
            "Ef56Gh78 and sk-proj"
        );
        assert_eq!(min_masked_run(20), 10);
        assert_eq!(mask_key(KEY, "plain words only"), "plain words only");
    }

    #[test]
    fn short_keys_are_masked_whole_only_and_repeats_stay_linear() {
        assert_eq!(mask_key("abc-12", "x abc-12 y abc 12"), "x *** y abc 12");
        assert_eq!(mask_key("", "text"), "text");
        assert_eq!(min_masked_run(100), 12);
        assert_eq!(min_masked_run(8), 8);
        let many = format!("{} end", KEY.replace('-', " ").repeat(10_000));
        // Quadratic work here (240 kB of the key's letters) would run for minutes, not fail a
        // wall-clock bound: speed is measured in benches, never timed in unit tests.
        assert_eq!(mask_key(KEY, &many), "*** end");
        // Key-alphabet text that is not the key, and separators only, stay as they are.
        let noise: String = (0..200_000u32)
            .map(|i| char::from(b"abcdefghij0123456789-- \n"[(i * 7919 % 24) as usize]))
            .collect();
        assert_eq!(mask_key(KEY, &noise), noise);
    }
}
