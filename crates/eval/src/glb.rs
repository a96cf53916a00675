//! Reading triangle meshes out of glTF / GLB files, node by node, in world coordinates.

use std::path::{Path, PathBuf};

use nalgebra::Matrix4;
use scenethesis_import::{GltfError, GltfFile, GltfNode};
use scenethesis_scene_graph::{Mesh, MeshPart};

use crate::EvalError;

/// One node of a glTF scene with the triangles of its own meshes in world coordinates.
#[derive(Debug, Clone)]
pub struct GlbNode {
    /// The node's name (`node_<index>` when it has none).
    pub name: String,
    /// World-from-node transform.
    pub world: Matrix4<f64>,
    /// The node's own mesh primitives (triangles only), already in world coordinates.
    pub mesh: Mesh,
    /// Child nodes.
    pub children: Vec<GlbNode>,
    /// Whether it groups the objects of one room of a house (`extras` `{"room": type}`).
    pub is_room: bool,
}

impl GlbNode {
    /// The meshes of this node and all its descendants merged into one (world coordinates).
    pub fn subtree_mesh(&self) -> Mesh {
        let mut out = self.mesh.clone();
        for child in &self.children {
            out.append(&child.subtree_mesh());
        }
        out
    }

    /// The first node named `name` in this subtree (depth first, this node first).
    pub fn find(&self, name: &str) -> Option<&GlbNode> {
        if self.name == name {
            return Some(self);
        }
        self.children.iter().find_map(|c| c.find(name))
    }

    /// The yaw about +Y of the node's frame: the angle from +Z to its +Z axis projected on the
    /// floor plane (0 when that axis is vertical).
    pub fn yaw(&self) -> f64 {
        let z = self.world.fixed_view::<3, 1>(0, 2).into_owned();
        if z.x.hypot(z.z) < 1e-9 {
            0.0
        } else {
            z.x.atan2(z.z)
        }
    }
}

/// The root nodes of a glTF file's default scene (or of its first scene).
#[derive(Debug, Clone)]
pub struct GlbScene {
    /// The file it was read from.
    pub path: PathBuf,
    /// Top-level nodes, in file order.
    pub roots: Vec<GlbNode>,
}

impl GlbScene {
    /// Reads a `.glb` or `.gltf` file with the workspace's hardened glTF reader
    /// ([`scenethesis_import::GltfFile`]): size, depth, cycle, count and coordinate
    /// limits; external buffers must lie in the file's own folder (or be `data:` URIs).
    pub fn read(path: &Path) -> Result<Self, EvalError> {
        let file = GltfFile::read(path, None).map_err(|e| bad(path, e))?;
        Ok(Self::from_file(&file, path))
    }

    /// Parses glTF / GLB bytes; `path` names the file in errors and locates external buffers
    /// (which must lie in its folder).
    pub fn from_slice(bytes: &[u8], path: &Path) -> Result<Self, EvalError> {
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let file = GltfFile::from_slice(bytes, dir, dir).map_err(|e| bad(path, e))?;
        Ok(Self::from_file(&file, path))
    }

    fn from_file(file: &GltfFile, path: &Path) -> Self {
        Self {
            path: path.to_owned(),
            roots: file.roots.iter().map(|n| convert(file, n)).collect(),
        }
    }

    /// The first node named `name` anywhere in the scene.
    pub fn find(&self, name: &str) -> Option<&GlbNode> {
        self.roots.iter().find_map(|r| r.find(name))
    }
}

fn bad(path: &Path, e: GltfError) -> EvalError {
    match e {
        GltfError::Io { path, source } => EvalError::Io { path, source },
        other => EvalError::BadGltf {
            path: path.to_owned(),
            reason: other.to_string(),
        },
    }
}

/// A primitive's vertices with exact duplicates merged (and its triangles re-indexed).
///
/// Exporters split a vertex wherever its normal changes (a box's 8 corners become 24
/// vertices), but the stability model reads a part's shape from its positions: split, a box
/// counts 12 points per level and its equidistant corners passed for a 12-sided cylinder
/// around it, which pushed its neighbours away (`eval` of an output folder reported nearly
/// every object unstable). Merging restores the solid's own vertex set.
pub fn welded(positions: &[[f32; 3]], triangles: &[[u32; 3]]) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let mut index_of: std::collections::HashMap<[u32; 3], u32> = std::collections::HashMap::new();
    let mut merged: Vec<[f32; 3]> = Vec::with_capacity(positions.len());
    let remap: Vec<u32> = positions
        .iter()
        .map(|p| {
            // -0.0 and 0.0 are one position.
            let key = p.map(|c| if c == 0.0 { 0 } else { c.to_bits() });
            *index_of.entry(key).or_insert_with(|| {
                merged.push(*p);
                merged.len() as u32 - 1
            })
        })
        .collect();
    let triangles = triangles
        .iter()
        .map(|t| t.map(|i| remap.get(i as usize).copied().unwrap_or(0)))
        .collect();
    (merged, triangles)
}

/// A node instance of the shared reader as a [`GlbNode`]: one part per triangle primitive
/// (named `<node>/<primitive index>`, its split vertices [`welded`]) with its own material.
fn convert(file: &GltfFile, node: &GltfNode) -> GlbNode {
    // Node names become object ids that `eval` prints: never let one drive the terminal.
    let name = node.name.as_deref().map_or_else(
        || format!("node_{}", node.index),
        |n| scenethesis_scene_graph::printable(n).into_owned(),
    );
    let mut mesh = Mesh::default();
    for p in &node.primitives {
        let m = file.material(p.material);
        let material_name = m.name.clone().unwrap_or_else(|| "default".into());
        mesh.materials.push(m.to_material(material_name));
        let (positions, triangles) = welded(&p.positions, &p.triangles);
        mesh.parts.push(MeshPart {
            name: format!("{name}/{}", p.index),
            material: mesh.materials.len() - 1,
            positions,
            triangles,
            joint: None,
            uvs: None,
        });
    }
    GlbNode {
        name,
        world: node.world,
        mesh,
        children: node.children.iter().map(|c| convert(file, c)).collect(),
        is_room: node.room.is_some(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit box as exporters write it: 4 vertices per face, 24 in all.
    fn split_box() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
        let corner = |i: usize| {
            [
                (i & 1) as f32 - 0.5,
                ((i >> 1) & 1) as f32,
                ((i >> 2) & 1) as f32 - 0.5,
            ]
        };
        let faces = [
            [0, 1, 3, 2],
            [4, 6, 7, 5],
            [0, 4, 5, 1],
            [2, 3, 7, 6],
            [0, 2, 6, 4],
            [1, 5, 7, 3],
        ];
        let mut positions = Vec::new();
        let mut triangles = Vec::new();
        for face in faces {
            let base = positions.len() as u32;
            positions.extend(face.iter().map(|&i| corner(i)));
            // Wound counter-clockwise seen from outside.
            triangles.push([base, base + 2, base + 1]);
            triangles.push([base, base + 3, base + 2]);
        }
        (positions, triangles)
    }

    #[test]
    fn a_split_box_welds_back_to_a_box_not_a_cylinder() {
        let (positions, triangles) = split_box();
        let split = MeshPart {
            name: "box".into(),
            material: 0,
            positions: positions.clone(),
            triangles: triangles.clone(),
            joint: None,
            uvs: None,
        };
        assert!(
            crate::stability::round_solid(&split).is_some(),
            "the bug this guards: split corners read as a 12-sided cylinder"
        );
        let (positions, triangles) = welded(&positions, &triangles);
        assert_eq!(positions.len(), 8);
        assert_eq!(triangles.len(), 12);
        let part = MeshPart {
            name: "box".into(),
            material: 0,
            positions,
            triangles,
            joint: None,
            uvs: None,
        };
        assert!(crate::stability::round_solid(&part).is_none());
        assert!(crate::stability::is_convex(&part));
    }
}
