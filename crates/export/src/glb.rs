//! glTF 2.0 binary (`.glb`) writer.
//!
//! Layout: one buffer (the BIN chunk); per primitive buffer views and accessors for POSITION
//! (with min/max), NORMAL and u32 indices, plus TEXCOORD_0 (box-projected, in tiles of its
//! library material) and TANGENT when its material wears a library material; all 4-byte
//! aligned. Each map of each library material used is one PNG image in the buffer, shared by
//! every material wearing it: `baseColorTexture` (tinted by `baseColorFactor`),
//! `metallicRoughnessTexture` and `normalTexture`, one repeating sampler. A part showing an
//! imported image (its material's [`texture`](scenethesis_scene_graph::Material::texture), at
//! the part's own texture coordinates) has TEXCOORD_0 from those coordinates and its material
//! that image, embedded once per file by digest, as `baseColorTexture`. Glass adds
//! `KHR_materials_transmission` and `KHR_materials_ior`. Nodes are flat under the
//! scene root: the architecture pieces first (`floor`, `wall_0`, …, then each window's glass
//! pane named by the window's id; geometry in world coordinates, identity transform, `extras`
//! `{"architecture": "floor" | "wall" | "window"}`), then one node per object in scene order,
//! named by its id, with translation, a rotation about +Y and a uniform scale from its pose. In
//! a house (`architecture.rooms` not empty) the objects of each room are the children of a
//! node named by the room's id (`extras` `{"room": type}`, no transform), after the pieces;
//! objects in no room stay at the root. Node `extras` carry
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
//! the wall it is cut into (whose frame is the world's), pivoting at its hinge; a double
//! door's second leaf is its sibling `<door>_leaf_2`.

use std::collections::BTreeMap;

use serde::Serialize;
use serde_json::{json, Value};

use crate::architecture::{leaves, pieces, PieceKind};
use crate::articulation::Articulation;
use crate::geometry::{library_of, material_key, shade, worn, Mapping};
use crate::ExportScene;
use scenethesis_materials::{maps, LibraryMaterial, MapKind};
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
    #[serde(skip_serializing_if = "Vec::is_empty")]
    textures: Vec<Value>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    images: Vec<Value>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    samplers: Vec<Value>,
    accessors: Vec<Accessor>,
    buffer_views: Vec<BufferView>,
    buffers: Vec<Buffer>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    extensions_used: Vec<&'static str>,
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

/// glTF sampler constants: linear filtering with mipmaps, repeating in both directions.
const LINEAR: u32 = 9729;
const LINEAR_MIPMAP_LINEAR: u32 = 9987;
const REPEAT: u32 = 10497;
const TRANSMISSION: &str = "KHR_materials_transmission";
const IOR: &str = "KHR_materials_ior";

#[derive(Serialize)]
#[serde(rename_all = "camelCase")]
struct BufferView {
    buffer: usize,
    byte_offset: usize,
    byte_length: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    target: Option<u32>,
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
    /// Textures and images, one per map of each library material used (shared by every
    /// material that wears it).
    textures: Vec<Value>,
    images: Vec<Value>,
    texture_index: BTreeMap<(usize, MapKind), usize>,
    /// The texture of each imported image embedded, by digest.
    image_index: BTreeMap<u64, usize>,
    uses_transmission: bool,
}

impl Builder {
    fn new() -> Self {
        Self {
            bin: Vec::new(),
            accessors: Vec::new(),
            views: Vec::new(),
            materials: Vec::new(),
            material_index: BTreeMap::new(),
            meshes: Vec::new(),
            textures: Vec::new(),
            images: Vec::new(),
            texture_index: BTreeMap::new(),
            image_index: BTreeMap::new(),
            uses_transmission: false,
        }
    }

    fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
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
        let view = self.view(&bytes, Some(ARRAY_BUFFER));
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
        let view = self.view(&bytes, Some(ELEMENT_ARRAY_BUFFER));
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

    /// A float accessor of `N` components per element (`VEC2` texture coordinates, `VEC4`
    /// tangents).
    fn float_accessor<const N: usize>(&mut self, data: &[[f32; N]], kind: &'static str) -> usize {
        let bytes: Vec<u8> = data
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let view = self.view(&bytes, Some(ARRAY_BUFFER));
        self.accessors.push(Accessor {
            buffer_view: view,
            component_type: FLOAT,
            count: data.len(),
            kind,
            min: None,
            max: None,
        });
        self.accessors.len() - 1
    }

    /// The texture of one map of a library material: its PNG embedded in the buffer once, on
    /// first use.
    fn texture(&mut self, library: &LibraryMaterial, kind: MapKind) -> usize {
        let key = (library.index(), kind);
        if let Some(&i) = self.texture_index.get(&key) {
            return i;
        }
        let view = self.view(maps(library).png(kind), None);
        self.images.push(json!({
            "name": format!("{}_{}", library.id, kind.suffix()),
            "bufferView": view,
            "mimeType": "image/png",
        }));
        self.textures
            .push(json!({ "sampler": 0, "source": self.images.len() - 1 }));
        self.texture_index.insert(key, self.textures.len() - 1);
        self.textures.len() - 1
    }

    /// The texture of an imported image: its PNG embedded in the buffer once, on first use.
    fn image_texture(&mut self, image: &scenethesis_scene_graph::TextureImage) -> usize {
        if let Some(&i) = self.image_index.get(&image.digest()) {
            return i;
        }
        let view = self.view(image.png(), None);
        self.images.push(json!({
            "name": format!("image_{}", image.digest_hex()),
            "bufferView": view,
            "mimeType": "image/png",
        }));
        self.textures
            .push(json!({ "sampler": 0, "source": self.images.len() - 1 }));
        self.image_index
            .insert(image.digest(), self.textures.len() - 1);
        self.textures.len() - 1
    }

    /// The index of a glTF material equal to `m`, added on first use. Materials that agree in
    /// name, every factor and image are shared across objects. A material with an image has it
    /// as `baseColorTexture`. A material wearing a library material
    /// gets its base-colour, metallic-roughness and normal textures (the factors rescaled so
    /// the surface keeps its colour and roughness on average), glass its transmission.
    fn material(&mut self, m: &Material) -> usize {
        let key = material_key(m);
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
        if let Some(image) = &m.texture {
            let index = self.image_texture(image);
            value["pbrMetallicRoughness"]["baseColorTexture"] = json!({ "index": index });
        } else if let Some(library) = library_of(m) {
            self.add_textures(&mut value, m, library);
        }
        self.materials.push(value);
        self.material_index.insert(key, self.materials.len() - 1);
        self.materials.len() - 1
    }

    /// The textures of `library` on the glTF material `value` of scene material `m`.
    fn add_textures(&mut self, value: &mut Value, m: &Material, library: &LibraryMaterial) {
        let maps = maps(library);
        let clamp = |v: f32| v.clamp(0.0, 1.0);
        let color = self.texture(library, MapKind::BaseColor);
        let mr = self.texture(library, MapKind::MetallicRoughness);
        let normal = self.texture(library, MapKind::Normal);
        let pbr = &mut value["pbrMetallicRoughness"];
        pbr["baseColorFactor"] = json!(maps.color_factor(m.base_color));
        pbr["baseColorTexture"] = json!({ "index": color });
        pbr["metallicRoughnessTexture"] = json!({ "index": mr });
        pbr["roughnessFactor"] = json!(maps.roughness_factor(clamp(m.roughness)));
        value["normalTexture"] = json!({ "index": normal });
        if library.transmissive {
            self.uses_transmission = true;
            value["extensions"] = json!({
                TRANSMISSION: { "transmissionFactor": 1.0 },
                IOR: { "ior": 1.5 },
            });
        }
    }

    fn mesh(&mut self, name: &str, mesh: &Mesh) -> usize {
        let mut primitives = Vec::new();
        for part in mesh.parts.iter().filter(|p| !p.triangles.is_empty()) {
            let scene_material = worn(part, &mesh.materials[part.material]);
            let shaded = shade(part, Mapping::of(part, &scene_material));
            let position = self.vec3_accessor(&shaded.positions, true);
            let normal = self.vec3_accessor(&shaded.normals, false);
            let mut attributes = BTreeMap::from([("NORMAL", normal), ("POSITION", position)]);
            if !shaded.uvs.is_empty() {
                attributes.insert("TEXCOORD_0", self.float_accessor(&shaded.uvs, "VEC2"));
            }
            if !shaded.tangents.is_empty() {
                attributes.insert("TANGENT", self.float_accessor(&shaded.tangents, "VEC4"));
            }
            let indices = self.index_accessor(&shaded.indices);
            let material = self.material(&scene_material);
            primitives.push(Primitive {
                attributes,
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

/// The scene root's nodes: the architecture pieces (the first `first_object` nodes), then in
/// a house (`architecture.rooms` not empty) one node per room, named by its id with `extras`
/// `{"room": type}`, holding the nodes of the objects whose `room` it is; then every object
/// in no room of the house. Room nodes are appended to `nodes`.
fn group_by_room(
    scene: &scenethesis_scene_graph::Scene,
    nodes: &mut Vec<Node>,
    first_object: usize,
) -> Vec<usize> {
    let rooms = &scene.architecture.rooms;
    let object_node = |k: usize| first_object + k;
    let mut roots: Vec<usize> = (0..first_object).collect();
    for room in rooms {
        let children = (scene.objects.iter().enumerate())
            .filter(|(_, o)| o.room.as_deref() == Some(room.id.as_str()))
            .map(|(k, _)| object_node(k))
            .collect();
        nodes.push(Node {
            name: room.id.clone(),
            mesh: None,
            children,
            translation: None,
            rotation: None,
            scale: None,
            extras: json!({ "room": room.room_type }),
        });
        roots.push(nodes.len() - 1);
    }
    let in_a_room = |o: &scenethesis_scene_graph::SceneObject| {
        o.room
            .as_deref()
            .is_some_and(|r| rooms.iter().any(|room| room.id == r))
    };
    roots.extend(
        (scene.objects.iter().enumerate())
            .filter(|(_, o)| !in_a_room(o))
            .map(|(k, _)| object_node(k)),
    );
    roots
}

/// The scene as a glTF 2.0 binary file.
pub fn to_glb(export: &ExportScene<'_>) -> Vec<u8> {
    let scene = export.scene();
    let mut b = Builder::new();
    let mut nodes = Vec::new();
    for piece in pieces(&scene.architecture, &scene.look) {
        let mesh = b.mesh(&piece.id, &piece.to_mesh());
        let kind = match piece.kind {
            PieceKind::Floor => "floor",
            PieceKind::Wall => "wall",
            PieceKind::Window => "window",
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
            let articulation = Articulation::of_leaf(leaf);
            add_links(&mut b, &mut nodes, wall, &leaf.door, &articulation);
        }
    }
    let scene_nodes = group_by_room(scene, &mut nodes, first_object);
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
            nodes: scene_nodes,
        }],
        nodes,
        meshes: b.meshes,
        materials: b.materials,
        samplers: if b.textures.is_empty() {
            Vec::new()
        } else {
            vec![json!({
                "magFilter": LINEAR,
                "minFilter": LINEAR_MIPMAP_LINEAR,
                "wrapS": REPEAT,
                "wrapT": REPEAT,
            })]
        },
        textures: b.textures,
        images: b.images,
        accessors: b.accessors,
        buffer_views: b.views,
        buffers: vec![Buffer {
            byte_length: b.bin.len(),
        }],
        extensions_used: if b.uses_transmission {
            vec![IOR, TRANSMISSION]
        } else {
            Vec::new()
        },
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
