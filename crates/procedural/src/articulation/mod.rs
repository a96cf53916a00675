//! Articulated parts shared by the generators: the joints of hinged doors, lids and sliding
//! drawers, and the parts that move with them (a door leaf with its handle, a hollow drawer
//! box). Everything is drawn closed (state 0) in the builder's frame: +Y up, front +Z.
//!
//! Hinge conventions (a positive state opens, by the right-hand rule about the axis):
//! a door hinged on its left edge turns about −Y (its free edge swings toward +Z, opening to
//! the left), on its right edge about +Y; a door hinged at its bottom (an oven) turns about +X
//! and opens down; a lid hinged at its back turns about −X and opens up; a drawer slides
//! along +Z.

use scenethesis_primitives::{rect_surface, AssetBuilder};
use scenethesis_scene_graph::{Joint, JointKind, OpensTo, SurfaceKind};

/// How far a side-hinged door or a back-hinged lid opens: a quarter turn (90°), square to
/// its body. The judge asks every part to open through [`OPEN_SHARE`](scenethesis_scene_graph::OPEN_SHARE)
/// of its range freely, here 81°. A door turns about its outer front corner, so the leaf stays
/// behind the body's side; only its handle, 2.4 cm proud near the free edge, swings past that
/// side as the door nears square. At 81° it stays behind the side for any door wider than
/// 0.2 m, so a locker standing a centimetre from a side wall opens (at 88°, the test of a
/// 97° hinge, the handle met the wall).
pub(crate) const DOOR_OPEN: f32 = std::f32::consts::FRAC_PI_2;

/// A revolute joint named `name` through `anchor` about `axis`, open up to `open` radians.
pub(crate) fn hinge(
    name: &str,
    anchor: [f32; 3],
    axis: [f32; 3],
    open: f32,
    opens_to: OpensTo,
) -> Joint {
    Joint {
        name: name.to_owned(),
        kind: JointKind::Revolute,
        axis,
        anchor,
        limits: [0.0, open],
        opens_to,
        parent: None,
    }
}

/// A vertical hinge at (`x`, `z`) for a door hinged on its left edge (`hinge_left`) or on its
/// right edge, opening outward (toward +Z) by up to [`DOOR_OPEN`].
pub(crate) fn side_hinge(name: &str, x: f32, y: f32, z: f32, hinge_left: bool) -> Joint {
    if hinge_left {
        hinge(name, [x, y, z], [0.0, -1.0, 0.0], DOOR_OPEN, OpensTo::Left)
    } else {
        hinge(name, [x, y, z], [0.0, 1.0, 0.0], DOOR_OPEN, OpensTo::Right)
    }
}

/// A horizontal hinge along x at height `y`, depth `z`, for a door hinged at its bottom that
/// falls open toward +Z by up to `open` radians (an oven, a dishwasher).
pub(crate) fn bottom_hinge(name: &str, y: f32, z: f32, open: f32) -> Joint {
    hinge(name, [0.0, y, z], [1.0, 0.0, 0.0], open, OpensTo::Down)
}

/// A horizontal hinge along x at height `y`, depth `z`, for a lid hinged at its back that
/// lifts up by up to `open` radians (a chest, a toilet lid).
pub(crate) fn back_hinge(name: &str, y: f32, z: f32, open: f32) -> Joint {
    hinge(name, [0.0, y, z], [-1.0, 0.0, 0.0], open, OpensTo::Up)
}

/// A prismatic joint sliding out along +Z by up to `travel` metres, anchored at the closed
/// front centre `anchor`.
pub(crate) fn slide(name: &str, anchor: [f32; 3], travel: f32) -> Joint {
    Joint {
        name: name.to_owned(),
        kind: JointKind::Prismatic,
        axis: [0.0, 0.0, 1.0],
        anchor,
        limits: [0.0, travel],
        opens_to: OpensTo::Out,
        parent: None,
    }
}

/// The materials of a moving part: its panel and its handle.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LinkMaterials {
    /// The door leaf or drawer box.
    pub panel: usize,
    /// The handle.
    pub handle: usize,
}

/// A side-hinged door leaf, closed: its extent, its back face on the plane `z`, its
/// thickness, and the edge it hangs on.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Leaf {
    /// Left and right edges.
    pub x: [f32; 2],
    /// Bottom and top edges.
    pub y: [f32; 2],
    /// The back face's z (the body's front face).
    pub z: f32,
    /// Thickness toward +Z.
    pub thickness: f32,
    /// Hinged on its left edge (else its right edge).
    pub hinge_left: bool,
}

/// Adds the door leaf `name`, hinged at its outer front corner so that it swings clear of the
/// body, with a vertical bar handle near its free edge.
pub(crate) fn door(b: &mut AssetBuilder, name: &str, m: LinkMaterials, leaf: Leaf) {
    let Leaf {
        x,
        y,
        z,
        thickness,
        hinge_left,
    } = leaf;
    let hinge_x = if hinge_left { x[0] } else { x[1] };
    b.joint(side_hinge(name, hinge_x, y[0], z + thickness, hinge_left));
    b.link(Some(name));
    b.cuboid(name, m.panel, [x[0], y[0], z], [x[1], y[1], z + thickness]);
    let inset = (0.15 * (x[1] - x[0])).min(0.05);
    let hx = if hinge_left {
        x[1] - inset
    } else {
        x[0] + inset
    };
    let half = (0.15 * (y[1] - y[0])).clamp(0.04, 0.12);
    let hy = if y[1] - y[0] > 1.2 {
        y[0] + 0.5 * (y[1] - y[0]).min(2.0)
    } else {
        0.5 * (y[0] + y[1])
    };
    bar_handle(
        b,
        &format!("{name}_handle"),
        m.handle,
        [hx, hy, z + thickness],
        [0.0, half],
    );
    b.link(None);
}

/// Adds a bar handle standing `0.022` m proud of the face at `base` = (x, y, face z): a grip
/// of half extents `half` = (along x, along y) on two short standoffs.
pub(crate) fn bar_handle(
    b: &mut AssetBuilder,
    name: &str,
    material: usize,
    base: [f32; 3],
    half: [f32; 2],
) {
    let [x, y, z] = base;
    let (gx, gy) = (half[0].max(0.007), half[1].max(0.007));
    b.cuboid(
        name,
        material,
        [x - gx, y - gy, z + 0.014],
        [x + gx, y + gy, z + 0.024],
    );
    let ends: [[f32; 2]; 2] = if half[0] >= half[1] {
        [[x - 0.8 * gx, y], [x + 0.8 * gx, y]]
    } else {
        [[x, y - 0.8 * gy], [x, y + 0.8 * gy]]
    };
    for (k, [ex, ey]) in ends.into_iter().enumerate() {
        b.cuboid(
            &format!("{name}_post_{k}"),
            material,
            [ex - 0.005, ey - 0.005, z - 0.001],
            [ex + 0.005, ey + 0.005, z + 0.0145],
        );
    }
}

/// A drawer's outer box: x, y and z ranges (z from its back to the front face of its front
/// panel).
#[derive(Debug, Clone, Copy)]
pub(crate) struct DrawerBox {
    /// Left and right outer faces.
    pub x: [f32; 2],
    /// Underside and top of the front panel.
    pub y: [f32; 2],
    /// Back face and the front panel's front face.
    pub z: [f32; 2],
    /// Free height above the front panel's top before the body above (the board over the
    /// drawer's bay), added to the interior's clearance.
    pub headroom: f32,
}

/// Front panel, side, back and bottom board thickness of a drawer.
const DRAWER_FRONT: f32 = 0.018;
const DRAWER_WALL: f32 = 0.012;

/// Adds the hollow drawer `name`: a front panel, two sides, a back and a bottom around an open
/// top, sliding out along +Z by 0.8 of its depth, with a horizontal bar handle on the front and
/// an `Interior` support surface (`{name}_interior`) on its inside bottom.
pub(crate) fn drawer(b: &mut AssetBuilder, name: &str, m: LinkMaterials, d: DrawerBox) {
    let ([x0, x1], [y0, y1], [z0, z1]) = (d.x, d.y, d.z);
    let (t, w) = (DRAWER_FRONT, DRAWER_WALL);
    let side_top = y1 - (0.15 * (y1 - y0)).min(0.03);
    let (mx, my) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    b.joint(slide(name, [mx, my, z1], 0.8 * (z1 - z0)));
    b.link(Some(name));
    b.cuboid(
        &format!("{name}_front"),
        m.panel,
        [x0, y0, z1 - t],
        [x1, y1, z1],
    );
    b.cuboid(
        &format!("{name}_bottom"),
        m.panel,
        [x0, y0, z0],
        [x1, y0 + w, z1 - t + 0.001],
    );
    b.cuboid(
        &format!("{name}_back"),
        m.panel,
        [x0, y0 + w - 0.001, z0],
        [x1, side_top, z0 + w],
    );
    for (side, (a, c)) in [("left", (x0, x0 + w)), ("right", (x1 - w, x1))] {
        b.cuboid(
            &format!("{name}_side_{side}"),
            m.panel,
            [a, y0 + w - 0.001, z0 + w - 0.001],
            [c, side_top, z1 - t + 0.001],
        );
    }
    let half = (0.25 * (x1 - x0)).min(0.08);
    bar_handle(
        b,
        &format!("{name}_handle"),
        m.handle,
        [mx, my, z1],
        [half, 0.0],
    );
    b.link(None);
    b.surface(rect_surface(
        &format!("{name}_interior"),
        SurfaceKind::Interior,
        [x0 + w, z0 + w],
        [x1 - w, z1 - t],
        y0 + w,
        Some(y1 + d.headroom - (y0 + w)),
        0.01,
    ));
}
