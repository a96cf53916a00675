//! Small items of work, worship and service places: candle and desk globe.

use std::f32::consts::{PI, TAU};

use rand_chacha::ChaCha8Rng;

use super::builder::Builder;
use crate::random::{coin, color, int, uniform};
use nalgebra::Vector3;
use scenethesis_primitives::{arc, rotated_ellipsoid, rotation_from_y, sphere};
use scenethesis_scene_graph::{Asset, Placement};

/// Wax colours: ivory, white, church red, cream, beeswax.
const WAX: &[[f32; 3]] = &[
    [0.93, 0.9, 0.8],
    [0.96, 0.96, 0.94],
    [0.62, 0.08, 0.08],
    [0.95, 0.88, 0.7],
    [0.85, 0.65, 0.3],
];

/// Holder metals: brass, silver, wrought iron.
const HOLDER: &[[f32; 3]] = &[[0.78, 0.6, 0.3], [0.8, 0.8, 0.82], [0.12, 0.12, 0.12]];

/// Candle: either a pillar candle (0.05–0.09 across, 0.08–0.2 tall) on a round dish holder
/// (0.1–0.15 across), or a taper candle (0.022 across, 0.18–0.28 tall) in a candlestick (foot
/// 0.08–0.12 across, 0.08–0.22 tall, with a knop and a drip cup); a wick and a small flame on
/// top. Overall 0.12–0.55 tall.
pub(crate) fn candle(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let wax = b.material("wax", color(rng, WAX, 0.03), 0.6);
    let holder = b.metal("holder", color(rng, HOLDER, 0.03), 0.35);
    let top = if coin(rng, 0.5) {
        pillar(&mut b, wax, holder, rng)
    } else {
        taper(&mut b, wax, holder, rng)
    };
    let wick = b.material("wick", [0.08, 0.07, 0.06], 0.9);
    let flame = b.material("flame", [1.0, 0.78, 0.3], 0.2);
    b.frustum(
        "wick",
        wick,
        [0.0, 0.0],
        0.0015,
        0.0012,
        top - 0.001,
        top + 0.012,
        6,
    );
    b.ellipsoid(
        "flame",
        flame,
        [0.0, top + 0.024, 0.0],
        [0.006, 0.015, 0.006],
    );
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// A pillar candle on a dish; returns the height of the candle's top.
fn pillar(b: &mut Builder, wax: usize, holder: usize, rng: &mut ChaCha8Rng) -> f32 {
    let r = 0.5 * uniform(rng, 0.05, 0.09);
    let dish = (r + uniform(rng, 0.02, 0.035)).max(0.05);
    b.frustum("dish", holder, [0.0, 0.0], dish, dish, 0.0, 0.008, 24);
    b.frustum(
        "dish_rim",
        holder,
        [0.0, 0.0],
        dish,
        1.06 * dish,
        0.007,
        0.018,
        24,
    );
    let top = 0.008 + uniform(rng, 0.08, 0.2);
    b.frustum("candle", wax, [0.0, 0.0], r, r, 0.007, top, 20);
    top
}

/// A taper candle in a candlestick with a foot, a stem with a knop and a drip cup; returns the
/// height of the candle's top.
fn taper(b: &mut Builder, wax: usize, holder: usize, rng: &mut ChaCha8Rng) -> f32 {
    let foot = 0.5 * uniform(rng, 0.08, 0.12);
    let stem_top = uniform(rng, 0.08, 0.22);
    b.frustum("foot", holder, [0.0, 0.0], foot, foot, 0.0, 0.01, 24);
    b.frustum(
        "foot_dome",
        holder,
        [0.0, 0.0],
        foot,
        0.014,
        0.009,
        0.035,
        24,
    );
    b.frustum(
        "stem",
        holder,
        [0.0, 0.0],
        0.011,
        0.009,
        0.034,
        stem_top,
        12,
    );
    let knop = 0.034 + 0.45 * (stem_top - 0.034);
    b.ellipsoid("knop", holder, [0.0, knop, 0.0], [0.02, 0.015, 0.02]);
    b.frustum(
        "drip_cup",
        holder,
        [0.0, 0.0],
        0.012,
        0.032,
        stem_top - 0.001,
        stem_top + 0.012,
        20,
    );
    let top = stem_top + uniform(rng, 0.18, 0.28);
    b.frustum(
        "candle",
        wax,
        [0.0, 0.0],
        0.011,
        0.01,
        stem_top + 0.002,
        top,
        14,
    );
    top
}

/// Ocean blues of printed globes.
const OCEAN: &[[f32; 3]] = &[[0.2, 0.42, 0.7], [0.55, 0.72, 0.85], [0.1, 0.18, 0.35]];

/// Land tints: green, tan, antique parchment.
const LAND: &[[f32; 3]] = &[[0.35, 0.55, 0.3], [0.8, 0.7, 0.48], [0.88, 0.8, 0.6]];

/// Earth's axial tilt, radians (23.4°).
const AXIAL_TILT: f32 = 0.408;

/// Desk globe: a sphere 0.2–0.32 across on an axis tilted 23.4° toward +X, held at its poles
/// by a half meridian ring, on a stem and a round base (0.14–0.2 across); 0.28–0.49 tall. Blue
/// (or antique) oceans and 4–7 land masses raised slightly off the sphere.
pub(crate) fn globe(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let ocean = b.material("ocean", color(rng, OCEAN, 0.03), 0.35);
    let land = b.material("land", color(rng, LAND, 0.03), 0.5);
    let stand = if coin(rng, 0.5) {
        b.metal("stand", color(rng, HOLDER, 0.03), 0.3)
    } else {
        b.material("stand", [0.35, 0.22, 0.12], 0.5)
    };
    let r = 0.5 * uniform(rng, 0.2, 0.32);
    let base = 0.5 * uniform(rng, 0.14, 0.2);
    let ring = r + 0.012;
    let stem_top = uniform(rng, 0.06, 0.16);
    let centre = [0.0, stem_top + ring, 0.0];
    b.frustum("base", stand, [0.0, 0.0], base, base, 0.0, 0.015, 28);
    b.frustum(
        "base_top",
        stand,
        [0.0, 0.0],
        base,
        0.3 * base,
        0.014,
        0.035,
        28,
    );
    b.frustum(
        "stem",
        stand,
        [0.0, 0.0],
        0.012,
        0.009,
        0.034,
        stem_top + 0.004,
        12,
    );
    b.add(sphere("sphere", ocean, centre, r, 14, 24));
    continents(&mut b, land, centre, r, rng);
    meridian(&mut b, stand, centre, r, ring);
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// 4–7 flat land masses lying on the sphere of radius `r` about `centre`.
fn continents(b: &mut Builder, land: usize, centre: [f32; 3], r: f32, rng: &mut ChaCha8Rng) {
    for k in 0..int(rng, 4, 7) {
        let (lon, lat) = (uniform(rng, 0.0, TAU), uniform(rng, -1.1, 1.1));
        let dir = Vector3::new(lat.cos() * lon.cos(), lat.sin(), lat.cos() * lon.sin());
        let at = [0, 1, 2].map(|i| centre[i] + 0.96 * r * dir[i]);
        let radii = [
            uniform(rng, 0.2, 0.45) * r,
            0.06 * r,
            uniform(rng, 0.15, 0.35) * r,
        ];
        let rot = rotation_from_y(&dir);
        b.add(rotated_ellipsoid(
            &format!("land_{k}"),
            land,
            at,
            radii,
            &rot,
        ));
    }
}

/// The half meridian ring of radius `ring` in the x-y plane, from the south pole round the +X
/// side to the north pole, with the pins holding the sphere at its poles.
fn meridian(b: &mut Builder, stand: usize, centre: [f32; 3], r: f32, ring: f32) {
    let (s, c) = AXIAL_TILT.sin_cos();
    let south = [-s, -c, 0.0];
    let side = [c, -s, 0.0];
    let points = arc(centre, south, side, ring, 0.0, PI, 24);
    b.polyline("meridian", stand, &points, 0.005);
    for (name, sign) in [("pin_south", 1.0f32), ("pin_north", -1.0)] {
        let at = |d: f32| [0, 1, 2].map(|i| centre[i] + sign * d * south[i]);
        b.tube(name, stand, at(0.95 * r), at(ring + 0.004), 0.004, 0.004, 8);
    }
}
