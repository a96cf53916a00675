//! Bathroom and laundry fixtures: toilet, bathtub, shower, towel rack, bath mat, standing
//! mirror, laundry hamper and washing machine. Fronts face +Z; the side that goes against a
//! wall (cistern, tub's tap end, shower riser) is at −Z.

use rand_chacha::ChaCha8Rng;

use crate::articulation;
use crate::items::builder::Builder;
use crate::materials::Palette;
use crate::random::{coin, int, uniform};
use scenethesis_primitives::{
    convex_hull, cylinder, prism_x, rect, rod, rounded_box, square_post, strut,
};
use scenethesis_scene_graph::{Asset, Placement};

/// Adds an oval wall of `segments` convex slabs around `center` = (x, z): at height `y0` the
/// outer half axes are `axes` scaled by `s0` and the inner ones `wall` less, likewise at `y1`
/// with `s1` (a flaring bowl when `s1 > s0`). Every slab is a closed convex hull.
#[allow(clippy::too_many_arguments)]
fn oval_wall(
    b: &mut Builder,
    name: &str,
    material: usize,
    center: [f32; 2],
    axes: [f32; 2],
    (s0, y0): (f32, f32),
    (s1, y1): (f32, f32),
    wall: f32,
    segments: u32,
) {
    let point = |a: f32, scale: f32, inset: f32, y: f32| -> [f32; 3] {
        [
            center[0] + (axes[0] * scale - inset) * a.cos(),
            y,
            center[1] + (axes[1] * scale - inset) * a.sin(),
        ]
    };
    for k in 0..segments {
        let a0 = std::f32::consts::TAU * k as f32 / segments as f32;
        let a1 = std::f32::consts::TAU * (k + 1) as f32 / segments as f32;
        let mut pts = Vec::with_capacity(8);
        for a in [a0, a1] {
            pts.push(point(a, s0, 0.0, y0));
            pts.push(point(a, s0, wall, y0));
            pts.push(point(a, s1, 0.0, y1));
            pts.push(point(a, s1, wall, y1));
        }
        if let Some(part) = convex_hull(&format!("{name}_{k}"), material, &pts) {
            b.add(part);
        }
    }
}

/// An oval (x, z) polygon of `n` corners, counter-clockwise seen from above.
fn oval(center: [f32; 2], axes: [f32; 2], n: usize) -> Vec<[f32; 2]> {
    (0..n)
        .map(|i| {
            let a = std::f32::consts::TAU * i as f32 / n as f32;
            [center[0] + axes[0] * a.cos(), center[1] - axes[1] * a.sin()]
        })
        .collect()
}

/// Toilet (close-coupled): width 0.36–0.42, height 0.72–0.84 (lid up reaches ≈ 0.9), depth
/// 0.6–0.72; a hollow oval bowl on a pedestal, a seat ring and a lid drawn closed (both hinged
/// at the back, opening up), a cistern at the back with a flush button and a usable top.
pub(super) fn toilet(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let china = b.fixed("vitreous_china", [0xF5, 0xF5, 0xF2], 0.12, 0.0);
    let seat_m = if coin(rng, 0.7) {
        china
    } else {
        b.palette(Palette::Wood, rng)
    };
    let chrome = b.palette(Palette::Metal, rng);
    let w = uniform(rng, 0.36, 0.42);
    let (ax, az) = (0.5 * w - 0.01, uniform(rng, 0.22, 0.26));
    let cd = uniform(rng, 0.16, 0.2);
    let seat_h = uniform(rng, 0.39, 0.43);
    let tank_top = uniform(rng, 0.72, 0.82);
    let z0 = -0.5 * (cd + 2.0 * az - 0.04);
    let zc = z0 + cd + az - 0.04;
    let hw = 0.5 * w;
    // Pan: a pedestal joined to the rear block under the cistern.
    b.cuboid(
        "pedestal",
        china,
        [-0.12, 0.0, z0 + 0.02],
        [0.12, 0.24, zc + 0.55 * az],
    );
    b.cuboid(
        "rear_block",
        china,
        [-0.14, 0.0, z0 + 0.02],
        [0.14, seat_h - 0.02, z0 + cd],
    );
    let rim = seat_h - 0.02;
    oval_wall(
        &mut b,
        "bowl",
        china,
        [0.0, zc],
        [ax, az],
        (0.55, 0.22),
        (1.0, rim),
        0.025,
        16,
    );
    b.add(scenethesis_primitives::prism_y(
        "bowl_floor",
        china,
        &oval([0.0, zc], [0.55 * ax, 0.55 * az], 16),
        0.2,
        0.25,
    ));
    // Seat ring and lid, drawn closed, both hinged at the cistern's front above the seat.
    let hinge_z = z0 + cd - 0.005;
    b.joint(articulation::back_hinge("seat", seat_h, hinge_z, 1.5));
    b.link(Some("seat"));
    oval_wall(
        &mut b,
        "seat",
        seat_m,
        [0.0, zc + 0.01],
        [ax, az],
        (1.0, rim),
        (1.0, seat_h),
        0.06,
        16,
    );
    b.joint(articulation::back_hinge("lid", seat_h + 0.02, hinge_z, 1.5));
    b.link(Some("lid"));
    b.add(scenethesis_primitives::prism_y(
        "lid",
        seat_m,
        &oval([0.0, zc + 0.01], [ax, az], 16),
        seat_h,
        seat_h + 0.02,
    ));
    b.link(None);
    // Cistern.
    b.cuboid("cistern", china, [-hw, rim, z0], [hw, tank_top, z0 + cd]);
    b.add(cylinder(
        "flush_button",
        chrome,
        [0.0, z0 + 0.5 * cd],
        0.02,
        tank_top - 0.002,
        tank_top + 0.006,
        12,
    ));
    b.top(
        "cistern_top",
        rect(-hw + 0.03, z0 + 0.03, hw - 0.03, z0 + 0.5 * cd - 0.03),
        tank_top,
    );
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// Bathtub: width 1.5–1.8, height 0.5–0.66, depth 0.7–0.82; an open tub with a thick rim and a
/// real hollow, built in on a plinth or freestanding on four feet, with a tap at the −x end.
pub(super) fn bathtub(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let enamel = b.fixed("enamel", [0xF4, 0xF4, 0xF1], 0.15, 0.0);
    let chrome = b.palette(Palette::Metal, rng);
    let (w, d) = (uniform(rng, 1.5, 1.8), uniform(rng, 0.7, 0.8));
    let h = uniform(rng, 0.5, 0.58);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let freestanding = coin(rng, 0.35);
    let y0 = if freestanding {
        let foot = b.palette(Palette::Metal, rng);
        let fh = uniform(rng, 0.06, 0.1);
        for (i, (sx, sz)) in super::carcass::CORNERS.iter().enumerate() {
            b.frustum(
                &format!("foot_{i}"),
                foot,
                [sx * (hw - 0.12), sz * (hd - 0.1)],
                0.035,
                0.05,
                0.0,
                fh + 0.01,
                10,
            );
        }
        fh
    } else {
        0.0
    };
    let wall = uniform(rng, 0.06, 0.08);
    let inner = b.open_box("tub", enamel, [-hw, y0, -hd], [hw, y0 + h, hd], wall, 0.06);
    // The tap on the −x end's rim, its spout over the water.
    let tap_x = -hw + 0.5 * wall;
    b.add(cylinder(
        "tap",
        chrome,
        [tap_x, 0.0],
        0.02,
        y0 + h - 0.002,
        y0 + h + 0.12,
        12,
    ));
    b.add(rod(
        "spout",
        chrome,
        [tap_x, y0 + h + 0.1, 0.0],
        [tap_x + 0.14, y0 + h + 0.08, 0.0],
        0.014,
        0.012,
        8,
    ));
    b.interior(
        rect(
            -hw + wall + 0.25,
            -hd + wall + 0.03,
            hw - wall - 0.03,
            hd - wall - 0.03,
        ),
        inner,
    );
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// Shower: width 0.8–1.0, height 1.95–2.1, depth 0.8–1.0; a tray with a low lip, a glass side
/// panel and half a glass front (the other half is the way in), a riser rail at the back with
/// an overhead head.
pub(super) fn shower(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let tray = b.fixed("tray", [0xF2, 0xF2, 0xEF], 0.2, 0.0);
    let glass = b.glass("shower_glass", [0.82, 0.9, 0.92], 0.25);
    let metal = b.palette(Palette::Metal, rng);
    let (w, d) = (uniform(rng, 0.8, 1.0), uniform(rng, 0.8, 1.0));
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let th = uniform(rng, 0.04, 0.08);
    let h = uniform(rng, 1.95, 2.02);
    let inner = b.open_box("tray", tray, [-hw, 0.0, -hd], [hw, th, hd], 0.04, 0.03);
    let t = 0.008;
    b.cuboid(
        "glass_side",
        glass,
        [hw - 0.03 - t, th, -hd + 0.02],
        [hw - 0.03, h, hd - 0.02],
    );
    b.cuboid(
        "glass_front",
        glass,
        [0.0, th, hd - 0.03 - t],
        [hw - 0.03, h, hd - 0.03],
    );
    b.add(square_post(
        "post",
        metal,
        [hw - 0.035, hd - 0.035],
        0.025,
        th,
        h,
    ));
    b.cuboid(
        "rail",
        metal,
        [0.0, h - 0.03, hd - 0.045],
        [hw - 0.03, h, hd - 0.02],
    );
    // Riser and head at the back.
    let rz = -hd + 0.03;
    b.add(rod(
        "riser",
        metal,
        [0.0, th, rz],
        [0.0, h - 0.1, rz],
        0.012,
        0.012,
        8,
    ));
    let head_z = -hd + uniform(rng, 0.18, 0.24);
    b.add(rod(
        "arm",
        metal,
        [0.0, h - 0.1, rz],
        [0.0, h - 0.1, head_z],
        0.01,
        0.01,
        8,
    ));
    let head_r = uniform(rng, 0.06, 0.1);
    b.frustum(
        "head",
        metal,
        [0.0, head_z],
        head_r,
        0.03,
        h - 0.14,
        h - 0.1,
        16,
    );
    b.cuboid("valve", metal, [-0.05, 1.0, rz], [0.05, 1.1, rz + 0.04]);
    b.interior(rect(-hw + 0.06, -hd + 0.1, hw - 0.06, hd - 0.06), inner);
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// Towel rack (wall-mounted): width 0.45–0.8, height 0.06–0.9, depth 0.08–0.16; one or two bars
/// on brackets, or a heated ladder rail of 5–10 bars; often a towel hangs over the top bar.
pub(super) fn towel_rack(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let metal = b.palette(Palette::Metal, rng);
    let w = uniform(rng, 0.45, 0.8);
    let hw = 0.5 * w;
    let ladder = coin(rng, 0.4);
    let depth = uniform(rng, 0.07, 0.1);
    let top = if ladder {
        let h = uniform(rng, 0.6, 0.9);
        for (i, x) in [-hw + 0.015, hw - 0.015].iter().enumerate() {
            b.add(rod(
                &format!("upright_{i}"),
                metal,
                [*x, 0.0, depth],
                [*x, h, depth],
                0.015,
                0.015,
                10,
            ));
            for (k, y) in [0.1 * h, 0.9 * h].iter().enumerate() {
                b.add(rod(
                    &format!("bracket_{i}_{k}"),
                    metal,
                    [*x, *y, 0.0],
                    [*x, *y, depth],
                    0.01,
                    0.01,
                    8,
                ));
            }
        }
        let bars = int(rng, 5, 10);
        for k in 0..bars {
            let y = 0.04 + (h - 0.08) * k as f32 / (bars - 1) as f32;
            b.add(rod(
                &format!("bar_{k}"),
                metal,
                [-hw + 0.015, y, depth],
                [hw - 0.015, y, depth],
                0.011,
                0.011,
                8,
            ));
        }
        h - 0.04
    } else {
        let bars = int(rng, 1, 2);
        for k in 0..bars {
            let z = depth * (k + 1) as f32 / bars as f32;
            b.add(rod(
                &format!("bar_{k}"),
                metal,
                [-hw, 0.03, z],
                [hw, 0.03, z],
                0.01,
                0.01,
                8,
            ));
        }
        for (i, x) in [-hw + 0.02, hw - 0.02].iter().enumerate() {
            b.cuboid(
                &format!("plate_{i}"),
                metal,
                [x - 0.02, 0.0, 0.0],
                [x + 0.02, 0.06, 0.008],
            );
            b.cuboid(
                &format!("arm_{i}"),
                metal,
                [x - 0.008, 0.02, 0.0],
                [x + 0.008, 0.04, depth + 0.012],
            );
        }
        0.03
    };
    if coin(rng, 0.55) {
        let cloth = b.palette(Palette::Fabric, rng);
        let tw = uniform(rng, 0.5, 0.85) * w;
        let drop = uniform(rng, 0.25, 0.4).min(top + 0.01 - 0.005).max(0.02);
        let bar_z = depth;
        let y_top = top + 0.012;
        b.cuboid(
            "towel_top",
            cloth,
            [-0.5 * tw, y_top - 0.005, bar_z - 0.016],
            [0.5 * tw, y_top + 0.006, bar_z + 0.016],
        );
        b.cuboid(
            "towel_back",
            cloth,
            [-0.5 * tw, y_top - drop, bar_z - 0.016],
            [0.5 * tw, y_top, bar_z - 0.011],
        );
        b.cuboid(
            "towel_front",
            cloth,
            [-0.5 * tw, y_top - drop, bar_z + 0.011],
            [0.5 * tw, y_top, bar_z + 0.016],
        );
    }
    b.finish(Placement::Wall, [0.9, 1.1])
}

/// Bath mat: width 0.5–0.9, height 0.01–0.025, depth 0.4–0.6; a soft rounded slab.
pub(super) fn bath_mat(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let cloth = if coin(rng, 0.7) {
        b.palette(Palette::Fabric, rng)
    } else {
        b.palette(Palette::Rubber, rng)
    };
    let (w, d, h) = (
        uniform(rng, 0.5, 0.9),
        uniform(rng, 0.4, 0.6),
        uniform(rng, 0.01, 0.025),
    );
    b.add(rounded_box(
        "mat",
        cloth,
        [0.0, 0.5 * h, 0.0],
        [0.5 * w, 0.5 * h, 0.5 * d],
        0.3,
    ));
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
    b.finish(Placement::Floor, [0.85, 1.2])
}

/// Standing (wardrobe, full-length) mirror: width 0.4–0.8, height 1.45–1.9, depth 0.3–0.55; a
/// framed glass leaning back on a rear prop, or a cheval frame swung between two posts on feet.
pub(super) fn standing_mirror(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let frame = if coin(rng, 0.6) {
        b.palette(Palette::Wood, rng)
    } else {
        b.palette(Palette::CoatedMetal, rng)
    };
    let glass = b.fixed("mirror", [0xE8, 0xEC, 0xEE], 0.02, 1.0);
    let w = uniform(rng, 0.4, 0.8);
    let hw = 0.5 * w;
    let fw = uniform(rng, 0.03, 0.06);
    let t = 0.03;
    if coin(rng, 0.55) {
        // Leaning: the panel's foot at z = 0, its top leaned back by `lean`.
        let h = uniform(rng, 1.45, 1.85);
        let lean = h * uniform(rng, 0.1, 0.16);
        let profile = [[0.0, 0.0], [t, 0.0], [t - lean, h], [-lean, h]];
        b.add(prism_x("frame", frame, &profile, -hw, hw));
        let inset = |f: f32| f * lean / h;
        let (gy0, gy1) = (fw, h - fw);
        let gp = [
            [t - inset(gy0), gy0],
            [t + 0.004 - inset(gy0), gy0],
            [t + 0.004 - inset(gy1), gy1],
            [t - inset(gy1), gy1],
        ];
        b.add(prism_x("glass", glass, &gp, -hw + fw, hw - fw));
        let prop_top = 0.6 * h;
        let foot_z = -lean - uniform(rng, 0.15, 0.3);
        b.add(strut(
            "prop",
            frame,
            [0.0, 0.0, foot_z],
            [0.0, prop_top, -inset(prop_top) - 0.01],
            [0.04, 0.025],
        ));
    } else {
        // Cheval: two posts on feet, the mirror between them.
        let h = uniform(rng, 1.5, 1.9);
        let fd = uniform(rng, 0.3, 0.45);
        for (i, x) in [-hw - 0.02, hw + 0.02].iter().enumerate() {
            b.add(square_post(
                &format!("post_{i}"),
                frame,
                [*x, 0.0],
                0.04,
                0.03,
                h,
            ));
            b.cuboid(
                &format!("foot_{i}"),
                frame,
                [x - 0.025, 0.0, -0.5 * fd],
                [x + 0.025, 0.035, 0.5 * fd],
            );
        }
        let (y0, y1) = (0.25, h - 0.05);
        b.cuboid(
            "frame",
            frame,
            [-hw + 0.001, y0, -0.5 * t],
            [hw - 0.001, y1, 0.5 * t],
        );
        b.cuboid(
            "glass",
            glass,
            [-hw + fw, y0 + fw, 0.5 * t - 0.001],
            [hw - fw, y1 - fw, 0.5 * t + 0.004],
        );
        b.cuboid(
            "stretcher",
            frame,
            [-hw - 0.02, 0.06, -0.015],
            [hw + 0.02, 0.1, 0.015],
        );
    }
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// Laundry hamper: width 0.35–0.55, height 0.5–0.7, depth 0.32–0.45; an open round or square
/// basket (wicker, fabric or plastic) with a real hollow and two handle cut-outs' rims.
pub(super) fn laundry_hamper(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let body = match int(rng, 0, 2) {
        0 => b.fixed("wicker", [0xB0, 0x8A, 0x58], 0.8, 0.0),
        1 => b.palette(Palette::Fabric, rng),
        _ => b.palette(Palette::Plastic, rng),
    };
    let h = uniform(rng, 0.5, 0.7);
    if coin(rng, 0.5) {
        let r = uniform(rng, 0.175, 0.225);
        b.frustum("base", body, [0.0, 0.0], 0.92 * r, 0.92 * r, 0.0, 0.02, 20);
        b.ring(
            "wall",
            body,
            [0.0, 0.0],
            (0.92 * r - 0.012, 0.92 * r, 0.01),
            (r - 0.012, r, h),
            20,
        );
        b.ring(
            "rim",
            body,
            [0.0, 0.0],
            (r - 0.014, r + 0.006, h - 0.03),
            (r - 0.014, r + 0.006, h),
            20,
        );
        b.interior(
            scenethesis_primitives::disc([0.0, 0.0], 0.92 * r - 0.03, 12),
            0.02,
        );
    } else {
        let (w, d) = (uniform(rng, 0.35, 0.55), uniform(rng, 0.32, 0.45));
        let floor = b.open_box(
            "basket",
            body,
            [-0.5 * w, 0.0, -0.5 * d],
            [0.5 * w, h, 0.5 * d],
            0.012,
            0.02,
        );
        b.cuboid(
            "rim_front",
            body,
            [-0.5 * w, h - 0.03, 0.5 * d - 0.006],
            [0.5 * w, h, 0.5 * d + 0.006],
        );
        b.cuboid(
            "rim_back",
            body,
            [-0.5 * w, h - 0.03, -0.5 * d - 0.006],
            [0.5 * w, h, -0.5 * d + 0.006],
        );
        b.interior(
            rect(
                -0.5 * w + 0.03,
                -0.5 * d + 0.03,
                0.5 * w - 0.03,
                0.5 * d - 0.03,
            ),
            floor,
        );
    }
    b.finish(Placement::Floor, [0.85, 1.15])
}

/// Washing machine: width 0.595–0.6, height 0.82–0.86, depth 0.55–0.62; a front loader with a
/// round glass door hinged on its left and a control panel, or a top loader with a lid hinged
/// at its back and a rear console.
pub(super) fn washing_machine(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let body = match int(rng, 0, 3) {
        0 | 1 => b.fixed("appliance_white", [0xF2, 0xF2, 0xF0], 0.3, 0.0),
        2 => b.fixed("appliance_silver", [0xB8, 0xBA, 0xBC], 0.3, 0.6),
        _ => b.fixed("appliance_graphite", [0x3A, 0x3C, 0x40], 0.35, 0.2),
    };
    let dark = b.fixed("door_glass", [0x20, 0x28, 0x30], 0.05, 0.0);
    let trim = b.palette(Palette::Metal, rng);
    let (w, h, d) = (
        uniform(rng, 0.595, 0.6),
        uniform(rng, 0.82, 0.86),
        uniform(rng, 0.55, 0.62),
    );
    let (hw, hd) = (0.5 * w, 0.5 * d);
    b.cuboid("cabinet", body, [-hw, 0.0, -hd], [hw, h, hd]);
    if coin(rng, 0.75) {
        let r = uniform(rng, 0.15, 0.17);
        let cy = 0.45 * h;
        // The round door, hinged on its left edge, with a grip on its right.
        b.joint(articulation::side_hinge("door", -r, cy, hd + 0.05, true));
        b.link(Some("door"));
        b.add(rod(
            "door_ring",
            trim,
            [0.0, cy, hd - 0.002],
            [0.0, cy, hd + 0.04],
            r,
            r,
            24,
        ));
        b.add(rod(
            "door_glass",
            dark,
            [0.0, cy, hd + 0.039],
            [0.0, cy, hd + 0.05],
            0.75 * r,
            0.75 * r,
            24,
        ));
        b.cuboid(
            "door_grip",
            trim,
            [r - 0.03, cy - 0.05, hd + 0.039],
            [r - 0.005, cy + 0.05, hd + 0.06],
        );
        b.link(None);
        b.cuboid(
            "panel",
            trim,
            [-hw + 0.02, h - 0.12, hd - 0.002],
            [hw - 0.02, h - 0.02, hd + 0.004],
        );
        b.cuboid(
            "drawer",
            body,
            [-hw + 0.03, h - 0.11, hd + 0.003],
            [-hw + 0.2, h - 0.03, hd + 0.012],
        );
        b.add(rod(
            "knob",
            dark,
            [0.12, h - 0.07, hd + 0.003],
            [0.12, h - 0.07, hd + 0.025],
            0.025,
            0.025,
            12,
        ));
        b.top("top", rect(-hw + 0.03, -hd + 0.03, hw - 0.03, hd - 0.03), h);
    } else {
        b.joint(articulation::back_hinge("lid", h + 0.01, -hd + 0.16, 1.5));
        b.link(Some("lid"));
        b.cuboid(
            "lid",
            trim,
            [-hw + 0.04, h - 0.002, -hd + 0.16],
            [hw - 0.04, h + 0.01, hd - 0.04],
        );
        b.link(None);
        b.cuboid(
            "console",
            body,
            [-hw, h - 0.01, -hd],
            [hw, h + 0.1, -hd + 0.1],
        );
        b.add(rod(
            "knob",
            dark,
            [0.15, h + 0.05, -hd + 0.1],
            [0.15, h + 0.05, -hd + 0.12],
            0.025,
            0.025,
            12,
        ));
        b.top(
            "lid_top",
            rect(-hw + 0.06, -hd + 0.18, hw - 0.06, hd - 0.06),
            h + 0.01,
        );
    }
    b.finish(Placement::Floor, [0.98, 1.02])
}
