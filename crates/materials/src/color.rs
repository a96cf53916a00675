//! sRGB transfer for 8-bit channels: decoding through a 256-entry table (built once), encoding
//! by searching it, so that encoding is exact and repeatable.

use std::sync::OnceLock;

fn table() -> &'static [f32; 256] {
    static TABLE: OnceLock<[f32; 256]> = OnceLock::new();
    TABLE.get_or_init(|| {
        std::array::from_fn(|i| {
            let c = i as f32 / 255.0;
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        })
    })
}

/// The linear value of an sRGB byte.
pub fn srgb_byte_to_linear(c: u8) -> f32 {
    table()[c as usize]
}

/// Buckets of equal width over linear `[0, 1]` for [`linear_to_srgb_byte`]'s search.
const BUCKETS: usize = 4096;

/// For every bucket, the first byte whose linear value is at least the bucket's lower edge:
/// the search for a value in the bucket starts there.
fn bucket_starts() -> &'static [u16; BUCKETS] {
    static STARTS: OnceLock<[u16; BUCKETS]> = OnceLock::new();
    STARTS.get_or_init(|| {
        let t = table();
        std::array::from_fn(|b| {
            let edge = b as f32 / BUCKETS as f32;
            t.partition_point(|&v| v < edge) as u16
        })
    })
}

/// The sRGB byte whose linear value is nearest to `linear` (clamped to `[0, 1]`).
pub fn linear_to_srgb_byte(linear: f32) -> u8 {
    let t = table();
    let x = linear.clamp(0.0, 1.0);
    // The first byte whose value is at least x (searched from the start of x's bucket, whose
    // edge x·BUCKETS rounds down to exactly), then the nearer of it and the one below.
    let bucket = ((x * BUCKETS as f32) as usize).min(BUCKETS - 1);
    let mut hi = bucket_starts()[bucket] as usize;
    while hi < 256 && t[hi] < x {
        hi += 1;
    }
    let hi = hi.min(255);
    if hi > 0 && (x - t[hi - 1]) <= (t[hi] - x) {
        (hi - 1) as u8
    } else {
        hi as u8
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_round_trip() {
        for b in 0..=255u8 {
            assert_eq!(linear_to_srgb_byte(srgb_byte_to_linear(b)), b);
        }
        assert_eq!(linear_to_srgb_byte(2.0), 255);
        assert_eq!(linear_to_srgb_byte(-1.0), 0);
    }
}
