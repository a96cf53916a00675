//! The carcass family: a box of boards split into columns and rows of open compartments, with
//! optional drawers, glass doors, doors, lips, and feet. Bookshelves, cabinets,
//! lockers, wardrobes, fridges, counters and stands are all carcasses with different numbers.
//!
//! The open side faces +Z. Every compartment that is not a drawer becomes a
//! [`SurfaceKind::Shelf`] support surface whose clearance reaches the underside of the board
//! above it. Doors and drawers are moving links drawn closed: doors on vertical hinges at
//! their outer edge, drawers as hollow boxes sliding out along +Z (see
//! [`crate::articulation`]).

use crate::articulation::{self, DrawerBox, Leaf, LinkMaterials};
use scenethesis_primitives::{cylinder, ellipsoid, rect_surface, square_post, AssetBuilder};
use scenethesis_scene_graph::SurfaceKind;

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
    /// Hinged glass doors over the whole front (display cases, drinks fridges).
    Glass,
    /// Hinged doors above the drawer rows, drawn closed.
    Doors,
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

    /// The materials of the doors and drawers: the front and the handles.
    pub fn link(&self) -> LinkMaterials {
        LinkMaterials {
            panel: self.front,
            handle: self.handle,
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
    /// The lowest rows are closed by drawers (hollow drawer boxes with handles, sliding out).
    pub drawer_rows: usize,
    pub back: bool,
    /// Corner posts of this section instead of side boards and dividers.
    pub posts: Option<f32>,
    pub top_board: bool,
    pub front: Front,
    /// A retaining lip of this height at the front of every open compartment (0 for none).
    pub lip: f32,
    /// Columns left open when the front has doors (a TV stand's middle bays).
    pub open_columns: Vec<usize>,
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
        open_columns: Vec::new(),
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
    let f = Frame::new(c, m, center, prefix);
    f.add_feet(b);
    f.add_body(b);
    let floors = f.add_rows(b);
    f.add_front(b, &floors);
    if c.top_board {
        b.top_surface(
            &format!("{prefix}top"),
            [f.cx - f.hw, f.cz - f.hd],
            [f.cx + f.hw, f.cz + f.hd],
            f.h,
            0.03,
        );
    }
}

/// Thickness of a glass front.
const GLASS_T: f32 = 0.008;

/// A carcass being built: its parts' materials, name prefix and the measures every phase
/// shares (asset frame, metres).
struct Frame<'a> {
    c: &'a Carcass,
    m: CarcassMaterials,
    prefix: &'a str,
    /// Centre of the footprint.
    cx: f32,
    cz: f32,
    /// Half width, half depth and board thickness.
    hw: f32,
    hd: f32,
    t: f32,
    /// Underside of the bottom board, and the total height.
    y0: f32,
    h: f32,
    /// Front face of the back board, and the front of the compartments.
    zb: f32,
    zf: f32,
    /// Interior x range between the sides (or posts) and y range between bottom and top.
    xi0: f32,
    xi1: f32,
    yi0: f32,
    yi1: f32,
    /// Clear width of one column.
    column_w: f32,
}

impl<'a> Frame<'a> {
    fn new(c: &'a Carcass, m: CarcassMaterials, center: [f32; 2], prefix: &'a str) -> Self {
        let (cx, cz) = (center[0], center[1]);
        let (hw, hd, t) = (0.5 * c.width, 0.5 * c.depth, c.board);
        let y0 = c.body_bottom();
        let h = c.height;
        let back_t = if c.back { (0.6 * t).max(0.008) } else { 0.0 };
        let zb = cz - hd + back_t;
        let zf = cz + hd;
        let (xi0, xi1) = match c.posts {
            Some(p) => (cx - hw + p, cx + hw - p),
            None => (cx - hw + t, cx + hw - t),
        };
        let yi0 = y0 + t;
        let yi1 = if c.top_board { h - t } else { h };
        let column_w = (xi1 - xi0 - (c.columns as f32 - 1.0) * t) / c.columns as f32;
        Self {
            c,
            m,
            prefix,
            cx,
            cz,
            hw,
            hd,
            t,
            y0,
            h,
            zb,
            zf,
            xi0,
            xi1,
            yi0,
            yi1,
            column_w,
        }
    }

    /// Left edge of column `i`'s clear space.
    fn column_x0(&self, i: usize) -> f32 {
        self.xi0 + i as f32 * (self.column_w + self.t)
    }

    /// Feet: a plinth, legs (with the surface under the body when tall enough) or casters.
    fn add_feet(&self, b: &mut AssetBuilder) {
        let (prefix, m) = (self.prefix, self.m);
        let (cx, cz, hw, hd) = (self.cx, self.cz, self.hw, self.hd);
        match self.c.feet {
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
    }

    /// Body boards: bottom, top, back, then the sides and dividers (or the corner posts).
    fn add_body(&self, b: &mut AssetBuilder) {
        let (c, prefix, m) = (self.c, self.prefix, self.m);
        let (cx, cz, hw, hd, h, y0) = (self.cx, self.cz, self.hw, self.hd, self.h, self.y0);
        b.cuboid(
            &format!("{prefix}bottom"),
            m.body,
            [cx - hw, y0, cz - hd],
            [cx + hw, self.yi0, cz + hd],
        );
        if c.top_board {
            b.cuboid(
                &format!("{prefix}top"),
                m.body,
                [cx - hw, h - self.t, cz - hd],
                [cx + hw, h, cz + hd],
            );
        }
        if c.back {
            b.cuboid(
                &format!("{prefix}back"),
                m.back,
                [cx - hw, y0, cz - hd],
                [cx + hw, h, self.zb],
            );
        }
        let side_y0 = match c.feet {
            Feet::Plinth { .. } => 0.0,
            _ => y0,
        };
        match c.posts {
            Some(p) => self.add_posts(b, p, side_y0),
            None => self.add_sides(b, side_y0),
        }
    }

    /// Corner posts of section `p` instead of side boards, and posts between the columns.
    fn add_posts(&self, b: &mut AssetBuilder, p: f32, side_y0: f32) {
        let (cx, cz, hw, hd, t) = (self.cx, self.cz, self.hw, self.hd, self.t);
        let mut xs = vec![cx - hw + 0.5 * p, cx + hw - 0.5 * p];
        xs.extend((1..self.c.columns).map(|i| self.column_x0(i) - 0.5 * t));
        for (i, x) in xs.into_iter().enumerate() {
            for (k, z) in [cz - hd + 0.5 * p, cz + hd - 0.5 * p]
                .into_iter()
                .enumerate()
            {
                b.part(square_post(
                    &format!("{}post_{i}_{k}", self.prefix),
                    self.m.side,
                    [x, z],
                    p,
                    side_y0,
                    self.h,
                ));
            }
        }
    }

    /// Side boards and the dividers between the columns.
    fn add_sides(&self, b: &mut AssetBuilder, side_y0: f32) {
        let (prefix, m) = (self.prefix, self.m);
        let (cx, cz, hw, hd, h, t) = (self.cx, self.cz, self.hw, self.hd, self.h, self.t);
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
        for i in 1..self.c.columns {
            let x = self.column_x0(i);
            b.cuboid(
                &format!("{prefix}divider_{i}"),
                m.body,
                [x - t, self.yi0 - 0.001, self.zb - 0.001],
                [x, self.yi1 + 0.001, self.zf],
            );
        }
    }

    /// Rows: the shelf boards, then each compartment (a drawer, or an open shelf surface with
    /// its lip). Returns the rows' floors, bottom up.
    fn add_rows(&self, b: &mut AssetBuilder) -> Vec<f32> {
        let t = self.t;
        let (yi0, yi1) = (self.yi0, self.yi1);
        let mut floors = vec![yi0];
        let mut ceilings = Vec::new();
        for (k, f) in self.c.shelves.iter().enumerate() {
            let y = yi0 + f * (yi1 - yi0);
            let (lo, hi) = (y - 0.5 * t, y + 0.5 * t);
            b.cuboid(
                &format!("{}shelf_{k}", self.prefix),
                self.m.shelf,
                [self.xi0 - 0.001, lo, self.zb - 0.001],
                [self.xi1 + 0.001, hi, self.zf - 0.005],
            );
            ceilings.push(lo);
            floors.push(hi);
        }
        ceilings.push(yi1);
        let rows = floors.len();
        for col in 0..self.c.columns {
            for row in 0..rows {
                let span = [floors[row], ceilings[row]];
                if row < self.c.drawer_rows {
                    self.add_drawer(b, col, row, span);
                } else {
                    self.add_compartment(b, col, row, span, row + 1 == rows);
                }
            }
        }
        floors
    }

    /// The hollow drawer closing compartment (`col`, `row`) between `span` (floor, ceiling),
    /// its front slightly proud of the body.
    fn add_drawer(&self, b: &mut AssetBuilder, col: usize, row: usize, span: [f32; 2]) {
        let (x0, x1) = (self.column_x0(col), self.column_x0(col) + self.column_w);
        let gap = 0.003;
        articulation::drawer(
            b,
            &format!("{}drawer_{col}_{row}", self.prefix),
            self.m.link(),
            DrawerBox {
                x: [x0 + gap, x1 - gap],
                y: [span[0] + gap, span[1] - gap],
                z: [self.zb + 0.02, self.cz + self.hd + 0.006],
                headroom: gap,
            },
        );
    }

    /// The open compartment (`col`, `row`) between `span` (floor, ceiling): its lip and its
    /// support surface (a top surface when it is the last row and nothing covers it).
    fn add_compartment(
        &self,
        b: &mut AssetBuilder,
        col: usize,
        row: usize,
        span: [f32; 2],
        last_row: bool,
    ) {
        let (c, prefix, zf) = (self.c, self.prefix, self.zf);
        let (x0, x1) = (self.column_x0(col), self.column_x0(col) + self.column_w);
        let (floor, ceiling) = (span[0], span[1]);
        let name = if c.columns == 1 {
            format!("{prefix}shelf_{row}")
        } else {
            format!("{prefix}shelf_{col}_{row}")
        };
        let mut front = zf;
        if c.lip > 0.0 {
            let lip_t = 0.012;
            b.cuboid(
                &format!("{prefix}lip_{col}_{row}"),
                self.m.shelf,
                [x0, floor - 0.001, zf - 0.005 - lip_t],
                [x1, floor + c.lip, zf - 0.005],
            );
            front = zf - 0.005 - lip_t;
        }
        let open_above = last_row && !c.top_board;
        b.surface(rect_surface(
            &name,
            if open_above {
                SurfaceKind::Top
            } else {
                SurfaceKind::Shelf
            },
            [x0, self.zb],
            [x1, front],
            floor,
            (!open_above).then_some(ceiling - floor),
            0.015,
        ));
    }

    /// Front: nothing, or closed glass or board doors over the body's front face (above the
    /// drawer rows; `floors` are the rows' floors): one door per column, or a pair when the
    /// column is wide, hinged on the outer edges.
    fn add_front(&self, b: &mut AssetBuilder, floors: &[f32]) {
        let (y0, thickness) = match self.c.front {
            Front::Open => return,
            Front::Glass => (self.y0, GLASS_T),
            Front::Doors => (
                floors
                    .get(self.c.drawer_rows)
                    .map_or(self.y0, |f| f - self.t),
                self.t.max(0.015),
            ),
        };
        let (t, n) = (self.t, self.c.columns);
        let m = self.m.link();
        let mut door = 0;
        for col in (0..n).filter(|c| !self.c.open_columns.contains(c)) {
            let x0 = if col == 0 {
                self.cx - self.hw
            } else {
                self.column_x0(col) - 0.5 * t
            };
            let x1 = if col + 1 == n {
                self.cx + self.hw
            } else {
                self.column_x0(col) + self.column_w + 0.5 * t
            };
            let leaves: Vec<(f32, f32, bool)> = if x1 - x0 > 0.65 {
                let mid = 0.5 * (x0 + x1);
                vec![(x0, mid, true), (mid, x1, false)]
            } else {
                vec![(x0, x1, 2 * col < n)]
            };
            for (a, c, hinge_left) in leaves {
                articulation::door(
                    b,
                    &format!("{}door_{door}", self.prefix),
                    m,
                    Leaf {
                        x: [a + 0.002, c - 0.002],
                        y: [y0 + 0.002, self.h],
                        z: self.cz + self.hd,
                        thickness,
                        hinge_left,
                    },
                );
                door += 1;
            }
        }
    }
}

/// The four corner signs, counter-clockwise.
pub(super) const CORNERS: [(f32, f32); 4] = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
