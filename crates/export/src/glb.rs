//! glTF 2.0 binary (`.glb`) writer.
//!
//! Layout: one buffer (the BIN chunk); per primitive three buffer views and accessors
//! (POSITION with min/max, NORMAL, u32 indices), all 4-byte aligned. Nodes are flat under the
//! scene root: the architecture pieces first (`floor`, `wall_0`, …; geometry in world
//! coordinates, identity transform), then one node per object in scene order, named by its id,
//! with translation, a rotation about +Y and a uniform scale from its pose. Node `extras` carry
//! the object's category, parent, support and asset; primitive `extras` the part name.
//!
//! An articulated object's node holds its body's mesh and has one child node per joint (a
//! nested joint's node under its parent's), appended after the root nodes and named
//! `<object>_<joint>`: its translation at the joint's anchor in the parent node's frame,
//! rotated or slid by the joint's state, its mesh in that frame, and `extras`
//! `{"joint": {name, kind, axis, anchor, limits, opens_to, parent?, state}}` as `scene.json`
//! writes the joint (radians or metres, asset units). Turning a node about `axis` (a revolute
//! joint) or moving it along `axis` (a prismatic one) animates the part in Blender or
//! three.js. A room door's leaf is such a link node, `<door>_leaf`, a child of the node of
//! the wall it is cut into (whose frame is the world's), pivoting at its hinge.

use std::collections::BTreeMap;

use serde::Serialize;
use serde_json::{json, Value};

use crate::architecture::{leaves, pieces, PieceKind};
use crate::articulation::Articulation;
use crate::geometry::shade;
use crate::ExportScene;
use scenethesis_scene_graph::{JointState, Material, Mesh};

const GLB_MAGIC: u32 = 0x4654_6C67;
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;

#[derive(Serialize)]
#[serde(rename_all = "camelCase")]
struct Root {
    asset: Asset,
    scene: usize,
    scenes: Vec<SceneDef>,
    nodes: Vec<Node>,
    meshes: Vec<MeshDef>,
    materials: Vec<Value>,
    accessors: Vec<Accessor>,
    buffer_views: Vec<BufferView>,
    buffers: Vec<Buffer>,
}

#[derive(Serialize)]
struct Asset {
    version: &'static str,
    generator: &'static str,
}

#[derive(Serialize)]
struct SceneDef {
    name: &'static str,
    nodes: Vec<usize>,
}

#[derive(Serialize)]
struct Node {
    name: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    mesh: Option<usize>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    children: Vec<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    translation: Option<[f64; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rotation: Option<[f64; 4]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    scale: Option<[f64; 3]>,
    extras: Value,
}

#[derive(Serialize)]
struct MeshDef {
    name: String,
    primitives: Vec<Primitive>,
}

#[derive(Serialize)]
struct Primitive {
    attributes: BTreeMap<&'static str, usize>,
    indices: usize,
    material: usize,
    extras: Value,
}

#[derive(Serialize)]
#[serde(rename_all = "camelCase")]
struct Accessor {
    buffer_view: usize,
    component_type: u32,
    count: usize,
    #[serde(rename = "type")]
    kind: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    min: Option<[f32; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    max: Option<[f32; 3]>,
}

#[derive(Serialize)]
#[serde(rename_all = "camelCase")]
struct BufferView {
    buffer: usize,
    byte_offset: usize,
    byte_length: usize,
    target: u32,
}

#[derive(Serialize)]
#[serde(rename_all = "camelCase")]
struct Buffer {
    byte_length: usize,
}

/// Builds the JSON and binary parts while meshes are added.
struct Builder {
    bin: Vec<u8>,
    accessors: Vec<Accessor>,
    views: Vec<BufferView>,
    materials: Vec<Value>,
    material_index: BTreeMap<String, usize>,
    meshes: Vec<MeshDef>,
}

impl Builder {
    fn view(&mut self, bytes: &[u8], target: u32) -> usize {
        while self.bin.len() % 4 != 0 {
            self.bin.push(0);
        }
        self.views.push(BufferView {
            buffer: 0,
            byte_offset: self.bin.len(),
            byte_length: bytes.len(),
            target,
        });
        self.bin.extend_from_slice(bytes);
        self.views.len() - 1
    }

    fn vec3_accessor(&mut self, data: &[[f32; 3]], bounds: bool) -> usize {
        let bytes: Vec<u8> = data
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let view = self.view(&bytes, ARRAY_BUFFER);
        let (min, max) = if bounds {
            let mut min = [f32::INFINITY; 3];
            let mut max = [f32::NEG_INFINITY; 3];
            for p in data {
                for k in 0..3 {
                    min[k] = min[k].min(p[k]);
                    max[k] = max[k].max(p[k]);
                }
            }
            (Some(min), Some(max))
        } else {
            (None, None)
        };
        self.accessors.push(Accessor {
            buffer_view: view,
            component_type: FLOAT,
            count: data.len(),
            kind: "VEC3",
            min,
            max,
        });
        self.accessors.len() - 1
    }

    fn index_accessor(&mut self, indices: &[u32]) -> usize {
        let bytes: Vec<u8> = indices.iter().flat_map(|v| v.to_le_bytes()).collect();
        let view = self.view(&bytes, ELEMENT_ARRAY_BUFFER);
        self.accessors.push(Accessor {
            buffer_view: view,
            component_type: UNSIGNED_INT,
            count: indices.len(),
            kind: "SCALAR",
            min: None,
            max: None,
        });
        self.accessors.len() - 1
    }

    /// The index of a glTF material equal to `m`, added on first use. Materials that agree in
    /// name and every factor are shared across objects.
    fn material(&mut self, m: &Material) -> usize {
        let key = format!(
            "{}|{:?}|{}|{}",
            m.name,
            m.base_color.map(f32::to_bits),
            m.roughness.to_bits(),
            m.metallic.to_bits()
        );
        if let Some(&i) = self.material_index.get(&key) {
            return i;
        }
        let clamp = |v: f32| v.clamp(0.0, 1.0);
        let mut value = json!({
            "name": m.name,
            "pbrMetallicRoughness": {
                "baseColorFactor": m.base_color.map(clamp),
                "metallicFactor": clamp(m.metallic),
                "roughnessFactor": clamp(m.roughness),
            },
        });
        if m.base_color[3] < 1.0 {
            value["alphaMode"] = json!("BLEND");
        }
        self.materials.push(value);
        self.material_index.insert(key, self.materials.len() - 1);
        self.materials.len() - 1
    }

    fn mesh(&mut self, name: &str, mesh: &Mesh) -> usize {
        let mut primitives = Vec::new();
        for part in mesh.parts.iter().filter(|p| !p.triangles.is_empty()) {
            let shaded = shade(part);
            let position = self.vec3_accessor(&shaded.positions, true);
            let normal = self.vec3_accessor(&shaded.normals, false);
            let indices = self.index_accessor(&shaded.indices);
            let material = self.material(&mesh.materials[part.material]);
            primitives.push(Primitive {
                attributes: BTreeMap::from([("NORMAL", normal), ("POSITION", position)]),
                indices,
                material,
                extras: json!({ "part": part.name }),
            });
        }
        self.meshes.push(MeshDef {
            name: name.to_owned(),
            primitives,
        });
        self.meshes.len() - 1
    }
}

/// The link nodes of an articulated object (or a door, `owner` its id), appended after every
/// root node: one per joint, a child of its parent link's node (or of the object's node, or the
/// door's wall's, `object_node`), at the joint's
/// anchor and moved by its state, holding the link's mesh in its own frame, its `extras`
/// `{"joint": …}` the joint as `scene.json` writes it (radians or metres, asset units).
fn add_links(
    b: &mut Builder,
    nodes: &mut Vec<Node>,
    object_node: usize,
    owner: &str,
    articulation: &Articulation<'_>,
) {
    let mut indices = Vec::with_capacity(articulation.links.len());
    for (i, link) in articulation.links.iter().enumerate() {
        let name = format!("{owner}_{}", link.joint.name);
        let mesh = link.has_geometry().then(|| b.mesh(&name, &link.mesh));
        let local = articulation.local_pose(i);
        let t = local.translation.vector;
        let q = local.rotation;
        let joint = JointState {
            joint: link.joint.clone(),
            state: link.state as f32,
        };
        nodes.push(Node {
            name,
            mesh,
            children: Vec::new(),
            translation: Some([t.x, t.y, t.z]),
            rotation: Some([q.i, q.j, q.k, q.w]),
            scale: None,
            extras: json!({ "joint": as_written(&joint) }),
        });
        let index = nodes.len() - 1;
        let parent = link.parent.map_or(object_node, |p| indices[p]);
        nodes[parent].children.push(index);
        indices.push(index);
    }
}

/// A joint as `scene.json` writes it: through text, so that `f32` values keep their shortest
/// form (1.9, not 1.899999976158142).
fn as_written(joint: &JointState) -> Value {
    serde_json::to_string(joint)
        .ok()
        .and_then(|text| serde_json::from_str(&text).ok())
        .unwrap_or(Value::Null)
}

/// The scene as a glTF 2.0 binary file.
pub fn to_glb(export: &ExportScene<'_>) -> Vec<u8> {
    let scene = export.scene();
    let mut b = Builder {
        bin: Vec::new(),
        accessors: Vec::new(),
        views: Vec::new(),
        materials: Vec::new(),
        material_index: BTreeMap::new(),
        meshes: Vec::new(),
    };
    let mut nodes = Vec::new();
    for piece in pieces(&scene.architecture) {
        let mesh = b.mesh(&piece.id, &piece.to_mesh());
        let kind = match piece.kind {
            PieceKind::Floor => "floor",
            PieceKind::Wall => "wall",
        };
        nodes.push(Node {
            name: piece.id.clone(),
            mesh: Some(mesh),
            children: Vec::new(),
            translation: None,
            rotation: None,
            scale: None,
            extras: json!({ "architecture": kind }),
        });
    }
    let articulations: Vec<Option<Articulation<'_>>> = scene
        .objects
        .iter()
        .map(|o| Articulation::of(o, export.mesh(o)))
        .collect();
    for (object, articulation) in scene.objects.iter().zip(&articulations) {
        let body = articulation
            .as_ref()
            .map_or(export.mesh(object), |a| &a.body);
        let drawn = body.parts.iter().any(|p| !p.triangles.is_empty());
        let mesh = drawn.then(|| b.mesh(&object.id, body));
        let pose = &object.pose;
        let t = pose.translation;
        let half = pose.yaw / 2.0;
        nodes.push(Node {
            name: object.id.clone(),
            mesh,
            children: Vec::new(),
            translation: Some([t.x, t.y, t.z]),
            rotation: Some([0.0, half.sin(), 0.0, half.cos()]),
            scale: Some([pose.scale; 3]),
            extras: json!({
                "category": object.category,
                "parent": object.parent.to_string(),
                "support": object.support.as_str(),
                "asset": object.asset.to_string(),
            }),
        });
    }
    let roots = nodes.len();
    let first_object = roots - scene.objects.len();
    for (k, (object, articulation)) in scene.objects.iter().zip(&articulations).enumerate() {
        if let Some(articulation) = articulation {
            add_links(
                &mut b,
                &mut nodes,
                first_object + k,
                &object.id,
                articulation,
            );
        }
    }
    for leaf in &leaves(&scene.architecture) {
        if let Some(wall) = nodes[..first_object]
            .iter()
            .position(|n| n.name == leaf.wall)
        {
            let articulation = Articulation::of_leaf(&leaf.geometry);
            add_links(&mut b, &mut nodes, wall, &leaf.door, &articulation);
        }
    }
    while b.bin.len() % 4 != 0 {
        b.bin.push(0);
    }
    let root = Root {
        asset: Asset {
            version: "2.0",
            generator: "scenethesis-export",
        },
        scene: 0,
        scenes: vec![SceneDef {
            name: "scene",
            nodes: (0..roots).collect(),
        }],
        nodes,
        meshes: b.meshes,
        materials: b.materials,
        accessors: b.accessors,
        buffer_views: b.views,
        buffers: vec![Buffer {
            byte_length: b.bin.len(),
        }],
    };
    let mut json = serde_json::to_vec(&root).expect("glTF JSON serialization cannot fail");
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    let total = 12 + 8 + json.len() + 8 + b.bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(&GLB_MAGIC.to_le_bytes());
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(&CHUNK_JSON.to_le_bytes());
    out.extend_from_slice(&json);
    out.extend_from_slice(&(b.bin.len() as u32).to_le_bytes());
    out.extend_from_slice(&CHUNK_BIN.to_le_bytes());
    out.extend_from_slice(&b.bin);
    out
}
