//! Closed, outward-oriented mesh parts to build assets from. Every function returns a part that
//! passes [`MeshPart::is_closed_and_oriented`] with positive volume.

use scenethesis_scene_graph::MeshPart;

/// An axis-aligned box from `min` to `max` (asset frame), 8 vertices and 12 triangles.
pub fn cuboid(name: &str, material: usize, min: [f32; 3], max: [f32; 3]) -> MeshPart {
    let positions = (0..8)
        .map(|i| {
            [
                if i & 1 == 0 { min[0] } else { max[0] },
                if i & 2 == 0 { min[1] } else { max[1] },
                if i & 4 == 0 { min[2] } else { max[2] },
            ]
        })
        .collect();
    let triangles = vec![
        [0, 2, 1],
        [1, 2, 3],
        [4, 5, 6],
        [5, 7, 6],
        [0, 1, 4],
        [1, 5, 4],
        [2, 6, 3],
        [3, 6, 7],
        [0, 4, 2],
        [2, 4, 6],
        [1, 3, 5],
        [3, 7, 5],
    ];
    MeshPart {
        name: name.into(),
        material,
        positions,
        triangles,
    }
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
    }
}
