//! Kitchen items: microwave, toaster, coffee machine, kettle, pot, pan, cutlery, cutting board,
//! knife block and dish rack. Cookware is hollow (a pot holds things); appliances stand on
//! small feet and face +Z.

use rand_chacha::ChaCha8Rng;

use super::builder::Builder;
use crate::articulation;
use crate::materials::Palette;
use crate::random::{coin, color, int, uniform};
use scenethesis_primitives::{disc, prism_x, rect, rounded_box};
use scenethesis_scene_graph::{Asset, Placement, SurfaceKind};

const APPLIANCE: &[[f32; 3]] = &[
    [0.92, 0.92, 0.9],
    [0.08, 0.08, 0.09],
    [0.55, 0.56, 0.58],
    [0.7, 0.12, 0.1],
    [0.85, 0.8, 0.68],
];

/// An appliance body colour: painted or brushed steel.
fn appliance_body(b: &mut Builder, rng: &mut ChaCha8Rng) -> usize {
    if coin(rng, 0.35) {
        b.palette(Palette::Metal, rng)
    } else {
        b.material("appliance", color(rng, APPLIANCE, 0.03), 0.35)
    }
}

/// Microwave oven: width 0.44–0.56, height 0.26–0.34, depth 0.33–0.43; a box with a door hinged
/// on its left edge over the left two thirds (a dark window, a handle at its free edge), a
/// keypad panel; usable top.
pub(crate) fn microwave(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let body = appliance_body(&mut b, rng);
    let dark = b.material("window", [0.03, 0.03, 0.035], 0.1);
    let (w, h, d) = (
        uniform(rng, 0.44, 0.56),
        uniform(rng, 0.25, 0.32),
        uniform(rng, 0.33, 0.42),
    );
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let foot = 0.012;
    for (i, (sx, sz)) in [(-1.0f32, -1.0f32), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .enumerate()
    {
        b.frustum(
            &format!("foot_{i}"),
            dark,
            [sx * (hw - 0.04), sz * (hd - 0.04)],
            0.012,
            0.012,
            0.0,
            foot + 0.002,
            8,
        );
    }
    b.cuboid("body", body, [-hw, foot, -hd], [hw, foot + h, hd]);
    let split = hw - 0.3 * w;
    // The door, hinged on its left edge: a panel with the window and a handle at its free edge.
    let door_z = hd + 0.012;
    b.joint(articulation::side_hinge(
        "door",
        -hw + 0.004,
        foot,
        door_z,
        true,
    ));
    b.link(Some("door"));
    b.cuboid(
        "door",
        body,
        [-hw + 0.004, foot + 0.004, hd - 0.001],
        [split - 0.004, foot + h - 0.004, door_z],
    );
    b.cuboid(
        "door_window",
        dark,
        [-hw + 0.03, foot + 0.04, door_z - 0.001],
        [split - 0.04, foot + h - 0.04, door_z + 0.003],
    );
    b.cuboid(
        "handle",
        body,
        [split - 0.03, foot + 0.05, door_z - 0.001],
        [split - 0.015, foot + h - 0.05, door_z + 0.025],
    );
    b.link(None);
    b.cuboid(
        "keypad",
        dark,
        [split + 0.02, foot + 0.5 * h, hd - 0.001],
        [hw - 0.02, foot + h - 0.03, hd + 0.003],
    );
    b.top(
        "top",
        rect(-hw + 0.03, -hd + 0.03, hw - 0.03, hd - 0.03),
        foot + h,
    );
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// Toaster: width 0.24–0.34, height 0.18–0.22, depth 0.15–0.22; a body built around two or four
/// open bread slots (real cavities), a lever and a browning knob.
pub(crate) fn toaster(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let body = appliance_body(&mut b, rng);
    let dark = b.material("lever", [0.05, 0.05, 0.05], 0.4);
    let slots_x = if coin(rng, 0.7) { 2 } else { 4 };
    let (h, d) = (uniform(rng, 0.18, 0.21), uniform(rng, 0.15, 0.2));
    let slot_w = 0.032;
    let wall = uniform(rng, 0.02, 0.03);
    let w = slots_x as f32 * slot_w + (slots_x as f32 + 1.0) * wall + 0.04;
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let floor = 0.05;
    b.cuboid("base", body, [-hw, 0.0, -hd], [hw, floor, hd]);
    b.cuboid("front", body, [-hw, floor - 0.001, hd - 0.03], [hw, h, hd]);
    b.cuboid("back", body, [-hw, floor - 0.001, -hd], [hw, h, -hd + 0.03]);
    let mut x = -hw;
    for k in 0..=slots_x {
        let ww = if k == 0 || k == slots_x {
            wall + 0.02
        } else {
            wall
        };
        b.cuboid(
            &format!("wall_{k}"),
            body,
            [x, floor - 0.001, -hd + 0.029],
            [x + ww, h, hd - 0.029],
        );
        x += ww + slot_w;
    }
    b.cuboid(
        "lever",
        dark,
        [hw - 0.001, 0.6 * h, -0.015],
        [hw + 0.02, 0.6 * h + 0.012, 0.015],
    );
    b.tube(
        "knob",
        dark,
        [0.0, 0.35 * h, hd - 0.001],
        [0.0, 0.35 * h, hd + 0.015],
        0.012,
        0.012,
        10,
    );
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// Coffee machine: width 0.18–0.32, height 0.3–0.42, depth 0.25–0.4; a back tower with a
/// water tank, a head overhanging a drip tray and a spout, and the cup bay under it (a shelf
/// with the head above).
pub(crate) fn coffee_machine(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let body = appliance_body(&mut b, rng);
    let dark = b.material("drip_tray", [0.06, 0.06, 0.065], 0.3);
    let tank = b.glass("water_tank", [0.75, 0.85, 0.95], 0.35);
    let (w, h, d) = (
        uniform(rng, 0.18, 0.32),
        uniform(rng, 0.3, 0.42),
        uniform(rng, 0.25, 0.4),
    );
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let tower = uniform(rng, 0.12, 0.16);
    let head = uniform(rng, 0.08, 0.11);
    let tray = 0.025;
    b.cuboid("drip_tray", dark, [-hw, 0.0, -hd], [hw, tray, hd]);
    b.cuboid(
        "tower",
        body,
        [-hw, tray - 0.001, -hd],
        [hw, h, -hd + tower],
    );
    b.cuboid(
        "tank",
        tank,
        [-hw + 0.02, 0.3 * h, -hd - 0.0],
        [hw - 0.02, h - 0.02, -hd + 0.04],
    );
    b.cuboid(
        "head",
        body,
        [-hw, h - head, -hd + tower - 0.001],
        [hw, h, hd - 0.015],
    );
    let spout_z = 0.5 * (-hd + tower + hd - 0.015);
    let spout_bottom = h - head - 0.025;
    b.frustum(
        "spout",
        dark,
        [0.0, spout_z],
        0.012,
        0.018,
        spout_bottom,
        h - head + 0.001,
        10,
    );
    b.surface(
        "cup_bay",
        SurfaceKind::Shelf,
        rect(-hw + 0.02, -hd + tower + 0.02, hw - 0.02, hd - 0.02),
        tray,
        Some(spout_bottom - 0.005 - tray),
    );
    b.top(
        "top",
        rect(-hw + 0.02, -hd + 0.02, hw - 0.02, hd - 0.035),
        h,
    );
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// Kettle: width (with spout and handle) 0.2–0.3, height 0.2–0.28, Ø 0.14–0.18; a tapered
/// body with a lid and knob, a spout at the front and a handle at the back, often on a base.
pub(crate) fn kettle(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let body = appliance_body(&mut b, rng);
    let dark = b.material("handle", [0.06, 0.06, 0.06], 0.5);
    let r = uniform(rng, 0.07, 0.09);
    let h = uniform(rng, 0.17, 0.23);
    let base = if coin(rng, 0.6) {
        b.frustum(
            "power_base",
            dark,
            [0.0, 0.0],
            r + 0.01,
            r + 0.008,
            0.0,
            0.02,
            24,
        );
        0.02
    } else {
        0.0
    };
    b.frustum(
        "body",
        body,
        [0.0, 0.0],
        r,
        0.8 * r,
        base - 0.001,
        base + h,
        24,
    );
    b.frustum(
        "lid",
        body,
        [0.0, 0.0],
        0.7 * r,
        0.6 * r,
        base + h - 0.001,
        base + h + 0.012,
        24,
    );
    b.frustum(
        "knob",
        dark,
        [0.0, 0.0],
        0.012,
        0.01,
        base + h + 0.011,
        base + h + 0.03,
        10,
    );
    b.tube(
        "spout",
        body,
        [0.0, base + 0.45 * h, 0.75 * r],
        [0.0, base + 0.85 * h, 1.45 * r],
        0.016,
        0.009,
        10,
    );
    let pts = [
        [0.0, base + 0.25 * h, -0.9 * r],
        [0.0, base + 0.3 * h, -1.4 * r],
        [0.0, base + 0.85 * h, -1.35 * r],
        [0.0, base + 0.95 * h, -0.75 * r],
    ];
    b.polyline("handle", dark, &pts, 0.011);
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// Cooking pot: width (with handles) 0.2–0.36, height 0.1–0.22, Ø 0.16–0.28; a base and a
/// straight wall around a real hollow, two side handles.
pub(crate) fn pot(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let metal = if coin(rng, 0.7) {
        b.palette(Palette::Metal, rng)
    } else {
        b.palette(Palette::CoatedMetal, rng)
    };
    let dark = b.material("handles", [0.06, 0.06, 0.06], 0.5);
    let r = uniform(rng, 0.08, 0.14);
    let h = uniform(rng, 0.1, 0.22).min(1.4 * r + 0.04);
    let wall = 0.004;
    let base = 0.006;
    b.frustum("base", metal, [0.0, 0.0], r, r, 0.0, base, 28);
    b.ring(
        "wall",
        metal,
        [0.0, 0.0],
        (r - wall, r, 0.002),
        (r - wall, r, h),
        28,
    );
    for (i, sx) in [-1.0f32, 1.0].iter().enumerate() {
        b.cuboid(
            &format!("handle_{i}"),
            dark,
            [
                if *sx < 0.0 { -r - 0.04 } else { r - 0.002 },
                h - 0.035,
                -0.025,
            ],
            [
                if *sx < 0.0 { -r + 0.002 } else { r + 0.04 },
                h - 0.02,
                0.025,
            ],
        );
    }
    b.interior(disc([0.0, 0.0], r - wall - 0.01, 14), base);
    b.finish(Placement::Surface, [0.85, 1.15])
}

/// Frying pan: width (with handle) 0.36–0.58, height 0.04–0.09, Ø 0.2–0.3; a shallow flared
/// wall around a real hollow and a long handle toward +x.
pub(crate) fn pan(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let metal = if coin(rng, 0.5) {
        b.palette(Palette::Metal, rng)
    } else {
        b.material("nonstick", [0.08, 0.08, 0.09], 0.4)
    };
    let grip = b.material("handle", [0.05, 0.04, 0.04], 0.6);
    let r = uniform(rng, 0.1, 0.15);
    let h = uniform(rng, 0.035, 0.06);
    let wall = 0.004;
    let base = 0.005;
    let r0 = 0.82 * r;
    b.frustum("base", metal, [0.0, 0.0], r0, r0, 0.0, base, 28);
    b.ring(
        "wall",
        metal,
        [0.0, 0.0],
        (r0 - wall, r0, 0.002),
        (r - wall, r, h),
        28,
    );
    let len = uniform(rng, 0.16, 0.26);
    b.tube(
        "handle",
        grip,
        [r - 0.004, h - 0.01, 0.0],
        [r + len, h + 0.02, 0.0],
        0.012,
        0.01,
        10,
    );
    b.interior(disc([0.0, 0.0], r0 - wall - 0.01, 14), base);
    b.finish(Placement::Surface, [0.85, 1.15])
}

/// Cutlery (a place setting lying flat): width 0.07–0.12, height 0.01–0.02, depth 0.17–0.23; a
/// fork with tines, a knife and a spoon with a shallow bowl, side by side.
pub(crate) fn cutlery(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let steel = if coin(rng, 0.8) {
        b.metal("steel", [0.8, 0.8, 0.82], 0.2)
    } else {
        b.metal("brass", [0.78, 0.62, 0.3], 0.25)
    };
    let len = uniform(rng, 0.17, 0.22);
    let gap = uniform(rng, 0.028, 0.04);
    let t = 0.003;
    let hl = 0.6 * len;
    let z0 = -0.5 * len;
    // Fork at −x: handle, neck, four tines toward −z.
    let fx = -gap;
    b.cuboid(
        "fork_handle",
        steel,
        [fx - 0.007, 0.0, z0 + len - hl],
        [fx + 0.007, t, z0 + len],
    );
    b.cuboid(
        "fork_head",
        steel,
        [fx - 0.012, 0.0, z0 + 0.05],
        [fx + 0.012, t, z0 + len - hl + 0.001],
    );
    for k in 0..4 {
        let x = fx - 0.0105 + k as f32 * 0.007;
        b.cuboid(
            &format!("fork_tine_{k}"),
            steel,
            [x, 0.0, z0],
            [x + 0.0025, t, z0 + 0.051],
        );
    }
    // Knife in the middle.
    b.cuboid(
        "knife_handle",
        steel,
        [-0.007, 0.0, z0 + len - hl],
        [0.007, 1.6 * t, z0 + len],
    );
    b.cuboid(
        "knife_blade",
        steel,
        [-0.009, 0.0, z0 + 0.005],
        [0.009, 0.5 * t, z0 + len - hl + 0.001],
    );
    // Spoon at +x.
    let sx = gap;
    b.cuboid(
        "spoon_handle",
        steel,
        [sx - 0.006, 0.0, z0 + 0.055],
        [sx + 0.006, t, z0 + len],
    );
    b.ellipsoid(
        "spoon_bowl",
        steel,
        [sx, 0.006, z0 + 0.03],
        [0.02, 0.006, 0.03],
    );
    b.flatten_base(0.0005);
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// Cutting board: width 0.28–0.46, height 0.015–0.035, depth 0.2–0.32; a wooden or plastic slab
/// with rounded edges, sometimes a handle tab; usable top.
pub(crate) fn cutting_board(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let m = if coin(rng, 0.7) {
        b.palette(Palette::Wood, rng)
    } else {
        b.palette(Palette::Plastic, rng)
    };
    let (w, h, d) = (
        uniform(rng, 0.28, 0.4),
        uniform(rng, 0.015, 0.035),
        uniform(rng, 0.2, 0.32),
    );
    b.add(rounded_box(
        "board",
        m,
        [0.0, 0.5 * h, 0.0],
        [0.5 * w, 0.5 * h, 0.5 * d],
        0.3,
    ));
    if coin(rng, 0.4) {
        b.add(rounded_box(
            "tab",
            m,
            [0.5 * w + 0.025, 0.5 * h, 0.0],
            [0.035, 0.5 * h, 0.035],
            0.3,
        ));
    }
    b.top(
        "top",
        rect(
            -0.5 * w + 0.02,
            -0.5 * d + 0.02,
            0.5 * w - 0.02,
            0.5 * d - 0.02,
        ),
        h,
    );
    b.finish(Placement::Surface, [0.85, 1.15])
}

/// Knife block: width 0.1–0.16, height 0.24–0.34 (with handles), depth 0.16–0.24; a wedge of
/// wood leaning back with 3–6 knife handles standing out of its top.
pub(crate) fn knife_block(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let wood = b.palette(Palette::Wood, rng);
    let grip = b.material(
        "handles",
        color(rng, &[[0.05, 0.05, 0.05], [0.35, 0.22, 0.12]], 0.02),
        0.5,
    );
    let (w, h, d) = (
        uniform(rng, 0.1, 0.16),
        uniform(rng, 0.2, 0.26),
        uniform(rng, 0.16, 0.22),
    );
    let hd = 0.5 * d;
    let lean = 0.45 * d;
    let top_d = 0.09;
    // Side profile (z, y): a wedge whose top slopes back.
    let profile = [
        [-hd, 0.0],
        [hd, 0.0],
        [hd - lean + top_d, h],
        [hd - lean, h],
    ];
    b.add(prism_x("block", wood, &profile, -0.5 * w, 0.5 * w));
    let n = int(rng, 3, 6);
    let dir = [0.0, h, -0.5 * lean];
    let len = (dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
    let (uy, uz) = (dir[1] / len, dir[2] / len);
    for k in 0..n {
        let x = -0.5 * w + 0.02 + (w - 0.04) * (k as f32 + 0.5) / n as f32;
        let z = hd - lean + 0.5 * top_d + if k % 2 == 0 { -0.02 } else { 0.02 };
        let hl = uniform(rng, 0.07, 0.1);
        b.tube(
            &format!("handle_{k}"),
            grip,
            [x, h - 0.01, z],
            [x, h - 0.01 + hl * uy, z + hl * uz],
            0.009,
            0.011,
            8,
        );
    }
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// Dish rack: width 0.34–0.5, height 0.12–0.2, depth 0.26–0.36; a drip tray with a low rim, a
/// row of plate tines along the back half and an open front half for cups and bowls.
pub(crate) fn dish_rack(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let wire = if coin(rng, 0.6) {
        b.palette(Palette::Metal, rng)
    } else {
        b.palette(Palette::Plastic, rng)
    };
    let (w, d) = (uniform(rng, 0.34, 0.5), uniform(rng, 0.26, 0.36));
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let h = uniform(rng, 0.12, 0.2);
    let floor = b.open_box("tray", wire, [-hw, 0.0, -hd], [hw, 0.035, hd], 0.006, 0.01);
    let tines = int(rng, 7, 12);
    for k in 0..tines {
        let x = -hw + 0.03 + (w - 0.06) * k as f32 / (tines - 1) as f32;
        for (row, z) in [-hd + 0.03, -0.02].iter().enumerate() {
            b.cuboid(
                &format!("tine_{row}_{k}"),
                wire,
                [x - 0.002, floor - 0.001, z - 0.002],
                [x + 0.002, h, z + 0.002],
            );
        }
    }
    b.cuboid(
        "rail",
        wire,
        [-hw + 0.02, h - 0.006, -hd + 0.025],
        [hw - 0.02, h, -hd + 0.035],
    );
    b.interior(rect(-hw + 0.02, 0.01, hw - 0.02, hd - 0.02), floor);
    b.finish(Placement::Surface, [0.9, 1.1])
}
