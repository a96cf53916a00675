//! Byte-mutation fuzzing for every parser of the workspace, small enough to run inside
//! `cargo test` in CI: each target (`tests/fuzz.rs`) starts from a valid seed input, applies a
//! few random [`Mutation`]s drawn by proptest and feeds the result to the parser, which must
//! return (an error is fine) without panicking, within a time budget per target.
//!
//! The case count can be raised for a longer local run with the `PROPTEST_CASES` environment
//! variable; the time budget per target with `SCENETHESIS_FUZZ_SECONDS`.

#![warn(missing_docs)]

use std::time::{Duration, Instant};

use proptest::prelude::*;

/// Tokens that often break parsers of numbers and structure, inserted whole by
/// [`Mutation::Insert`].
pub const TOKENS: &[&[u8]] = &[
    b"1e308",
    b"-1e308",
    b"1e400",
    b"NaN",
    b"-0",
    b"4294967295",
    b"18446744073709551616",
    b"-1",
    b"0",
    b"null",
    b"[]",
    b"{}",
    b"\"",
    b"..",
    b"../../",
    b"/etc/passwd",
    b"\x1b[31m",
    b"\xff\xfe",
    b"\0",
    b"\n",
];

/// One edit of an input.
#[derive(Debug, Clone)]
pub enum Mutation {
    /// Flip the bits of `mask` in the byte at `at` (modulo the length).
    Flip {
        /// Position (taken modulo the length).
        at: usize,
        /// Bits to flip.
        mask: u8,
    },
    /// Overwrite the byte at `at` with `byte`.
    Set {
        /// Position (taken modulo the length).
        at: usize,
        /// The new byte.
        byte: u8,
    },
    /// Insert one of [`TOKENS`] at `at`.
    Insert {
        /// Position (taken modulo the length + 1).
        at: usize,
        /// Index into [`TOKENS`] (modulo its length).
        token: usize,
    },
    /// Delete up to `len` bytes from `at`.
    Delete {
        /// Position (taken modulo the length).
        at: usize,
        /// How many bytes.
        len: usize,
    },
    /// Copy up to `len` bytes from `from` to `at` (repeats structure).
    Duplicate {
        /// Source position.
        from: usize,
        /// Destination position.
        at: usize,
        /// How many bytes.
        len: usize,
    },
    /// Cut the input at `at`.
    Truncate {
        /// New length (modulo the length + 1).
        at: usize,
    },
}

impl Mutation {
    /// Applies the edit to `bytes`.
    pub fn apply(&self, bytes: &mut Vec<u8>) {
        let n = bytes.len();
        match *self {
            Mutation::Flip { at, mask } if n > 0 => bytes[at % n] ^= mask.max(1),
            Mutation::Set { at, byte } if n > 0 => bytes[at % n] = byte,
            Mutation::Insert { at, token } => {
                let at = at % (n + 1);
                let token = TOKENS[token % TOKENS.len()];
                bytes.splice(at..at, token.iter().copied());
            }
            Mutation::Delete { at, len } if n > 0 => {
                let at = at % n;
                let end = (at + len % 64 + 1).min(n);
                bytes.drain(at..end);
            }
            Mutation::Duplicate { from, at, len } if n > 0 => {
                let from = from % n;
                let end = (from + len % 256 + 1).min(n);
                let chunk: Vec<u8> = bytes[from..end].to_vec();
                let at = at % (n + 1);
                bytes.splice(at..at, chunk);
            }
            Mutation::Truncate { at } => bytes.truncate(at % (n + 1)),
            _ => {}
        }
    }
}

/// A random edit.
pub fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(at, mask)| Mutation::Flip { at, mask }),
        (any::<usize>(), any::<u8>()).prop_map(|(at, byte)| Mutation::Set { at, byte }),
        (any::<usize>(), any::<usize>()).prop_map(|(at, token)| Mutation::Insert { at, token }),
        (any::<usize>(), any::<usize>()).prop_map(|(at, len)| Mutation::Delete { at, len }),
        (any::<usize>(), any::<usize>(), any::<usize>())
            .prop_map(|(from, at, len)| Mutation::Duplicate { from, at, len }),
        any::<usize>().prop_map(|at| Mutation::Truncate { at }),
    ]
}

/// One to eight random edits.
pub fn mutations() -> impl Strategy<Value = Vec<Mutation>> {
    proptest::collection::vec(mutation(), 1..8)
}

/// `seed` with `edits` applied in order.
pub fn mutate(seed: &[u8], edits: &[Mutation]) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for e in edits {
        e.apply(&mut bytes);
    }
    bytes
}

/// The proptest configuration of a fuzz target: `cases` cases (or `PROPTEST_CASES`), no
/// failure files written, shrinking bounded to 64 steps and 5 s.
pub fn config(cases: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(cases);
    ProptestConfig {
        cases,
        failure_persistence: None,
        max_shrink_iters: 64,
        max_shrink_time: 5_000,
        ..ProptestConfig::default()
    }
}

/// The wall-clock budget of one target: once spent, the remaining cases return at once, so a
/// target never runs much longer than this in CI, however slow the machine.
#[derive(Debug, Clone, Copy)]
pub struct Budget {
    start: Instant,
    limit: Duration,
}

impl Budget {
    /// A budget of `seconds` (or `SCENETHESIS_FUZZ_SECONDS`) from now.
    pub fn new(seconds: f64) -> Self {
        let seconds = std::env::var("SCENETHESIS_FUZZ_SECONDS")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(seconds);
        Self {
            start: Instant::now(),
            limit: Duration::from_secs_f64(seconds),
        }
    }

    /// Whether the budget is spent.
    pub fn spent(&self) -> bool {
        self.start.elapsed() > self.limit
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mutations_edit_as_documented() {
        let seed = b"abcdef";
        assert_eq!(mutate(seed, &[Mutation::Truncate { at: 3 }]), b"abc");
        assert_eq!(
            mutate(seed, &[Mutation::Set { at: 7, byte: b'X' }]),
            b"aXcdef"
        );
        assert_eq!(mutate(seed, &[Mutation::Delete { at: 1, len: 1 }]), b"adef");
        assert_eq!(
            mutate(seed, &[Mutation::Insert { at: 0, token: 7 }]),
            b"-1abcdef"
        );
        assert_eq!(
            mutate(
                seed,
                &[Mutation::Duplicate {
                    from: 0,
                    at: 6,
                    len: 1
                }]
            ),
            b"abcdefab"
        );
        assert_eq!(mutate(b"", &[Mutation::Flip { at: 3, mask: 1 }]), b"");
    }
}
