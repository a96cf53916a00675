//! Laboratory and clinic items: beakers, flasks, test-tube racks, microscopes and patient
//! monitors.

use rand_chacha::ChaCha8Rng;

use super::builder::Builder;
use crate::random::{color, uniform, uniform3};
use scenethesis_primitives::{disc, rotation};
use scenethesis_scene_graph::{Asset, Placement};

/// Glass beaker with a spout, hollow: Ø 0.05–0.09, 0.07–0.13 m high.
pub(crate) fn beaker(rng: &mut ChaCha8Rng) -> Asset {
    let r = uniform(rng, 0.025, 0.045);
    let h = uniform(rng, 0.07, 0.13).max(r * 1.3);
    let wall = 0.0018;
    let mut b = Builder::new();
    let glass = b.glass("borosilicate", [0.85, 0.93, 0.97], 0.3);
    let marks = b.material("graduation", [0.95, 0.95, 0.95], 0.5);
    b.frustum("base", glass, [0.0, 0.0], r, r, 0.0, 0.003, 24);
    b.ring(
        "wall",
        glass,
        [0.0, 0.0],
        (r - wall, r, 0.001),
        (r - wall, r, h),
        24,
    );
    b.cuboid(
        "spout",
        glass,
        [-0.006, h - 0.004, r - 0.001],
        [0.006, h, r + 0.004],
    );
    b.cuboid(
        "graduation",
        marks,
        [-0.004, h * 0.3, r - 0.0005],
        [0.004, h * 0.75, r + 0.0004],
    );
    b.interior(disc([0.0, 0.0], r - wall - 0.003, 12), 0.003);
    b.finish(Placement::Surface, [0.8, 1.3])
}

/// Erlenmeyer flask, hollow: conical body Ø 0.06–0.13 at the base, 0.10–0.20 m high.
pub(crate) fn flask(rng: &mut ChaCha8Rng) -> Asset {
    let rb = uniform(rng, 0.03, 0.065);
    let h = uniform(rng, 0.1, 0.2).max(rb * 2.2);
    let rn = rb * uniform(rng, 0.28, 0.35);
    let wall = 0.0018;
    let mut b = Builder::new();
    let glass = b.glass("borosilicate", [0.85, 0.93, 0.97], 0.3);
    let body_h = h * 0.72;
    b.frustum("base", glass, [0.0, 0.0], rb, rb, 0.0, 0.003, 24);
    b.ring(
        "body",
        glass,
        [0.0, 0.0],
        (rb - wall, rb, 0.001),
        (rn - wall, rn, body_h),
        24,
    );
    b.ring(
        "neck",
        glass,
        [0.0, 0.0],
        (rn - wall, rn, body_h - 0.001),
        (rn - wall, rn, h - 0.004),
        16,
    );
    b.ring(
        "lip",
        glass,
        [0.0, 0.0],
        (rn - wall, rn + 0.002, h - 0.004),
        (rn - wall, rn + 0.002, h),
        16,
    );
    if uniform(rng, 0.0, 1.0) < 0.5 {
        let liquid = b.material(
            "liquid",
            color(
                rng,
                &[
                    [0.2, 0.5, 0.9],
                    [0.9, 0.3, 0.2],
                    [0.3, 0.8, 0.3],
                    [0.9, 0.8, 0.2],
                ],
                0.05,
            ),
            0.1,
        );
        let fill = body_h * uniform(rng, 0.15, 0.4);
        let rf = rb - (rb - rn) * fill / body_h - wall - 0.0005;
        b.frustum(
            "liquid",
            liquid,
            [0.0, 0.0],
            rb - wall - 0.0005,
            rf,
            0.003,
            fill,
            24,
        );
    }
    b.finish(Placement::Surface, [0.8, 1.3])
}

/// Test-tube rack with a perforated top board and 3–8 tubes: 0.16–0.30 × 0.09–0.12 (h) × 0.06 m.
pub(crate) fn test_tube_rack(rng: &mut ChaCha8Rng) -> Asset {
    let holes = 4 + (uniform(rng, 0.0, 4.99) as usize);
    let pitch = uniform(rng, 0.022, 0.028);
    let w = holes as f32 * pitch + 0.03;
    let h = uniform(rng, 0.07, 0.09);
    let d = 0.06;
    let hole = 0.018;
    let mut b = Builder::new();
    let rack = b.material(
        "rack",
        color(
            rng,
            &[
                [0.9, 0.9, 0.9],
                [0.2, 0.45, 0.8],
                [0.85, 0.75, 0.2],
                [0.6, 0.45, 0.3],
            ],
            0.04,
        ),
        0.5,
    );
    let glass = b.glass("tube_glass", [0.85, 0.93, 0.97], 0.35);
    let (x, z) = (w / 2.0, d / 2.0);
    b.cuboid("base", rack, [-x, 0.0, -z], [x, 0.008, z]);
    b.cuboid("end_left", rack, [-x, 0.0, -z], [-x + 0.008, h, z]);
    b.cuboid("end_right", rack, [x - 0.008, 0.0, -z], [x, h, z]);
    // Top board: front and back strips plus bars between the holes.
    let (t0, t1) = (h - 0.008, h);
    b.cuboid("top_back", rack, [-x, t0, -z], [x, t1, -hole / 2.0]);
    b.cuboid("top_front", rack, [-x, t0, hole / 2.0], [x, t1, z]);
    let x0 = -(holes as f32 * pitch) / 2.0;
    for k in 0..=holes {
        let cx = x0 + k as f32 * pitch;
        let (a, bb) = (
            if k == 0 {
                -x
            } else {
                cx - (pitch - hole) / 2.0
            },
            if k == holes {
                x
            } else {
                cx + (pitch - hole) / 2.0
            },
        );
        b.cuboid(
            &format!("top_bar_{k}"),
            rack,
            [a, t0, -hole / 2.0],
            [bb, t1, hole / 2.0],
        );
    }
    let tubes = 3 + (uniform(rng, 0.0, (holes - 3) as f32 + 0.99) as usize).min(holes - 3);
    for k in 0..tubes {
        let cx = x0 + (k as f32 + 0.5) * pitch;
        let tube_r = hole / 2.0 - 0.002;
        let top = h + uniform(rng, 0.03, 0.06);
        b.frustum(
            &format!("tube_{k}"),
            glass,
            [cx, 0.0],
            tube_r * 0.6,
            tube_r,
            0.008,
            0.02,
            12,
        );
        b.ring(
            &format!("tube_{k}_wall"),
            glass,
            [cx, 0.0],
            (tube_r - 0.0012, tube_r, 0.018),
            (tube_r - 0.0012, tube_r, top),
            12,
        );
    }
    b.finish(Placement::Surface, [0.9, 1.15])
}

/// Compound light microscope: base, arm, stage, tilted head with eyepieces: 0.30–0.42 m high.
pub(crate) fn microscope(rng: &mut ChaCha8Rng) -> Asset {
    let s = uniform(rng, 0.3, 0.42) / 0.36;
    let mut b = Builder::new();
    let body = b.material(
        "enamel",
        color(
            rng,
            &[[0.92, 0.92, 0.9], [0.15, 0.15, 0.16], [0.25, 0.35, 0.5]],
            0.03,
        ),
        0.4,
    );
    let metal = b.metal("optics_metal", [0.6, 0.6, 0.62], 0.3);
    let black = b.material("rubber", [0.05, 0.05, 0.05], 0.8);
    let v = |p: [f32; 3]| p.map(|c| c * s);
    b.cuboid("base", body, v([-0.08, 0.0, -0.11]), v([0.08, 0.035, 0.1]));
    b.cuboid("arm", body, v([-0.03, 0.035, -0.1]), v([0.03, 0.26, -0.05]));
    b.cuboid(
        "stage",
        body,
        v([-0.07, 0.11, -0.05]),
        v([0.07, 0.12, 0.07]),
    );
    b.cuboid(
        "stage_clip",
        metal,
        v([-0.04, 0.12, 0.02]),
        v([0.04, 0.123, 0.03]),
    );
    b.frustum(
        "condenser",
        metal,
        [0.0, 0.02 * s],
        0.02 * s,
        0.02 * s,
        0.07 * s,
        0.11 * s,
        16,
    );
    b.cuboid(
        "head_mount",
        body,
        v([-0.035, 0.22, -0.08]),
        v([0.035, 0.27, 0.03]),
    );
    b.frustum(
        "nosepiece",
        metal,
        [0.0, 0.02 * s],
        0.03 * s,
        0.025 * s,
        0.2 * s,
        0.22 * s,
        16,
    );
    for (i, dx) in [-0.015f32, 0.0, 0.015].iter().enumerate() {
        b.tube(
            &format!("objective_{i}"),
            metal,
            v([*dx, 0.2, 0.02]),
            v([*dx * 1.3, 0.15, 0.02]),
            0.007 * s,
            0.005 * s,
            10,
        );
    }
    let tilt = rotation([1.0, 0.0, 0.0], -0.7);
    let dir = tilt * nalgebra::Vector3::new(0.0, 0.09 * s, 0.0);
    for (i, dx) in [-0.016f32, 0.016].iter().enumerate() {
        let a = v([*dx, 0.265, -0.02]);
        let bb = [a[0], a[1] + dir.y, a[2] + dir.z];
        b.tube(
            &format!("eyepiece_{i}"),
            black,
            a,
            bb,
            0.011 * s,
            0.012 * s,
            12,
        );
    }
    b.tube(
        "focus_knobs",
        metal,
        v([-0.05, 0.16, -0.075]),
        v([0.05, 0.16, -0.075]),
        0.014 * s,
        0.014 * s,
        16,
    );
    b.finish(Placement::Surface, [0.9, 1.15])
}

/// Bedside patient monitor with a screen, handle and feet: 0.26–0.36 wide × 0.24–0.32 high.
pub(crate) fn patient_monitor(rng: &mut ChaCha8Rng) -> Asset {
    let (w, h, d) = uniform3(rng, [0.26, 0.36], [0.22, 0.28], [0.12, 0.18]);
    let mut b = Builder::new();
    let case = b.material(
        "case",
        color(
            rng,
            &[[0.9, 0.9, 0.88], [0.75, 0.78, 0.8], [0.3, 0.32, 0.35]],
            0.03,
        ),
        0.5,
    );
    let screen = b.material("screen", [0.02, 0.05, 0.04], 0.1);
    let trace = b.material("trace", [0.1, 0.9, 0.3], 0.3);
    let (x, z) = (w / 2.0, d / 2.0);
    let y0 = 0.015;
    for (i, sx) in [-1.0f32, 1.0].iter().enumerate() {
        b.cuboid(
            &format!("foot_{i}"),
            case,
            [sx * x * 0.8 - 0.02, 0.0, -z * 0.8],
            [sx * x * 0.8 + 0.02, y0, z * 0.8],
        );
    }
    b.cuboid("body", case, [-x, y0, -z], [x, y0 + h, z]);
    b.cuboid(
        "screen",
        screen,
        [-x + 0.02, y0 + 0.03, z - 0.002],
        [x * 0.55, y0 + h - 0.02, z + 0.002],
    );
    b.cuboid(
        "ecg_trace",
        trace,
        [-x + 0.035, y0 + h * 0.65, z + 0.002],
        [x * 0.5, y0 + h * 0.65 + 0.004, z + 0.003],
    );
    b.cuboid(
        "spo2_trace",
        trace,
        [-x + 0.035, y0 + h * 0.4, z + 0.002],
        [x * 0.5, y0 + h * 0.4 + 0.004, z + 0.003],
    );
    b.cuboid(
        "keypad",
        case,
        [x * 0.62, y0 + 0.03, z - 0.002],
        [x - 0.015, y0 + h * 0.6, z + 0.004],
    );
    b.cuboid(
        "handle",
        case,
        [-x * 0.5, y0 + h, -0.012],
        [x * 0.5, y0 + h + 0.025, 0.012],
    );
    b.finish(Placement::Surface, [0.9, 1.15])
}
