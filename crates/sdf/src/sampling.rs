//! Point sampling and clustering utilities for physics-aware optimization.
//!
//! All sampling is seeded ([`rand_chacha::ChaCha8Rng`]) and reproducible across platforms.

use std::collections::HashMap;

use nalgebra::{Point3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use scenethesis_scene_graph::Mesh;

/// `count` points spread uniformly by area over every triangle of every part of `mesh`
/// (asset frame). Degenerate triangles get no points; an empty or zero-area mesh gives none.
pub fn surface_points(mesh: &Mesh, count: usize, seed: u64) -> Vec<Point3<f32>> {
    let mut tris: Vec<[Vector3<f32>; 3]> = Vec::with_capacity(mesh.triangle_count());
    let mut cumulative: Vec<f64> = Vec::with_capacity(mesh.triangle_count());
    let mut total = 0.0f64;
    for part in &mesh.parts {
        for t in &part.triangles {
            let Some(c) = t
                .iter()
                .map(|&i| part.positions.get(i as usize).map(|p| Vector3::from(*p)))
                .collect::<Option<Vec<_>>>()
            else {
                continue;
            };
            let area = 0.5 * (c[1] - c[0]).cross(&(c[2] - c[0])).norm() as f64;
            if !(area > 0.0 && area.is_finite()) {
                continue;
            }
            total += area;
            cumulative.push(total);
            tris.push([c[0], c[1], c[2]]);
        }
    }
    if tris.is_empty() || count == 0 {
        return Vec::new();
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|_| {
            let target = rng.random::<f64>() * total;
            let k = cumulative
                .partition_point(|&c| c <= target)
                .min(tris.len() - 1);
            let [a, b, c] = tris[k];
            let (r1, r2): (f32, f32) = (rng.random(), rng.random());
            let s = r1.sqrt();
            Point3::from(a * (1.0 - s) + b * (s * (1.0 - r2)) + c * (s * r2))
        })
        .collect()
}

/// `count` points uniform in the bottom band of the box `[min, max]`: x and z over the whole
/// footprint, y within `band` metres above `min.y` (clamped to the box height). These stand in
/// for an object's contact region when checking support and stability.
pub fn bottom_points(
    min: Point3<f32>,
    max: Point3<f32>,
    band: f32,
    count: usize,
    seed: u64,
) -> Vec<Point3<f32>> {
    let top = (min.y + band.max(0.0)).min(max.y).max(min.y);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut lerp = |a: f32, b: f32| a + (b - a) * rng.random::<f32>();
    (0..count)
        .map(|_| {
            let x = lerp(min.x, max.x);
            let y = lerp(min.y, top);
            let z = lerp(min.z, max.z);
            Point3::new(x, y, z)
        })
        .collect()
}

/// Hashes grid cells for [`negative_clusters`]: a multiply–rotate mix of the coordinates, many
/// times cheaper than the standard library's SipHash, which made the clustering the optimizer's
/// costliest step (it runs at every evaluation of a colliding pose). Only lookups use it, so
/// the clusters do not depend on it.
#[derive(Default, Clone, Copy)]
struct CellHasher(u64);

impl std::hash::Hasher for CellHasher {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }

    fn write_u64(&mut self, v: u64) {
        self.0 = (self.0.rotate_left(5) ^ v).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }

    fn write_i64(&mut self, v: i64) {
        self.write_u64(v as u64);
    }

    fn write_usize(&mut self, v: usize) {
        self.write_u64(v as u64);
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// The [`std::hash::BuildHasher`] of [`CellHasher`].
type BuildCellHasher = std::hash::BuildHasherDefault<CellHasher>;

/// Groups the points with negative distance into clusters: two such points are linked when
/// they are at most `link_radius` apart, and clusters are the connected groups (the number of
/// separate penetration regions is the result's length). Each cluster lists point indices in
/// increasing order; clusters are ordered by their first index. A non-positive radius links
/// only coincident points.
pub fn negative_clusters(
    points: &[Point3<f32>],
    distances: &[f32],
    link_radius: f32,
) -> Vec<Vec<usize>> {
    let negative: Vec<usize> = (0..points.len().min(distances.len()))
        .filter(|&i| distances[i] < 0.0)
        .collect();
    if negative.is_empty() {
        return Vec::new();
    }
    let radius = if link_radius.is_finite() && link_radius > 0.0 {
        link_radius
    } else {
        0.0
    };
    let cell = if radius > 0.0 { radius } else { 1.0 };
    let key = |p: &Point3<f32>| -> [i64; 3] { [p.x, p.y, p.z].map(|v| (v / cell).floor() as i64) };
    let mut grid: HashMap<[i64; 3], Vec<usize>, BuildCellHasher> = HashMap::default();
    for (slot, &i) in negative.iter().enumerate() {
        grid.entry(key(&points[i])).or_default().push(slot);
    }
    let mut parent: Vec<usize> = (0..negative.len()).collect();
    fn find(parent: &mut [usize], mut x: usize) -> usize {
        while parent[x] != x {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        x
    }
    let r2 = radius * radius;
    for (slot, &i) in negative.iter().enumerate() {
        let p = points[i];
        let k = key(&p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(others) = grid.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) else {
                        continue;
                    };
                    for &other in others {
                        if other <= slot || (points[negative[other]] - p).norm_squared() > r2 {
                            continue;
                        }
                        let (a, b) = (find(&mut parent, slot), find(&mut parent, other));
                        if a != b {
                            parent[a.max(b)] = a.min(b);
                        }
                    }
                }
            }
        }
    }
    let mut clusters: Vec<Vec<usize>> = Vec::new();
    let mut cluster_of_root: Vec<usize> = vec![usize::MAX; negative.len()];
    for (slot, &point) in negative.iter().enumerate() {
        let r = find(&mut parent, slot);
        if cluster_of_root[r] == usize::MAX {
            cluster_of_root[r] = clusters.len();
            clusters.push(Vec::new());
        }
        clusters[cluster_of_root[r]].push(point);
    }
    clusters
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;
    use scenethesis_scene_graph::{Material, MeshPart};

    fn cube_mesh() -> Mesh {
        let (positions, triangles) = shapes::cuboid(nalgebra::Vector3::new(0.5, 0.5, 0.5));
        Mesh {
            parts: vec![MeshPart {
                name: "cube".into(),
                material: 0,
                positions,
                triangles,
                joint: None,
                uvs: None,
            }],
            materials: vec![Material::new("m", [0.5; 3], 0.5)],
        }
    }

    #[test]
    fn surface_points_lie_on_the_surface_and_are_seeded() {
        let mesh = cube_mesh();
        let a = surface_points(&mesh, 500, 7);
        assert_eq!(a, surface_points(&mesh, 500, 7));
        assert_ne!(a, surface_points(&mesh, 500, 8));
        for p in &a {
            let on_face = p.coords.iter().any(|v| (v.abs() - 0.5).abs() < 1e-5);
            assert!(on_face && p.coords.amax() <= 0.5 + 1e-5, "{p:?}");
        }
        // Area-uniform: each of the six faces gets about a sixth.
        let top = a.iter().filter(|p| (p.y - 0.5).abs() < 1e-5).count();
        assert!((50..120).contains(&top), "top face got {top} of 500");
    }

    #[test]
    fn bottom_points_stay_in_band() {
        let pts = bottom_points(
            Point3::new(-1.0, 0.0, -2.0),
            Point3::new(1.0, 3.0, 2.0),
            0.05,
            200,
            1,
        );
        assert_eq!(pts.len(), 200);
        assert!(pts
            .iter()
            .all(|p| p.y >= 0.0 && p.y <= 0.05 && p.x.abs() <= 1.0 && p.z.abs() <= 2.0));
    }

    #[test]
    fn clusters_split_distant_groups() {
        let points = vec![
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(0.05, 0.0, 0.0),
            Point3::new(5.0, 0.0, 0.0),
            Point3::new(0.1, 0.0, 0.0),
            Point3::new(5.02, 0.0, 0.0),
            Point3::new(2.0, 0.0, 0.0),
        ];
        let d = vec![-0.1, -0.1, -0.2, -0.1, -0.1, 0.3];
        let c = negative_clusters(&points, &d, 0.06);
        assert_eq!(c, vec![vec![0, 1, 3], vec![2, 4]]);
        assert!(negative_clusters(&points, &[1.0; 6], 0.06).is_empty());
    }
}
