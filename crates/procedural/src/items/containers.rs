//! Containers: crates, boxes, bins, baskets, barrels, pallets, toolboxes, coolers, cans and
//! buckets. Open containers are a floor plus separate wall parts, so their inside stays hollow.

use rand_chacha::ChaCha8Rng;

use super::builder::Builder;
use crate::articulation;
use crate::random::{color, uniform, uniform3};
use scenethesis_primitives::{arc, disc, rect, square_post};
use scenethesis_scene_graph::{Asset, Placement};

const WOODS: &[[f32; 3]] = &[
    [0.55, 0.38, 0.22],
    [0.68, 0.52, 0.33],
    [0.45, 0.3, 0.18],
    [0.75, 0.62, 0.45],
];
const PLASTICS: &[[f32; 3]] = &[
    [0.15, 0.35, 0.7],
    [0.75, 0.15, 0.12],
    [0.2, 0.55, 0.25],
    [0.85, 0.75, 0.15],
    [0.2, 0.2, 0.22],
    [0.85, 0.85, 0.82],
    [0.6, 0.6, 0.62],
];
const METALS: &[[f32; 3]] = &[[0.6, 0.6, 0.62], [0.35, 0.36, 0.38], [0.75, 0.72, 0.68]];

/// Slatted wooden crate, open on top: 0.40–0.60 × 0.26–0.36 (h) × 0.30–0.42 m.
pub(crate) fn wooden_crate(rng: &mut ChaCha8Rng) -> Asset {
    let (w, h, d) = uniform3(rng, [0.4, 0.6], [0.26, 0.36], [0.3, 0.42]);
    let (board, floor) = (uniform(rng, 0.012, 0.018), 0.015);
    let mut b = Builder::new();
    let wood = b.material("crate_wood", color(rng, WOODS, 0.05), 0.8);
    let (x, z) = (w / 2.0, d / 2.0);
    b.cuboid("floor", wood, [-x, 0.0, -z], [x, floor, z]);
    let slats = 3;
    let gap = uniform(rng, 0.01, 0.025);
    let slat_h = (h - floor - gap * (slats - 1) as f32) / slats as f32;
    for s in 0..slats {
        let y0 = floor + s as f32 * (slat_h + gap);
        let y1 = y0 + slat_h;
        b.cuboid(
            &format!("slat_back_{s}"),
            wood,
            [-x, y0, -z],
            [x, y1, -z + board],
        );
        b.cuboid(
            &format!("slat_front_{s}"),
            wood,
            [-x, y0, z - board],
            [x, y1, z],
        );
        b.cuboid(
            &format!("slat_left_{s}"),
            wood,
            [-x, y0, -z],
            [-x + board, y1, z],
        );
        b.cuboid(
            &format!("slat_right_{s}"),
            wood,
            [x - board, y0, -z],
            [x, y1, z],
        );
    }
    let post = board * 2.5;
    for (i, (sx, sz)) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)]
        .iter()
        .enumerate()
    {
        let (cx, cz) = (sx * (x - board - post / 2.0), sz * (z - board - post / 2.0));
        b.add(square_post(
            &format!("post_{i}"),
            wood,
            [cx, cz],
            post,
            0.0,
            h,
        ));
    }
    let m = board + post + 0.01;
    b.interior(rect(-x + m, -z + m, x - m, z - m), floor);
    b.finish(Placement::Floor, [0.8, 1.25])
}

/// Closed cardboard box with a tape strip: 0.25–0.60 × 0.18–0.45 (h) × 0.22–0.45 m.
pub(crate) fn cardboard_box(rng: &mut ChaCha8Rng) -> Asset {
    let (w, h, d) = uniform3(rng, [0.25, 0.6], [0.18, 0.45], [0.22, 0.45]);
    let mut b = Builder::new();
    let card = b.material(
        "cardboard",
        color(
            rng,
            &[[0.66, 0.5, 0.32], [0.74, 0.6, 0.42], [0.9, 0.88, 0.84]],
            0.04,
        ),
        0.9,
    );
    let tape = b.material(
        "tape",
        color(rng, &[[0.8, 0.68, 0.45], [0.85, 0.85, 0.85]], 0.03),
        0.4,
    );
    let (x, z) = (w / 2.0, d / 2.0);
    b.cuboid("body", card, [-x, 0.0, -z], [x, h, z]);
    let t = uniform(rng, 0.04, 0.06) / 2.0;
    b.cuboid(
        "tape_top",
        tape,
        [-t, h - 0.001, -z - 0.001],
        [t, h + 0.001, z + 0.001],
    );
    b.top(
        "top",
        rect(-x + 0.01, -z + 0.01, x - 0.01, z - 0.01),
        h + 0.001,
    );
    b.finish(Placement::Floor, [0.7, 1.4])
}

/// Plastic storage bin with a lip, open on top: 0.38–0.62 × 0.20–0.36 (h) × 0.28–0.42 m.
pub(crate) fn storage_bin(rng: &mut ChaCha8Rng) -> Asset {
    let (w, h, d) = uniform3(rng, [0.38, 0.62], [0.2, 0.36], [0.28, 0.42]);
    let wall = uniform(rng, 0.004, 0.007);
    let mut b = Builder::new();
    let plastic = b.material("bin_plastic", color(rng, PLASTICS, 0.04), 0.5);
    let (x, z) = (w / 2.0 - 0.01, d / 2.0 - 0.01);
    let floor = b.open_box(
        "bin",
        plastic,
        [-x, 0.0, -z],
        [x, h - 0.012, z],
        wall,
        0.006,
    );
    let (lx, lz) = (x + 0.01, z + 0.01);
    b.cuboid(
        "lip_back",
        plastic,
        [-lx, h - 0.012, -lz],
        [lx, h, -z + wall],
    );
    b.cuboid(
        "lip_front",
        plastic,
        [-lx, h - 0.012, z - wall],
        [lx, h, lz],
    );
    b.cuboid(
        "lip_left",
        plastic,
        [-lx, h - 0.012, -lz],
        [-x + wall, h, lz],
    );
    b.cuboid(
        "lip_right",
        plastic,
        [x - wall, h - 0.012, -lz],
        [lx, h, lz],
    );
    let m = wall + 0.01;
    b.interior(rect(-x + m, -z + m, x - m, z - m), floor);
    b.finish(Placement::Floor, [0.8, 1.25])
}

/// Round woven basket with a flared wall, open on top: Ø 0.22–0.40 at the rim, 0.12–0.26 m high.
pub(crate) fn basket(rng: &mut ChaCha8Rng) -> Asset {
    let r_top = uniform(rng, 0.11, 0.2);
    let r_bottom = r_top * uniform(rng, 0.75, 0.92);
    let h = uniform(rng, 0.12, 0.26);
    let wall = 0.012;
    let mut b = Builder::new();
    let weave = b.material(
        "wicker",
        color(
            rng,
            &[[0.72, 0.55, 0.32], [0.6, 0.42, 0.24], [0.82, 0.72, 0.52]],
            0.04,
        ),
        0.95,
    );
    b.frustum(
        "base",
        weave,
        [0.0, 0.0],
        r_bottom,
        r_bottom,
        0.0,
        0.012,
        24,
    );
    b.ring(
        "wall",
        weave,
        [0.0, 0.0],
        (r_bottom - wall, r_bottom, 0.004),
        (r_top - wall, r_top, h - 0.015),
        20,
    );
    b.ring(
        "rim",
        weave,
        [0.0, 0.0],
        (r_top - wall - 0.004, r_top + 0.004, h - 0.018),
        (r_top - wall - 0.004, r_top + 0.004, h),
        20,
    );
    b.interior(disc([0.0, 0.0], r_bottom - wall - 0.01, 12), 0.012);
    b.finish(Placement::Surface, [0.75, 1.3])
}

/// Wooden barrel with a closed lid and metal hoops: Ø 0.50–0.64, 0.80–0.98 m high.
pub(crate) fn barrel(rng: &mut ChaCha8Rng) -> Asset {
    let r_end = uniform(rng, 0.25, 0.3);
    let r_belly = r_end * uniform(rng, 1.06, 1.12);
    let h = uniform(rng, 0.8, 0.98);
    let mut b = Builder::new();
    let wood = b.material("barrel_wood", color(rng, WOODS, 0.05), 0.8);
    let hoop = b.metal("hoop", color(rng, METALS, 0.03), 0.5);
    let (y1, y2) = (h * 0.3, h * 0.7);
    b.frustum("staves_low", wood, [0.0, 0.0], r_end, r_belly, 0.0, y1, 24);
    b.frustum("staves_mid", wood, [0.0, 0.0], r_belly, r_belly, y1, y2, 24);
    b.frustum("staves_high", wood, [0.0, 0.0], r_belly, r_end, y2, h, 24);
    for (i, y) in [0.06 * h, y1, y2, 0.94 * h].iter().enumerate() {
        let t = (y / h - 0.5).abs();
        let r = r_belly - (r_belly - r_end) * ((t - 0.2).max(0.0) / 0.3).min(1.0) + 0.004;
        b.frustum(
            &format!("hoop_{i}"),
            hoop,
            [0.0, 0.0],
            r,
            r,
            y - 0.015,
            y + 0.015,
            24,
        );
    }
    b.top("top", disc([0.0, 0.0], r_end - 0.03, 12), h);
    b.finish(Placement::Floor, [0.85, 1.15])
}

/// Wooden shipping pallet (EUR 1.20 × 0.80 or 1.20 × 1.00), 0.14–0.15 m high.
pub(crate) fn pallet(rng: &mut ChaCha8Rng) -> Asset {
    let (w, d) = (
        1.2,
        if uniform(rng, 0.0, 1.0) < 0.5 {
            0.8
        } else {
            1.0
        },
    );
    let h = uniform(rng, 0.14, 0.15);
    let mut b = Builder::new();
    let wood = b.material("pallet_wood", color(rng, WOODS, 0.06), 0.9);
    let (x, z) = (w / 2.0, d / 2.0);
    let deck = 0.022;
    for (i, bz) in [-z, 0.0f32, z].iter().enumerate() {
        let bz0 = (bz - 0.05).max(-z);
        let bz1 = (bz0 + 0.1).min(z);
        b.cuboid(&format!("bottom_{i}"), wood, [-x, 0.0, bz0], [x, deck, bz1]);
        for (j, bx) in [-x, 0.0f32, x].iter().enumerate() {
            let bx0 = (bx - 0.0725).max(-x);
            let bx1 = (bx0 + 0.145).min(x);
            b.cuboid(
                &format!("block_{i}_{j}"),
                wood,
                [bx0, deck, bz0],
                [bx1, h - 2.0 * deck, bz1],
            );
        }
    }
    for (j, bx) in [-x, 0.0f32, x].iter().enumerate() {
        let bx0 = (bx - 0.0725).max(-x);
        let bx1 = (bx0 + 0.145).min(x);
        b.cuboid(
            &format!("stringer_{j}"),
            wood,
            [bx0, h - 2.0 * deck, -z],
            [bx1, h - deck, z],
        );
    }
    let boards = 5;
    let bw = (w - 0.02 * (boards - 1) as f32) / boards as f32;
    for k in 0..boards {
        let x0 = -x + k as f32 * (bw + 0.02);
        b.cuboid(
            &format!("deck_{k}"),
            wood,
            [x0, h - deck, -z],
            [x0 + bw, h, z],
        );
    }
    b.top("top", rect(-x, -z, x, z), h);
    b.finish(Placement::Floor, [0.97, 1.03])
}

/// Plastic shopping basket with two handles, open on top: 0.40–0.48 × 0.20–0.25 (h) × 0.28–0.33 m.
pub(crate) fn shopping_basket(rng: &mut ChaCha8Rng) -> Asset {
    let (w, h, d) = uniform3(rng, [0.4, 0.48], [0.2, 0.25], [0.28, 0.33]);
    let mut b = Builder::new();
    let plastic = b.material(
        "basket_plastic",
        color(
            rng,
            &[
                [0.75, 0.1, 0.1],
                [0.1, 0.3, 0.7],
                [0.1, 0.5, 0.2],
                [0.2, 0.2, 0.2],
            ],
            0.04,
        ),
        0.5,
    );
    let grip = b.material(
        "handle",
        color(rng, &[[0.15, 0.15, 0.15], [0.8, 0.8, 0.8]], 0.03),
        0.4,
    );
    let (x, z) = (w / 2.0, d / 2.0);
    let wall = 0.005;
    let floor = b.open_box("basket", plastic, [-x, 0.0, -z], [x, h, z], wall, 0.006);
    for (i, sz) in [-1.0f32, 1.0].iter().enumerate() {
        // Handles folded down outside the long walls.
        let zz = sz * (z + 0.008);
        let pts = [
            [-x * 0.7, h - 0.01, zz],
            [-x * 0.55, h - 0.05, zz],
            [x * 0.55, h - 0.05, zz],
            [x * 0.7, h - 0.01, zz],
        ];
        b.polyline(&format!("handle_{i}"), grip, &pts, 0.006);
    }
    let m = wall + 0.01;
    b.interior(rect(-x + m, -z + m, x - m, z - m), floor);
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// Closed toolbox with a lid and a carry handle: 0.38–0.56 × 0.17–0.26 (h) × 0.19–0.26 m.
pub(crate) fn toolbox(rng: &mut ChaCha8Rng) -> Asset {
    let (w, h, d) = uniform3(rng, [0.38, 0.56], [0.15, 0.21], [0.19, 0.26]);
    let mut b = Builder::new();
    let shell = b.material(
        "toolbox_shell",
        color(
            rng,
            &[
                [0.75, 0.1, 0.08],
                [0.1, 0.25, 0.6],
                [0.9, 0.55, 0.05],
                [0.15, 0.15, 0.16],
            ],
            0.03,
        ),
        0.45,
    );
    let metal = b.metal("latch", color(rng, METALS, 0.02), 0.35);
    let (x, z) = (w / 2.0, d / 2.0);
    let lid_y = h * 0.72;
    b.cuboid("body", shell, [-x, 0.0, -z], [x, lid_y, z]);
    b.cuboid(
        "lid",
        shell,
        [-x - 0.004, lid_y, -z - 0.004],
        [x + 0.004, h, z + 0.004],
    );
    for (i, sx) in [-0.6f32, 0.6].iter().enumerate() {
        b.cuboid(
            &format!("latch_{i}"),
            metal,
            [sx * x - 0.015, lid_y - 0.03, z],
            [sx * x + 0.015, lid_y + 0.01, z + 0.008],
        );
        b.cuboid(
            &format!("handle_post_{i}"),
            shell,
            [sx * x * 0.6 - 0.012, h, -0.012],
            [sx * x * 0.6 + 0.012, h + 0.04, 0.012],
        );
    }
    b.cuboid(
        "handle_grip",
        shell,
        [-x * 0.36 - 0.012, h + 0.03, -0.014],
        [x * 0.36 + 0.012, h + 0.055, 0.014],
    );
    b.finish(Placement::Floor, [0.85, 1.2])
}

/// Picnic cooler with a closed lid hinged at its back and side grips: 0.48–0.72 × 0.34–0.46 (h) × 0.32–0.44 m.
pub(crate) fn cooler(rng: &mut ChaCha8Rng) -> Asset {
    let (w, h, d) = uniform3(rng, [0.48, 0.72], [0.34, 0.46], [0.32, 0.44]);
    let mut b = Builder::new();
    let body = b.material(
        "cooler_body",
        color(
            rng,
            &[
                [0.1, 0.3, 0.7],
                [0.75, 0.12, 0.1],
                [0.2, 0.5, 0.3],
                [0.85, 0.85, 0.85],
            ],
            0.04,
        ),
        0.5,
    );
    let lid = b.material(
        "cooler_lid",
        color(rng, &[[0.92, 0.92, 0.9], [0.2, 0.2, 0.22]], 0.03),
        0.5,
    );
    let (x, z) = (w / 2.0, d / 2.0);
    let lid_y = h - uniform(rng, 0.05, 0.08);
    b.cuboid("body", body, [-x, 0.0, -z], [x, lid_y, z]);
    // The lid, hinged along its back edge, with a grip lip at the front.
    b.joint(articulation::back_hinge(
        "lid",
        h,
        -z - 0.005,
        articulation::DOOR_OPEN,
    ));
    b.link(Some("lid"));
    b.cuboid(
        "lid",
        lid,
        [-x - 0.005, lid_y, -z - 0.005],
        [x + 0.005, h, z + 0.005],
    );
    b.cuboid(
        "lid_lip",
        lid,
        [-0.08, lid_y + 0.005, z + 0.004],
        [0.08, lid_y + 0.02, z + 0.02],
    );
    b.link(None);
    for (i, sx) in [-1.0f32, 1.0].iter().enumerate() {
        b.cuboid(
            &format!("grip_{i}"),
            lid,
            [sx * x - 0.012, lid_y - 0.06, -0.06],
            [sx * x + 0.012, lid_y - 0.03, 0.06],
        );
    }
    b.top("top", rect(-x + 0.01, -z + 0.01, x - 0.01, z - 0.01), h);
    b.finish(Placement::Floor, [0.85, 1.15])
}

/// Round trash can, open on top: Ø 0.22–0.40, 0.30–0.75 m high, metal or plastic.
pub(crate) fn trash_can(rng: &mut ChaCha8Rng) -> Asset {
    let r_top = uniform(rng, 0.11, 0.2);
    let r_bottom = r_top * uniform(rng, 0.8, 1.0);
    let h = uniform(rng, 0.3, 0.75).max(r_top * 2.2);
    let wall = 0.004;
    let mut b = Builder::new();
    let shell = if uniform(rng, 0.0, 1.0) < 0.5 {
        b.metal("can_metal", color(rng, METALS, 0.03), 0.35)
    } else {
        b.material("can_plastic", color(rng, PLASTICS, 0.04), 0.55)
    };
    b.frustum("base", shell, [0.0, 0.0], r_bottom, r_bottom, 0.0, 0.01, 24);
    b.ring(
        "wall",
        shell,
        [0.0, 0.0],
        (r_bottom - wall, r_bottom, 0.005),
        (r_top - wall, r_top, h),
        24,
    );
    b.interior(disc([0.0, 0.0], r_bottom - wall - 0.01, 12), 0.01);
    b.finish(Placement::Floor, [0.8, 1.2])
}

/// Builds a bucket with a bail handle folded down around the outside of the rim.
pub(crate) fn bucket_of(
    b: &mut Builder,
    shell: usize,
    bail: usize,
    r_bottom: f32,
    r_top: f32,
    h: f32,
) {
    let wall = 0.003;
    b.frustum(
        "base",
        shell,
        [0.0, 0.0],
        r_bottom,
        r_bottom,
        0.0,
        0.008,
        24,
    );
    b.ring(
        "wall",
        shell,
        [0.0, 0.0],
        (r_bottom - wall, r_bottom, 0.004),
        (r_top - wall, r_top, h),
        24,
    );
    b.ring(
        "rim",
        shell,
        [0.0, 0.0],
        (r_top - wall, r_top + 0.004, h - 0.012),
        (r_top - wall, r_top + 0.004, h),
        24,
    );
    let y = h - 0.03;
    let r = r_top + 0.01;
    let pts = arc(
        [0.0, y, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, -1.0],
        r,
        0.0,
        std::f32::consts::PI,
        10,
    );
    b.polyline("bail", bail, &pts, 0.003);
    b.interior(disc([0.0, 0.0], r_bottom - wall - 0.01, 12), 0.008);
}

/// Bucket with a folded bail handle, open on top: Ø 0.24–0.32 at the rim, 0.24–0.32 m high.
pub(crate) fn bucket(rng: &mut ChaCha8Rng) -> Asset {
    let r_top = uniform(rng, 0.12, 0.16);
    let r_bottom = r_top * uniform(rng, 0.78, 0.88);
    let h = uniform(rng, 0.24, 0.32);
    let mut b = Builder::new();
    let shell = if uniform(rng, 0.0, 1.0) < 0.4 {
        b.metal("bucket_metal", color(rng, METALS, 0.03), 0.4)
    } else {
        b.material("bucket_plastic", color(rng, PLASTICS, 0.04), 0.5)
    };
    let bail = b.metal("bail", [0.7, 0.7, 0.72], 0.3);
    bucket_of(&mut b, shell, bail, r_bottom, r_top, h);
    b.finish(Placement::Floor, [0.8, 1.2])
}
