//! Equipment and fixtures: gym machines, pianos, studio and shop fixtures, kitchen appliances,
//! lamps, plants and floor coverings. Users of a machine face +Z.

use std::f32::consts::{PI, TAU};

use rand_chacha::ChaCha8Rng;

use super::carcass::{self, Carcass, CarcassMaterials, Feet, CORNERS};
use super::{mat, mat_either, SCALE};
use crate::articulation;
use crate::materials::{fixed_material, Palette};
use crate::random::{coin, int, uniform, uniform3};
use scenethesis_primitives::{
    beam, cylinder, disc_surface, ellipsoid, frustum, hexahedron, prism_y, rect_surface, rod,
    sphere, square_post, strut, AssetBuilder,
};
use scenethesis_scene_graph::{Asset, Placement, SurfaceKind};

fn finish(b: AssetBuilder) -> Asset {
    b.finish(Placement::Floor, SCALE)
}

/// Treadmill: width 0.75–0.92, height 1.3–1.5, length 1.7–2.0; a belt deck, a motor hood and
/// console at the front (+Z) on two uprights, handrails.
pub(super) fn treadmill(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat(&mut b, Palette::CoatedMetal, rng);
    let belt = mat(&mut b, Palette::Rubber, rng);
    let console = b.material(fixed_material(
        "console_black",
        [0x20, 0x22, 0x26],
        0.3,
        0.0,
    ));
    let (w, h, l) = uniform3(rng, [0.75, 0.92], [1.3, 1.5], [1.7, 2.0]);
    let (hw, hl) = (0.5 * w, 0.5 * l);
    let deck_h = uniform(rng, 0.18, 0.24);
    b.cuboid(
        "deck",
        frame,
        [-hw + 0.05, 0.03, -hl],
        [hw - 0.05, deck_h - 0.01, hl - 0.3],
    );
    b.cuboid(
        "belt",
        belt,
        [-hw + 0.1, deck_h - 0.012, -hl + 0.02],
        [hw - 0.1, deck_h, hl - 0.32],
    );
    b.cuboid(
        "motor_hood",
        frame,
        [-hw + 0.05, 0.03, hl - 0.32],
        [hw - 0.05, deck_h + 0.1, hl],
    );
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * (hw - 0.03);
        b.cuboid(
            &format!("side_rail_{i}"),
            frame,
            [x - 0.03, 0.0, -hl],
            [x + 0.03, deck_h + 0.01, hl - 0.3],
        );
        b.part(beam(
            &format!("upright_{i}"),
            frame,
            [x, deck_h, hl - 0.2],
            [x, h - 0.1, hl - 0.35],
            [0.06, 0.05],
        ));
        b.part(beam(
            &format!("handrail_{i}"),
            frame,
            [x, h - 0.3, hl - 0.33],
            [x, h - 0.3, hl - 0.8],
            [0.035, 0.035],
        ));
    }
    let corners = std::array::from_fn(|k| {
        let x = if k & 1 == 0 { -hw + 0.02 } else { hw - 0.02 };
        let y = if k & 2 == 0 { h - 0.2 } else { h };
        let z =
            hl - 0.42 + if k & 2 == 0 { 0.0 } else { 0.08 } + if k & 4 == 0 { 0.0 } else { 0.14 };
        [x, y, z]
    });
    b.part(hexahedron("console", console, corners));
    finish(b)
}

/// Exercise bike: width 0.5–0.65, height 1.1–1.35, length 1.0–1.3; stabiliser feet, a flywheel
/// at the front, saddle, handlebars and console.
pub(super) fn exercise_bike(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat(&mut b, Palette::CoatedMetal, rng);
    let dark = mat(&mut b, Palette::Rubber, rng);
    let saddle = mat(&mut b, Palette::Leather, rng);
    let (w, h, l) = uniform3(rng, [0.5, 0.65], [1.1, 1.35], [1.0, 1.3]);
    let (hw, hl) = (0.5 * w, 0.5 * l);
    for (i, z) in [-hl + 0.04, hl - 0.04].into_iter().enumerate() {
        b.part(rod(
            &format!("stabiliser_{i}"),
            frame,
            [-hw, 0.04, z],
            [hw, 0.04, z],
            0.035,
            0.035,
            10,
        ));
    }
    b.part(beam(
        "spine",
        frame,
        [0.0, 0.06, -hl + 0.04],
        [0.0, 0.06, hl - 0.04],
        [0.06, 0.05],
    ));
    let fly_r = uniform(rng, 0.2, 0.25);
    let fly_z = hl - 0.2;
    b.part(rod(
        "flywheel",
        dark,
        [-0.04, fly_r + 0.1, fly_z],
        [0.04, fly_r + 0.1, fly_z],
        fly_r,
        fly_r,
        24,
    ));
    let seat_h = uniform(rng, 0.85, 1.0);
    let seat_z = -hl + 0.3;
    b.part(beam(
        "seat_tube",
        frame,
        [0.0, 0.06, seat_z + 0.15],
        [0.0, seat_h - 0.05, seat_z],
        [0.05, 0.05],
    ));
    b.part(ellipsoid(
        "saddle",
        saddle,
        [0.0, seat_h - 0.03, seat_z],
        [0.12, 0.04, 0.15],
        6,
        12,
    ));
    let bar_y = h - 0.05;
    b.part(beam(
        "head_tube",
        frame,
        [0.0, 0.06, fly_z - 0.25],
        [0.0, bar_y, fly_z - 0.1],
        [0.06, 0.06],
    ));
    b.part(rod(
        "handlebar",
        frame,
        [-0.25, bar_y, fly_z - 0.18],
        [0.25, bar_y, fly_z - 0.18],
        0.016,
        0.016,
        10,
    ));
    b.cuboid(
        "console",
        dark,
        [-0.1, bar_y, fly_z - 0.16],
        [0.1, h, fly_z - 0.04],
    );
    b.cuboid(
        "fly_guard",
        frame,
        [-0.05, 0.08, fly_z - 0.05],
        [0.05, 2.0 * fly_r + 0.08, fly_z + 0.05],
    );
    finish(b)
}

/// Weight bench: width 0.5–1.2 (with uprights), height 0.43–1.2, length 1.1–1.4; a padded bench
/// on a steel frame, optional barbell uprights.
pub(super) fn weight_bench(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat(&mut b, Palette::CoatedMetal, rng);
    let pad = mat(&mut b, Palette::Leather, rng);
    let l = uniform(rng, 1.1, 1.4);
    let hl = 0.5 * l;
    let pad_h = uniform(rng, 0.43, 0.47);
    let pad_w = uniform(rng, 0.26, 0.3);
    b.cuboid(
        "pad",
        pad,
        [-0.5 * pad_w, pad_h - 0.07, -hl + 0.05],
        [0.5 * pad_w, pad_h, hl - 0.05],
    );
    b.cuboid(
        "rail",
        frame,
        [-0.03, pad_h - 0.13, -hl + 0.1],
        [0.03, pad_h - 0.069, hl - 0.1],
    );
    for (i, z) in [-hl + 0.1, hl - 0.1].into_iter().enumerate() {
        b.cuboid(
            &format!("post_{i}"),
            frame,
            [-0.03, 0.05, z - 0.03],
            [0.03, pad_h - 0.1, z + 0.03],
        );
        b.cuboid(
            &format!("foot_{i}"),
            frame,
            [-0.25, 0.0, z - 0.04],
            [0.25, 0.06, z + 0.04],
        );
    }
    if coin(rng, 0.5) {
        let up_h = uniform(rng, 1.0, 1.2);
        let uw = uniform(rng, 0.5, 0.6);
        let z = -hl + 0.08;
        for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
            let x = sx * 0.5 * uw;
            b.cuboid(
                &format!("upright_{i}"),
                frame,
                [x - 0.03, 0.0, z - 0.03],
                [x + 0.03, up_h, z + 0.03],
            );
            b.cuboid(
                &format!("j_hook_{i}"),
                frame,
                [x - 0.02, up_h - 0.2, z],
                [x + 0.02, up_h - 0.16, z + 0.1],
            );
        }
        b.cuboid(
            "upright_base",
            frame,
            [-0.5 * uw, 0.0, z - 0.04],
            [0.5 * uw, 0.05, z + 0.04],
        );
    }
    b.top_surface(
        "pad",
        [-0.5 * pad_w, -hl + 0.05],
        [0.5 * pad_w, hl - 0.05],
        pad_h,
        0.03,
    );
    finish(b)
}

/// Squat (power) rack: width 1.2–1.45, height 2.1–2.4, depth 1.0–1.4; four uprights joined at
/// the top and the floor, safety arms, a loaded barbell on the J-hooks.
pub(super) fn squat_rack(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat(&mut b, Palette::CoatedMetal, rng);
    let bar = mat(&mut b, Palette::Metal, rng);
    let plate = mat(&mut b, Palette::Rubber, rng);
    let (w, h, d) = uniform3(rng, [1.2, 1.4], [2.1, 2.4], [1.0, 1.3]);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let post = 0.075;
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        let (x, z) = (sx * (hw - 0.5 * post), sz * (hd - 0.5 * post));
        b.part(square_post(
            &format!("upright_{i}"),
            frame,
            [x, z],
            post,
            0.0,
            h,
        ));
    }
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * (hw - 0.5 * post);
        b.cuboid(
            &format!("base_{i}"),
            frame,
            [x - 0.5 * post, 0.0, -hd],
            [x + 0.5 * post, 0.05, hd],
        );
        b.cuboid(
            &format!("top_side_{i}"),
            frame,
            [x - 0.5 * post, h - post, -hd],
            [x + 0.5 * post, h, hd],
        );
        b.cuboid(
            &format!("safety_{i}"),
            frame,
            [x - 0.03, 0.55, -hd],
            [x + 0.03, 0.6, hd],
        );
    }
    b.cuboid("top_back", frame, [-hw, h - post, -hd], [hw, h, -hd + post]);
    b.part(rod(
        "pull_up_bar",
        bar,
        [-hw, h - 0.05, hd - 0.04],
        [hw, h - 0.05, hd - 0.04],
        0.016,
        0.016,
        10,
    ));
    let bar_y = uniform(rng, 1.2, 1.45);
    let bz = hd - 0.5 * post;
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * (hw - 0.5 * post);
        b.cuboid(
            &format!("j_hook_{i}"),
            frame,
            [x - 0.035, bar_y - 0.05, bz + 0.03],
            [x + 0.035, bar_y - 0.014, bz + 0.1],
        );
    }
    let bar_len = uniform(rng, 2.0, 2.2);
    let (bzc, by) = (bz + 0.065, bar_y);
    b.part(rod(
        "barbell",
        bar,
        [-0.5 * bar_len, by, bzc],
        [0.5 * bar_len, by, bzc],
        0.014,
        0.014,
        12,
    ));
    let plates = int(rng, 0, 2);
    for i in 0..plates {
        for (k, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
            let x = sx * (hw + 0.06 + 0.05 * i as f32);
            let r = 0.225 - 0.05 * i as f32;
            b.part(rod(
                &format!("plate_{i}_{k}"),
                plate,
                [x - 0.02, by, bzc],
                [x + 0.02, by, bzc],
                r,
                r,
                24,
            ));
        }
    }
    finish(b)
}

/// Keyboard keys: a white slab and black key strips, front edge at `z_front`.
fn keyboard(b: &mut AssetBuilder, width: f32, y: f32, z_front: f32) {
    let white = b.material(fixed_material("ivory", [0xF4, 0xF0, 0xE6], 0.3, 0.0));
    let black = b.material(fixed_material("ebony", [0x14, 0x14, 0x16], 0.3, 0.0));
    let hw = 0.5 * width;
    b.cuboid(
        "white_keys",
        white,
        [-hw, y, z_front - 0.15],
        [hw, y + 0.025, z_front],
    );
    let octaves = 7;
    let ow = width / octaves as f32;
    for o in 0..octaves {
        for (k, f) in [1.0f32, 2.0, 4.0, 5.0, 6.0].into_iter().enumerate() {
            let x = -hw + o as f32 * ow + f * ow / 7.0;
            b.cuboid(
                &format!("black_key_{o}_{k}"),
                black,
                [x - 0.006, y + 0.024, z_front - 0.15],
                [x + 0.006, y + 0.037, z_front - 0.055],
            );
        }
    }
}

/// Grand piano: width 1.45–1.6, height 1.5–1.8 (lid propped open), length 1.5–2.3; the case
/// outline as two convex prisms, three legs, keyboard at the front (+Z), lid on a prop stick.
pub(super) fn grand_piano(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let case = b.material(if coin(rng, 0.8) {
        fixed_material("piano_black", [0x0C, 0x0C, 0x0E], 0.1, 0.0)
    } else {
        fixed_material("piano_white", [0xF2, 0xF2, 0xF0], 0.12, 0.0)
    });
    let brass = b.material(fixed_material("brass", [0xC8, 0xA0, 0x50], 0.3, 1.0));
    let w = uniform(rng, 1.45, 1.58);
    let l = uniform(rng, 1.5, 2.3);
    let hw = 0.5 * w;
    let body_y0 = uniform(rng, 0.6, 0.66);
    let body_y1 = body_y0 + 0.3;
    // Keyboard end at z = 0 .. front; the case runs toward −Z. The bass side (−X) is straight;
    // the treble side curves in: front block + tapering tail.
    let front = 0.0;
    let k = 0.45 * l;
    let block = [[-hw, front], [hw, front], [hw, front - k], [-hw, front - k]];
    let tail = [
        [-hw, front - k],
        [hw, front - k],
        [0.25 * w - hw, front - l + 0.05],
        [-hw + 0.2, front - l],
        [-hw, front - l + 0.15],
    ];
    b.part(prism_y("case_front", case, &block, body_y0, body_y1));
    b.part(prism_y("case_tail", case, &tail, body_y0, body_y1));
    keyboard(&mut b, w - 0.12, body_y0 - 0.02, front + 0.25);
    b.cuboid(
        "key_bed",
        case,
        [-hw, body_y0 - 0.06, front - 0.01],
        [hw, body_y0 - 0.019, front + 0.26],
    );
    b.cuboid(
        "cheek_left",
        case,
        [-hw, body_y0 - 0.06, front - 0.01],
        [-hw + 0.06, body_y0 + 0.12, front + 0.27],
    );
    b.cuboid(
        "cheek_right",
        case,
        [hw - 0.06, body_y0 - 0.06, front - 0.01],
        [hw, body_y0 + 0.12, front + 0.27],
    );
    for (i, (x, z)) in [
        (-hw + 0.12, front + 0.1),
        (hw - 0.12, front + 0.1),
        (-hw + 0.4, front - l + 0.25),
    ]
    .into_iter()
    .enumerate()
    {
        b.part(frustum(
            &format!("leg_{i}"),
            case,
            [x, z],
            0.045,
            0.07,
            0.05,
            body_y0 + 0.01,
            12,
        ));
        b.part(sphere(
            &format!("caster_{i}"),
            brass,
            [x, 0.03, z],
            0.03,
            6,
            10,
        ));
    }
    b.cuboid(
        "lyre",
        case,
        [-0.12, 0.05, front - 0.25],
        [0.12, body_y0, front - 0.2],
    );
    b.cuboid(
        "pedals",
        brass,
        [-0.1, 0.06, front - 0.2],
        [0.1, 0.08, front - 0.08],
    );
    b.cuboid(
        "music_desk",
        case,
        [-0.35, body_y1, front - 0.2],
        [0.35, body_y1 + 0.28, front - 0.18],
    );
    // Lid hinged on the straight bass side, propped open.
    let lift = uniform(rng, 0.45, 0.65);
    let lid_w = w - 0.05;
    let corners = std::array::from_fn(|i| {
        let across = if i & 1 == 0 { 0.0 } else { lid_w };
        let y = body_y1 + 0.002 + across * lift.sin() + if i & 2 == 0 { 0.0 } else { 0.02 };
        let x = -hw + across * lift.cos();
        let z = if i & 4 == 0 {
            front - l + 0.1
        } else {
            front - 0.05
        };
        [x, y, z]
    });
    b.part(hexahedron("lid", case, corners));
    let prop_top = [
        -hw + 0.8 * lid_w * lift.cos(),
        body_y1 + 0.8 * lid_w * lift.sin(),
        front - 0.5 * l,
    ];
    b.part(beam(
        "lid_prop",
        case,
        [hw - 0.1, body_y1, front - 0.5 * l],
        prop_top,
        [0.02, 0.02],
    ));
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// Upright piano: width 1.45–1.55, height 1.1–1.32, depth 0.55–0.65; a tall case with the
/// keyboard shelf toward +Z, toe blocks and pedals; things stand on its top.
pub(super) fn upright_piano(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let case = b.material(match int(rng, 0, 2) {
        0 => fixed_material("piano_black", [0x0C, 0x0C, 0x0E], 0.1, 0.0),
        1 => fixed_material("piano_walnut", [0x5D, 0x40, 0x2C], 0.3, 0.0),
        _ => fixed_material("piano_white", [0xF2, 0xF2, 0xF0], 0.12, 0.0),
    });
    let brass = b.material(fixed_material("brass", [0xC8, 0xA0, 0x50], 0.3, 1.0));
    let (w, h, d) = uniform3(rng, [1.45, 1.55], [1.1, 1.32], [0.55, 0.65]);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let body_d = uniform(rng, 0.3, 0.36);
    let z_back = -hd;
    b.cuboid("case", case, [-hw, 0.0, z_back], [hw, h, z_back + body_d]);
    let key_y = uniform(rng, 0.68, 0.74);
    b.cuboid(
        "key_bed",
        case,
        [-hw, key_y - 0.1, z_back + body_d - 0.01],
        [hw, key_y, z_back + body_d + 0.2],
    );
    keyboard(&mut b, w - 0.12, key_y - 0.001, z_back + body_d + 0.17);
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * (hw - 0.03);
        b.cuboid(
            &format!("cheek_{i}"),
            case,
            [x - 0.03, key_y - 0.1, z_back + body_d - 0.01],
            [x + 0.03, key_y + 0.08, z_back + body_d + 0.2],
        );
        b.cuboid(
            &format!("toe_block_{i}"),
            case,
            [x - 0.03, 0.0, z_back + body_d - 0.01],
            [x + 0.03, 0.08, hd],
        );
        b.cuboid(
            &format!("leg_{i}"),
            case,
            [x - 0.03, 0.0, z_back + body_d + 0.12],
            [x + 0.03, key_y - 0.099, z_back + body_d + 0.17],
        );
    }
    b.cuboid(
        "pedals",
        brass,
        [-0.1, 0.05, z_back + body_d - 0.01],
        [0.1, 0.07, z_back + body_d + 0.1],
    );
    b.cuboid(
        "music_desk",
        case,
        [-0.35, key_y + 0.2, z_back + body_d - 0.01],
        [0.35, key_y + 0.3, z_back + body_d + 0.04],
    );
    b.top_surface("top", [-hw, z_back], [hw, z_back + body_d], h, 0.03);
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// Music stand: width 0.45–0.55, height 1.0–1.45, depth 0.45–0.55; tripod legs, a pole and a
/// tilted desk with a ledge.
pub(super) fn music_stand(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let metal = mat(&mut b, Palette::CoatedMetal, rng);
    let h = uniform(rng, 1.0, 1.45);
    let spread = uniform(rng, 0.25, 0.3);
    for i in 0..3 {
        let a = i as f32 / 3.0 * TAU + 0.5 * PI;
        b.part(strut(
            &format!("leg_{i}"),
            metal,
            [spread * a.cos(), 0.0, -spread * a.sin()],
            [0.0, 0.35, 0.0],
            [0.015, 0.015],
        ));
    }
    let desk_bottom = h - 0.35;
    b.part(cylinder(
        "pole",
        metal,
        [0.0, 0.0],
        0.011,
        0.3,
        desk_bottom + 0.05,
        8,
    ));
    let tilt = uniform(rng, 0.2, 0.4);
    let corners = std::array::from_fn(|k| {
        let x = if k & 1 == 0 { -0.25 } else { 0.25 };
        let up = k & 2 != 0;
        let y = if up { h } else { desk_bottom };
        let z = if up { -0.35 * tilt.sin() } else { 0.0 } + if k & 4 == 0 { 0.0 } else { 0.01 };
        [x, y, z]
    });
    b.part(hexahedron("desk", metal, corners));
    b.cuboid(
        "ledge",
        metal,
        [-0.25, desk_bottom - 0.01, 0.0],
        [0.25, desk_bottom + 0.02, 0.06],
    );
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// Easel: width 0.55–0.75, height 1.5–1.9, depth 0.55–0.8; an A-frame of two front legs and a
/// back leg, a tray ledge and a canvas.
pub(super) fn easel(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let wood = mat(&mut b, Palette::Wood, rng);
    let canvas = b.material(fixed_material("canvas", [0xF0, 0xEC, 0xE0], 0.9, 0.0));
    let h = uniform(rng, 1.5, 1.9);
    let spread = uniform(rng, 0.25, 0.35);
    let top = [0.0, h, 0.0];
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        b.part(strut(
            &format!("front_leg_{i}"),
            wood,
            [sx * spread, 0.0, 0.15],
            top,
            [0.035, 0.02],
        ));
    }
    let back = uniform(rng, 0.4, 0.6);
    b.part(strut(
        "back_leg",
        wood,
        [0.0, 0.0, -back],
        [0.0, h - 0.02, -0.01],
        [0.03, 0.02],
    ));
    let tray_y = uniform(rng, 0.6, 0.8);
    let tray_z = 0.15 * (1.0 - tray_y / h) + 0.02;
    b.cuboid(
        "tray",
        wood,
        [-0.3, tray_y - 0.03, tray_z - 0.04],
        [0.3, tray_y, tray_z + 0.05],
    );
    let (cw, ch) = (uniform(rng, 0.4, 0.6), uniform(rng, 0.5, 0.7));
    let corners = std::array::from_fn(|k| {
        let x = if k & 1 == 0 { -0.5 * cw } else { 0.5 * cw };
        let up = k & 2 != 0;
        let y = tray_y + if up { ch } else { 0.0 };
        let z = tray_z + 0.015 - if up { 0.15 * ch / h } else { 0.0 }
            + if k & 4 == 0 { 0.0 } else { 0.02 };
        [x, y, z]
    });
    b.part(hexahedron("canvas", canvas, corners));
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// Rocking horse: width 0.3–0.4, height 0.6–0.85, length 0.85–1.15; curved rockers of straight
/// segments, four legs, a body, neck and head. The rockers have an odd number of segments, so
/// the lowest one is flat and centred: the horse rests on it instead of on the edge between
/// two segments, from which it would rock off under its forward-leaning head.
pub(super) fn rocking_horse(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let wood = mat_either(&mut b, 0.5, Palette::Wood, Palette::PaintedWood, rng);
    let saddle = mat(&mut b, Palette::BrightPlastic, rng);
    let l = uniform(rng, 0.85, 1.15);
    let hl = 0.5 * l;
    let w = uniform(rng, 0.3, 0.4);
    let r = 1.2 * l;
    let n = 7;
    let arc = (hl / r).asin();
    for (k, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * 0.5 * (w - 0.03);
        for i in 0..n {
            let (a0, a1) = (
                -arc + 2.0 * arc * i as f32 / n as f32,
                -arc + 2.0 * arc * (i + 1) as f32 / n as f32,
            );
            let p = |a: f32| [x, r - r * a.cos() + 0.02, r * a.sin()];
            b.part(beam(
                &format!("rocker_{k}_{i}"),
                wood,
                p(a0),
                p(a1),
                [0.03, 0.04],
            ));
        }
    }
    let body_y = uniform(rng, 0.42, 0.55);
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        b.part(beam(
            &format!("leg_{i}"),
            wood,
            [sx * 0.5 * (w - 0.03), 0.03, sz * 0.32 * l],
            [sx * 0.05, body_y, sz * 0.2 * l],
            [0.035, 0.035],
        ));
    }
    b.part(ellipsoid(
        "body",
        wood,
        [0.0, body_y + 0.05, 0.0],
        [0.11, 0.1, 0.3 * l],
        8,
        14,
    ));
    b.part(ellipsoid(
        "saddle",
        saddle,
        [0.0, body_y + 0.13, -0.02],
        [0.1, 0.03, 0.1],
        6,
        12,
    ));
    b.part(beam(
        "neck",
        wood,
        [0.0, body_y + 0.05, 0.22 * l],
        [0.0, body_y + 0.3, 0.3 * l],
        [0.06, 0.08],
    ));
    b.part(ellipsoid(
        "head",
        wood,
        [0.0, body_y + 0.3, 0.35 * l],
        [0.05, 0.07, 0.12],
        6,
        12,
    ));
    b.finish(Placement::Floor, [0.8, 1.2])
}

/// Stove (range): width 0.6–0.9, height 0.9–1.1 (with backguard), depth 0.6–0.7; an oven with
/// a closed door hinged at its bottom, a cooktop with four burners and control knobs.
pub(super) fn stove(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.6, Palette::Metal, Palette::Plastic, rng);
    let dark = b.material(fixed_material(
        "cooktop_black",
        [0x16, 0x16, 0x18],
        0.2,
        0.0,
    ));
    let (w, d) = (uniform(rng, 0.6, 0.9), uniform(rng, 0.6, 0.7));
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let h = uniform(rng, 0.9, 0.93);
    b.cuboid("body", body, [-hw, 0.0, -hd], [hw, h - 0.01, hd]);
    b.cuboid(
        "cooktop",
        dark,
        [-hw + 0.01, h - 0.011, -hd + 0.01],
        [hw - 0.01, h, hd - 0.01],
    );
    // The oven door, hinged at its bottom edge, and its handle bar on two posts.
    b.joint(articulation::bottom_hinge(
        "oven_door",
        0.12,
        hd + 0.02,
        1.5,
    ));
    b.link(Some("oven_door"));
    b.cuboid(
        "oven_door",
        dark,
        [-hw + 0.04, 0.12, hd - 0.001],
        [hw - 0.04, h - 0.2, hd + 0.02],
    );
    b.part(rod(
        "oven_handle",
        body,
        [-hw + 0.08, h - 0.24, hd + 0.05],
        [hw - 0.08, h - 0.24, hd + 0.05],
        0.012,
        0.012,
        8,
    ));
    for (i, x) in [-hw + 0.1, hw - 0.1].into_iter().enumerate() {
        b.cuboid(
            &format!("oven_handle_post_{i}"),
            body,
            [x - 0.006, h - 0.246, hd + 0.019],
            [x + 0.006, h - 0.234, hd + 0.045],
        );
    }
    b.link(None);
    let bg = uniform(rng, 0.08, 0.18);
    b.cuboid(
        "backguard",
        body,
        [-hw, h - 0.01, -hd],
        [hw, h + bg, -hd + 0.05],
    );
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        b.part(cylinder(
            &format!("burner_{i}"),
            body,
            [sx * 0.27 * w, sz * 0.22 * d + 0.02],
            0.05,
            h - 0.002,
            h + 0.012,
            12,
        ));
    }
    let knobs = int(rng, 4, 5);
    for i in 0..knobs {
        let x = -hw + (i as f32 + 0.5) * w / knobs as f32;
        b.part(rod(
            &format!("knob_{i}"),
            body,
            [x, h - 0.08, hd - 0.001],
            [x, h - 0.08, hd + 0.025],
            0.018,
            0.018,
            10,
        ));
    }
    b.top_surface(
        "cooktop_centre",
        [-0.27 * w + 0.06, -0.1],
        [0.27 * w - 0.06, 0.1],
        h,
        0.005,
    );
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// Sink (vanity): width 0.5–1.0, height 0.95–1.2 (with tap), depth 0.45–0.6; a basin sunk in a
/// counter (four slabs around the hole), a tap, and an open cabinet bay below.
pub(super) fn sink(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.5, Palette::Wood, Palette::PaintedWood, rng);
    let top = mat_either(&mut b, 0.5, Palette::Stone, Palette::Ceramic, rng);
    let basin_m = b.material(fixed_material("basin_white", [0xF4, 0xF4, 0xF2], 0.15, 0.0));
    let chrome = mat(&mut b, Palette::Metal, rng);
    let (w, d) = (uniform(rng, 0.5, 1.0), uniform(rng, 0.45, 0.6));
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let h = uniform(rng, 0.82, 0.88);
    let t = 0.03;
    let c = Carcass {
        width: w,
        height: h - t + 0.001,
        depth: d,
        board: 0.018,
        feet: Feet::Plinth {
            height: 0.08,
            recess: 0.04,
        },
        columns: 1,
        shelves: vec![],
        top_board: false,
        ..Carcass::PLAIN
    };
    carcass::build(
        &mut b,
        &c,
        CarcassMaterials::uniform(body, chrome),
        [0.0, 0.0],
        "cabinet_",
    );
    let depth_in = uniform(rng, 0.12, 0.16);
    // The hole and the basin below it.
    let (bx, bz0, bz1) = (0.5 * w - 0.08, -hd + 0.12, hd - 0.05);
    let basin_bottom = h - depth_in;
    // The basin hangs inside the cabinet: lower the cabinet's clearance under it.
    let cabinet_top = basin_bottom - 0.02;
    for s in b.surfaces_mut() {
        s.kind = SurfaceKind::Shelf;
        s.clearance = Some(cabinet_top - 0.01 - s.height);
    }
    b.cuboid("counter_back", top, [-hw, h - t, -hd], [hw, h, bz0]);
    b.cuboid("counter_front", top, [-hw, h - t, bz1], [hw, h, hd]);
    b.cuboid(
        "counter_left",
        top,
        [-hw, h - t, bz0 - 0.001],
        [-bx, h, bz1 + 0.001],
    );
    b.cuboid(
        "counter_right",
        top,
        [bx, h - t, bz0 - 0.001],
        [hw, h, bz1 + 0.001],
    );
    let wall = 0.012;
    b.cuboid(
        "basin_bottom",
        basin_m,
        [-bx, basin_bottom - wall, bz0],
        [bx, basin_bottom, bz1],
    );
    b.cuboid(
        "basin_back",
        basin_m,
        [-bx, basin_bottom - wall, bz0],
        [bx, h - t + 0.001, bz0 + wall],
    );
    b.cuboid(
        "basin_front",
        basin_m,
        [-bx, basin_bottom - wall, bz1 - wall],
        [bx, h - t + 0.001, bz1],
    );
    b.cuboid(
        "basin_left",
        basin_m,
        [-bx, basin_bottom - wall, bz0],
        [-bx + wall, h - t + 0.001, bz1],
    );
    b.cuboid(
        "basin_right",
        basin_m,
        [bx - wall, basin_bottom - wall, bz0],
        [bx, h - t + 0.001, bz1],
    );
    let tap_z = -hd + 0.06;
    let tap_h = uniform(rng, 0.15, 0.3);
    b.part(cylinder(
        "tap",
        chrome,
        [0.0, tap_z],
        0.018,
        h - 0.001,
        h + tap_h,
        10,
    ));
    b.part(beam(
        "spout",
        chrome,
        [0.0, h + tap_h - 0.01, tap_z],
        [0.0, h + tap_h - 0.04, tap_z + 0.14],
        [0.02, 0.02],
    ));
    let spout_bottom = h + tap_h - 0.04 - 0.015;
    b.surface(rect_surface(
        "basin",
        SurfaceKind::Interior,
        [-bx + wall, bz0 + wall],
        [bx - wall, bz1 - wall],
        basin_bottom,
        Some(spout_bottom - 0.01 - basin_bottom),
        0.01,
    ));
    if hw - bx >= 0.08 {
        b.top_surface("counter_left", [-hw, bz0], [-bx, bz1], h, 0.01);
    }
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// Step ladder: width 0.45–0.55, height 0.9–1.9, depth 0.5–0.95 (opened); front stiles with
/// flat steps, rear legs and a top platform.
pub(super) fn ladder(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let metal = mat_either(&mut b, 0.6, Palette::Metal, Palette::Wood, rng);
    let cap = mat(&mut b, Palette::BrightPlastic, rng);
    let h = uniform(rng, 0.9, 1.9);
    let w = uniform(rng, 0.45, 0.55);
    let hw = 0.5 * w;
    let front_foot = 0.45 * h * 0.55;
    let back_foot = -0.45 * h * 0.45;
    let top_z = 0.0;
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * (hw - 0.02);
        b.part(strut(
            &format!("stile_{i}"),
            metal,
            [x, 0.0, front_foot],
            [x, h - 0.05, top_z + 0.05],
            [0.03, 0.07],
        ));
        b.part(strut(
            &format!("rear_leg_{i}"),
            metal,
            [x * 0.9, 0.0, back_foot],
            [x * 0.9, h - 0.05, top_z - 0.05],
            [0.03, 0.05],
        ));
    }
    let steps = ((h - 0.2) / 0.27).floor().max(1.0) as usize;
    for i in 0..steps {
        let y = (i + 1) as f32 * h / (steps + 1) as f32;
        let z = front_foot + (top_z + 0.05 - front_foot) * (y / (h - 0.05));
        b.cuboid(
            &format!("step_{i}"),
            metal,
            [-hw + 0.03, y - 0.02, z - 0.06],
            [hw - 0.03, y, z + 0.06],
        );
    }
    b.cuboid("top_cap", cap, [-hw, h - 0.06, -0.1], [hw, h, 0.12]);
    b.top_surface("top_cap", [-hw, -0.1], [hw, 0.12], h, 0.02);
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// Tyre (lying flat): width 0.55–0.8, height 0.16–0.3, depth 0.55–0.8; a ring of convex tread
/// segments around an open hole.
pub(super) fn tire(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let shade = int(rng, 0x16, 0x2C) as u8;
    let rubber = b.material(fixed_material(
        "tyre_rubber",
        [shade, shade, shade + 2],
        uniform(rng, 0.8, 0.95),
        0.0,
    ));
    let r_out = uniform(rng, 0.275, 0.4);
    let r_in = r_out * uniform(rng, 0.55, 0.7);
    let h = uniform(rng, 0.16, 0.3);
    let bead = 0.7 * h;
    let n = 24;
    for i in 0..n {
        let (a0, a1) = (i as f32 / n as f32 * TAU, (i + 1) as f32 / n as f32 * TAU);
        // Outer radius of the segment faces is widened so the chord touches the circle.
        let ro = r_out / (PI / n as f32).cos();
        let corners = std::array::from_fn(|k| {
            let a = if k & 4 == 0 { a0 } else { a1 };
            let outer = k & 1 != 0;
            let r = if outer { ro } else { r_in };
            let half = if outer { 0.5 * h } else { 0.5 * bead };
            let y = 0.5 * h + if k & 2 == 0 { -half } else { half };
            [r * a.cos(), y, r * a.sin()]
        });
        b.part(hexahedron(&format!("tread_{i}"), rubber, corners));
    }
    b.finish(Placement::Floor, [0.8, 1.25])
}

/// Coat rack: width 0.4–0.6, height 1.7–1.95, depth 0.4–0.6; a pole on a cross base with
/// hooks around the top.
pub(super) fn coat_rack(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let wood = mat_either(&mut b, 0.6, Palette::Wood, Palette::CoatedMetal, rng);
    let h = uniform(rng, 1.7, 1.95);
    let r = uniform(rng, 0.2, 0.3);
    for i in 0..4 {
        let a = i as f32 / 4.0 * TAU;
        b.part(beam(
            &format!("foot_{i}"),
            wood,
            [0.0, 0.2, 0.0],
            [r * a.cos(), 0.0, r * a.sin()],
            [0.03, 0.03],
        ));
    }
    b.part(cylinder("pole", wood, [0.0, 0.0], 0.022, 0.1, h, 12));
    let hooks = int(rng, 4, 8);
    for i in 0..hooks {
        let a = i as f32 / hooks as f32 * TAU;
        let y = h - 0.12 - if i % 2 == 0 { 0.0 } else { 0.15 };
        b.part(beam(
            &format!("hook_{i}"),
            wood,
            [0.0, y - 0.05, 0.0],
            [0.14 * a.cos(), y + 0.05, 0.14 * a.sin()],
            [0.015, 0.015],
        ));
    }
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// Pedestal (display plinth): width 0.3–0.6, height 0.75–1.15, depth 0.3–0.6; a square block or
/// a column with a cap; the top carries a sculpture or vase.
pub(super) fn pedestal(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.5, Palette::PaintedWood, Palette::Stone, rng);
    let h = uniform(rng, 0.75, 1.15);
    let w = uniform(rng, 0.3, 0.6);
    let hw = 0.5 * w;
    if coin(rng, 0.6) {
        b.cuboid("block", body, [-hw, 0.0, -hw], [hw, h, hw]);
        b.top_surface("top", [-hw, -hw], [hw, hw], h, 0.03);
    } else {
        b.cuboid("plinth", body, [-hw, 0.0, -hw], [hw, 0.08, hw]);
        b.part(cylinder(
            "column",
            body,
            [0.0, 0.0],
            0.35 * w,
            0.079,
            h - 0.05,
            20,
        ));
        b.cuboid("cap", body, [-hw, h - 0.051, -hw], [hw, h, hw]);
        b.top_surface("top", [-hw, -hw], [hw, hw], h, 0.03);
    }
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// Stanchion (queue post): width 0.3–0.36, height 0.9–1.0, depth 0.3–0.36; a weighted base,
/// a post and a belt head.
pub(super) fn stanchion(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let metal = mat(&mut b, Palette::Metal, rng);
    let dark = mat(&mut b, Palette::CoatedMetal, rng);
    let h = uniform(rng, 0.9, 1.0);
    let r = uniform(rng, 0.15, 0.18);
    // A flat round foot under a bevelled top (see `table_lamp`): the cylinder rests still in
    // the stability simulation, a frustum hull on the floor rocks after settling 1.25 mm.
    b.part(cylinder("base", dark, [0.0, 0.0], r, 0.0, 0.015, 24));
    b.part(frustum(
        "base_top",
        dark,
        [0.0, 0.0],
        r,
        0.8 * r,
        0.015,
        0.04,
        24,
    ));
    b.part(cylinder(
        "post",
        metal,
        [0.0, 0.0],
        0.03,
        0.039,
        h - 0.06,
        12,
    ));
    b.part(cylinder("head", metal, [0.0, 0.0], 0.04, h - 0.061, h, 12));
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// Floor lamp: width 0.3–0.55, height 1.4–1.85, depth 0.3–0.55; a weighted base, a pole and a
/// drum or cone shade.
pub(super) fn floor_lamp(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let metal = mat_either(&mut b, 0.5, Palette::Metal, Palette::CoatedMetal, rng);
    let shade_m = mat_either(&mut b, 0.7, Palette::Paper, Palette::Fabric, rng);
    let h = uniform(rng, 1.4, 1.85);
    let base_r = uniform(rng, 0.14, 0.18);
    b.part(cylinder("base", metal, [0.0, 0.0], base_r, 0.0, 0.03, 24));
    let shade_h = uniform(rng, 0.22, 0.35);
    let (r0, r1) = (uniform(rng, 0.16, 0.27), uniform(rng, 0.1, 0.2));
    b.part(cylinder(
        "pole",
        metal,
        [0.0, 0.0],
        0.012,
        0.029,
        h - 0.5 * shade_h,
        10,
    ));
    b.part(frustum(
        "shade",
        shade_m,
        [0.0, 0.0],
        r0,
        r1.min(r0),
        h - shade_h,
        h,
        24,
    ));
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// Potted plant: width 0.3–1.0, height 0.5–1.8, depth 0.3–1.0; a tapered pot with soil, a stem
/// and clustered foliage ellipsoids.
pub(super) fn plant(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let pot = mat(&mut b, Palette::Ceramic, rng);
    let soil = b.material(fixed_material("soil", [0x3A, 0x2A, 0x1E], 0.95, 0.0));
    let stem_m = mat(&mut b, Palette::Wood, rng);
    let leaf = mat(&mut b, Palette::Foliage, rng);
    let h = uniform(rng, 0.5, 1.8);
    let pot_r = uniform(rng, 0.12, 0.22);
    let pot_h = uniform(rng, 0.2, 0.35).min(0.4 * h);
    b.part(frustum(
        "pot",
        pot,
        [0.0, 0.0],
        0.78 * pot_r,
        pot_r,
        0.0,
        pot_h,
        20,
    ));
    b.part(cylinder(
        "soil",
        soil,
        [0.0, 0.0],
        0.93 * pot_r,
        pot_h - 0.03,
        pot_h + 0.005,
        20,
    ));
    let crown_r = uniform(rng, 0.15, 0.5).min(0.45 * h);
    let crown_y = h - crown_r;
    b.part(cylinder(
        "stem",
        stem_m,
        [0.0, 0.0],
        0.015,
        pot_h - 0.01,
        crown_y,
        8,
    ));
    let clusters = int(rng, 4, 7);
    b.part(ellipsoid(
        "foliage_core",
        leaf,
        [0.0, crown_y, 0.0],
        [0.8 * crown_r, crown_r, 0.8 * crown_r],
        8,
        12,
    ));
    for i in 0..clusters {
        let a = i as f32 / clusters as f32 * TAU + uniform(rng, -0.3, 0.3);
        let rr = uniform(rng, 0.35, 0.5) * crown_r;
        let off = crown_r - rr;
        let y = crown_y + uniform(rng, -0.4, 0.2) * crown_r;
        b.part(ellipsoid(
            &format!("foliage_{i}"),
            leaf,
            [off * a.cos(), y, off * a.sin()],
            [rr, 0.8 * rr, rr],
            6,
            10,
        ));
    }
    b.finish(Placement::Floor, [0.8, 1.2])
}

/// Rug: width 1.2–3.0, height 0.008–0.015, depth 0.8–2.4; a thin rectangular or round slab.
pub(super) fn rug(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let cloth = mat(&mut b, Palette::Fabric, rng);
    let t = uniform(rng, 0.008, 0.015);
    if coin(rng, 0.25) {
        let r = uniform(rng, 0.6, 1.2);
        b.part(cylinder("rug", cloth, [0.0, 0.0], r, 0.0, t, 40));
        b.surface(disc_surface(
            "top",
            SurfaceKind::Top,
            [0.0, 0.0],
            r - 0.05,
            t,
            None,
            16,
        ));
    } else {
        let (w, d) = (uniform(rng, 1.2, 3.0), uniform(rng, 0.8, 2.4));
        b.cuboid(
            "rug",
            cloth,
            [-0.5 * w, 0.0, -0.5 * d],
            [0.5 * w, t, 0.5 * d],
        );
        b.top_surface("top", [-0.5 * w, -0.5 * d], [0.5 * w, 0.5 * d], t, 0.05);
    }
    b.finish(Placement::Floor, [0.8, 1.25])
}

/// Yoga mat: width 0.58–0.66, height 0.004–0.15 (rolled), depth 0.15–1.85; flat on the floor or
/// rolled up.
pub(super) fn yoga_mat(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let foam = mat(&mut b, Palette::Rubber, rng);
    let w = uniform(rng, 0.58, 0.66);
    if coin(rng, 0.75) {
        let (l, t) = (uniform(rng, 1.72, 1.85), uniform(rng, 0.004, 0.008));
        b.cuboid(
            "mat",
            foam,
            [-0.5 * w, 0.0, -0.5 * l],
            [0.5 * w, t, 0.5 * l],
        );
        b.top_surface("top", [-0.5 * w, -0.5 * l], [0.5 * w, 0.5 * l], t, 0.03);
    } else {
        let r = uniform(rng, 0.06, 0.075);
        b.part(rod(
            "rolled_mat",
            foam,
            [-0.5 * w, r, 0.0],
            [0.5 * w, r, 0.0],
            r,
            r,
            20,
        ));
    }
    b.finish(Placement::Floor, [0.9, 1.1])
}
