//! Reading triangle meshes out of glTF / GLB files, node by node, in world coordinates.

use std::path::{Path, PathBuf};

use nalgebra::{Matrix4, Point3, Vector3};
use scenethesis_scene_graph::{Material, Mesh, MeshPart};

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
    /// Reads a `.glb` or `.gltf` file (external buffers are resolved next to it; embedded
    /// base64 buffers are not supported).
    pub fn read(path: &Path) -> Result<Self, EvalError> {
        let bytes = std::fs::read(path).map_err(|source| EvalError::Io {
            path: path.to_owned(),
            source,
        })?;
        Self::from_slice(&bytes, path)
    }

    /// Parses glTF / GLB bytes; `path` names the file in errors and locates external buffers.
    pub fn from_slice(bytes: &[u8], path: &Path) -> Result<Self, EvalError> {
        let gltf = gltf::Gltf::from_slice(bytes).map_err(|source| EvalError::Gltf {
            path: path.to_owned(),
            source,
        })?;
        let dir = path.parent().unwrap_or(Path::new("."));
        let mut buffers = Vec::new();
        for buffer in gltf.document.buffers() {
            let data = match buffer.source() {
                gltf::buffer::Source::Bin => {
                    gltf.blob.clone().ok_or_else(|| EvalError::BadGltf {
                        path: path.to_owned(),
                        reason: "buffer refers to a missing BIN chunk".into(),
                    })?
                }
                gltf::buffer::Source::Uri(uri) => {
                    if uri.starts_with("data:") {
                        return Err(EvalError::BadGltf {
                            path: path.to_owned(),
                            reason: "embedded base64 buffers are not supported; use GLB".into(),
                        });
                    }
                    let file = dir.join(uri);
                    std::fs::read(&file).map_err(|source| EvalError::Io { path: file, source })?
                }
            };
            buffers.push(data);
        }
        let scene = gltf
            .document
            .default_scene()
            .or_else(|| gltf.document.scenes().next());
        let roots = match scene {
            Some(scene) => scene
                .nodes()
                .map(|n| read_node(&n, &Matrix4::identity(), &buffers, path))
                .collect::<Result<Vec<_>, _>>()?,
            None => Vec::new(),
        };
        Ok(Self {
            path: path.to_owned(),
            roots,
        })
    }

    /// The first node named `name` anywhere in the scene.
    pub fn find(&self, name: &str) -> Option<&GlbNode> {
        self.roots.iter().find_map(|r| r.find(name))
    }
}

fn read_node(
    node: &gltf::Node,
    parent: &Matrix4<f64>,
    buffers: &[Vec<u8>],
    path: &Path,
) -> Result<GlbNode, EvalError> {
    let cols = node.transform().matrix();
    let local = Matrix4::from_fn(|r, c| cols[c][r] as f64);
    let world = parent * local;
    let name = node
        .name()
        .map(str::to_owned)
        .unwrap_or_else(|| format!("node_{}", node.index()));
    let mut mesh = Mesh::default();
    if let Some(m) = node.mesh() {
        let mirrored = world.fixed_view::<3, 3>(0, 0).determinant() < 0.0;
        for (k, prim) in m.primitives().enumerate() {
            if prim.mode() != gltf::mesh::Mode::Triangles {
                continue;
            }
            let reader = prim.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
            let Some(positions) = reader.read_positions() else {
                continue;
            };
            let positions: Vec<[f32; 3]> = positions
                .map(|p| {
                    let w = world.transform_point(&Point3::from(Vector3::from(p).cast::<f64>()));
                    [w.x as f32, w.y as f32, w.z as f32]
                })
                .collect();
            let indices: Vec<u32> = match reader.read_indices() {
                Some(ix) => ix.into_u32().collect(),
                None => (0..positions.len() as u32).collect(),
            };
            if indices.iter().any(|&i| i as usize >= positions.len()) {
                return Err(EvalError::BadGltf {
                    path: path.to_owned(),
                    reason: format!("node {name}: index out of range"),
                });
            }
            let triangles = indices
                .chunks_exact(3)
                .map(|t| {
                    if mirrored {
                        [t[0], t[2], t[1]]
                    } else {
                        [t[0], t[1], t[2]]
                    }
                })
                .collect();
            let pbr = prim.material().pbr_metallic_roughness();
            let c = pbr.base_color_factor();
            mesh.materials.push(Material {
                name: prim.material().name().unwrap_or("default").to_owned(),
                base_color: c,
                roughness: pbr.roughness_factor(),
                metallic: pbr.metallic_factor(),
            });
            mesh.parts.push(MeshPart {
                name: format!("{name}/{k}"),
                material: mesh.materials.len() - 1,
                positions,
                triangles,
            });
        }
    }
    let children = node
        .children()
        .map(|c| read_node(&c, &world, buffers, path))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(GlbNode {
        name,
        world,
        mesh,
        children,
    })
}
