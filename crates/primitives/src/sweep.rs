//! Swept solids: lofts between two rings, prisms over a profile, polylines of tubes and the arcs they follow.

use scenethesis_scene_graph::MeshPart;

use crate::{orient_outward, tube};

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
        joint: None,
        uvs: None,
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
