//! Seeded draws shared by the generators: every random choice an asset makes goes through
//! these, from the category's [`rand_chacha::ChaCha8Rng`].

use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// A uniform random number in `[lo, hi]`.
pub(crate) fn uniform(rng: &mut ChaCha8Rng, lo: f32, hi: f32) -> f32 {
    if hi <= lo {
        lo
    } else {
        rng.random_range(lo..=hi)
    }
}

/// Three uniform draws in order, from the ranges `x`, `y` and `z`: an asset's width, height and
/// depth.
pub(crate) fn uniform3(
    rng: &mut ChaCha8Rng,
    x: [f32; 2],
    y: [f32; 2],
    z: [f32; 2],
) -> (f32, f32, f32) {
    let x = uniform(rng, x[0], x[1]);
    let y = uniform(rng, y[0], y[1]);
    let z = uniform(rng, z[0], z[1]);
    (x, y, z)
}

/// One element of a non-empty slice, chosen by the generator.
pub(crate) fn pick<'a, T>(rng: &mut ChaCha8Rng, items: &'a [T]) -> &'a T {
    &items[rng.random_range(0..items.len())]
}

/// A colour from `palette`, each channel jittered by up to ±`jitter` and clamped to [0, 1].
pub(crate) fn color(rng: &mut ChaCha8Rng, palette: &[[f32; 3]], jitter: f32) -> [f32; 3] {
    let base = *pick(rng, palette);
    base.map(|c| (c + uniform(rng, -jitter, jitter)).clamp(0.0, 1.0))
}

/// A uniform integer in `[lo, hi]`.
pub(crate) fn int(rng: &mut ChaCha8Rng, lo: usize, hi: usize) -> usize {
    if hi <= lo {
        lo
    } else {
        rng.random_range(lo..=hi)
    }
}

/// True with probability `p`.
pub(crate) fn coin(rng: &mut ChaCha8Rng, p: f64) -> bool {
    rng.random_bool(p)
}
