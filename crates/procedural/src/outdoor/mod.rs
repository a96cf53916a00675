//! Built-in outdoor generators: beach, camping and nature. Dimensions per category are
//! documented on each generator, in metres.

use std::f32::consts::{FRAC_PI_2, PI, TAU};

use rand_chacha::ChaCha8Rng;

use crate::category::Generator;
use crate::items::builder::Builder;
use crate::random::{color, uniform, uniform3};
use scenethesis_primitives::{arc, convex_hull, rect, rotated_ellipsoid, rotation, rounded_box};
use scenethesis_scene_graph::{Asset, Placement, SurfaceKind};

const BRIGHT: &[[f32; 3]] = &[
    [0.9, 0.15, 0.1],
    [0.1, 0.4, 0.85],
    [0.98, 0.85, 0.15],
    [0.1, 0.65, 0.35],
    [0.98, 0.5, 0.1],
    [0.95, 0.95, 0.95],
    [0.55, 0.2, 0.7],
];
const BARK: &[[f32; 3]] = &[[0.4, 0.3, 0.2], [0.35, 0.25, 0.16], [0.5, 0.4, 0.3]];
const LEAVES: &[[f32; 3]] = &[
    [0.2, 0.45, 0.15],
    [0.25, 0.55, 0.2],
    [0.15, 0.35, 0.12],
    [0.4, 0.55, 0.2],
];
const STONE: &[[f32; 3]] = &[
    [0.5, 0.48, 0.45],
    [0.4, 0.38, 0.36],
    [0.6, 0.56, 0.5],
    [0.45, 0.42, 0.38],
];

/// The outdoor generators of the registry, by category name (their rows are in
/// `data/categories.toml`).
pub(crate) const GENERATORS: &[(&str, Generator)] = &[
    ("beach_umbrella", beach_umbrella),
    ("beach_lounger", beach_lounger),
    ("beach_towel", beach_towel),
    ("surfboard", surfboard),
    ("palm_tree", palm_tree),
    ("sand_bucket", sand_bucket),
    ("beach_ball", beach_ball),
    ("sandcastle", sandcastle),
    ("tent", tent),
    ("campfire", campfire),
    ("lantern", lantern),
    ("backpack", backpack),
    ("rock", rock),
    ("tree", tree),
];

/// Beach umbrella: weighted base, pole 1.9–2.4 m, striped canopy Ø 1.6–2.2 m.
fn beach_umbrella(rng: &mut ChaCha8Rng) -> Asset {
    let h = uniform(rng, 1.9, 2.4);
    let r = uniform(rng, 0.8, 1.1);
    let drop = r * uniform(rng, 0.22, 0.3);
    let mut b = Builder::new();
    let c1 = b.material("canopy_a", color(rng, BRIGHT, 0.04), 0.8);
    let c2 = b.material("canopy_b", [0.97, 0.96, 0.92], 0.8);
    let pole = b.material(
        "pole",
        color(rng, &[[0.9, 0.9, 0.9], [0.6, 0.45, 0.3]], 0.03),
        0.5,
    );
    let base = b.material("base", [0.25, 0.25, 0.27], 0.7);
    // A weighted base (≈ 25 kg at water density) and a thin canopy keep the centre of mass low,
    // as a free-standing umbrella needs.
    // A flat round foot under the weighted cone (see `palm_tree`): the foot rests still in
    // simulation where a 20-sided frustum hull slid 2 cm after the optimizer's settle drop.
    b.frustum("base_foot", base, [0.0, 0.0], 0.3, 0.3, 0.0, 0.02, 24);
    b.frustum("base", base, [0.0, 0.0], 0.3, 0.24, 0.02, 0.11, 20);
    b.frustum("pole", pole, [0.0, 0.0], 0.019, 0.019, 0.02, h + 0.05, 12);
    let panels = 8;
    let thick = 0.003;
    for k in 0..panels {
        let (a0, a1) = (
            TAU * k as f32 / panels as f32,
            TAU * (k + 1) as f32 / panels as f32,
        );
        let rim = |a: f32, y: f32| [r * a.cos(), y, r * a.sin()];
        let y_rim = h - drop;
        let pts = [
            [0.0, h, 0.0],
            [0.0, h - thick, 0.0],
            rim(a0, y_rim),
            rim(a1, y_rim),
            rim(a0, y_rim - thick),
            rim(a1, y_rim - thick),
        ];
        let m = if k % 2 == 0 { c1 } else { c2 };
        b.add(convex_hull(&format!("canopy_{k}"), m, &pts).expect("canopy panel has volume"));
    }
    b.frustum("finial", pole, [0.0, 0.0], 0.025, 0.0, h, h + 0.08, 10);
    b.finish(Placement::Floor, [0.85, 1.15])
}

/// Beach lounger with a flat seat and a raised backrest: 1.75–1.95 × 0.30–0.40 (seat) × 0.55–0.70.
fn beach_lounger(rng: &mut ChaCha8Rng) -> Asset {
    let (l, seat_h, w) = uniform3(rng, [1.75, 1.95], [0.3, 0.4], [0.55, 0.7]);
    let back_angle = uniform(rng, 0.5, 0.9);
    let mut b = Builder::new();
    let frame = if uniform(rng, 0.0, 1.0) < 0.5 {
        b.material("teak", [0.55, 0.38, 0.22], 0.7)
    } else {
        b.metal("aluminium", [0.8, 0.8, 0.82], 0.4)
    };
    let fabric = b.material("sling", color(rng, BRIGHT, 0.05), 0.9);
    let (x, z) = (w / 2.0, l / 2.0);
    let back_len = l * 0.38;
    let seat_z0 = -z + back_len * back_angle.cos();
    let t = 0.04;
    b.cuboid("seat", fabric, [-x, seat_h - t, seat_z0], [x, seat_h, z]);
    // Hinged at the back of the seat, rising toward −Z at `back_angle` above horizontal.
    let rot = rotation([1.0, 0.0, 0.0], back_angle);
    let center = [
        0.0,
        seat_h - t / 2.0 + back_angle.sin() * back_len / 2.0,
        seat_z0 - back_angle.cos() * back_len / 2.0,
    ];
    b.add(scenethesis_primitives::rotated_box(
        "backrest",
        fabric,
        center,
        [x, t / 2.0, back_len / 2.0],
        &rot,
    ));
    for (i, (sx, zz)) in [
        (-1.0f32, seat_z0),
        (1.0, seat_z0),
        (-1.0, z - 0.05),
        (1.0, z - 0.05),
    ]
    .iter()
    .enumerate()
    {
        let xx = sx * (x - 0.03);
        b.cuboid(
            &format!("leg_{i}"),
            frame,
            [xx - 0.02, 0.0, zz - 0.02],
            [xx + 0.02, seat_h - t, zz + 0.02],
        );
    }
    b.cuboid(
        "rail_left",
        frame,
        [-x - 0.01, seat_h - t - 0.04, seat_z0 - 0.02],
        [-x + 0.02, seat_h - t, z],
    );
    b.cuboid(
        "rail_right",
        frame,
        [x - 0.02, seat_h - t - 0.04, seat_z0 - 0.02],
        [x + 0.01, seat_h - t, z],
    );
    b.top(
        "seat",
        rect(-x + 0.03, seat_z0 + 0.05, x - 0.03, z - 0.03),
        seat_h,
    );
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// Striped beach towel lying flat: 1.4–1.8 × 0.7–1.0 m, 4–6 mm thick.
fn beach_towel(rng: &mut ChaCha8Rng) -> Asset {
    let (l, w) = (uniform(rng, 1.4, 1.8), uniform(rng, 0.7, 1.0));
    let t = uniform(rng, 0.004, 0.006);
    let mut b = Builder::new();
    let a = b.material("towel_a", color(rng, BRIGHT, 0.05), 1.0);
    let c = b.material("towel_b", color(rng, BRIGHT, 0.05), 1.0);
    let stripes = 5 + (uniform(rng, 0.0, 4.99) as usize);
    let (x, z) = (w / 2.0, l / 2.0);
    for k in 0..stripes {
        let z0 = -z + l * k as f32 / stripes as f32;
        let z1 = -z + l * (k + 1) as f32 / stripes as f32;
        b.cuboid(
            &format!("stripe_{k}"),
            if k % 2 == 0 { a } else { c },
            [-x, 0.0, z0],
            [x, t, z1],
        );
    }
    b.top("top", rect(-x, -z, x, z), t);
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// Surfboard lying flat, nose toward +Z: 1.8–2.8 long, 0.48–0.58 wide, 0.06–0.08 thick.
fn surfboard(rng: &mut ChaCha8Rng) -> Asset {
    let (l, w, t) = uniform3(rng, [1.8, 2.8], [0.48, 0.58], [0.06, 0.08]);
    let mut b = Builder::new();
    let deck = b.material(
        "deck",
        color(
            rng,
            &[
                [0.95, 0.95, 0.92],
                [0.3, 0.7, 0.85],
                [0.95, 0.75, 0.2],
                [0.9, 0.4, 0.3],
            ],
            0.04,
        ),
        0.3,
    );
    let stripe = b.material("stringer", color(rng, BRIGHT, 0.04), 0.3);
    let outline = |s: f32| -> Vec<[f32; 2]> {
        (0..=24)
            .map(|i| {
                let u = i as f32 / 24.0; // tail (0) to nose (1)
                let half = w / 2.0
                    * s
                    * (PI * (0.15 + 0.85 * u))
                        .sin()
                        .max(0.0)
                        .powf(0.7)
                        .max(if u < 0.1 { 0.45 } else { 0.0 });
                (u, half)
            })
            .flat_map(|(u, half)| [[half, -l / 2.0 + l * u], [-half, -l / 2.0 + l * u]])
            .collect()
    };
    let mut pts = Vec::new();
    for (y, s) in [(0.0, 0.8), (t * 0.5, 1.0), (t, 0.85)] {
        pts.extend(outline(s).into_iter().map(|p| [p[0], y, p[1]]));
    }
    b.add(convex_hull("board", deck, &pts).expect("board has volume"));
    b.cuboid(
        "stringer",
        stripe,
        [-0.01, t * 0.5, -l * 0.42],
        [0.01, t * 0.97, l * 0.42],
    );
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// Palm tree: leaning, segmented trunk 4–7 m high with 7–10 drooping fronds and coconuts.
fn palm_tree(rng: &mut ChaCha8Rng) -> Asset {
    let h = uniform(rng, 4.0, 7.0);
    let lean = uniform(rng, 0.0, 0.06);
    let lean_dir = uniform(rng, 0.0, TAU);
    let mut b = Builder::new();
    let bark = b.material("palm_bark", color(rng, BARK, 0.04), 0.95);
    let leaf = b.material("frond", color(rng, LEAVES, 0.05), 0.8);
    let nut = b.material("coconut", [0.35, 0.25, 0.12], 0.7);
    let segs = 8;
    let mut trunk = Vec::new();
    for i in 0..=segs {
        let u = i as f32 / segs as f32;
        let off = h * lean * u * u;
        // The trunk starts inside the footing, so only the footing's flat foot meets the
        // ground.
        trunk.push([
            off * lean_dir.cos(),
            (h * u).max(0.05),
            off * lean_dir.sin(),
        ]);
    }
    for (k, w) in trunk.windows(2).enumerate() {
        let r0 = 0.2 - 0.08 * k as f32 / segs as f32;
        let r1 = r0 - 0.012;
        b.tube(&format!("trunk_{k}"), bark, w[0], w[1], r0, r1, 12);
    }
    // The root flare and its soil: a wide, heavy footing so the tree stands free in simulation.
    // Its foot is a flat cylinder (a round primitive in the stability simulation); a
    // many-sided frustum hull standing on the ground slid by up to 2.4 cm after the
    // optimizer's 1.25 mm settle drop.
    b.frustum("root_foot", bark, [0.0, 0.0], 0.55, 0.55, 0.0, 0.05, 24);
    b.frustum("root_flare", bark, [0.0, 0.0], 0.55, 0.22, 0.05, 0.3, 16);
    let top = trunk[segs];
    let fronds = 7 + (uniform(rng, 0.0, 3.99) as usize);
    let frond_len = uniform(rng, 1.8, 2.8);
    for f in 0..fronds {
        let yaw = TAU * f as f32 / fronds as f32 + uniform(rng, -0.2, 0.2);
        let rise = uniform(rng, 0.2, 0.6);
        let mut p = [top[0], top[1], top[2]];
        for s in 0..3 {
            let pitch = rise - s as f32 * uniform(rng, 0.35, 0.5);
            let seg = frond_len / 3.0;
            let dir = nalgebra::Vector3::new(
                yaw.cos() * pitch.cos(),
                pitch.sin(),
                yaw.sin() * pitch.cos(),
            );
            let c = [
                p[0] + dir.x * seg / 2.0,
                p[1] + dir.y * seg / 2.0,
                p[2] + dir.z * seg / 2.0,
            ];
            let rot = rotation([0.0, 1.0, 0.0], -yaw) * rotation([0.0, 0.0, 1.0], pitch);
            b.add(rotated_ellipsoid(
                &format!("frond_{f}_{s}"),
                leaf,
                c,
                [seg * 0.55, 0.02, 0.22 - 0.05 * s as f32],
                &rot,
            ));
            p = [p[0] + dir.x * seg, p[1] + dir.y * seg, p[2] + dir.z * seg];
        }
    }
    let nuts = (uniform(rng, 0.0, 4.99)) as usize;
    for k in 0..nuts {
        let a = TAU * k as f32 / nuts.max(1) as f32;
        b.add(scenethesis_primitives::sphere(
            &format!("coconut_{k}"),
            nut,
            [
                top[0] + 0.16 * a.cos(),
                top[1] - 0.15,
                top[2] + 0.16 * a.sin(),
            ],
            0.09,
            8,
            12,
        ));
    }
    b.finish(Placement::Floor, [0.8, 1.2])
}

/// Child's sand bucket with a folded handle, open on top: Ø 0.14–0.20, 0.12–0.17 m high.
fn sand_bucket(rng: &mut ChaCha8Rng) -> Asset {
    let r_top = uniform(rng, 0.07, 0.1);
    let r_bottom = r_top * uniform(rng, 0.75, 0.85);
    let h = uniform(rng, 0.12, 0.17);
    let mut b = Builder::new();
    let shell = b.material("bucket_plastic", color(rng, BRIGHT, 0.04), 0.5);
    let handle = b.material("handle_plastic", color(rng, BRIGHT, 0.04), 0.5);
    crate::items::containers::bucket_of(&mut b, shell, handle, r_bottom, r_top, h);
    b.finish(Placement::Floor, [0.85, 1.2])
}

/// Inflatable beach ball with six coloured lunes: Ø 0.30–0.50.
fn beach_ball(rng: &mut ChaCha8Rng) -> Asset {
    let r = uniform(rng, 0.15, 0.25);
    let mut b = Builder::new();
    let mut palette: Vec<usize> = BRIGHT
        .iter()
        .enumerate()
        .map(|(i, c)| b.material(&format!("vinyl_{i}"), *c, 0.35))
        .collect();
    let start = (uniform(rng, 0.0, palette.len() as f32 - 0.01)) as usize;
    palette.rotate_left(start);
    let lunes = 6;
    for k in 0..lunes {
        let (a0, a1) = (
            TAU * k as f32 / lunes as f32,
            TAU * (k + 1) as f32 / lunes as f32,
        );
        let mut pts = vec![[0.0, 0.0, 0.0], [0.0, 2.0 * r, 0.0], [0.0, r, 0.0]];
        for i in 1..12 {
            let phi = PI * i as f32 / 12.0;
            for j in 0..=3 {
                let a = a0 + (a1 - a0) * j as f32 / 3.0;
                pts.push([
                    r * phi.sin() * a.cos(),
                    r - r * phi.cos(),
                    r * phi.sin() * a.sin(),
                ]);
            }
        }
        b.add(
            convex_hull(&format!("lune_{k}"), palette[k % palette.len()], &pts)
                .expect("lune has volume"),
        );
    }
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// Sandcastle: mound, keep and four towers with conical roofs: 0.30–0.60 across, 0.25–0.50 high.
fn sandcastle(rng: &mut ChaCha8Rng) -> Asset {
    let s = uniform(rng, 0.3, 0.6);
    let mut b = Builder::new();
    let sand = b.material(
        "wet_sand",
        color(rng, &[[0.82, 0.7, 0.5], [0.76, 0.64, 0.45]], 0.03),
        1.0,
    );
    let flag = b.material("flag", color(rng, BRIGHT, 0.03), 0.8);
    let half = s / 2.0;
    b.frustum(
        "mound",
        sand,
        [0.0, 0.0],
        half,
        half * 0.8,
        0.0,
        s * 0.12,
        24,
    );
    let kh = s * uniform(rng, 0.4, 0.55);
    b.cuboid(
        "keep",
        sand,
        [-half * 0.45, s * 0.1, -half * 0.45],
        [half * 0.45, kh, half * 0.45],
    );
    for (i, (sx, sz)) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)]
        .iter()
        .enumerate()
    {
        let (cx, cz) = (sx * half * 0.55, sz * half * 0.55);
        let tr = half * 0.16;
        let th = kh * uniform(rng, 0.75, 0.95);
        b.frustum(
            &format!("tower_{i}"),
            sand,
            [cx, cz],
            tr * 1.1,
            tr,
            s * 0.1,
            th,
            16,
        );
        b.frustum(
            &format!("roof_{i}"),
            sand,
            [cx, cz],
            tr * 1.2,
            0.0,
            th,
            th + tr * 1.8,
            16,
        );
    }
    b.tube(
        "flagpole",
        sand,
        [0.0, kh - 0.01, 0.0],
        [0.0, kh + s * 0.25, 0.0],
        0.003,
        0.003,
        6,
    );
    b.cuboid(
        "flag",
        flag,
        [0.0, kh + s * 0.18, -0.002],
        [s * 0.12, kh + s * 0.24, 0.002],
    );
    b.finish(Placement::Floor, [0.7, 1.5])
}

/// A-frame tent with a floor, two roof panels, a back wall and a front door gap:
/// 1.9–2.3 long (z) × 1.2–1.6 wide × 1.0–1.3 high. The floor inside is a shelf with clearance.
fn tent(rng: &mut ChaCha8Rng) -> Asset {
    let (l, w, h) = uniform3(rng, [1.9, 2.3], [1.2, 1.6], [1.0, 1.3]);
    let mut b = Builder::new();
    let fly = b.material(
        "tent_fabric",
        color(
            rng,
            &[
                [0.15, 0.4, 0.25],
                [0.85, 0.45, 0.1],
                [0.2, 0.35, 0.65],
                [0.8, 0.75, 0.55],
            ],
            0.04,
        ),
        0.8,
    );
    let floor = b.material("groundsheet", [0.25, 0.25, 0.27], 0.9);
    let (x, z) = (w / 2.0, l / 2.0);
    let t = 0.01;
    b.cuboid("floor", floor, [-x, 0.0, -z], [x, t, z]);
    for (name, sx) in [("roof_left", -1.0f32), ("roof_right", 1.0)] {
        let pts = [
            [sx * x, 0.0, -z],
            [sx * x, 0.0, z],
            [0.0, h, -z],
            [0.0, h, z],
            [sx * (x + t * 1.5), 0.0, -z],
            [sx * (x + t * 1.5), 0.0, z],
            [sx * t * 1.5, h + t, -z],
            [sx * t * 1.5, h + t, z],
        ];
        b.add(convex_hull(name, fly, &pts).expect("roof panel has volume"));
    }
    let gable = |z0: f32, z1: f32, xa: f32, xb: f32| -> Vec<[f32; 3]> {
        // The part of the triangular end wall between x = xa and x = xb.
        let y = |xx: f32| h * (1.0 - xx.abs() / x);
        let mut pts = Vec::new();
        for zz in [z0, z1] {
            pts.push([xa, 0.0, zz]);
            pts.push([xb, 0.0, zz]);
            pts.push([xa, y(xa), zz]);
            pts.push([xb, y(xb), zz]);
            if xa < 0.0 && xb > 0.0 {
                pts.push([0.0, h, zz]);
            }
        }
        pts
    };
    b.add(convex_hull("back_wall", fly, &gable(-z, -z + t, -x, x)).expect("back wall has volume"));
    let door = x * uniform(rng, 0.35, 0.5);
    b.add(
        convex_hull("front_left", fly, &gable(z - t, z, -x, -door))
            .expect("front panel has volume"),
    );
    b.add(
        convex_hull("front_right", fly, &gable(z - t, z, door, x)).expect("front panel has volume"),
    );
    b.cuboid(
        "front_top",
        fly,
        [-door, h * (1.0 - door / x), z - t],
        [door, h * (1.0 - door / x) + 0.02, z],
    );
    // Usable floor: where at least 0.6 of the ridge height is free.
    let inner = x * 0.4;
    b.surface(
        "floor",
        SurfaceKind::Shelf,
        rect(-inner, -z + 0.05, inner, z - 0.05),
        t,
        Some(h * 0.6 - t),
    );
    b.finish(Placement::Floor, [0.9, 1.15])
}

/// Campfire: a ring of 7–10 stones around a teepee of 4–6 logs and flames: Ø 0.6–1.0.
fn campfire(rng: &mut ChaCha8Rng) -> Asset {
    let r = uniform(rng, 0.3, 0.5);
    let mut b = Builder::new();
    let stone = b.material("stone", color(rng, STONE, 0.04), 0.9);
    let wood = b.material("log", color(rng, BARK, 0.04), 0.9);
    let flame = b.material("flame", [1.0, 0.55, 0.1], 0.3);
    let ember = b.material("embers", [0.15, 0.08, 0.05], 1.0);
    let stones = 7 + (uniform(rng, 0.0, 3.99) as usize);
    for k in 0..stones {
        let a = TAU * k as f32 / stones as f32;
        let s = uniform(rng, 0.07, 0.11);
        let c = [r * a.cos(), 0.0, r * a.sin()];
        b.add(rock_hull(
            rng,
            &format!("stone_{k}"),
            stone,
            c,
            [s, s * 0.75, s],
        ));
    }
    b.frustum("embers", ember, [0.0, 0.0], r * 0.6, r * 0.5, 0.0, 0.02, 16);
    let logs = 4 + (uniform(rng, 0.0, 2.99) as usize);
    let top = r * uniform(rng, 0.7, 1.0);
    for k in 0..logs {
        let a = TAU * k as f32 / logs as f32 + uniform(rng, -0.2, 0.2);
        let foot = [r * 0.55 * a.cos(), 0.04, r * 0.55 * a.sin()];
        b.tube(
            &format!("log_{k}"),
            wood,
            foot,
            [0.02 * a.cos(), top, 0.02 * a.sin()],
            0.04,
            0.03,
            8,
        );
    }
    b.frustum(
        "flame_core",
        flame,
        [0.0, 0.0],
        r * 0.25,
        0.0,
        0.02,
        top * 0.9,
        10,
    );
    b.finish(Placement::Floor, [0.85, 1.2])
}

/// A faceted stone: the convex hull of points on a jittered ellipsoid resting on y = 0.
fn rock_hull(
    rng: &mut ChaCha8Rng,
    name: &str,
    material: usize,
    base_center: [f32; 3],
    radii: [f32; 3],
) -> scenethesis_scene_graph::MeshPart {
    let mut pts = Vec::new();
    for i in 0..28 {
        let phi = (1.0 - 2.0 * (i as f32 + 0.5) / 28.0).acos();
        let theta = i as f32 * 2.39996 + uniform(rng, -0.3, 0.3);
        let j = uniform(rng, 0.75, 1.0);
        let y = (radii[1] * phi.cos() * j).max(-radii[1] * 0.2);
        pts.push([
            base_center[0] + radii[0] * phi.sin() * theta.cos() * j,
            base_center[1] + radii[1] * 0.2 + y,
            base_center[2] + radii[2] * phi.sin() * theta.sin() * j,
        ]);
    }
    convex_hull(name, material, &pts).expect("rock points span a volume")
}

/// Camping lantern: base, glass chimney, vented cap and a bail handle: 0.20–0.35 m high.
fn lantern(rng: &mut ChaCha8Rng) -> Asset {
    let h = uniform(rng, 0.2, 0.35);
    let r = h * uniform(rng, 0.22, 0.3);
    let mut b = Builder::new();
    let body = b.metal(
        "lantern_metal",
        color(
            rng,
            &[
                [0.15, 0.3, 0.2],
                [0.6, 0.1, 0.08],
                [0.15, 0.15, 0.16],
                [0.7, 0.55, 0.3],
            ],
            0.04,
        ),
        0.45,
    );
    let glass = b.glass("chimney", [0.95, 0.9, 0.75], 0.4);
    let light = b.material("mantle", [1.0, 0.9, 0.6], 0.2);
    b.frustum("base", body, [0.0, 0.0], r, r * 0.9, 0.0, h * 0.25, 20);
    b.frustum(
        "chimney",
        glass,
        [0.0, 0.0],
        r * 0.75,
        r * 0.75,
        h * 0.25,
        h * 0.7,
        20,
    );
    b.frustum(
        "mantle",
        light,
        [0.0, 0.0],
        r * 0.2,
        r * 0.2,
        h * 0.3,
        h * 0.5,
        10,
    );
    b.frustum(
        "cap",
        body,
        [0.0, 0.0],
        r * 0.95,
        r * 0.3,
        h * 0.7,
        h * 0.85,
        20,
    );
    let pts = arc(
        [0.0, h * 0.85, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        r * 0.5,
        0.0,
        PI,
        8,
    );
    b.polyline("bail", body, &pts, 0.003);
    for (i, a) in [0.0f32, FRAC_PI_2 * 2.0].iter().enumerate() {
        b.tube(
            &format!("guard_{i}"),
            body,
            [r * 0.8 * a.cos(), h * 0.25, 0.0],
            [r * 0.8 * a.cos(), h * 0.7, 0.0],
            0.004,
            0.004,
            6,
        );
    }
    b.finish(Placement::Floor, [0.85, 1.2])
}

/// Backpack standing upright, front pocket toward +Z: 0.40–0.55 high × 0.28–0.36 × 0.15–0.24.
fn backpack(rng: &mut ChaCha8Rng) -> Asset {
    let (h, w, d) = uniform3(rng, [0.4, 0.55], [0.28, 0.36], [0.15, 0.24]);
    let mut b = Builder::new();
    let nylon = b.material(
        "nylon",
        color(
            rng,
            &[
                [0.15, 0.2, 0.4],
                [0.6, 0.1, 0.1],
                [0.2, 0.35, 0.2],
                [0.1, 0.1, 0.1],
                [0.85, 0.5, 0.1],
            ],
            0.04,
        ),
        0.8,
    );
    let trim = b.material("straps", [0.08, 0.08, 0.08], 0.9);
    b.add(rounded_box(
        "body",
        nylon,
        [0.0, h / 2.0, 0.0],
        [w / 2.0, h / 2.0, d / 2.0],
        0.35,
    ));
    // A flat, stiffened bottom panel: the pack stands upright instead of rocking on its
    // rounded base.
    b.cuboid(
        "base_panel",
        trim,
        [-w * 0.42, 0.0, -d * 0.42],
        [w * 0.42, 0.03, d * 0.42],
    );
    b.add(rounded_box(
        "front_pocket",
        nylon,
        [0.0, h * 0.3, d / 2.0],
        [w * 0.38, h * 0.2, d * 0.18],
        0.4,
    ));
    for (i, sx) in [-1.0f32, 1.0].iter().enumerate() {
        let xx = sx * w * 0.22;
        let pts = [
            [xx, h * 0.88, -d * 0.4],
            [xx, h * 0.8, -d / 2.0 - 0.02],
            [xx * 1.2, h * 0.35, -d / 2.0 - 0.025],
            [xx * 1.3, h * 0.12, -d * 0.42],
        ];
        b.polyline(&format!("strap_{i}"), trim, &pts, 0.012);
    }
    let handle = arc(
        [0.0, h * 0.98, -d * 0.1],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        0.04,
        0.0,
        PI,
        6,
    );
    b.polyline("top_handle", trim, &handle, 0.006);
    b.finish(Placement::Floor, [0.85, 1.15])
}

/// Rock or boulder: a faceted convex stone 0.2–1.2 m across.
fn rock(rng: &mut ChaCha8Rng) -> Asset {
    let s = uniform(rng, 0.2, 1.2);
    let radii = [
        s / 2.0,
        s / 2.0 * uniform(rng, 0.45, 0.8),
        s / 2.0 * uniform(rng, 0.6, 0.95),
    ];
    let mut b = Builder::new();
    let stone = b.material("rock", color(rng, STONE, 0.05), 0.95);
    let part = rock_hull(rng, "rock", stone, [0.0, 0.0, 0.0], radii);
    b.add(part);
    b.finish(Placement::Floor, [0.6, 1.6])
}

/// A tree, deciduous (clustered ellipsoid crown) or conifer (stacked cones): 3–8 m high.
fn tree(rng: &mut ChaCha8Rng) -> Asset {
    let h = uniform(rng, 3.0, 8.0);
    let mut b = Builder::new();
    let bark = b.material("bark", color(rng, BARK, 0.04), 0.95);
    let leaf = b.material("foliage", color(rng, LEAVES, 0.05), 0.85);
    let rt = h * uniform(rng, 0.025, 0.04);
    if uniform(rng, 0.0, 1.0) < 0.6 {
        let trunk_h = h * uniform(rng, 0.4, 0.55);
        b.frustum(
            "trunk",
            bark,
            [0.0, 0.0],
            rt * 1.2,
            rt * 0.8,
            0.0,
            trunk_h + h * 0.1,
            12,
        );
        let cr = (h - trunk_h) * 0.5;
        b.ellipsoid(
            "crown",
            leaf,
            [0.0, trunk_h + cr, 0.0],
            [cr * 0.9, cr, cr * 0.9],
        );
        let lobes = 4 + (uniform(rng, 0.0, 3.99) as usize);
        for k in 0..lobes {
            let a = TAU * k as f32 / lobes as f32 + uniform(rng, -0.3, 0.3);
            let lr = cr * uniform(rng, 0.5, 0.7);
            let c = [
                cr * 0.6 * a.cos(),
                trunk_h + cr * uniform(rng, 0.7, 1.2),
                cr * 0.6 * a.sin(),
            ];
            b.ellipsoid(&format!("crown_lobe_{k}"), leaf, c, [lr, lr * 0.85, lr]);
        }
        let branches = 2 + (uniform(rng, 0.0, 2.99) as usize);
        for k in 0..branches {
            let a = TAU * k as f32 / branches as f32 + uniform(rng, 0.0, 1.0);
            let y = trunk_h * uniform(rng, 0.8, 1.0);
            b.tube(
                &format!("branch_{k}"),
                bark,
                [0.0, y, 0.0],
                [cr * 0.6 * a.cos(), y + cr * 0.6, cr * 0.6 * a.sin()],
                rt * 0.5,
                rt * 0.3,
                8,
            );
        }
    } else {
        let trunk_h = h * 0.2;
        b.frustum("trunk", bark, [0.0, 0.0], rt, rt * 0.6, 0.0, h * 0.95, 12);
        let tiers = 3 + (uniform(rng, 0.0, 1.99) as usize);
        let width = h * uniform(rng, 0.18, 0.25);
        for k in 0..tiers {
            let u = k as f32 / tiers as f32;
            let y0 = trunk_h + (h - trunk_h) * u * 0.8;
            let r = width * (1.0 - u * 0.7);
            b.frustum(
                &format!("tier_{k}"),
                leaf,
                [0.0, 0.0],
                r,
                0.0,
                y0,
                y0 + (h - y0) * 0.6 + r * 0.5,
                16,
            );
        }
    }
    b.finish(Placement::Floor, [0.7, 1.3])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::catalog::generate;

    #[test]
    fn every_outdoor_category_meets_the_conventions_for_several_seeds() {
        for category in
            crate::catalog::categories().filter(|c| GENERATORS.iter().any(|(n, _)| *n == c.name))
        {
            for seed in 0..6 {
                crate::items::tests::check_asset(category, seed);
            }
        }
    }

    #[test]
    fn outdoor_sizes_are_realistic_and_seeded() {
        let size = |name: &str, seed| {
            generate(crate::catalog::category(name).unwrap(), seed)
                .info
                .size
        };
        for seed in 0..8 {
            let palm = size("palm_tree", seed);
            assert!((4.0..=7.6).contains(&palm[1]), "palm {palm:?}");
            let umbrella = size("beach_umbrella", seed);
            assert!(
                (1.9..=2.5).contains(&umbrella[1]) && umbrella[0] > 1.5,
                "umbrella {umbrella:?}"
            );
            let tent = size("tent", seed);
            assert!(
                (1.9..=2.3).contains(&tent[2]) && (1.2..=1.7).contains(&tent[0]),
                "tent {tent:?}"
            );
        }
        for category in
            crate::catalog::categories().filter(|c| GENERATORS.iter().any(|(n, _)| *n == c.name))
        {
            assert_eq!(
                generate(category, 5),
                generate(category, 5),
                "{}",
                category.name
            );
        }
    }
}
