//! Bathroom items: folded towels, toilet paper, soap and a toothbrush holder.

use rand_chacha::ChaCha8Rng;

use super::builder::Builder;
use crate::materials::Palette;
use crate::random::{coin, color, int, uniform};
use scenethesis_primitives::{rect, rounded_box};
use scenethesis_scene_graph::{Asset, Placement};

const TOWEL_COLOURS: &[[f32; 3]] = &[
    [0.95, 0.95, 0.93],
    [0.75, 0.85, 0.9],
    [0.3, 0.45, 0.6],
    [0.85, 0.75, 0.6],
    [0.55, 0.6, 0.5],
    [0.6, 0.6, 0.62],
    [0.85, 0.55, 0.55],
];

/// Folded towels: width 0.26–0.42, height 0.03–0.15, depth 0.18–0.32; a stack of one to three
/// soft folded slabs; usable top.
pub(crate) fn towel(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let (w, d) = (uniform(rng, 0.26, 0.4), uniform(rng, 0.18, 0.3));
    let n = int(rng, 1, 3);
    let same = coin(rng, 0.6);
    let first = color(rng, TOWEL_COLOURS, 0.03);
    let mut y = 0.0;
    for k in 0..n {
        let t = uniform(rng, 0.03, 0.05);
        let c = if same || k == 0 {
            first
        } else {
            color(rng, TOWEL_COLOURS, 0.03)
        };
        let m = b.material(&format!("terry_{k}"), c, 0.95);
        let jx = uniform(rng, -0.01, 0.01);
        b.add(rounded_box(
            &format!("towel_{k}"),
            m,
            [jx, y + 0.5 * t, 0.0],
            [0.5 * w, 0.5 * t, 0.5 * d],
            0.3,
        ));
        y += t - 0.001;
    }
    b.top(
        "top",
        rect(
            -0.5 * w + 0.04,
            -0.5 * d + 0.04,
            0.5 * w - 0.04,
            0.5 * d - 0.04,
        ),
        y + 0.001,
    );
    b.finish(Placement::Surface, [0.85, 1.2])
}

/// Toilet paper: width 0.1–0.24, height 0.095–0.115, depth 0.1–0.12; one to three standing rolls
/// around a hollow cardboard core.
pub(crate) fn toilet_paper(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let paper = b.material(
        "tissue",
        color(rng, &[[0.97, 0.97, 0.96], [0.95, 0.93, 0.88]], 0.02),
        0.95,
    );
    let core = b.material("core", [0.6, 0.45, 0.3], 0.9);
    let r = uniform(rng, 0.05, 0.06);
    let h = uniform(rng, 0.095, 0.115);
    let n = int(rng, 1, 2);
    for k in 0..n {
        let x = (k as f32 - 0.5 * (n as f32 - 1.0)) * (2.0 * r + 0.004);
        b.ring(
            &format!("roll_{k}"),
            paper,
            [x, 0.0],
            (0.0235, r, 0.0),
            (0.0235, r, h),
            20,
        );
        b.ring(
            &format!("core_{k}"),
            core,
            [x, 0.0],
            (0.022, 0.024, 0.001),
            (0.022, 0.024, h - 0.001),
            12,
        );
    }
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// Soap: width 0.08–0.14, height 0.025–0.2, depth 0.06–0.11; a bar resting in a dish, or a pump
/// dispenser bottle with its nozzle toward +Z.
pub(crate) fn soap(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let bar_c = color(
        rng,
        &[
            [0.95, 0.92, 0.85],
            [0.85, 0.6, 0.65],
            [0.6, 0.8, 0.6],
            [0.9, 0.8, 0.45],
        ],
        0.03,
    );
    if coin(rng, 0.5) {
        let dish = b.palette(Palette::Ceramic, rng);
        let soap = b.material("soap", bar_c, 0.5);
        let (w, d) = (uniform(rng, 0.1, 0.14), uniform(rng, 0.07, 0.1));
        let floor = b.open_box(
            "dish",
            dish,
            [-0.5 * w, 0.0, -0.5 * d],
            [0.5 * w, 0.018, 0.5 * d],
            0.006,
            0.006,
        );
        let (bw, bd) = (w - 0.035, d - 0.03);
        let bh = uniform(rng, 0.018, 0.028);
        b.add(rounded_box(
            "bar",
            soap,
            [0.0, floor + 0.5 * bh, 0.0],
            [0.5 * bw, 0.5 * bh, 0.5 * bd],
            0.3,
        ));
    } else {
        let bottle = b.material("dispenser", bar_c, 0.25);
        let pump = b.palette(Palette::Metal, rng);
        let r = uniform(rng, 0.03, 0.04);
        let h = uniform(rng, 0.12, 0.16);
        b.frustum("bottle", bottle, [0.0, 0.0], r, r, 0.0, h, 20);
        b.frustum(
            "shoulder",
            bottle,
            [0.0, 0.0],
            r,
            0.012,
            h - 0.001,
            h + 0.015,
            20,
        );
        b.frustum(
            "pump",
            pump,
            [0.0, 0.0],
            0.008,
            0.008,
            h + 0.014,
            h + 0.035,
            10,
        );
        b.cuboid(
            "head",
            pump,
            [-0.01, h + 0.034, -0.012],
            [0.01, h + 0.045, 0.05],
        );
    }
    b.finish(Placement::Surface, [0.85, 1.15])
}

/// Toothbrush holder: width 0.07–0.1, height 0.17–0.22 (with brushes), depth 0.07–0.1; a cup on
/// a base with one to three toothbrushes leaning in it.
pub(crate) fn toothbrush_holder(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let cup = b.palette(Palette::Ceramic, rng);
    let r = uniform(rng, 0.032, 0.04);
    let ch = uniform(rng, 0.09, 0.11);
    b.frustum("base", cup, [0.0, 0.0], r, r, 0.0, 0.008, 20);
    b.ring(
        "wall",
        cup,
        [0.0, 0.0],
        (r - 0.004, r, 0.002),
        (r - 0.004, r, ch),
        20,
    );
    let n = int(rng, 1, 3);
    for k in 0..n {
        let a = std::f32::consts::TAU * (k as f32 / n as f32 + uniform(rng, 0.0, 0.1));
        let (cx, cz) = (a.cos(), a.sin());
        let m = b.material(
            &format!("brush_{k}"),
            color(
                rng,
                &[
                    [0.2, 0.4, 0.8],
                    [0.9, 0.3, 0.3],
                    [0.3, 0.7, 0.4],
                    [0.95, 0.95, 0.95],
                ],
                0.03,
            ),
            0.4,
        );
        let foot = [-0.4 * r * cx, 0.009, -0.4 * r * cz];
        let tip = [0.9 * r * cx, ch + 0.08, 0.9 * r * cz];
        b.tube(&format!("handle_{k}"), m, foot, tip, 0.005, 0.005, 8);
        b.ellipsoid(
            &format!("bristles_{k}"),
            m,
            [tip[0], tip[1] + 0.01, tip[2]],
            [0.006, 0.014, 0.006],
        );
    }
    b.finish(Placement::Surface, [0.9, 1.1])
}
