//! The table family (rectangular or round tops on four legs, a pedestal, trestles or panel
//! ends, with optional apron and lower shelf), desks with a knee hole, counters built on
//! carcasses, and the special tables (picnic, pool).
//!
//! Tables expose a `top` surface, a `lower_shelf` when they have one, and an `under` floor
//! region between the legs whose clearance reaches the lowest part above it.

use rand_chacha::ChaCha8Rng;

use super::carcass::{self, Carcass, CarcassMaterials, Feet, Front, CORNERS};
use super::{mat, mat_either, SCALE};
use crate::articulation::{self, DrawerBox};
use crate::materials::{fixed_material, Palette};
use crate::random::{coin, int, uniform, uniform3};
use scenethesis_primitives::{
    beam, cylinder, disc_surface, frustum, rect_surface, rod, square_post, strut, AssetBuilder,
};
use scenethesis_scene_graph::{Asset, Placement, SurfaceKind};

/// How a table top is held up.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Support {
    /// Four square legs of this section, inset from the top's edge.
    Legs { section: f32, inset: f32 },
    /// One central column on a round foot.
    Pedestal,
    /// Two end frames (post on a foot beam) joined by a high stretcher.
    Trestle,
    /// Two solid end panels of this thickness.
    Panels { thickness: f32 },
}

/// The parameters of a table.
#[derive(Debug, Clone, Copy)]
struct Table {
    width: f32,
    depth: f32,
    height: f32,
    top_thickness: f32,
    round: bool,
    support: Support,
    /// Apron depth below the top (0 for none).
    apron: f32,
    /// Height of the lower shelf's upper face.
    lower_shelf: Option<f32>,
}

/// The floor region under a table, between its legs or ends, as (min, max) in (x, z).
type UnderRegion = Option<([f32; 2], [f32; 2])>;

fn build_table(b: &mut AssetBuilder, t: &Table, top_m: usize, leg_m: usize) {
    table_top(b, t, top_m);
    let under_top = t.height - t.top_thickness;
    // Each support returns the lowest part above the floor and the floor region under it.
    let (lowest_above_floor, under) = match t.support {
        Support::Legs { section, inset } => table_legs(b, t, top_m, leg_m, section, inset),
        Support::Pedestal => {
            pedestal(b, t, leg_m);
            (under_top, None)
        }
        Support::Trestle => trestles(b, t, leg_m),
        Support::Panels { thickness } => end_panels(b, t, top_m, leg_m, thickness),
    };
    if let Some((min, max)) = under {
        let clearance = lowest_above_floor - 0.02;
        if clearance >= 0.08 {
            b.surface(rect_surface(
                "under",
                SurfaceKind::Under,
                min,
                max,
                0.0,
                Some(clearance),
                0.03,
            ));
        }
    }
}

/// The top, round or rectangular, with its support surface.
fn table_top(b: &mut AssetBuilder, t: &Table, top_m: usize) {
    let (hw, hd, h) = (0.5 * t.width, 0.5 * t.depth, t.height);
    let under_top = h - t.top_thickness;
    if t.round {
        b.part(cylinder("top", top_m, [0.0, 0.0], hw, under_top, h, 40));
        b.surface(disc_surface(
            "top",
            SurfaceKind::Top,
            [0.0, 0.0],
            hw - 0.04,
            h,
            None,
            12,
        ));
    } else {
        b.cuboid("top", top_m, [-hw, under_top, -hd], [hw, h, hd]);
        b.top_surface("top", [-hw, -hd], [hw, hd], h, 0.03);
    }
}

/// Four legs inset from the top's edge (within the inscribed square of a round top), with the
/// apron and the lower shelf when the table has them.
fn table_legs(
    b: &mut AssetBuilder,
    t: &Table,
    top_m: usize,
    leg_m: usize,
    section: f32,
    inset: f32,
) -> (f32, UnderRegion) {
    let (hw, hd) = (0.5 * t.width, 0.5 * t.depth);
    let under_top = t.height - t.top_thickness;
    // Leg footprint: the rectangle the legs stand on (inner faces).
    let (fx, fz) = if t.round {
        (0.707 * hw, 0.707 * hd)
    } else {
        (hw, hd)
    };
    let mut lowest_above_floor = under_top;
    let (lx, lz) = (fx - inset - 0.5 * section, fz - inset - 0.5 * section);
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        b.part(square_post(
            &format!("leg_{i}"),
            leg_m,
            [sx * lx, sz * lz],
            section,
            0.0,
            under_top + 0.002,
        ));
    }
    if t.apron > 0.0 {
        let y0 = under_top - t.apron;
        let a = 0.02;
        b.cuboid(
            "apron_back",
            leg_m,
            [-lx, y0, -lz - 0.5 * a],
            [lx, under_top + 0.001, -lz + 0.5 * a],
        );
        b.cuboid(
            "apron_front",
            leg_m,
            [-lx, y0, lz - 0.5 * a],
            [lx, under_top + 0.001, lz + 0.5 * a],
        );
        b.cuboid(
            "apron_left",
            leg_m,
            [-lx - 0.5 * a, y0, -lz],
            [-lx + 0.5 * a, under_top + 0.001, lz],
        );
        b.cuboid(
            "apron_right",
            leg_m,
            [lx - 0.5 * a, y0, -lz],
            [lx + 0.5 * a, under_top + 0.001, lz],
        );
        lowest_above_floor = y0;
    }
    let (ix, iz) = (lx - 0.5 * section, lz - 0.5 * section);
    if let Some(shelf_y) = t.lower_shelf {
        let st = 0.02;
        b.cuboid(
            "lower_shelf",
            top_m,
            [-lx, shelf_y - st, -lz],
            [lx, shelf_y, lz],
        );
        b.surface(rect_surface(
            "lower_shelf",
            SurfaceKind::Shelf,
            [-ix, -iz],
            [ix, iz],
            shelf_y,
            Some(lowest_above_floor - shelf_y - 0.01),
            0.02,
        ));
        lowest_above_floor = shelf_y - st;
    }
    (lowest_above_floor, Some(([-ix, -iz], [ix, iz])))
}

/// One central column on a round foot.
fn pedestal(b: &mut AssetBuilder, t: &Table, leg_m: usize) {
    let under_top = t.height - t.top_thickness;
    let r = (0.12 * t.width).clamp(0.04, 0.07);
    b.part(cylinder(
        "column",
        leg_m,
        [0.0, 0.0],
        r,
        0.03,
        under_top + 0.002,
        16,
    ));
    b.part(frustum(
        "foot",
        leg_m,
        [0.0, 0.0],
        0.32 * t.width.min(t.depth) + 0.05,
        r,
        0.0,
        0.06,
        24,
    ));
}

/// Two end frames (post on a foot beam, under a head) joined by a high stretcher.
fn trestles(b: &mut AssetBuilder, t: &Table, leg_m: usize) -> (f32, UnderRegion) {
    let (hw, hd) = (0.5 * t.width, 0.5 * t.depth);
    let under_top = t.height - t.top_thickness;
    let post = 0.06;
    let x = hw - 0.12;
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        b.cuboid(
            &format!("trestle_post_{i}"),
            leg_m,
            [sx * x - 0.5 * post, 0.04, -0.5 * post],
            [sx * x + 0.5 * post, under_top + 0.002, 0.5 * post],
        );
        b.cuboid(
            &format!("trestle_foot_{i}"),
            leg_m,
            [sx * x - 0.04, 0.0, -hd + 0.05],
            [sx * x + 0.04, 0.06, hd - 0.05],
        );
        b.cuboid(
            &format!("trestle_head_{i}"),
            leg_m,
            [sx * x - 0.04, under_top - 0.05, -hd + 0.05],
            [sx * x + 0.04, under_top + 0.001, hd - 0.05],
        );
    }
    let y = under_top - 0.12;
    b.cuboid("stretcher", leg_m, [-x, y - 0.05, -0.025], [x, y, 0.025]);
    (
        y - 0.05,
        Some(([-x + 0.5 * post, -hd + 0.06], [x - 0.5 * post, hd - 0.06])),
    )
}

/// Two solid end panels, with the lower shelf between them when the table has one.
fn end_panels(
    b: &mut AssetBuilder,
    t: &Table,
    top_m: usize,
    leg_m: usize,
    thickness: f32,
) -> (f32, UnderRegion) {
    let (hw, hd) = (0.5 * t.width, 0.5 * t.depth);
    let under_top = t.height - t.top_thickness;
    let mut lowest_above_floor = under_top;
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x0 = if sx < 0.0 { -hw } else { hw - thickness };
        b.cuboid(
            &format!("end_panel_{i}"),
            leg_m,
            [x0, 0.0, -hd],
            [x0 + thickness, under_top + 0.002, hd],
        );
    }
    if let Some(shelf_y) = t.lower_shelf {
        b.cuboid(
            "lower_shelf",
            top_m,
            [-hw + thickness - 0.001, shelf_y - 0.02, -hd],
            [hw - thickness + 0.001, shelf_y, hd],
        );
        b.surface(rect_surface(
            "lower_shelf",
            SurfaceKind::Shelf,
            [-hw + thickness, -hd],
            [hw - thickness, hd],
            shelf_y,
            Some(under_top - shelf_y - 0.01),
            0.02,
        ));
        lowest_above_floor = shelf_y - 0.02;
    }
    (
        lowest_above_floor,
        Some(([-hw + thickness, -hd], [hw - thickness, hd])),
    )
}

fn table_materials(rng: &mut ChaCha8Rng, b: &mut AssetBuilder) -> (usize, usize) {
    let top = match int(rng, 0, 5) {
        0 => mat(b, Palette::Stone, rng),
        1 => mat(b, Palette::Glass, rng),
        2 => mat(b, Palette::PaintedWood, rng),
        _ => mat(b, Palette::Wood, rng),
    };
    let legs = if coin(rng, 0.5) {
        mat(b, Palette::Wood, rng)
    } else {
        mat(b, Palette::CoatedMetal, rng)
    };
    (top, legs)
}

/// Coffee table: width 0.8–1.3, height 0.36–0.47, depth 0.5–0.8 (round: diameter 0.7–1.0);
/// optional lower shelf.
pub(super) fn coffee_table(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let (top, legs) = table_materials(rng, &mut b);
    let round = coin(rng, 0.35);
    let width = if round {
        uniform(rng, 0.7, 1.0)
    } else {
        uniform(rng, 0.9, 1.3)
    };
    let panels = !round && coin(rng, 0.25);
    let t = Table {
        width,
        depth: if round { width } else { uniform(rng, 0.5, 0.7) },
        height: uniform(rng, 0.38, 0.46),
        top_thickness: uniform(rng, 0.02, 0.05),
        round,
        support: if panels {
            Support::Panels {
                thickness: uniform(rng, 0.03, 0.06),
            }
        } else {
            Support::Legs {
                section: uniform(rng, 0.03, 0.05),
                inset: uniform(rng, 0.02, 0.06),
            }
        },
        apron: 0.0,
        lower_shelf: (!round && coin(rng, 0.4)).then(|| uniform(rng, 0.1, 0.14)),
    };
    build_table(&mut b, &t, top, legs);
    b.finish(Placement::Floor, SCALE)
}

/// Side table: width 0.4–0.6, height 0.5–0.66, depth 0.4–0.6; square or round, optional lower
/// shelf.
pub(super) fn side_table(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let (top, legs) = table_materials(rng, &mut b);
    let round = coin(rng, 0.4);
    let width = uniform(rng, 0.4, 0.6);
    let t = Table {
        width,
        depth: if round { width } else { uniform(rng, 0.4, 0.6) },
        height: uniform(rng, 0.5, 0.65),
        top_thickness: uniform(rng, 0.02, 0.035),
        round,
        support: if round && coin(rng, 0.5) {
            Support::Pedestal
        } else {
            Support::Legs {
                section: uniform(rng, 0.025, 0.04),
                inset: uniform(rng, 0.01, 0.04),
            }
        },
        apron: 0.0,
        lower_shelf: coin(rng, 0.4).then(|| uniform(rng, 0.12, 0.25)),
    };
    build_table(&mut b, &t, top, legs);
    b.finish(Placement::Floor, SCALE)
}

/// Dining table: width 1.0–2.0 (round: diameter 1.0–1.3), height 0.74–0.78, depth 0.8–1.3;
/// four legs with an apron, a pedestal or trestles.
pub(super) fn dining_table(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let (top, legs) = table_materials(rng, &mut b);
    let round = coin(rng, 0.25);
    let width = if round {
        uniform(rng, 1.0, 1.3)
    } else {
        uniform(rng, 1.4, 2.0)
    };
    let support = match (round, int(rng, 0, 3)) {
        (true, 0) => Support::Pedestal,
        (false, 0) => Support::Trestle,
        _ => Support::Legs {
            section: uniform(rng, 0.05, 0.08),
            inset: uniform(rng, 0.03, 0.08),
        },
    };
    let t = Table {
        width,
        depth: if round { width } else { uniform(rng, 0.8, 1.0) },
        height: uniform(rng, 0.74, 0.78),
        top_thickness: uniform(rng, 0.025, 0.045),
        round,
        support,
        apron: uniform(rng, 0.06, 0.1),
        lower_shelf: None,
    };
    build_table(&mut b, &t, top, legs);
    b.finish(Placement::Floor, SCALE)
}

/// Desk: width 1.1–1.7, height 0.72–0.77, depth 0.6–0.8; a knee hole between a pedestal of
/// sliding drawers and a leg panel (or two panels and a shallow drawer under the top), modesty
/// panel at the back.
pub(super) fn desk(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.6, Palette::Wood, Palette::PaintedWood, rng);
    let handle = mat(&mut b, Palette::Metal, rng);
    let (w, h, d) = uniform3(rng, [1.1, 1.7], [0.72, 0.77], [0.6, 0.8]);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let top_t = uniform(rng, 0.025, 0.04);
    let under_top = h - top_t;
    b.cuboid("top", body, [-hw, under_top, -hd], [hw, h, hd]);
    b.top_surface("top", [-hw, -hd], [hw, hd], h, 0.03);
    let panel = 0.025;
    let pedestal = coin(rng, 0.7);
    let ped_w = uniform(rng, 0.38, 0.45);
    let side = if coin(rng, 0.5) { 1.0f32 } else { -1.0 };
    let (knee_x0, knee_x1);
    if pedestal {
        let rows = int(rng, 3, 4);
        let c = Carcass {
            width: ped_w,
            height: under_top + 0.002,
            depth: d - 0.04,
            board: 0.02,
            feet: Feet::Plinth {
                height: 0.05,
                recess: 0.02,
            },
            columns: 1,
            shelves: Carcass::even_shelves(rows),
            drawer_rows: rows,
            top_board: false,
            ..Carcass::PLAIN
        };
        let cx = side * (hw - 0.5 * ped_w);
        carcass::build(
            &mut b,
            &c,
            CarcassMaterials::uniform(body, handle),
            [cx, -0.02],
            "pedestal_",
        );
        b.surfaces_mut()
            .retain(|s| !s.name.starts_with("pedestal_") || s.name.ends_with("_interior"));
        let x_other = -side * (hw - 0.5 * panel);
        b.cuboid(
            "leg_panel",
            body,
            [x_other - 0.5 * panel, 0.0, -hd],
            [x_other + 0.5 * panel, under_top + 0.002, hd],
        );
        if side > 0.0 {
            knee_x0 = -hw + panel;
            knee_x1 = hw - ped_w;
        } else {
            knee_x0 = -hw + ped_w;
            knee_x1 = hw - panel;
        }
    } else {
        for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
            let x = sx * (hw - 0.5 * panel);
            b.cuboid(
                &format!("leg_panel_{i}"),
                body,
                [x - 0.5 * panel, 0.0, -hd],
                [x + 0.5 * panel, under_top + 0.002, hd],
            );
        }
        knee_x0 = -hw + panel;
        knee_x1 = hw - panel;
    }
    let modesty_bottom = uniform(rng, 0.3, 0.45);
    b.cuboid(
        "modesty_panel",
        body,
        [knee_x0 - 0.001, modesty_bottom, -hd + 0.02],
        [knee_x1 + 0.001, under_top + 0.001, -hd + 0.04],
    );
    // Without a pedestal, a shallow drawer hangs under the top in the middle of the knee hole.
    let knee_top = if pedestal {
        under_top
    } else {
        let half = (0.3 * (knee_x1 - knee_x0)).min(0.3);
        let mx = 0.5 * (knee_x0 + knee_x1);
        articulation::drawer(
            &mut b,
            "drawer",
            CarcassMaterials::uniform(body, handle).link(),
            DrawerBox {
                x: [mx - half, mx + half],
                y: [under_top - 0.09, under_top - 0.002],
                z: [-hd + 0.06, hd - 0.01],
                headroom: 0.002,
            },
        );
        under_top - 0.09
    };
    b.surface(rect_surface(
        "under",
        SurfaceKind::Under,
        [knee_x0, -hd + 0.04],
        [knee_x1, hd],
        0.0,
        Some(knee_top - 0.02),
        0.03,
    ));
    b.finish(Placement::Floor, SCALE)
}

/// Kids' table: width 0.6–1.2, height 0.45–0.56, depth 0.5–0.8; bright colours, round or
/// rectangular.
pub(super) fn kids_table(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let top = mat_either(&mut b, 0.5, Palette::BrightPlastic, Palette::Wood, rng);
    let legs = mat(&mut b, Palette::BrightPlastic, rng);
    let round = coin(rng, 0.3);
    let width = if round {
        uniform(rng, 0.6, 0.9)
    } else {
        uniform(rng, 0.75, 1.2)
    };
    let t = Table {
        width,
        depth: if round { width } else { uniform(rng, 0.5, 0.7) },
        height: uniform(rng, 0.45, 0.55),
        top_thickness: uniform(rng, 0.02, 0.03),
        round,
        support: Support::Legs {
            section: uniform(rng, 0.035, 0.05),
            inset: 0.02,
        },
        apron: 0.0,
        lower_shelf: None,
    };
    build_table(&mut b, &t, top, legs);
    b.finish(Placement::Floor, SCALE)
}

/// Display table (store or museum): width 1.0–1.8, height 0.75–0.92, depth 0.6–0.95; panel ends
/// or legs, often a lower display shelf.
pub(super) fn display_table(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let (top, legs) = table_materials(rng, &mut b);
    let panels = coin(rng, 0.5);
    let t = Table {
        width: uniform(rng, 1.0, 1.8),
        depth: uniform(rng, 0.6, 0.95),
        height: uniform(rng, 0.75, 0.92),
        top_thickness: uniform(rng, 0.03, 0.05),
        round: false,
        support: if panels {
            Support::Panels {
                thickness: uniform(rng, 0.04, 0.07),
            }
        } else {
            Support::Legs {
                section: uniform(rng, 0.04, 0.06),
                inset: 0.03,
            }
        },
        apron: 0.0,
        lower_shelf: coin(rng, 0.6).then(|| uniform(rng, 0.15, 0.3)),
    };
    build_table(&mut b, &t, top, legs);
    b.finish(Placement::Floor, SCALE)
}

/// High (bar) table: width 0.6–0.9, height 1.0–1.1, depth 0.6–0.9; round on a pedestal or
/// square on legs.
pub(super) fn high_table(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let (top, legs) = table_materials(rng, &mut b);
    let round = coin(rng, 0.6);
    let width = uniform(rng, 0.6, 0.9);
    let t = Table {
        width,
        depth: width,
        height: uniform(rng, 1.0, 1.1),
        top_thickness: uniform(rng, 0.025, 0.04),
        round,
        support: if round {
            Support::Pedestal
        } else {
            Support::Legs {
                section: uniform(rng, 0.04, 0.05),
                inset: 0.03,
            }
        },
        apron: 0.0,
        lower_shelf: None,
    };
    build_table(&mut b, &t, top, legs);
    b.finish(Placement::Floor, SCALE)
}

/// Workbench: width 1.2–2.0, height 0.85–0.95, depth 0.6–0.8; a thick top on four heavy legs,
/// a lower shelf, optional pegboard back.
pub(super) fn workbench(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let top = mat(&mut b, Palette::Wood, rng);
    let legs = mat_either(&mut b, 0.5, Palette::Wood, Palette::CoatedMetal, rng);
    let t = Table {
        width: uniform(rng, 1.2, 2.0),
        depth: uniform(rng, 0.6, 0.8),
        height: uniform(rng, 0.85, 0.95),
        top_thickness: uniform(rng, 0.04, 0.07),
        round: false,
        support: Support::Legs {
            section: uniform(rng, 0.06, 0.09),
            inset: 0.03,
        },
        apron: uniform(rng, 0.06, 0.1),
        lower_shelf: Some(uniform(rng, 0.15, 0.25)),
    };
    build_table(&mut b, &t, top, legs);
    if coin(rng, 0.5) {
        let (hw, hd) = (0.5 * t.width, 0.5 * t.depth);
        let board = mat(&mut b, Palette::Paper, rng);
        let ph = uniform(rng, 0.5, 0.8);
        b.cuboid(
            "pegboard",
            board,
            [-hw, t.height - 0.001, -hd],
            [hw, t.height + ph, -hd + 0.02],
        );
        for s in b.surfaces_mut() {
            if s.name == "top" {
                for p in &mut s.polygon {
                    p[1] = p[1].max(-hd + 0.05);
                }
            }
        }
    }
    b.finish(Placement::Floor, SCALE)
}

/// Nightstand: width 0.4–0.56, height 0.5–0.68, depth 0.35–0.45; a sliding drawer over an open
/// cubby.
pub(super) fn nightstand(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.6, Palette::Wood, Palette::PaintedWood, rng);
    let handle = mat(&mut b, Palette::Metal, rng);
    let drawer_on_top = uniform(rng, 0.6, 0.7);
    let c = Carcass {
        width: uniform(rng, 0.4, 0.56),
        height: uniform(rng, 0.5, 0.68),
        depth: uniform(rng, 0.35, 0.45),
        board: 0.018,
        feet: Feet::Legs {
            height: uniform(rng, 0.06, 0.16),
            section: 0.03,
        },
        columns: 1,
        shelves: vec![drawer_on_top],
        ..Carcass::PLAIN
    };
    carcass::build(
        &mut b,
        &c,
        CarcassMaterials::uniform(body, handle),
        [0.0, 0.0],
        "",
    );
    // The upper row is a drawer: close it and drop its compartment.
    let shelf_top = c.body_bottom() + c.board + drawer_on_top * c.interior_height() + 0.5 * c.board;
    let (hw, hd) = (0.5 * c.width - c.board, 0.5 * c.depth);
    b.surfaces_mut().retain(|s| s.name != "shelf_1");
    articulation::drawer(
        &mut b,
        "drawer",
        CarcassMaterials::uniform(body, handle).link(),
        DrawerBox {
            x: [-hw + 0.003, hw - 0.003],
            y: [shelf_top + 0.003, c.height - c.board - 0.003],
            z: [-hd + 0.03, hd + 0.005],
            headroom: 0.003,
        },
    );
    b.finish(Placement::Floor, SCALE)
}

/// Picnic table: width 1.5–2.1, height 0.72–0.78, depth 1.4–1.7 (with its benches); plank top
/// and two attached benches on A-frame legs.
pub(super) fn picnic_table(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let wood = mat(&mut b, Palette::Wood, rng);
    let (w, h) = (uniform(rng, 1.5, 2.1), uniform(rng, 0.72, 0.78));
    let top_d = uniform(rng, 0.7, 0.8);
    let seat_h = uniform(rng, 0.43, 0.46);
    let bench_d = 0.25;
    let reach = uniform(rng, 0.7, 0.85);
    let hw = 0.5 * w;
    let planks = 5;
    let pd = top_d / planks as f32;
    for i in 0..planks {
        let z0 = -0.5 * top_d + i as f32 * pd;
        b.cuboid(
            &format!("top_plank_{i}"),
            wood,
            [-hw, h - 0.04, z0 + 0.004],
            [hw, h, z0 + pd - 0.004],
        );
    }
    for (k, sz) in [-1.0f32, 1.0].into_iter().enumerate() {
        let zc = sz * reach;
        b.cuboid(
            &format!("bench_{k}"),
            wood,
            [-hw, seat_h - 0.04, zc - 0.5 * bench_d],
            [hw, seat_h, zc + 0.5 * bench_d],
        );
        b.top_surface(
            &format!("bench_{k}"),
            [-hw, zc - 0.5 * bench_d],
            [hw, zc + 0.5 * bench_d],
            seat_h,
            0.03,
        );
    }
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * (hw - 0.25);
        b.part(strut(
            &format!("leg_a_{i}"),
            wood,
            [x, 0.0, -reach + 0.05],
            [x, h - 0.04, -0.15],
            [0.05, 0.08],
        ));
        b.part(strut(
            &format!("leg_b_{i}"),
            wood,
            [x, 0.0, reach - 0.05],
            [x, h - 0.04, 0.15],
            [0.05, 0.08],
        ));
        b.cuboid(
            &format!("cross_{i}"),
            wood,
            [x - 0.03, seat_h - 0.12, -reach - 0.5 * bench_d + 0.02],
            [x + 0.03, seat_h - 0.04, reach + 0.5 * bench_d - 0.02],
        );
        b.cuboid(
            &format!("top_cleat_{i}"),
            wood,
            [x - 0.03, h - 0.1, -0.5 * top_d + 0.02],
            [x + 0.03, h - 0.04, 0.5 * top_d - 0.02],
        );
    }
    b.top_surface("top", [-hw, -0.5 * top_d], [hw, 0.5 * top_d], h, 0.03);
    b.finish(Placement::Floor, SCALE)
}

/// Lab bench: width 1.5–2.4, height 0.88–0.95, depth 0.75–0.9; a resin or stone top over two
/// open base cabinets with a knee space between, and a reagent shelf on posts at the back.
pub(super) fn lab_bench(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = b.material(fixed_material("lab_white", [0xE8, 0xE8, 0xE4], 0.45, 0.1));
    let top = mat(&mut b, Palette::Stone, rng);
    let handle = mat(&mut b, Palette::Metal, rng);
    let (w, h, d) = uniform3(rng, [1.5, 2.4], [0.88, 0.95], [0.75, 0.9]);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let top_t = 0.03;
    b.cuboid("top", top, [-hw, h - top_t, -hd], [hw, h, hd]);
    let cab_w = uniform(rng, 0.45, 0.6);
    let c = Carcass {
        width: cab_w,
        height: h - top_t + 0.001,
        depth: d - 0.05,
        board: 0.018,
        feet: Feet::Plinth {
            height: 0.1,
            recess: 0.04,
        },
        columns: 1,
        shelves: vec![0.5],
        ..Carcass::PLAIN
    };
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let cx = sx * (hw - 0.5 * cab_w);
        carcass::build(
            &mut b,
            &c,
            CarcassMaterials::uniform(body, handle),
            [cx, -0.025],
            &format!("cabinet_{i}_"),
        );
    }
    b.surfaces_mut().retain(|s| !s.name.ends_with("_top"));
    // The reagent shelf stands on the back of the top.
    let shelf_h = uniform(rng, 0.45, 0.6);
    let shelf_d = uniform(rng, 0.2, 0.25);
    let post = 0.03;
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * (hw - 0.1);
        b.cuboid(
            &format!("shelf_post_{i}"),
            handle,
            [x - 0.5 * post, h - 0.001, -hd + 0.02],
            [x + 0.5 * post, h + shelf_h, -hd + 0.02 + post],
        );
    }
    b.cuboid(
        "reagent_shelf",
        body,
        [-hw + 0.05, h + shelf_h - 0.02, -hd + 0.01],
        [hw - 0.05, h + shelf_h, -hd + 0.01 + shelf_d],
    );
    b.top_surface(
        "reagent_shelf",
        [-hw + 0.05, -hd + 0.01],
        [hw - 0.05, -hd + 0.01 + shelf_d],
        h + shelf_h,
        0.03,
    );
    let front_of_shelf = -hd + 0.01 + shelf_d;
    b.top_surface("top", [-hw, front_of_shelf], [hw, hd], h, 0.03);
    b.surface(rect_surface(
        "top_under_shelf",
        SurfaceKind::Shelf,
        [-hw + 0.1 + post, -hd + 0.02 + post],
        [hw - 0.1 - post, front_of_shelf],
        h,
        Some(shelf_h - 0.03),
        0.02,
    ));
    let knee = hw - cab_w;
    if knee > 0.2 {
        b.surface(rect_surface(
            "under",
            SurfaceKind::Under,
            [-knee, -hd],
            [knee, hd],
            0.0,
            Some(h - top_t - 0.02),
            0.03,
        ));
    }
    b.finish(Placement::Floor, SCALE)
}

/// Pool table: width 2.3–2.9 (length along x), height 0.78–0.82, depth 1.3–1.65; a slate bed
/// inside cushion rails broken at six pockets, on six or four heavy legs.
pub(super) fn pool_table(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let wood = mat(&mut b, Palette::Wood, rng);
    let cloth = b.material(if coin(rng, 0.7) {
        fixed_material("baize_green", [0x1E, 0x6E, 0x3A], 0.95, 0.0)
    } else {
        fixed_material("baize_blue", [0x1E, 0x4E, 0x8C], 0.95, 0.0)
    });
    let pocket_m = b.material(fixed_material("pocket_black", [0x18, 0x18, 0x18], 0.9, 0.0));
    let (w, d) = (uniform(rng, 2.3, 2.9), uniform(rng, 1.3, 1.65));
    let h = uniform(rng, 0.78, 0.82);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let rail = uniform(rng, 0.1, 0.14);
    let bed_y = h - 0.05;
    b.cuboid(
        "apron",
        wood,
        [-hw, bed_y - 0.22, -hd],
        [hw, bed_y - 0.03, hd],
    );
    b.cuboid(
        "bed",
        cloth,
        [-hw + rail - 0.01, bed_y - 0.04, -hd + rail - 0.01],
        [hw - rail + 0.01, bed_y, hd - rail + 0.01],
    );
    let pocket = 0.13;
    // Long rails: two per side split at the middle pocket; short rails: one per end.
    let (px0, px1) = (-hw + pocket, hw - pocket);
    let mid = 0.5 * pocket;
    for (k, sz) in [-1.0f32, 1.0].into_iter().enumerate() {
        let (z0, z1) = if sz < 0.0 {
            (-hd, -hd + rail)
        } else {
            (hd - rail, hd)
        };
        b.cuboid(
            &format!("rail_{k}_left"),
            wood,
            [px0, bed_y - 0.031, z0],
            [-mid, h, z1],
        );
        b.cuboid(
            &format!("rail_{k}_right"),
            wood,
            [mid, bed_y - 0.031, z0],
            [px1, h, z1],
        );
        b.cuboid(
            &format!("pocket_mid_{k}"),
            pocket_m,
            [-mid, bed_y - 0.12, z0],
            [mid, bed_y - 0.02, z1],
        );
    }
    for (k, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let (x0, x1) = if sx < 0.0 {
            (-hw, -hw + rail)
        } else {
            (hw - rail, hw)
        };
        b.cuboid(
            &format!("rail_end_{k}"),
            wood,
            [x0, bed_y - 0.031, -hd + pocket],
            [x1, h, hd - pocket],
        );
    }
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        b.part(cylinder(
            &format!("pocket_{i}"),
            pocket_m,
            [sx * (hw - 0.06), sz * (hd - 0.06)],
            0.065,
            bed_y - 0.14,
            bed_y - 0.02,
            12,
        ));
    }
    let legs = if w > 2.6 { 3 } else { 2 };
    for i in 0..legs {
        let x = -hw + 0.2 + i as f32 * (w - 0.4) / (legs - 1) as f32;
        for (k, sz) in [-1.0f32, 1.0].into_iter().enumerate() {
            b.part(frustum(
                &format!("leg_{i}_{k}"),
                wood,
                [x, sz * (hd - 0.2)],
                0.07,
                0.09,
                0.0,
                bed_y - 0.2,
                12,
            ));
        }
    }
    b.top_surface(
        "bed",
        [-hw + rail, -hd + rail],
        [hw - rail, hd - rail],
        bed_y,
        0.03,
    );
    b.finish(Placement::Floor, SCALE)
}

/// A counter: a carcass under an overhanging top, its bays behind hinged doors (over a row of
/// drawers, one time in two). `customer_side` closes the front instead and turns open bays to
/// face −Z (the staff side), with the top overhanging +Z.
fn counter(
    rng: &mut ChaCha8Rng,
    width: (f32, f32),
    height: (f32, f32),
    depth: (f32, f32),
    customer_side: bool,
    bar: bool,
) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.5, Palette::Wood, Palette::PaintedWood, rng);
    let top = mat_either(&mut b, 0.6, Palette::Stone, Palette::Wood, rng);
    let handle = mat(&mut b, Palette::Metal, rng);
    let (w, h, d) = uniform3(
        rng,
        [width.0, width.1],
        [height.0, height.1],
        [depth.0, depth.1],
    );
    let top_t = uniform(rng, 0.03, 0.05);
    let overhang = if bar { uniform(rng, 0.2, 0.3) } else { 0.03 };
    let body_d = d - overhang;
    let columns = ((w / 0.6).round() as usize).max(2);
    let c = Carcass {
        width: w,
        height: h - top_t + 0.001,
        depth: body_d,
        board: 0.02,
        feet: Feet::Plinth {
            height: 0.1,
            recess: 0.05,
        },
        columns,
        shelves: vec![uniform(rng, 0.45, 0.55)],
        // A kitchen run: doors, over a row of drawers one time in two.
        drawer_rows: usize::from(!customer_side && coin(rng, 0.5)),
        front: if customer_side {
            Front::Open
        } else {
            Front::Doors
        },
        ..Carcass::PLAIN
    };
    let body_cz = -0.5 * overhang;
    carcass::build(
        &mut b,
        &c,
        CarcassMaterials::uniform(body, handle),
        [0.0, body_cz],
        "",
    );
    b.surfaces_mut().retain(|s| s.name != "top");
    if customer_side {
        b.turn_around([0.0, body_cz]);
    }
    let (hw, hd) = (0.5 * w, 0.5 * d);
    b.cuboid(
        "counter_top",
        top,
        [-hw - 0.01, h - top_t, -hd],
        [hw + 0.01, h, hd],
    );
    b.top_surface("top", [-hw, -hd], [hw, hd], h, 0.03);
    if bar {
        let rail_z = hd - overhang + 0.12;
        b.part(rod(
            "foot_rail",
            handle,
            [-hw, 0.22, rail_z],
            [hw, 0.22, rail_z],
            0.025,
            0.025,
            12,
        ));
        for (i, x) in [-hw + 0.1, 0.0, hw - 0.1].into_iter().enumerate() {
            b.part(beam(
                &format!("rail_bracket_{i}"),
                handle,
                [x, 0.22, hd - overhang - 0.005],
                [x, 0.22, rail_z],
                [0.02, 0.02],
            ));
        }
    }
    b.finish(Placement::Floor, SCALE)
}

/// Checkout counter: width 1.4–2.4, height 0.9–1.0, depth 0.6–0.8; closed toward the customer
/// (+Z), open shelves on the cashier's side (−Z).
pub(super) fn checkout_counter(rng: &mut ChaCha8Rng) -> Asset {
    counter(rng, (1.4, 2.4), (0.9, 1.0), (0.6, 0.8), true, false)
}

/// Bar counter: width 1.8–3.0, height 1.05–1.15, depth 0.55–0.75; the top overhangs the
/// customer side (+Z) over a foot rail, shelves open to the bartender (−Z).
pub(super) fn bar_counter(rng: &mut ChaCha8Rng) -> Asset {
    counter(rng, (1.8, 3.0), (1.05, 1.15), (0.55, 0.75), true, true)
}

/// Kitchen counter: width 1.2–2.4, height 0.88–0.92, depth 0.6–0.66; base cabinets with
/// hinged doors (and a row of drawers, one time in two) under a worktop.
pub(super) fn kitchen_counter(rng: &mut ChaCha8Rng) -> Asset {
    counter(rng, (1.2, 2.4), (0.88, 0.92), (0.6, 0.66), false, false)
}
