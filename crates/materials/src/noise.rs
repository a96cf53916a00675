//! Tileable noise from integer hashing: every lattice coordinate is taken modulo the period,
//! so a field sampled over one tile `[0, 1)²` joins its own copy seamlessly at every edge.
//! Only additions, multiplications and comparisons of `f32` are used, so the same inputs give
//! the same bits on every run.

/// A 32-bit integer hash of a lattice point and a seed (an avalanche mix of three words).
pub fn hash(x: u32, y: u32, seed: u32) -> u32 {
    let mut h = x
        .wrapping_mul(0x8DA6_B343)
        .wrapping_add(y.wrapping_mul(0xD816_3841))
        .wrapping_add(seed.wrapping_mul(0xCB1A_B31F))
        ^ 0x9E37_79B9;
    h ^= h >> 16;
    h = h.wrapping_mul(0x7FEB_352D);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846C_A68B);
    h ^ (h >> 16)
}

/// [`hash`] as a number in `[0, 1)`.
pub fn unit(x: u32, y: u32, seed: u32) -> f32 {
    (hash(x, y, seed) >> 8) as f32 / (1u32 << 24) as f32
}

/// The smooth step `3t² − 2t³` used to blend lattice values.
pub fn fade(t: f32) -> f32 {
    t * t * (3.0 - 2.0 * t)
}

/// Linear interpolation from `a` (t = 0) to `b` (t = 1).
pub fn lerp(a: f32, b: f32, t: f32) -> f32 {
    a + (b - a) * t
}

/// `edge0 → 0`, `edge1 → 1`, smooth in between (either order of edges).
pub fn smoothstep(edge0: f32, edge1: f32, x: f32) -> f32 {
    fade(((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0))
}

/// The fractional part of `x` in `[0, 1)`.
pub fn fract(x: f32) -> f32 {
    x - floor(x)
}

/// The largest integer not above `x`, for `|x| < 2³¹` (every lattice coordinate here): the
/// same value as `f32::floor`, through a truncating conversion instead of a call into the
/// maths library (texture generation calls it for every lattice lookup).
fn floor(x: f32) -> f32 {
    let truncated = x as i32 as f32;
    if truncated > x {
        truncated - 1.0
    } else {
        truncated
    }
}

/// Lattice index of `x` (in cells) wrapped into `0..period`.
fn wrap(cell: i64, period: u32) -> u32 {
    if (0..period as i64).contains(&cell) {
        cell as u32
    } else {
        cell.rem_euclid(period as i64) as u32
    }
}

/// The lattice index after `cell` (already in `0..period`), wrapped.
fn next(cell: u32, period: u32) -> u32 {
    if cell + 1 >= period {
        0
    } else {
        cell + 1
    }
}

/// Value noise in `[0, 1)` at tile coordinates `(u, v)`, with `px` × `py` lattice cells across
/// one tile (so it repeats with period 1 in both coordinates).
pub fn value(u: f32, v: f32, px: u32, py: u32, seed: u32) -> f32 {
    let (x, y) = (u * px as f32, v * py as f32);
    let (x0, y0) = (floor(x), floor(y));
    let (tx, ty) = (fade(x - x0), fade(y - y0));
    let (ix0, iy0) = (wrap(x0 as i64, px), wrap(y0 as i64, py));
    let (ix1, iy1) = (next(ix0, px), next(iy0, py));
    let at = |cx: u32, cy: u32| unit(cx, cy, seed);
    lerp(
        lerp(at(ix0, iy0), at(ix1, iy0), tx),
        lerp(at(ix0, iy1), at(ix1, iy1), tx),
        ty,
    )
}

/// Fractal sum of `octaves` layers of [`value`] noise, each with twice the cells of the one
/// before and `gain` times its weight, normalised to `[0, 1)`.
pub fn fbm(u: f32, v: f32, px: u32, py: u32, octaves: u32, gain: f32, seed: u32) -> f32 {
    let (mut sum, mut weight, mut total) = (0.0, 1.0, 0.0);
    for o in 0..octaves {
        let scale = 1 << o;
        sum += weight * value(u, v, px * scale, py * scale, seed.wrapping_add(o * 7919));
        total += weight;
        weight *= gain;
    }
    sum / total
}

/// Cellular (Worley) noise: the distance from `(u, v)` to the nearest of one random feature
/// point per cell of a `cells` × `cells` grid, in cell units (about 0 to 1), with the hash of
/// the nearest cell (to colour cells one by one).
pub fn cellular(u: f32, v: f32, cells: u32, seed: u32) -> (f32, u32) {
    let (x, y) = (u * cells as f32, v * cells as f32);
    let (cx, cy) = (floor(x) as i64, floor(y) as i64);
    let mut best = (f32::INFINITY, 0);
    for dy in -1..=1 {
        for dx in -1..=1 {
            let (gx, gy) = (cx + dx, cy + dy);
            let (wx, wy) = (wrap(gx, cells), wrap(gy, cells));
            let h = hash(wx, wy, seed);
            let fx = gx as f32 + (h & 0xFFFF) as f32 / 65536.0;
            let fy = gy as f32 + (h >> 16) as f32 / 65536.0;
            let d = ((fx - x) * (fx - x) + (fy - y) * (fy - y)).sqrt();
            if d < best.0 {
                best = (d, h);
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn value_noise_repeats_over_one_tile_and_stays_in_range() {
        for i in 0..50 {
            let t = i as f32 / 50.0;
            let a = value(0.0, t, 4, 6, 3);
            let b = value(1.0, t, 4, 6, 3);
            assert!((a - b).abs() < 1e-6, "seam along u at {t}: {a} vs {b}");
            let c = fbm(t, 0.0, 3, 3, 4, 0.5, 9);
            let d = fbm(t, 1.0, 3, 3, 4, 0.5, 9);
            assert!((c - d).abs() < 1e-6, "seam along v at {t}");
            assert!((0.0..1.0).contains(&a) && (0.0..1.0).contains(&c));
        }
        assert_ne!(value(0.3, 0.3, 4, 4, 1), value(0.3, 0.3, 4, 4, 2));
    }

    #[test]
    fn cellular_noise_is_periodic() {
        let (a, ha) = cellular(0.01, 0.5, 8, 5);
        let (b, hb) = cellular(1.01, 0.5, 8, 5);
        assert!((a - b).abs() < 1e-4 && ha == hb);
    }
}
