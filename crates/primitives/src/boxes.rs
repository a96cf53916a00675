//! Boxes: axis-aligned, oriented, sheared and rounded hexahedra (legs, slabs, beams, struts).

use nalgebra::Rotation3;
use scenethesis_scene_graph::MeshPart;

use crate::{convex_hull, frame, orient_outward, transformed};

/// An axis-aligned box from `min` to `max` (asset frame), 8 vertices and 12 triangles
/// ([`MeshPart::cuboid`]).
pub fn cuboid(name: &str, material: usize, min: [f32; 3], max: [f32; 3]) -> MeshPart {
    MeshPart::cuboid(name, material, min, max)
}

/// A vertical post of square section `side` centred at `center` = (x, z), from `y0` to `y1`:
/// table and bed legs, rack uprights, crate corner posts.
pub fn square_post(
    name: &str,
    material: usize,
    center: [f32; 2],
    side: f32,
    y0: f32,
    y1: f32,
) -> MeshPart {
    let half = 0.5 * side;
    cuboid(
        name,
        material,
        [center[0] - half, y0, center[1] - half],
        [center[0] + half, y1, center[1] + half],
    )
}

/// A hexahedron from its 8 corners, indexed like [`cuboid`]: bit 0 of the index selects the
/// far side along the first edge direction, bit 1 along the second, bit 2 along the third. The
/// part is convex when every face is planar and the corners are in convex position (a sheared
/// or tapered box, a wedge with a non-zero top, a tyre segment). Faces are oriented outward
/// whatever the handedness of the corner order.
pub fn hexahedron(name: &str, material: usize, corners: [[f32; 3]; 8]) -> MeshPart {
    let mut part = MeshPart::from_box_corners(name, material, corners);
    orient_outward(&mut part);
    part
}

/// A box with edge directions `axes` (unit vectors, mutually perpendicular), centred at `center`
/// with half extents `half` along those axes.
pub fn oriented_box(
    name: &str,
    material: usize,
    center: [f32; 3],
    axes: [[f32; 3]; 3],
    half: [f32; 3],
) -> MeshPart {
    let corners = std::array::from_fn(|i| {
        let s = |bit: usize| if i & (1 << bit) == 0 { -1.0 } else { 1.0 };
        std::array::from_fn(|k| {
            center[k]
                + s(0) * half[0] * axes[0][k]
                + s(1) * half[1] * axes[1][k]
                + s(2) * half[2] * axes[2][k]
        })
    });
    hexahedron(name, material, corners)
}

/// A box from `y0` to `y1` with footprint half extents `half` = (x, z), centred at `center` =
/// (x, z) and turned by `yaw` radians about +Y (same sense as a pose's yaw).
pub fn box_yaw(
    name: &str,
    material: usize,
    center: [f32; 2],
    half: [f32; 2],
    y0: f32,
    y1: f32,
    yaw: f32,
) -> MeshPart {
    let (s, c) = yaw.sin_cos();
    oriented_box(
        name,
        material,
        [center[0], 0.5 * (y0 + y1), center[1]],
        [[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]],
        [half[0], 0.5 * (y1 - y0), half[1]],
    )
}

/// A straight bar of rectangular cross-section `section` = (width, thickness) from `a` to `b`
/// (slanted legs, rails, ladder stiles, frames).
pub fn beam(name: &str, material: usize, a: [f32; 3], b: [f32; 3], section: [f32; 2]) -> MeshPart {
    let axis = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let (u, v) = frame(axis);
    let corners = std::array::from_fn(|i| {
        let su = if i & 1 == 0 { -0.5 } else { 0.5 } * section[0];
        let sv = if i & 2 == 0 { -0.5 } else { 0.5 } * section[1];
        let end = if i & 4 == 0 { a } else { b };
        std::array::from_fn(|k| end[k] + su * u[k] + sv * v[k])
    });
    hexahedron(name, material, corners)
}

/// A leg standing flat: a prism of horizontal cross-section `section` = (x, z) sheared from
/// `bottom` up to `top`, with horizontal end faces (splayed legs whose feet rest flat on the
/// floor, ladder stiles, A-frames).
pub fn strut(
    name: &str,
    material: usize,
    bottom: [f32; 3],
    top: [f32; 3],
    section: [f32; 2],
) -> MeshPart {
    let corners = std::array::from_fn(|i| {
        let end = if i & 2 == 0 { bottom } else { top };
        let dx = if i & 1 == 0 { -0.5 } else { 0.5 } * section[0];
        let dz = if i & 4 == 0 { -0.5 } else { 0.5 } * section[1];
        [end[0] + dx, end[1], end[2] + dz]
    });
    hexahedron(name, material, corners)
}

/// A box with half extents `half` centred at the origin, rotated by `rot` and moved to `center`.
pub fn rotated_box(
    name: &str,
    material: usize,
    center: [f32; 3],
    half: [f32; 3],
    rot: &Rotation3<f32>,
) -> MeshPart {
    let part = cuboid(name, material, half.map(|h| -h), half);
    transformed(part, rot, center)
}

/// A rounded box: the convex hull of a superellipsoid with half extents `half` centred at
/// `center` (`roundness` 0 is a sharp box, 1 an ellipsoid).
pub fn rounded_box(
    name: &str,
    material: usize,
    center: [f32; 3],
    half: [f32; 3],
    roundness: f32,
) -> MeshPart {
    let e = roundness.clamp(0.05, 1.0);
    let f = |c: f32| c.signum() * c.abs().powf(e);
    let (rings, segments) = (8, 16);
    let mut points = vec![
        [center[0], center[1] - half[1], center[2]],
        [center[0], center[1] + half[1], center[2]],
    ];
    for r in 1..rings {
        let v = std::f32::consts::PI * (r as f32 / rings as f32 - 0.5);
        for k in 0..segments {
            let u = std::f32::consts::TAU * (k as f32 + 0.5) / segments as f32;
            points.push([
                center[0] + half[0] * f(v.cos()) * f(u.cos()),
                center[1] + half[1] * f(v.sin()),
                center[2] + half[2] * f(v.cos()) * f(u.sin()),
            ]);
        }
    }
    convex_hull(name, material, &points).expect("a rounded box has volume")
}
