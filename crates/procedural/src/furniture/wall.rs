//! Wall and ceiling assets. Wall assets have their back face on the wall at −Z and face +Z;
//! like every asset their origin is the centre of the footprint at the lowest point. Ceiling
//! assets hang down from their top; their origin is at their lowest point as well.

use rand_chacha::ChaCha8Rng;

use super::{mat, mat_either};
use crate::materials::{fixed_material, Palette};
use crate::random::{coin, int, uniform};
use scenethesis_primitives::{
    cylinder, frustum, prism_z, rect_surface, regular_polygon, sphere, AssetBuilder,
};
use scenethesis_scene_graph::{Asset, Placement, SurfaceKind};

/// A rectangular frame of four bars around a panel (`w` × `h`, frame `bar` wide, `depth` deep),
/// with its back at z = 0.
fn framed_panel(
    b: &mut AssetBuilder,
    frame: usize,
    panel: usize,
    w: f32,
    h: f32,
    bar: f32,
    depth: f32,
) {
    let hw = 0.5 * w;
    b.cuboid("frame_bottom", frame, [-hw, 0.0, 0.0], [hw, bar, depth]);
    b.cuboid("frame_top", frame, [-hw, h - bar, 0.0], [hw, h, depth]);
    b.cuboid("frame_left", frame, [-hw, 0.0, 0.0], [-hw + bar, h, depth]);
    b.cuboid("frame_right", frame, [hw - bar, 0.0, 0.0], [hw, h, depth]);
    b.cuboid(
        "panel",
        panel,
        [-hw + bar - 0.001, bar - 0.001, 0.002],
        [hw - bar + 0.001, h - bar + 0.001, 0.6 * depth],
    );
}

/// Painting: width 0.3–1.5, height 0.3–1.2, depth 0.02–0.05; a framed canvas.
pub(super) fn painting(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat_either(&mut b, 0.6, Palette::Wood, Palette::Metal, rng);
    let canvas = mat(
        &mut b,
        match int(rng, 0, 3) {
            0 => Palette::Foliage,
            1 => Palette::BrightPlastic,
            2 => Palette::Fabric,
            _ => Palette::Paper,
        },
        rng,
    );
    let (w, h) = (uniform(rng, 0.3, 1.5), uniform(rng, 0.3, 1.2));
    framed_panel(
        &mut b,
        frame,
        canvas,
        w,
        h,
        uniform(rng, 0.02, 0.07).min(0.15 * w.min(h)),
        uniform(rng, 0.02, 0.05),
    );
    b.finish(Placement::Wall, [0.7, 1.3])
}

/// Whiteboard: width 0.9–2.4, height 0.6–1.2, depth 0.02–0.08 (with tray); an aluminium frame,
/// a white board and a marker tray.
pub(super) fn whiteboard(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat(&mut b, Palette::Metal, rng);
    let board = b.material(fixed_material("whiteboard", [0xF8, 0xF8, 0xF8], 0.15, 0.0));
    let (w, h) = (uniform(rng, 0.9, 2.4), uniform(rng, 0.6, 1.2));
    framed_panel(&mut b, frame, board, w, h, 0.02, 0.02);
    let tray_w = 0.6 * w;
    b.cuboid(
        "tray",
        frame,
        [-0.5 * tray_w, -0.02, 0.0],
        [0.5 * tray_w, 0.0, 0.08],
    );
    b.cuboid(
        "tray_lip",
        frame,
        [-0.5 * tray_w, -0.02, 0.07],
        [0.5 * tray_w, 0.01, 0.08],
    );
    b.top_surface(
        "tray",
        [-0.5 * tray_w, 0.02],
        [0.5 * tray_w, 0.07],
        0.0,
        0.005,
    );
    b.finish(Placement::Wall, [0.9, 1.1])
}

/// Wall shelf: width 0.5–1.2, height 0.03–0.75, depth 0.15–0.3; one to three floating boards
/// (lower boards are compartments under the ones above).
pub(super) fn wall_shelf(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let wood = mat_either(&mut b, 0.6, Palette::Wood, Palette::PaintedWood, rng);
    let bracket = mat(&mut b, Palette::CoatedMetal, rng);
    let (w, d) = (uniform(rng, 0.5, 1.2), uniform(rng, 0.15, 0.3));
    let hw = 0.5 * w;
    let boards = int(rng, 1, 3);
    let t = uniform(rng, 0.02, 0.035);
    let gap = uniform(rng, 0.25, 0.33);
    for i in 0..boards {
        let y = i as f32 * gap;
        b.cuboid(&format!("board_{i}"), wood, [-hw, y, 0.0], [hw, y + t, d]);
        for (k, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
            let x = sx * (hw - 0.08);
            b.cuboid(
                &format!("bracket_{i}_{k}"),
                bracket,
                [x - 0.01, y - 0.06, 0.0],
                [x + 0.01, y + 0.001, 0.7 * d],
            );
        }
        let last = i + 1 == boards;
        b.surface(rect_surface(
            &format!("board_{i}"),
            if last {
                SurfaceKind::Top
            } else {
                SurfaceKind::Shelf
            },
            [-hw, 0.0],
            [hw, d],
            y + t,
            (!last).then_some(gap - t - 0.005),
            0.02,
        ));
    }
    b.finish(Placement::Wall, [0.85, 1.15])
}

/// Mirror: width 0.3–1.0, height 0.4–1.6, depth 0.015–0.04; a rectangular or oval glass in a
/// frame.
pub(super) fn mirror(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat_either(&mut b, 0.5, Palette::Wood, Palette::Metal, rng);
    let glass = b.material(fixed_material("mirror", [0xE8, 0xEC, 0xEE], 0.02, 1.0));
    let (w, h) = (uniform(rng, 0.3, 1.0), uniform(rng, 0.4, 1.6));
    let depth = uniform(rng, 0.015, 0.04);
    if coin(rng, 0.3) {
        let outline: Vec<[f32; 2]> = regular_polygon([0.0, 0.0], 1.0, 32)
            .into_iter()
            .map(|p| [0.5 * w * p[0], 0.5 * h + 0.5 * h * p[1]])
            .collect();
        let inner: Vec<[f32; 2]> = outline
            .iter()
            .map(|p| [0.9 * p[0], 0.5 * h + 0.9 * (p[1] - 0.5 * h)])
            .collect();
        b.part(prism_z("frame", frame, &outline, 0.0, 0.6 * depth));
        b.part(prism_z("glass", glass, &inner, 0.0, depth));
    } else {
        framed_panel(&mut b, frame, glass, w, h, uniform(rng, 0.02, 0.06), depth);
    }
    b.finish(Placement::Wall, [0.8, 1.2])
}

/// Pendant lamp: width 0.2–0.6, height 0.45–1.3 (with cord), depth 0.2–0.6; a ceiling canopy,
/// a cord and a drum, cone or globe shade.
pub(super) fn pendant_lamp(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let metal = mat_either(&mut b, 0.5, Palette::Metal, Palette::CoatedMetal, rng);
    let shade_m = mat(
        &mut b,
        match int(rng, 0, 2) {
            0 => Palette::Glass,
            1 => Palette::Paper,
            _ => Palette::CoatedMetal,
        },
        rng,
    );
    let bulb = b.material(fixed_material("bulb", [0xFF, 0xF4, 0xD8], 0.1, 0.0));
    let cord = uniform(rng, 0.2, 0.8);
    let r = uniform(rng, 0.1, 0.3);
    let shade_h = uniform(rng, 0.15, 0.3).min(1.6 * r);
    let top = shade_h + cord + 0.04;
    b.part(cylinder(
        "canopy",
        metal,
        [0.0, 0.0],
        0.06,
        top - 0.04,
        top,
        16,
    ));
    b.part(cylinder(
        "cord",
        metal,
        [0.0, 0.0],
        0.004,
        shade_h - 0.01,
        top - 0.039,
        6,
    ));
    if coin(rng, 0.3) {
        b.part(sphere(
            "globe",
            shade_m,
            [0.0, 0.5 * shade_h, 0.0],
            0.5 * shade_h,
            12,
            18,
        ));
    } else {
        b.part(frustum(
            "shade",
            shade_m,
            [0.0, 0.0],
            r,
            0.35 * r,
            0.0,
            shade_h,
            24,
        ));
        b.part(sphere("bulb", bulb, [0.0, 0.3 * shade_h, 0.0], 0.03, 6, 10));
    }
    b.finish(Placement::Ceiling, [0.8, 1.2])
}
