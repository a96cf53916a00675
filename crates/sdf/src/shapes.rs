//! Closed, outward-oriented triangle meshes of simple shapes, as `(positions, triangles)`:
//! reference geometry for tests, benchmarks and quick analytic checks.

use nalgebra::Vector3;

/// Positions and counter-clockwise (seen from outside) triangles.
pub type TriangleMesh = (Vec<[f32; 3]>, Vec<[u32; 3]>);

/// An axis-aligned box centred on the origin, 8 shared vertices and 12 triangles.
pub fn cuboid(half_extents: Vector3<f32>) -> TriangleMesh {
    let h = half_extents;
    let positions = (0..8)
        .map(|i| {
            [
                if i & 1 == 0 { -h.x } else { h.x },
                if i & 2 == 0 { -h.y } else { h.y },
                if i & 4 == 0 { -h.z } else { h.z },
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
    (positions, triangles)
}

/// A latitude–longitude sphere of radius `radius` whose radius is modulated by
/// `1 + bump · sin(5θ) · sin(4φ)` (θ polar, φ azimuth; `bump = 0` gives a plain sphere).
/// It has `2 · segments · (rings − 1)` triangles: `segments = 100, rings = 50` gives 9 800,
/// `segments = 100, rings = 51` gives 10 000.
pub fn bumpy_sphere(radius: f32, bump: f32, segments: u32, rings: u32) -> TriangleMesh {
    let segments = segments.max(3);
    let rings = rings.max(2);
    let mut positions = Vec::new();
    let point = |theta: f32, phi: f32| {
        let r = radius * (1.0 + bump * (5.0 * theta).sin() * (4.0 * phi).sin());
        [
            r * theta.sin() * phi.cos(),
            r * theta.cos(),
            r * theta.sin() * phi.sin(),
        ]
    };
    positions.push(point(0.0, 0.0)); // north pole, index 0
    for ring in 1..rings {
        let theta = std::f32::consts::PI * ring as f32 / rings as f32;
        for s in 0..segments {
            let phi = std::f32::consts::TAU * s as f32 / segments as f32;
            positions.push(point(theta, phi));
        }
    }
    positions.push(point(std::f32::consts::PI, 0.0));
    let south = positions.len() as u32 - 1;
    let at = |ring: u32, s: u32| 1 + (ring - 1) * segments + (s % segments);
    let mut triangles = Vec::new();
    for s in 0..segments {
        triangles.push([0, at(1, s + 1), at(1, s)]);
    }
    for ring in 1..rings - 1 {
        for s in 0..segments {
            let (a, b) = (at(ring, s), at(ring, s + 1));
            let (c, d) = (at(ring + 1, s), at(ring + 1, s + 1));
            triangles.push([a, b, c]);
            triangles.push([b, d, c]);
        }
    }
    for s in 0..segments {
        triangles.push([south, at(rings - 1, s), at(rings - 1, s + 1)]);
    }
    (positions, triangles)
}

/// A torus around the y axis: major radius `major`, tube radius `minor`, with
/// `2 · segments · sides` triangles.
pub fn torus(major: f32, minor: f32, segments: u32, sides: u32) -> TriangleMesh {
    let (segments, sides) = (segments.max(3), sides.max(3));
    let mut positions = Vec::with_capacity((segments * sides) as usize);
    for i in 0..segments {
        let u = std::f32::consts::TAU * i as f32 / segments as f32;
        for j in 0..sides {
            let v = std::f32::consts::TAU * j as f32 / sides as f32;
            let r = major + minor * v.cos();
            positions.push([r * u.cos(), minor * v.sin(), r * u.sin()]);
        }
    }
    let at = |i: u32, j: u32| (i % segments) * sides + (j % sides);
    let mut triangles = Vec::with_capacity((2 * segments * sides) as usize);
    for i in 0..segments {
        for j in 0..sides {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1));
            triangles.push([a, c, b]);
            triangles.push([b, c, d]);
        }
    }
    (positions, triangles)
}
