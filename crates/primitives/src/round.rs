//! Round solids: cylinders, cones, spheres, ellipsoids, rods, tubes and ring slabs.

use nalgebra::{Rotation3, Vector3};
use scenethesis_scene_graph::MeshPart;

use crate::{compact, frame, hexahedron, loft, rotation_from_y, transformed};

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
        joint: None,
        uvs: None,
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
        joint: None,
        uvs: None,
    }
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
