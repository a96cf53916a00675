//! Storage furniture: carcasses with open compartments (bookshelves, cabinets, lockers,
//! wardrobes, fridges, stands) and open-top boxes (toy box, chest freezer), racks and carts.
//! All open sides face +Z.

use rand_chacha::ChaCha8Rng;

use super::carcass::{self, Carcass, CarcassMaterials, Feet, Front, CORNERS};
use super::{mat, mat_either, SCALE};
use crate::articulation;
use crate::materials::{fixed_material, Palette};
use crate::random::{coin, int, uniform, uniform3};
use scenethesis_primitives::{beam, rect_surface, rod, square_post, AssetBuilder};
use scenethesis_scene_graph::{Asset, Placement, SurfaceKind};

/// Picks shelf fractions for `rows` rows (at least one row) of a carcass with compartments
/// between `lo` and `hi` metres clear.
fn rows_for(rng: &mut ChaCha8Rng, c: &Carcass, lo: f32, hi: f32) -> Vec<f32> {
    let (min, max) = Carcass::row_counts(c.interior_height(), c.board, lo, hi);
    Carcass::even_shelves(int(rng, min, max))
}

fn wood_materials(rng: &mut ChaCha8Rng, b: &mut AssetBuilder) -> CarcassMaterials {
    let body = mat(
        b,
        if coin(rng, 0.6) {
            Palette::Wood
        } else {
            Palette::PaintedWood
        },
        rng,
    );
    let handle = mat(b, Palette::Metal, rng);
    CarcassMaterials::uniform(body, handle)
}

fn metal_materials(rng: &mut ChaCha8Rng, b: &mut AssetBuilder) -> CarcassMaterials {
    let body = mat(b, Palette::CoatedMetal, rng);
    let handle = mat(b, Palette::Metal, rng);
    CarcassMaterials::uniform(body, handle)
}

fn finish(b: AssetBuilder) -> Asset {
    b.finish(Placement::Floor, SCALE)
}

/// Bookshelf: width 0.6–1.2, height 1.6–2.1, depth 0.28–0.38; 1–3 columns of compartments
/// 0.25–0.42 clear, back panel, kick plinth.
pub(super) fn bookshelf(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let m = wood_materials(rng, &mut b);
    let width = uniform(rng, 0.6, 1.2);
    let mut c = Carcass {
        width,
        height: uniform(rng, 1.6, 2.1),
        depth: uniform(rng, 0.28, 0.38),
        board: uniform(rng, 0.018, 0.028),
        feet: Feet::Plinth {
            height: uniform(rng, 0.04, 0.1),
            recess: 0.02,
        },
        columns: if width > 0.9 {
            int(rng, 1, 3)
        } else {
            int(rng, 1, 2)
        },
        shelves: vec![],
        ..Carcass::PLAIN
    };
    c.shelves = rows_for(rng, &c, 0.25, 0.42);
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    finish(b)
}

/// Display shelf: width 0.8–1.4, height 1.2–1.9, depth 0.3–0.45; open frame of corner posts
/// with 3–5 shelves, optional back.
pub(super) fn display_shelf(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat_either(&mut b, 0.5, Palette::Metal, Palette::Wood, rng);
    let shelf = mat_either(&mut b, 0.5, Palette::Wood, Palette::PaintedWood, rng);
    let m = CarcassMaterials {
        body: shelf,
        shelf,
        side: frame,
        back: shelf,
        front: shelf,
        handle: frame,
    };
    let mut c = Carcass {
        width: uniform(rng, 0.8, 1.4),
        height: uniform(rng, 1.2, 1.9),
        depth: uniform(rng, 0.3, 0.45),
        board: uniform(rng, 0.02, 0.03),
        feet: Feet::Legs {
            height: uniform(rng, 0.04, 0.1),
            section: 0.03,
        },
        columns: 1,
        shelves: vec![],
        back: coin(rng, 0.5),
        posts: Some(uniform(rng, 0.025, 0.04)),
        ..Carcass::PLAIN
    };
    c.shelves = rows_for(rng, &c, 0.28, 0.45);
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    finish(b)
}

/// Store shelf (gondola): width 0.9–1.33, height 1.4–2.0, depth 0.45–0.6; metal end panels,
/// back panel, 1–2 bays of 4–6 shelves with price-rail lips.
pub(super) fn store_shelf(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let m = metal_materials(rng, &mut b);
    let mut c = Carcass {
        width: uniform(rng, 0.9, 1.33),
        height: uniform(rng, 1.4, 2.0),
        depth: uniform(rng, 0.45, 0.6),
        board: 0.02,
        feet: Feet::Plinth {
            height: uniform(rng, 0.08, 0.14),
            recess: 0.0,
        },
        columns: int(rng, 1, 2),
        shelves: vec![],
        lip: uniform(rng, 0.025, 0.04),
        ..Carcass::PLAIN
    };
    c.shelves = rows_for(rng, &c, 0.26, 0.4);
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    finish(b)
}

/// Cabinet: width 0.6–1.2, height 0.8–1.9, depth 0.4–0.6; 1–2 columns, 2–5 rows behind
/// closed hinged doors.
pub(super) fn cabinet(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let m = wood_materials(rng, &mut b);
    let width = uniform(rng, 0.6, 1.2);
    let mut c = Carcass {
        width,
        height: uniform(rng, 0.8, 1.9),
        depth: uniform(rng, 0.4, 0.6),
        board: uniform(rng, 0.018, 0.025),
        feet: if coin(rng, 0.5) {
            Feet::Plinth {
                height: uniform(rng, 0.06, 0.1),
                recess: 0.04,
            }
        } else {
            Feet::Legs {
                height: uniform(rng, 0.08, 0.16),
                section: 0.04,
            }
        },
        columns: if width > 0.9 { 2 } else { 1 },
        shelves: vec![],
        front: Front::Doors,
        ..Carcass::PLAIN
    };
    c.shelves = rows_for(rng, &c, 0.26, 0.45);
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    finish(b)
}

/// Tool cabinet (rolling tool chest): width 0.6–1.05, height 0.85–1.15, depth 0.45–0.52; stacked
/// drawers on casters, work top.
pub(super) fn tool_cabinet(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let m = metal_materials(rng, &mut b);
    let rows = int(rng, 4, 8);
    let c = Carcass {
        width: uniform(rng, 0.6, 1.05),
        height: uniform(rng, 0.85, 1.15),
        depth: uniform(rng, 0.45, 0.52),
        board: 0.015,
        feet: Feet::Casters {
            height: uniform(rng, 0.1, 0.14),
        },
        columns: 1,
        shelves: Carcass::even_shelves(rows),
        drawer_rows: rows,
        ..Carcass::PLAIN
    };
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    finish(b)
}

/// Chemical (safety) cabinet: width 0.6–1.2, height 0.9–1.8, depth 0.45–0.6; coated steel,
/// closed hinged doors, shelves with spill lips.
pub(super) fn chemical_cabinet(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = b.material(if coin(rng, 0.5) {
        fixed_material("safety_yellow", [0xE8, 0xB8, 0x20], 0.45, 0.4)
    } else {
        fixed_material("safety_red", [0xC0, 0x28, 0x20], 0.45, 0.4)
    });
    let handle = mat(&mut b, Palette::Metal, rng);
    let m = CarcassMaterials::uniform(body, handle);
    let mut c = Carcass {
        width: uniform(rng, 0.6, 1.2),
        height: uniform(rng, 0.9, 1.8),
        depth: uniform(rng, 0.45, 0.6),
        board: 0.02,
        feet: Feet::Plinth {
            height: uniform(rng, 0.05, 0.08),
            recess: 0.0,
        },
        columns: 1,
        shelves: vec![],
        front: Front::Doors,
        lip: 0.03,
        ..Carcass::PLAIN
    };
    c.shelves = rows_for(rng, &c, 0.28, 0.45);
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    finish(b)
}

/// Locker bank: width 0.3–1.6 (1–4 lockers of 0.3–0.4), height 1.7–1.95, depth 0.42–0.52; each
/// locker a tall bay with a hat shelf behind its closed hinged door.
pub(super) fn locker(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let m = metal_materials(rng, &mut b);
    let columns = int(rng, 1, 4);
    let c = Carcass {
        width: columns as f32 * uniform(rng, 0.3, 0.4),
        height: uniform(rng, 1.7, 1.95),
        depth: uniform(rng, 0.42, 0.52),
        board: 0.015,
        feet: Feet::Plinth {
            height: uniform(rng, 0.08, 0.12),
            recess: 0.0,
        },
        columns,
        shelves: vec![uniform(rng, 0.78, 0.84)],
        front: Front::Doors,
        ..Carcass::PLAIN
    };
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    finish(b)
}

/// Wardrobe: width 0.9–1.6, height 1.9–2.2, depth 0.55–0.65; a hat shelf over a hanging space
/// with a rail behind closed hinged doors.
pub(super) fn wardrobe(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let m = wood_materials(rng, &mut b);
    let width = uniform(rng, 0.9, 1.6);
    let c = Carcass {
        width,
        height: uniform(rng, 1.9, 2.2),
        depth: uniform(rng, 0.55, 0.65),
        board: 0.02,
        feet: Feet::Plinth {
            height: uniform(rng, 0.06, 0.1),
            recess: 0.03,
        },
        columns: if width > 1.2 { 2 } else { 1 },
        shelves: vec![uniform(rng, 0.8, 0.86)],
        front: Front::Doors,
        ..Carcass::PLAIN
    };
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    // A hanging rail below the hat shelf of each column lowers the bay's clearance.
    let hat = c.body_bottom() + c.board + c.shelves[0] * c.interior_height() - 0.5 * c.board;
    let rail_y = hat - 0.07;
    let inner = 0.5 * width - c.board;
    b.part(rod(
        "hanging_rail",
        m.handle,
        [-inner, rail_y, 0.0],
        [inner, rail_y, 0.0],
        0.013,
        0.013,
        10,
    ));
    for s in b.surfaces_mut() {
        if s.kind == SurfaceKind::Shelf && s.height < rail_y {
            s.clearance = Some(rail_y - 0.015 - s.height);
        }
    }
    finish(b)
}

/// Dresser (chest of drawers): width 0.8–1.5, height 0.75–1.05, depth 0.45–0.55; 3–5 rows of
/// drawers in 1–2 columns on short legs.
pub(super) fn dresser(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let m = wood_materials(rng, &mut b);
    let rows = int(rng, 3, 5);
    let width = uniform(rng, 0.8, 1.5);
    let c = Carcass {
        width,
        height: uniform(rng, 0.75, 1.05),
        depth: uniform(rng, 0.45, 0.55),
        board: 0.02,
        feet: Feet::Legs {
            height: uniform(rng, 0.05, 0.1),
            section: 0.04,
        },
        columns: if width > 1.1 { 2 } else { 1 },
        shelves: Carcass::even_shelves(rows),
        drawer_rows: rows,
        ..Carcass::PLAIN
    };
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    finish(b)
}

/// TV stand: width 1.2–2.0, height 0.4–0.6, depth 0.35–0.5; 2–4 bays, the outer ones behind
/// hinged doors and the middle ones open (one of two open), on legs or a plinth.
pub(super) fn tv_stand(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let m = wood_materials(rng, &mut b);
    let height = uniform(rng, 0.4, 0.6);
    let legs = coin(rng, 0.5);
    let mut c = Carcass {
        width: uniform(rng, 1.2, 2.0),
        height,
        depth: uniform(rng, 0.35, 0.5),
        board: uniform(rng, 0.018, 0.025),
        feet: if legs {
            Feet::Legs {
                height: uniform(rng, 0.08, 0.14),
                section: 0.035,
            }
        } else {
            Feet::Plinth {
                height: 0.04,
                recess: 0.02,
            }
        },
        columns: int(rng, 2, 4),
        shelves: vec![],
        back: coin(rng, 0.5),
        front: Front::Doors,
        ..Carcass::PLAIN
    };
    c.open_columns = if c.columns == 2 {
        vec![1]
    } else {
        (1..c.columns - 1).collect()
    };
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    finish(b)
}

/// Display case (vitrine): width 0.6–1.5, height 1.0–2.0, depth 0.4–0.6; a solid base with glass
/// sides, front and top around 1–4 glass-shelved bays.
pub(super) fn display_case(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.5, Palette::Wood, Palette::PaintedWood, rng);
    let glass = mat(&mut b, Palette::Glass, rng);
    let handle = mat(&mut b, Palette::Metal, rng);
    let m = CarcassMaterials {
        body,
        shelf: glass,
        side: glass,
        back: body,
        front: glass,
        handle,
    };
    let tall = coin(rng, 0.5);
    let base = if tall {
        uniform(rng, 0.1, 0.2)
    } else {
        uniform(rng, 0.6, 0.85)
    };
    let mut c = Carcass {
        width: uniform(rng, 0.6, 1.5),
        height: if tall {
            uniform(rng, 1.6, 2.0)
        } else {
            base + uniform(rng, 0.35, 0.5)
        },
        depth: uniform(rng, 0.4, 0.6),
        board: 0.012,
        feet: Feet::Plinth {
            height: base,
            recess: 0.0,
        },
        columns: 1,
        shelves: vec![],
        front: Front::Glass,
        ..Carcass::PLAIN
    };
    c.shelves = rows_for(rng, &c, 0.25, 0.5);
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    finish(b)
}

/// A box with walls of `wall` thickness whose top a lid closes: bottom, four walls, and an
/// `Interior` surface on the inside floor reaching up to the walls' top.
#[allow(clippy::too_many_arguments)]
pub(super) fn open_box(
    b: &mut AssetBuilder,
    material: usize,
    w: f32,
    h: f32,
    d: f32,
    wall: f32,
    y0: f32,
    name: &str,
) {
    let (hw, hd) = (0.5 * w, 0.5 * d);
    b.cuboid("bottom", material, [-hw, y0, -hd], [hw, y0 + wall, hd]);
    b.cuboid(
        "wall_back",
        material,
        [-hw, y0, -hd],
        [hw, y0 + h, -hd + wall],
    );
    b.cuboid(
        "wall_front",
        material,
        [-hw, y0, hd - wall],
        [hw, y0 + h, hd],
    );
    b.cuboid(
        "wall_left",
        material,
        [-hw, y0, -hd],
        [-hw + wall, y0 + h, hd],
    );
    b.cuboid(
        "wall_right",
        material,
        [hw - wall, y0, -hd],
        [hw, y0 + h, hd],
    );
    b.surface(rect_surface(
        name,
        SurfaceKind::Interior,
        [-hw + wall, -hd + wall],
        [hw - wall, hd - wall],
        y0 + wall,
        Some(h - wall - 0.005),
        0.01,
    ));
}

/// A lid `t` thick closed on the box of width `w` and depth `d` whose walls end at `top`, hinged
/// along its back top edge and opening up by as much as `open` radians.
fn hinged_lid(b: &mut AssetBuilder, material: usize, w: f32, d: f32, top: f32, t: f32, open: f32) {
    let (hw, hd) = (0.5 * w, 0.5 * d);
    b.joint(articulation::back_hinge("lid", top + t, -hd, open));
    b.link(Some("lid"));
    b.cuboid("lid", material, [-hw, top, -hd], [hw, top + t, hd]);
    b.cuboid(
        "lid_grip",
        material,
        [-0.06, top - 0.015, hd],
        [0.06, top + t, hd + 0.02],
    );
    b.link(None);
}

/// Toy box: width 0.6–1.0, height 0.42–0.58 with its lid, depth 0.35–0.5; a box closed by a lid
/// hinged at its back.
pub(super) fn toy_box(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(
        &mut b,
        0.5,
        Palette::BrightPlastic,
        Palette::PaintedWood,
        rng,
    );
    let (w, h, d) = uniform3(rng, [0.6, 1.0], [0.4, 0.55], [0.35, 0.5]);
    let wall = uniform(rng, 0.015, 0.025);
    open_box(&mut b, body, w, h, d, wall, 0.0, "inside");
    hinged_lid(&mut b, body, w, d, h, wall, articulation::DOOR_OPEN);
    finish(b)
}

/// Chest freezer: width 0.9–1.6, height 0.9–0.96 with its lid, depth 0.6–0.75; insulated walls
/// closed by a lid hinged at its back.
pub(super) fn chest_freezer(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat(&mut b, Palette::Plastic, rng);
    let (w, h, d) = uniform3(rng, [0.9, 1.6], [0.84, 0.9], [0.6, 0.75]);
    let wall = uniform(rng, 0.06, 0.08);
    open_box(&mut b, body, w, h, d, wall, 0.0, "inside");
    hinged_lid(&mut b, body, w, d, h, 0.06, 1.45);
    finish(b)
}

/// Pallet rack: width 1.8–2.8, height 2.0–3.4, depth 0.9–1.1; steel uprights, beam pairs and
/// decks at 2–4 levels (the lowest on the floor).
pub(super) fn pallet_rack(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let upright = b.material(fixed_material("rack_blue", [0x24, 0x50, 0x9C], 0.45, 0.5));
    let beam_m = b.material(fixed_material("rack_orange", [0xE0, 0x6C, 0x1C], 0.45, 0.5));
    let deck = mat_either(&mut b, 0.5, Palette::Wood, Palette::Metal, rng);
    let (w, h, d) = uniform3(rng, [1.8, 2.8], [2.0, 3.4], [0.9, 1.1]);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let post = 0.08;
    for (i, (sx, sz)) in CORNERS.iter().enumerate() {
        let (x, z) = (sx * (hw - 0.5 * post), sz * (hd - 0.5 * post));
        b.part(square_post(
            &format!("upright_{i}"),
            upright,
            [x, z],
            post,
            0.0,
            h,
        ));
    }
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * (hw - 0.5 * post);
        for (k, y) in [0.15, 0.5 * h, h - 0.1].into_iter().enumerate() {
            b.cuboid(
                &format!("side_brace_{i}_{k}"),
                upright,
                [x - 0.02, y - 0.02, -hd],
                [x + 0.02, y + 0.02, hd],
            );
        }
    }
    let levels = int(rng, 2, 4);
    let gap = h / levels as f32;
    let beam_h = 0.1;
    let mut decks = Vec::new();
    for l in 1..levels {
        let y = l as f32 * gap;
        for (k, z) in [-hd + 0.5 * post, hd - 0.5 * post].into_iter().enumerate() {
            b.cuboid(
                &format!("beam_{l}_{k}"),
                beam_m,
                [-hw + post, y - beam_h, z - 0.025],
                [hw - post, y, z + 0.025],
            );
        }
        b.cuboid(
            &format!("deck_{l}"),
            deck,
            [-hw + post, y - 0.01, -hd + 0.02],
            [hw - post, y + 0.02, hd - 0.02],
        );
        decks.push(y + 0.02);
    }
    // The floor bay is the lowest level; the top beams carry one more deck.
    let top_y = h - 0.02;
    for (k, z) in [-hd + 0.5 * post, hd - 0.5 * post].into_iter().enumerate() {
        b.cuboid(
            &format!("beam_top_{k}"),
            beam_m,
            [-hw + post, top_y - beam_h, z - 0.025],
            [hw - post, top_y, z + 0.025],
        );
    }
    let floors: Vec<f32> = std::iter::once(0.0).chain(decks.iter().copied()).collect();
    let ceilings: Vec<f32> = decks
        .iter()
        .map(|y| y - 0.02 - beam_h)
        .chain(std::iter::once(top_y - beam_h))
        .collect();
    for (l, (floor, ceiling)) in floors.iter().zip(&ceilings).enumerate() {
        b.surface(rect_surface(
            &format!("level_{l}"),
            if l == 0 {
                SurfaceKind::Under
            } else {
                SurfaceKind::Shelf
            },
            [-hw + post, -hd + post],
            [hw - post, hd - post],
            *floor,
            Some(ceiling - floor - 0.01),
            0.02,
        ));
    }
    finish(b)
}

/// Shelving unit (wire or steel): width 0.9–1.2, height 1.5–1.9, depth 0.35–0.6; four posts and
/// 4–6 shelves, open all round.
pub(super) fn shelving_unit(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let metal = mat_either(&mut b, 0.6, Palette::Metal, Palette::CoatedMetal, rng);
    let m = CarcassMaterials::uniform(metal, metal);
    let mut c = Carcass {
        width: uniform(rng, 0.9, 1.2),
        height: uniform(rng, 1.5, 1.9),
        depth: uniform(rng, 0.35, 0.6),
        board: 0.02,
        feet: Feet::Legs {
            height: uniform(rng, 0.05, 0.12),
            section: 0.025,
        },
        columns: 1,
        shelves: vec![],
        back: false,
        posts: Some(0.025),
        ..Carcass::PLAIN
    };
    c.shelves = rows_for(rng, &c, 0.26, 0.42);
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    finish(b)
}

/// Medical cart: width 0.5–0.8, height 0.9–1.05, depth 0.42–0.55; drawers under an open bay on
/// casters, a work top and a push handle.
pub(super) fn medical_cart(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.6, Palette::Plastic, Palette::CoatedMetal, rng);
    let drawer = mat(&mut b, Palette::BrightPlastic, rng);
    let handle = mat(&mut b, Palette::Metal, rng);
    let m = CarcassMaterials {
        front: drawer,
        ..CarcassMaterials::uniform(body, handle)
    };
    let w = uniform(rng, 0.5, 0.76);
    let d = uniform(rng, 0.42, 0.5);
    let rows = int(rng, 3, 5);
    let c = Carcass {
        width: w,
        height: uniform(rng, 0.85, 0.98),
        depth: d,
        board: 0.018,
        feet: Feet::Casters {
            height: uniform(rng, 0.1, 0.13),
        },
        columns: 1,
        shelves: Carcass::even_shelves(rows),
        drawer_rows: rows - 1,
        ..Carcass::PLAIN
    };
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    let y = c.height - 0.1;
    for (i, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = sx * 0.5 * w;
        b.part(beam(
            &format!("handle_arm_{i}"),
            handle,
            [x, y, -0.5 * d + 0.05],
            [x + sx * 0.04, y, -0.5 * d + 0.05],
            [0.02, 0.02],
        ));
    }
    b.part(rod(
        "handle_bar",
        handle,
        [-0.5 * w - 0.05, y, -0.5 * d + 0.05],
        [0.5 * w + 0.05, y, -0.5 * d + 0.05],
        0.012,
        0.012,
        10,
    ));
    finish(b)
}

/// Refrigerator: width 0.6–0.8, height 1.7–1.95, depth 0.65–0.75; an open fresh-food section
/// with 3–5 shelves above a freezer drawer, behind a closed hinged door (a pair when wide).
pub(super) fn refrigerator(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.5, Palette::Metal, Palette::Plastic, rng);
    let inside = b.material(fixed_material("fridge_liner", [0xF2, 0xF2, 0xF0], 0.3, 0.0));
    let glass = mat(&mut b, Palette::Glass, rng);
    let handle = mat(&mut b, Palette::Metal, rng);
    let m = CarcassMaterials {
        body,
        shelf: glass,
        side: body,
        back: inside,
        front: body,
        handle,
    };
    let rows = int(rng, 4, 5);
    let freezer = uniform(rng, 0.22, 0.3);
    let mut shelves = vec![freezer];
    shelves.extend((1..rows).map(|i| freezer + (1.0 - freezer) * i as f32 / rows as f32));
    let c = Carcass {
        width: uniform(rng, 0.6, 0.8),
        height: uniform(rng, 1.7, 1.95),
        depth: uniform(rng, 0.65, 0.75),
        board: 0.04,
        feet: Feet::Plinth {
            height: 0.05,
            recess: 0.04,
        },
        columns: 1,
        shelves,
        drawer_rows: 1,
        front: Front::Doors,
        ..Carcass::PLAIN
    };
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    finish(b)
}

/// Drinks fridge (glass-door merchandiser): width 0.55–0.75, height 1.75–2.05, depth 0.6–0.7;
/// 4–6 wire shelves behind a glass door, a lit header panel on top.
pub(super) fn drinks_fridge(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.5, Palette::CoatedMetal, Palette::Plastic, rng);
    let glass = mat(&mut b, Palette::Glass, rng);
    let wire = mat(&mut b, Palette::Metal, rng);
    let header = mat(&mut b, Palette::BrightPlastic, rng);
    let m = CarcassMaterials {
        body,
        shelf: wire,
        side: body,
        back: body,
        front: glass,
        handle: wire,
    };
    let height = uniform(rng, 1.6, 1.85);
    let mut c = Carcass {
        width: uniform(rng, 0.55, 0.75),
        height,
        depth: uniform(rng, 0.6, 0.7),
        board: 0.04,
        feet: Feet::Plinth {
            height: uniform(rng, 0.08, 0.12),
            recess: 0.0,
        },
        columns: 1,
        shelves: vec![],
        front: Front::Glass,
        ..Carcass::PLAIN
    };
    c.shelves = rows_for(rng, &c, 0.22, 0.35);
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    let header_h = uniform(rng, 0.15, 0.2);
    b.cuboid(
        "header",
        header,
        [-0.5 * c.width, height - 0.002, -0.5 * c.depth],
        [0.5 * c.width, height + header_h, 0.5 * c.depth],
    );
    for s in b.surfaces_mut() {
        if s.name == "top" {
            s.height = height + header_h;
        }
    }
    finish(b)
}

/// Fume hood: width 1.2–1.8, height 2.3–2.5, depth 0.75–0.9; a base cabinet with a work surface
/// inside a hood (sides, back, ceiling, raised glass sash).
pub(super) fn fume_hood(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = b.material(fixed_material("lab_white", [0xE8, 0xE8, 0xE4], 0.45, 0.1));
    let top = mat(&mut b, Palette::Stone, rng);
    let glass = mat(&mut b, Palette::Glass, rng);
    let handle = mat(&mut b, Palette::Metal, rng);
    let (w, h, d) = uniform3(rng, [1.2, 1.8], [2.3, 2.5], [0.75, 0.9]);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let base_h = uniform(rng, 0.85, 0.9);
    let c = Carcass {
        width: w,
        height: base_h - 0.03,
        depth: d,
        board: 0.02,
        feet: Feet::Plinth {
            height: 0.1,
            recess: 0.05,
        },
        columns: 2,
        shelves: vec![],
        ..Carcass::PLAIN
    };
    carcass::build(
        &mut b,
        &c,
        CarcassMaterials::uniform(body, handle),
        [0.0, 0.0],
        "base_",
    );
    b.surfaces_mut().retain(|s| s.name != "base_top");
    b.cuboid(
        "work_surface",
        top,
        [-hw, base_h - 0.032, -hd],
        [hw, base_h, hd + 0.02],
    );
    let wall = 0.05;
    b.cuboid(
        "hood_left",
        body,
        [-hw, base_h - 0.002, -hd],
        [-hw + wall, h, hd],
    );
    b.cuboid(
        "hood_right",
        body,
        [hw - wall, base_h - 0.002, -hd],
        [hw, h, hd],
    );
    b.cuboid(
        "hood_back",
        body,
        [-hw, base_h - 0.002, -hd],
        [hw, h, -hd + wall],
    );
    let ceiling = h - uniform(rng, 0.25, 0.35);
    b.cuboid("hood_ceiling", body, [-hw, ceiling, -hd], [hw, h, hd]);
    let sash_bottom = base_h + uniform(rng, 0.35, 0.5);
    b.cuboid(
        "sash",
        glass,
        [-hw + wall, sash_bottom, hd - 0.02],
        [hw - wall, ceiling + 0.002, hd - 0.01],
    );
    b.cuboid(
        "sash_handle",
        handle,
        [-hw + wall, sash_bottom - 0.01, hd - 0.03],
        [hw - wall, sash_bottom + 0.01, hd],
    );
    b.surface(rect_surface(
        "work_surface",
        SurfaceKind::Shelf,
        [-hw + wall, -hd + wall],
        [hw - wall, hd - 0.03],
        base_h,
        Some(sash_bottom - 0.015 - base_h),
        0.03,
    ));
    finish(b)
}

/// Magazine rack: width 0.45–0.9, height 0.8–1.3, depth 0.28–0.4; 3–5 tiers with front lips.
pub(super) fn magazine_rack(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let m = if coin(rng, 0.6) {
        wood_materials(rng, &mut b)
    } else {
        metal_materials(rng, &mut b)
    };
    let rows = int(rng, 3, 5);
    let height = uniform(rng, 0.8, 1.3);
    let c = Carcass {
        width: uniform(rng, 0.45, 0.9),
        height,
        depth: uniform(rng, 0.28, 0.4),
        board: 0.018,
        feet: Feet::Legs {
            height: 0.04,
            section: 0.03,
        },
        columns: 1,
        shelves: Carcass::even_shelves(rows),
        top_board: false,
        lip: uniform(rng, 0.06, 0.1),
        ..Carcass::PLAIN
    };
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    finish(b)
}

/// Dumbbell rack: width 1.0–2.0, height 0.65–0.9, depth 0.45–0.6; two or three open tiers with
/// cradle lips on a steel frame.
pub(super) fn dumbbell_rack(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat(&mut b, Palette::CoatedMetal, rng);
    let tray = mat(&mut b, Palette::Rubber, rng);
    let m = CarcassMaterials {
        shelf: tray,
        ..CarcassMaterials::uniform(frame, frame)
    };
    let rows = int(rng, 2, 3);
    let c = Carcass {
        width: uniform(rng, 1.0, 2.0),
        height: uniform(rng, 0.65, 0.9),
        depth: uniform(rng, 0.45, 0.6),
        board: 0.03,
        feet: Feet::Legs {
            height: 0.12,
            section: 0.05,
        },
        columns: 1,
        shelves: Carcass::even_shelves(rows),
        back: false,
        posts: Some(0.05),
        top_board: false,
        lip: 0.04,
        ..Carcass::PLAIN
    };
    carcass::build(&mut b, &c, m, [0.0, 0.0], "");
    finish(b)
}

/// Cue rack (floor stand): width 0.45–0.8, height 1.2–1.5, depth 0.25–0.35; a base with cup
/// holes, a back board and a slotted top bar holding 4–8 cues upright.
pub(super) fn cue_rack(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let wood = mat(&mut b, Palette::Wood, rng);
    let cue = mat(&mut b, Palette::Wood, rng);
    let (w, h, d) = uniform3(rng, [0.45, 0.8], [1.2, 1.5], [0.25, 0.35]);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    b.cuboid("base", wood, [-hw, 0.0, -hd], [hw, 0.08, hd]);
    b.cuboid("back_board", wood, [-hw, 0.0, -hd], [hw, h, -hd + 0.03]);
    let bar_y = h - uniform(rng, 0.2, 0.35);
    b.cuboid(
        "holder_bar",
        wood,
        [-hw, bar_y, -hd],
        [hw, bar_y + 0.05, -hd + 0.12],
    );
    let cues = int(rng, 4, 8);
    for i in 0..cues {
        let x = -hw + (i as f32 + 0.5) * w / cues as f32;
        let z = -hd + 0.07;
        b.part(rod(
            &format!("cue_{i}"),
            cue,
            [x, 0.079, z + 0.015],
            [x, (1.45f32).min(h + 0.2), z],
            0.014,
            0.007,
            8,
        ));
    }
    finish(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn open_box_interior_is_above_its_bottom() {
        let mut b = AssetBuilder::new();
        let m = b.material(fixed_material("m", [1, 2, 3], 0.5, 0.0));
        open_box(&mut b, m, 1.0, 0.5, 0.8, 0.02, 0.0, "inside");
        let asset = b.finish(Placement::Floor, SCALE);
        let s = &asset.info.support_surfaces[0];
        assert_eq!(s.kind, SurfaceKind::Interior);
        assert!((s.height - 0.02).abs() < 1e-6);
        assert!(asset.mesh.parts.iter().all(|p| p.is_closed_and_oriented()));
    }
}
