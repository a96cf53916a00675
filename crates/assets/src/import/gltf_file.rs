//! glTF 2.0 loading (binary `.glb`, and `.gltf` with external or embedded buffers): every
//! triangle primitive of every node in the default scene becomes one part, in scene space (node
//! transforms applied), with its material's base colour, roughness and metalness.

use std::collections::BTreeMap;
use std::path::Path;

use gltf::mesh::Mode;
use nalgebra::{Matrix4, Point3};
use scenethesis_scene_graph::{Material, Mesh, MeshPart};

use super::MeshLoadError;

/// Loads a `.glb` or `.gltf` file.
pub(super) fn load(path: &Path) -> Result<Mesh, MeshLoadError> {
    let bytes = std::fs::read(path)?;
    let gltf = gltf::Gltf::from_slice(&bytes).map_err(|e| MeshLoadError::Gltf(e.to_string()))?;
    let base = path.parent().unwrap_or_else(|| Path::new("."));
    let mut buffers = Vec::new();
    for buffer in gltf.buffers() {
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => gltf.blob.clone().ok_or_else(|| {
                MeshLoadError::Gltf("buffer refers to a missing GLB binary chunk".into())
            })?,
            gltf::buffer::Source::Uri(uri) => read_uri(base, uri)?,
        };
        if data.len() < buffer.length() {
            return Err(MeshLoadError::Gltf(format!(
                "buffer {} holds {} bytes, expected {}",
                buffer.index(),
                data.len(),
                buffer.length()
            )));
        }
        buffers.push(data);
    }
    let mut loader = Loader {
        buffers: &buffers,
        mesh: Mesh::default(),
        materials: BTreeMap::new(),
    };
    let scene = gltf.default_scene().or_else(|| gltf.scenes().next());
    match scene {
        Some(scene) => {
            for node in scene.nodes() {
                loader.node(&node, &Matrix4::identity())?;
            }
        }
        None => {
            // No scene: take every node that is nobody's child.
            let children: std::collections::BTreeSet<usize> = gltf
                .nodes()
                .flat_map(|n| n.children().map(|c| c.index()).collect::<Vec<_>>())
                .collect();
            for node in gltf.nodes().filter(|n| !children.contains(&n.index())) {
                loader.node(&node, &Matrix4::identity())?;
            }
        }
    }
    if loader.mesh.triangle_count() == 0 {
        return Err(MeshLoadError::Empty);
    }
    Ok(loader.mesh)
}

struct Loader<'a> {
    buffers: &'a [Vec<u8>],
    mesh: Mesh,
    /// glTF material index (None = default material) → index in `mesh.materials`.
    materials: BTreeMap<Option<usize>, usize>,
}

impl Loader<'_> {
    fn node(&mut self, node: &gltf::Node<'_>, parent: &Matrix4<f32>) -> Result<(), MeshLoadError> {
        let local = Matrix4::from(node.transform().matrix());
        let world = parent * local;
        if let Some(mesh) = node.mesh() {
            let mirrored = world.fixed_view::<3, 3>(0, 0).determinant() < 0.0;
            for primitive in mesh.primitives() {
                self.primitive(node, &mesh, &primitive, &world, mirrored)?;
            }
        }
        for child in node.children() {
            self.node(&child, &world)?;
        }
        Ok(())
    }

    fn primitive(
        &mut self,
        node: &gltf::Node<'_>,
        mesh: &gltf::Mesh<'_>,
        primitive: &gltf::Primitive<'_>,
        world: &Matrix4<f32>,
        mirrored: bool,
    ) -> Result<(), MeshLoadError> {
        let mode = primitive.mode();
        if !matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            return Ok(()); // Points and lines carry no surface.
        }
        let reader = primitive.reader(|b| self.buffers.get(b.index()).map(|d| d.as_slice()));
        let positions: Vec<[f32; 3]> = reader
            .read_positions()
            .ok_or_else(|| {
                MeshLoadError::Gltf(format!(
                    "mesh {} primitive {} has no POSITION",
                    mesh.index(),
                    primitive.index()
                ))
            })?
            .map(|p| {
                let q = world.transform_point(&Point3::from(p));
                [q.x, q.y, q.z]
            })
            .collect();
        let indices: Vec<u32> = match reader.read_indices() {
            Some(i) => i.into_u32().collect(),
            None => (0..positions.len() as u32).collect(),
        };
        if let Some(&bad) = indices.iter().find(|&&i| i as usize >= positions.len()) {
            return Err(MeshLoadError::Gltf(format!(
                "mesh {} primitive {}: index {bad} out of range ({} vertices)",
                mesh.index(),
                primitive.index(),
                positions.len()
            )));
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
        triangles.retain(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
        if mirrored {
            for t in &mut triangles {
                t.swap(1, 2);
            }
        }
        if triangles.is_empty() {
            return Ok(());
        }
        let material = self.material(&primitive.material());
        let name = match (node.name(), mesh.name()) {
            (Some(n), _) | (None, Some(n)) => format!("{n}_{}", primitive.index()),
            _ => format!("mesh{}_{}", mesh.index(), primitive.index()),
        };
        let mut part = MeshPart {
            name,
            material,
            positions,
            triangles,
        };
        crate::primitives::compact(&mut part);
        self.mesh.parts.push(part);
        Ok(())
    }

    fn material(&mut self, material: &gltf::Material<'_>) -> usize {
        let key = material.index();
        if let Some(&i) = self.materials.get(&key) {
            return i;
        }
        let pbr = material.pbr_metallic_roughness();
        let name = material
            .name()
            .map(str::to_owned)
            .unwrap_or_else(|| key.map_or("default".into(), |i| format!("material_{i}")));
        self.mesh.materials.push(Material {
            name,
            base_color: pbr.base_color_factor(),
            roughness: pbr.roughness_factor(),
            metallic: pbr.metallic_factor(),
        });
        let i = self.mesh.materials.len() - 1;
        self.materials.insert(key, i);
        i
    }
}

/// Reads a buffer URI: a `data:` URI with base64 payload or a path relative to the glTF file.
fn read_uri(base: &Path, uri: &str) -> Result<Vec<u8>, MeshLoadError> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, payload) = rest
            .split_once(";base64,")
            .ok_or_else(|| MeshLoadError::Gltf("data URI is not base64".into()))?;
        return decode_base64(payload)
            .ok_or_else(|| MeshLoadError::Gltf("invalid base64 in data URI".into()));
    }
    let path = base.join(percent_decode(uri));
    std::fs::read(&path)
        .map_err(|e| MeshLoadError::Gltf(format!("cannot read buffer {}: {e}", path.display())))
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
}
