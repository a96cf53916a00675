//! The family patterns: what a surface looks like at one point of its tile, independent of its
//! colour. A pattern gives an albedo multiplier (the asset's colour tints it), a height (turned
//! into the normal map) and a roughness multiplier. Every pattern is periodic over the tile.

use crate::noise::{cellular, fbm, fract, lerp, smoothstep, unit, value};

/// One point of a pattern.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Texel {
    /// Linear albedo multiplier per channel, in `[0, 1]`.
    pub albedo: [f32; 3],
    /// Surface height, about `[0, 1]` (relative: only its slopes matter, scaled by the
    /// material's bump strength).
    pub height: f32,
    /// Roughness multiplier in `[0, 1]`.
    pub roughness: f32,
}

impl Texel {
    fn grey(albedo: f32, height: f32, roughness: f32) -> Self {
        Self {
            albedo: [albedo; 3],
            height,
            roughness,
        }
    }
}

/// A family's pattern and its parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Pattern {
    /// Wood grain running along u: growth rings across v warped by noise, fine pores and
    /// streaks along the grain.
    Wood {
        /// Rings across one tile.
        rings: u32,
        /// How much darker the late wood of a ring is, 0–1.
        contrast: f32,
        /// How far noise bends the rings, in rings.
        warp: f32,
        /// Depth of the pores, 0–1.
        pores: f32,
    },
    /// Floorboards: wood grain on boards along u, `boards` across the tile, with dark seams and
    /// staggered end joints.
    Planks {
        /// Boards across one tile.
        boards: u32,
    },
    /// Paint over wood: a flat colour with the grain faintly in its relief.
    PaintedWood,
    /// Woven cloth: `threads` warp and weft threads across the tile in plain weave, with
    /// `slub` irregularity of thread thickness and colour.
    Weave {
        /// Threads across one tile.
        threads: u32,
        /// Irregularity of the threads, 0–1.
        slub: f32,
    },
    /// Velvet: a dense pile with soft crushed patches that catch the light differently.
    Velvet,
    /// Felt and baize: matted fibres, no weave.
    Felt,
    /// Leather: pebbled grain (cellular bumps) with darker creases.
    Leather,
    /// Brushed metal: fine streaks along u.
    Brushed,
    /// Polished metal or glass: almost flat, very faint waviness.
    Polished,
    /// Cast or wrought iron: mottled, pitted.
    CastIron,
    /// Powder coat: fine orange-peel relief.
    PowderCoat,
    /// Marble: a cloudy ground crossed by warped veins.
    Marble,
    /// Granite: speckled crystals of three tones.
    Granite,
    /// Slate: cleft layers along u.
    Slate,
    /// Travertine: bands with small pores.
    Travertine,
    /// Square tiles with grout lines: `tiles` across the tile.
    Tiles {
        /// Tiles across one texture tile.
        tiles: u32,
    },
    /// Unglazed fired clay: warm mottling and pores.
    Terracotta,
    /// Glazed ceramic: smooth with a faint mottled glaze.
    Glaze,
    /// Concrete: mottled grey with pits and aggregate.
    Concrete,
    /// Plastic: smooth with a very fine texture.
    Plastic,
    /// Rubber: fine matte grain.
    Rubber,
    /// Foam: open cells.
    Foam,
    /// Paper: fine fibres.
    Paper,
    /// Corrugated cardboard: faint flutes along u and fibres.
    Cardboard,
    /// Plaster: broad trowel marks.
    Plaster,
    /// Wall paint: roller stipple.
    Paint,
    /// Carpet: a dense looped pile.
    Carpet,
    /// Leaves: veins along u.
    Leaf,
    /// Soil: granular clumps.
    Soil,
    /// Sand: fine grains over low wind ripples across v.
    Sand,
    /// Lawn: dense blades along v in tufts, with drier and greener patches.
    Grass,
    /// Loose gravel: rounded pebbles of varied tone with dark gaps between them.
    Gravel,
    /// Paving slabs in running bond: `rows` rows of slabs twice as long as they are wide,
    /// each row shifted by half a slab, with sunken joints.
    Pavers {
        /// Rows of slabs across one tile.
        rows: u32,
    },
}

impl Pattern {
    /// The pattern at tile coordinates `(u, v)` in `[0, 1)`, with `seed` varying the noise;
    /// albedo and roughness clamped to `[0, 1]`.
    pub fn texel(&self, u: f32, v: f32, seed: u32) -> Texel {
        let t = self.unclamped(u, v, seed);
        Texel {
            albedo: t.albedo.map(|c| c.clamp(0.0, 1.0)),
            height: t.height,
            roughness: t.roughness.clamp(0.0, 1.0),
        }
    }

    fn unclamped(&self, u: f32, v: f32, seed: u32) -> Texel {
        match *self {
            Pattern::Wood {
                rings,
                contrast,
                warp,
                pores,
            } => wood(u, v, rings, contrast, warp, pores, seed),
            Pattern::Planks { boards } => planks(u, v, boards, seed),
            Pattern::PaintedWood => {
                let grain = wood(u, v, 6, 0.6, 1.5, 0.3, seed);
                let speck = value(u, v, 128, 128, seed ^ 5);
                Texel::grey(
                    0.96 + 0.03 * speck,
                    grain.height * 0.35,
                    0.95 + 0.05 * speck,
                )
            }
            Pattern::Weave { threads, slub } => weave(u, v, threads, slub, seed),
            Pattern::Velvet => {
                let crush = fbm(u, v, 3, 3, 4, 0.55, seed);
                let pile = value(u, v, 256, 256, seed ^ 1);
                Texel::grey(
                    0.72 + 0.25 * crush + 0.03 * pile,
                    pile * 0.3,
                    0.9 + 0.1 * crush,
                )
            }
            Pattern::Felt => {
                let fibre = fbm(u, v, 32, 32, 3, 0.6, seed);
                let blotch = fbm(u, v, 4, 4, 3, 0.5, seed ^ 3);
                Texel::grey(0.85 + 0.1 * fibre + 0.05 * blotch, fibre, 1.0)
            }
            Pattern::Leather => leather(u, v, seed),
            Pattern::Brushed => {
                let streak = fbm(u, v, 2, 128, 3, 0.5, seed);
                let fine = value(u, v, 8, 256, seed ^ 9);
                Texel::grey(
                    0.9 + 0.07 * streak + 0.03 * fine,
                    fine * 0.5,
                    0.8 + 0.2 * streak,
                )
            }
            Pattern::Polished => {
                let wave = fbm(u, v, 4, 4, 3, 0.5, seed);
                Texel::grey(0.98 + 0.02 * wave, wave * 0.2, 0.85 + 0.15 * wave)
            }
            Pattern::CastIron => {
                let mottle = fbm(u, v, 8, 8, 4, 0.55, seed);
                let (pit, _) = cellular(u, v, 24, seed ^ 2);
                let pitted = smoothstep(0.18, 0.05, pit);
                Texel::grey(
                    0.8 + 0.2 * mottle - 0.2 * pitted,
                    mottle * 0.6 - 0.5 * pitted + 0.5,
                    0.75 + 0.25 * mottle,
                )
            }
            Pattern::PowderCoat => {
                let peel = fbm(u, v, 24, 24, 3, 0.5, seed);
                Texel::grey(0.97 + 0.03 * peel, peel, 0.9 + 0.1 * peel)
            }
            Pattern::Marble => marble(u, v, seed),
            Pattern::Granite => granite(u, v, seed),
            Pattern::Slate => {
                let layer = fbm(u, v, 2, 24, 4, 0.6, seed);
                let cleft = fbm(u, v, 6, 6, 3, 0.5, seed ^ 4);
                Texel::grey(
                    0.75 + 0.2 * layer + 0.05 * cleft,
                    0.6 * layer + 0.4 * cleft,
                    0.9,
                )
            }
            Pattern::Travertine => {
                let band = fbm(u, v, 1, 12, 4, 0.6, seed);
                let (pore, _) = cellular(u, v, 20, seed ^ 6);
                let hole = smoothstep(0.16, 0.06, pore) * smoothstep(0.5, 0.7, band);
                Texel::grey(
                    0.82 + 0.18 * band - 0.25 * hole,
                    0.7 - 0.6 * hole,
                    0.9 + 0.1 * hole,
                )
            }
            Pattern::Tiles { tiles } => tile_grid(u, v, tiles, seed),
            Pattern::Terracotta => {
                let mottle = fbm(u, v, 6, 6, 4, 0.55, seed);
                let grit = unit((u * 256.0) as u32, (v * 256.0) as u32, seed ^ 8);
                Texel::grey(
                    0.78 + 0.2 * mottle + 0.02 * grit,
                    0.5 * mottle + 0.3 * grit,
                    0.9 + 0.1 * grit,
                )
            }
            Pattern::Glaze => {
                let pool = fbm(u, v, 4, 4, 4, 0.5, seed);
                Texel::grey(0.9 + 0.1 * pool, pool * 0.3, 0.8 + 0.2 * pool)
            }
            Pattern::Concrete => concrete(u, v, seed),
            Pattern::Plastic => {
                let fine = fbm(u, v, 64, 64, 2, 0.5, seed);
                Texel::grey(0.98 + 0.02 * fine, fine * 0.25, 0.95 + 0.05 * fine)
            }
            Pattern::Rubber => {
                let fine = fbm(u, v, 96, 96, 2, 0.5, seed);
                Texel::grey(0.93 + 0.07 * fine, fine, 1.0)
            }
            Pattern::Foam => {
                let (cell, _) = cellular(u, v, 40, seed);
                let open = smoothstep(0.35, 0.0, cell);
                Texel::grey(0.95 - 0.2 * open, 1.0 - open, 1.0)
            }
            Pattern::Paper => {
                let fibre = fbm(u, v, 48, 96, 3, 0.6, seed);
                Texel::grey(0.95 + 0.05 * fibre, fibre * 0.4, 0.95 + 0.05 * fibre)
            }
            Pattern::Cardboard => {
                let flute = 0.5 + 0.5 * triangle(v * 32.0);
                let fibre = fbm(u, v, 64, 32, 3, 0.6, seed);
                Texel::grey(
                    0.85 + 0.1 * fibre + 0.05 * flute,
                    0.5 * flute + 0.3 * fibre,
                    1.0,
                )
            }
            Pattern::Plaster => {
                let trowel = fbm(u, v, 3, 3, 5, 0.6, seed);
                let fine = value(u, v, 128, 128, seed ^ 1);
                Texel::grey(0.93 + 0.06 * trowel + 0.01 * fine, trowel, 0.9 + 0.1 * fine)
            }
            Pattern::Paint => {
                let stipple = fbm(u, v, 64, 64, 3, 0.55, seed);
                Texel::grey(0.97 + 0.03 * stipple, stipple, 0.95 + 0.05 * stipple)
            }
            Pattern::Carpet => {
                let tuft = value(u, v, 128, 128, seed);
                let loops = fbm(u, v, 256, 256, 1, 0.5, seed ^ 2);
                let shade = fbm(u, v, 4, 4, 3, 0.5, seed ^ 3);
                Texel::grey(
                    0.7 + 0.15 * tuft + 0.1 * loops + 0.05 * shade,
                    0.5 * tuft + 0.5 * loops,
                    1.0,
                )
            }
            Pattern::Leaf => {
                let vein = smoothstep(0.06, 0.0, triangle(v * 6.0 + 2.0 * u).abs() * 0.5);
                let cells = fbm(u, v, 16, 16, 3, 0.5, seed);
                Texel::grey(
                    0.82 + 0.12 * cells + 0.06 * vein,
                    0.4 * cells + 0.6 * vein,
                    0.9,
                )
            }
            Pattern::Soil => {
                let (clump, h) = cellular(u, v, 32, seed);
                let tone = (h >> 8) as f32 / (1u32 << 24) as f32;
                let crumb = fbm(u, v, 64, 64, 2, 0.5, seed ^ 1);
                Texel::grey(
                    0.7 + 0.2 * tone + 0.1 * crumb,
                    1.0 - clump.min(1.0) * 0.7 + 0.3 * crumb - 0.3,
                    1.0,
                )
            }
            Pattern::Sand => sand(u, v, seed),
            Pattern::Grass => grass(u, v, seed),
            Pattern::Gravel => gravel(u, v, seed),
            Pattern::Pavers { rows } => pavers(u, v, rows, seed),
        }
    }
}

/// A triangle wave in `[-1, 1]` with period 1 (a cheap, exactly periodic stand-in for a cosine).
fn triangle(x: f32) -> f32 {
    4.0 * (fract(x) - 0.5).abs() - 1.0
}

fn wood(u: f32, v: f32, rings: u32, contrast: f32, warp: f32, pores: f32, seed: u32) -> Texel {
    // Rings across v, bent by low-frequency noise that varies slowly along the grain (u).
    let bend = fbm(u, v, 2, 3, 3, 0.5, seed) - 0.5;
    let ring = fract(v * rings as f32 + warp * bend * 2.0);
    // Early wood light and wide, late wood a darker band at the ring's end.
    let late = smoothstep(0.6, 0.95, ring) * (1.0 - smoothstep(0.95, 1.0, ring));
    let streak = fbm(u, v, 4, 64, 3, 0.6, seed ^ 11);
    let pore_noise = value(u, v, 32, 256, seed ^ 13);
    let pore = smoothstep(0.75, 0.95, pore_noise) * pores;
    let a = 1.0 - contrast * late - 0.12 * streak - 0.25 * pore;
    // Late wood a touch redder-brown: less blue than red.
    let albedo = [a, a * 0.98, a * (1.0 - 0.06 * late)];
    Texel {
        albedo: albedo.map(|c| c.clamp(0.0, 1.0)),
        height: (0.6 - 0.3 * late + 0.2 * streak - 0.5 * pore).clamp(0.0, 1.0),
        roughness: 0.85 + 0.15 * pore + 0.05 * late,
    }
}

fn planks(u: f32, v: f32, boards: u32, seed: u32) -> Texel {
    let row = (v * boards as f32).floor();
    let across = fract(v * boards as f32);
    // Each board is offset along u by its own fraction; a joint every half tile.
    let offset = unit(row as u32, 0, seed ^ 21);
    let along = fract(u * 2.0 + offset);
    let board = (row as u32) * 2 + (fract(u + offset / 2.0) * 2.0).floor() as u32;
    let board_seed = seed.wrapping_add(board.wrapping_mul(101));
    let mut t = wood(u, fract(v + offset), 9, 0.35, 1.2, 0.4, board_seed);
    let tone = 0.85 + 0.15 * unit(board, 1, seed ^ 23);
    let seam = smoothstep(0.012, 0.0, across.min(1.0 - across)).max(smoothstep(
        0.006,
        0.0,
        along.min(1.0 - along),
    ));
    t.albedo = t.albedo.map(|c| lerp(c * tone, 0.35, seam));
    t.height = lerp(t.height * 0.6 + 0.4, 0.0, seam);
    t.roughness = lerp(t.roughness, 1.0, seam);
    t
}

fn weave(u: f32, v: f32, threads: u32, slub: f32, seed: u32) -> Texel {
    let n = threads as f32;
    let (x, y) = (u * n, v * n);
    let (i, j) = (x.floor() as u32, y.floor() as u32);
    let (fx, fy) = (fract(x), fract(y));
    // Plain weave: the warp thread (along v) is on top where i + j is even.
    let warp_on_top = (i + j) % 2 == 0;
    let bump = |f: f32| 1.0 - (2.0 * f - 1.0) * (2.0 * f - 1.0);
    let thread_tone = |k: u32, axis: u32| 1.0 - slub * 0.25 * unit(k, axis, seed);
    let (h, tone) = if warp_on_top {
        (bump(fx) * (0.6 + 0.4 * bump(fy)), thread_tone(i, 0))
    } else {
        (bump(fy) * (0.6 + 0.4 * bump(fx)), thread_tone(j, 1))
    };
    let fuzz = value(u, v, 256, 256, seed ^ 3);
    let blotch = fbm(u, v, 4, 4, 3, 0.5, seed ^ 5);
    let a = (0.72 + 0.2 * h) * tone + 0.04 * fuzz + slub * 0.06 * blotch;
    Texel::grey(a.clamp(0.0, 1.0), h, 0.95 + 0.05 * fuzz)
}

fn leather(u: f32, v: f32, seed: u32) -> Texel {
    let (d, _) = cellular(u, v, 48, seed);
    let pebble = 1.0 - smoothstep(0.0, 0.75, d);
    let crease = fbm(u, v, 6, 6, 4, 0.55, seed ^ 7);
    let wrinkle = smoothstep(0.05, 0.0, (crease - 0.5).abs()) * 0.5;
    let a = 0.82 + 0.12 * pebble - 0.15 * wrinkle + 0.06 * crease;
    Texel::grey(
        a.clamp(0.0, 1.0),
        (0.7 * pebble - 0.3 * wrinkle + 0.3).clamp(0.0, 1.0),
        0.75 + 0.25 * (1.0 - pebble),
    )
}

fn marble(u: f32, v: f32, seed: u32) -> Texel {
    let cloud = fbm(u, v, 3, 3, 5, 0.55, seed);
    let warp = fbm(u, v, 2, 2, 4, 0.6, seed ^ 1);
    let line = fbm(fract(u + 0.3 * warp), v, 2, 2, 5, 0.6, seed ^ 2);
    let vein = smoothstep(0.025, 0.0, (line - 0.5).abs());
    let thin = smoothstep(0.008, 0.0, (fbm(u, v, 4, 4, 5, 0.6, seed ^ 3) - 0.5).abs());
    let a = 0.93 + 0.07 * cloud - 0.45 * vein - 0.25 * thin;
    Texel {
        albedo: [a, a, a * (1.0 + 0.02 * vein)].map(|c| c.clamp(0.0, 1.0)),
        height: 0.5 - 0.1 * vein,
        roughness: 0.9 + 0.1 * vein,
    }
}

fn granite(u: f32, v: f32, seed: u32) -> Texel {
    let (d, h) = cellular(u, v, 96, seed);
    let kind = h % 10;
    let crystal = match kind {
        0..=2 => 0.3,
        3..=7 => 0.75,
        _ => 1.0,
    };
    let fine = value(u, v, 256, 256, seed ^ 4);
    let a = crystal * (0.9 + 0.1 * fine);
    Texel::grey(a, 0.5 + 0.3 * (1.0 - d.min(1.0)) * 0.5, 0.85 + 0.15 * fine)
}

fn tile_grid(u: f32, v: f32, tiles: u32, seed: u32) -> Texel {
    let n = tiles as f32;
    let (x, y) = (u * n, v * n);
    let (fx, fy) = (fract(x), fract(y));
    let edge = fx.min(1.0 - fx).min(fy).min(1.0 - fy);
    let grout = smoothstep(0.018, 0.01, edge);
    let bevel = smoothstep(0.01, 0.05, edge);
    let tile = unit(x.floor() as u32, y.floor() as u32, seed);
    let glaze = fbm(u, v, 8, 8, 3, 0.5, seed ^ 2);
    let face = 0.93 + 0.05 * tile + 0.02 * glaze;
    let a = lerp(face, 0.55, grout);
    Texel::grey(a, bevel * (1.0 - grout), lerp(0.6, 1.0, grout))
}

fn concrete(u: f32, v: f32, seed: u32) -> Texel {
    let mottle = fbm(u, v, 4, 4, 5, 0.55, seed);
    let (pit, _) = cellular(u, v, 40, seed ^ 3);
    let hole = smoothstep(0.1, 0.03, pit);
    let (grain, h) = cellular(u, v, 128, seed ^ 5);
    let aggregate = if h % 7 == 0 {
        0.06 * (1.0 - grain.min(1.0))
    } else {
        0.0
    };
    Texel::grey(
        (0.8 + 0.18 * mottle - 0.3 * hole + aggregate).clamp(0.0, 1.0),
        (0.6 + 0.2 * mottle - 0.5 * hole).clamp(0.0, 1.0),
        1.0 - 0.1 * mottle,
    )
}

fn sand(u: f32, v: f32, seed: u32) -> Texel {
    // Ripples a few centimetres apart, wandering along u; grains at texel scale.
    let wander = fbm(u, v, 2, 2, 3, 0.5, seed) - 0.5;
    let ripple = 0.5 + 0.5 * triangle(v * 9.0 + 1.5 * wander);
    let grain = unit((u * 256.0) as u32, (v * 256.0) as u32, seed ^ 3);
    let patch = fbm(u, v, 4, 4, 3, 0.5, seed ^ 5);
    Texel::grey(
        0.85 + 0.08 * patch + 0.07 * grain - 0.04 * ripple,
        0.7 * ripple + 0.3 * grain,
        0.9 + 0.1 * grain,
    )
}

fn grass(u: f32, v: f32, seed: u32) -> Texel {
    // Blades: noise stretched along v, thin across u; tufts and patches vary the tone.
    let blade = fbm(u, v, 128, 24, 2, 0.5, seed);
    let (tuft, _) = cellular(u, v, 16, seed ^ 7);
    let patch = fbm(u, v, 3, 3, 4, 0.55, seed ^ 9);
    let shade = 0.7 + 0.3 * blade - 0.15 * tuft.min(1.0);
    let dry = smoothstep(0.55, 0.8, patch) * 0.35;
    // Dry grass is yellower: more red, less blue than green.
    let albedo = [shade * (0.85 + dry), shade, shade * (0.8 - 0.5 * dry)];
    Texel {
        albedo,
        height: 0.7 * blade + 0.3 * (1.0 - tuft.min(1.0)),
        roughness: 0.9 + 0.1 * blade,
    }
}

fn gravel(u: f32, v: f32, seed: u32) -> Texel {
    let (d, h) = cellular(u, v, 32, seed);
    let stone = 1.0 - smoothstep(0.35, 0.75, d);
    let tone = 0.65 + 0.35 * ((h >> 8) & 0xFF) as f32 / 255.0;
    let warm = ((h >> 16) & 0xFF) as f32 / 255.0 * 0.08;
    let fine = value(u, v, 256, 256, seed ^ 2);
    let a = lerp(0.3, tone * (0.95 + 0.05 * fine), stone);
    Texel {
        albedo: [a * (1.0 + warm), a, a * (1.0 - warm)],
        height: stone * (0.8 + 0.2 * fine),
        roughness: lerp(1.0, 0.85 + 0.1 * fine, stone),
    }
}

fn pavers(u: f32, v: f32, rows: u32, seed: u32) -> Texel {
    let n = rows as f32;
    let y = v * n;
    let row = y.floor();
    // Slabs twice as long as wide: `rows / 2` slabs per row along u, odd rows shifted half.
    let per_row = (rows / 2).max(1) as f32;
    let x = u * per_row + 0.5 * (row as u32 % 2) as f32;
    let (fx, fy) = (fract(x), fract(y));
    // Distance to the nearest joint in row heights.
    let edge = (fx.min(1.0 - fx) * n / per_row).min(fy.min(1.0 - fy));
    let joint = smoothstep(0.03, 0.015, edge);
    let slab = unit((x.floor() as u32) % per_row as u32, row as u32, seed);
    let surface = concrete(u, v, seed ^ 11);
    let face = (0.88 + 0.1 * slab) * surface.albedo[0];
    Texel::grey(
        lerp(face, 0.45, joint),
        lerp(0.5 + 0.3 * surface.height, 0.0, joint),
        lerp(0.85 + 0.1 * slab, 1.0, joint),
    )
}

#[cfg(test)]
mod tests {
    #[test]
    fn every_pattern_stays_in_range() {
        for pattern in crate::library::library().iter().map(|m| m.pattern) {
            for k in 0..64 {
                let (u, v) = ((k % 8) as f32 / 8.0, (k / 8) as f32 / 8.0);
                let t = pattern.texel(u, v, 1);
                assert!(
                    t.albedo.iter().all(|c| (0.0..=1.0).contains(c))
                        && (0.0..=1.0).contains(&t.roughness)
                        && t.height.is_finite(),
                    "{pattern:?} at ({u}, {v}): {t:?}"
                );
            }
        }
    }
}
