//! The carcass family: a box of boards split into columns and rows of open compartments, with
//! optional drawers, glass front, doors left open, lips, and feet. Bookshelves, cabinets,
//! lockers, wardrobes, fridges, counters and stands are all carcasses with different numbers.
//!
//! The open side faces +Z. Every open compartment becomes a [`SurfaceKind::Shelf`] support
//! surface whose clearance reaches the underside of the board above it.

use std::f32::consts::PI;

use rand_chacha::ChaCha8Rng;

use crate::primitives::{box_yaw, cylinder, ellipsoid, rect_surface, square_post, AssetBuilder};
use crate::random::{coin, uniform};
use crate::SurfaceKind;

/// What the carcass body stands on.
#[derive(Debug, Clone, Copy)]
pub(super) enum Feet {
    /// A solid kick plinth of this height, set back by `recess` at the front.
    Plinth { height: f32, recess: f32 },
    /// Four square legs of this height and section.
    Legs { height: f32, section: f32 },
    /// Four casters (wheel radius about a third of the height).
    Casters { height: f32 },
}

impl Feet {
    fn height(&self) -> f32 {
        match *self {
            Feet::Plinth { height, .. } | Feet::Legs { height, .. } | Feet::Casters { height } => {
                height
            }
        }
    }
}

/// How the front is closed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Front {
    /// Open compartments.
    Open,
    /// A glass pane over the whole front (display cases, drinks fridges).
    Glass,
    /// Hinged doors swung open by this angle in radians (π/2 is square to the front).
    Doors { angle: f32 },
}

impl Front {
    /// Doors left open just past square (1.6–1.75 rad).
    pub fn doors_left_open(rng: &mut ChaCha8Rng) -> Self {
        Front::Doors {
            angle: uniform(rng, 1.6, 1.75),
        }
    }

    /// Doors left open (as [`Front::doors_left_open`]) with probability `p`, otherwise an open
    /// front.
    pub fn doors_or_open(rng: &mut ChaCha8Rng, p: f64) -> Self {
        if coin(rng, p) {
            Self::doors_left_open(rng)
        } else {
            Front::Open
        }
    }
}

/// The materials of a carcass.
#[derive(Debug, Clone, Copy)]
pub(super) struct CarcassMaterials {
    pub body: usize,
    pub shelf: usize,
    pub side: usize,
    pub back: usize,
    pub front: usize,
    pub handle: usize,
}

impl CarcassMaterials {
    /// Everything in one material except handles.
    pub fn uniform(body: usize, handle: usize) -> Self {
        Self {
            body,
            shelf: body,
            side: body,
            back: body,
            front: body,
            handle,
        }
    }
}

/// The parameters of a carcass.
#[derive(Debug, Clone)]
pub(super) struct Carcass {
    pub width: f32,
    pub height: f32,
    pub depth: f32,
    pub board: f32,
    pub feet: Feet,
    pub columns: usize,
    /// Shelf board positions as ascending fractions in (0, 1) of the interior height.
    pub shelves: Vec<f32>,
    /// The lowest rows are closed by drawers (solid drawer boxes with handles).
    pub drawer_rows: usize,
    pub back: bool,
    /// Corner posts of this section instead of side boards and dividers.
    pub posts: Option<f32>,
    pub top_board: bool,
    pub front: Front,
    /// A retaining lip of this height at the front of every open compartment (0 for none).
    pub lip: f32,
}

impl Carcass {
    /// A carcass without optional parts: no drawers, a back, side boards rather than posts, a
    /// top board, an open front and no lip. Its size, board, feet, columns and shelves are zero
    /// or empty: generators set those and take the rest from here with `..Carcass::PLAIN`.
    pub const PLAIN: Carcass = Carcass {
        width: 0.0,
        height: 0.0,
        depth: 0.0,
        board: 0.0,
        feet: Feet::Plinth {
            height: 0.0,
            recess: 0.0,
        },
        columns: 0,
        shelves: Vec::new(),
        drawer_rows: 0,
        back: true,
        posts: None,
        top_board: true,
        front: Front::Open,
        lip: 0.0,
    };

    /// Evenly spaced shelves giving `rows` rows.
    pub fn even_shelves(rows: usize) -> Vec<f32> {
        (1..rows).map(|i| i as f32 / rows as f32).collect()
    }

    /// The number of rows that keeps each compartment's clear height between `lo` and `hi`
    /// metres for this interior height and board, as a range of admissible counts.
    pub fn row_counts(interior: f32, board: f32, lo: f32, hi: f32) -> (usize, usize) {
        let max = ((interior + board) / (lo + board)).floor().max(1.0) as usize;
        let min = ((interior + board) / (hi + board)).ceil().max(1.0) as usize;
        (min.min(max), max)
    }

    /// Height of the bottom board's underside.
    pub fn body_bottom(&self) -> f32 {
        self.feet.height()
    }

    /// Interior height between the bottom board and the top board (or the top edge).
    pub fn interior_height(&self) -> f32 {
        let top = if self.top_board {
            self.height - self.board
        } else {
            self.height
        };
        top - (self.body_bottom() + self.board)
    }
}

/// Adds the carcass centred at (`center` x, z) to `b`, with support surfaces named with
/// `prefix` (e.g. `shelf_0_2` for column 0, row 2).
pub(super) fn build(
    b: &mut AssetBuilder,
    c: &Carcass,
    m: CarcassMaterials,
    center: [f32; 2],
    prefix: &str,
) {
    let (cx, cz) = (center[0], center[1]);
    let (hw, hd, t) = (0.5 * c.width, 0.5 * c.depth, c.board);
    let y0 = c.body_bottom();
    let h = c.height;
    let back_t = if c.back { (0.6 * t).max(0.008) } else { 0.0 };
    let glass_t = 0.008;
    let zb = cz - hd + back_t;
    let mut zf = cz + hd;
    if c.front == Front::Glass {
        zf -= glass_t;
    }
    let (xi0, xi1) = match c.posts {
        Some(p) => (cx - hw + p, cx + hw - p),
        None => (cx - hw + t, cx + hw - t),
    };
    let yi0 = y0 + t;
    let yi1 = if c.top_board { h - t } else { h };

    // Feet.
    match c.feet {
        Feet::Plinth { height, recess } => b.cuboid(
            &format!("{prefix}plinth"),
            m.body,
            [cx - hw + 0.01, 0.0, cz - hd + 0.01],
            [cx + hw - 0.01, height + 0.002, cz + hd - recess],
        ),
        Feet::Legs { height, section } => {
            for (i, (sx, sz)) in CORNERS.iter().enumerate() {
                let (x, z) = (
                    cx + sx * (hw - 0.02 - 0.5 * section),
                    cz + sz * (hd - 0.02 - 0.5 * section),
                );
                b.part(square_post(
                    &format!("{prefix}leg_{i}"),
                    m.body,
                    [x, z],
                    section,
                    0.0,
                    height + 0.005,
                ));
            }
            if height >= 0.12 {
                let (ix, iz) = (hw - 0.02 - section, hd - 0.02 - section);
                b.surface(rect_surface(
                    &format!("{prefix}under"),
                    SurfaceKind::Under,
                    [cx - ix, cz - iz],
                    [cx + ix, cz + iz],
                    0.0,
                    Some(height - 0.02),
                    0.02,
                ));
            }
        }
        Feet::Casters { height } => {
            let r = 0.35 * height;
            for (i, (sx, sz)) in CORNERS.iter().enumerate() {
                let (x, z) = (cx + sx * (hw - 0.05), cz + sz * (hd - 0.05));
                b.part(ellipsoid(
                    &format!("{prefix}wheel_{i}"),
                    m.handle,
                    [x, r, z],
                    [0.4 * r, r, r],
                    6,
                    10,
                ));
                b.part(cylinder(
                    &format!("{prefix}caster_{i}"),
                    m.handle,
                    [x, z],
                    0.6 * r,
                    1.6 * r,
                    height + 0.003,
                    8,
                ));
            }
        }
    }

    // Body boards.
    b.cuboid(
        &format!("{prefix}bottom"),
        m.body,
        [cx - hw, y0, cz - hd],
        [cx + hw, yi0, cz + hd],
    );
    if c.top_board {
        b.cuboid(
            &format!("{prefix}top"),
            m.body,
            [cx - hw, h - t, cz - hd],
            [cx + hw, h, cz + hd],
        );
    }
    if c.back {
        b.cuboid(
            &format!("{prefix}back"),
            m.back,
            [cx - hw, y0, cz - hd],
            [cx + hw, h, zb],
        );
    }
    let side_y0 = match c.feet {
        Feet::Plinth { .. } => 0.0,
        _ => y0,
    };
    let column_w = (xi1 - xi0 - (c.columns as f32 - 1.0) * t) / c.columns as f32;
    let column_x0 = |i: usize| xi0 + i as f32 * (column_w + t);
    match c.posts {
        Some(p) => {
            let mut xs = vec![cx - hw + 0.5 * p, cx + hw - 0.5 * p];
            xs.extend((1..c.columns).map(|i| column_x0(i) - 0.5 * t));
            for (i, x) in xs.into_iter().enumerate() {
                for (k, z) in [cz - hd + 0.5 * p, cz + hd - 0.5 * p]
                    .into_iter()
                    .enumerate()
                {
                    b.part(square_post(
                        &format!("{prefix}post_{i}_{k}"),
                        m.side,
                        [x, z],
                        p,
                        side_y0,
                        h,
                    ));
                }
            }
        }
        None => {
            b.cuboid(
                &format!("{prefix}side_left"),
                m.side,
                [cx - hw, side_y0, cz - hd],
                [cx - hw + t, h, cz + hd],
            );
            b.cuboid(
                &format!("{prefix}side_right"),
                m.side,
                [cx + hw - t, side_y0, cz - hd],
                [cx + hw, h, cz + hd],
            );
            for i in 1..c.columns {
                let x = column_x0(i);
                b.cuboid(
                    &format!("{prefix}divider_{i}"),
                    m.body,
                    [x - t, yi0 - 0.001, zb - 0.001],
                    [x, yi1 + 0.001, zf],
                );
            }
        }
    }

    // Rows: floors and ceilings.
    let mut floors = vec![yi0];
    let mut ceilings = Vec::new();
    for (k, f) in c.shelves.iter().enumerate() {
        let y = yi0 + f * (yi1 - yi0);
        let (lo, hi) = (y - 0.5 * t, y + 0.5 * t);
        b.cuboid(
            &format!("{prefix}shelf_{k}"),
            m.shelf,
            [xi0 - 0.001, lo, zb - 0.001],
            [xi1 + 0.001, hi, zf - 0.005],
        );
        ceilings.push(lo);
        floors.push(hi);
    }
    ceilings.push(yi1);
    let rows = floors.len();

    for col in 0..c.columns {
        let (x0, x1) = (column_x0(col), column_x0(col) + column_w);
        for row in 0..rows {
            let (floor, ceiling) = (floors[row], ceilings[row]);
            let name = if c.columns == 1 {
                format!("{prefix}shelf_{row}")
            } else {
                format!("{prefix}shelf_{col}_{row}")
            };
            if row < c.drawer_rows {
                let gap = 0.003;
                b.cuboid(
                    &format!("{prefix}drawer_{col}_{row}"),
                    m.front,
                    [x0 + gap, floor + gap, zb + 0.02],
                    [x1 - gap, ceiling - gap, cz + hd + 0.006],
                );
                let (mx, my) = (0.5 * (x0 + x1), 0.5 * (floor + ceiling));
                let hl = (0.25 * (x1 - x0)).min(0.08);
                b.cuboid(
                    &format!("{prefix}drawer_handle_{col}_{row}"),
                    m.handle,
                    [mx - hl, my - 0.008, cz + hd + 0.005],
                    [mx + hl, my + 0.008, cz + hd + 0.025],
                );
                continue;
            }
            let mut front = zf;
            if c.lip > 0.0 {
                let lip_t = 0.012;
                b.cuboid(
                    &format!("{prefix}lip_{col}_{row}"),
                    m.shelf,
                    [x0, floor - 0.001, zf - 0.005 - lip_t],
                    [x1, floor + c.lip, zf - 0.005],
                );
                front = zf - 0.005 - lip_t;
            }
            let open_above = row + 1 == rows && !c.top_board;
            b.surface(rect_surface(
                &name,
                if open_above {
                    SurfaceKind::Top
                } else {
                    SurfaceKind::Shelf
                },
                [x0, zb],
                [x1, front],
                floor,
                (!open_above).then_some(ceiling - floor),
                0.015,
            ));
        }
    }

    // Front.
    match c.front {
        Front::Open => {}
        Front::Glass => b.cuboid(
            &format!("{prefix}glass_front"),
            m.front,
            [cx - hw, y0, cz + hd - glass_t],
            [cx + hw, h, cz + hd],
        ),
        Front::Doors { angle } => {
            let door_y0 = floors.get(c.drawer_rows).map_or(y0, |f| f - t);
            let door_t = t.max(0.015);
            let mut door = 0;
            for col in 0..c.columns {
                let (x0, x1) = (column_x0(col) - t, column_x0(col) + column_w + t);
                let pair = x1 - x0 > 0.65;
                let leaves: Vec<(f32, f32, bool)> = if pair {
                    let mid = 0.5 * (x0 + x1);
                    vec![(x0, mid, true), (mid, x1, false)]
                } else {
                    vec![(x0, x1, col % 2 == 0)]
                };
                for (a, bx, hinge_left) in leaves {
                    let width = bx - a - 0.004;
                    let (hinge_x, dir_x, yaw) = if hinge_left {
                        (a, angle.cos(), -angle)
                    } else {
                        (bx, -angle.cos(), angle + PI)
                    };
                    let dir_z = angle.sin();
                    // The door's inner face stays at the hinge line, so it never enters a bay.
                    let along = 0.5 * width;
                    let out = 0.5 * door_t;
                    let normal = if hinge_left {
                        [dir_z, -dir_x]
                    } else {
                        [-dir_z, dir_x]
                    };
                    let centre = [
                        hinge_x + dir_x * along + normal[0] * out,
                        cz + hd + dir_z * along + normal[1] * out,
                    ];
                    b.part(box_yaw(
                        &format!("{prefix}door_{door}"),
                        m.front,
                        centre,
                        [0.5 * width, 0.5 * door_t],
                        door_y0,
                        h,
                        yaw,
                    ));
                    door += 1;
                }
            }
        }
    }

    if c.top_board {
        b.top_surface(
            &format!("{prefix}top"),
            [cx - hw, cz - hd],
            [cx + hw, cz + hd],
            h,
            0.03,
        );
    }
}

/// The four corner signs, counter-clockwise.
pub(super) const CORNERS: [(f32, f32); 4] = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
