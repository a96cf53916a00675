//! Convex part builders and an asset builder shared by the item and outdoor generators.
//!
//! Every part made here is convex (or a closed union-free solid the caller treats as one convex
//! piece), closed and outward-oriented, so that per-part convex hulls keep the cavities of hollow
//! things open: a mug is a base disc, a ring of wall slabs and a handle, never one closed shell.

use nalgebra::{Point3, Rotation3, Unit, Vector3};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use scenethesis_scene_graph::{AssetRef, Material, Mesh, MeshPart};

use crate::primitives::{cuboid, ellipsoid, frustum};
use crate::{Asset, AssetInfo, Placement, SupportSurface, SurfaceKind};

/// A uniform random number in `[lo, hi]`.
pub(crate) fn uniform(rng: &mut ChaCha8Rng, lo: f32, hi: f32) -> f32 {
    if hi <= lo {
        lo
    } else {
        rng.random_range(lo..=hi)
    }
}

/// One element of a non-empty slice, chosen by the generator.
pub(crate) fn pick<'a, T>(rng: &mut ChaCha8Rng, items: &'a [T]) -> &'a T {
    &items[rng.random_range(0..items.len())]
}

/// A colour from `palette`, each channel jittered by up to ±`jitter` and clamped to [0, 1].
pub(crate) fn color(rng: &mut ChaCha8Rng, palette: &[[f32; 3]], jitter: f32) -> [f32; 3] {
    let base = *pick(rng, palette);
    base.map(|c| (c + uniform(rng, -jitter, jitter)).clamp(0.0, 1.0))
}

/// A hexahedron with the cuboid's topology: `corners[i]` takes the place of the box corner whose
/// bit 0 selects x, bit 1 y and bit 2 z. Convex when the corners are (a box sheared, tapered or
/// bent into a planar-faced solid, e.g. a wall slab of a ring); the corner order must keep the
/// box's handedness.
pub(crate) fn hexahedron(name: &str, material: usize, corners: [[f32; 3]; 8]) -> MeshPart {
    let mut part = cuboid(name, material, [0.0; 3], [1.0; 3]);
    part.positions = corners.to_vec();
    part
}

/// The convex solid of one ring slab between angles `a0` and `a1` (radians, from +X toward +Z),
/// with inner and outer radii `(r_in, r_out)` at `y0` and at `y1`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn ring_slab(
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

/// A frustum whose axis runs from `a` to `b` (radius `r0` at `a`, `r1` at `b`).
pub(crate) fn tube(
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
pub(crate) fn rotation_from_y(direction: &Vector3<f32>) -> Rotation3<f32> {
    let y = Vector3::y();
    Rotation3::rotation_between(&y, direction)
        .unwrap_or_else(|| Rotation3::from_axis_angle(&Vector3::x_axis(), std::f32::consts::PI))
}

/// A rotation by `angle` radians about `axis`.
pub(crate) fn rotation(axis: [f32; 3], angle: f32) -> Rotation3<f32> {
    Rotation3::from_axis_angle(&Unit::new_normalize(Vector3::from(axis)), angle)
}

/// `part` rotated about the origin, then moved by `offset` (a proper rotation keeps orientation).
pub(crate) fn transformed(mut part: MeshPart, rot: &Rotation3<f32>, offset: [f32; 3]) -> MeshPart {
    for p in &mut part.positions {
        let q = rot * Point3::from(*p);
        *p = [q.x + offset[0], q.y + offset[1], q.z + offset[2]];
    }
    part
}

/// A box with half extents `half` centred at the origin, rotated by `rot` and moved to `center`.
pub(crate) fn oriented_box(
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
pub(crate) fn oriented_ellipsoid(
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
pub(crate) fn convex_hull(name: &str, material: usize, points: &[[f32; 3]]) -> Option<MeshPart> {
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
    crate::primitives::compact(&mut part);
    Some(part)
}

/// A rounded box: the convex hull of a superellipsoid with half extents `half` centred at
/// `center` (`roundness` 0 is a sharp box, 1 an ellipsoid).
pub(crate) fn rounded_box(
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
pub(crate) fn polyline(
    name: &str,
    material: usize,
    points: &[[f32; 3]],
    radius: f32,
) -> Vec<MeshPart> {
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
pub(crate) fn arc(
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
pub(crate) fn rect(x0: f32, z0: f32, x1: f32, z1: f32) -> Vec<[f32; 2]> {
    vec![[x0, z0], [x0, z1], [x1, z1], [x1, z0]]
}

/// A regular polygon of `n` corners inscribed in a circle, counter-clockwise seen from above.
pub(crate) fn disc(center: [f32; 2], radius: f32, n: usize) -> Vec<[f32; 2]> {
    (0..n)
        .map(|i| {
            let a = std::f32::consts::TAU * i as f32 / n as f32;
            [center[0] + radius * a.cos(), center[1] - radius * a.sin()]
        })
        .collect()
}

/// Collects parts, materials and support surfaces, then normalises them into an [`Asset`].
#[derive(Default)]
pub(crate) struct Builder {
    parts: Vec<MeshPart>,
    materials: Vec<Material>,
    surfaces: Vec<SupportSurface>,
}

impl Builder {
    /// An empty builder.
    pub(crate) fn new() -> Self {
        Self::default()
    }

    /// Adds a dielectric material and returns its index.
    pub(crate) fn material(&mut self, name: &str, rgb: [f32; 3], roughness: f32) -> usize {
        self.materials.push(Material::new(name, rgb, roughness));
        self.materials.len() - 1
    }

    /// Adds a metallic material and returns its index.
    pub(crate) fn metal(&mut self, name: &str, rgb: [f32; 3], roughness: f32) -> usize {
        let mut m = Material::new(name, rgb, roughness);
        m.metallic = 1.0;
        self.materials.push(m);
        self.materials.len() - 1
    }

    /// Adds a translucent material (alpha < 1) and returns its index.
    pub(crate) fn glass(&mut self, name: &str, rgb: [f32; 3], alpha: f32) -> usize {
        let mut m = Material::new(name, rgb, 0.05);
        m.base_color[3] = alpha;
        self.materials.push(m);
        self.materials.len() - 1
    }

    /// Adds a finished part.
    pub(crate) fn add(&mut self, part: MeshPart) {
        self.parts.push(part);
    }

    /// Adds an axis-aligned box.
    pub(crate) fn cuboid(&mut self, name: &str, material: usize, min: [f32; 3], max: [f32; 3]) {
        self.add(cuboid(name, material, min, max));
    }

    /// Adds a vertical frustum (a cylinder when `r0 == r1`).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn frustum(
        &mut self,
        name: &str,
        material: usize,
        center: [f32; 2],
        r0: f32,
        r1: f32,
        y0: f32,
        y1: f32,
        segments: u32,
    ) {
        self.add(frustum(name, material, center, r0, r1, y0, y1, segments));
    }

    /// Adds an axis-aligned ellipsoid.
    pub(crate) fn ellipsoid(
        &mut self,
        name: &str,
        material: usize,
        center: [f32; 3],
        radii: [f32; 3],
    ) {
        self.add(ellipsoid(name, material, center, radii, 10, 16));
    }

    /// Adds tubes joining consecutive points.
    pub(crate) fn polyline(
        &mut self,
        name: &str,
        material: usize,
        points: &[[f32; 3]],
        radius: f32,
    ) {
        for part in polyline(name, material, points, radius) {
            self.add(part);
        }
    }

    /// Adds a tube (frustum) between two points.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn tube(
        &mut self,
        name: &str,
        material: usize,
        a: [f32; 3],
        b: [f32; 3],
        r0: f32,
        r1: f32,
        segments: u32,
    ) {
        self.add(tube(name, material, a, b, r0, r1, segments));
    }

    /// Adds a ring of `segments` convex wall slabs around a vertical axis, inner and outer radii
    /// `(r_in, r_out)` at `y0` and at `y1`: the wall of a mug, bowl, bucket or barrel.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn ring(
        &mut self,
        name: &str,
        material: usize,
        center: [f32; 2],
        bottom: (f32, f32, f32),
        top: (f32, f32, f32),
        segments: u32,
    ) {
        let n = segments.max(3);
        for k in 0..n {
            let a0 = std::f32::consts::TAU * k as f32 / n as f32;
            let a1 = std::f32::consts::TAU * (k + 1) as f32 / n as f32;
            self.add(ring_slab(
                &format!("{name}_{k}"),
                material,
                center,
                a0,
                a1,
                bottom,
                top,
            ));
        }
    }

    /// Adds an open-top rectangular tub: a floor of thickness `floor` and four walls of thickness
    /// `wall` around the outer box `min`..`max`. Returns the inner floor's height.
    pub(crate) fn open_box(
        &mut self,
        name: &str,
        material: usize,
        min: [f32; 3],
        max: [f32; 3],
        wall: f32,
        floor: f32,
    ) -> f32 {
        let inner_y = min[1] + floor;
        self.cuboid(
            &format!("{name}_floor"),
            material,
            min,
            [max[0], inner_y, max[2]],
        );
        let y0 = inner_y - floor * 0.5;
        self.cuboid(
            &format!("{name}_wall_back"),
            material,
            [min[0], y0, min[2]],
            [max[0], max[1], min[2] + wall],
        );
        self.cuboid(
            &format!("{name}_wall_front"),
            material,
            [min[0], y0, max[2] - wall],
            [max[0], max[1], max[2]],
        );
        self.cuboid(
            &format!("{name}_wall_left"),
            material,
            [min[0], y0, min[2]],
            [min[0] + wall, max[1], max[2]],
        );
        self.cuboid(
            &format!("{name}_wall_right"),
            material,
            [max[0] - wall, y0, min[2]],
            [max[0], max[1], max[2]],
        );
        inner_y
    }

    /// Adds a support surface.
    pub(crate) fn surface(
        &mut self,
        name: &str,
        kind: SurfaceKind,
        polygon: Vec<[f32; 2]>,
        height: f32,
        clearance: Option<f32>,
    ) {
        self.surfaces.push(SupportSurface {
            name: name.into(),
            kind,
            polygon,
            height,
            clearance,
        });
    }

    /// Moves everything so that the origin is the footprint centre at the lowest point, and
    /// returns the asset with its size measured from the mesh.
    pub(crate) fn finish(mut self, placement: Placement, scale_range: [f32; 2]) -> Asset {
        let mut min = [f32::INFINITY; 3];
        let mut max = [f32::NEG_INFINITY; 3];
        for p in self.parts.iter().flat_map(|p| p.positions.iter()) {
            for k in 0..3 {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
            }
        }
        let shift = [-(min[0] + max[0]) * 0.5, -min[1], -(min[2] + max[2]) * 0.5];
        for p in self.parts.iter_mut().flat_map(|p| p.positions.iter_mut()) {
            for k in 0..3 {
                p[k] += shift[k];
            }
        }
        for s in &mut self.surfaces {
            s.height += shift[1];
            for q in &mut s.polygon {
                q[0] += shift[0];
                q[1] += shift[2];
            }
        }
        Asset {
            info: AssetInfo {
                source: AssetRef::Procedural {
                    generator: String::new(),
                    seed: 0,
                },
                category: String::new(),
                synonyms: Vec::new(),
                size: [max[0] - min[0], max[1] - min[1], max[2] - min[2]],
                placement,
                front: [0.0, 0.0, 1.0],
                support_surfaces: self.surfaces,
                scale_range,
            },
            mesh: Mesh {
                parts: self.parts,
                materials: self.materials,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
            oriented_box(
                "box",
                0,
                [1.0, 0.0, 0.0],
                [0.1, 0.2, 0.3],
                &rotation([1.0, 1.0, 0.0], 0.6),
            ),
            oriented_ellipsoid(
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
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let points: Vec<[f32; 3]> = (0..40)
            .map(|_| {
                [
                    uniform(&mut rng, -1.0, 1.0),
                    uniform(&mut rng, 0.0, 0.5),
                    uniform(&mut rng, -0.3, 0.3),
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
        for poly in [rect(-1.0, -1.0, 1.0, 2.0), disc([0.0, 0.0], 1.0, 12)] {
            let n = poly.len();
            let twice: f32 = (0..n)
                .map(|i| poly[i][0] * poly[(i + 1) % n][1] - poly[(i + 1) % n][0] * poly[i][1])
                .sum();
            assert!(twice < 0.0);
        }
    }
}
