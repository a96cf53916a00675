//! Degenerate geometry removed before an imported mesh reaches the distance-field build:
//! zero-area and repeated triangles dropped, comparing corners after welding identical
//! vertex positions. The triangles kept keep their own vertices (a file's vertices split for
//! flat shading stay split) and vertices no triangle uses any more are removed.
//!
//! A file of millions of identical triangles is under the triangle limit but makes the
//! distance field's bounding-volume hierarchy degenerate (every box the same), so the build
//! takes minutes and gigabytes; after cleaning it is one triangle.

use std::collections::{BTreeSet, HashMap};

use scenethesis_scene_graph::{Mesh, MeshPart};

/// What [`clean_mesh`] removed.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Cleaned {
    /// Vertices at the same position as an earlier one of their part (welded for comparing
    /// triangles).
    pub welded_vertices: usize,
    /// Triangles dropped for having zero area (repeated corners or corners on one line).
    pub degenerate_triangles: usize,
    /// Triangles dropped for repeating another's corners (in any order or winding).
    pub duplicate_triangles: usize,
}

/// Drops each part's zero-area triangles and triangles whose corners repeat an earlier
/// triangle's (corners compared after welding identical positions) and the vertices left
/// unused; parts left without triangles are removed. The order of what is kept is unchanged,
/// so the result is deterministic, and a mesh with nothing to drop is left untouched.
pub fn clean_mesh(mesh: &mut Mesh) -> Cleaned {
    let mut total = Cleaned::default();
    for part in &mut mesh.parts {
        let c = clean_part(part);
        total.welded_vertices += c.welded_vertices;
        total.degenerate_triangles += c.degenerate_triangles;
        total.duplicate_triangles += c.duplicate_triangles;
    }
    mesh.parts.retain(|p| !p.triangles.is_empty());
    total
}

fn clean_part(part: &mut MeshPart) -> Cleaned {
    let (welded, remap) = weld(&part.positions);
    let mut seen = BTreeSet::new();
    let mut c = Cleaned {
        welded_vertices: part.positions.len() - welded.len(),
        ..Cleaned::default()
    };
    let mut triangles = Vec::with_capacity(part.triangles.len());
    for t in &part.triangles {
        let corners = t.map(|i| remap[i as usize]);
        if zero_area(&corners, &welded) {
            c.degenerate_triangles += 1;
            continue;
        }
        let mut key = corners;
        key.sort_unstable();
        if !seen.insert(key) {
            c.duplicate_triangles += 1;
            continue;
        }
        triangles.push(*t);
    }
    if triangles.len() != part.triangles.len() {
        let positions = std::mem::take(&mut part.positions);
        let kept;
        (part.positions, part.triangles, kept) = drop_unused(positions, triangles);
        if let Some(uvs) = &mut part.uvs {
            *uvs = kept.iter().filter_map(|&i| uvs.get(i).copied()).collect();
        }
    }
    c
}

/// The distinct positions in first-seen order and each old index's new index. Positions are
/// compared bit for bit (`-0.0` and `0.0` are made equal).
fn weld(positions: &[[f32; 3]]) -> (Vec<[f32; 3]>, Vec<u32>) {
    let mut index: HashMap<[u32; 3], u32> = HashMap::with_capacity(positions.len());
    let mut kept = Vec::with_capacity(positions.len());
    let remap = positions
        .iter()
        .map(|p| {
            let key = p.map(|v| (v + 0.0).to_bits());
            *index.entry(key).or_insert_with(|| {
                kept.push(*p);
                kept.len() as u32 - 1
            })
        })
        .collect();
    (kept, remap)
}

/// Whether a triangle has repeated corners or corners on one line (area 0 in f64).
fn zero_area(t: &[u32; 3], positions: &[[f32; 3]]) -> bool {
    if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
        return true;
    }
    let [a, b, c] = t.map(|i| positions[i as usize].map(f64::from));
    let (u, v) = (
        [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
        [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
    );
    let cross = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    cross.iter().all(|x| *x == 0.0)
}

/// Removes vertices no triangle uses (keeping order) and renumbers the triangles; also returns
/// the old index of every vertex kept.
fn drop_unused(
    positions: Vec<[f32; 3]>,
    triangles: Vec<[u32; 3]>,
) -> (Vec<[f32; 3]>, Vec<[u32; 3]>, Vec<usize>) {
    let mut new_index = vec![u32::MAX; positions.len()];
    for t in &triangles {
        for &i in t {
            new_index[i as usize] = 0;
        }
    }
    let mut kept = Vec::new();
    let mut old = Vec::new();
    for (i, p) in positions.into_iter().enumerate() {
        if new_index[i] == 0 {
            new_index[i] = kept.len() as u32;
            kept.push(p);
            old.push(i);
        }
    }
    let triangles = triangles
        .into_iter()
        .map(|t| t.map(|i| new_index[i as usize]))
        .collect();
    (kept, triangles, old)
}

#[cfg(test)]
mod tests {
    use super::*;
    use scenethesis_scene_graph::Material;

    fn part(positions: Vec<[f32; 3]>, triangles: Vec<[u32; 3]>) -> Mesh {
        Mesh {
            parts: vec![MeshPart {
                name: "p".into(),
                material: 0,
                positions,
                triangles,
                joint: None,
                uvs: None,
            }],
            materials: vec![Material::new("grey", [0.5; 3], 0.8)],
        }
    }

    #[test]
    fn identical_triangles_become_one() {
        let tri = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let n = 1000;
        let positions: Vec<[f32; 3]> = (0..n).flat_map(|_| tri).collect();
        let triangles = (0..n as u32)
            .map(|k| [3 * k, 3 * k + 1, 3 * k + 2])
            .collect();
        let mut mesh = part(positions, triangles);
        let c = clean_mesh(&mut mesh);
        assert_eq!(c.welded_vertices, 3 * n - 3);
        assert_eq!(c.duplicate_triangles, n - 1);
        assert_eq!(c.degenerate_triangles, 0);
        assert_eq!(mesh.parts[0].triangles, vec![[0, 1, 2]]);
        assert_eq!(mesh.parts[0].positions, tri.to_vec());
    }

    #[test]
    fn a_clean_mesh_is_left_as_it_is() {
        let mut mesh = Mesh::cuboid(
            "body",
            Material::new("grey", [0.5; 3], 0.8),
            [0.0; 3],
            [1.0, 2.0, 3.0],
        );
        let before = mesh.clone();
        let c = clean_mesh(&mut mesh);
        assert_eq!((c.degenerate_triangles, c.duplicate_triangles), (0, 0));
        assert_eq!(mesh, before);
    }

    #[test]
    fn zero_area_and_reversed_repeats_are_dropped_and_empty_parts_removed() {
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        // A line, a repeated corner, a triangle and its reverse.
        let mut mesh = part(
            positions.clone(),
            vec![[0, 1, 2], [0, 0, 3], [0, 1, 3], [3, 1, 0]],
        );
        let c = clean_mesh(&mut mesh);
        assert_eq!((c.degenerate_triangles, c.duplicate_triangles), (2, 1));
        assert_eq!(mesh.parts[0].triangles, vec![[0, 1, 2]]);
        assert_eq!(mesh.parts[0].positions.len(), 3);
        let mut flat = part(positions, vec![[0, 1, 2]]);
        clean_mesh(&mut flat);
        assert!(flat.parts.is_empty());
    }
}
