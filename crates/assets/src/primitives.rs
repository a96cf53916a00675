//! Closed, outward-oriented mesh parts to build assets from. Every function returns a part that
//! passes [`MeshPart::is_closed_and_oriented`] with positive volume.

use nalgebra::{Point3, Rotation3, Unit, Vector3};
use scenethesis_scene_graph::{AssetRef, Material, Mesh, MeshPart};

use crate::{Asset, AssetInfo, Placement, SupportSurface, SurfaceKind};

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

/// A vertical cylinder (axis +Y) centred at (`cx`, `cz`) from `y0` to `y1`, with `segments`
/// sides (at least 3) and capped ends.
pub fn cylinder(
    name: &str,
    material: usize,
    center: [f32; 2],
    radius: f32,
    y0: f32,
    y1: f32,
    segments: u32,
) -> MeshPart {
    frustum(name, material, center, radius, radius, y0, y1, segments)
}

/// A vertical truncated cone (axis +Y) with radius `r0` at `y0` and `r1` at `y1` (either may be
/// zero for a cone), capped ends.
#[allow(clippy::too_many_arguments)]
pub fn frustum(
    name: &str,
    material: usize,
    center: [f32; 2],
    r0: f32,
    r1: f32,
    y0: f32,
    y1: f32,
    segments: u32,
) -> MeshPart {
    let n = segments.max(3);
    let mut positions = Vec::with_capacity(2 * n as usize + 2);
    for (r, y) in [(r0, y0), (r1, y1)] {
        for i in 0..n {
            let a = i as f32 / n as f32 * std::f32::consts::TAU;
            positions.push([center[0] + r * a.cos(), y, center[1] + r * a.sin()]);
        }
    }
    let bottom = positions.len() as u32;
    positions.push([center[0], y0, center[1]]);
    positions.push([center[0], y1, center[1]]);
    let top = bottom + 1;
    let mut triangles = Vec::with_capacity(4 * n as usize);
    for i in 0..n {
        let j = (i + 1) % n;
        // Angles grow from +X toward +Z, which is clockwise seen from above (+Y toward viewer).
        triangles.push([i, n + i, j]);
        triangles.push([j, n + i, n + j]);
        triangles.push([bottom, i, j]);
        triangles.push([top, n + j, n + i]);
    }
    // A zero radius collapses a ring to duplicate points; weld it onto the centre point.
    let mut part = MeshPart {
        name: name.into(),
        material,
        positions,
        triangles,
    };
    if r0 == 0.0 {
        weld_ring(&mut part, 0, n, bottom);
    }
    if r1 == 0.0 {
        weld_ring(&mut part, n, n, top);
    }
    part
}

/// Replaces ring vertices `start..start+n` by `center` and drops the triangles that collapse.
fn weld_ring(part: &mut MeshPart, start: u32, n: u32, center: u32) {
    for t in &mut part.triangles {
        for i in t.iter_mut() {
            if (start..start + n).contains(i) {
                *i = center;
            }
        }
    }
    part.triangles
        .retain(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
    // Ring vertices stay in the list unused; compact them away.
    compact(part);
}

/// A UV sphere centred at `center` with `rings` latitude bands and `segments` longitude bands.
pub fn sphere(
    name: &str,
    material: usize,
    center: [f32; 3],
    radius: f32,
    rings: u32,
    segments: u32,
) -> MeshPart {
    ellipsoid(name, material, center, [radius; 3], rings, segments)
}

/// An axis-aligned ellipsoid with semi-axes `radii`.
pub fn ellipsoid(
    name: &str,
    material: usize,
    center: [f32; 3],
    radii: [f32; 3],
    rings: u32,
    segments: u32,
) -> MeshPart {
    let (rings, segments) = (rings.max(2), segments.max(3));
    let mut positions = vec![[center[0], center[1] - radii[1], center[2]]];
    for r in 1..rings {
        let phi = std::f32::consts::PI * r as f32 / rings as f32;
        let (y, s) = (-phi.cos(), phi.sin());
        for k in 0..segments {
            let a = std::f32::consts::TAU * k as f32 / segments as f32;
            positions.push([
                center[0] + radii[0] * s * a.cos(),
                center[1] + radii[1] * y,
                center[2] + radii[2] * s * a.sin(),
            ]);
        }
    }
    positions.push([center[0], center[1] + radii[1], center[2]]);
    let top = positions.len() as u32 - 1;
    let ring = |r: u32, k: u32| 1 + (r - 1) * segments + k % segments;
    let mut triangles = Vec::new();
    for k in 0..segments {
        triangles.push([0, ring(1, k), ring(1, k + 1)]);
        triangles.push([top, ring(rings - 1, k + 1), ring(rings - 1, k)]);
    }
    for r in 1..rings - 1 {
        for k in 0..segments {
            let (a, b, c, d) = (
                ring(r, k),
                ring(r, k + 1),
                ring(r + 1, k),
                ring(r + 1, k + 1),
            );
            triangles.push([a, c, b]);
            triangles.push([b, c, d]);
        }
    }
    MeshPart {
        name: name.into(),
        material,
        positions,
        triangles,
    }
}

/// Drops unused vertices and renumbers the triangles.
pub fn compact(part: &mut MeshPart) {
    let mut map = vec![u32::MAX; part.positions.len()];
    let mut positions = Vec::new();
    for t in &mut part.triangles {
        for i in t.iter_mut() {
            if map[*i as usize] == u32::MAX {
                map[*i as usize] = positions.len() as u32;
                positions.push(part.positions[*i as usize]);
            }
            *i = map[*i as usize];
        }
    }
    part.positions = positions;
}

/// Flips every triangle of `part` when its signed volume is negative, so faces point outward.
pub fn orient_outward(part: &mut MeshPart) {
    if part.signed_volume() < 0.0 {
        for t in &mut part.triangles {
            t.swap(1, 2);
        }
    }
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

/// Two unit vectors perpendicular to `axis` and to each other, (u, v) with u × v along `axis`.
fn frame(axis: [f32; 3]) -> ([f32; 3], [f32; 3]) {
    let w = normalized(axis);
    let reference = if w[1].abs() < 0.9 {
        [0.0, 1.0, 0.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let u = normalized(cross(reference, w));
    let v = cross(w, u);
    (u, v)
}

fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalized(a: [f32; 3]) -> [f32; 3] {
    let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt().max(1e-12);
    [a[0] / n, a[1] / n, a[2] / n]
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

/// Joins two convex rings of equal length (same winding) into a closed part: side quads between
/// them and a fan to each ring's centroid as caps. Faces are oriented outward.
pub fn loft(name: &str, material: usize, ring0: &[[f32; 3]], ring1: &[[f32; 3]]) -> MeshPart {
    assert_eq!(
        ring0.len(),
        ring1.len(),
        "loft rings must have equal length"
    );
    let n = ring0.len() as u32;
    assert!(n >= 3, "loft rings need at least 3 points");
    let centroid = |ring: &[[f32; 3]]| {
        let mut c = [0.0f32; 3];
        for p in ring {
            for k in 0..3 {
                c[k] += p[k] / ring.len() as f32;
            }
        }
        c
    };
    let mut positions = Vec::with_capacity(2 * n as usize + 2);
    positions.extend_from_slice(ring0);
    positions.extend_from_slice(ring1);
    positions.push(centroid(ring0));
    positions.push(centroid(ring1));
    let (c0, c1) = (2 * n, 2 * n + 1);
    let mut triangles = Vec::with_capacity(4 * n as usize);
    for i in 0..n {
        let j = (i + 1) % n;
        triangles.push([i, n + i, j]);
        triangles.push([j, n + i, n + j]);
        triangles.push([c0, i, j]);
        triangles.push([c1, n + j, n + i]);
    }
    let mut part = MeshPart {
        name: name.into(),
        material,
        positions,
        triangles,
    };
    orient_outward(&mut part);
    part
}

/// A prism over a convex polygon in (x, z) (either winding), from `y0` to `y1`.
pub fn prism_y(name: &str, material: usize, polygon: &[[f32; 2]], y0: f32, y1: f32) -> MeshPart {
    let ring = |y: f32| -> Vec<[f32; 3]> { polygon.iter().map(|p| [p[0], y, p[1]]).collect() };
    loft(name, material, &ring(y0), &ring(y1))
}

/// A prism over a convex polygon in (z, y) (a side profile, either winding), from `x0` to `x1`:
/// wedge-shaped seats, sloped backs, ramps.
pub fn prism_x(name: &str, material: usize, profile: &[[f32; 2]], x0: f32, x1: f32) -> MeshPart {
    let ring = |x: f32| -> Vec<[f32; 3]> { profile.iter().map(|p| [x, p[1], p[0]]).collect() };
    loft(name, material, &ring(x0), &ring(x1))
}

/// A prism over a convex polygon in (x, y) (a front profile, either winding), from `z0` to `z1`.
pub fn prism_z(name: &str, material: usize, profile: &[[f32; 2]], z0: f32, z1: f32) -> MeshPart {
    let ring = |z: f32| -> Vec<[f32; 3]> { profile.iter().map(|p| [p[0], p[1], z]).collect() };
    loft(name, material, &ring(z0), &ring(z1))
}

/// A cylinder (or truncated cone when `r0 != r1`; both radii must be positive) along the
/// segment from `a` to `b`, with `segments` sides.
#[allow(clippy::too_many_arguments)]
pub fn rod(
    name: &str,
    material: usize,
    a: [f32; 3],
    b: [f32; 3],
    r0: f32,
    r1: f32,
    segments: u32,
) -> MeshPart {
    let (u, v) = frame([b[0] - a[0], b[1] - a[1], b[2] - a[2]]);
    let n = segments.max(3);
    let ring = |c: [f32; 3], r: f32| -> Vec<[f32; 3]> {
        (0..n)
            .map(|i| {
                let t = i as f32 / n as f32 * std::f32::consts::TAU;
                let (s, co) = t.sin_cos();
                std::array::from_fn(|k| c[k] + r * (co * u[k] + s * v[k]))
            })
            .collect()
    };
    loft(name, material, &ring(a, r0), &ring(b, r1))
}

/// A regular polygon of `sides` corners with circumradius `radius` around `center` in (x, z),
/// counter-clockwise seen from above.
pub fn regular_polygon(center: [f32; 2], radius: f32, sides: u32) -> Vec<[f32; 2]> {
    let n = sides.max(3);
    (0..n)
        .map(|i| {
            let a = -(i as f32) / n as f32 * std::f32::consts::TAU;
            [center[0] + radius * a.cos(), center[1] + radius * a.sin()]
        })
        .collect()
}

/// The part moved by `offset`.
pub fn translated(mut part: MeshPart, offset: [f32; 3]) -> MeshPart {
    for p in &mut part.positions {
        for k in 0..3 {
            p[k] += offset[k];
        }
    }
    part
}

/// The part turned by `yaw` radians about the vertical axis through `pivot` = (x, z), in the
/// same sense as a pose's yaw.
pub fn rotated_y(mut part: MeshPart, yaw: f32, pivot: [f32; 2]) -> MeshPart {
    let (s, c) = yaw.sin_cos();
    for p in &mut part.positions {
        let (x, z) = (p[0] - pivot[0], p[2] - pivot[1]);
        p[0] = pivot[0] + c * x + s * z;
        p[2] = pivot[1] - s * x + c * z;
    }
    part
}

/// The convex solid of one ring slab between angles `a0` and `a1` (radians, from +X toward +Z),
/// with inner and outer radii `(r_in, r_out)` at `y0` and at `y1`.
#[allow(clippy::too_many_arguments)]
pub fn ring_slab(
    name: &str,
    material: usize,
    center: [f32; 2],
    a0: f32,
    a1: f32,
    bottom: (f32, f32, f32),
    top: (f32, f32, f32),
) -> MeshPart {
    let mut corners = [[0.0; 3]; 8];
    for (i, corner) in corners.iter_mut().enumerate() {
        let (r_in, r_out, y) = if i & 2 == 0 { bottom } else { top };
        let r = if i & 1 == 0 { r_in } else { r_out };
        let a = if i & 4 == 0 { a0 } else { a1 };
        *corner = [center[0] + r * a.cos(), y, center[1] + r * a.sin()];
    }
    hexahedron(name, material, corners)
}

/// A frustum whose axis runs from `a` to `b` (radius `r0` at `a`, `r1` at `b`): the vertical
/// [`frustum`] turned onto the axis (handles, spouts, branches). [`rod`] builds the same shape as
/// a [`loft`] between two rings, with a different vertex layout.
pub fn tube(
    name: &str,
    material: usize,
    a: [f32; 3],
    b: [f32; 3],
    r0: f32,
    r1: f32,
    segments: u32,
) -> MeshPart {
    let (va, vb) = (Vector3::from(a), Vector3::from(b));
    let axis = vb - va;
    let length = axis.norm().max(1e-6);
    let part = frustum(name, material, [0.0, 0.0], r0, r1, 0.0, length, segments);
    transformed(part, &rotation_from_y(&axis), a)
}

/// The rotation taking +Y onto `direction`.
pub fn rotation_from_y(direction: &Vector3<f32>) -> Rotation3<f32> {
    let y = Vector3::y();
    Rotation3::rotation_between(&y, direction)
        .unwrap_or_else(|| Rotation3::from_axis_angle(&Vector3::x_axis(), std::f32::consts::PI))
}

/// A rotation by `angle` radians about `axis`.
pub fn rotation(axis: [f32; 3], angle: f32) -> Rotation3<f32> {
    Rotation3::from_axis_angle(&Unit::new_normalize(Vector3::from(axis)), angle)
}

/// `part` rotated about the origin, then moved by `offset` (a proper rotation keeps orientation).
pub fn transformed(mut part: MeshPart, rot: &Rotation3<f32>, offset: [f32; 3]) -> MeshPart {
    for p in &mut part.positions {
        let q = rot * Point3::from(*p);
        *p = [q.x + offset[0], q.y + offset[1], q.z + offset[2]];
    }
    part
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

/// An ellipsoid with semi-axes `radii` about the origin, rotated by `rot` and moved to `center`.
pub fn rotated_ellipsoid(
    name: &str,
    material: usize,
    center: [f32; 3],
    radii: [f32; 3],
    rot: &Rotation3<f32>,
) -> MeshPart {
    let part = ellipsoid(name, material, [0.0; 3], radii, 8, 14);
    transformed(part, rot, center)
}

/// The convex hull of `points` as a closed, outward-oriented part, or `None` when the points
/// are (nearly) coplanar. Incremental construction; meant for a few dozen points.
pub fn convex_hull(name: &str, material: usize, points: &[[f32; 3]]) -> Option<MeshPart> {
    let pts: Vec<Vector3<f64>> = points
        .iter()
        .map(|p| Vector3::from(*p).cast::<f64>())
        .collect();
    let scale = pts.iter().map(|p| p.amax()).fold(1e-3f64, f64::max);
    // Points closer than this to a face's plane count as on it (f32 inputs carry ~1e-7 noise).
    let eps = 1e-5 * scale;
    // Initial tetrahedron: two far points, the point farthest from their line, then from the plane.
    let i0 = 0;
    let i1 = (0..pts.len()).max_by(|&a, &b| {
        (pts[a] - pts[i0])
            .norm_squared()
            .total_cmp(&(pts[b] - pts[i0]).norm_squared())
    })?;
    let line = pts[i1] - pts[i0];
    let dist_line = |k: usize| line.cross(&(pts[k] - pts[i0])).norm();
    let i2 = (0..pts.len()).max_by(|&a, &b| dist_line(a).total_cmp(&dist_line(b)))?;
    let normal = line.cross(&(pts[i2] - pts[i0]));
    if normal.norm() < eps * line.norm() {
        return None;
    }
    let dist_plane = |k: usize| normal.dot(&(pts[k] - pts[i0]));
    let i3 = (0..pts.len()).max_by(|&a, &b| dist_plane(a).abs().total_cmp(&dist_plane(b).abs()))?;
    if dist_plane(i3).abs() < eps * normal.norm() {
        return None;
    }
    let (i0, i1, i2, i3) = (i0 as u32, i1 as u32, i2 as u32, i3 as u32);
    let mut faces: Vec<[u32; 3]> = if dist_plane(i3 as usize) > 0.0 {
        vec![[i0, i2, i1], [i0, i1, i3], [i1, i2, i3], [i2, i0, i3]]
    } else {
        vec![[i0, i1, i2], [i0, i3, i1], [i1, i3, i2], [i2, i3, i0]]
    };
    let face_plane = |f: &[u32; 3]| {
        let [a, b, c] = f.map(|i| pts[i as usize]);
        let n = (b - a).cross(&(c - a));
        (n, a)
    };
    for k in 0..pts.len() as u32 {
        if [i0, i1, i2, i3].contains(&k) {
            continue;
        }
        let p = pts[k as usize];
        let visible: Vec<bool> = faces
            .iter()
            .map(|f| {
                let (n, a) = face_plane(f);
                n.dot(&(p - a)) > eps * n.norm()
            })
            .collect();
        if !visible.iter().any(|&v| v) {
            continue;
        }
        let mut visible_edges = std::collections::BTreeSet::new();
        for (f, _) in faces.iter().zip(&visible).filter(|(_, v)| **v) {
            for e in 0..3 {
                visible_edges.insert((f[e], f[(e + 1) % 3]));
            }
        }
        let horizon: Vec<(u32, u32)> = visible_edges
            .iter()
            .filter(|(a, b)| !visible_edges.contains(&(*b, *a)))
            .copied()
            .collect();
        let mut kept: Vec<[u32; 3]> = faces
            .iter()
            .zip(&visible)
            .filter(|(_, v)| !**v)
            .map(|(f, _)| *f)
            .collect();
        kept.extend(horizon.iter().map(|&(a, b)| [a, b, k]));
        faces = kept;
    }
    let mut part = MeshPart {
        name: name.into(),
        material,
        positions: points.to_vec(),
        triangles: faces,
    };
    compact(&mut part);
    Some(part)
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

/// Tubes of radius `radius` joining consecutive `points` (a bent handle, a bail, a frond).
pub fn polyline(name: &str, material: usize, points: &[[f32; 3]], radius: f32) -> Vec<MeshPart> {
    points
        .windows(2)
        .enumerate()
        .map(|(k, w)| {
            tube(
                &format!("{name}_{k}"),
                material,
                w[0],
                w[1],
                radius,
                radius,
                8,
            )
        })
        .collect()
}

/// Points on a circular arc of radius `radius` about `center` in the plane spanned by the unit
/// vectors `u` and `v`, from angle `t0` to `t1` (radians) in `n` steps.
pub fn arc(
    center: [f32; 3],
    u: [f32; 3],
    v: [f32; 3],
    radius: f32,
    t0: f32,
    t1: f32,
    n: usize,
) -> Vec<[f32; 3]> {
    (0..=n)
        .map(|i| {
            let t = t0 + (t1 - t0) * i as f32 / n as f32;
            let (c, s) = (radius * t.cos(), radius * t.sin());
            [
                center[0] + c * u[0] + s * v[0],
                center[1] + c * u[1] + s * v[1],
                center[2] + c * u[2] + s * v[2],
            ]
        })
        .collect()
}

/// A rectangle in (x, z), counter-clockwise seen from above.
pub fn rect(x0: f32, z0: f32, x1: f32, z1: f32) -> Vec<[f32; 2]> {
    vec![[x0, z0], [x0, z1], [x1, z1], [x1, z0]]
}

/// A regular polygon of `n` corners inscribed in a circle, counter-clockwise seen from above,
/// starting at +X. The same polygon as [`regular_polygon`] but for the last bit of rounding
/// (the angle is computed as `TAU · i / n` rather than `−(i / n) · TAU`); the item generators'
/// support surfaces are defined by this rounding, so the two are kept apart.
pub fn disc(center: [f32; 2], radius: f32, n: usize) -> Vec<[f32; 2]> {
    (0..n)
        .map(|i| {
            let a = std::f32::consts::TAU * i as f32 / n as f32;
            [center[0] + radius * a.cos(), center[1] - radius * a.sin()]
        })
        .collect()
}

/// Families of plausible materials an asset picks from per seed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Palette {
    /// Natural wood tones (oak, walnut, pine, maple, cherry, teak).
    Wood,
    /// Painted or laminated wood (white, black, grey, sage, navy).
    PaintedWood,
    /// Bright metals (steel, aluminium, chrome, brass).
    Metal,
    /// Powder-coated metal (black, graphite, white, blue, red, green).
    CoatedMetal,
    /// Upholstery fabric (grey, beige, navy, olive, rust, charcoal, cream).
    Fabric,
    /// Leather and vinyl (brown, black, tan, oxblood).
    Leather,
    /// Plastics in muted colours (white, grey, black, beige).
    Plastic,
    /// Toy-like saturated plastics (red, yellow, blue, green, orange, purple).
    BrightPlastic,
    /// Clear or tinted glass (semi-transparent base colour).
    Glass,
    /// Stone and concrete (marble, granite, slate, concrete).
    Stone,
    /// Plant foliage greens.
    Foliage,
    /// Glazed ceramic (white, terracotta, blue, sage, black).
    Ceramic,
    /// Rubber and foam (black, dark grey, blue, purple, green yoga mats).
    Rubber,
    /// Paper, canvas and board (white, cream, kraft, coloured covers).
    Paper,
}

/// (name, sRGB colour, roughness, metallic) entries of each palette.
fn palette_entries(palette: Palette) -> &'static [(&'static str, [u8; 3], f32, f32)] {
    match palette {
        Palette::Wood => &[
            ("oak", [0xB8, 0x8A, 0x5A], 0.6, 0.0),
            ("walnut", [0x5D, 0x40, 0x2C], 0.55, 0.0),
            ("pine", [0xD8, 0xB4, 0x7E], 0.65, 0.0),
            ("maple", [0xE0, 0xC0, 0x90], 0.6, 0.0),
            ("cherry", [0x8E, 0x4A, 0x32], 0.5, 0.0),
            ("teak", [0x9A, 0x6A, 0x3C], 0.55, 0.0),
            ("ash", [0xC9, 0xB0, 0x8C], 0.6, 0.0),
        ],
        Palette::PaintedWood => &[
            ("white_paint", [0xEE, 0xEC, 0xE6], 0.5, 0.0),
            ("black_paint", [0x24, 0x24, 0x26], 0.45, 0.0),
            ("grey_paint", [0x8C, 0x8E, 0x90], 0.5, 0.0),
            ("sage_paint", [0x9C, 0xAF, 0x88], 0.5, 0.0),
            ("navy_paint", [0x2A, 0x3A, 0x5C], 0.5, 0.0),
            ("cream_paint", [0xE8, 0xDC, 0xC0], 0.5, 0.0),
        ],
        Palette::Metal => &[
            ("steel", [0xA8, 0xAA, 0xAD], 0.35, 1.0),
            ("aluminium", [0xC8, 0xCA, 0xCC], 0.3, 1.0),
            ("chrome", [0xDD, 0xDE, 0xE0], 0.12, 1.0),
            ("brass", [0xC8, 0xA0, 0x50], 0.3, 1.0),
            ("brushed_steel", [0x9A, 0x9C, 0x9E], 0.45, 1.0),
        ],
        Palette::CoatedMetal => &[
            ("black_metal", [0x2A, 0x2A, 0x2C], 0.5, 0.6),
            ("graphite_metal", [0x4A, 0x4C, 0x50], 0.5, 0.6),
            ("white_metal", [0xE4, 0xE4, 0xE2], 0.45, 0.4),
            ("blue_metal", [0x2E, 0x5A, 0x9C], 0.45, 0.5),
            ("red_metal", [0xB0, 0x2A, 0x24], 0.45, 0.5),
            ("green_metal", [0x3A, 0x6A, 0x48], 0.45, 0.5),
            ("grey_metal", [0x80, 0x84, 0x88], 0.45, 0.6),
        ],
        Palette::Fabric => &[
            ("grey_fabric", [0x80, 0x80, 0x82], 0.95, 0.0),
            ("beige_fabric", [0xC8, 0xB8, 0x9A], 0.95, 0.0),
            ("navy_fabric", [0x2C, 0x3A, 0x5A], 0.95, 0.0),
            ("olive_fabric", [0x6E, 0x70, 0x44], 0.95, 0.0),
            ("rust_fabric", [0xA4, 0x54, 0x32], 0.95, 0.0),
            ("charcoal_fabric", [0x3C, 0x3C, 0x40], 0.95, 0.0),
            ("cream_fabric", [0xE6, 0xDE, 0xCC], 0.95, 0.0),
            ("teal_fabric", [0x2E, 0x6E, 0x6E], 0.95, 0.0),
        ],
        Palette::Leather => &[
            ("brown_leather", [0x6A, 0x40, 0x28], 0.6, 0.0),
            ("black_leather", [0x22, 0x20, 0x20], 0.55, 0.0),
            ("tan_leather", [0xB0, 0x7A, 0x48], 0.6, 0.0),
            ("oxblood_leather", [0x5A, 0x1E, 0x1E], 0.55, 0.0),
        ],
        Palette::Plastic => &[
            ("white_plastic", [0xEC, 0xEC, 0xEA], 0.5, 0.0),
            ("grey_plastic", [0x90, 0x92, 0x94], 0.5, 0.0),
            ("black_plastic", [0x26, 0x26, 0x28], 0.45, 0.0),
            ("beige_plastic", [0xD6, 0xCC, 0xB4], 0.5, 0.0),
        ],
        Palette::BrightPlastic => &[
            ("red_plastic", [0xD8, 0x30, 0x2C], 0.4, 0.0),
            ("yellow_plastic", [0xF2, 0xC8, 0x1E], 0.4, 0.0),
            ("blue_plastic", [0x24, 0x6C, 0xD0], 0.4, 0.0),
            ("green_plastic", [0x3C, 0xA8, 0x48], 0.4, 0.0),
            ("orange_plastic", [0xF0, 0x80, 0x20], 0.4, 0.0),
            ("purple_plastic", [0x84, 0x4C, 0xC0], 0.4, 0.0),
        ],
        Palette::Glass => &[
            ("clear_glass", [0xDC, 0xEC, 0xF0], 0.05, 0.0),
            ("tinted_glass", [0xA8, 0xC0, 0xC0], 0.05, 0.0),
        ],
        Palette::Stone => &[
            ("white_marble", [0xE8, 0xE6, 0xE2], 0.25, 0.0),
            ("black_granite", [0x30, 0x30, 0x32], 0.3, 0.0),
            ("slate", [0x5C, 0x62, 0x68], 0.6, 0.0),
            ("concrete", [0xA0, 0x9E, 0x98], 0.85, 0.0),
            ("travertine", [0xD6, 0xC8, 0xAC], 0.5, 0.0),
        ],
        Palette::Foliage => &[
            ("leaf_green", [0x3C, 0x7A, 0x34], 0.8, 0.0),
            ("dark_leaf", [0x24, 0x50, 0x28], 0.8, 0.0),
            ("yellow_leaf", [0x7A, 0x94, 0x38], 0.8, 0.0),
            ("blue_leaf", [0x3A, 0x6A, 0x58], 0.8, 0.0),
        ],
        Palette::Ceramic => &[
            ("white_ceramic", [0xF0, 0xEE, 0xEA], 0.2, 0.0),
            ("terracotta", [0xB8, 0x5C, 0x38], 0.8, 0.0),
            ("blue_ceramic", [0x3A, 0x5E, 0x90], 0.2, 0.0),
            ("sage_ceramic", [0x9C, 0xB0, 0x94], 0.25, 0.0),
            ("black_ceramic", [0x28, 0x28, 0x2A], 0.25, 0.0),
        ],
        Palette::Rubber => &[
            ("black_rubber", [0x1E, 0x1E, 0x20], 0.9, 0.0),
            ("grey_rubber", [0x50, 0x52, 0x54], 0.9, 0.0),
            ("blue_foam", [0x3A, 0x6E, 0xB0], 0.85, 0.0),
            ("purple_foam", [0x7A, 0x4E, 0x9E], 0.85, 0.0),
            ("green_foam", [0x58, 0x9A, 0x5C], 0.85, 0.0),
        ],
        Palette::Paper => &[
            ("white_paper", [0xF4, 0xF2, 0xEC], 0.9, 0.0),
            ("cream_paper", [0xEC, 0xE2, 0xC8], 0.9, 0.0),
            ("kraft", [0xB8, 0x94, 0x68], 0.9, 0.0),
            ("red_cover", [0xA0, 0x2C, 0x2C], 0.7, 0.0),
            ("blue_cover", [0x2C, 0x4C, 0x8C], 0.7, 0.0),
            ("green_cover", [0x2C, 0x6C, 0x44], 0.7, 0.0),
        ],
    }
}

/// sRGB byte to linear channel.
fn srgb_to_linear(c: u8) -> f32 {
    let c = c as f32 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// A material drawn from `palette`: one of its entries, brightness jittered by up to ±8 % so
/// that two seeds rarely share exactly the same colour. Glass gets an alpha of 0.3.
pub fn pick_material(palette: Palette, rng: &mut impl rand::Rng) -> Material {
    let entries = palette_entries(palette);
    let (name, rgb, roughness, metallic) = entries[rng.random_range(0..entries.len())];
    let jitter = rng.random_range(0.92f32..1.08);
    let c = rgb.map(|v| (srgb_to_linear(v) * jitter).clamp(0.0, 1.0));
    let alpha = if palette == Palette::Glass { 0.3 } else { 1.0 };
    Material {
        name: name.into(),
        base_color: [c[0], c[1], c[2], alpha],
        roughness,
        metallic,
    }
}

/// A material with a fixed sRGB colour (for parts that do not vary: screens, rubber feet).
pub fn fixed_material(name: &str, srgb: [u8; 3], roughness: f32, metallic: f32) -> Material {
    let c = srgb.map(srgb_to_linear);
    Material {
        name: name.into(),
        base_color: [c[0], c[1], c[2], 1.0],
        roughness,
        metallic,
    }
}

/// A support surface over the axis-aligned rectangle `min`..`max` in (x, z), shrunk by `margin`
/// on every side (never below a 1 cm square around the centre).
pub fn rect_surface(
    name: &str,
    kind: SurfaceKind,
    min: [f32; 2],
    max: [f32; 2],
    height: f32,
    clearance: Option<f32>,
    margin: f32,
) -> SupportSurface {
    let shrink = |lo: f32, hi: f32| {
        let m = margin.min(0.5 * (hi - lo) - 0.005).max(0.0);
        (lo + m, hi - m)
    };
    let (x0, x1) = shrink(min[0], max[0]);
    let (z0, z1) = shrink(min[1], max[1]);
    SupportSurface {
        name: name.into(),
        kind,
        polygon: rect(x0, z0, x1, z1),
        height,
        clearance,
    }
}

/// A support surface over a regular `sides`-gon inscribed in the circle of `radius` (already
/// shrunk by the caller) around `center` in (x, z).
pub fn disc_surface(
    name: &str,
    kind: SurfaceKind,
    center: [f32; 2],
    radius: f32,
    height: f32,
    clearance: Option<f32>,
    sides: u32,
) -> SupportSurface {
    SupportSurface {
        name: name.into(),
        kind,
        polygon: regular_polygon(center, radius, sides),
        height,
        clearance,
    }
}

/// Collects parts, materials and support surfaces, then normalises them into an [`Asset`]
/// whose origin is the centre of its footprint at its lowest point.
#[derive(Debug, Default, Clone)]
pub struct AssetBuilder {
    mesh: Mesh,
    surfaces: Vec<SupportSurface>,
}

impl AssetBuilder {
    /// An empty builder.
    pub fn new() -> Self {
        Self::default()
    }

    /// Flattens the underside into a contact patch: every vertex lower than `depth` above the
    /// parts' lowest point is raised onto that plane. A tessellated sphere or a cylinder lying
    /// on its side otherwise rests on one vertex or edge and rolls off it in simulation (a real
    /// ball or fruit flattens into its contact patch the same way). Convex parts stay convex
    /// while `depth` is below their second ring of vertices.
    pub fn flatten_base(&mut self, depth: f32) {
        let lowest = self
            .mesh
            .parts
            .iter()
            .flat_map(|p| p.positions.iter().map(|v| v[1]))
            .fold(f32::INFINITY, f32::min);
        if !lowest.is_finite() {
            return;
        }
        let plane = lowest + depth;
        for part in &mut self.mesh.parts {
            for v in &mut part.positions {
                v[1] = v[1].max(plane);
            }
        }
    }

    /// Adds `material` (or finds an identical one) and returns its index.
    pub fn material(&mut self, material: Material) -> usize {
        if let Some(i) = self.mesh.materials.iter().position(|m| *m == material) {
            return i;
        }
        self.mesh.materials.push(material);
        self.mesh.materials.len() - 1
    }

    /// Adds a part (its material index must come from [`AssetBuilder::material`]).
    pub fn part(&mut self, part: MeshPart) -> &mut Self {
        self.mesh.parts.push(part);
        self
    }

    /// Adds an axis-aligned box part.
    pub fn cuboid(&mut self, name: &str, material: usize, min: [f32; 3], max: [f32; 3]) {
        self.mesh.parts.push(cuboid(name, material, min, max));
    }

    /// Adds a support surface (in the same frame as the parts).
    pub fn surface(&mut self, surface: SupportSurface) -> &mut Self {
        self.surfaces.push(surface);
        self
    }

    /// Adds an upward-facing support surface open above (a table top, a seat, a counter) over
    /// the axis-aligned rectangle `min`..`max` in (x, z), shrunk by `margin` as in
    /// [`rect_surface`].
    pub fn top_surface(
        &mut self,
        name: &str,
        min: [f32; 2],
        max: [f32; 2],
        height: f32,
        margin: f32,
    ) -> &mut Self {
        self.surface(rect_surface(
            name,
            SurfaceKind::Top,
            min,
            max,
            height,
            None,
            margin,
        ))
    }

    /// The support surfaces added so far, to adjust them after later parts.
    pub fn surfaces_mut(&mut self) -> &mut Vec<SupportSurface> {
        &mut self.surfaces
    }

    /// Turns everything added so far by half a turn about the vertical axis through `pivot`
    /// = (x, z), e.g. to make compartments built facing +Z open toward −Z.
    pub fn turn_around(&mut self, pivot: [f32; 2]) {
        for part in &mut self.mesh.parts {
            for p in &mut part.positions {
                p[0] = 2.0 * pivot[0] - p[0];
                p[2] = 2.0 * pivot[1] - p[2];
            }
        }
        for s in &mut self.surfaces {
            for p in &mut s.polygon {
                p[0] = 2.0 * pivot[0] - p[0];
                p[1] = 2.0 * pivot[1] - p[1];
            }
        }
    }

    /// The parts added so far.
    pub fn parts(&self) -> &[MeshPart] {
        &self.mesh.parts
    }

    /// Moves everything so that the footprint centre at the lowest point is the origin, and
    /// returns the asset with its size from the mesh bounds. `source`, `category` and
    /// `synonyms` are left for [`crate::catalog::generate`] to fill in.
    ///
    /// # Panics
    /// When no part was added.
    pub fn finish(mut self, placement: Placement, scale_range: [f32; 2]) -> Asset {
        let bounds = self
            .mesh
            .bounds()
            .expect("an asset needs at least one part");
        let (min, max) = (bounds.min.cast::<f32>(), bounds.max.cast::<f32>());
        let shift = [-0.5 * (min.x + max.x), -min.y, -0.5 * (min.z + max.z)];
        for part in &mut self.mesh.parts {
            for p in &mut part.positions {
                for k in 0..3 {
                    p[k] += shift[k];
                }
            }
        }
        for s in &mut self.surfaces {
            for p in &mut s.polygon {
                p[0] += shift[0];
                p[1] += shift[2];
            }
            s.height += shift[1];
        }
        let size = max - min;
        Asset {
            info: AssetInfo {
                source: AssetRef::Procedural {
                    generator: String::new(),
                    seed: 0,
                },
                category: String::new(),
                synonyms: Vec::new(),
                size: [size.x, size.y, size.z],
                placement,
                front: [0.0, 0.0, 1.0],
                support_surfaces: self.surfaces,
                scale_range,
            },
            mesh: self.mesh,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(part: &MeshPart, volume: f64, tol: f64) {
        assert!(
            part.is_closed_and_oriented(),
            "{} is not closed and oriented",
            part.name
        );
        let v = part.signed_volume();
        assert!(
            (v - volume).abs() <= tol * volume,
            "{}: volume {v}, expected {volume}",
            part.name
        );
    }

    #[test]
    fn primitives_are_closed_outward_and_have_the_right_volume() {
        use std::f64::consts::PI;
        check(
            &cuboid("box", 0, [0.0, 0.0, 0.0], [1.0, 2.0, 3.0]),
            6.0,
            1e-6,
        );
        let post = square_post("post", 0, [1.0, 2.0], 0.2, 0.5, 3.5);
        check(&post, 0.12, 1e-5);
        assert_eq!(post.positions[0], [0.9, 0.5, 1.9]);
        check(
            &cylinder("cyl", 0, [0.5, 0.5], 0.5, 0.0, 2.0, 64),
            PI * 0.25 * 2.0,
            0.01,
        );
        check(
            &frustum("cone", 0, [0.0, 0.0], 1.0, 0.0, 0.0, 3.0, 128),
            PI,
            0.01,
        );
        check(
            &frustum("cone_down", 0, [0.0, 0.0], 0.0, 1.0, 0.0, 3.0, 128),
            PI,
            0.01,
        );
        check(
            &sphere("ball", 0, [0.0, 1.0, 0.0], 1.0, 48, 96),
            4.0 / 3.0 * PI,
            0.01,
        );
        check(
            &box_yaw("turned", 0, [1.0, 2.0], [0.5, 1.0], 0.0, 3.0, 0.7),
            6.0,
            1e-5,
        );
        check(
            &beam("bar", 0, [0.0, 0.0, 0.0], [1.0, 2.0, 2.0], [0.1, 0.2]),
            0.06,
            1e-5,
        );
        check(
            &strut("strut", 0, [0.0, 0.0, 0.0], [0.3, 2.0, -0.2], [0.1, 0.2]),
            0.04,
            1e-5,
        );
        check(
            &rod("rod", 0, [0.0, 0.0, 0.0], [0.0, 0.0, -2.0], 0.5, 0.5, 128),
            PI * 0.25 * 2.0,
            0.01,
        );
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        check(&prism_y("py", 0, &square, 0.0, 2.0), 2.0, 1e-6);
        check(&prism_x("px", 0, &square, 1.0, 0.0), 1.0, 1e-6);
        check(&prism_z("pz", 0, &square, 0.0, 3.0), 3.0, 1e-6);
        let wedge = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [0.0, 0.5, 1.0],
            [1.0, 0.5, 1.0],
        ];
        check(&hexahedron("wedge", 0, wedge), 0.75, 1e-6);
        let mut mirrored = wedge;
        mirrored.swap(0, 1);
        mirrored.swap(2, 3);
        mirrored.swap(4, 5);
        mirrored.swap(6, 7);
        check(&hexahedron("mirrored", 0, mirrored), 0.75, 1e-6);
    }

    fn is_convex(part: &MeshPart) -> bool {
        part.triangles.iter().all(|t| {
            let [a, b, c] = t.map(|i| Vector3::from(part.positions[i as usize]).cast::<f64>());
            let n = (b - a).cross(&(c - a));
            part.positions.iter().all(|p| {
                n.dot(&(Vector3::from(*p).cast::<f64>() - a)) <= 1e-9 * n.norm().max(1e-12) + 1e-7
            })
        })
    }

    #[test]
    fn builders_make_closed_outward_convex_parts() {
        let parts = [
            ring_slab(
                "slab",
                0,
                [0.0, 0.0],
                0.0,
                0.7,
                (0.03, 0.04, 0.0),
                (0.05, 0.06, 0.1),
            ),
            tube("tube", 0, [0.1, 0.2, 0.3], [0.5, 0.1, -0.4], 0.03, 0.02, 12),
            rotated_box(
                "box",
                0,
                [1.0, 0.0, 0.0],
                [0.1, 0.2, 0.3],
                &rotation([1.0, 1.0, 0.0], 0.6),
            ),
            rotated_ellipsoid(
                "ell",
                0,
                [0.0, 1.0, 0.0],
                [0.3, 0.05, 0.1],
                &rotation([0.0, 0.0, 1.0], 0.4),
            ),
        ];
        for part in &parts {
            assert!(part.is_closed_and_oriented(), "{}", part.name);
            assert!(part.signed_volume() > 0.0, "{}", part.name);
            assert!(is_convex(part), "{} is not convex", part.name);
        }
    }

    #[test]
    fn convex_hull_of_random_points_is_closed_convex_and_contains_them() {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let points: Vec<[f32; 3]> = (0..40)
            .map(|_| {
                [
                    crate::random::uniform(&mut rng, -1.0, 1.0),
                    crate::random::uniform(&mut rng, 0.0, 0.5),
                    crate::random::uniform(&mut rng, -0.3, 0.3),
                ]
            })
            .collect();
        let hull = convex_hull("rock", 0, &points).unwrap();
        assert!(hull.is_closed_and_oriented());
        assert!(is_convex(&hull));
        let cube: Vec<[f32; 3]> = (0..8)
            .map(|i| [(i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32])
            .collect();
        let hull = convex_hull("cube", 0, &cube).unwrap();
        assert!((hull.signed_volume() - 1.0).abs() < 1e-6);
        assert!(convex_hull(
            "flat",
            0,
            &[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 1.0]]
        )
        .is_none());
    }

    #[test]
    fn polygons_wind_counter_clockwise_seen_from_above() {
        // Counter-clockwise seen from +Y is negative in the (x, z) shoelace sum.
        for poly in [
            rect(-1.0, -1.0, 1.0, 2.0),
            regular_polygon([0.0, 0.0], 1.0, 12),
        ] {
            let n = poly.len();
            let twice: f32 = (0..n)
                .map(|i| poly[i][0] * poly[(i + 1) % n][1] - poly[(i + 1) % n][0] * poly[i][1])
                .sum();
            assert!(twice < 0.0);
        }
    }

    #[test]
    fn builder_moves_the_footprint_centre_to_the_origin() {
        let mut b = AssetBuilder::new();
        let m = b.material(fixed_material("m", [10, 20, 30], 0.5, 0.0));
        assert_eq!(b.material(fixed_material("m", [10, 20, 30], 0.5, 0.0)), m);
        b.cuboid("slab", m, [1.0, 2.0, 3.0], [3.0, 2.5, 4.0]);
        b.surface(rect_surface(
            "top",
            SurfaceKind::Top,
            [1.0, 3.0],
            [3.0, 4.0],
            2.5,
            None,
            0.1,
        ));
        let asset = b.finish(Placement::Floor, [0.9, 1.1]);
        assert_eq!(asset.info.size, [2.0, 0.5, 1.0]);
        let top = &asset.info.support_surfaces[0];
        assert_eq!(top.height, 0.5);
        assert!((top.area() - 1.8 * 0.8).abs() < 1e-5);
        let [cx, cz] = top.center();
        assert!(cx.abs() < 1e-6 && cz.abs() < 1e-6, "centre {cx} {cz}");
        let bounds = asset.mesh.bounds().unwrap();
        assert_eq!(bounds.min.y, 0.0);
        assert_eq!(bounds.min.x, -1.0);
    }

    #[test]
    fn palettes_vary_with_the_seed_and_repeat_with_it() {
        use rand::SeedableRng;
        let draw = |seed| {
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
            pick_material(Palette::Wood, &mut rng)
        };
        assert_eq!(draw(3), draw(3));
        assert!((0..8).any(|s| draw(s) != draw(0)));
        assert_eq!(regular_polygon([0.0, 0.0], 1.0, 4).len(), 4);
    }
}
