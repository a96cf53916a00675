//! Beds and care furniture. A bed's head is at −Z and its foot at +Z (the sleeper faces +Z).

use std::f32::consts::TAU;

use rand_chacha::ChaCha8Rng;

use super::carcass::CORNERS;
use super::{mat, mat_either, SCALE};
use crate::materials::{fixed_material, Palette};
use crate::random::{coin, int, uniform};
use scenethesis_primitives::{beam, box_yaw, cylinder, ellipsoid, square_post, AssetBuilder};
use scenethesis_scene_graph::{Asset, Placement};

/// Bed: width 0.9–1.9 (single to king), height 0.85–1.3 (headboard), length 2.0–2.25; frame on
/// legs, mattress top 0.45–0.62, pillows, headboard, optional footboard.
pub(super) fn bed(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat_either(&mut b, 0.6, Palette::Wood, Palette::Fabric, rng);
    let sheet = mat_either(&mut b, 0.5, Palette::Paper, Palette::Fabric, rng);
    let pillow = b.material(fixed_material("pillow_white", [0xF2, 0xF0, 0xEA], 0.9, 0.0));
    let sizes = [0.9f32, 1.2, 1.4, 1.6, 1.8];
    let mattress_w = sizes[int(rng, 0, sizes.len() - 1)];
    let mattress_l = uniform(rng, 1.9, 2.05);
    let w = mattress_w + 0.08;
    let l = mattress_l + 0.1;
    let (hw, hl) = (0.5 * w, 0.5 * l);
    let leg_h = uniform(rng, 0.08, 0.25);
    let rail_top = leg_h + uniform(rng, 0.15, 0.22);
    let top = rail_top + uniform(rng, 0.18, 0.26) - 0.04;
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        b.part(square_post(
            &format!("leg_{i}"),
            frame,
            [sx * (hw - 0.03), sz * (hl - 0.03)],
            0.06,
            0.0,
            leg_h + 0.002,
        ));
    }
    b.cuboid("frame", frame, [-hw, leg_h, -hl], [hw, rail_top, hl]);
    let (mw, ml) = (0.5 * mattress_w, 0.5 * mattress_l);
    let mz = hl - 0.04 - ml;
    b.cuboid(
        "mattress",
        sheet,
        [-mw, rail_top - 0.04, mz - ml],
        [mw, top, mz + ml],
    );
    let head_h = uniform(rng, 0.85, 1.3);
    b.cuboid(
        "headboard",
        frame,
        [-hw, leg_h, -hl - 0.06],
        [hw, head_h, -hl + 0.005],
    );
    if coin(rng, 0.4) {
        b.cuboid(
            "footboard",
            frame,
            [-hw, leg_h, hl - 0.005],
            [hw, top + uniform(rng, 0.05, 0.2), hl + 0.05],
        );
    }
    let pillows = if mattress_w >= 1.2 { 2 } else { 1 };
    let pw = mattress_w / pillows as f32;
    for i in 0..pillows {
        let x = -mw + (i as f32 + 0.5) * pw;
        b.part(ellipsoid(
            &format!("pillow_{i}"),
            pillow,
            [x, top + 0.05, mz - ml + 0.25],
            [0.4 * pw, 0.07, 0.2],
            8,
            14,
        ));
    }
    b.top_surface("mattress", [-mw, mz - ml + 0.5], [mw, mz + ml], top, 0.05);
    b.finish(Placement::Floor, SCALE)
}

/// Hospital bed: width 0.95–1.05, height 0.9–1.2, length 2.1–2.3; frame on casters, mattress
/// 0.55–0.7 high, head and foot boards, side rails.
pub(super) fn hospital_bed(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat(&mut b, Palette::CoatedMetal, rng);
    let board = mat(&mut b, Palette::Plastic, rng);
    let sheet = b.material(fixed_material("sheet_white", [0xF0, 0xF2, 0xF2], 0.9, 0.0));
    let wheel = mat(&mut b, Palette::Rubber, rng);
    let (w, l) = (uniform(rng, 0.95, 1.05), uniform(rng, 2.1, 2.3));
    let (hw, hl) = (0.5 * w, 0.5 * l);
    let top = uniform(rng, 0.55, 0.7);
    let frame_y = top - 0.2;
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        let (x, z) = (sx * (hw - 0.08), sz * (hl - 0.1));
        b.part(ellipsoid(
            &format!("wheel_{i}"),
            wheel,
            [x, 0.06, z],
            [0.025, 0.06, 0.06],
            6,
            10,
        ));
        b.part(cylinder(
            &format!("caster_post_{i}"),
            frame,
            [x, z],
            0.02,
            0.1,
            frame_y - 0.1,
            8,
        ));
    }
    b.cuboid(
        "base_frame",
        frame,
        [-hw + 0.1, frame_y - 0.12, -hl + 0.15],
        [hw - 0.1, frame_y - 0.08, hl - 0.15],
    );
    for (i, sz) in [-1.0f32, 1.0].into_iter().enumerate() {
        b.cuboid(
            &format!("base_cross_{i}"),
            frame,
            [-hw + 0.05, frame_y - 0.12, sz * (hl - 0.1) - 0.025],
            [hw - 0.05, frame_y - 0.08, sz * (hl - 0.1) + 0.025],
        );
    }
    b.cuboid("deck", frame, [-hw, frame_y - 0.08, -hl], [hw, frame_y, hl]);
    b.cuboid(
        "mattress",
        sheet,
        [-hw + 0.03, frame_y - 0.005, -hl + 0.06],
        [hw - 0.03, top, hl - 0.06],
    );
    let head_h = uniform(rng, 0.9, 1.2);
    b.cuboid(
        "headboard",
        board,
        [-hw, frame_y - 0.08, -hl - 0.04],
        [hw, head_h, -hl + 0.002],
    );
    b.cuboid(
        "footboard",
        board,
        [-hw, frame_y - 0.08, hl - 0.002],
        [hw, top + 0.25, hl + 0.04],
    );
    let up = coin(rng, 0.5);
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let raised = up || i == 0;
        let (y0, y1) = if raised {
            (top + 0.02, top + 0.3)
        } else {
            (frame_y - 0.25, frame_y - 0.03)
        };
        let x = sx * (hw + 0.02);
        b.cuboid(
            &format!("side_rail_{i}"),
            board,
            [x - 0.015, y0, -hl + 0.25],
            [x + 0.015, y1, 0.2],
        );
    }
    b.top_surface(
        "mattress",
        [-hw + 0.03, -hl + 0.5],
        [hw - 0.03, hl - 0.06],
        top,
        0.05,
    );
    b.finish(Placement::Floor, SCALE)
}

/// IV stand: width 0.5–0.62, height 1.7–2.1, depth 0.5–0.62; a five-leg caster base, a pole
/// and a four-hook crown.
pub(super) fn iv_stand(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let metal = mat(&mut b, Palette::Metal, rng);
    let wheel = mat(&mut b, Palette::Rubber, rng);
    let h = uniform(rng, 1.7, 2.1);
    let r = uniform(rng, 0.25, 0.31);
    for i in 0..5 {
        let a = i as f32 / 5.0 * TAU;
        let (x, z) = (r * a.cos(), r * a.sin());
        b.part(beam(
            &format!("foot_{i}"),
            metal,
            [0.0, 0.07, 0.0],
            [x, 0.07, z],
            [0.025, 0.02],
        ));
        b.part(ellipsoid(
            &format!("caster_{i}"),
            wheel,
            [x, 0.03, z],
            [0.015, 0.03, 0.03],
            6,
            10,
        ));
    }
    b.part(cylinder(
        "pole",
        metal,
        [0.0, 0.0],
        0.012,
        0.05,
        h - 0.02,
        10,
    ));
    for i in 0..4 {
        let a = i as f32 / 4.0 * TAU;
        let tip = [0.13 * a.cos(), h - 0.06, 0.13 * a.sin()];
        b.part(beam(
            &format!("hook_arm_{i}"),
            metal,
            [0.0, h - 0.02, 0.0],
            tip,
            [0.008, 0.008],
        ));
        b.part(beam(
            &format!("hook_tip_{i}"),
            metal,
            tip,
            [tip[0], h, tip[2]],
            [0.008, 0.008],
        ));
    }
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// Privacy (folding) screen: width 1.2–2.0, height 1.6–1.85, depth 0.3–0.55; three or four
/// framed fabric panels folded in a zig-zag on small feet.
pub(super) fn privacy_screen(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat_either(&mut b, 0.5, Palette::Metal, Palette::Wood, rng);
    let cloth = mat(&mut b, Palette::Fabric, rng);
    let panels = int(rng, 3, 4);
    let pw = uniform(rng, 0.45, 0.55);
    let h = uniform(rng, 1.6, 1.85);
    let fold = uniform(rng, 0.3, 0.5);
    let mut x = 0.0f32;
    let mut points = Vec::new();
    for i in 0..=panels {
        let z = if i % 2 == 0 { 0.0 } else { pw * fold.sin() };
        points.push([x, z]);
        x += pw * fold.cos();
    }
    for (i, pair) in points.windows(2).enumerate() {
        let (a, c) = (pair[0], pair[1]);
        let yaw = -(c[1] - a[1]).atan2(c[0] - a[0]);
        let mid = [0.5 * (a[0] + c[0]), 0.5 * (a[1] + c[1])];
        let len = ((c[0] - a[0]).powi(2) + (c[1] - a[1]).powi(2)).sqrt();
        b.part(box_yaw(
            &format!("panel_fabric_{i}"),
            cloth,
            mid,
            [0.5 * len - 0.02, 0.008],
            0.1,
            h - 0.04,
            yaw,
        ));
        b.part(box_yaw(
            &format!("panel_top_{i}"),
            frame,
            mid,
            [0.5 * len, 0.015],
            h - 0.04,
            h,
            yaw,
        ));
        b.part(box_yaw(
            &format!("panel_bottom_{i}"),
            frame,
            mid,
            [0.5 * len, 0.015],
            0.06,
            0.1,
            yaw,
        ));
    }
    for (i, p) in points.iter().enumerate() {
        b.part(cylinder(
            &format!("hinge_post_{i}"),
            frame,
            *p,
            0.018,
            0.03,
            h,
            8,
        ));
        b.part(cylinder(
            &format!("foot_{i}"),
            frame,
            *p,
            0.03,
            0.0,
            0.032,
            8,
        ));
    }
    b.finish(Placement::Floor, [0.9, 1.1])
}
