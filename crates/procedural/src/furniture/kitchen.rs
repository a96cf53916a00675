//! Kitchen furniture: kitchen island, wall cabinet, range hood and dishwasher. Fronts face +Z;
//! wall-mounted pieces have their wall side at −Z.

use rand_chacha::ChaCha8Rng;

use super::carcass::{self, Carcass, CarcassMaterials, Feet, Front};
use super::{mat, mat_either, SCALE};
use crate::articulation;
use crate::items::builder::Builder;
use crate::materials::Palette;
use crate::random::{coin, int, uniform};
use scenethesis_primitives::{prism_x, rect, rect_surface, rod, AssetBuilder};
use scenethesis_scene_graph::{Asset, Placement, SurfaceKind};

/// Kitchen island: width 1.2–2.2, height 0.9–0.95, depth 0.85–1.2; a cabinet run with hinged
/// doors (over a row of drawers, one of two) toward +Z under a stone or wood worktop that overhangs the back by 0.22–0.32 m
/// so stools fit under it.
pub(super) fn kitchen_island(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.6, Palette::PaintedWood, Palette::Wood, rng);
    let handle = mat(&mut b, Palette::Metal, rng);
    let top_m = mat_either(&mut b, 0.65, Palette::Stone, Palette::Wood, rng);
    let w = uniform(rng, 1.2, 2.2);
    let cd = uniform(rng, 0.6, 0.85);
    let overhang = uniform(rng, 0.22, 0.32);
    let h = uniform(rng, 0.9, 0.95);
    let t = uniform(rng, 0.03, 0.04);
    let d = cd + overhang;
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let columns = int(rng, 2, 3).min((w / 0.45) as usize).max(1);
    let c = Carcass {
        width: w - 0.04,
        height: h - t + 0.001,
        depth: cd,
        board: 0.018,
        feet: Feet::Plinth {
            height: 0.1,
            recess: 0.05,
        },
        columns,
        shelves: vec![0.5],
        top_board: false,
        drawer_rows: usize::from(coin(rng, 0.5)),
        front: Front::Doors,
        ..Carcass::PLAIN
    };
    let cz = hd - 0.5 * cd;
    carcass::build(
        &mut b,
        &c,
        CarcassMaterials::uniform(body, handle),
        [0.0, cz],
        "",
    );
    // The top row is closed by the worktop: its clearance ends under it.
    for s in b.surfaces_mut() {
        let cap = h - t - 0.01 - s.height;
        if s.kind != SurfaceKind::Interior {
            s.kind = SurfaceKind::Shelf;
        }
        s.clearance = Some(s.clearance.map_or(cap, |cl| cl.min(cap)));
    }
    b.cuboid("worktop", top_m, [-hw, h - t, -hd], [hw, h, hd]);
    b.top_surface("worktop", [-hw, -hd], [hw, hd], h, 0.03);
    b.surface(rect_surface(
        "under_overhang",
        SurfaceKind::Under,
        [-hw + 0.04, -hd + 0.02],
        [hw - 0.04, cz - 0.5 * cd - 0.01],
        0.0,
        Some(h - t - 0.02),
        0.01,
    ));
    b.finish(Placement::Floor, SCALE)
}

/// Wall cabinet (kitchen or bathroom): width 0.4–1.2, height 0.5–0.9, depth 0.28–0.36 with its
/// doors closed; 1–2 columns of 2–3 shelf rows behind closed hinged doors.
pub(super) fn wall_cabinet(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.6, Palette::PaintedWood, Palette::Wood, rng);
    let handle = mat(&mut b, Palette::Metal, rng);
    let w = uniform(rng, 0.4, 1.2);
    let h = uniform(rng, 0.5, 0.9);
    let rows = if h > 0.7 { int(rng, 2, 3) } else { 2 };
    let c = Carcass {
        width: w,
        height: h,
        depth: uniform(rng, 0.28, 0.36),
        board: 0.018,
        feet: Feet::Plinth {
            height: 0.0,
            recess: 0.0,
        },
        columns: if w > 0.8 { 2 } else { 1 },
        shelves: Carcass::even_shelves(rows),
        front: Front::Doors,
        ..Carcass::PLAIN
    };
    carcass::build(
        &mut b,
        &c,
        CarcassMaterials::uniform(body, handle),
        [0.0, 0.0],
        "",
    );
    b.finish(Placement::Wall, SCALE)
}

/// Range hood (chimney extractor): width 0.6–0.9, height 0.55–1.05, depth 0.45–0.52; a slim
/// canopy with a dark filter underneath, a sloped top and a chimney up the wall.
pub(super) fn range_hood(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let steel = mat_either(&mut b, 0.7, Palette::Metal, Palette::CoatedMetal, rng);
    let filter = b.material(crate::materials::fixed_material(
        "filter",
        [0x30, 0x30, 0x32],
        0.5,
        0.6,
    ));
    let w = uniform(rng, 0.6, 0.9);
    let d = uniform(rng, 0.45, 0.52);
    let hw = 0.5 * w;
    let lip = uniform(rng, 0.05, 0.08);
    let slope = uniform(rng, 0.18, 0.3);
    let chimney = uniform(rng, 0.3, 0.65);
    let cd = uniform(rng, 0.2, 0.26);
    b.cuboid("canopy", steel, [-hw, 0.0, 0.0], [hw, lip, d]);
    b.cuboid(
        "filter",
        filter,
        [-hw + 0.03, -0.0, 0.03],
        [hw - 0.03, 0.004, d - 0.03],
    );
    b.part(prism_x(
        "hood",
        steel,
        &[
            [0.0, lip - 0.001],
            [d, lip - 0.001],
            [cd, lip + slope],
            [0.0, lip + slope],
        ],
        -hw,
        hw,
    ));
    let cw = uniform(rng, 0.24, 0.3);
    b.cuboid(
        "chimney",
        steel,
        [-0.5 * cw, lip + slope - 0.002, 0.0],
        [0.5 * cw, lip + slope + chimney, cd],
    );
    for (i, x) in [-0.1f32, 0.0, 0.1].iter().enumerate() {
        b.part(rod(
            &format!("button_{i}"),
            filter,
            [*x, 0.5 * lip, d - 0.001],
            [*x, 0.5 * lip, d + 0.006],
            0.008,
            0.008,
            8,
        ));
    }
    b.finish(Placement::Wall, [0.95, 1.05])
}

/// Dishwasher: width 0.445–0.45 (slimline) or 0.595–0.6, height 0.82–0.87 (under a worktop),
/// depth 0.55–0.6; a closed front door hinged at its bottom, with a handle and a control strip over a recessed
/// plinth, and behind it a real hollow tub (floor, back, sides and top as separate slabs) with
/// two thin wire racks; usable top.
pub(super) fn dishwasher(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = Builder::new();
    let body = match int(rng, 0, 3) {
        0 | 1 => b.fixed("appliance_white", [0xF2, 0xF2, 0xF0], 0.3, 0.0),
        2 => b.fixed("appliance_steel", [0xB8, 0xBA, 0xBC], 0.3, 0.6),
        _ => b.fixed("appliance_black", [0x2A, 0x2C, 0x30], 0.35, 0.2),
    };
    let tub = b.fixed("tub_steel", [0xC8, 0xCA, 0xCC], 0.25, 0.8);
    let dark = b.fixed("control_strip", [0x18, 0x1A, 0x1E], 0.2, 0.0);
    let trim = b.palette(Palette::Metal, rng);
    let w = if coin(rng, 0.25) {
        uniform(rng, 0.445, 0.45)
    } else {
        uniform(rng, 0.595, 0.6)
    };
    let (h, d) = (uniform(rng, 0.82, 0.87), uniform(rng, 0.55, 0.6));
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let (plinth, wall, door) = (uniform(rng, 0.08, 0.11), 0.02, 0.045);
    let back = hd - door;
    // The plinth, set back from the door.
    b.cuboid(
        "plinth",
        body,
        [-hw + 0.01, 0.0, -hd],
        [hw - 0.01, plinth, back - 0.04],
    );
    // The tub: open toward the door, closed on every other side.
    b.cuboid(
        "tub_floor",
        tub,
        [-hw, plinth, -hd],
        [hw, plinth + wall, back],
    );
    b.cuboid("tub_top", tub, [-hw, h - wall, -hd], [hw, h, back]);
    b.cuboid(
        "tub_back",
        tub,
        [-hw, plinth + wall - 0.001, -hd],
        [hw, h - wall + 0.001, -hd + wall],
    );
    for (name, x0, x1) in [("tub_left", -hw, -hw + wall), ("tub_right", hw - wall, hw)] {
        b.cuboid(
            name,
            body,
            [x0, plinth + wall - 0.001, -hd + wall - 0.001],
            [x1, h - wall + 0.001, back],
        );
    }
    // Two wire racks as thin slabs, free of the walls.
    let inner = h - wall - (plinth + wall);
    for (name, at) in [("rack_lower", 0.12), ("rack_upper", 0.55)] {
        let y = plinth + wall + at * inner;
        b.cuboid(
            name,
            trim,
            [-hw + wall + 0.015, y, -hd + wall + 0.02],
            [hw - wall - 0.015, y + 0.008, back - 0.02],
        );
    }
    // The door hinged at its bottom edge with a bar handle, under a fixed control strip.
    b.joint(articulation::bottom_hinge("door", plinth, hd, 1.5));
    b.link(Some("door"));
    b.cuboid("door", body, [-hw, plinth, back], [hw, h - 0.07, hd]);
    b.cuboid(
        "handle",
        trim,
        [-0.3 * w, h - 0.12, hd - 0.001],
        [0.3 * w, h - 0.1, hd + 0.025],
    );
    b.link(None);
    b.cuboid("control_strip", dark, [-hw, h - 0.07, back], [hw, h, hd]);
    b.top("top", rect(-hw + 0.02, -hd + 0.02, hw - 0.02, hd - 0.02), h);
    b.finish(Placement::Floor, [0.98, 1.02])
}
