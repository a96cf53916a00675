//! Care, nursery, salon and clothing furniture: crib, changing table, rocking chair, high chair,
//! clothes rack, mannequin, examination table, dental chair, massage table, barber chair and
//! ironing board. Fronts face +Z; couches and boards whose length runs across the front
//! (examination and massage tables, the ironing board) have their length along X.

use rand_chacha::ChaCha8Rng;

use super::carcass::{self, Carcass, CarcassMaterials, Feet, CORNERS};
use super::{mat, mat_either, SCALE};
use crate::materials::{fixed_material, Palette};
use crate::random::{coin, int, pick, uniform};
use scenethesis_primitives::{
    beam, convex_hull, cylinder, ellipsoid, frustum, prism_x, prism_y, rect_surface, rod,
    rotated_box, rotation, rounded_box, sphere, square_post, strut, tube, AssetBuilder,
};
use scenethesis_scene_graph::{Asset, Placement, SurfaceKind};

/// Clear gap between crib slats, under the 6 cm that safety standards allow.
const SLAT_GAP: f32 = 0.055;

/// Crib (baby cot): width 1.3–1.47, height 0.85–1.0, depth 0.7–0.84, around a 1.2 × 0.6 m
/// (European) or 1.33 × 0.7 m (US) mattress; four corner posts, top and bottom rails with vertical
/// slats under 6 cm apart on all four sides (or solid end boards), and a mattress on a base at
/// 0.2–0.42 whose top is the `mattress` interior surface.
pub(super) fn crib(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let wood = mat_either(&mut b, 0.55, Palette::Wood, Palette::PaintedWood, rng);
    let sheet = mat_either(&mut b, 0.6, Palette::Paper, Palette::Fabric, rng);
    let (mw, md) = *pick(rng, &[(1.2f32, 0.6f32), (1.33, 0.7)]);
    let post = uniform(rng, 0.04, 0.055);
    let (hw, hd) = (0.5 * mw + post + 0.012, 0.5 * md + post + 0.012);
    let h = uniform(rng, 0.85, 1.0);
    let base = uniform(rng, 0.2, 0.42);
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        let c = [sx * (hw - 0.5 * post), sz * (hd - 0.5 * post)];
        b.part(square_post(&format!("post_{i}"), wood, c, post, 0.0, h));
    }
    let rails = [base - 0.06, h];
    let (xi, zi) = (hw - post + 0.002, hd - post + 0.002);
    for (name, z) in [("back", -hd + 0.5 * post), ("front", hd - 0.5 * post)] {
        slatted_side(&mut b, wood, name, [-xi, xi], z, rails, false);
    }
    let boards = coin(rng, 0.35);
    for (name, x) in [("left", -hw + 0.5 * post), ("right", hw - 0.5 * post)] {
        if boards {
            b.cuboid(
                name,
                wood,
                [x - 0.01, rails[0], -zi],
                [x + 0.01, h - 0.02, zi],
            );
        } else {
            slatted_side(&mut b, wood, name, [-zi, zi], x, rails, true);
        }
    }
    b.cuboid("base", wood, [-xi, base - 0.03, -zi], [xi, base, zi]);
    let top = base + uniform(rng, 0.08, 0.12);
    let (mx, mz) = (0.5 * mw, 0.5 * md);
    b.part(rounded_box(
        "mattress",
        sheet,
        [0.0, 0.5 * (base + top) - 0.001, 0.0],
        [mx, 0.5 * (top - base) + 0.001, mz],
        0.2,
    ));
    b.surface(rect_surface(
        "mattress",
        SurfaceKind::Interior,
        [-mx, -mz],
        [mx, mz],
        top,
        None,
        0.08,
    ));
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// Adds one slatted side of a crib between its posts: a bottom and a top rail at `rails` (the
/// bottom rail's underside, the top rail's top) over `span`, and vertical slats between them,
/// running along X at depth `at`, or along Z at x = `at` when `along_z`.
fn slatted_side(
    b: &mut AssetBuilder,
    m: usize,
    name: &str,
    span: [f32; 2],
    at: f32,
    rails: [f32; 2],
    along_z: bool,
) {
    let put = |b: &mut AssetBuilder, part: &str, u: [f32; 2], y: [f32; 2], half: f32| {
        if along_z {
            b.cuboid(part, m, [at - half, y[0], u[0]], [at + half, y[1], u[1]]);
        } else {
            b.cuboid(part, m, [u[0], y[0], at - half], [u[1], y[1], at + half]);
        }
    };
    let rail = 0.045;
    let (y0, y1) = (rails[0], rails[1]);
    put(
        b,
        &format!("{name}_rail_bottom"),
        span,
        [y0, y0 + rail],
        0.013,
    );
    put(b, &format!("{name}_rail_top"), span, [y1 - rail, y1], 0.016);
    let slat = 0.024;
    let n = ((span[1] - span[0] - SLAT_GAP) / (slat + SLAT_GAP)).ceil() as usize;
    let pitch = (span[1] - span[0]) / (n as f32 + 1.0);
    for k in 1..=n {
        let u = span[0] + k as f32 * pitch;
        put(
            b,
            &format!("{name}_slat_{k}"),
            [u - 0.5 * slat, u + 0.5 * slat],
            [y0 + rail - 0.002, y1 - rail + 0.002],
            0.009,
        );
    }
}

/// Changing table: width 0.8–1.0, height 0.93–1.06 (the guard rails), depth 0.53–0.63; a carcass
/// 0.85–0.92 high on legs or a plinth with two or three drawers (or one drawer under two open
/// shelves), and on top a padded changing mat between guard rails at the back and sides (its top
/// the `pad` surface).
pub(super) fn changing_table(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.6, Palette::PaintedWood, Palette::Wood, rng);
    let handle = mat(&mut b, Palette::Metal, rng);
    let pad = mat_either(&mut b, 0.5, Palette::Plastic, Palette::Fabric, rng);
    let (w, d) = (uniform(rng, 0.8, 1.0), uniform(rng, 0.5, 0.6));
    let h = uniform(rng, 0.85, 0.92);
    let (rows, drawer_rows) = if coin(rng, 0.7) {
        let rows = int(rng, 2, 3);
        (rows, rows)
    } else {
        (3, 1)
    };
    let feet = if coin(rng, 0.5) {
        Feet::Legs {
            height: uniform(rng, 0.08, 0.14),
            section: 0.04,
        }
    } else {
        Feet::Plinth {
            height: 0.07,
            recess: 0.03,
        }
    };
    let c = Carcass {
        width: w,
        height: h,
        depth: d,
        board: 0.018,
        feet,
        columns: 1,
        shelves: Carcass::even_shelves(rows),
        drawer_rows,
        ..Carcass::PLAIN
    };
    carcass::build(
        &mut b,
        &c,
        CarcassMaterials::uniform(body, handle),
        [0.0, 0.0],
        "",
    );
    b.surfaces_mut().retain(|s| s.name != "top");
    changing_pad(&mut b, [body, pad], w, d, h, rng);
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// The changing mat on a changing table's top at `h`: guard rails at the back and both sides
/// (material `m[0]`), a padded mat between them (`m[1]`) and its `pad` surface.
fn changing_pad(b: &mut AssetBuilder, m: [usize; 2], w: f32, d: f32, h: f32, rng: &mut ChaCha8Rng) {
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let rail = uniform(rng, 0.08, 0.14);
    let t = 0.018;
    b.cuboid(
        "rail_back",
        m[0],
        [-hw, h - 0.001, -hd],
        [hw, h + rail, -hd + t],
    );
    for (name, x) in [("rail_left", -hw), ("rail_right", hw - t)] {
        b.cuboid(name, m[0], [x, h - 0.001, -hd], [x + t, h + rail, hd]);
    }
    let pad_t = uniform(rng, 0.05, 0.07);
    let (px, pz) = (hw - t - 0.005, 0.5 * (d - t) - 0.01);
    let cz = -hd + t + 0.005 + pz;
    b.part(rounded_box(
        "mat",
        m[1],
        [0.0, h + 0.5 * pad_t - 0.001, cz],
        [px, 0.5 * pad_t + 0.001, pz],
        0.3,
    ));
    b.top_surface("pad", [-px, cz - pz], [px, cz + pz], h + pad_t, 0.08);
}

/// Rocking chair: width 0.51–0.59, height 0.95–1.12, depth 0.83–0.97 (the runners); a wooden seat
/// 0.4–0.46 high on four legs standing on two curved runners (flat under the middle, so that it
/// rests still), a back of 5–7 spindles leaning back under a top rail, and two arms.
pub(super) fn rocking_chair(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let wood = mat_either(&mut b, 0.7, Palette::Wood, Palette::PaintedWood, rng);
    let (sw, sd) = (uniform(rng, 0.44, 0.52), uniform(rng, 0.4, 0.46));
    let seat = uniform(rng, 0.4, 0.46);
    let hl = 0.5 * uniform(rng, 0.82, 0.96);
    let x = 0.5 * sw - 0.02;
    let runner = |z: f32| {
        let off = ((z + 0.03).abs() - 0.17).max(0.0);
        0.09 * (off / (hl - 0.14)).powi(2)
    };
    for (k, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let zs = [-hl, -0.72 * hl, -0.2, 0.14, 0.66 * hl, hl];
        for (i, w) in zs.windows(2).enumerate() {
            let p = |z: f32| [sx * x, 0.0175 + runner(z), z];
            b.part(beam(
                &format!("runner_{k}_{i}"),
                wood,
                p(w[0]),
                p(w[1]),
                [0.035, 0.035],
            ));
        }
    }
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        let z = sz * (0.5 * sd - 0.03);
        let c = [sx * x, z];
        let y0 = runner(z) + 0.02;
        b.part(square_post(
            &format!("leg_{i}"),
            wood,
            c,
            0.035,
            y0,
            seat - 0.02,
        ));
    }
    b.cuboid(
        "seat",
        wood,
        [-0.5 * sw, seat - 0.03, -0.5 * sd],
        [0.5 * sw, seat, 0.5 * sd],
    );
    rocking_chair_back(&mut b, wood, [sw, sd, seat], rng);
    b.top_surface(
        "seat",
        [-0.5 * sw + 0.05, -0.5 * sd + 0.05],
        [0.5 * sw - 0.05, 0.5 * sd],
        seat,
        0.03,
    );
    b.finish(Placement::Floor, SCALE)
}

/// A rocking chair's back and arms over the seat `s` = (width, depth, height): two back posts
/// leaning back, a top rail, spindles between seat and rail, and arms on front posts.
fn rocking_chair_back(b: &mut AssetBuilder, wood: usize, s: [f32; 3], rng: &mut ChaCha8Rng) {
    let [sw, sd, seat] = s;
    let h = uniform(rng, 0.95, 1.12);
    let lean = uniform(rng, 0.12, 0.18);
    let (x, z0) = (0.5 * sw - 0.02, -0.5 * sd + 0.02);
    let zt = z0 - lean;
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        b.part(beam(
            &format!("back_post_{i}"),
            wood,
            [sx * x, seat - 0.03, z0],
            [sx * x, h - 0.02, zt],
            [0.035, 0.035],
        ));
    }
    b.cuboid(
        "top_rail",
        wood,
        [-0.5 * sw, h - 0.08, zt - 0.018],
        [0.5 * sw, h, zt + 0.018],
    );
    let n = int(rng, 5, 7);
    for k in 0..n {
        let sx = -x + 2.0 * x * (k as f32 + 1.0) / (n as f32 + 1.0);
        b.part(beam(
            &format!("spindle_{k}"),
            wood,
            [sx, seat - 0.005, z0],
            [sx, h - 0.07, zt],
            [0.018, 0.018],
        ));
    }
    let arm = seat + uniform(rng, 0.2, 0.24);
    let za = z0 - lean * (arm - seat) / (h - seat);
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let ax = sx * (0.5 * sw + 0.005);
        b.cuboid(
            &format!("arm_{i}"),
            wood,
            [ax - 0.03, arm, za - 0.02],
            [ax + 0.03, arm + 0.025, 0.5 * sd + 0.04],
        );
        b.part(square_post(
            &format!("arm_post_{i}"),
            wood,
            [ax, 0.5 * sd - 0.02],
            0.03,
            seat - 0.02,
            arm + 0.002,
        ));
    }
}

/// High chair: width 0.49–0.62, height 0.93–1.07, depth 0.58–0.71; a child's seat 0.55–0.62 high
/// with a back and armrest sides on four splayed legs joined by a footrest, and a tray with a rim
/// resting on the armrests in front (its top the `tray` surface).
pub(super) fn high_chair(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat_either(&mut b, 0.5, Palette::Wood, Palette::CoatedMetal, rng);
    let shell = mat_either(
        &mut b,
        0.6,
        Palette::BrightPlastic,
        Palette::PaintedWood,
        rng,
    );
    let (sw, sd) = (uniform(rng, 0.34, 0.4), uniform(rng, 0.3, 0.34));
    let seat = uniform(rng, 0.55, 0.62);
    let (bx, bz) = (uniform(rng, 0.25, 0.31), uniform(rng, 0.27, 0.32));
    let (tx, tz) = (0.5 * sw - 0.03, 0.5 * sd - 0.03);
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        b.part(strut(
            &format!("leg_{i}"),
            frame,
            [sx * (bx - 0.02), 0.0, sz * (bz - 0.02)],
            [sx * tx, seat - 0.03, sz * tz],
            [0.032, 0.032],
        ));
    }
    let fy = seat - uniform(rng, 0.24, 0.3);
    let f = fy / (seat - 0.03);
    let (fx, fz) = (
        bx - 0.02 + (tx - bx + 0.02) * f,
        bz - 0.02 + (tz - bz + 0.02) * f,
    );
    b.cuboid(
        "footrest",
        frame,
        [-fx, fy - 0.02, fz - 0.04],
        [fx, fy, fz + 0.03],
    );
    b.cuboid(
        "seat",
        shell,
        [-0.5 * sw, seat - 0.04, -0.5 * sd],
        [0.5 * sw, seat, 0.5 * sd],
    );
    let back = seat + uniform(rng, 0.38, 0.45);
    b.cuboid(
        "back",
        shell,
        [-0.5 * sw, seat - 0.01, -0.5 * sd],
        [0.5 * sw, back, -0.5 * sd + 0.03],
    );
    let tray_y = seat + uniform(rng, 0.18, 0.22);
    for (name, x) in [("side_left", -0.5 * sw), ("side_right", 0.5 * sw - 0.025)] {
        b.cuboid(
            name,
            shell,
            [x, seat - 0.01, -0.5 * sd],
            [x + 0.025, tray_y, 0.5 * sd],
        );
    }
    high_chair_tray(&mut b, shell, [0.5 * sw + 0.05, 0.5 * sd, tray_y], rng);
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// A high chair's tray resting on its armrests at `t` = (half width, seat front z, height): a board
/// reaching forward, a rim on its front and sides, and the `tray` surface.
fn high_chair_tray(b: &mut AssetBuilder, m: usize, t: [f32; 3], rng: &mut ChaCha8Rng) {
    let [hw, z0, y] = t;
    let z1 = z0 + uniform(rng, 0.16, 0.22);
    let (zb, rim, th) = (z0 - 0.08, 0.012, 0.02);
    b.cuboid("tray", m, [-hw, y, zb], [hw, y + th, z1]);
    b.cuboid(
        "tray_rim_front",
        m,
        [-hw, y + th - 0.001, z1 - rim],
        [hw, y + th + 0.025, z1],
    );
    for (name, x) in [("tray_rim_left", -hw), ("tray_rim_right", hw - rim)] {
        b.cuboid(
            name,
            m,
            [x, y + th - 0.001, z0],
            [x + rim, y + th + 0.025, z1],
        );
    }
    b.top_surface("tray", [-hw + rim, z0], [hw - rim, z1 - rim], y + th, 0.02);
}

/// Clothes rack (rolling garment rail): width 1.0–1.6, height 1.5–1.8, depth 0.45–0.6; two uprights
/// on caster feet joined by a base bar and a top rail, with 3–8 garments hanging across the rail (a
/// hook, a shoulder bar and a flat cloth shape each).
pub(super) fn clothes_rack(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let metal = mat(&mut b, Palette::Metal, rng);
    let wheel = mat(&mut b, Palette::Rubber, rng);
    let (w, h, d) = (
        uniform(rng, 1.0, 1.6),
        uniform(rng, 1.5, 1.8),
        uniform(rng, 0.45, 0.6),
    );
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let foot = 0.1;
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * (hw - 0.02);
        b.cuboid(
            &format!("foot_{i}"),
            metal,
            [x - 0.02, foot - 0.03, -hd],
            [x + 0.02, foot, hd],
        );
        b.part(cylinder(
            &format!("upright_{i}"),
            metal,
            [x, 0.0],
            0.014,
            foot - 0.01,
            h,
            10,
        ));
        for (k, sz) in [-1.0f32, 1.0].into_iter().enumerate() {
            let z = sz * (hd - 0.035);
            b.part(ellipsoid(
                &format!("wheel_{i}_{k}"),
                wheel,
                [x, 0.03, z],
                [0.012, 0.03, 0.03],
                6,
                10,
            ));
            b.part(cylinder(
                &format!("caster_{i}_{k}"),
                metal,
                [x, z],
                0.01,
                0.05,
                foot - 0.02,
                8,
            ));
        }
    }
    b.part(rod(
        "base_bar",
        metal,
        [-hw + 0.02, foot - 0.015, 0.0],
        [hw - 0.02, foot - 0.015, 0.0],
        0.013,
        0.013,
        10,
    ));
    b.part(rod(
        "rail",
        metal,
        [-hw + 0.005, h - 0.014, 0.0],
        [hw - 0.005, h - 0.014, 0.0],
        0.014,
        0.014,
        10,
    ));
    let n = int(rng, 3, 8);
    let span = w - 0.3;
    for k in 0..n {
        let x = -0.5 * span + span * (k as f32 + 0.5) / n as f32 + uniform(rng, -0.02, 0.02);
        garment(
            &mut b,
            &format!("garment_{k}"),
            x,
            [h - 0.014, d, foot],
            rng,
        );
    }
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// A garment on a hanger at x on a rail at `r` = (rail height, rack depth, base bar height): a hook
/// over the rail, a shoulder bar across Z and a flat cloth shape with sloping shoulders, 0.5–1.1
/// long but clear of the base bar.
fn garment(b: &mut AssetBuilder, name: &str, x: f32, r: [f32; 3], rng: &mut ChaCha8Rng) {
    let [rail, depth, base] = r;
    let cloth = mat(b, Palette::Fabric, rng);
    let wire = b.material(fixed_material("hanger", [0x3A, 0x2E, 0x26], 0.5, 0.0));
    let hook = [
        [x, rail - 0.06, 0.0],
        [x, rail + 0.005, 0.024],
        [x, rail + 0.025, 0.0],
        [x, rail + 0.005, -0.024],
    ];
    for (k, pair) in hook.windows(2).enumerate() {
        b.part(tube(
            &format!("{name}_hook_{k}"),
            wire,
            pair[0],
            pair[1],
            0.003,
            0.003,
            6,
        ));
    }
    let gw = uniform(rng, 0.36, (depth - 0.04).min(0.46));
    let top = rail - 0.1;
    b.cuboid(
        &format!("{name}_hanger"),
        wire,
        [x - 0.007, top - 0.015, -0.5 * gw],
        [x + 0.007, rail - 0.055, 0.5 * gw],
    );
    let bottom = (top - uniform(rng, 0.5, 1.1)).max(base + 0.1);
    let t = 0.5 * uniform(rng, 0.015, 0.03);
    let g = 0.5 * gw;
    let profile = [
        [-g, bottom],
        [g, bottom],
        [g + 0.01, top - 0.08],
        [0.3 * g, top],
        [-0.3 * g, top],
        [-g - 0.01, top - 0.08],
    ];
    b.part(prism_x(
        &format!("{name}_cloth"),
        cloth,
        &profile,
        x - t,
        x + t,
    ));
}

/// Mannequin (dress form): width 0.32–0.4, height 1.36–1.68, depth 0.29–0.4; a torso of convex
/// bands (hips, waist, bust toward +Z, shoulders), a neck with a cap and knob, on a pole over a
/// weighted round base or a three-legged tripod.
pub(super) fn mannequin(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let cover = mat_either(&mut b, 0.6, Palette::Fabric, Palette::Plastic, rng);
    let stand = mat_either(&mut b, 0.5, Palette::Wood, Palette::Metal, rng);
    let s = uniform(rng, 0.88, 1.08);
    let y0 = uniform(rng, 0.72, 0.9);
    let r = uniform(rng, 0.16, 0.2);
    if coin(rng, 0.5) {
        b.part(frustum(
            "base",
            stand,
            [0.0, 0.0],
            r,
            r - 0.02,
            0.0,
            0.04,
            24,
        ));
    } else {
        for k in 0..3 {
            let a = std::f32::consts::TAU * (k as f32 / 3.0 + 0.25);
            let foot = [r * a.cos(), 0.0, r * a.sin()];
            let top = [0.0, 0.28, 0.0];
            b.part(strut(&format!("leg_{k}"), stand, foot, top, [0.03, 0.03]));
        }
    }
    b.part(cylinder(
        "pole",
        stand,
        [0.0, 0.0],
        0.014,
        0.02,
        y0 + 0.1,
        10,
    ));
    torso(&mut b, cover, y0, s);
    let neck = y0 + 0.58 * s;
    b.part(cylinder(
        "neck",
        cover,
        [0.0, 0.0],
        0.05 * s,
        neck - 0.03,
        neck + 0.1 * s,
        16,
    ));
    b.part(frustum(
        "neck_cap",
        stand,
        [0.0, 0.0],
        0.052 * s,
        0.04 * s,
        neck + 0.1 * s - 0.002,
        neck + 0.12 * s,
        16,
    ));
    b.part(sphere(
        "knob",
        stand,
        [0.0, neck + 0.13 * s, 0.0],
        0.018,
        6,
        10,
    ));
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// The horizontal sections of a dress form's torso, bottom up: height above the torso's underside,
/// half width, half depth and forward offset (metres, before scaling): the hip line, the widest
/// hip, the waist, the bust, the shoulders and the shoulder top around the neck.
const TORSO: [[f32; 4]; 6] = [
    [0.0, 0.13, 0.1, 0.0],
    [0.1, 0.17, 0.13, 0.0],
    [0.27, 0.13, 0.1, 0.0],
    [0.42, 0.16, 0.12, 0.015],
    [0.52, 0.18, 0.1, 0.0],
    [0.59, 0.07, 0.055, 0.0],
];

/// A dress form's torso from `y0` up, scaled by `s`: one convex band between each pair of
/// neighbouring [`TORSO`] sections, and the bust.
fn torso(b: &mut AssetBuilder, m: usize, y0: f32, s: f32) {
    let ring = |[y, rx, rz, dz]: [f32; 4]| -> Vec<[f32; 3]> {
        (0..20)
            .map(|k| {
                let a = std::f32::consts::TAU * k as f32 / 20.0;
                [rx * s * a.cos(), y0 + y * s, (dz + rz * a.sin()) * s]
            })
            .collect()
    };
    for (k, pair) in TORSO.windows(2).enumerate() {
        let mut points = ring(pair[0]);
        points.extend(ring(pair[1]));
        let band = convex_hull(&format!("torso_{k}"), m, &points).expect("a torso band has volume");
        b.part(band);
    }
    for (name, x) in [("bust_left", -0.07f32), ("bust_right", 0.07)] {
        let c = [x * s, y0 + 0.41 * s, 0.08 * s];
        b.part(ellipsoid(
            name,
            m,
            c,
            [0.06 * s, 0.055 * s, 0.05 * s],
            8,
            14,
        ));
    }
}

/// Examination table (couch): width 1.79–1.94 (with the paper roll), height 0.87–1.17 (the raised
/// head section), depth 0.65–0.75 (with the handles); a cabinet base 0.6–0.7 high of two or three
/// drawer columns in two or three rows, a padded top with its `pad` surface, a head section raised
/// 20–40° at −X on a strut, and a paper roll at the head end.
pub(super) fn exam_table(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.6, Palette::Plastic, Palette::PaintedWood, rng);
    let handle = mat(&mut b, Palette::Metal, rng);
    let pad = mat_either(&mut b, 0.6, Palette::Leather, Palette::Plastic, rng);
    let paper = b.material(fixed_material("paper_roll", [0xF4, 0xF3, 0xEE], 0.9, 0.0));
    let (w, d, h) = (
        uniform(rng, 1.7, 1.85),
        uniform(rng, 0.62, 0.72),
        uniform(rng, 0.6, 0.7),
    );
    let rows = int(rng, 2, 3);
    let c = Carcass {
        width: w,
        height: h,
        depth: d,
        board: 0.018,
        feet: Feet::Plinth {
            height: 0.06,
            recess: 0.03,
        },
        columns: int(rng, 2, 3),
        shelves: Carcass::even_shelves(rows),
        drawer_rows: rows,
        ..Carcass::PLAIN
    };
    carcass::build(
        &mut b,
        &c,
        CarcassMaterials::uniform(body, handle),
        [0.0, 0.0],
        "",
    );
    b.surfaces_mut().retain(|s| s.name != "top");
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let head = uniform(rng, 0.55, 0.7);
    let xh = -hw + head;
    let t = 0.07;
    b.part(rounded_box(
        "pad",
        pad,
        [0.5 * (xh + hw), h + 0.5 * t - 0.001, 0.0],
        [0.5 * (hw - xh), 0.5 * t + 0.001, hd - 0.01],
        0.25,
    ));
    let a = uniform(rng, 0.35, 0.7);
    let rot = rotation([0.0, 0.0, 1.0], -a);
    let hinge = nalgebra::Vector3::new(xh - 0.005, h + 0.5 * t, 0.0);
    let centre = hinge + rot * nalgebra::Vector3::new(-0.5 * head + 0.005, 0.0, 0.0);
    b.part(rotated_box(
        "head_section",
        pad,
        centre.into(),
        [0.5 * head - 0.005, 0.5 * t, hd - 0.01],
        &rot,
    ));
    let under = hinge + rot * nalgebra::Vector3::new(-0.6 * head, -0.5 * t, 0.0);
    b.part(beam(
        "head_strut",
        handle,
        [under.x, h - 0.005, 0.0],
        [under.x, under.y + 0.01, 0.0],
        [0.04, 0.04],
    ));
    b.part(rod(
        "paper_roll",
        paper,
        [-hw - 0.045, h - 0.06, -hd + 0.06],
        [-hw - 0.045, h - 0.06, hd - 0.06],
        0.045,
        0.045,
        16,
    ));
    for (i, z) in [-hd + 0.04, hd - 0.06].into_iter().enumerate() {
        b.cuboid(
            &format!("roll_bracket_{i}"),
            handle,
            [-hw - 0.06, h - 0.08, z],
            [-hw + 0.001, h - 0.04, z + 0.02],
        );
    }
    b.top_surface("pad", [xh + 0.02, -hd], [hw, hd], h + t, 0.06);
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// A box of half extents `half` whose local +Y runs from `start` in the y–z plane at `angle`
/// radians from +Y toward +Z (negative leans back toward −Z), `half[1]` long on each side of its
/// centre: reclined backrests, leg rests and head sections.
fn slanted_box(
    name: &str,
    m: usize,
    start: [f32; 3],
    angle: f32,
    half: [f32; 3],
) -> scenethesis_scene_graph::MeshPart {
    let rot = rotation([1.0, 0.0, 0.0], angle);
    let c = nalgebra::Vector3::from(start) + rot * nalgebra::Vector3::new(0.0, half[1], 0.0);
    rotated_box(name, m, c.into(), half, &rot)
}

/// Dental chair: width 0.75–0.85 (with the lamp post), height 1.55–1.8 (the lamp), depth 1.66–1.85
/// reclined; a floor plate and lift column under an upholstered seat 0.55–0.65 high (the `seat`
/// surface), a backrest reclined 50–65° toward −Z with a headrest, a leg rest sloping down toward
/// +Z, armrests, and an operating lamp on a post beside the backrest and an arm over the chest.
pub(super) fn dental_chair(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let uph = mat_either(&mut b, 0.6, Palette::Leather, Palette::Plastic, rng);
    let shell = b.material(fixed_material("dental_white", [0xEE, 0xEF, 0xEC], 0.4, 0.0));
    let seat = uniform(rng, 0.45, 0.55);
    b.cuboid("floor_plate", shell, [-0.3, 0.0, -0.55], [0.3, 0.05, 0.38]);
    b.cuboid(
        "column",
        shell,
        [-0.13, 0.049, -0.18],
        [0.13, seat - 0.03, 0.1],
    );
    b.cuboid(
        "seat_frame",
        shell,
        [-0.26, seat - 0.04, -0.22],
        [0.26, seat + 0.01, 0.24],
    );
    b.part(rounded_box(
        "seat",
        uph,
        [0.0, seat + 0.045, 0.01],
        [0.26, 0.05, 0.24],
        0.3,
    ));
    let recline = -uniform(rng, 0.87, 1.13);
    let back_l = uniform(rng, 0.62, 0.72);
    let hinge = [0.0, seat + 0.06, -0.22];
    b.part(slanted_box(
        "backrest",
        uph,
        hinge,
        recline,
        [0.25, 0.5 * back_l, 0.05],
    ));
    let rot = rotation([1.0, 0.0, 0.0], recline);
    let end = nalgebra::Vector3::from(hinge) + rot * nalgebra::Vector3::new(0.0, back_l, 0.0);
    b.part(slanted_box(
        "headrest",
        uph,
        end.into(),
        recline,
        [0.13, 0.1, 0.05],
    ));
    let legs = std::f32::consts::FRAC_PI_2 + uniform(rng, 0.25, 0.4);
    b.part(slanted_box(
        "leg_rest",
        uph,
        [0.0, seat + 0.045, 0.2],
        legs,
        [0.22, 0.3, 0.045],
    ));
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * 0.3;
        b.cuboid(
            &format!("arm_{i}"),
            uph,
            [x - 0.04, seat + 0.2, -0.12],
            [x + 0.04, seat + 0.25, 0.22],
        );
        b.cuboid(
            &format!("arm_post_{i}"),
            shell,
            [x - 0.015, seat - 0.02, 0.0],
            [x + 0.015, seat + 0.205, 0.05],
        );
        let (x0, x1) = if sx < 0.0 { (x, -0.25) } else { (0.25, x) };
        b.cuboid(
            &format!("arm_bracket_{i}"),
            shell,
            [x0, seat - 0.02, 0.0],
            [x1, seat + 0.01, 0.05],
        );
    }
    dental_lamp(&mut b, shell, rng);
    b.top_surface("seat", [-0.2, -0.12], [0.2, 0.2], seat + 0.095, 0.03);
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// A dental chair's operating lamp: a post on a foot beside the floor plate's back, an arm over the
/// chest and a lamp head facing down.
fn dental_lamp(b: &mut AssetBuilder, m: usize, rng: &mut ChaCha8Rng) {
    let top = uniform(rng, 1.55, 1.8);
    let (px, pz) = (uniform(rng, 0.36, 0.46), -0.5);
    b.cuboid(
        "lamp_foot",
        m,
        [0.26, 0.0, pz - 0.05],
        [px + 0.05, 0.06, pz + 0.05],
    );
    b.part(cylinder("lamp_post", m, [px, pz], 0.03, 0.05, top, 12));
    let lz = -uniform(rng, 0.1, 0.3);
    b.part(beam(
        "lamp_arm",
        m,
        [px, top - 0.02, pz],
        [0.0, top - 0.02, lz],
        [0.04, 0.04],
    ));
    b.part(rounded_box(
        "lamp_head",
        m,
        [0.0, top - 0.08, lz],
        [0.16, 0.05, 0.08],
        0.4,
    ));
}

/// Massage table: width 2.07–2.22 (with the face cradle), height 0.62–0.86, depth 0.6–0.76; a
/// padded top (the `top` surface) on a board and aprons over four legs joined by stretchers, and a
/// face cradle (a horseshoe cushion) on two bars at the +X end.
pub(super) fn massage_table(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let pad = mat_either(&mut b, 0.6, Palette::Leather, Palette::Fabric, rng);
    let frame = mat_either(&mut b, 0.6, Palette::Wood, Palette::Metal, rng);
    let (l, h, d) = (
        uniform(rng, 1.83, 1.93),
        uniform(rng, 0.62, 0.85),
        uniform(rng, 0.6, 0.76),
    );
    let (hl, hd) = (0.5 * l, 0.5 * d);
    b.part(rounded_box(
        "pad",
        pad,
        [0.0, h - 0.045, 0.0],
        [hl, 0.045, hd],
        0.25,
    ));
    b.cuboid(
        "board",
        frame,
        [-hl + 0.01, h - 0.1, -hd + 0.01],
        [hl - 0.01, h - 0.07, hd - 0.01],
    );
    for (i, sz) in [-1.0f32, 1.0].into_iter().enumerate() {
        let z = sz * (hd - 0.04);
        b.cuboid(
            &format!("apron_{i}"),
            frame,
            [-hl + 0.06, h - 0.18, z - 0.01],
            [hl - 0.06, h - 0.099, z + 0.01],
        );
    }
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        let c = [sx * (hl - 0.1), sz * (hd - 0.07)];
        b.part(square_post(
            &format!("leg_{i}"),
            frame,
            c,
            0.045,
            0.0,
            h - 0.099,
        ));
    }
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * (hl - 0.1);
        b.cuboid(
            &format!("stretcher_{i}"),
            frame,
            [x - 0.015, 0.12, -hd + 0.07],
            [x + 0.015, 0.16, hd - 0.07],
        );
    }
    b.cuboid(
        "stretcher_long",
        frame,
        [-hl + 0.1, 0.12, -0.015],
        [hl - 0.1, 0.15, 0.015],
    );
    face_cradle(&mut b, [pad, frame], hl, h, rng);
    b.top_surface("top", [-hl, -hd], [hl, hd], h, 0.06);
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// A massage table's face cradle beyond the end at x = `hl`: two bars from under the top, a plate
/// and a horseshoe cushion open toward the table, level with the top at `h`.
fn face_cradle(b: &mut AssetBuilder, m: [usize; 2], hl: f32, h: f32, rng: &mut ChaCha8Rng) {
    let [pad, frame] = m;
    let reach = uniform(rng, 0.24, 0.3);
    let (x0, x1) = (hl + reach - 0.26, hl + reach);
    for (i, z) in [-0.08f32, 0.08].into_iter().enumerate() {
        b.part(beam(
            &format!("cradle_bar_{i}"),
            frame,
            [hl - 0.15, h - 0.085, z],
            [x1 - 0.06, h - 0.07, z],
            [0.022, 0.022],
        ));
    }
    b.cuboid(
        "cradle_plate",
        frame,
        [x0, h - 0.075, -0.13],
        [x1, h - 0.055, 0.13],
    );
    for (i, z) in [-0.095f32, 0.095].into_iter().enumerate() {
        b.part(rounded_box(
            &format!("cradle_cushion_{i}"),
            pad,
            [0.5 * (x0 + x1) - 0.03, h - 0.025, z],
            [0.5 * (x1 - x0) - 0.03, 0.032, 0.035],
            0.4,
        ));
    }
    b.part(rounded_box(
        "cradle_cushion_end",
        pad,
        [x1 - 0.04, h - 0.025, 0.0],
        [0.04, 0.032, 0.13],
        0.4,
    ));
}

/// Barber chair: width 0.66–0.72, height 1.1–1.35 (the headrest), depth 0.8–1.0 (the footrest); a
/// chrome round base 0.56–0.64 across with a hydraulic column, an upholstered seat 0.53–0.59 high
/// (the `seat` surface), a back leaning 8–15° with a headrest on a stem, armrests on chrome
/// supports and a footrest plate in front.
pub(super) fn barber_chair(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let chrome = b.material(fixed_material("chrome", [0xC8, 0xCA, 0xCE], 0.15, 1.0));
    let uph = mat_either(&mut b, 0.7, Palette::Leather, Palette::Fabric, rng);
    let r = uniform(rng, 0.28, 0.32);
    let seat = uniform(rng, 0.5, 0.56);
    let (sw, sd) = (uniform(rng, 0.5, 0.56), uniform(rng, 0.46, 0.52));
    let (hw, hd) = (0.5 * sw, 0.5 * sd);
    b.part(frustum(
        "base",
        chrome,
        [0.0, 0.0],
        r,
        r - 0.03,
        0.0,
        0.05,
        32,
    ));
    b.part(cylinder(
        "column",
        chrome,
        [0.0, 0.0],
        0.06,
        0.049,
        seat - 0.09,
        16,
    ));
    b.cuboid("pump_pedal", chrome, [0.06, 0.07, -0.02], [0.2, 0.09, 0.02]);
    b.cuboid(
        "seat_frame",
        chrome,
        [-hw, seat - 0.1, -hd],
        [hw, seat - 0.06, hd],
    );
    b.part(rounded_box(
        "seat",
        uph,
        [0.0, seat - 0.02, 0.0],
        [hw - 0.01, 0.05, hd],
        0.3,
    ));
    barber_back(&mut b, [uph, chrome], [hw, hd, seat], rng);
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * (hw + 0.04);
        b.cuboid(
            &format!("arm_{i}"),
            uph,
            [x - 0.04, seat + 0.17, -hd + 0.04],
            [x + 0.04, seat + 0.22, hd + 0.03],
        );
        b.cuboid(
            &format!("arm_support_{i}"),
            chrome,
            [x - 0.012, seat - 0.1, hd - 0.06],
            [x + 0.012, seat + 0.171, hd - 0.02],
        );
        let (xa, xb) = if sx < 0.0 {
            (x - 0.012, -hw + 0.01)
        } else {
            (hw - 0.01, x + 0.012)
        };
        b.cuboid(
            &format!("arm_rail_{i}"),
            chrome,
            [xa, seat - 0.1, hd - 0.06],
            [xb, seat - 0.07, hd - 0.02],
        );
    }
    barber_footrest(&mut b, chrome, [hd, seat], rng);
    b.top_surface(
        "seat",
        [-hw + 0.05, -hd + 0.08],
        [hw - 0.05, hd],
        seat + 0.03,
        0.03,
    );
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// A barber chair's back over the seat `s` = (half width, half depth, height): an upholstered
/// back leaning 8–15° toward −Z, and a headrest on a chrome stem above it.
fn barber_back(b: &mut AssetBuilder, m: [usize; 2], s: [f32; 3], rng: &mut ChaCha8Rng) {
    let ([uph, chrome], [hw, hd, seat]) = (m, s);
    let lean = -uniform(rng, 0.14, 0.26);
    let back_h = uniform(rng, 0.45, 0.55);
    let start = [0.0, seat - 0.05, -hd + 0.04];
    b.part(slanted_box(
        "back",
        uph,
        start,
        lean,
        [hw - 0.02, 0.5 * back_h, 0.055],
    ));
    let rot = rotation([1.0, 0.0, 0.0], lean);
    let top = nalgebra::Vector3::from(start) + rot * nalgebra::Vector3::new(0.0, back_h, -0.02);
    let stem = uniform(rng, 0.06, 0.16);
    b.part(slanted_box(
        "headrest_stem",
        chrome,
        (top - rot * nalgebra::Vector3::new(0.0, 0.05, 0.0)).into(),
        lean,
        [0.02, 0.5 * stem + 0.05, 0.012],
    ));
    let head = top + rot * nalgebra::Vector3::new(0.0, stem, 0.0);
    b.part(slanted_box(
        "headrest",
        uph,
        head.into(),
        lean,
        [0.13, 0.07, 0.045],
    ));
}

/// A barber chair's footrest under the seat front at `s` = (seat half depth, seat height): two
/// chrome bars down and forward to a plate about 0.17 above the floor.
fn barber_footrest(b: &mut AssetBuilder, m: usize, s: [f32; 2], rng: &mut ChaCha8Rng) {
    let [hd, seat] = s;
    let z = hd + uniform(rng, 0.12, 0.2);
    for (i, x) in [-0.14f32, 0.14].into_iter().enumerate() {
        b.part(beam(
            &format!("footrest_bar_{i}"),
            m,
            [x, seat - 0.08, hd - 0.03],
            [x, 0.19, z],
            [0.022, 0.022],
        ));
    }
    b.cuboid(
        "footrest",
        m,
        [-0.2, 0.165, z - 0.08],
        [0.2, 0.19, z + 0.08],
    );
}

/// Ironing board: width 1.24–1.39 (the board's length, its nose toward +X, with the iron rest),
/// height 0.75–0.95, depth 0.36–0.46; a padded board 0.33–0.4 wide with a pointed nose (its square
/// part the `board` surface), a wire iron rest at the square end, on two crossed U-shaped steel
/// legs with rubber-capped foot bars.
pub(super) fn ironing_board(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let cover = mat(&mut b, Palette::Fabric, rng);
    let steel = mat(&mut b, Palette::CoatedMetal, rng);
    let rubber = mat(&mut b, Palette::Rubber, rng);
    let (l, h, bw) = (
        uniform(rng, 1.1, 1.25),
        uniform(rng, 0.75, 0.95),
        uniform(rng, 0.33, 0.4),
    );
    let (hl, g) = (0.5 * l, 0.5 * bw);
    let xn = hl - uniform(rng, 0.3, 0.38);
    let outline = [
        [-hl, -g],
        [xn, -g],
        [hl - 0.1, -0.5 * g],
        [hl, 0.0],
        [hl - 0.1, 0.5 * g],
        [xn, g],
        [-hl, g],
    ];
    b.part(prism_y("board", steel, &outline, h - 0.035, h - 0.024));
    b.part(prism_y("cover", cover, &outline, h - 0.025, h));
    b.cuboid(
        "iron_rest",
        steel,
        [-hl - 0.14, h - 0.03, -0.11],
        [-hl + 0.02, h - 0.022, 0.11],
    );
    for (i, z) in [-0.11f32, 0.1].into_iter().enumerate() {
        b.cuboid(
            &format!("iron_rest_rail_{i}"),
            steel,
            [-hl - 0.14, h - 0.025, z],
            [-hl + 0.001, h - 0.01, z + 0.01],
        );
    }
    let feet = [uniform(rng, 0.34, 0.4), uniform(rng, 0.18, 0.23)];
    for (k, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        ironing_leg(
            &mut b,
            [steel, rubber],
            k,
            sx,
            [feet[0], feet[1], h - 0.035],
        );
    }
    let yc = 0.02 + (h - 0.065) * feet[0] / (feet[0] + 0.3);
    b.part(rod(
        "pivot",
        steel,
        [0.0, yc, -0.15],
        [0.0, yc, 0.15],
        0.008,
        0.008,
        8,
    ));
    b.top_surface("board", [-hl, -g], [xn, g], h, 0.04);
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// One U-shaped leg of an ironing board, `k` of two: from a rubber-capped foot bar at x = `sx` ·
/// `f[0]` (half width `f[1]` along Z) across to x = −`sx` · 0.3 under the board at `f[2]`.
fn ironing_leg(b: &mut AssetBuilder, m: [usize; 2], k: usize, sx: f32, f: [f32; 3]) {
    let [steel, rubber] = m;
    let [fx, fw, top] = f;
    let zl = if k == 0 { 0.14 } else { 0.115 };
    let (x0, x1) = (sx * fx, -sx * 0.3);
    b.cuboid(
        &format!("foot_{k}"),
        rubber,
        [x0 - 0.018, 0.0, -fw],
        [x0 + 0.018, 0.03, fw],
    );
    for (i, z) in [-zl, zl].into_iter().enumerate() {
        b.part(tube(
            &format!("leg_{k}_{i}"),
            steel,
            [x0, 0.02, z],
            [x1, top - 0.01, z],
            0.011,
            0.011,
            8,
        ));
    }
    b.cuboid(
        &format!("mount_{k}"),
        steel,
        [x1 - 0.015, top - 0.02, -zl - 0.01],
        [x1 + 0.015, top + 0.001, zl + 0.01],
    );
}
