//! Living, hall and study furniture: fireplace, curtain, window blind, wall clock, shoe rack,
//! suitcase and filing cabinet. Fronts face +Z; wall-mounted pieces have their wall side at −Z.

use rand_chacha::ChaCha8Rng;

use super::carcass::{self, Carcass, CarcassMaterials, Feet, Front, CORNERS};
use super::{mat, mat_either, SCALE};
use crate::materials::{fixed_material, Palette};
use crate::random::{coin, int, uniform};
use scenethesis_primitives::{
    box_yaw, cylinder, ellipsoid, rod, rotated_box, rotation, rounded_box, AssetBuilder,
};
use scenethesis_scene_graph::{Asset, Placement};

/// Fireplace (mantel surround): width 1.2–1.7, height 1.0–1.3, depth 0.3–0.5; a hearth slab,
/// two jambs, a lintel and a mantel shelf around a recessed firebox with logs on a grate.
pub(super) fn fireplace(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let surround = mat_either(&mut b, 0.55, Palette::Stone, Palette::PaintedWood, rng);
    let hearth_m = mat(&mut b, Palette::Stone, rng);
    let soot = b.material(fixed_material("firebox", [0x1C, 0x1A, 0x18], 0.9, 0.0));
    let log = b.material(fixed_material("log", [0x5A, 0x3E, 0x28], 0.9, 0.0));
    let w = uniform(rng, 1.2, 1.7);
    let d = uniform(rng, 0.3, 0.5);
    let mantel_h = uniform(rng, 1.0, 1.25);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let jamb = uniform(rng, 0.18, 0.3);
    let hearth = uniform(rng, 0.03, 0.06);
    let opening = uniform(rng, 0.6, 0.75).min(mantel_h - 0.2);
    let body_z0 = -hd;
    let body_z1 = hd - uniform(rng, 0.1, 0.16);
    b.cuboid("hearth", hearth_m, [-hw, 0.0, -hd], [hw, hearth, hd]);
    b.cuboid(
        "jamb_left",
        surround,
        [-hw + 0.04, hearth - 0.001, body_z0],
        [-hw + 0.04 + jamb, mantel_h, body_z1],
    );
    b.cuboid(
        "jamb_right",
        surround,
        [hw - 0.04 - jamb, hearth - 0.001, body_z0],
        [hw - 0.04, mantel_h, body_z1],
    );
    b.cuboid(
        "lintel",
        surround,
        [-hw + 0.04 + jamb - 0.001, hearth + opening, body_z0],
        [hw - 0.04 - jamb + 0.001, mantel_h, body_z1],
    );
    b.cuboid(
        "firebox_back",
        soot,
        [-hw + 0.04 + jamb - 0.001, hearth - 0.001, body_z0],
        [
            hw - 0.04 - jamb + 0.001,
            hearth + opening + 0.001,
            body_z0 + 0.06,
        ],
    );
    let shelf_t = uniform(rng, 0.04, 0.07);
    b.cuboid(
        "mantel_shelf",
        surround,
        [-hw, mantel_h - 0.001, body_z0],
        [hw, mantel_h + shelf_t, body_z1 + 0.06],
    );
    // Logs on a low grate.
    let gz = 0.5 * (body_z0 + 0.06 + body_z1);
    let gw = (w - 2.0 * (0.04 + jamb)) * 0.6;
    b.cuboid(
        "grate",
        soot,
        [-0.5 * gw, hearth - 0.001, gz - 0.08],
        [0.5 * gw, hearth + 0.06, gz + 0.08],
    );
    for (i, dz) in [-0.04f32, 0.04].iter().enumerate() {
        b.part(rod(
            &format!("log_{i}"),
            log,
            [-0.4 * gw, hearth + 0.1, gz + dz],
            [0.4 * gw, hearth + 0.1, gz + dz],
            0.045,
            0.045,
            10,
        ));
    }
    b.top_surface(
        "mantel",
        [-hw, body_z0],
        [hw, body_z1 + 0.06],
        mantel_h + shelf_t,
        0.03,
    );
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// Curtain (a pair of drapes on a rod): width 1.2–2.6, height 1.5–2.25, depth 0.07–0.16; pleated
/// panels drawn closed or gathered at the sides, hanging from a rod with finials.
pub(super) fn curtain(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let cloth = mat(&mut b, Palette::Fabric, rng);
    let metal = mat_either(&mut b, 0.6, Palette::Metal, Palette::Wood, rng);
    let w = uniform(rng, 1.2, 2.6);
    // At most 2.2 m: hung from 0.5 m up on a 2.8 m wall it still clears the ceiling.
    let h = uniform(rng, 1.5, 2.2);
    let hw = 0.5 * w;
    let rod_z = 0.07;
    b.part(rod(
        "rod",
        metal,
        [-hw, h, rod_z],
        [hw, h, rod_z],
        0.012,
        0.012,
        10,
    ));
    for (i, x) in [-hw, hw].iter().enumerate() {
        b.part(scenethesis_primitives::sphere(
            &format!("finial_{i}"),
            metal,
            [*x, h, rod_z],
            0.025,
            6,
            10,
        ));
        b.cuboid(
            &format!("bracket_{i}"),
            metal,
            [x - 0.01 * x.signum() - 0.008, h - 0.01, 0.0],
            [x - 0.01 * x.signum() + 0.008, h + 0.01, rod_z],
        );
    }
    let closed = coin(rng, 0.45);
    let panel = if closed {
        0.5 * w - 0.05
    } else {
        uniform(rng, 0.18, 0.3) * w
    };
    let folds = int(rng, 5, 9);
    let fold_w = panel / folds as f32;
    let bottom = uniform(rng, 0.0, 0.06).min(h * 0.1);
    for (side, sx) in [(0, -1.0f32), (1, 1.0)] {
        for k in 0..folds {
            let x_outer = sx * (hw - 0.03);
            let x = x_outer - sx * (k as f32 + 0.5) * fold_w;
            let yaw = if k % 2 == 0 { 0.55 } else { -0.55 };
            let half = [0.5 * fold_w / (0.55f32).cos() + 0.004, 0.006];
            b.part(box_yaw(
                &format!("panel_{side}_{k}"),
                cloth,
                [x, rod_z],
                half,
                bottom,
                h - 0.02,
                yaw,
            ));
        }
    }
    b.finish(Placement::Wall, [0.9, 1.1])
}

/// Window blind: width 0.6–1.6, height 0.7–1.6, depth 0.04–0.07; a head rail over either
/// horizontal slats or a roller tube with a fabric sheet, and a weighted bottom rail.
pub(super) fn window_blind(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let w = uniform(rng, 0.6, 1.6);
    let h = uniform(rng, 0.7, 1.6);
    let hw = 0.5 * w;
    let rail = mat_either(&mut b, 0.6, Palette::Plastic, Palette::Metal, rng);
    let depth = uniform(rng, 0.04, 0.06);
    b.cuboid("head_rail", rail, [-hw, h - 0.05, 0.0], [hw, h, depth]);
    if coin(rng, 0.5) {
        let slat = mat_either(&mut b, 0.5, Palette::Wood, Palette::Plastic, rng);
        let pitch = uniform(rng, 0.025, 0.05);
        let n = (((h - 0.08) / pitch) as usize).clamp(8, 48);
        let pitch = (h - 0.08) / n as f32;
        let tilt = uniform(rng, -0.5, 0.5);
        let rot = rotation([1.0, 0.0, 0.0], tilt);
        for k in 0..n {
            let y = 0.03 + (k as f32 + 0.5) * pitch;
            b.part(rotated_box(
                &format!("slat_{k}"),
                slat,
                [0.0, y, 0.5 * depth],
                [hw - 0.01, 0.002, 0.4 * depth],
                &rot,
            ));
        }
        for (i, x) in [-0.3 * w, 0.3 * w].iter().enumerate() {
            b.cuboid(
                &format!("ladder_{i}"),
                rail,
                [x - 0.004, 0.02, 0.5 * depth - 0.002],
                [x + 0.004, h - 0.05, 0.5 * depth + 0.002],
            );
        }
        b.cuboid(
            "bottom_rail",
            rail,
            [-hw + 0.005, 0.0, 0.0],
            [hw - 0.005, 0.03, depth],
        );
    } else {
        let fabric = mat(&mut b, Palette::Fabric, rng);
        b.part(rod(
            "roller",
            rail,
            [-hw + 0.01, h - 0.08, 0.5 * depth],
            [hw - 0.01, h - 0.08, 0.5 * depth],
            0.025,
            0.025,
            12,
        ));
        b.cuboid(
            "sheet",
            fabric,
            [-hw + 0.02, 0.02, 0.5 * depth - 0.002],
            [hw - 0.02, h - 0.08, 0.5 * depth + 0.002],
        );
        b.cuboid(
            "bottom_rail",
            rail,
            [-hw + 0.02, 0.0, 0.5 * depth - 0.01],
            [hw - 0.02, 0.025, 0.5 * depth + 0.01],
        );
    }
    b.finish(Placement::Wall, [0.9, 1.1])
}

/// Wall clock: diameter 0.25–0.45, depth 0.035–0.06; a round or square case, a dial, twelve
/// hour marks and two hands.
pub(super) fn wall_clock(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let case = mat_either(&mut b, 0.5, Palette::Wood, Palette::CoatedMetal, rng);
    let face = b.material(fixed_material("dial", [0xF4, 0xF2, 0xEA], 0.6, 0.0));
    let ink = b.material(fixed_material("hands", [0x12, 0x12, 0x12], 0.4, 0.0));
    let r = uniform(rng, 0.125, 0.225);
    let depth = uniform(rng, 0.035, 0.06);
    let cy = r;
    if coin(rng, 0.75) {
        b.part(rod(
            "case",
            case,
            [0.0, cy, 0.0],
            [0.0, cy, depth - 0.004],
            r,
            r,
            32,
        ));
    } else {
        b.part(rounded_box(
            "case",
            case,
            [0.0, cy, 0.5 * (depth - 0.004)],
            [r, r, 0.5 * (depth - 0.004)],
            0.3,
        ));
    }
    b.part(rod(
        "dial",
        face,
        [0.0, cy, depth - 0.006],
        [0.0, cy, depth - 0.002],
        0.88 * r,
        0.88 * r,
        32,
    ));
    for k in 0..12 {
        let a = std::f32::consts::TAU * k as f32 / 12.0;
        let rot = rotation([0.0, 0.0, 1.0], -a);
        let off = rot * nalgebra::Vector3::new(0.0, 0.78 * r, 0.0);
        b.part(rotated_box(
            &format!("mark_{k}"),
            ink,
            [off.x, cy + off.y, depth - 0.0015],
            [0.004, if k % 3 == 0 { 0.06 } else { 0.03 } * r, 0.0008],
            &rot,
        ));
    }
    for (name, len, angle) in [
        (
            "hour_hand",
            0.45 * r,
            uniform(rng, 0.0, std::f32::consts::TAU),
        ),
        (
            "minute_hand",
            0.7 * r,
            uniform(rng, 0.0, std::f32::consts::TAU),
        ),
    ] {
        let rot = rotation([0.0, 0.0, 1.0], -angle);
        let off = rot * nalgebra::Vector3::new(0.0, 0.5 * len, 0.0);
        b.part(rotated_box(
            name,
            ink,
            [off.x, cy + off.y, depth - 0.0004],
            [0.005, 0.5 * len, 0.0008],
            &rot,
        ));
    }
    b.finish(Placement::Wall, [0.85, 1.2])
}

/// Shoe rack: width 0.6–1.0, height 0.45–0.95, depth 0.26–0.36; 2–4 open tiers between four
/// posts, open all round.
pub(super) fn shoe_rack(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let m = mat_either(&mut b, 0.55, Palette::Wood, Palette::CoatedMetal, rng);
    let h = uniform(rng, 0.45, 0.95);
    let tiers = ((h / 0.2) as usize).clamp(2, 4);
    let c = Carcass {
        width: uniform(rng, 0.6, 1.0),
        height: h,
        depth: uniform(rng, 0.26, 0.36),
        board: 0.018,
        feet: Feet::Legs {
            height: 0.04,
            section: 0.025,
        },
        columns: 1,
        shelves: Carcass::even_shelves(tiers),
        back: false,
        posts: Some(0.025),
        ..Carcass::PLAIN
    };
    carcass::build(&mut b, &c, CarcassMaterials::uniform(m, m), [0.0, 0.0], "");
    b.finish(Placement::Floor, SCALE)
}

/// Suitcase (standing upright): width 0.36–0.5, height 0.58–0.82, depth 0.22–0.32; a rounded
/// shell with ribs, four spinner wheels, a retracted telescopic handle and a carry handle.
pub(super) fn suitcase(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let shell = mat_either(&mut b, 0.6, Palette::Plastic, Palette::BrightPlastic, rng);
    let dark = b.material(fixed_material("wheels", [0x1A, 0x1A, 0x1A], 0.7, 0.0));
    let w = uniform(rng, 0.36, 0.5);
    let d = uniform(rng, 0.22, 0.3);
    let wheel = 0.06;
    let body_h = uniform(rng, 0.5, 0.7);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        let (x, z) = (sx * (hw - 0.04), sz * (hd - 0.04));
        b.part(ellipsoid(
            &format!("wheel_{i}"),
            dark,
            [x, 0.025, z],
            [0.012, 0.025, 0.025],
            6,
            10,
        ));
        b.part(cylinder(
            &format!("caster_{i}"),
            dark,
            [x, z],
            0.015,
            0.03,
            wheel + 0.005,
            8,
        ));
    }
    b.part(rounded_box(
        "shell",
        shell,
        [0.0, wheel + 0.5 * body_h, 0.0],
        [hw, 0.5 * body_h, hd],
        0.3,
    ));
    let ribs = int(rng, 0, 3);
    for k in 0..ribs {
        let x = -hw + w * (k as f32 + 1.0) / (ribs as f32 + 1.0);
        b.cuboid(
            &format!("rib_{k}"),
            shell,
            [x - 0.012, wheel + 0.04, hd - 0.004],
            [x + 0.012, wheel + body_h - 0.04, hd + 0.006],
        );
    }
    let top = wheel + body_h;
    let handle_up = uniform(rng, 0.02, 0.12);
    for (i, x) in [-0.12f32, 0.12].iter().enumerate() {
        b.cuboid(
            &format!("tube_{i}"),
            dark,
            [x - 0.01, top - 0.05, -hd + 0.02],
            [x + 0.01, top + handle_up, -hd + 0.045],
        );
    }
    b.cuboid(
        "grip",
        dark,
        [-0.14, top + handle_up - 0.001, -hd + 0.015],
        [0.14, top + handle_up + 0.03, -hd + 0.05],
    );
    b.cuboid(
        "carry_handle",
        dark,
        [-0.07, top - 0.01, -0.015],
        [0.07, top + 0.025, 0.015],
    );
    b.finish(Placement::Floor, [0.85, 1.15])
}

/// Filing cabinet: width 0.38–0.5, height 0.68–1.35, depth 0.5–0.63; 2–4 stacked drawers of coated
/// steel on a low plinth, a usable top.
pub(super) fn filing_cabinet(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.7, Palette::CoatedMetal, Palette::PaintedWood, rng);
    let handle = mat(&mut b, Palette::Metal, rng);
    let rows = int(rng, 2, 4);
    let c = Carcass {
        width: uniform(rng, 0.38, 0.5),
        height: rows as f32 * uniform(rng, 0.3, 0.33) + 0.05,
        depth: uniform(rng, 0.5, 0.63),
        board: 0.012,
        feet: Feet::Plinth {
            height: 0.04,
            recess: 0.02,
        },
        columns: 1,
        shelves: Carcass::even_shelves(rows),
        drawer_rows: rows,
        front: Front::Open,
        ..Carcass::PLAIN
    };
    carcass::build(
        &mut b,
        &c,
        CarcassMaterials::uniform(body, handle),
        [0.0, 0.0],
        "",
    );
    b.finish(Placement::Floor, SCALE)
}
