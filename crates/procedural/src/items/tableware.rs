//! Tableware and drinks: mugs, cups, plates, bowls, vases, bottles, cans, fruit, water bottles
//! and paint cans. Vessels are a base plus a ring of wall slabs, hollow inside.

use std::f32::consts::{FRAC_PI_2, PI};

use rand_chacha::ChaCha8Rng;

use super::builder::Builder;
use crate::random::{color, pick, uniform};
use scenethesis_primitives::{arc, disc};
use scenethesis_scene_graph::{Asset, Placement};

const CERAMICS: &[[f32; 3]] = &[
    [0.95, 0.95, 0.93],
    [0.15, 0.25, 0.5],
    [0.7, 0.2, 0.15],
    [0.2, 0.45, 0.35],
    [0.9, 0.8, 0.55],
    [0.15, 0.15, 0.15],
    [0.6, 0.75, 0.85],
];

/// Ceramic mug with a handle, hollow: Ø 0.075–0.09, 0.088–0.105 m high (handle adds ≈ 0.03).
pub(crate) fn mug(rng: &mut ChaCha8Rng) -> Asset {
    let r = uniform(rng, 0.0375, 0.045);
    let h = uniform(rng, 0.088, 0.105);
    let wall = uniform(rng, 0.004, 0.005);
    let mut b = Builder::new();
    let glaze = b.material("glaze", color(rng, CERAMICS, 0.04), 0.3);
    let base = 0.007;
    b.frustum("base", glaze, [0.0, 0.0], r, r, 0.0, base, 24);
    b.ring(
        "wall",
        glaze,
        [0.0, 0.0],
        (r - wall, r, 0.002),
        (r - wall, r, h),
        24,
    );
    let hr = h * uniform(rng, 0.28, 0.34);
    let pts = arc(
        [r - 0.004, h * 0.52, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        hr,
        -FRAC_PI_2,
        FRAC_PI_2,
        8,
    );
    b.polyline("handle", glaze, &pts, 0.005);
    b.interior(disc([0.0, 0.0], r - wall - 0.004, 12), base);
    b.finish(Placement::Surface, [0.9, 1.15])
}

/// Tapered drinking cup (paper, glass or ceramic), hollow: Ø 0.07–0.09 at the rim, 0.07–0.12 m.
pub(crate) fn cup(rng: &mut ChaCha8Rng) -> Asset {
    let r_top = uniform(rng, 0.035, 0.045);
    let r_bottom = r_top * uniform(rng, 0.65, 0.85);
    let h = uniform(rng, 0.07, 0.12);
    let mut b = Builder::new();
    let kind = uniform(rng, 0.0, 1.0);
    let shell = if kind < 0.35 {
        b.glass("cup_glass", [0.85, 0.92, 0.95], 0.35)
    } else {
        b.material("cup", color(rng, CERAMICS, 0.05), 0.5)
    };
    let wall = 0.0025;
    let base = 0.005;
    b.frustum("base", shell, [0.0, 0.0], r_bottom, r_bottom, 0.0, base, 24);
    b.ring(
        "wall",
        shell,
        [0.0, 0.0],
        (r_bottom - wall, r_bottom, 0.001),
        (r_top - wall, r_top, h),
        24,
    );
    b.interior(disc([0.0, 0.0], r_bottom - wall - 0.004, 12), base);
    b.finish(Placement::Surface, [0.85, 1.2])
}

/// Dinner plate with a raised rim: Ø 0.20–0.28, 0.018–0.028 m high.
pub(crate) fn plate(rng: &mut ChaCha8Rng) -> Asset {
    let r = uniform(rng, 0.1, 0.14);
    let h = uniform(rng, 0.018, 0.028);
    let mut b = Builder::new();
    let glaze = b.material("plate_glaze", color(rng, CERAMICS, 0.03), 0.25);
    let flat = r * 0.68;
    b.frustum(
        "foot",
        glaze,
        [0.0, 0.0],
        flat * 0.8,
        flat * 0.85,
        0.0,
        0.006,
        32,
    );
    b.frustum("well", glaze, [0.0, 0.0], flat, flat, 0.004, 0.009, 32);
    b.ring(
        "rim",
        glaze,
        [0.0, 0.0],
        (flat - 0.004, flat + 0.002, 0.004),
        (r - 0.004, r, h),
        32,
    );
    b.top("top", disc([0.0, 0.0], flat - 0.008, 12), 0.009);
    b.finish(Placement::Surface, [0.85, 1.15])
}

/// Bowl with a curved wall (two tilted slab rings), hollow: Ø 0.12–0.22, 0.05–0.10 m high.
pub(crate) fn bowl(rng: &mut ChaCha8Rng) -> Asset {
    let r = uniform(rng, 0.06, 0.11);
    let h = uniform(rng, 0.05, 0.1).min(r * 1.1);
    let wall = 0.004;
    let mut b = Builder::new();
    let glaze = b.material("bowl_glaze", color(rng, CERAMICS, 0.04), 0.3);
    let r_foot = r * 0.45;
    let base = 0.007;
    b.frustum("foot", glaze, [0.0, 0.0], r_foot, r_foot, 0.0, base, 24);
    let r_mid = r * 0.86;
    let y_mid = h * 0.5;
    b.ring(
        "wall_low",
        glaze,
        [0.0, 0.0],
        (r_foot - wall, r_foot, 0.002),
        (r_mid - wall, r_mid, y_mid),
        24,
    );
    b.ring(
        "wall_high",
        glaze,
        [0.0, 0.0],
        (r_mid - wall, r_mid, y_mid - 0.001),
        (r - wall, r, h),
        24,
    );
    b.interior(disc([0.0, 0.0], r_foot - wall - 0.003, 10), base);
    b.finish(Placement::Surface, [0.8, 1.25])
}

/// Adds a hollow vessel of revolution through the profile `(radius, height)` from the base up,
/// wall thickness `wall`, with a solid base disc.
fn vessel(b: &mut Builder, name: &str, material: usize, profile: &[(f32, f32)], wall: f32) {
    let (r0, _) = profile[0];
    b.frustum(
        &format!("{name}_base"),
        material,
        [0.0, 0.0],
        r0,
        r0,
        0.0,
        wall * 1.5,
        24,
    );
    for (k, w) in profile.windows(2).enumerate() {
        let ((ra, ya), (rb, yb)) = (w[0], w[1]);
        b.ring(
            &format!("{name}_wall_{k}"),
            material,
            [0.0, 0.0],
            (ra - wall, ra, ya),
            (rb - wall, rb, yb),
            20,
        );
    }
}

/// Flower vase, hollow, in one of several profiles: 0.18–0.40 m high, Ø 0.08–0.18.
pub(crate) fn vase(rng: &mut ChaCha8Rng) -> Asset {
    let h = uniform(rng, 0.18, 0.4);
    let belly = uniform(rng, 0.04, 0.09);
    let neck = belly * uniform(rng, 0.45, 0.75);
    let lip = neck * uniform(rng, 1.0, 1.35);
    let mut b = Builder::new();
    let glaze = if uniform(rng, 0.0, 1.0) < 0.25 {
        b.glass(
            "vase_glass",
            color(rng, &[[0.7, 0.85, 0.9], [0.5, 0.7, 0.5]], 0.05),
            0.4,
        )
    } else {
        b.material("vase_glaze", color(rng, CERAMICS, 0.06), 0.3)
    };
    let profile = [
        (belly * 0.7, 0.0),
        (belly, h * 0.35),
        (belly * 0.9, h * 0.55),
        (neck, h * 0.8),
        (lip, h),
    ];
    vessel(&mut b, "vase", glaze, &profile, 0.004);
    b.finish(Placement::Surface, [0.8, 1.25])
}

/// Closed glass bottle (wine, beer or oil): 0.22–0.32 m high, Ø 0.06–0.08.
pub(crate) fn bottle(rng: &mut ChaCha8Rng) -> Asset {
    let h = uniform(rng, 0.22, 0.32);
    let r = uniform(rng, 0.03, 0.04);
    let rn = uniform(rng, 0.011, 0.015);
    let mut b = Builder::new();
    let glass = b.glass(
        "bottle_glass",
        color(
            rng,
            &[[0.1, 0.35, 0.15], [0.4, 0.22, 0.08], [0.8, 0.9, 0.9]],
            0.04,
        ),
        0.75,
    );
    let label = b.material(
        "label",
        color(
            rng,
            &[[0.95, 0.92, 0.85], [0.8, 0.2, 0.15], [0.15, 0.2, 0.4]],
            0.04,
        ),
        0.7,
    );
    let cap = b.metal(
        "cap",
        color(
            rng,
            &[[0.8, 0.7, 0.3], [0.7, 0.7, 0.72], [0.6, 0.1, 0.1]],
            0.03,
        ),
        0.4,
    );
    let body = h * uniform(rng, 0.55, 0.65);
    let shoulder = body + h * 0.12;
    b.frustum("body", glass, [0.0, 0.0], r, r, 0.0, body, 24);
    b.frustum(
        "label",
        label,
        [0.0, 0.0],
        r + 0.0008,
        r + 0.0008,
        body * 0.35,
        body * 0.85,
        24,
    );
    b.frustum("shoulder", glass, [0.0, 0.0], r, rn, body, shoulder, 24);
    b.frustum("neck", glass, [0.0, 0.0], rn, rn, shoulder, h - 0.02, 16);
    b.frustum(
        "cap",
        cap,
        [0.0, 0.0],
        rn + 0.0015,
        rn + 0.0015,
        h - 0.02,
        h,
        16,
    );
    b.finish(Placement::Surface, [0.85, 1.15])
}

/// Drinks can: Ø 0.066, 0.115–0.168 m high (330 ml to 500 ml), printed colours.
pub(crate) fn can(rng: &mut ChaCha8Rng) -> Asset {
    let h = *pick(rng, &[0.115f32, 0.122, 0.146, 0.168]);
    let r = if h > 0.14 {
        0.033
    } else {
        uniform(rng, 0.031, 0.033)
    };
    let mut b = Builder::new();
    let print = b.material(
        "can_print",
        color(
            rng,
            &[
                [0.8, 0.05, 0.05],
                [0.1, 0.3, 0.8],
                [0.1, 0.6, 0.2],
                [0.95, 0.8, 0.1],
                [0.1, 0.1, 0.1],
                [0.85, 0.85, 0.88],
            ],
            0.05,
        ),
        0.3,
    );
    let alu = b.metal("aluminium", [0.8, 0.8, 0.82], 0.3);
    b.frustum("bottom", alu, [0.0, 0.0], r * 0.85, r, 0.0, 0.008, 24);
    b.frustum("body", print, [0.0, 0.0], r, r, 0.008, h - 0.012, 24);
    b.frustum("neck", alu, [0.0, 0.0], r, r * 0.85, h - 0.012, h, 24);
    b.top("top", disc([0.0, 0.0], r * 0.7, 8), h);
    b.finish(Placement::Surface, [0.95, 1.05])
}

/// A piece of fruit: apple (Ø 0.07–0.09), orange (Ø 0.07–0.09), pear (0.09–0.12 high), lemon
/// or banana (0.17–0.22 long).
pub(crate) fn fruit(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let stem = b.material("stem", [0.35, 0.25, 0.12], 0.8);
    // Depth of the contact patch that keeps the fruit from rolling off its lowest vertex: 2 mm
    // for round fruit; a banana's octagonal belly needs 6 mm to lie on a flat strip.
    let base_depth = match rng_index(rng, 5) {
        0 => {
            let r = uniform(rng, 0.035, 0.045);
            let skin = b.material(
                "apple_skin",
                color(
                    rng,
                    &[[0.75, 0.08, 0.08], [0.45, 0.7, 0.15], [0.85, 0.7, 0.2]],
                    0.05,
                ),
                0.4,
            );
            b.ellipsoid("apple", skin, [0.0, r * 0.9, 0.0], [r, r * 0.9, r]);
            b.frustum(
                "stem",
                stem,
                [0.0, 0.0],
                0.002,
                0.0015,
                r * 1.7,
                r * 1.7 + 0.015,
                6,
            );
            0.002
        }
        1 => {
            let r = uniform(rng, 0.035, 0.045);
            let skin = b.material("orange_peel", color(rng, &[[0.95, 0.5, 0.05]], 0.04), 0.6);
            b.ellipsoid("orange", skin, [0.0, r, 0.0], [r, r * 0.96, r]);
            0.002
        }
        2 => {
            let h = uniform(rng, 0.09, 0.12);
            let skin = b.material(
                "pear_skin",
                color(rng, &[[0.65, 0.75, 0.2], [0.8, 0.6, 0.2]], 0.05),
                0.5,
            );
            let r = h * 0.3;
            b.ellipsoid("pear_body", skin, [0.0, r, 0.0], [r, r, r]);
            b.ellipsoid(
                "pear_neck",
                skin,
                [0.0, h * 0.62, 0.0],
                [r * 0.62, h * 0.3, r * 0.62],
            );
            b.frustum(
                "stem",
                stem,
                [0.0, 0.0],
                0.002,
                0.0015,
                h * 0.9,
                h + 0.012,
                6,
            );
            0.002
        }
        3 => {
            let l = uniform(rng, 0.07, 0.09);
            let skin = b.material(
                "lemon_peel",
                color(rng, &[[0.95, 0.85, 0.15], [0.5, 0.75, 0.15]], 0.04),
                0.6,
            );
            b.ellipsoid(
                "lemon",
                skin,
                [0.0, l * 0.33, 0.0],
                [l * 0.5, l * 0.33, l * 0.33],
            );
            0.002
        }
        _ => {
            let l = uniform(rng, 0.17, 0.22);
            let skin = b.material(
                "banana_peel",
                color(rng, &[[0.95, 0.8, 0.15], [0.7, 0.75, 0.2]], 0.04),
                0.5,
            );
            let bend = uniform(rng, 0.5, 0.8);
            let radius = l / bend;
            let pts = arc(
                [0.0, radius + 0.018, 0.0],
                [0.0, -1.0, 0.0],
                [1.0, 0.0, 0.0],
                radius,
                -bend / 2.0,
                bend / 2.0,
                6,
            );
            let n = pts.len() - 1;
            for (k, w) in pts.windows(2).enumerate() {
                let t = (k as f32 + 0.5) / n as f32;
                let rr = 0.018 * (1.0 - (2.0 * t - 1.0).powi(2) * 0.6);
                b.tube(&format!("banana_{k}"), skin, w[0], w[1], rr, rr, 8);
            }
            b.tube(
                "banana_tip",
                stem,
                pts[n],
                [pts[n][0] + 0.01, pts[n][1] + 0.004, 0.0],
                0.005,
                0.004,
                6,
            );
            0.006
        }
    };
    b.flatten_base(base_depth);
    b.finish(Placement::Surface, [0.85, 1.2])
}

/// A random index in `0..n`.
fn rng_index(rng: &mut ChaCha8Rng, n: usize) -> usize {
    (uniform(rng, 0.0, n as f32 - 1e-3) as usize).min(n - 1)
}

/// Reusable water bottle (plastic or steel) with a cap: Ø 0.065–0.08, 0.20–0.27 m high.
pub(crate) fn water_bottle(rng: &mut ChaCha8Rng) -> Asset {
    let r = uniform(rng, 0.0325, 0.04);
    let h = uniform(rng, 0.2, 0.27);
    let mut b = Builder::new();
    let shell = if uniform(rng, 0.0, 1.0) < 0.5 {
        b.metal(
            "steel",
            color(
                rng,
                &[
                    [0.75, 0.75, 0.78],
                    [0.2, 0.4, 0.7],
                    [0.15, 0.15, 0.15],
                    [0.7, 0.2, 0.3],
                ],
                0.04,
            ),
            0.35,
        )
    } else {
        b.glass("pet", [0.75, 0.88, 0.95], 0.45)
    };
    let cap = b.material(
        "cap",
        color(
            rng,
            &[[0.1, 0.1, 0.1], [0.1, 0.3, 0.75], [0.9, 0.9, 0.9]],
            0.03,
        ),
        0.5,
    );
    let shoulder = h * 0.8;
    b.frustum("body", shell, [0.0, 0.0], r, r, 0.0, shoulder, 24);
    b.frustum(
        "shoulder",
        shell,
        [0.0, 0.0],
        r,
        r * 0.62,
        shoulder,
        h - 0.035,
        24,
    );
    b.frustum("cap", cap, [0.0, 0.0], r * 0.66, r * 0.62, h - 0.035, h, 16);
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// Paint tin with a closed lid and a bail folded down: Ø 0.10–0.18, 0.12–0.20 m high.
pub(crate) fn paint_can(rng: &mut ChaCha8Rng) -> Asset {
    let r = uniform(rng, 0.05, 0.09);
    let h = uniform(rng, 0.12, 0.2).max(r * 1.3);
    let mut b = Builder::new();
    let tin = b.metal("tin", [0.75, 0.75, 0.77], 0.35);
    let label = b.material(
        "paint_label",
        color(
            rng,
            &[
                [0.9, 0.9, 0.88],
                [0.8, 0.15, 0.1],
                [0.1, 0.3, 0.7],
                [0.95, 0.75, 0.1],
                [0.2, 0.55, 0.3],
            ],
            0.05,
        ),
        0.6,
    );
    b.frustum("body", tin, [0.0, 0.0], r, r, 0.0, h - 0.006, 32);
    b.frustum(
        "label",
        label,
        [0.0, 0.0],
        r + 0.0008,
        r + 0.0008,
        h * 0.15,
        h * 0.8,
        32,
    );
    b.frustum(
        "lid",
        tin,
        [0.0, 0.0],
        r + 0.002,
        r - 0.004,
        h - 0.006,
        h,
        32,
    );
    let pts = arc(
        [0.0, h - 0.02, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, -1.0],
        r + 0.008,
        0.0,
        PI,
        10,
    );
    b.polyline("bail", tin, &pts, 0.0025);
    b.top("lid", disc([0.0, 0.0], r - 0.01, 12), h);
    b.finish(Placement::Surface, [0.85, 1.2])
}
