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
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3)
    })
}
