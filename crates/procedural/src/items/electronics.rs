//! Electronics: laptops, monitors, keyboards, televisions and cash registers. Screens face +Z.

use rand_chacha::ChaCha8Rng;

use super::builder::Builder;
use crate::articulation;
use crate::random::{color, uniform, uniform3};
use scenethesis_primitives::{convex_hull, rotated_box, rotation};
use scenethesis_scene_graph::{Asset, Placement};

const CASES: &[[f32; 3]] = &[
    [0.12, 0.12, 0.13],
    [0.7, 0.7, 0.72],
    [0.85, 0.85, 0.86],
    [0.25, 0.26, 0.3],
];

/// Open laptop, lid at 100–120° on a hinge (state 0 as drawn, folding shut at its lower limit): 0.30–0.38 wide × 0.21–0.26 deep, base 0.015–0.02 thick.
pub(crate) fn laptop(rng: &mut ChaCha8Rng) -> Asset {
    let (w, d, t) = uniform3(rng, [0.3, 0.38], [0.21, 0.26], [0.015, 0.02]);
    let open = uniform(rng, 1.75, 2.1);
    let mut b = Builder::new();
    let shell = b.metal("shell", color(rng, CASES, 0.02), 0.35);
    let keys = b.material("keys", [0.05, 0.05, 0.06], 0.6);
    let screen = b.material("screen", [0.02, 0.03, 0.05], 0.05);
    let (x, z) = (w / 2.0, d / 2.0);
    b.cuboid("base", shell, [-x, 0.0, -z], [x, t, z]);
    b.cuboid(
        "keyboard",
        keys,
        [-x + 0.02, t, -z + 0.02],
        [x - 0.02, t + 0.001, -z + d * 0.5],
    );
    b.cuboid(
        "touchpad",
        keys,
        [-0.05, t, -z + d * 0.58],
        [0.05, t + 0.0008, z - 0.015],
    );
    // Lid hinged at the back edge, rotated back from closed by `open` radians.
    let lt = 0.006;
    let rot = rotation([1.0, 0.0, 0.0], -(open - std::f32::consts::FRAC_PI_2));
    let hinge = nalgebra::Vector3::new(0.0, t, -z);
    // State 0 is the pose drawn; the screen folds shut by `open` (less a little) and leans
    // back a little further.
    b.joint(scenethesis_scene_graph::Joint {
        limits: [-(open - 0.03), 0.35],
        ..articulation::back_hinge("screen", t, -z, 0.35)
    });
    b.link(Some("screen"));
    let lid_center = hinge + rot * nalgebra::Vector3::new(0.0, d / 2.0, -lt / 2.0);
    b.add(rotated_box(
        "lid",
        shell,
        lid_center.into(),
        [x, d / 2.0, lt / 2.0],
        &rot,
    ));
    let display_center = hinge + rot * nalgebra::Vector3::new(0.0, d / 2.0, 0.0008);
    b.add(rotated_box(
        "display",
        screen,
        display_center.into(),
        [x - 0.012, d / 2.0 - 0.015, 0.0008],
        &rot,
    ));
    b.link(None);
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// Desktop monitor on a stand: 16:9 panel 0.48–0.72 wide, 0.38–0.55 m high overall.
pub(crate) fn monitor(rng: &mut ChaCha8Rng) -> Asset {
    let w = uniform(rng, 0.48, 0.72);
    let ph = w * 9.0 / 16.0 + 0.02;
    let t = uniform(rng, 0.02, 0.05);
    let lift = uniform(rng, 0.08, 0.13);
    let mut b = Builder::new();
    let case = b.material("bezel", color(rng, CASES, 0.02), 0.4);
    let screen = b.material("screen", [0.02, 0.03, 0.05], 0.05);
    let (x, bd) = (w / 2.0, uniform(rng, 0.09, 0.12));
    b.cuboid(
        "stand_base",
        case,
        [-0.11, 0.0, -bd - 0.02],
        [0.11, 0.012, bd - 0.02],
    );
    b.cuboid(
        "stand_neck",
        case,
        [-0.025, 0.01, -0.06],
        [0.025, lift + ph * 0.5, -0.04],
    );
    b.cuboid("panel", case, [-x, lift, -0.04], [x, lift + ph, -0.04 + t]);
    b.cuboid(
        "display",
        screen,
        [-x + 0.008, lift + 0.015, -0.04 + t],
        [x - 0.008, lift + ph - 0.008, -0.04 + t + 0.001],
    );
    b.finish(Placement::Surface, [0.85, 1.2])
}

/// Computer keyboard with individual keys: 0.35–0.46 × 0.12–0.16 × 0.02–0.035 m.
pub(crate) fn keyboard(rng: &mut ChaCha8Rng) -> Asset {
    let (w, d) = (uniform(rng, 0.35, 0.46), uniform(rng, 0.12, 0.16));
    let t = uniform(rng, 0.012, 0.02);
    let mut b = Builder::new();
    let case = b.material("keyboard_case", color(rng, CASES, 0.02), 0.5);
    let keys = b.material(
        "keycaps",
        color(
            rng,
            &[[0.08, 0.08, 0.09], [0.9, 0.9, 0.9], [0.5, 0.5, 0.52]],
            0.02,
        ),
        0.6,
    );
    let (x, z) = (w / 2.0, d / 2.0);
    let back_t = t + uniform(rng, 0.0, 0.006);
    let shell = [
        [-x, 0.0, -z],
        [x, 0.0, -z],
        [-x, 0.0, z],
        [x, 0.0, z],
        [-x, back_t, -z],
        [x, back_t, -z],
        [-x, t * 0.6, z],
        [x, t * 0.6, z],
    ];
    b.add(convex_hull("case", case, &shell).expect("keyboard case has volume"));
    let rows = 5;
    let pitch_z = (d - 0.02) / rows as f32;
    let cols = ((w - 0.02) / 0.019).floor() as usize;
    let pitch_x = (w - 0.02) / cols as f32;
    for r in 0..rows {
        let zc = -z + 0.01 + (r as f32 + 0.5) * pitch_z;
        let top = back_t + (t * 0.6 - back_t) * (zc + z) / d;
        if r == rows - 1 {
            // Space bar row: modifiers and a long bar.
            b.cuboid(
                "space_bar",
                keys,
                [-pitch_x * 3.0, top - 0.002, zc - pitch_z * 0.4],
                [pitch_x * 3.0, top + 0.006, zc + pitch_z * 0.4],
            );
            continue;
        }
        for c in 0..cols {
            let xc = -x + 0.01 + (c as f32 + 0.5) * pitch_x;
            b.cuboid(
                &format!("key_{r}_{c}"),
                keys,
                [xc - pitch_x * 0.42, top - 0.002, zc - pitch_z * 0.42],
                [xc + pitch_x * 0.42, top + 0.006, zc + pitch_z * 0.42],
            );
        }
    }
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// Flat-screen television on a pedestal or two feet: 32–65" (0.72–1.45 m wide).
pub(crate) fn television(rng: &mut ChaCha8Rng) -> Asset {
    let w = uniform(rng, 0.72, 1.45);
    let ph = w * 9.0 / 16.0 + 0.02;
    let t = uniform(rng, 0.04, 0.08);
    let lift = uniform(rng, 0.05, 0.09);
    let mut b = Builder::new();
    let case = b.material(
        "tv_case",
        color(
            rng,
            &[[0.05, 0.05, 0.06], [0.2, 0.2, 0.22], [0.6, 0.6, 0.62]],
            0.02,
        ),
        0.4,
    );
    let screen = b.material("screen", [0.01, 0.015, 0.02], 0.05);
    let x = w / 2.0;
    let depth = uniform(rng, 0.2, 0.3).max(w * 0.18);
    if uniform(rng, 0.0, 1.0) < 0.5 {
        b.cuboid(
            "pedestal",
            case,
            [-w * 0.15, 0.0, -depth / 2.0],
            [w * 0.15, 0.015, depth / 2.0],
        );
        b.cuboid("neck", case, [-0.04, 0.01, -0.03], [0.04, lift + 0.1, 0.0]);
    } else {
        for (i, sx) in [-1.0f32, 1.0].iter().enumerate() {
            let fx = sx * x * 0.8;
            let foot = [
                [fx - 0.03, 0.0, -depth / 2.0],
                [fx + 0.03, 0.0, -depth / 2.0],
                [fx - 0.03, 0.0, depth / 2.0],
                [fx + 0.03, 0.0, depth / 2.0],
                [fx - 0.02, lift + 0.06, -0.01],
                [fx + 0.02, lift + 0.06, -0.01],
                [fx - 0.02, lift + 0.06, 0.01],
                [fx + 0.02, lift + 0.06, 0.01],
            ];
            b.add(convex_hull(&format!("foot_{i}"), case, &foot).expect("foot has volume"));
        }
    }
    b.cuboid("panel", case, [-x, lift, -t / 2.0], [x, lift + ph, t / 2.0]);
    b.cuboid(
        "display",
        screen,
        [-x + 0.01, lift + 0.02, t / 2.0],
        [x - 0.01, lift + ph - 0.01, t / 2.0 + 0.001],
    );
    b.finish(Placement::Surface, [0.9, 1.1])
}

/// Point-of-sale cash register: drawer base, sloped keypad, customer display: 0.33–0.42 wide.
pub(crate) fn cash_register(rng: &mut ChaCha8Rng) -> Asset {
    let (w, d) = (uniform(rng, 0.33, 0.42), uniform(rng, 0.36, 0.44));
    let mut b = Builder::new();
    let case = b.material("register_case", color(rng, CASES, 0.02), 0.45);
    let keys = b.material("keypad", [0.15, 0.15, 0.16], 0.6);
    let screen = b.material("display", [0.1, 0.3, 0.25], 0.1);
    let (x, z) = (w / 2.0, d / 2.0);
    let drawer_h = uniform(rng, 0.09, 0.12);
    b.cuboid("drawer", case, [-x, 0.0, -z], [x, drawer_h, z]);
    let top = [
        [-x, drawer_h, -z],
        [x, drawer_h, -z],
        [-x, drawer_h, z],
        [x, drawer_h, z],
        [-x, drawer_h + 0.12, -z],
        [x, drawer_h + 0.12, -z],
        [-x, drawer_h + 0.04, z * 0.2],
        [x, drawer_h + 0.04, z * 0.2],
    ];
    b.add(convex_hull("console", case, &top).expect("console has volume"));
    let slope = rotation([1.0, 0.0, 0.0], (0.08f32 / (z * 1.2)).atan());
    b.add(rotated_box(
        "keypad",
        keys,
        [0.0, drawer_h + 0.08, -z * 0.4],
        [x * 0.7, 0.004, z * 0.45],
        &slope,
    ));
    b.cuboid(
        "pole",
        case,
        [-0.015, drawer_h + 0.1, -z + 0.02],
        [0.015, drawer_h + 0.25, -z + 0.05],
    );
    b.cuboid(
        "customer_display",
        screen,
        [-0.08, drawer_h + 0.24, -z + 0.01],
        [0.08, drawer_h + 0.3, -z + 0.06],
    );
    b.finish(Placement::Surface, [0.9, 1.1])
}
