//! Craft machines: sewing machine, pottery wheel and kiln. Fronts (the needle and stitch dial, the
//! potter's side of the wheel, the kiln's control box) face +Z.

use rand_chacha::ChaCha8Rng;

use super::builder::Builder;
use crate::articulation::{back_hinge, DOOR_OPEN};
use crate::materials::Palette;
use crate::random::{coin, color, pick, uniform};
use scenethesis_primitives::{disc, prism_x, rect, rounded_box, square_post};
use scenethesis_scene_graph::{Asset, Placement, SurfaceKind};

/// Body colours of domestic sewing machines: white, cream, pastel blue, pink and grey.
const MACHINE_COLOURS: &[[f32; 3]] = &[
    [0.93, 0.93, 0.91],
    [0.92, 0.89, 0.8],
    [0.62, 0.76, 0.86],
    [0.9, 0.7, 0.76],
    [0.6, 0.62, 0.64],
];

/// Sewing machine: width 0.4–0.48 (with the handwheel), height 0.31–0.37 (with the spool), depth
/// 0.17–0.21; a flat bed with a steel needle plate, a pillar at the right (+X) carrying the arm
/// across to the head at the left, a needle bar and presser foot under the head, a stitch dial on
/// the pillar's front, a handwheel on the right side and a spool on top.
pub(crate) fn sewing_machine(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let body = b.material("machine_body", color(rng, MACHINE_COLOURS, 0.02), 0.35);
    let steel = b.metal("steel", [0.75, 0.76, 0.78], 0.25);
    let dark = b.material("dial", [0.12, 0.12, 0.13], 0.5);
    let thread = b.palette(Palette::BrightPlastic, rng);
    let (w, h, d) = (
        uniform(rng, 0.37, 0.45),
        uniform(rng, 0.26, 0.31),
        uniform(rng, 0.17, 0.21),
    );
    let (hw, hd, bed) = (0.5 * w, 0.5 * d, uniform(rng, 0.05, 0.07));
    b.cuboid("bed", body, [-hw, 0.0, -hd], [hw, bed, hd]);
    b.cuboid(
        "pillar",
        body,
        [hw - 0.11, bed - 0.001, -hd + 0.01],
        [hw - 0.01, h - 0.05, hd - 0.03],
    );
    b.add(rounded_box(
        "arm",
        body,
        [0.0, h - 0.045, -0.01],
        [hw - 0.005, 0.045, hd - 0.03],
        0.3,
    ));
    let hx = -hw + 0.05;
    b.cuboid(
        "head",
        body,
        [-hw + 0.005, h - 0.17, -hd + 0.03],
        [-hw + 0.095, h - 0.04, hd - 0.02],
    );
    needle_area(&mut b, steel, [hx, bed, h], hd);
    let dial_z = hd - 0.03;
    b.tube(
        "stitch_dial",
        dark,
        [hw - 0.06, h - 0.13, dial_z - 0.002],
        [hw - 0.06, h - 0.13, dial_z + 0.015],
        0.025,
        0.025,
        16,
    );
    let wheel_r = uniform(rng, 0.045, 0.055);
    let wheel_y = h - 0.09;
    b.tube(
        "handwheel",
        dark,
        [hw - 0.01, wheel_y, -0.01],
        [hw + 0.028, wheel_y, -0.01],
        wheel_r,
        wheel_r,
        20,
    );
    let sx = hw - 0.14;
    b.frustum(
        "spool_pin",
        steel,
        [sx, -0.02],
        0.003,
        0.003,
        h - 0.005,
        h + 0.055,
        6,
    );
    b.frustum(
        "spool",
        thread,
        [sx, -0.02],
        0.016,
        0.016,
        h - 0.002,
        h + 0.04,
        14,
    );
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// A sewing machine's stitching area under the head at `at` = (needle x, bed top, machine
/// height), the bed `hd` deep on each side: the needle plate, the needle bar and the presser
/// foot on its bar.
fn needle_area(b: &mut Builder, steel: usize, at: [f32; 3], hd: f32) {
    let [hx, bed, h] = at;
    b.cuboid(
        "needle_plate",
        steel,
        [hx - 0.05, bed - 0.001, -0.03],
        [hx + 0.06, bed + 0.002, hd - 0.01],
    );
    b.frustum(
        "needle_bar",
        steel,
        [hx, 0.03],
        0.004,
        0.004,
        bed + 0.018,
        h - 0.165,
        8,
    );
    b.cuboid(
        "presser_foot",
        steel,
        [hx - 0.012, bed + 0.002, 0.012],
        [hx + 0.012, bed + 0.012, 0.055],
    );
    b.frustum(
        "presser_bar",
        steel,
        [hx, 0.005],
        0.003,
        0.003,
        bed + 0.01,
        h - 0.165,
        8,
    );
}

/// Pottery wheel: width 0.56–0.67, height 0.44–0.59, depth 0.75–0.88 (with the pedal); a motor body
/// on four short legs, a round splash pan 0.56–0.66 across around a metal wheel head 0.3–0.36
/// across (its top the `wheel_head` surface), a foot pedal at the front right on the potter's side
/// and its cable, and on some seeds a shelf for tools along the back.
pub(crate) fn pottery_wheel(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let body = b.palette(
        if coin(rng, 0.6) {
            Palette::CoatedMetal
        } else {
            Palette::Plastic
        },
        rng,
    );
    let pan = b.palette(Palette::Plastic, rng);
    let steel = b.metal("wheel_head", [0.7, 0.71, 0.72], 0.35);
    let dark = b.material("pedal", [0.1, 0.1, 0.11], 0.6);
    let r = uniform(rng, 0.28, 0.33);
    let (bw, bd) = (uniform(rng, 0.4, 0.48), uniform(rng, 0.42, 0.5));
    let legs = uniform(rng, 0.08, 0.18);
    let top = legs + uniform(rng, 0.25, 0.3);
    for (i, (sx, sz)) in [(-1.0f32, -1.0f32), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .enumerate()
    {
        b.add(square_post(
            &format!("leg_{i}"),
            body,
            [sx * (0.5 * bw - 0.03), sz * (0.5 * bd - 0.03)],
            0.035,
            0.0,
            legs + 0.005,
        ));
    }
    b.cuboid(
        "body",
        body,
        [-0.5 * bw, legs, -0.5 * bd],
        [0.5 * bw, top, 0.5 * bd],
    );
    b.frustum(
        "pan_floor",
        pan,
        [0.0, 0.0],
        r - 0.02,
        r,
        top - 0.001,
        top + 0.015,
        24,
    );
    b.ring(
        "pan_wall",
        pan,
        [0.0, 0.0],
        (r - 0.008, r, top + 0.01),
        (r - 0.006, r + 0.004, top + 0.11),
        24,
    );
    let head_r = uniform(rng, 0.15, 0.18);
    let head = top + uniform(rng, 0.05, 0.07);
    b.frustum(
        "shaft",
        steel,
        [0.0, 0.0],
        0.03,
        0.03,
        top + 0.01,
        head - 0.02,
        12,
    );
    b.frustum(
        "wheel_head",
        steel,
        [0.0, 0.0],
        head_r - 0.005,
        head_r,
        head - 0.022,
        head,
        32,
    );
    pedal(&mut b, dark, [0.5 * bw, 0.5 * bd, legs], rng);
    if coin(rng, 0.4) {
        b.cuboid(
            "tool_shelf",
            pan,
            [-0.5 * bw, top - 0.05, -0.5 * bd - 0.12],
            [0.5 * bw, top - 0.03, -0.5 * bd + 0.001],
        );
    }
    b.surface(
        "wheel_head",
        SurfaceKind::Top,
        disc([0.0, 0.0], 0.8 * head_r, 12),
        head,
        None,
    );
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// A pottery wheel's foot pedal on the floor in front of the body's right half, the body given as
/// `s` = (half width, half depth, underside height), with its cable to the body.
fn pedal(b: &mut Builder, m: usize, s: [f32; 3], rng: &mut ChaCha8Rng) {
    let [hw, hd, under] = s;
    let x = hw - uniform(rng, 0.08, 0.14);
    let (z0, z1) = (hd + uniform(rng, 0.08, 0.14), hd + 0.32);
    let x0 = x - 0.06;
    b.add(prism_x(
        "pedal",
        m,
        &[[z0, 0.0], [z1 - 0.06, 0.0], [z1 - 0.06, 0.03], [z0, 0.07]],
        x0,
        x0 + 0.12,
    ));
    b.tube(
        "pedal_cable",
        m,
        [x, 0.03, z0 + 0.01],
        [x, under + 0.02, hd - 0.02],
        0.006,
        0.006,
        6,
    );
}

/// Kiln (electric pottery kiln): width 0.63–0.92, height 0.79–1.1, depth 0.73–1.02 (with the
/// control box); an 8- or 12-sided firebrick body in a steel jacket with two bands on a stand of
/// four legs, a control box on the front, and a lid hinged at its back that lifts up to 90° (`lid`,
/// closed = 0); inside, the kiln floor is the `kiln_floor` shelf surface under the lid.
pub(crate) fn kiln(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let jacket = b.metal(
        "jacket",
        color(rng, &[[0.72, 0.73, 0.74], [0.55, 0.56, 0.58]], 0.03),
        0.45,
    );
    let brick = b.material("firebrick", [0.86, 0.8, 0.7], 0.95);
    let stand = b.palette(Palette::CoatedMetal, rng);
    let n = *pick(rng, &[8u32, 12]);
    let r = uniform(rng, 0.31, 0.45);
    let wall = uniform(rng, 0.07, 0.085);
    let y0 = uniform(rng, 0.15, 0.22);
    let top = y0 + uniform(rng, 0.55, 0.8);
    for (i, (sx, sz)) in [(-1.0f32, -1.0f32), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .enumerate()
    {
        let c = [sx * 0.55 * r, sz * 0.55 * r];
        b.add(square_post(
            &format!("stand_leg_{i}"),
            stand,
            c,
            0.03,
            0.0,
            y0 + 0.001,
        ));
    }
    b.frustum("floor", brick, [0.0, 0.0], r, r, y0, y0 + 0.07, n);
    b.ring(
        "wall",
        jacket,
        [0.0, 0.0],
        (r - wall, r, y0 + 0.03),
        (r - wall, r, top),
        n,
    );
    for (k, f) in [0.3f32, 0.75].into_iter().enumerate() {
        let y = y0 + f * (top - y0);
        b.ring(
            &format!("band_{k}"),
            stand,
            [0.0, 0.0],
            (r - 0.01, r + 0.008, y),
            (r - 0.01, r + 0.008, y + 0.025),
            n,
        );
    }
    let yc = y0 + 0.45 * (top - y0);
    b.cuboid(
        "control_box",
        stand,
        [-0.12, yc - 0.13, r - 0.03],
        [0.12, yc + 0.13, r + 0.08],
    );
    b.cuboid(
        "controller",
        brick,
        [-0.06, yc + 0.02, r + 0.079],
        [0.06, yc + 0.09, r + 0.085],
    );
    for (i, x) in [-0.14f32, 0.14].into_iter().enumerate() {
        b.cuboid(
            &format!("hinge_{i}"),
            stand,
            [x - 0.03, top - 0.05, -r - 0.03],
            [x + 0.03, top + 0.001, -r + 0.09],
        );
    }
    kiln_lid(&mut b, [jacket, stand], n, r, top, rng);
    let s = 0.6 * (r - wall);
    let floor = y0 + 0.07;
    b.surface(
        "kiln_floor",
        SurfaceKind::Shelf,
        rect(-s, -s, s, s),
        floor,
        Some(top - floor),
    );
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// A kiln's lid on the body of `n` sides and radius `r` (a corner at −Z) topped at `top`: a slab of
/// the body's outline hinged at its back corner, with a handle at its front, all on the `lid`
/// joint.
fn kiln_lid(b: &mut Builder, m: [usize; 2], n: u32, r: f32, top: f32, rng: &mut ChaCha8Rng) {
    let [jacket, stand] = m;
    let t = uniform(rng, 0.07, 0.09);
    b.joint(back_hinge("lid", top + t, -r, DOOR_OPEN));
    b.link(Some("lid"));
    b.frustum("lid", jacket, [0.0, 0.0], r, r, top, top + t, n);
    b.cuboid(
        "lid_handle",
        stand,
        [-0.08, top + 0.3 * t, r - 0.01],
        [0.08, top + 0.8 * t, r + 0.045],
    );
    b.link(None);
}
