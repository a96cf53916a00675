//! Household small items: remote control, phone, keys, alarm clock and printer. Fronts (screens,
//! dials, paper exits) face +Z.

use rand_chacha::ChaCha8Rng;

use super::builder::Builder;
use crate::materials::Palette;
use crate::random::{coin, color, int, uniform};
use scenethesis_primitives::{arc, prism_x, rect, rotated_box, rotation, rounded_box};
use scenethesis_scene_graph::{Asset, Placement};

const DARK_PLASTICS: &[[f32; 3]] = &[
    [0.05, 0.05, 0.055],
    [0.2, 0.2, 0.22],
    [0.85, 0.85, 0.83],
    [0.45, 0.47, 0.5],
];

/// Remote control: width 0.04–0.06, height 0.016–0.026, depth 0.14–0.22; a rounded bar with a
/// grid of buttons on top, lying with its buttons up and its infrared end toward −Z.
pub(crate) fn remote_control(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let case = b.material("case", color(rng, DARK_PLASTICS, 0.02), 0.5);
    let keys = b.material(
        "buttons",
        color(
            rng,
            &[[0.3, 0.3, 0.32], [0.7, 0.7, 0.7], [0.6, 0.1, 0.1]],
            0.03,
        ),
        0.6,
    );
    let (w, h, d) = (
        uniform(rng, 0.04, 0.06),
        uniform(rng, 0.014, 0.022),
        uniform(rng, 0.14, 0.22),
    );
    b.add(rounded_box(
        "case",
        case,
        [0.0, 0.5 * h, 0.0],
        [0.5 * w, 0.5 * h, 0.5 * d],
        0.3,
    ));
    let cols = 3;
    let rows = int(rng, 4, 7);
    for r in 0..rows {
        for c in 0..cols {
            let x = (c as f32 - 1.0) * 0.3 * w;
            let z = -0.35 * d + r as f32 * (0.65 * d) / rows as f32;
            b.frustum(
                &format!("button_{r}_{c}"),
                keys,
                [x, z],
                0.0045,
                0.004,
                h - 0.001,
                h + 0.003,
                8,
            );
        }
    }
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// Phone: a smartphone lying face up (width 0.065–0.08, height 0.008–0.012, depth 0.14–0.17),
/// or a desk telephone (width 0.18–0.24, height 0.08–0.11, depth 0.18–0.22) with a handset on a
/// sloped base and a keypad.
pub(crate) fn phone(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let case = b.material("case", color(rng, DARK_PLASTICS, 0.03), 0.35);
    let screen = b.material("screen", [0.02, 0.02, 0.03], 0.05);
    if coin(rng, 0.65) {
        let (w, h, d) = (
            uniform(rng, 0.065, 0.08),
            uniform(rng, 0.008, 0.011),
            uniform(rng, 0.14, 0.17),
        );
        b.add(rounded_box(
            "body",
            case,
            [0.0, 0.5 * h, 0.0],
            [0.5 * w, 0.5 * h, 0.5 * d],
            0.3,
        ));
        b.cuboid(
            "screen",
            screen,
            [-0.5 * w + 0.003, h - 0.001, -0.5 * d + 0.004],
            [0.5 * w - 0.003, h + 0.0005, 0.5 * d - 0.004],
        );
    } else {
        let (w, d) = (uniform(rng, 0.18, 0.22), uniform(rng, 0.18, 0.21));
        let (front_h, back_h) = (0.04, uniform(rng, 0.06, 0.07));
        let hd = 0.5 * d;
        b.add(prism_x(
            "base",
            case,
            &[[-hd, 0.0], [hd, 0.0], [hd, front_h], [-hd, back_h]],
            -0.5 * w,
            0.5 * w,
        ));
        let keys = b.material("keys", [0.75, 0.75, 0.73], 0.6);
        let slope = (back_h - front_h) / d;
        for r in 0..4 {
            for c in 0..3 {
                let x = 0.5 * w - 0.085 + c as f32 * 0.022;
                let z = hd - 0.03 - r as f32 * 0.022;
                let y = front_h + slope * (hd - z);
                b.cuboid(
                    &format!("key_{r}_{c}"),
                    keys,
                    [x - 0.008, y - 0.003, z - 0.008],
                    [x + 0.008, y + 0.004, z + 0.008],
                );
            }
        }
        // Handset lying across the left part of the base.
        let hx = -0.5 * w + 0.045;
        let y = back_h + 0.002;
        b.add(rounded_box(
            "handset",
            case,
            [hx, y + 0.012, 0.0],
            [0.025, 0.014, 0.5 * d - 0.01],
            0.3,
        ));
    }
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// Keys: width 0.05–0.09, height 0.003–0.006, depth 0.05–0.09; a split ring with two to four
/// keys fanned out, lying flat.
pub(crate) fn keys(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let ring = b.metal("ring", [0.75, 0.75, 0.77], 0.25);
    let brass = b.metal("key_brass", [0.8, 0.65, 0.35], 0.3);
    let steel = b.metal("key_steel", [0.7, 0.71, 0.73], 0.3);
    let rr = uniform(rng, 0.01, 0.014);
    let wire = 0.0012;
    let pts = arc(
        [0.0, wire, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
        rr,
        0.0,
        std::f32::consts::TAU,
        14,
    );
    b.polyline("ring", ring, &pts, wire);
    let n = int(rng, 2, 4);
    let spread = uniform(rng, 0.5, 1.1);
    for k in 0..n {
        let a = std::f32::consts::FRAC_PI_2 + spread * (k as f32 - 0.5 * (n as f32 - 1.0));
        let (ux, uz) = (a.cos(), a.sin());
        let m = if coin(rng, 0.5) { brass } else { steel };
        let head_c = [ux * (rr + 0.012), 0.0015, uz * (rr + 0.012)];
        let len = uniform(rng, 0.03, 0.045);
        let rot = rotation([0.0, 1.0, 0.0], -a);
        b.add(rotated_box(
            &format!("key_head_{k}"),
            m,
            head_c,
            [0.011, 0.0015, 0.01],
            &rot,
        ));
        let blade_c = [
            ux * (rr + 0.022 + 0.5 * len),
            0.001,
            uz * (rr + 0.022 + 0.5 * len),
        ];
        b.add(rotated_box(
            &format!("key_blade_{k}"),
            m,
            blade_c,
            [0.5 * len + 0.002, 0.001, 0.0035],
            &rot,
        ));
    }
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// Alarm clock: width 0.1–0.16, height 0.07–0.17, depth 0.05–0.08; a twin-bell clock on two
/// legs with a dial toward +Z, or a digital block with a dark display.
pub(crate) fn alarm_clock(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let case = b.material(
        "case",
        color(
            rng,
            &[
                [0.75, 0.1, 0.1],
                [0.1, 0.1, 0.1],
                [0.85, 0.85, 0.82],
                [0.2, 0.4, 0.7],
                [0.8, 0.65, 0.3],
            ],
            0.03,
        ),
        0.35,
    );
    let ink = b.material("ink", [0.03, 0.03, 0.03], 0.4);
    if coin(rng, 0.55) {
        let r = uniform(rng, 0.045, 0.06);
        let depth = uniform(rng, 0.035, 0.05);
        let leg = 0.012;
        let cy = leg + r;
        let face = b.material("dial", [0.96, 0.95, 0.9], 0.6);
        b.tube(
            "body",
            case,
            [0.0, cy, -0.5 * depth],
            [0.0, cy, 0.5 * depth],
            r,
            r,
            24,
        );
        b.tube(
            "dial",
            face,
            [0.0, cy, 0.5 * depth - 0.001],
            [0.0, cy, 0.5 * depth + 0.002],
            0.85 * r,
            0.85 * r,
            24,
        );
        for (i, sx) in [-1.0f32, 1.0].iter().enumerate() {
            let a = 0.75f32;
            b.ellipsoid(
                &format!("bell_{i}"),
                case,
                [sx * r * a.sin(), cy + r * a.cos() + 0.004, 0.0],
                [0.45 * r, 0.3 * r, 0.45 * r],
            );
            b.cuboid(
                &format!("leg_{i}"),
                case,
                [sx * 0.6 * r - 0.006, 0.0, -0.5 * depth],
                [sx * 0.6 * r + 0.006, cy - 0.8 * r, 0.5 * depth],
            );
        }
        for (name, len, angle) in [
            (
                "hour_hand",
                0.4 * r,
                uniform(rng, 0.0, std::f32::consts::TAU),
            ),
            (
                "minute_hand",
                0.65 * r,
                uniform(rng, 0.0, std::f32::consts::TAU),
            ),
        ] {
            let rot = rotation([0.0, 0.0, 1.0], -angle);
            let off = rot * nalgebra::Vector3::new(0.0, 0.5 * len, 0.0);
            b.add(rotated_box(
                name,
                ink,
                [off.x, cy + off.y, 0.5 * depth + 0.0028],
                [0.0025, 0.5 * len, 0.0008],
                &rot,
            ));
        }
    } else {
        let (w, h, d) = (
            uniform(rng, 0.1, 0.16),
            uniform(rng, 0.07, 0.1),
            uniform(rng, 0.05, 0.08),
        );
        let hd = 0.5 * d;
        b.add(prism_x(
            "body",
            case,
            &[[-hd, 0.0], [hd, 0.0], [hd - 0.012, h], [-hd, h]],
            -0.5 * w,
            0.5 * w,
        ));
        let lit = b.material("digits", [0.9, 0.15, 0.1], 0.2);
        let slope = 0.012 / h;
        let (y0, y1) = (0.2 * h, 0.8 * h);
        b.add(prism_x(
            "display",
            ink,
            &[
                [hd - slope * y0 - 0.001, y0],
                [hd - slope * y0 + 0.003, y0],
                [hd - slope * y1 + 0.003, y1],
                [hd - slope * y1 - 0.001, y1],
            ],
            -0.5 * w + 0.012,
            0.5 * w - 0.012,
        ));
        let ym = 0.5 * (y0 + y1);
        b.cuboid(
            "digits",
            lit,
            [-0.3 * w, ym - 0.012, hd - slope * ym + 0.002],
            [0.3 * w, ym + 0.012, hd - slope * ym + 0.0045],
        );
    }
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// Printer: width 0.38–0.5, height 0.16–0.34 (with the paper support), depth 0.3–0.45; a body
/// with a control panel, a paper support standing up at the back and an output tray at the
/// front; usable top in front of the support.
pub(crate) fn printer(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let body = b.material("printer", color(rng, DARK_PLASTICS, 0.02), 0.45);
    let panel = b.palette(Palette::Plastic, rng);
    let screen = b.material("screen", [0.05, 0.08, 0.1], 0.1);
    let (w, h, d) = (
        uniform(rng, 0.38, 0.5),
        uniform(rng, 0.14, 0.22),
        uniform(rng, 0.3, 0.4),
    );
    let (hw, hd) = (0.5 * w, 0.5 * d);
    b.cuboid("body", body, [-hw, 0.0, -hd], [hw, h, hd]);
    b.cuboid(
        "output_tray",
        panel,
        [-0.3 * w, 0.04, hd - 0.001],
        [0.3 * w, 0.05, hd + uniform(rng, 0.04, 0.08)],
    );
    b.cuboid(
        "panel",
        panel,
        [hw - 0.14, h - 0.05, hd - 0.001],
        [hw - 0.02, h - 0.01, hd + 0.006],
    );
    b.cuboid(
        "screen",
        screen,
        [hw - 0.12, h - 0.04, hd + 0.005],
        [hw - 0.06, h - 0.02, hd + 0.008],
    );
    let support = uniform(rng, 0.06, 0.12);
    b.add(prism_x(
        "paper_support",
        panel,
        &[
            [-hd + 0.01, h - 0.001],
            [-hd + 0.03, h - 0.001],
            [-hd - 0.01, h + support],
            [-hd - 0.02, h + support],
        ],
        -0.35 * w,
        0.35 * w,
    ));
    b.top("top", rect(-hw + 0.03, -hd + 0.06, hw - 0.03, hd - 0.03), h);
    b.finish(Placement::Surface, [0.9, 1.1])
}
