//! Wavefront OBJ loading: `v` and `f` records (polygons fan-triangulated, `v/vt/vn` forms,
//! negative indices), one part per object/group and material run, and diffuse colours (`Kd`),
//! shininess (`Ns`) and opacity (`d`) from `mtllib` files when present. A diffuse texture
//! (`map_Kd`) that can be used is kept on its material, and a part of that material whose
//! every face corner names a texture coordinate (`vt`, flipped to glTF's v-down convention)
//! keeps them, its vertices then split where one position has several; a texture that cannot
//! be used is a warning, and its material keeps the plain `Kd` colour.

use std::collections::BTreeMap;
use std::path::Path;

use scenethesis_scene_graph::{printable, Material, Mesh, MeshPart, TextureImage};

use super::limits::{
    MAX_FILE_COORDINATE, MAX_MTL_BYTES, MAX_OBJ_BYTES, MAX_TEXTURE_BYTES, MAX_TRIANGLES,
    MAX_VERTICES,
};
use super::MeshLoadError;

/// Loads an `.obj` file (and the `.mtl` files it names, if they can be read and lie inside
/// `root`; one that does not is ignored with a warning in the log), with one warning per
/// diffuse texture that could not be used.
pub(super) fn load(path: &Path, root: &Path) -> Result<(Mesh, Vec<String>), MeshLoadError> {
    let bytes = scenethesis_scene_graph::read_bounded(path, MAX_OBJ_BYTES)?;
    let text = String::from_utf8_lossy(&bytes);
    let base = path.parent().unwrap_or_else(|| Path::new("."));
    let read_texture = |file: &str| {
        let resolved = super::gltf_file::resolve_inside(base, root, file)?;
        scenethesis_scene_graph::read_bounded(&resolved, MAX_TEXTURE_BYTES)
            .map_err(|e| e.to_string())
    };
    parse_with_textures(&text, Some(&read_texture), |name| {
        let resolved = match super::gltf_file::resolve_inside(base, root, name) {
            Ok(p) => p,
            Err(reason) => {
                tracing::warn!(
                    "{}: ignoring material library: {reason}",
                    scenethesis_scene_graph::printable(&path.display().to_string())
                );
                return None;
            }
        };
        let bytes = scenethesis_scene_graph::read_bounded(&resolved, MAX_MTL_BYTES).ok()?;
        Some(String::from_utf8_lossy(&bytes).into_owned())
    })
}

/// Reads encoded texture files by name.
type TextureReader<'a> = &'a dyn Fn(&str) -> Result<Vec<u8>, String>;

/// The diffuse texture (`file`, from `map_Kd`) of material `material` as a texture image, or
/// the warning that says why it cannot be used (its material then keeps the plain `Kd`
/// colour).
fn read_texture_of(
    read: TextureReader<'_>,
    material: &str,
    file: &str,
) -> Result<TextureImage, String> {
    read(file)
        .and_then(|bytes| super::textures::texture_image(&bytes))
        .map_err(|reason| {
            format!(
                "material `{}`: diffuse texture `{}` (map_Kd) cannot be used ({reason}); using \
                 the plain Kd colour",
                printable(material),
                printable(file)
            )
        })
}

/// Parses OBJ text; `read_mtl` returns the text of a material library by its file name.
/// Diffuse textures are not read.
pub(super) fn parse(
    text: &str,
    read_mtl: impl Fn(&str) -> Option<String>,
) -> Result<Mesh, MeshLoadError> {
    parse_with_textures(text, None, read_mtl).map(|(mesh, _)| mesh)
}

/// [`parse`], also reading the diffuse texture (`map_Kd`) of every material a part uses with
/// `read_texture` (when given): the warnings say which could not be used.
fn parse_with_textures(
    text: &str,
    read_texture: Option<TextureReader<'_>>,
    read_mtl: impl Fn(&str) -> Option<String>,
) -> Result<(Mesh, Vec<String>), MeshLoadError> {
    let mut records = Records::default();
    let mut parts = Parts {
        read_texture,
        ..Parts::default()
    };
    let mut group = String::from("mesh");
    let mut current_material = String::new();
    let mut triangles = 0usize;

    for (n, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("").trim();
        let mut fields = line.split_whitespace();
        let Some(tag) = fields.next() else { continue };
        let err = |message: String| MeshLoadError::Obj {
            line: n + 1,
            message,
        };
        match tag {
            "v" => {
                let mut p = [0.0f32; 3];
                for c in &mut p {
                    let f = fields
                        .next()
                        .ok_or_else(|| err("vertex needs three coordinates".into()))?;
                    *c = f.parse().map_err(|_| {
                        err(format!(
                            "bad coordinate `{}`",
                            scenethesis_scene_graph::printable(f)
                        ))
                    })?;
                    if !c.is_finite() || c.abs() > MAX_FILE_COORDINATE as f32 {
                        return Err(err(format!(
                            "coordinate `{f}` is not a finite number within ±{MAX_FILE_COORDINATE}"
                        )));
                    }
                }
                if records.vertices.len() >= MAX_VERTICES {
                    return Err(err(format!(
                        "more than the limit of {MAX_VERTICES} vertices"
                    )));
                }
                records.vertices.push(p);
            }
            "vt" => {
                // A texture coordinate that cannot be read leaves the faces naming it without
                // texture coordinates (and their part plain), as before they were read.
                let mut uv = [0.0f32; 2];
                let mut ok = true;
                for c in &mut uv {
                    match fields.next().and_then(|f| f.parse::<f32>().ok()) {
                        Some(v) if v.is_finite() && v.abs() <= MAX_FILE_COORDINATE as f32 => *c = v,
                        _ => ok = false,
                    }
                }
                if records.texcoords.len() < MAX_VERTICES {
                    records.texcoords.push(ok.then_some([uv[0], 1.0 - uv[1]]));
                }
            }
            "f" => {
                let mut face = Vec::new();
                for token in fields {
                    let mut indices = token.split('/');
                    let first = indices.next().unwrap_or("");
                    let texcoord =
                        indices
                            .next()
                            .and_then(|t| t.parse::<i64>().ok())
                            .and_then(|i| {
                                let count = records.texcoords.len() as i64;
                                let resolved = if i > 0 { i - 1 } else { count + i };
                                (i != 0 && (0..count).contains(&resolved))
                                    .then_some(resolved as u32)
                                    .filter(|&r| records.texcoords[r as usize].is_some())
                            });
                    let i: i64 = first.parse().map_err(|_| {
                        err(format!(
                            "bad face index `{}`",
                            scenethesis_scene_graph::printable(token)
                        ))
                    })?;
                    let count = records.vertices.len() as i64;
                    let resolved = if i > 0 { i - 1 } else { count + i };
                    if i == 0 || resolved < 0 || resolved >= count {
                        return Err(err(format!(
                            "face index {i} out of range ({count} vertices so far)"
                        )));
                    }
                    face.push((resolved as u32, texcoord));
                }
                if face.len() < 3 {
                    return Err(err("a face needs at least three vertices".into()));
                }
                triangles += face.len() - 2;
                if triangles > MAX_TRIANGLES {
                    return Err(err(format!(
                        "more than the limit of {MAX_TRIANGLES} triangles"
                    )));
                }
                for k in 1..face.len() - 1 {
                    let t = [face[0], face[k], face[k + 1]];
                    if t[0].0 != t[1].0 && t[1].0 != t[2].0 && t[0].0 != t[2].0 {
                        parts.pending.push(t);
                    }
                }
            }
            "o" | "g" => {
                parts.flush(&records, &group, &current_material);
                group = fields.collect::<Vec<_>>().join("_");
                if group.is_empty() {
                    group = "mesh".into();
                }
            }
            "usemtl" => {
                parts.flush(&records, &group, &current_material);
                current_material = fields.collect::<Vec<_>>().join(" ");
            }
            "mtllib" => {
                let name = line["mtllib".len()..].trim();
                if let Some(text) = read_mtl(name) {
                    parse_mtl(&text, &mut records.library, &mut records.textures);
                }
            }
            _ => {} // vn, s, l, p and the rest carry nothing we keep.
        }
    }
    parts.flush(&records, &group, &current_material);
    if parts.mesh.triangle_count() == 0 {
        return Err(MeshLoadError::Empty);
    }
    Ok((parts.mesh, parts.warnings))
}

/// What the OBJ text has declared so far that parts refer to: vertex positions, texture
/// coordinates (`None` for one that could not be read), the materials of its libraries and the
/// diffuse texture file (`map_Kd`) each names.
#[derive(Default)]
struct Records {
    vertices: Vec<[f32; 3]>,
    texcoords: Vec<Option<[f32; 2]>>,
    library: BTreeMap<String, Material>,
    textures: BTreeMap<String, String>,
}

/// A face corner: its vertex and, when it names a readable one, its texture coordinate.
type Corner = (u32, Option<u32>);

/// The mesh being read: finished parts, the triangles of the part being filled and the index of
/// every material used so far.
#[derive(Default)]
struct Parts<'a> {
    mesh: Mesh,
    /// Global-index triangles of the part being filled.
    pending: Vec<[Corner; 3]>,
    material_index: BTreeMap<String, usize>,
    /// Reads the diffuse textures of the materials used (none read without it).
    read_texture: Option<TextureReader<'a>>,
    /// One line per diffuse texture that could not be used.
    warnings: Vec<String>,
}

impl Parts<'_> {
    /// Closes the part being filled (if it has triangles) as object/group `group` with
    /// `material` (looked up in `records`' library, a grey default when missing; on its first
    /// use its diffuse texture is read), keeping only the vertices it uses: by position, or by
    /// position and texture coordinate when the material has a texture and every corner of the
    /// part names a texture coordinate.
    fn flush(&mut self, records: &Records, group: &str, material: &str) {
        let Records {
            vertices,
            texcoords,
            library,
            textures,
        } = records;
        if self.pending.is_empty() {
            return;
        }
        let mesh = &mut self.mesh;
        let (read_texture, warnings) = (self.read_texture, &mut self.warnings);
        let m = *self
            .material_index
            .entry(material.to_owned())
            .or_insert_with(|| {
                let mut mat = library.get(material).cloned().unwrap_or_else(|| {
                    Material::new(
                        if material.is_empty() {
                            "default"
                        } else {
                            material
                        },
                        [0.7, 0.7, 0.7],
                        0.7,
                    )
                });
                if let (Some(read), Some(file)) = (read_texture, textures.get(material)) {
                    match read_texture_of(read, &mat.name, file) {
                        Ok(texture) => mat.texture = Some(texture),
                        Err(warning) => warnings.push(warning),
                    }
                }
                mesh.materials.push(mat);
                mesh.materials.len() - 1
            });
        let textured = mesh.materials[m].texture.is_some()
            && self.pending.iter().flatten().all(|(_, t)| t.is_some());
        let mut local: std::collections::HashMap<Corner, u32> = std::collections::HashMap::new();
        let mut positions = Vec::new();
        let mut uvs = Vec::new();
        let triangles = std::mem::take(&mut self.pending)
            .into_iter()
            .map(|t| {
                t.map(|(i, texcoord)| {
                    let key = (i, if textured { texcoord } else { None });
                    *local.entry(key).or_insert_with(|| {
                        positions.push(vertices[i as usize]);
                        if let Some(uv) = key.1.and_then(|k| texcoords[k as usize]) {
                            uvs.push(uv);
                        }
                        positions.len() as u32 - 1
                    })
                })
            })
            .collect();
        let part = MeshPart {
            name: if material.is_empty() {
                group.to_owned()
            } else {
                format!("{group}_{material}")
            },
            material: m,
            positions,
            triangles,
            joint: None,
            uvs: textured.then_some(uvs),
        };
        mesh.parts.push(part);
    }
}

/// Reads `newmtl` blocks: `Kd` (diffuse colour), `Ns` (shininess → roughness), `d`/`Tr`
/// (opacity), `Pm` (metalness, PBR extension) and `map_Kd` (the diffuse texture's file, its
/// last field after any options, into `textures`).
fn parse_mtl(
    text: &str,
    library: &mut BTreeMap<String, Material>,
    textures: &mut BTreeMap<String, String>,
) {
    let mut current: Option<String> = None;
    for raw in text.lines() {
        let line = raw.split('#').next().unwrap_or("").trim();
        let mut fields = line.split_whitespace();
        let Some(tag) = fields.next() else { continue };
        let nums: Vec<f32> = fields.clone().filter_map(|f| f.parse().ok()).collect();
        if tag == "newmtl" {
            let name = fields.collect::<Vec<_>>().join(" ");
            library.insert(
                name.clone(),
                Material::new(name.clone(), [0.7, 0.7, 0.7], 0.7),
            );
            current = Some(name);
            continue;
        }
        let Some(m) = current.as_ref().and_then(|n| library.get_mut(n)) else {
            continue;
        };
        if tag == "map_Kd" {
            if let Some(file) = fields.last() {
                textures.insert(m.name.clone(), file.to_owned());
            }
            continue;
        }
        match (tag, nums.as_slice()) {
            ("Kd", [r, g, b, ..]) => {
                m.base_color[..3].copy_from_slice(&[*r, *g, *b].map(|c| c.clamp(0.0, 1.0)))
            }
            ("Ns", [ns, ..]) => m.roughness = (2.0 / (ns.max(0.0) + 2.0)).sqrt().clamp(0.0, 1.0),
            ("d", [d, ..]) => m.base_color[3] = d.clamp(0.0, 1.0),
            ("Tr", [t, ..]) => m.base_color[3] = (1.0 - t).clamp(0.0, 1.0),
            ("Pr", [r, ..]) => m.roughness = r.clamp(0.0, 1.0),
            ("Pm", [p, ..]) => m.metallic = p.clamp(0.0, 1.0),
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quads_negative_indices_groups_and_materials() {
        let obj = "mtllib box.mtl\n\
                   o cube\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
                   usemtl red\nf -4 -1 -2 -3\n\
                   usemtl blue\nf 1/1/1 2/2/2 3/3/3\n";
        let mtl = "newmtl red\nKd 0.9 0.1 0.1\nNs 48\nnewmtl blue\nKd 0.1 0.1 0.9\nd 0.5\n";
        let mesh = parse(obj, |name| (name == "box.mtl").then(|| mtl.to_string())).unwrap();
        assert_eq!(mesh.parts.len(), 2);
        assert_eq!(
            mesh.parts[0].triangles.len(),
            2,
            "a quad becomes two triangles"
        );
        assert_eq!(mesh.parts[0].name, "cube_red");
        let red = &mesh.materials[mesh.parts[0].material];
        assert_eq!(red.base_color, [0.9, 0.1, 0.1, 1.0]);
        assert!((red.roughness - 0.2).abs() < 1e-6);
        assert_eq!(mesh.materials[mesh.parts[1].material].base_color[3], 0.5);
        // The negative indices −4 −1 −2 −3 are vertices 0 3 2 1.
        let p = &mesh.parts[0];
        let first: Vec<[f32; 3]> = p.triangles[0]
            .iter()
            .map(|&i| p.positions[i as usize])
            .collect();
        assert_eq!(
            first,
            vec![[0.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]]
        );
    }

    #[test]
    fn malformed_lines_name_the_line() {
        let e = parse("v 0 0 0\nv 1 0 0\nf 1 2 7\n", |_| None).unwrap_err();
        assert!(matches!(e, MeshLoadError::Obj { line: 3, .. }), "{e}");
        let e = parse("v 0 zero 0\n", |_| None).unwrap_err();
        assert!(e.to_string().contains("line 1"), "{e}");
        assert!(matches!(
            parse("v 0 0 0\n", |_| None),
            Err(MeshLoadError::Empty)
        ));
    }
}
