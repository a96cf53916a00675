//! The one stable hash of the project: 64-bit FNV-1a. Seeds derived from names and the keys of
//! resumable work are built on it, so it must give the same value on every platform and in
//! every release (unlike `std`'s hashers).

/// The 64-bit FNV-1a hash of `bytes`.
///
/// ```
/// use scenethesis_scene_graph::fnv1a64;
/// assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
/// assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
/// ```
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    fnv1a64_from(FNV_OFFSET_BASIS, bytes)
}

/// The FNV-1a offset basis: the state [`fnv1a64`] starts from.
pub const FNV_OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;

/// FNV-1a over `bytes` starting from `state` instead of the offset basis: continues a hash,
/// or (with `FNV_OFFSET_BASIS ^ seed`) makes a seeded one.
///
/// ```
/// use scenethesis_scene_graph::{fnv1a64, fnv1a64_from, FNV_OFFSET_BASIS};
/// assert_eq!(fnv1a64_from(fnv1a64(b"ab"), b"cd"), fnv1a64(b"abcd"));
/// assert_ne!(fnv1a64_from(FNV_OFFSET_BASIS ^ 1, b"id"), fnv1a64(b"id"));
/// ```
pub fn fnv1a64_from(state: u64, bytes: &[u8]) -> u64 {
    bytes.iter().fold(state, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// The SplitMix64 output function: spreads nearby inputs (seeds, variants) over the whole
/// range, so neighbouring seeds give unrelated values.
///
/// ```
/// use scenethesis_scene_graph::mix64;
/// assert_eq!(mix64(0), 0);
/// assert_ne!(mix64(1) >> 32, mix64(2) >> 32);
/// ```
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The golden-ratio increment of SplitMix64, used to spread seeds and variants before
/// [`mix64`].
pub const GOLDEN_GAMMA: u64 = 0x9e37_79b9_7f4a_7c15;

#[cfg(test)]
mod tests {
    use super::*;

    /// The values every seed of the project rests on; a change here changes every output.
    #[test]
    fn the_seeding_hash_is_stable() {
        assert_eq!(
            fnv1a64(b"sofa_0"),
            fnv1a64_from(FNV_OFFSET_BASIS, b"sofa_0")
        );
        assert_eq!(fnv1a64(b"foobar"), 0x85944171f73967e8);
        assert_eq!(mix64(GOLDEN_GAMMA), 0xe220a8397b1dcdaf);
    }
}
