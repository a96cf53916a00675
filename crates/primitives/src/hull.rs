//! The convex hull of a point set, as a closed part (rocks, rounded boxes).

use nalgebra::Vector3;
use scenethesis_scene_graph::MeshPart;

use crate::compact;

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
        joint: None,
        uvs: None,
    };
    compact(&mut part);
    Some(part)
}
