//! Media small items: a video projector and over-ear headphones. The projector's lens faces
//! +Z; the headphones lie flat with their band behind the ear cups (toward −Z).

use rand_chacha::ChaCha8Rng;

use super::builder::Builder;
use crate::materials::Palette;
use crate::random::{coin, color, int, uniform};
use scenethesis_primitives::{arc, rod, rounded_box};
use scenethesis_scene_graph::{Asset, Placement};

const CASES: &[[f32; 3]] = &[
    [0.85, 0.85, 0.84],
    [0.1, 0.1, 0.11],
    [0.55, 0.56, 0.58],
    [0.92, 0.9, 0.86],
];

/// Video projector (a home or office projector: width 0.26–0.36, height 0.09–0.13, depth
/// 0.2–0.3 plus the lens): a rounded case on four small feet, a lens barrel with a focus ring and glass
/// on the front (+Z, centred or to one side), a vent grille beside it and buttons on top.
pub(crate) fn projector(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let case = b.material("projector_case", color(rng, CASES, 0.02), 0.45);
    let dark = b.material("lens_barrel", [0.03, 0.03, 0.035], 0.4);
    let glass = b.glass("lens_glass", [0.15, 0.2, 0.3], 0.85);
    let (w, h, d) = (
        uniform(rng, 0.26, 0.36),
        uniform(rng, 0.075, 0.115),
        uniform(rng, 0.2, 0.3),
    );
    let (hw, hd, foot) = (0.5 * w, 0.5 * d, 0.012);
    for (i, (sx, sz)) in [(-1.0f32, -1.0f32), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .into_iter()
        .enumerate()
    {
        b.frustum(
            &format!("foot_{i}"),
            dark,
            [sx * (hw - 0.03), sz * (hd - 0.03)],
            0.01,
            0.012,
            0.0,
            foot + 0.002,
            10,
        );
    }
    b.add(rounded_box(
        "case",
        case,
        [0.0, foot + 0.5 * h, 0.0],
        [hw, 0.5 * h, hd],
        0.25,
    ));
    let r = (0.32 * h).clamp(0.025, 0.04);
    let lens_x = if coin(rng, 0.5) { 0.0 } else { hw - r - 0.03 };
    let y = foot + 0.5 * h;
    lens(&mut b, [dark, glass], [lens_x, y], r, hd);
    let vents = int(rng, 4, 7);
    let vent_x = if lens_x == 0.0 {
        -hw + 0.03
    } else {
        -hw + 0.04
    };
    for k in 0..vents {
        let x = vent_x + k as f32 * 0.012;
        b.cuboid(
            &format!("vent_{k}"),
            dark,
            [x, y - 0.35 * h, hd - 0.01],
            [x + 0.006, y + 0.3 * h, hd + 0.002],
        );
    }
    for k in 0..3 {
        let x = hw - 0.05 - k as f32 * 0.025;
        b.frustum(
            &format!("button_{k}"),
            dark,
            [x, -hd + 0.05],
            0.007,
            0.006,
            foot + h - 0.003,
            foot + h + 0.003,
            8,
        );
    }
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// The lens on the front face `zf`: a barrel of radius `r` at (x, y) = `at`, a focus ring and
/// the glass.
fn lens(b: &mut Builder, [dark, glass]: [usize; 2], at: [f32; 2], r: f32, zf: f32) {
    let [x, y] = at;
    b.add(rod(
        "lens_barrel",
        dark,
        [x, y, zf - 0.01],
        [x, y, zf + 0.02],
        r,
        r,
        20,
    ));
    b.add(rod(
        "focus_ring",
        dark,
        [x, y, zf + 0.004],
        [x, y, zf + 0.012],
        r + 0.004,
        r + 0.004,
        20,
    ));
    b.add(rod(
        "lens",
        glass,
        [x, y, zf + 0.019],
        [x, y, zf + 0.023],
        0.75 * r,
        0.7 * r,
        20,
    ));
}

/// Over-ear headphones lying flat (width 0.22–0.28, height 0.07–0.09, depth 0.13–0.165): two
/// ear cups (0.09–0.11 across) resting on their cushions, a fork over each cup, and the
/// headband, padded in its middle, arching behind them (−Z) at the height of the cups' tops.
pub(crate) fn headphones(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let shell = b.material("headphone_shell", color(rng, CASES, 0.03), 0.4);
    let cushion = b.palette(Palette::Leather, rng);
    let metal = b.metal("band_steel", [0.7, 0.7, 0.72], 0.3);
    let rc = uniform(rng, 0.045, 0.055);
    let cup_h = uniform(rng, 0.032, 0.045);
    let sep = rc + uniform(rng, 0.02, 0.03);
    let pad = uniform(rng, 0.018, 0.024);
    for (k, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * sep;
        b.frustum(
            &format!("cushion_{k}"),
            cushion,
            [x, 0.0],
            0.92 * rc,
            rc,
            0.0,
            pad,
            20,
        );
        b.frustum(
            &format!("cup_{k}"),
            shell,
            [x, 0.0],
            rc,
            0.85 * rc,
            pad - 0.001,
            pad + cup_h,
            20,
        );
        fork(
            &mut b,
            metal,
            &format!("fork_{k}"),
            x,
            rc,
            pad + 0.5 * cup_h,
            pad + cup_h,
        );
    }
    let yb = pad + cup_h + 0.006;
    let band = arc(
        [0.0, yb, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, -1.0],
        sep,
        0.0,
        std::f32::consts::PI,
        14,
    );
    b.polyline("band", metal, &band, 0.006);
    b.polyline("band_pad", shell, &band[4..=10], 0.013);
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// A fork over the cup at `x` (radius `rc`): an arm down each side (front and back) to the
/// cup's pivot height `pivot`, joined by a bridge over the cup at `top` where the band meets it.
fn fork(b: &mut Builder, metal: usize, name: &str, x: f32, rc: f32, pivot: f32, top: f32) {
    for (k, sz) in [-1.0f32, 1.0].into_iter().enumerate() {
        let z = sz * (rc + 0.006);
        b.cuboid(
            &format!("{name}_arm_{k}"),
            metal,
            [x - 0.006, pivot - 0.006, z - 0.004],
            [x + 0.006, top + 0.012, z + 0.004],
        );
    }
    b.cuboid(
        &format!("{name}_bridge"),
        metal,
        [x - 0.006, top + 0.002, -rc - 0.01],
        [x + 0.006, top + 0.012, rc + 0.01],
    );
}
