//! Work, worship and service furniture: vending machine, wine rack, server rack, pew, altar,
//! lectern, water cooler, photocopier, safe, treasure chest, punching bag and bunk bed.
//!
//! Fronts face +Z, the side a person uses (a lectern's reader, a copier's operator); doors,
//! drawers and lids are drawn closed and open through [`crate::articulation`].

use std::f32::consts::PI;

use rand_chacha::ChaCha8Rng;

use super::carcass::{self, Carcass, CarcassMaterials, Feet, Front, CORNERS};
use super::{mat, mat_either, SCALE};
use crate::articulation::{self, Leaf, LinkMaterials};
use crate::materials::{fixed_material, Palette};
use crate::random::{coin, int, pick, uniform, uniform3};
use scenethesis_primitives::{
    cylinder, ellipsoid, frustum, prism_x, rect_surface, rod, rotated_box, rotation, square_post,
    strut, AssetBuilder,
};
use scenethesis_scene_graph::{Asset, Placement, SurfaceKind};

/// Registers a fixed material given in sRGB bytes.
fn fixed(b: &mut AssetBuilder, name: &str, srgb: [u8; 3], roughness: f32, metallic: f32) -> usize {
    b.material(fixed_material(name, srgb, roughness, metallic))
}

/// Registers a translucent fixed material (glass, a water bottle) of opacity `alpha`.
fn translucent(b: &mut AssetBuilder, name: &str, srgb: [u8; 3], alpha: f32) -> usize {
    let mut m = fixed_material(name, srgb, 0.05, 0.0);
    m.base_color[3] = alpha;
    b.material(m)
}

/// Bright packaging colours of snacks and drinks.
const PRODUCT_COLOURS: [[u8; 3]; 8] = [
    [0xD8, 0x22, 0x2A],
    [0xF2, 0xB1, 0x1B],
    [0x1E, 0x5C, 0xB8],
    [0x2E, 0x9E, 0x48],
    [0xE8, 0x6A, 0x1C],
    [0x7A, 0x2E, 0x8E],
    [0xF0, 0xEE, 0xE6],
    [0x5A, 0x32, 0x1E],
];

// ---------------------------------------------------------------------------------------------
// Vending machine.

/// The measures of a vending machine every part shares.
struct Vending {
    hw: f32,
    hd: f32,
    h: f32,
    /// Front face of the cabinet (the door's back face) and the door's thickness.
    zf: f32,
    door_t: f32,
    /// Left edge of the keypad column, bottom of the window, top of the window.
    split: f32,
    win_y0: f32,
    win_y1: f32,
}

/// Vending machine: width 0.75–1.0, height 1.75–1.95, depth 0.7–0.85 (a snack machine is about
/// 0.9 × 1.83 × 0.85); a steel cabinet with 4–6 trays of products behind a door hinged on its
/// left edge: a glass window, a keypad column with display and coin slot, a pickup flap below.
pub(super) fn vending_machine(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat(&mut b, Palette::CoatedMetal, rng);
    let (w, h, d) = uniform3(rng, [0.75, 1.0], [1.75, 1.95], [0.7, 0.85]);
    let door_t = 0.06;
    let v = Vending {
        hw: 0.5 * w,
        hd: 0.5 * d,
        h,
        zf: 0.5 * d - door_t,
        door_t,
        split: -0.5 * w + uniform(rng, 0.68, 0.74) * w,
        win_y0: uniform(rng, 0.5, 0.6),
        win_y1: h - uniform(rng, 0.1, 0.16),
    };
    vending_cabinet(&mut b, &v, body);
    vending_products(&mut b, &v, rng);
    vending_door(&mut b, &v, body, rng);
    b.top_surface("top", [-v.hw, -v.hd], [v.hw, v.zf], h, 0.03);
    b.finish(Placement::Floor, SCALE)
}

/// The hollow cabinet: plinth, back, sides, top and the wall of the mechanism column.
fn vending_cabinet(b: &mut AssetBuilder, v: &Vending, body: usize) {
    let (hw, hd, h, zf, t) = (v.hw, v.hd, v.h, v.zf, 0.03);
    b.cuboid("plinth", body, [-hw, 0.0, -hd], [hw, 0.1, zf]);
    b.cuboid("back", body, [-hw, 0.0, -hd], [hw, h, -hd + t]);
    b.cuboid("side_left", body, [-hw, 0.0, -hd], [-hw + t, h, zf]);
    b.cuboid("side_right", body, [hw - t, 0.0, -hd], [hw, h, zf]);
    b.cuboid("roof", body, [-hw, h - t, -hd], [hw, h, zf]);
    b.cuboid(
        "mechanism",
        body,
        [v.split, 0.1, -hd + t],
        [hw - t, h - t, zf - 0.01],
    );
}

/// Rows of product trays behind the window, each with a product in every slot.
fn vending_products(b: &mut AssetBuilder, v: &Vending, rng: &mut ChaCha8Rng) {
    let tray = fixed(b, "tray_steel", [0x9A, 0x9C, 0xA0], 0.4, 0.8);
    let colours: Vec<usize> = (0..4)
        .map(|k| {
            let c = *pick(rng, &PRODUCT_COLOURS);
            fixed(b, &format!("product_{k}"), c, 0.5, 0.0)
        })
        .collect();
    let rows = int(rng, 4, 6);
    let slots = int(rng, 4, 7);
    let (x0, x1) = (-v.hw + 0.04, v.split - 0.01);
    let (y0, y1) = (v.win_y0 + 0.02, v.win_y1 - 0.02);
    let row_h = (y1 - y0) / rows as f32;
    let slot_w = (x1 - x0) / slots as f32;
    let cans = coin(rng, 0.35);
    for r in 0..rows {
        let y = y0 + r as f32 * row_h;
        b.cuboid(
            &format!("tray_{r}"),
            tray,
            [x0, y, -v.hd + 0.05],
            [x1, y + 0.01, v.zf - 0.02],
        );
        for s in 0..slots {
            let x = x0 + (s as f32 + 0.5) * slot_w;
            let m = colours[(r * 3 + s) % colours.len()];
            let name = format!("product_{r}_{s}");
            let z = v.zf - 0.08;
            if cans {
                let rr = (0.38 * slot_w).min(0.033);
                b.part(cylinder(
                    &name,
                    m,
                    [x, z],
                    rr,
                    y + 0.009,
                    y + 0.009 + 0.12,
                    12,
                ));
            } else {
                let (hx, top) = (0.36 * slot_w, (0.6 * row_h).min(0.2));
                b.cuboid(
                    &name,
                    m,
                    [x - hx, y + 0.009, z - 0.02],
                    [x + hx, y + top, z + 0.02],
                );
            }
        }
    }
}

/// The door on its left hinge: stile, header with a sign, window glass, bottom panel with the
/// pickup flap, and the keypad column with display, keys, coin slot and lock.
fn vending_door(b: &mut AssetBuilder, v: &Vending, body: usize, rng: &mut ChaCha8Rng) {
    let glass = translucent(b, "window_glass", [0x4C, 0x5E, 0x68], 0.3);
    let sign = mat(b, Palette::BrightPlastic, rng);
    let dark = fixed(b, "panel_black", [0x18, 0x18, 0x1A], 0.5, 0.1);
    let steel = mat(b, Palette::Metal, rng);
    let (hw, h, zf, t, split) = (v.hw, v.h, v.zf, v.door_t, v.split);
    let z1 = zf + t;
    b.joint(articulation::side_hinge("door", -hw, 0.1, z1, true));
    b.link(Some("door"));
    b.cuboid("door_stile", body, [-hw, 0.1, zf], [-hw + 0.05, h, z1]);
    b.cuboid(
        "door_header",
        sign,
        [-hw + 0.049, v.win_y1, zf],
        [split, h, z1],
    );
    b.cuboid(
        "door_bottom",
        body,
        [-hw + 0.049, 0.1, zf],
        [split, v.win_y0, z1],
    );
    b.cuboid(
        "door_glass",
        glass,
        [-hw + 0.049, v.win_y0 - 0.001, zf + 0.02],
        [split + 0.001, v.win_y1 + 0.001, zf + 0.03],
    );
    b.cuboid("door_keypad_column", dark, [split, 0.1, zf], [hw, h, z1]);
    let flap_top = (v.win_y0 - 0.08).min(0.45);
    b.cuboid(
        "pickup_flap",
        dark,
        [-hw + 0.09, flap_top - 0.18, z1 - 0.001],
        [split - 0.07, flap_top, z1 + 0.004],
    );
    vending_keypad(b, v, steel);
    b.link(None);
}

/// The keypad, display, coin slot and lock on the door's right column.
fn vending_keypad(b: &mut AssetBuilder, v: &Vending, steel: usize) {
    let screen = fixed(b, "display", [0x1C, 0x4A, 0x3C], 0.2, 0.0);
    let z1 = v.zf + v.door_t;
    let cx = 0.5 * (v.split + v.hw);
    let ky = 0.6 * v.h;
    b.cuboid(
        "display",
        screen,
        [cx - 0.07, ky + 0.2, z1 - 0.001],
        [cx + 0.07, ky + 0.27, z1 + 0.004],
    );
    for k in 0..12 {
        let (i, j) = ((k % 3) as f32 - 1.0, (k / 3) as f32);
        let (x, y) = (cx + 0.035 * i, ky + 0.16 - 0.035 * j);
        b.cuboid(
            &format!("key_{k}"),
            steel,
            [x - 0.012, y - 0.012, z1 - 0.001],
            [x + 0.012, y + 0.012, z1 + 0.006],
        );
    }
    b.cuboid(
        "coin_slot",
        steel,
        [cx - 0.03, ky - 0.05, z1 - 0.001],
        [cx + 0.03, ky, z1 + 0.006],
    );
    b.part(rod(
        "lock",
        steel,
        [cx, ky - 0.2, z1 - 0.001],
        [cx, ky - 0.2, z1 + 0.006],
        0.015,
        0.015,
        12,
    ));
}

// ---------------------------------------------------------------------------------------------
// Wine rack.

/// Wine rack: width 0.33–1.06, height 0.37–1.35, depth 0.24–0.32 with bottle necks out to 0.33
/// (cells 0.095–0.115 clear, one bottle each); a grid of 3–8 columns and 3–10 rows of square
/// cells on a plinth, some holding a bottle lying neck-out, the empty ones shelf surfaces
/// (bottles lie in them), a usable top.
pub(super) fn wine_rack(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let wood = mat_either(&mut b, 0.75, Palette::Wood, Palette::PaintedWood, rng);
    let cell = uniform(rng, 0.095, 0.115);
    let board = uniform(rng, 0.012, 0.018);
    let (cols, rows) = (int(rng, 3, 8), int(rng, 3, 10));
    let plinth = uniform(rng, 0.02, 0.05);
    let c = Carcass {
        width: cols as f32 * (cell + board) + board,
        height: rows as f32 * (cell + board) + board + plinth,
        depth: uniform(rng, 0.24, 0.32),
        board,
        feet: Feet::Plinth {
            height: plinth,
            recess: 0.01,
        },
        columns: cols,
        shelves: Carcass::even_shelves(rows),
        back: coin(rng, 0.4),
        ..Carcass::PLAIN
    };
    carcass::build(
        &mut b,
        &c,
        CarcassMaterials::uniform(wood, wood),
        [0.0, 0.0],
        "",
    );
    let filled = wine_bottles(&mut b, &c, cell, rng);
    b.surfaces_mut().retain(|s| !filled.contains(&s.name));
    b.finish(Placement::Floor, SCALE)
}

/// Lays a bottle, neck toward +Z, into about half of the cells of the rack `c` (cells `cell`
/// clear); returns the names of the filled cells' surfaces.
fn wine_bottles(b: &mut AssetBuilder, c: &Carcass, cell: f32, rng: &mut ChaCha8Rng) -> Vec<String> {
    let greens = [[0x1E, 0x3A, 0x22], [0x3A, 0x24, 0x10], [0x22, 0x22, 0x20]];
    let glass: Vec<usize> = greens
        .iter()
        .enumerate()
        .map(|(k, &g)| fixed(b, &format!("bottle_glass_{k}"), g, 0.1, 0.0))
        .collect();
    let t = c.board;
    let (x0, z0) = (-0.5 * c.width + t, -0.5 * c.depth + 0.02);
    let (yi0, yi1) = (c.body_bottom() + t, c.height - t);
    // The floor of each row, as the carcass lays its shelf boards.
    let floor = |row: usize| match row {
        0 => yi0,
        _ => yi0 + c.shelves[row - 1] * (yi1 - yi0) + 0.5 * t,
    };
    let share = uniform(rng, 0.3, 0.7) as f64;
    let mut filled = Vec::new();
    for col in 0..c.columns {
        for row in 0..c.shelves.len() + 1 {
            if !coin(rng, share) {
                continue;
            }
            let r = (0.5 * cell - 0.01).min(0.037);
            let x = x0 + col as f32 * (cell + t) + 0.5 * cell;
            let y = floor(row) + r;
            let m = glass[(col + 2 * row) % glass.len()];
            let name = format!("bottle_{col}_{row}");
            let (zb, zs) = (z0, z0 + 0.2);
            b.part(rod(
                &format!("{name}_body"),
                m,
                [x, y, zb],
                [x, y, zs],
                r,
                r,
                12,
            ));
            b.part(rod(
                &format!("{name}_shoulder"),
                m,
                [x, y, zs - 0.001],
                [x, y, zs + 0.05],
                r,
                0.014,
                12,
            ));
            b.part(rod(
                &format!("{name}_neck"),
                m,
                [x, y, zs + 0.049],
                [x, y, zs + 0.1],
                0.014,
                0.015,
                10,
            ));
            filled.push(format!("shelf_{col}_{row}"));
        }
    }
    filled
}

// ---------------------------------------------------------------------------------------------
// Server rack.

/// One rack unit (1U), metres.
const RACK_UNIT: f32 = 0.04445;

/// Server rack: width 0.6–0.8, height 2.01–2.05 (42U), depth 0.9–1.2 (a typical data-centre rack
/// is 0.6 × 2.0 × 1.07); a steel cabinet on levelling feet with 19-inch mounting rails holding
/// 1U–4U servers with status lights, and a perforated front door hinged on one side.
pub(super) fn server_rack(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = fixed(&mut b, "rack_black", [0x1E, 0x1F, 0x22], 0.5, 0.4);
    let mesh = fixed(&mut b, "perforated_steel", [0x4A, 0x4D, 0x52], 0.85, 0.5);
    let handle = mat(&mut b, Palette::Metal, rng);
    let (w, d) = (uniform(rng, 0.6, 0.8), uniform(rng, 0.9, 1.2));
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let u0 = 0.1;
    let h = u0 + 42.0 * RACK_UNIT + uniform(rng, 0.045, 0.08);
    let zf = hd - 0.025;
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        let (x, z) = (sx * (hw - 0.05), sz * (hd - 0.05));
        b.part(cylinder(
            &format!("foot_{i}"),
            handle,
            [x, z],
            0.025,
            0.0,
            0.041,
            10,
        ));
    }
    b.cuboid("bottom", body, [-hw, 0.04, -hd], [hw, 0.07, zf]);
    b.cuboid("roof", body, [-hw, h - 0.03, -hd], [hw, h, zf]);
    b.cuboid("rear_door", body, [-hw, 0.04, -hd], [hw, h, -hd + 0.02]);
    for (name, x0, x1) in [
        ("side_left", -hw, -hw + 0.02),
        ("side_right", hw - 0.02, hw),
    ] {
        b.cuboid(name, body, [x0, 0.04, -hd], [x1, h, zf]);
    }
    let rail_z = zf - 0.1;
    for (i, x) in [-0.232f32, 0.232].into_iter().enumerate() {
        for (k, z) in [rail_z, -hd + 0.12].into_iter().enumerate() {
            b.part(square_post(
                &format!("rail_{i}_{k}"),
                body,
                [x, z],
                0.02,
                0.07,
                h - 0.03,
            ));
        }
    }
    rack_servers(&mut b, u0, rail_z, rng);
    let hinge_left = coin(rng, 0.5);
    articulation::door(
        &mut b,
        "door",
        LinkMaterials {
            panel: mesh,
            handle,
        },
        Leaf {
            x: [-hw + 0.002, hw - 0.002],
            y: [0.045, h - 0.002],
            z: zf,
            thickness: 0.02,
            hinge_left,
        },
    );
    rack_door_frame(&mut b, body, [hw, h, zf + 0.02]);
    b.top_surface("top", [-hw, -hd], [hw, zf], h, 0.03);
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// Fills the 42 units above `u0` with 1U–4U servers and gaps, their bezels at `front_z`.
fn rack_servers(b: &mut AssetBuilder, u0: f32, front_z: f32, rng: &mut ChaCha8Rng) {
    let chassis = fixed(b, "server_steel", [0x8C, 0x8E, 0x92], 0.4, 0.8);
    let bezel = fixed(b, "bezel_black", [0x12, 0x12, 0x14], 0.5, 0.1);
    let (name, colour) = *pick(
        rng,
        &[
            ("led_green", [0x40, 0xE0, 0x70]),
            ("led_blue", [0x40, 0x90, 0xF0]),
        ],
    );
    let led = fixed(b, name, colour, 0.2, 0.0);
    let depth = uniform(rng, 0.6, 0.75);
    let (mut u, mut n) = (0usize, 0usize);
    while u < 42 {
        if !coin(rng, 0.72) {
            u += 1;
            continue;
        }
        let size = (*pick(rng, &[1usize, 1, 2, 2, 4])).min(42 - u);
        let (y0, y1) = (
            u0 + u as f32 * RACK_UNIT + 0.001,
            u0 + (u + size) as f32 * RACK_UNIT - 0.001,
        );
        b.cuboid(
            &format!("server_{n}"),
            chassis,
            [-0.22, y0, front_z - depth],
            [0.22, y1, front_z],
        );
        b.cuboid(
            &format!("server_{n}_bezel"),
            bezel,
            [-0.241, y0, front_z - 0.001],
            [0.241, y1, front_z + 0.006],
        );
        b.cuboid(
            &format!("server_{n}_led"),
            led,
            [0.15, y1 - 0.014, front_z + 0.005],
            [0.2, y1 - 0.008, front_z + 0.009],
        );
        u += size;
        n += 1;
    }
}

/// The door's solid frame around its perforated panel (on the door's link), `size` = (half
/// width, height, the panel's front face).
fn rack_door_frame(b: &mut AssetBuilder, body: usize, size: [f32; 3]) {
    let [hw, h, z] = size;
    let f = 0.04;
    b.link(Some("door"));
    b.cuboid(
        "door_frame_left",
        body,
        [-hw + 0.002, 0.045, z - 0.002],
        [-hw + f, h - 0.002, z + 0.004],
    );
    b.cuboid(
        "door_frame_right",
        body,
        [hw - f, 0.045, z - 0.002],
        [hw - 0.002, h - 0.002, z + 0.004],
    );
    b.cuboid(
        "door_frame_top",
        body,
        [-hw + f, h - f, z - 0.002],
        [hw - f, h - 0.002, z + 0.004],
    );
    b.cuboid(
        "door_frame_bottom",
        body,
        [-hw + f, 0.045, z - 0.002],
        [hw - f, 0.045 + f, z + 0.004],
    );
    b.link(None);
}

// ---------------------------------------------------------------------------------------------
// Pew, altar, lectern.

/// Pew: length 1.5–3.6, height 0.88–1.0, depth 0.55–0.7; a seat 0.43–0.47 high between shaped
/// end panels (a middle support when longer than 2.4), a raked back with a cap rail, a rail
/// under the seat front and sometimes a seat cushion.
pub(super) fn pew(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let wood = mat(&mut b, Palette::Wood, rng);
    let (l, h, d) = uniform3(rng, [1.5, 3.6], [0.88, 1.0], [0.55, 0.7]);
    let (hl, hd) = (0.5 * l, 0.5 * d);
    let seat = uniform(rng, 0.43, 0.47);
    let end_t = 0.05;
    let profile = [
        [-hd, 0.0],
        [hd, 0.0],
        [hd, seat + 0.14],
        [-hd + 0.12, h],
        [-hd, h],
    ];
    b.part(prism_x("end_left", wood, &profile, -hl, -hl + end_t));
    b.part(prism_x("end_right", wood, &profile, hl - end_t, hl));
    let rake = uniform(rng, 0.06, 0.1);
    let zb = -hd + 0.03 + rake;
    let (x0, x1) = (-hl + end_t - 0.005, hl - end_t + 0.005);
    b.cuboid(
        "seat",
        wood,
        [x0, seat - 0.04, zb - 0.01],
        [x1, seat, hd - 0.02],
    );
    b.cuboid(
        "seat_rail",
        wood,
        [x0, seat - 0.13, hd - 0.06],
        [x1, seat - 0.039, hd - 0.035],
    );
    let back = [
        [zb - 0.03, seat - 0.04],
        [zb, seat - 0.04],
        [zb - rake, h - 0.03],
        [zb - rake - 0.03, h - 0.03],
    ];
    b.part(prism_x("back", wood, &back, x0, x1));
    let zt = zb - rake - 0.015;
    b.cuboid(
        "cap_rail",
        wood,
        [x0, h - 0.035, zt - 0.03],
        [x1, h - 0.005, zt + 0.03],
    );
    b.cuboid("floor_rail", wood, [x0, 0.05, -0.03], [x1, 0.12, 0.03]);
    if l > 2.4 {
        b.cuboid(
            "middle_support",
            wood,
            [-0.03, 0.0, -0.15],
            [0.03, seat - 0.039, hd - 0.08],
        );
    }
    let mut top = seat;
    if coin(rng, 0.4) {
        let cloth = mat(&mut b, Palette::Fabric, rng);
        top = seat + 0.03;
        b.cuboid(
            "cushion",
            cloth,
            [x0 + 0.01, seat - 0.001, zb],
            [x1 - 0.01, top, hd - 0.03],
        );
    }
    b.top_surface("seat", [x0, zb], [x1, hd - 0.03], top, 0.04);
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// Altar: width 1.2–2.4, height 0.96–1.06, depth 0.6–1.0; a stone block or a wooden table on
/// four legs, under a white cloth that covers the top and hangs over both ends, and a coloured
/// frontal hanging on the front.
pub(super) fn altar(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let stone = coin(rng, 0.5);
    let body = if stone {
        mat(&mut b, Palette::Stone, rng)
    } else {
        mat(&mut b, Palette::Wood, rng)
    };
    let linen = fixed(&mut b, "altar_linen", [0xF4, 0xF2, 0xEA], 0.9, 0.0);
    let colours = [
        [0x2C, 0x6E, 0x3A],
        [0x5E, 0x2A, 0x72],
        [0xA8, 0x1E, 0x24],
        [0xD8, 0xB0, 0x48],
    ];
    let frontal = fixed(&mut b, "frontal", *pick(rng, &colours), 0.8, 0.0);
    let (w, top, d) = uniform3(rng, [1.2, 2.4], [0.95, 1.05], [0.6, 1.0]);
    let (hw, hd, slab) = (0.5 * w, 0.5 * d, 0.06);
    b.cuboid("mensa", body, [-hw, top - slab, -hd], [hw, top, hd]);
    if stone {
        b.cuboid(
            "base",
            body,
            [-hw + 0.06, 0.0, -hd + 0.06],
            [hw - 0.06, top - slab + 0.001, hd - 0.06],
        );
    } else {
        for (i, (sx, sz)) in CORNERS.iter().enumerate() {
            b.part(square_post(
                &format!("leg_{i}"),
                body,
                [sx * (hw - 0.08), sz * (hd - 0.08)],
                0.08,
                0.0,
                top - slab + 0.001,
            ));
        }
        b.cuboid(
            "apron",
            body,
            [-hw + 0.06, top - slab - 0.12, -hd + 0.06],
            [hw - 0.06, top - slab + 0.001, hd - 0.06],
        );
    }
    let c = 0.004;
    b.cuboid(
        "cloth",
        linen,
        [-hw - c, top - 0.001, -hd - c],
        [hw + c, top + c, hd + c],
    );
    let drop = uniform(rng, 0.25, 0.6).min(top - 0.2);
    for (name, x0, x1) in [
        ("cloth_end_left", -hw - c, -hw),
        ("cloth_end_right", hw, hw + c),
    ] {
        b.cuboid(name, linen, [x0, top - drop, -hd - c], [x1, top, hd + c]);
    }
    let fw = uniform(rng, 0.4, 0.9) * w;
    let fdrop = uniform(rng, 0.3, 1.0) * (top - 0.1);
    b.cuboid(
        "frontal",
        frontal,
        [-0.5 * fw, top - fdrop, hd + c - 0.001],
        [0.5 * fw, top + c, hd + 2.0 * c],
    );
    b.top_surface("top", [-hw, -hd], [hw, hd], top + c, 0.06);
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// Lectern: width 0.45–0.6, height 1.12–1.25, depth 0.38–0.52; a reading desk sloping down
/// toward the reader (+Z) with a book ledge and a flat strip at its high back edge, on a
/// podium box with a shelf open to the reader, or on a column; a heavy base plate. The
/// audience sees its back (−Z).
pub(super) fn lectern(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let wood = mat_either(&mut b, 0.7, Palette::Wood, Palette::PaintedWood, rng);
    let (w, y_high, d) = uniform3(rng, [0.45, 0.6], [1.12, 1.25], [0.38, 0.5]);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let slope = uniform(rng, 0.25, 0.4);
    let flat = 0.09;
    let y_low = y_high - (d - flat) * slope.tan();
    let y_body = y_low - 0.04;
    let podium = coin(rng, 0.6);
    let (bw, bd) = if podium {
        (w - 0.04, d - 0.06)
    } else {
        (w * 0.85, d * 0.9)
    };
    b.cuboid(
        "base",
        wood,
        [-0.5 * bw, 0.0, -0.5 * bd],
        [0.5 * bw, 0.04, 0.5 * bd],
    );
    if podium {
        lectern_podium(&mut b, wood, [0.5 * bw - 0.02, y_body, 0.5 * bd - 0.02]);
    } else {
        b.part(square_post(
            "column",
            wood,
            [0.0, 0.0],
            0.11,
            0.039,
            y_body + 0.001,
        ));
    }
    let profile = [
        [-hd, y_body],
        [hd, y_body],
        [hd, y_low],
        [-hd + flat, y_high],
        [-hd, y_high],
    ];
    b.part(prism_x("desk", wood, &profile, -hw, hw));
    let lip = [
        [hd - 0.02, y_low - 0.01],
        [hd + 0.005, y_low - 0.01],
        [hd + 0.005, y_low + 0.03],
        [hd - 0.02, y_low + 0.03],
    ];
    b.part(prism_x("book_ledge", wood, &lip, -hw, hw));
    b.top_surface("top", [-hw, -hd], [hw, -hd + flat], y_high, 0.015);
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// The podium box under a lectern's desk: sides, a closed back toward the audience, and a
/// shelf open to the reader; `half` = (half width, height, half depth).
fn lectern_podium(b: &mut AssetBuilder, wood: usize, half: [f32; 3]) {
    let [hw, top, hd] = half;
    let t = 0.018;
    b.cuboid(
        "side_left",
        wood,
        [-hw, 0.039, -hd],
        [-hw + t, top + 0.001, hd],
    );
    b.cuboid(
        "side_right",
        wood,
        [hw - t, 0.039, -hd],
        [hw, top + 0.001, hd],
    );
    b.cuboid(
        "panel_back",
        wood,
        [-hw, 0.039, -hd],
        [hw, top + 0.001, -hd + t],
    );
    let shelf_y = top - 0.3;
    b.cuboid(
        "shelf",
        wood,
        [-hw + t - 0.001, shelf_y - t, -hd + t - 0.001],
        [hw - t + 0.001, shelf_y, hd],
    );
    b.surface(rect_surface(
        "shelf",
        SurfaceKind::Shelf,
        [-hw + t, -hd + t],
        [hw - t, hd],
        shelf_y,
        Some(top - shelf_y - 0.005),
        0.02,
    ));
}

// ---------------------------------------------------------------------------------------------
// Water cooler, photocopier.

/// Water cooler (bottled water dispenser): width 0.3–0.34, height 1.35–1.49 with its bottle,
/// depth 0.31–0.38 with its tap buttons; a cabinet on feet with a recessed dispensing bay on its
/// front (hot and cold taps over a drip tray), a collar on top holding an inverted 19-litre
/// bottle (0.27 across).
pub(super) fn water_cooler(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.7, Palette::Plastic, Palette::CoatedMetal, rng);
    let dark = fixed(&mut b, "bay_grey", [0x3A, 0x3C, 0x40], 0.6, 0.0);
    let (w, body_h, d) = uniform3(rng, [0.3, 0.34], [0.86, 0.96], [0.3, 0.36]);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let bay = [body_h - uniform(rng, 0.4, 0.45), body_h - 0.12];
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        let (x, z) = (sx * (hw - 0.03), sz * (hd - 0.03));
        b.cuboid(
            &format!("foot_{i}"),
            dark,
            [x - 0.02, 0.0, z - 0.02],
            [x + 0.02, 0.021, z + 0.02],
        );
    }
    cooler_cabinet(&mut b, [body, dark], [hw, body_h, hd], bay);
    water_bottle(&mut b, body_h, rng);
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// A cooler's cabinet of half width, height and half depth `size` from 0.02 up, with the
/// dispensing bay recessed into its front between the heights `bay`: two taps (red hot, blue
/// cold) over a drip tray, which is a shelf surface; `m` = (body, bay grey).
fn cooler_cabinet(b: &mut AssetBuilder, m: [usize; 2], size: [f32; 3], bay: [f32; 2]) {
    let ([body, dark], [hw, h, hd], [bay0, bay1]) = (m, size, bay);
    let back = hd - 0.09;
    b.cuboid("cabinet", body, [-hw, 0.02, -hd], [hw, h, back]);
    b.cuboid(
        "front_lower",
        body,
        [-hw, 0.02, back - 0.001],
        [hw, bay0, hd],
    );
    b.cuboid("front_upper", body, [-hw, bay1, back - 0.001], [hw, h, hd]);
    for (name, x0, x1) in [
        ("cheek_left", -hw, -hw + 0.04),
        ("cheek_right", hw - 0.04, hw),
    ] {
        b.cuboid(
            name,
            body,
            [x0, bay0 - 0.001, back - 0.001],
            [x1, bay1 + 0.001, hd],
        );
    }
    let (x0, x1) = (-hw + 0.04, hw - 0.04);
    b.cuboid(
        "drip_tray",
        dark,
        [x0, bay0 - 0.001, back],
        [x1, bay0 + 0.012, hd - 0.005],
    );
    let taps = [(-0.055f32, [0xC8, 0x22, 0x22]), (0.055, [0x22, 0x5A, 0xC8])];
    for (k, (x, colour)) in taps.into_iter().enumerate() {
        let m = fixed(b, &format!("tap_{k}"), colour, 0.4, 0.0);
        let (s0, s1) = (
            [x - 0.012, bay1 - 0.05, hd - 0.07],
            [x + 0.012, bay1 + 0.001, hd - 0.035],
        );
        b.cuboid(&format!("spout_{k}"), m, s0, s1);
        let (k0, k1) = (
            [x - 0.018, bay1 + 0.02, hd - 0.001],
            [x + 0.018, bay1 + 0.05, hd + 0.012],
        );
        b.cuboid(&format!("tap_button_{k}"), m, k0, k1);
    }
    b.surface(rect_surface(
        "drip_tray",
        SurfaceKind::Shelf,
        [x0, back],
        [x1, hd - 0.005],
        bay0 + 0.012,
        Some(bay1 - 0.05 - bay0 - 0.02),
        0.005,
    ));
}

/// The collar on a cooler's top at `top` and the inverted bottle in it.
fn water_bottle(b: &mut AssetBuilder, top: f32, rng: &mut ChaCha8Rng) {
    let collar = fixed(b, "collar", [0xE8, 0xE8, 0xE6], 0.5, 0.0);
    let water = translucent(
        b,
        "bottle_water",
        [0x6A, 0xA8, 0xD8],
        uniform(rng, 0.35, 0.55),
    );
    b.part(frustum(
        "collar",
        collar,
        [0.0, 0.0],
        0.12,
        0.1,
        top - 0.001,
        top + 0.05,
        20,
    ));
    let r = 0.135;
    let y0 = top + 0.02;
    let neck = y0 + 0.06;
    let shoulder = neck + 0.08;
    let body_top = shoulder + uniform(rng, 0.3, 0.34);
    b.part(cylinder(
        "bottle_neck",
        water,
        [0.0, 0.0],
        0.028,
        y0,
        neck + 0.001,
        14,
    ));
    b.part(frustum(
        "bottle_shoulder",
        water,
        [0.0, 0.0],
        0.028,
        r,
        neck,
        shoulder + 0.001,
        24,
    ));
    b.part(cylinder(
        "bottle_body",
        water,
        [0.0, 0.0],
        r,
        shoulder,
        body_top,
        24,
    ));
    b.part(frustum(
        "bottle_base",
        water,
        [0.0, 0.0],
        r,
        0.9 * r,
        body_top - 0.001,
        body_top + 0.025,
        24,
    ));
}

/// Photocopier (floor-standing multifunction copier): width 0.58–0.7, height 1.06–1.24, depth
/// 0.64–0.77 with its control panel (e.g. 0.59 × 1.16 × 0.68); 2–4 paper-tray drawers in a
/// cabinet on casters, a print engine with an inner output bay, a scanner under a
/// document-feeder lid hinged at its back, and a tilted control panel on the front.
pub(super) fn photocopier(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let shell = mat(&mut b, Palette::Plastic, rng);
    let dark = fixed(&mut b, "copier_grey", [0x3C, 0x3E, 0x42], 0.6, 0.0);
    let (w, base_h, d) = uniform3(rng, [0.58, 0.7], [0.5, 0.62], [0.6, 0.72]);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let trays = int(rng, 2, 4);
    let c = Carcass {
        width: w,
        height: base_h,
        depth: d,
        board: 0.015,
        feet: Feet::Casters { height: 0.07 },
        columns: 1,
        shelves: Carcass::even_shelves(trays),
        drawer_rows: trays,
        ..Carcass::PLAIN
    };
    carcass::build(
        &mut b,
        &c,
        CarcassMaterials::uniform(shell, dark),
        [0.0, 0.0],
        "",
    );
    b.surfaces_mut().retain(|s| s.name != "top");
    let engine = base_h + uniform(rng, 0.22, 0.28);
    let bay = engine + uniform(rng, 0.12, 0.15);
    let scan = bay + uniform(rng, 0.08, 0.1);
    b.cuboid(
        "engine",
        shell,
        [-hw, base_h - 0.001, -hd],
        [hw, engine, hd],
    );
    b.cuboid(
        "spine",
        shell,
        [hw - 0.12, engine - 0.001, -hd],
        [hw, bay + 0.001, hd],
    );
    b.cuboid(
        "bay_back",
        shell,
        [-hw, engine - 0.001, -hd],
        [hw - 0.12, bay + 0.001, -hd + 0.1],
    );
    b.cuboid(
        "output_tray",
        dark,
        [-hw + 0.03, engine - 0.001, -hd + 0.1],
        [hw - 0.13, engine + 0.008, hd - 0.03],
    );
    b.surface(rect_surface(
        "output_tray",
        SurfaceKind::Shelf,
        [-hw + 0.03, -hd + 0.1],
        [hw - 0.13, hd - 0.03],
        engine + 0.008,
        Some(bay - engine - 0.015),
        0.02,
    ));
    b.cuboid("scanner", shell, [-hw, bay, -hd], [hw, scan, hd]);
    copier_panel(&mut b, [hw, bay, hd], dark);
    copier_lid(&mut b, [hw, scan, hd], shell, dark);
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// The control panel tilted up on the front right under the scanner's front edge, `at` =
/// (half width, the scanner's underside, half depth).
fn copier_panel(b: &mut AssetBuilder, at: [f32; 3], dark: usize) {
    let [hw, y, hd] = at;
    let rot = rotation([1.0, 0.0, 0.0], -0.6);
    b.part(rotated_box(
        "control_panel",
        dark,
        [0.45 * hw, y + 0.035, hd + 0.005],
        [0.5 * hw, 0.012, 0.035],
        &rot,
    ));
}

/// The document feeder lid on the scanner, hinged at its back top edge, `at` = (half width,
/// the scanner's top, half depth).
fn copier_lid(b: &mut AssetBuilder, at: [f32; 3], shell: usize, dark: usize) {
    let [hw, y, hd] = at;
    let t = 0.04;
    b.joint(articulation::back_hinge("lid", y + t, -hd, 1.3));
    b.link(Some("lid"));
    b.cuboid("lid", shell, [-hw, y, -hd], [hw, y + t, hd]);
    b.cuboid(
        "feeder",
        shell,
        [-hw + 0.03, y + t - 0.001, -hd + 0.02],
        [hw - 0.03, y + t + 0.07, -hd + 0.26],
    );
    b.cuboid(
        "feeder_tray",
        dark,
        [-hw + 0.08, y + t - 0.001, -hd + 0.25],
        [hw - 0.08, y + t + 0.025, hd - 0.06],
    );
    b.link(None);
}

// ---------------------------------------------------------------------------------------------
// Safe, treasure chest.

/// Safe: width 0.35–0.6, height 0.35–1.0, depth 0.38–0.59 with its dial (a home safe is about
/// 0.45 × 0.6 × 0.45); thick steel walls on a low plinth, 1–3 shelves inside behind a door
/// hinged on its left edge with a combination dial, a spoked handle and a bar handle; a usable
/// top.
pub(super) fn safe(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat(&mut b, Palette::CoatedMetal, rng);
    let steel = mat(&mut b, Palette::Metal, rng);
    let (w, h, d) = uniform3(rng, [0.35, 0.6], [0.35, 1.0], [0.35, 0.55]);
    let rows = if h < 0.55 { 1 } else { int(rng, 2, 3) };
    let c = Carcass {
        width: w,
        height: h,
        depth: d - 0.045,
        board: uniform(rng, 0.035, 0.045),
        feet: Feet::Plinth {
            height: 0.015,
            recess: 0.01,
        },
        columns: 1,
        shelves: Carcass::even_shelves(rows),
        front: Front::Doors,
        ..Carcass::PLAIN
    };
    carcass::build(
        &mut b,
        &c,
        CarcassMaterials::uniform(body, steel),
        [0.0, 0.0],
        "",
    );
    let face = 0.5 * c.depth + c.board;
    safe_lock(&mut b, steel, [0.0, 0.55 * h, face]);
    b.finish(Placement::Floor, SCALE)
}

/// The combination dial and the spoked handle on the safe's door (its link), centred at
/// `at` = (x, y, the door's front face).
fn safe_lock(b: &mut AssetBuilder, steel: usize, at: [f32; 3]) {
    let [x, y, z] = at;
    b.link(Some("door_0"));
    b.part(rod(
        "dial",
        steel,
        [x, y + 0.06, z - 0.001],
        [x, y + 0.06, z + 0.02],
        0.035,
        0.03,
        24,
    ));
    b.part(rod(
        "hub",
        steel,
        [x, y - 0.06, z - 0.001],
        [x, y - 0.06, z + 0.03],
        0.02,
        0.02,
        12,
    ));
    for k in 0..3 {
        let a = PI * (0.5 + 2.0 * k as f32 / 3.0);
        let tip = [x + 0.07 * a.cos(), y - 0.06 + 0.07 * a.sin(), z + 0.03];
        b.part(rod(
            &format!("spoke_{k}"),
            steel,
            [x, y - 0.06, z + 0.025],
            tip,
            0.006,
            0.006,
            8,
        ));
    }
    b.link(None);
}

/// Treasure chest: width 0.6–1.0, height 0.47–0.7 with its domed lid, depth 0.4–0.55; a wooden
/// box on four feet bound with iron or brass bands, a lock plate, and a barrel-vaulted lid
/// hinged at its back; the inside is an open interior.
pub(super) fn treasure_chest(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let wood = mat(&mut b, Palette::Wood, rng);
    let bands = [[0x2E, 0x2C, 0x2A], [0xB0, 0x8A, 0x3C]];
    let metal = fixed(&mut b, "bands", *pick(rng, &bands), 0.45, 0.9);
    let (w, box_h, d) = uniform3(rng, [0.6, 1.0], [0.3, 0.45], [0.4, 0.55]);
    let (hw, hd, foot) = (0.5 * w, 0.5 * d, 0.03);
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        let (x, z) = (sx * (hw - 0.04), sz * (hd - 0.04));
        b.cuboid(
            &format!("foot_{i}"),
            metal,
            [x - 0.03, 0.0, z - 0.03],
            [x + 0.03, foot + 0.001, z + 0.03],
        );
    }
    super::storage::open_box(&mut b, wood, w, box_h, d, 0.02, foot, "inside");
    let top = foot + box_h;
    let straps = [-0.3 * w, 0.3 * w];
    for (k, x) in straps.into_iter().enumerate() {
        b.cuboid(
            &format!("band_front_{k}"),
            metal,
            [x - 0.025, foot, hd - 0.001],
            [x + 0.025, top, hd + 0.005],
        );
    }
    b.cuboid(
        "lock_plate",
        metal,
        [-0.045, top - 0.11, hd - 0.001],
        [0.045, top - 0.01, hd + 0.008],
    );
    chest_lid(
        &mut b,
        [hw, top, hd],
        uniform(rng, 0.12, 0.22).min(hd),
        [wood, metal],
    );
    b.finish(Placement::Floor, SCALE)
}

/// The chest's half-barrel lid of rise `dome` on the box top (`at` = half width, top, half
/// depth) with two bands and a hasp, hinged along its back bottom edge.
fn chest_lid(b: &mut AssetBuilder, at: [f32; 3], dome: f32, m: [usize; 2]) {
    let [hw, top, hd] = at;
    let [wood, metal] = m;
    let vault = |grow: f32| -> Vec<[f32; 2]> {
        (0..=12)
            .map(|k| {
                let a = PI * k as f32 / 12.0;
                [(hd + grow) * a.cos(), top + (dome + grow) * a.sin()]
            })
            .collect()
    };
    b.joint(articulation::back_hinge(
        "lid",
        top,
        -hd,
        articulation::DOOR_OPEN,
    ));
    b.link(Some("lid"));
    b.part(prism_x("lid", wood, &vault(0.0), -hw, hw));
    for (k, x) in [-0.3 * (2.0 * hw), 0.3 * (2.0 * hw)]
        .into_iter()
        .enumerate()
    {
        b.part(prism_x(
            &format!("lid_band_{k}"),
            metal,
            &vault(0.005),
            x - 0.025,
            x + 0.025,
        ));
    }
    b.cuboid(
        "hasp",
        metal,
        [-0.025, top - 0.07, hd + 0.004],
        [0.025, top + 0.03, hd + 0.012],
    );
    b.link(None);
}

// ---------------------------------------------------------------------------------------------
// Punching bag, bunk bed.

/// Punching bag on a free-standing frame: width 1.15–1.56 with its weight plates, height 2.1–2.4,
/// depth 1.2–1.6; an H-shaped floor base with weight plates at the back, an upright with braces,
/// a boom reaching forward and a heavy bag (0.3–0.38 across, 0.9–1.2 long) hanging on chains.
pub(super) fn punching_bag(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat(&mut b, Palette::CoatedMetal, rng);
    let leather = mat_either(&mut b, 0.6, Palette::Leather, Palette::Rubber, rng);
    let steel = mat(&mut b, Palette::Metal, rng);
    let (w, h, d) = uniform3(rng, [1.0, 1.4], [2.1, 2.4], [1.2, 1.6]);
    let post_z = -0.5 * d + 0.25;
    let bag_z = post_z + uniform(rng, 0.65, 0.85).min(d - 0.55);
    bag_frame(
        &mut b,
        [frame, steel],
        [0.5 * w, h, 0.5 * d],
        [post_z, bag_z],
    );
    let (r, len) = (uniform(rng, 0.15, 0.19), uniform(rng, 0.9, 1.2));
    let top = h - 0.1 - uniform(rng, 0.3, 0.45);
    heavy_bag(&mut b, [leather, steel], [bag_z, top, h], [r, len]);
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// A heavy-bag stand of half width, height and half depth `size`: two base rails, two cross
/// rails, an upright at `z`[0] with two braces, a boom reaching to `z`[1] (the bag's axis) and a
/// weight plate on a peg at each back corner; `m` = (frame, steel).
fn bag_frame(b: &mut AssetBuilder, m: [usize; 2], size: [f32; 3], z: [f32; 2]) {
    let ([frame, steel], [hw, h, hd], [post_z, bag_z]) = (m, size, z);
    let s = 0.06;
    for (i, x) in [-hw + 0.5 * s, hw - 0.5 * s].into_iter().enumerate() {
        b.cuboid(
            &format!("base_rail_{i}"),
            frame,
            [x - 0.5 * s, 0.0, -hd],
            [x + 0.5 * s, s, hd],
        );
        let peg = [x, -hd + 0.12];
        b.part(cylinder(
            &format!("plate_peg_{i}"),
            steel,
            peg,
            0.02,
            s - 0.001,
            s + 0.12,
            8,
        ));
        b.part(cylinder(
            &format!("plate_{i}"),
            frame,
            peg,
            0.11,
            s - 0.001,
            s + 0.05,
            20,
        ));
    }
    for (k, z) in [post_z, hd - 0.1].into_iter().enumerate() {
        b.cuboid(
            &format!("cross_rail_{k}"),
            frame,
            [-hw, 0.0, z - 0.5 * s],
            [hw, s, z + 0.5 * s],
        );
    }
    b.part(square_post(
        "upright",
        frame,
        [0.0, post_z],
        0.08,
        s - 0.001,
        h,
    ));
    for (k, x) in [-hw + s, hw - s].into_iter().enumerate() {
        let (foot, head) = ([x, s - 0.001, post_z], [0.0, 0.9, post_z]);
        b.part(strut(
            &format!("brace_{k}"),
            frame,
            foot,
            head,
            [0.04, 0.04],
        ));
    }
    b.cuboid(
        "boom",
        frame,
        [-0.04, h - 0.1, post_z],
        [0.04, h - 0.02, bag_z + 0.06],
    );
}

/// The bag of radius and length `size` with bevelled ends, its top at `at`[1] under the boom
/// (its underside at `at`[2] − 0.1), hanging from a swivel on three chains; `at`[0] is the
/// bag's z; `m` = (leather, steel).
fn heavy_bag(b: &mut AssetBuilder, m: [usize; 2], at: [f32; 3], size: [f32; 2]) {
    let ([leather, steel], [z, top, h], [r, len]) = (m, at, size);
    let bottom = (top - len).max(0.3);
    let c = [0.0, z];
    b.part(frustum(
        "bag_bottom",
        leather,
        c,
        0.85 * r,
        r,
        bottom,
        bottom + 0.04,
        20,
    ));
    b.part(cylinder(
        "bag",
        leather,
        c,
        r,
        bottom + 0.039,
        top - 0.039,
        20,
    ));
    b.part(frustum(
        "bag_top",
        leather,
        c,
        r,
        0.85 * r,
        top - 0.04,
        top,
        20,
    ));
    let swivel = [0.0, top + 0.18, z];
    b.part(rod(
        "swivel",
        steel,
        swivel,
        [0.0, h - 0.099, z],
        0.01,
        0.01,
        8,
    ));
    for k in 0..3 {
        let a = 2.0 * PI * k as f32 / 3.0;
        let foot = [0.7 * r * a.cos(), top - 0.01, z + 0.7 * r * a.sin()];
        b.part(rod(
            &format!("chain_{k}"),
            steel,
            foot,
            swivel,
            0.005,
            0.005,
            6,
        ));
    }
}

/// Section of a bunk bed's corner posts.
const BUNK_POST: f32 = 0.06;

/// Bunk bed: width 1.02–1.13 (single mattresses 0.9–1.0 wide) with its ladder, height 1.5–1.75,
/// length 2.0–2.1; four corner posts, two frames with mattresses (tops 0.39–0.48 and
/// 1.14–1.43 high), head and foot boards, guard boards around the upper bunk and a ladder on
/// its +X side near the foot (+Z); the −X side goes against a wall.
pub(super) fn bunk_bed(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat_either(&mut b, 0.65, Palette::Wood, Palette::CoatedMetal, rng);
    let sheet = mat_either(&mut b, 0.5, Palette::Paper, Palette::Fabric, rng);
    let pillow = fixed(&mut b, "pillow_white", [0xF2, 0xF0, 0xEA], 0.9, 0.0);
    let (mw, h, ml) = uniform3(rng, [0.9, 1.0], [1.5, 1.75], [1.9, 2.0]);
    let p = BUNK_POST;
    let (hw, hl) = (0.5 * mw + 0.05, 0.5 * ml + 0.05);
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        let at = [sx * (hw - 0.5 * p), sz * (hl - 0.5 * p)];
        b.part(square_post(&format!("post_{i}"), frame, at, p, 0.0, h));
    }
    let lower = uniform(rng, 0.15, 0.2);
    let upper = h - uniform(rng, 0.55, 0.6);
    let mattress = uniform(rng, 0.14, 0.18);
    let (low_top, up_top) = (lower + 0.1 + mattress, upper + 0.1 + mattress);
    let m = [frame, sheet, pillow];
    bunk_tier(&mut b, "lower", [hw - p, lower, hl - p], mattress, m);
    bunk_tier(&mut b, "upper", [hw - p, upper, hl - p], mattress, m);
    for (name, z) in [("head", -hl + 0.5 * p), ("foot", hl - 0.5 * p)] {
        let (z0, z1) = (z - 0.012, z + 0.012);
        b.cuboid(
            &format!("{name}board_upper"),
            frame,
            [-hw + p, upper, z0],
            [hw - p, h - 0.04, z1],
        );
        b.cuboid(
            &format!("{name}board_lower"),
            frame,
            [-hw + p, lower, z0],
            [hw - p, low_top + 0.15, z1],
        );
    }
    bunk_guards(&mut b, frame, [hw, upper, hl], up_top);
    bunk_ladder(&mut b, frame, [hw, upper, hl], up_top);
    let (x0, x1) = (-hw + p, hw - p);
    let (z0, z1) = (-hl + p + 0.5, hl - p);
    let clear = upper - low_top - 0.005;
    b.surface(rect_surface(
        "mattress_lower",
        SurfaceKind::Shelf,
        [x0, z0],
        [x1, z1],
        low_top,
        Some(clear),
        0.05,
    ));
    b.top_surface("mattress_upper", [x0, z0], [x1, z1], up_top, 0.05);
    b.finish(Placement::Floor, SCALE)
}

/// One bunk between the posts: two side rails 0.1 high from `at`[1], a deck, the mattress
/// `mattress` thick and a pillow at the head (−Z); `at` = (half inner width, rail bottom, half
/// inner length).
fn bunk_tier(b: &mut AssetBuilder, tier: &str, at: [f32; 3], mattress: f32, m: [usize; 3]) {
    let [hw, y, hl] = at;
    let [frame, sheet, pillow] = m;
    let top = y + 0.1;
    for (k, x) in [-hw - 0.03, hw + 0.03].into_iter().enumerate() {
        b.cuboid(
            &format!("{tier}_side_rail_{k}"),
            frame,
            [x - 0.02, y, -hl - 0.001],
            [x + 0.02, top, hl + 0.001],
        );
    }
    b.cuboid(
        &format!("{tier}_deck"),
        frame,
        [-hw - 0.011, top - 0.03, -hl],
        [hw + 0.011, top, hl],
    );
    let (mx, mz) = (hw - 0.005, hl - 0.005);
    b.cuboid(
        &format!("{tier}_mattress"),
        sheet,
        [-mx, top - 0.001, -mz],
        [mx, top + mattress, mz],
    );
    let centre = [0.0, top + mattress + 0.04, -hl + 0.25];
    b.part(ellipsoid(
        &format!("{tier}_pillow"),
        pillow,
        centre,
        [0.3, 0.06, 0.16],
        8,
        14,
    ));
}

/// Where a bunk bed's ladder leaves the +X guard open: the z of its two stiles.
fn ladder_z(hl: f32) -> [f32; 2] {
    let z1 = hl - BUNK_POST - 0.03;
    [z1 - 0.38, z1]
}

/// Guard boards around the upper mattress (top `up_top`): the whole −X side, the +X side up to
/// the ladder; `at` = (half width, the upper rails' bottom, half length).
fn bunk_guards(b: &mut AssetBuilder, frame: usize, at: [f32; 3], up_top: f32) {
    let [hw, upper, hl] = at;
    let (y0, y1) = (up_top + 0.08, up_top + 0.2);
    let x = hw - 0.5 * BUNK_POST;
    let z0 = -hl + BUNK_POST;
    b.cuboid(
        "guard_left",
        frame,
        [-x - 0.012, y0, z0 - 0.001],
        [-x + 0.012, y1, hl - BUNK_POST + 0.001],
    );
    let open = ladder_z(hl)[0] - 0.03;
    b.cuboid(
        "guard_right",
        frame,
        [x - 0.012, y0, z0 - 0.001],
        [x + 0.012, y1, open],
    );
    b.cuboid(
        "guard_post",
        frame,
        [x - 0.02, upper + 0.099, open - 0.04],
        [x + 0.02, y1, open],
    );
}

/// The ladder on the +X side near the foot: two stiles from the floor to above the upper
/// mattress and rungs up to the upper bunk; `at` as for [`bunk_guards`].
fn bunk_ladder(b: &mut AssetBuilder, frame: usize, at: [f32; 3], up_top: f32) {
    let [hw, upper, hl] = at;
    let x = hw + 0.008;
    let zs = ladder_z(hl);
    for (k, z) in zs.into_iter().enumerate() {
        b.cuboid(
            &format!("ladder_stile_{k}"),
            frame,
            [x - 0.02, 0.0, z - 0.02],
            [x + 0.02, up_top + 0.2, z + 0.02],
        );
    }
    let rungs = ((upper + 0.05) / 0.28).round().max(2.0) as usize;
    for k in 0..rungs {
        let y = (k as f32 + 1.0) * (upper + 0.05) / (rungs as f32 + 0.3);
        b.part(rod(
            &format!("ladder_rung_{k}"),
            frame,
            [x, y, zs[0] + 0.019],
            [x, y, zs[1] - 0.019],
            0.015,
            0.015,
            10,
        ));
    }
}
