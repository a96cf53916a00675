//! The one glTF 2.0 reader of the workspace (binary `.glb`, and `.gltf` with external or
//! embedded buffers), shared by asset import and `eval`. It treats its input as hostile:
//!
//! - the file and every external buffer are read with a size limit ([`super::limits`]);
//! - buffer URIs must be `data:` URIs or relative paths that, once canonicalised, stay inside
//!   the containment folder given by the caller (the asset pack, or the file's own folder);
//!   image URIs follow the same rule; a base-colour texture is decoded within the limits and
//!   kept on its material (a texture that cannot be used is a warning), and the primitives
//!   wearing it keep the texture coordinates it names (`TEXCOORD_n`);
//! - node hierarchies are walked with an explicit depth limit and a check for cycles (a node
//!   that is its own ancestor), and the total number of node instances, vertices and triangles
//!   is bounded, so a graph that shares nodes exponentially cannot blow up;
//! - accessors are checked against their buffer views and buffers before the `gltf` crate reads
//!   them (sparse accessors are refused), indices against the vertex count, texture
//!   coordinates for one finite pair per vertex;
//! - node transforms and vertex positions must be finite and within
//!   [`super::limits::MAX_FILE_COORDINATE`].
//!
//! Every problem is a [`GltfError`] naming the glTF field (`nodes[3]`, `accessors[7]`, ...).

use std::path::{Path, PathBuf};

use gltf::mesh::Mode;
use nalgebra::{Matrix4, Point3};
use scenethesis_scene_graph::{printable, read_bounded, Material, Mesh, MeshPart, TextureImage};

use super::limits::{
    MAX_BUFFER_BYTES, MAX_FILE_COORDINATE, MAX_GLTF_BYTES, MAX_NODE_DEPTH, MAX_NODE_INSTANCES,
    MAX_TEXTURE_BYTES, MAX_TRIANGLES, MAX_VERTICES,
};
use super::MeshLoadError;

/// Why a glTF / GLB file could not be read. The messages name the glTF field at fault but not
/// the file: callers add it.
#[derive(Debug, thiserror::Error)]
pub enum GltfError {
    /// The file or an external buffer could not be read (or is over its size limit).
    #[error("cannot read {path}: {source}")]
    Io {
        /// The file that could not be read.
        path: PathBuf,
        /// The OS error, or the size limit.
        source: std::io::Error,
    },
    /// The bytes are not glTF / GLB.
    #[error("not a valid glTF/GLB file: {0}")]
    Parse(gltf::Error),
    /// The file parsed but a field is unusable or over a limit.
    #[error("{field}: {reason}")]
    Invalid {
        /// The glTF field, e.g. `nodes[2].matrix` or `buffers[0].uri`.
        field: String,
        /// What is wrong and what was expected.
        reason: String,
    },
}

fn invalid(field: impl Into<String>, reason: impl Into<String>) -> GltfError {
    GltfError::Invalid {
        field: field.into(),
        reason: reason.into(),
    }
}

/// A material's name, factors and base-colour texture.
#[derive(Debug, Clone, PartialEq)]
pub struct GltfMaterial {
    /// The material's name, if it has one.
    pub name: Option<String>,
    /// Base colour factor (linear RGBA, each clamped to 0..=1).
    pub base_color: [f32; 4],
    /// Roughness factor (0..=1).
    pub roughness: f32,
    /// Metalness factor (0..=1).
    pub metallic: f32,
    /// The base-colour texture's image, when it could be used, and the index `n` of the
    /// `TEXCOORD_n` set it is sampled with.
    pub texture: Option<(TextureImage, u32)>,
}

impl GltfMaterial {
    /// The material as a scene-graph [`Material`] named `name`.
    pub fn to_material(&self, name: String) -> Material {
        Material {
            name,
            base_color: self.base_color,
            roughness: self.roughness,
            metallic: self.metallic,
            texture: self.texture.as_ref().map(|(image, _)| image.clone()),
        }
    }
}

/// One triangle primitive of a node, in world coordinates (file units).
#[derive(Debug, Clone)]
pub struct GltfPrimitive {
    /// Index of the glTF mesh.
    pub mesh: usize,
    /// The glTF mesh's name.
    pub mesh_name: Option<String>,
    /// Index of the primitive within its mesh.
    pub index: usize,
    /// The glTF material index (`None`: the default material).
    pub material: Option<usize>,
    /// Vertex positions, world coordinates (node transforms applied).
    pub positions: Vec<[f32; 3]>,
    /// Triangles (strips and fans converted; winding flipped under mirroring transforms).
    /// Degenerate triangles are kept.
    pub triangles: Vec<[u32; 3]>,
    /// Texture coordinates per vertex (glTF's convention, v down from the image's top), read
    /// when the primitive's material has a usable base-colour texture and the primitive the
    /// `TEXCOORD_n` set that texture names; `None` otherwise.
    pub uvs: Option<Vec<[f32; 2]>>,
}

/// One node instance of the scene.
#[derive(Debug, Clone)]
pub struct GltfNode {
    /// The glTF node index.
    pub index: usize,
    /// The node's name.
    pub name: Option<String>,
    /// World-from-node transform.
    pub world: Matrix4<f64>,
    /// The node's own triangle primitives.
    pub primitives: Vec<GltfPrimitive>,
    /// Child node instances.
    pub children: Vec<GltfNode>,
    /// The room type in the node's `extras` (`{"room": type}`): a node grouping the objects of
    /// one room of a house, as scenethesis writes them.
    pub room: Option<String>,
}

/// A glTF file's default scene (or first scene; without scenes, every node that is nobody's
/// child), read and checked.
#[derive(Debug, Clone)]
pub struct GltfFile {
    /// The materials, by glTF index.
    pub materials: Vec<GltfMaterial>,
    /// Top-level node instances, in file order.
    pub roots: Vec<GltfNode>,
    /// One line per base-colour texture that could not be used (missing, outside the asset
    /// folder, over a limit, not a PNG or JPEG), naming the material and the image; its
    /// material keeps the plain base-colour factor and no image.
    pub texture_warnings: Vec<String>,
}

/// The `room` string of a node's `extras`, if it has one.
fn room_of(node: &gltf::Node<'_>) -> Option<String> {
    let extras = node.extras().as_ref()?;
    let value: serde_json::Value = serde_json::from_str(extras.get()).ok()?;
    value.get("room")?.as_str().map(str::to_owned)
}

impl GltfFile {
    /// Reads a `.glb` / `.gltf` file. External buffers must resolve inside `root` (the asset
    /// pack folder; the file's own folder when `None`).
    pub fn read(path: &Path, root: Option<&Path>) -> Result<Self, GltfError> {
        let bytes = read_bounded(path, MAX_GLTF_BYTES).map_err(|source| GltfError::Io {
            path: path.to_owned(),
            source,
        })?;
        let dir = path.parent().unwrap_or(Path::new("."));
        let dir = if dir.as_os_str().is_empty() {
            Path::new(".")
        } else {
            dir
        };
        Self::from_slice(&bytes, dir, root.unwrap_or(dir))
    }

    /// Parses glTF / GLB bytes; relative buffer URIs are resolved against `dir` and must stay
    /// inside `root`.
    pub fn from_slice(bytes: &[u8], dir: &Path, root: &Path) -> Result<Self, GltfError> {
        let gltf = parse_checked(bytes)?;
        let mut buffers = Vec::new();
        let mut total = 0usize;
        for buffer in gltf.buffers() {
            let field = format!("buffers[{}]", buffer.index());
            let data = match buffer.source() {
                gltf::buffer::Source::Bin => gltf
                    .blob
                    .clone()
                    .ok_or_else(|| invalid(&field, "refers to a missing GLB binary chunk"))?,
                gltf::buffer::Source::Uri(uri) => read_uri(dir, root, uri, &field)?,
            };
            if data.len() < buffer.length() {
                return Err(invalid(
                    format!("{field}.byteLength"),
                    format!(
                        "is {}, but the data holds {} bytes",
                        buffer.length(),
                        data.len()
                    ),
                ));
            }
            total = total.saturating_add(data.len());
            if total as u64 > MAX_BUFFER_BYTES {
                return Err(invalid(
                    field,
                    format!("buffers hold more than the limit of {MAX_BUFFER_BYTES} bytes"),
                ));
            }
            buffers.push(data);
        }
        let mut materials: Vec<GltfMaterial> =
            gltf.materials().map(|m| read_material(&m)).collect();
        let texture_warnings = read_textures(&gltf, &buffers, dir, root, &mut materials);
        let mut walker = Walker {
            buffers: &buffers,
            texcoord_sets: materials
                .iter()
                .map(|m| m.texture.as_ref().map(|(_, set)| *set))
                .collect(),
            instances: 0,
            vertices: 0,
            triangles: 0,
            on_path: vec![false; gltf.nodes().len()],
        };
        let scene = gltf.default_scene().or_else(|| gltf.scenes().next());
        let root_nodes: Vec<gltf::Node<'_>> = match scene {
            Some(scene) => scene.nodes().collect(),
            None => {
                let mut is_child = vec![false; gltf.nodes().len()];
                for n in gltf.nodes() {
                    for c in n.children() {
                        is_child[c.index()] = true;
                    }
                }
                gltf.nodes().filter(|n| !is_child[n.index()]).collect()
            }
        };
        let roots = root_nodes
            .iter()
            .map(|n| walker.node(n, &Matrix4::identity(), 0))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            materials,
            roots,
            texture_warnings,
        })
    }

    /// The material of a primitive (`None`: the glTF default material, white, roughness and
    /// metalness 1).
    pub fn material(&self, index: Option<usize>) -> GltfMaterial {
        index
            .and_then(|i| self.materials.get(i).cloned())
            .unwrap_or(GltfMaterial {
                name: None,
                base_color: [1.0; 4],
                roughness: 1.0,
                metallic: 1.0,
                texture: None,
            })
    }
}

/// Parses without the `gltf` crate's validation, checks what that validation indexes without a
/// bounds check (a primitive's POSITION accessor), then validates.
fn parse_checked(bytes: &[u8]) -> Result<gltf::Gltf, GltfError> {
    let raw = gltf::Gltf::from_slice_without_validation(bytes).map_err(GltfError::Parse)?;
    let json = raw.document.into_json();
    let accessors = json.accessors.len();
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            for index in primitive.attributes.values() {
                if index.value() >= accessors {
                    return Err(invalid(
                        format!("meshes[{m}].primitives[{p}].attributes"),
                        format!(
                            "names accessor {}, but the file has {accessors}",
                            index.value()
                        ),
                    ));
                }
            }
        }
    }
    let document = gltf::Document::from_json(json).map_err(GltfError::Parse)?;
    Ok(gltf::Gltf {
        document,
        blob: raw.blob,
    })
}

fn unit(v: f32, default: f32) -> f32 {
    if v.is_finite() {
        v.clamp(0.0, 1.0)
    } else {
        default
    }
}

/// Reads the base-colour texture of every material that has one onto it; returns a warning for
/// each texture that could not be used (its material keeps the plain factor and no image).
fn read_textures(
    gltf: &gltf::Gltf,
    buffers: &[Vec<u8>],
    dir: &Path,
    root: &Path,
    materials: &mut [GltfMaterial],
) -> Vec<String> {
    let mut warnings = Vec::new();
    for (m, material) in gltf.materials().zip(materials.iter_mut()) {
        let Some(info) = m.pbr_metallic_roughness().base_color_texture() else {
            continue;
        };
        let image = info.texture().source();
        let decoded = image_bytes(&image, buffers, dir, root)
            .and_then(|bytes| super::textures::texture_image(&bytes));
        match decoded {
            Ok(texture) => material.texture = Some((texture, info.tex_coord())),
            Err(reason) => warnings.push(format!(
                "materials[{}]{}: base-colour texture images[{}]{} cannot be used ({reason}); \
                 using the plain base colour",
                m.index().map_or("(default)".into(), |i| i.to_string()),
                m.name()
                    .map_or(String::new(), |n| format!(" `{}`", printable(n))),
                image.index(),
                image_label(&image),
            )),
        }
    }
    warnings
}

/// The encoded bytes of a glTF image: from a buffer view, a data URI, or a file inside `root`.
fn image_bytes(
    image: &gltf::image::Image<'_>,
    buffers: &[Vec<u8>],
    dir: &Path,
    root: &Path,
) -> Result<Vec<u8>, String> {
    match image.source() {
        gltf::image::Source::View { view, .. } => {
            let data = &buffers[view.buffer().index()];
            let end = view.offset().saturating_add(view.length());
            data.get(view.offset()..end)
                .map(<[u8]>::to_vec)
                .ok_or_else(|| {
                    format!(
                        "bufferViews[{}] runs past the end of its buffer",
                        view.index()
                    )
                })
        }
        gltf::image::Source::Uri { uri, .. } if uri.starts_with("data:") => {
            read_uri(dir, root, uri, "image").map_err(|e| e.to_string())
        }
        gltf::image::Source::Uri { uri, .. } => {
            let path = resolve_inside(dir, root, &percent_decode(uri))?;
            read_bounded(&path, MAX_TEXTURE_BYTES).map_err(|e| e.to_string())
        }
    }
}

/// ` (\`file.png\`)` for an image stored in a file, empty for an embedded one.
fn image_label(image: &gltf::image::Image<'_>) -> String {
    match image.source() {
        gltf::image::Source::Uri { uri, .. } if !uri.starts_with("data:") => {
            format!(" (`{}`)", printable(&percent_decode(uri)))
        }
        _ => String::new(),
    }
}

fn read_material(m: &gltf::Material<'_>) -> GltfMaterial {
    let pbr = m.pbr_metallic_roughness();
    GltfMaterial {
        name: m.name().map(str::to_owned),
        base_color: pbr.base_color_factor().map(|c| unit(c, 1.0)),
        roughness: unit(pbr.roughness_factor(), 1.0),
        metallic: unit(pbr.metallic_factor(), 1.0),
        texture: None,
    }
}

struct Walker<'a> {
    buffers: &'a [Vec<u8>],
    /// Per glTF material, the `TEXCOORD_n` set its usable base-colour texture is sampled with.
    texcoord_sets: Vec<Option<u32>>,
    instances: usize,
    vertices: usize,
    triangles: usize,
    /// Nodes on the path from the root to the current node (cycle detection).
    on_path: Vec<bool>,
}

impl Walker<'_> {
    fn node(
        &mut self,
        node: &gltf::Node<'_>,
        parent: &Matrix4<f64>,
        depth: usize,
    ) -> Result<GltfNode, GltfError> {
        let field = format!("nodes[{}]", node.index());
        if self.on_path[node.index()] {
            return Err(invalid(
                format!("{field}.children"),
                "the node is its own ancestor (the node hierarchy has a cycle)",
            ));
        }
        if depth >= MAX_NODE_DEPTH {
            return Err(invalid(
                field,
                format!("the node hierarchy is deeper than the limit of {MAX_NODE_DEPTH}"),
            ));
        }
        self.instances += 1;
        if self.instances > MAX_NODE_INSTANCES {
            return Err(invalid(
                field,
                format!("the scene instantiates more than the limit of {MAX_NODE_INSTANCES} nodes"),
            ));
        }
        let cols = node.transform().matrix();
        if let Some(v) = cols
            .iter()
            .flatten()
            .find(|v| !v.is_finite() || v.abs() > MAX_FILE_COORDINATE as f32)
        {
            return Err(invalid(
                format!("{field}.matrix/translation/rotation/scale"),
                format!("holds {v}, expected finite values within ±{MAX_FILE_COORDINATE}"),
            ));
        }
        let local = Matrix4::from_fn(|r, c| cols[c][r] as f64);
        let world = parent * local;
        let mut primitives = Vec::new();
        if let Some(mesh) = node.mesh() {
            let mirrored = world.fixed_view::<3, 3>(0, 0).determinant() < 0.0;
            for primitive in mesh.primitives() {
                if let Some(p) = self.primitive(&mesh, &primitive, &world, mirrored)? {
                    primitives.push(p);
                }
            }
        }
        self.on_path[node.index()] = true;
        let children = node
            .children()
            .map(|c| self.node(&c, &world, depth + 1))
            .collect::<Result<Vec<_>, _>>();
        self.on_path[node.index()] = false;
        Ok(GltfNode {
            index: node.index(),
            name: node.name().map(str::to_owned),
            world,
            primitives,
            children: children?,
            room: room_of(node),
        })
    }

    fn primitive(
        &mut self,
        mesh: &gltf::Mesh<'_>,
        primitive: &gltf::Primitive<'_>,
        world: &Matrix4<f64>,
        mirrored: bool,
    ) -> Result<Option<GltfPrimitive>, GltfError> {
        let mode = primitive.mode();
        if !matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            return Ok(None); // Points and lines carry no surface.
        }
        let field = format!("meshes[{}].primitives[{}]", mesh.index(), primitive.index());
        let Some(accessor) = primitive.get(&gltf::Semantic::Positions) else {
            return Err(invalid(
                format!("{field}.attributes"),
                "has no POSITION attribute",
            ));
        };
        check_accessor(&accessor, self.buffers, Use::Positions)?;
        self.vertices = self.vertices.saturating_add(accessor.count());
        if self.vertices > MAX_VERTICES {
            return Err(invalid(
                field,
                format!("the scene holds more than the limit of {MAX_VERTICES} vertices"),
            ));
        }
        if let Some(indices) = primitive.indices() {
            check_accessor(&indices, self.buffers, Use::Indices)?;
        }
        let reader = primitive.reader(|b| self.buffers.get(b.index()).map(|d| d.as_slice()));
        let mut positions = Vec::with_capacity(accessor.count());
        for p in reader.read_positions().into_iter().flatten() {
            if let Some(v) = p
                .iter()
                .find(|v| !v.is_finite() || v.abs() > MAX_FILE_COORDINATE as f32)
            {
                return Err(invalid(
                    format!("accessors[{}]", accessor.index()),
                    format!(
                        "vertex {} holds {v}, expected finite positions within ±{MAX_FILE_COORDINATE}",
                        positions.len()
                    ),
                ));
            }
            let q = world.transform_point(&Point3::new(p[0] as f64, p[1] as f64, p[2] as f64));
            if let Some(v) = q
                .iter()
                .find(|v| !v.is_finite() || v.abs() > MAX_FILE_COORDINATE)
            {
                return Err(invalid(
                    field,
                    format!(
                        "node transforms put vertex {} at {v}, expected within ±{MAX_FILE_COORDINATE}",
                        positions.len()
                    ),
                ));
            }
            positions.push([q.x as f32, q.y as f32, q.z as f32]);
        }
        let indices: Vec<u32> = match reader.read_indices() {
            Some(i) => i.into_u32().collect(),
            None => (0..positions.len() as u32).collect(),
        };
        if let Some(&bad) = indices.iter().find(|&&i| i as usize >= positions.len()) {
            return Err(invalid(
                format!("{field}.indices"),
                format!("index {bad} out of range ({} vertices)", positions.len()),
            ));
        }
        let mut triangles: Vec<[u32; 3]> = match mode {
            Mode::Triangles => indices
                .chunks_exact(3)
                .map(|c| [c[0], c[1], c[2]])
                .collect(),
            Mode::TriangleStrip => indices
                .windows(3)
                .enumerate()
                .map(|(k, w)| {
                    if k % 2 == 0 {
                        [w[0], w[1], w[2]]
                    } else {
                        [w[1], w[0], w[2]]
                    }
                })
                .collect(),
            _ => indices
                .windows(2)
                .skip(1)
                .map(|w| [indices[0], w[0], w[1]])
                .collect(),
        };
        self.triangles = self.triangles.saturating_add(triangles.len());
        if self.triangles > MAX_TRIANGLES {
            return Err(invalid(
                field,
                format!("the scene holds more than the limit of {MAX_TRIANGLES} triangles"),
            ));
        }
        if mirrored {
            for t in &mut triangles {
                t.swap(1, 2);
            }
        }
        let set = primitive
            .material()
            .index()
            .and_then(|m| self.texcoord_sets.get(m).copied().flatten());
        let uvs = match set.and_then(|n| Some((n, primitive.get(&gltf::Semantic::TexCoords(n))?))) {
            Some((n, accessor)) => Some(self.texcoords(&reader, n, &accessor, positions.len())?),
            None => None,
        };
        Ok(Some(GltfPrimitive {
            mesh: mesh.index(),
            mesh_name: mesh.name().map(str::to_owned),
            index: primitive.index(),
            material: primitive.material().index(),
            positions,
            triangles,
            uvs,
        }))
    }

    /// The `TEXCOORD_n` set of a primitive with `vertices` vertices: one finite pair per
    /// vertex.
    fn texcoords<'a, 's, F>(
        &self,
        reader: &gltf::mesh::Reader<'a, 's, F>,
        set: u32,
        accessor: &gltf::Accessor<'_>,
        vertices: usize,
    ) -> Result<Vec<[f32; 2]>, GltfError>
    where
        F: Clone + Fn(gltf::Buffer<'a>) -> Option<&'s [u8]>,
    {
        check_accessor(accessor, self.buffers, Use::TexCoords)?;
        let field = format!("accessors[{}]", accessor.index());
        if accessor.count() != vertices {
            return Err(invalid(
                field,
                format!(
                    "TEXCOORD_{set} holds {} elements for {vertices} vertices",
                    accessor.count()
                ),
            ));
        }
        let uvs: Vec<[f32; 2]> = reader
            .read_tex_coords(set)
            .map(|t| t.into_f32().collect())
            .unwrap_or_default();
        if uvs.len() != vertices {
            return Err(invalid(field, format!("TEXCOORD_{set} cannot be read")));
        }
        if let Some(k) = uvs.iter().position(|uv| {
            uv.iter()
                .any(|v| !v.is_finite() || v.abs() > MAX_FILE_COORDINATE as f32)
        }) {
            return Err(invalid(
                field,
                format!(
                    "TEXCOORD_{set} of vertex {k} is {:?}, expected finite values within ±{MAX_FILE_COORDINATE}",
                    uvs[k]
                ),
            ));
        }
        Ok(uvs)
    }
}

/// What an accessor is read as, for [`check_accessor`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Use {
    /// `POSITION`: float VEC3.
    Positions,
    /// Indices: unsigned integer SCALAR.
    Indices,
    /// `TEXCOORD_n`: float, or normalized unsigned byte or short, VEC2.
    TexCoords,
}

/// Checks that an accessor lies inside its buffer view and buffer, is dense, and has the type
/// its use needs ([`Use`]), so that the `gltf` crate's reader cannot run off a slice.
fn check_accessor(
    accessor: &gltf::Accessor<'_>,
    buffers: &[Vec<u8>],
    usage: Use,
) -> Result<(), GltfError> {
    use gltf::accessor::{DataType, Dimensions};
    let field = format!("accessors[{}]", accessor.index());
    if accessor.sparse().is_some() {
        return Err(invalid(field, "sparse accessors are not supported"));
    }
    let ok_type = match usage {
        Use::Positions => {
            accessor.data_type() == DataType::F32 && accessor.dimensions() == Dimensions::Vec3
        }
        Use::Indices => {
            matches!(
                accessor.data_type(),
                DataType::U8 | DataType::U16 | DataType::U32
            ) && accessor.dimensions() == Dimensions::Scalar
        }
        Use::TexCoords => {
            (accessor.data_type() == DataType::F32
                || (matches!(accessor.data_type(), DataType::U8 | DataType::U16)
                    && accessor.normalized()))
                && accessor.dimensions() == Dimensions::Vec2
        }
    };
    if !ok_type {
        return Err(invalid(
            field,
            match usage {
                Use::Positions => "POSITION must be a FLOAT VEC3 accessor",
                Use::Indices => "indices must be an UNSIGNED_BYTE/SHORT/INT SCALAR accessor",
                Use::TexCoords => {
                    "TEXCOORD_n must be a FLOAT or normalized UNSIGNED_BYTE/SHORT VEC2 accessor"
                }
            },
        ));
    }
    let Some(view) = accessor.view() else {
        return Err(invalid(format!("{field}.bufferView"), "is missing"));
    };
    let Some(buffer) = buffers.get(view.buffer().index()) else {
        return Err(invalid(
            format!("bufferViews[{}].buffer", view.index()),
            "names a buffer that was not loaded",
        ));
    };
    let view_end = view.offset().checked_add(view.length());
    if view_end.is_none_or(|end| end > buffer.len()) {
        return Err(invalid(
            format!("bufferViews[{}]", view.index()),
            format!(
                "byteOffset {} + byteLength {} runs past the end of its {}-byte buffer",
                view.offset(),
                view.length(),
                buffer.len()
            ),
        ));
    }
    let element = accessor.size();
    let stride = view.stride().unwrap_or(element);
    if stride < element {
        return Err(invalid(
            format!("bufferViews[{}].byteStride", view.index()),
            format!("is {stride}, smaller than the {element}-byte element"),
        ));
    }
    let count = accessor.count();
    if count == 0 {
        return Err(invalid(format!("{field}.count"), "is 0"));
    }
    if count > MAX_VERTICES.max(MAX_TRIANGLES * 3) {
        return Err(invalid(
            format!("{field}.count"),
            format!("is {count}, over the limit of the scene"),
        ));
    }
    let end = stride
        .checked_mul(count - 1)
        .and_then(|v| v.checked_add(element))
        .and_then(|v| v.checked_add(accessor.offset()));
    if end.is_none_or(|end| end > view.length()) {
        return Err(invalid(
            field,
            format!(
                "{count} elements of {element} bytes (stride {stride}) from byteOffset {} run past the end of its {}-byte buffer view",
                accessor.offset(),
                view.length()
            ),
        ));
    }
    Ok(())
}

/// Reads a buffer URI: a `data:` URI with base64 payload, or a relative path (percent-escapes
/// decoded) that must resolve, after canonicalisation, inside `root`.
fn read_uri(dir: &Path, root: &Path, uri: &str, field: &str) -> Result<Vec<u8>, GltfError> {
    if let Some(rest) = uri.strip_prefix("data:") {
        if rest.len() as u64 > MAX_BUFFER_BYTES * 4 / 3 + 4 {
            return Err(invalid(
                format!("{field}.uri"),
                format!("data URI is larger than the limit of {MAX_BUFFER_BYTES} bytes"),
            ));
        }
        let (_, payload) = rest
            .split_once(";base64,")
            .ok_or_else(|| invalid(format!("{field}.uri"), "data URI is not base64"))?;
        return decode_base64(payload)
            .ok_or_else(|| invalid(format!("{field}.uri"), "invalid base64 in data URI"));
    }
    let path = resolve_inside(dir, root, &percent_decode(uri))
        .map_err(|reason| invalid(format!("{field}.uri"), reason))?;
    read_bounded(&path, MAX_BUFFER_BYTES).map_err(|source| GltfError::Io { path, source })
}

/// `relative` joined to `dir`, canonicalised, and checked to lie inside `root`. Refuses absolute
/// paths, URI schemes and anything that resolves (through `..` or symbolic links) outside.
pub fn resolve_inside(dir: &Path, root: &Path, relative: &str) -> Result<PathBuf, String> {
    let shown = scenethesis_scene_graph::printable(relative);
    if relative.is_empty() {
        return Err("is empty".into());
    }
    if relative.contains('\0') {
        return Err(format!("`{shown}` contains a NUL byte"));
    }
    let rel = Path::new(relative);
    if rel.is_absolute() || relative.starts_with('\\') || relative.contains("://") {
        return Err(
            "is an absolute path or a URL; only relative paths inside the asset folder are allowed"
                .into(),
        );
    }
    let root = root
        .canonicalize()
        .map_err(|e| format!("cannot resolve the folder {}: {e}", root.display()))?;
    let path = dir
        .join(rel)
        .canonicalize()
        .map_err(|e| format!("cannot open `{shown}`: {e}"))?;
    if !path.starts_with(&root) {
        return Err(format!(
            "resolves outside the asset folder {}",
            root.display()
        ));
    }
    Ok(path)
}

/// Decodes `%XX` escapes of a relative URI.
fn percent_decode(uri: &str) -> String {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' && i + 2 < bytes.len() {
            let hex = std::str::from_utf8(&bytes[i + 1..i + 3]).ok();
            if let Some(v) = hex.and_then(|h| u8::from_str_radix(h, 16).ok()) {
                out.push(v);
                i += 3;
                continue;
            }
        }
        out.push(bytes[i]);
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Standard base64 (with or without padding); `None` on a character outside the alphabet.
pub(super) fn decode_base64(text: &str) -> Option<Vec<u8>> {
    let mut out = Vec::with_capacity(text.len() * 3 / 4);
    let (mut acc, mut bits) = (0u32, 0u32);
    for c in text.bytes().filter(|c| !c.is_ascii_whitespace()) {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            b'=' => break,
            _ => return None,
        };
        acc = (acc << 6) | v as u32;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    Some(out)
}

/// Loads a `.glb` or `.gltf` asset file as one mesh (file frame and units): every triangle
/// primitive of every node instance becomes one part, degenerate triangles dropped, materials
/// shared by glTF index. External buffers must lie inside `root`.
/// Also returns the file's [`GltfFile::texture_warnings`].
pub(super) fn load(path: &Path, root: &Path) -> Result<(Mesh, Vec<String>), MeshLoadError> {
    let file = GltfFile::read(path, Some(root)).map_err(|e| MeshLoadError::Gltf(e.to_string()))?;
    let mut mesh = Mesh::default();
    let mut materials: std::collections::BTreeMap<Option<usize>, usize> = Default::default();
    let mut stack: Vec<&GltfNode> = file.roots.iter().rev().collect();
    while let Some(node) = stack.pop() {
        for p in &node.primitives {
            let mut triangles = p.triangles.clone();
            triangles.retain(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
            if triangles.is_empty() {
                continue;
            }
            let material = *materials.entry(p.material).or_insert_with(|| {
                let m = file.material(p.material);
                let name = m.name.clone().unwrap_or_else(|| {
                    p.material
                        .map_or("default".into(), |i| format!("material_{i}"))
                });
                mesh.materials.push(m.to_material(name));
                mesh.materials.len() - 1
            });
            let name = match (&node.name, &p.mesh_name) {
                (Some(n), _) | (None, Some(n)) => format!("{n}_{}", p.index),
                _ => format!("mesh{}_{}", p.mesh, p.index),
            };
            let mut part = MeshPart {
                name,
                material,
                positions: p.positions.clone(),
                triangles,
                joint: None,
                uvs: p.uvs.clone(),
            };
            scenethesis_primitives::compact(&mut part);
            mesh.parts.push(part);
        }
        stack.extend(node.children.iter().rev());
    }
    if mesh.triangle_count() == 0 {
        return Err(MeshLoadError::Empty);
    }
    Ok((mesh, file.texture_warnings))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_and_percent_decoding() {
        assert_eq!(decode_base64("aGVsbG8gd29ybGQ=").unwrap(), b"hello world");
        assert_eq!(decode_base64("AAEC").unwrap(), vec![0, 1, 2]);
        assert!(decode_base64("a*b").is_none());
        assert_eq!(percent_decode("my%20mesh.bin"), "my mesh.bin");
        assert_eq!(percent_decode("plain.bin"), "plain.bin");
    }

    #[test]
    fn paths_outside_the_root_are_refused() {
        let root = tempfile::tempdir().unwrap();
        let pack = root.path().join("pack");
        std::fs::create_dir(&pack).unwrap();
        std::fs::write(root.path().join("secret.bin"), b"secret").unwrap();
        std::fs::write(pack.join("ok.bin"), b"ok").unwrap();
        assert!(resolve_inside(&pack, &pack, "ok.bin").is_ok());
        let err = resolve_inside(&pack, &pack, "../secret.bin").unwrap_err();
        assert!(err.contains("outside the asset folder"), "{err}");
        let abs = root.path().join("secret.bin");
        let err = resolve_inside(&pack, &pack, abs.to_str().unwrap()).unwrap_err();
        assert!(err.contains("absolute path"), "{err}");
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(root.path().join("secret.bin"), pack.join("link.bin"))
                .unwrap();
            assert!(resolve_inside(&pack, &pack, "link.bin").is_err());
        }
    }
}
