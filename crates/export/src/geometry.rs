//! Geometry shared by the writers: vertex normals with a crease angle, mass properties of
//! closed meshes, frame conversion to Z-up and identifier sanitising.

use std::borrow::Cow;
use std::collections::{BTreeSet, HashMap};

use nalgebra::{Matrix3, UnitQuaternion, Vector3};
use scenethesis_materials::{BoxProjection, LibraryMaterial};
use scenethesis_scene_graph::{Material, Mesh, MeshPart, TextureImage};

/// Faces meeting at less than this angle share smooth vertex normals (a cylinder's side);
/// sharper edges (a box's corners) keep one normal per face.
const CREASE_ANGLE_DEG: f32 = 40.0;

/// A part ready for a renderer: vertices split wherever faces meet at a crease, with one
/// normal per vertex; when the part wears a library material, also split wherever faces are
/// projected along different axes, with texture coordinates in tiles of that material and
/// glTF tangents ([`scenethesis_materials::BoxProjection`], in the part's own frame); when it
/// shows its material's image, with the part's own texture coordinates (no tangents).
pub(crate) struct ShadedPart {
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    pub indices: Vec<u32>,
    /// Texture coordinates per vertex (empty without a library material or an image).
    pub uvs: Vec<[f32; 2]>,
    /// Tangents per vertex, `w` the bitangent's sign (empty without a library material).
    pub tangents: Vec<[f32; 4]>,
}

/// The library material a scene material wears, found by its name; `None` for a material
/// with an image of its own (an imported texture), which is shown instead.
pub(crate) fn library_of(material: &Material) -> Option<&'static LibraryMaterial> {
    if material.texture.is_some() {
        return None;
    }
    scenethesis_materials::resolve(&material.name)
}

/// The material `part` is written with: `material` itself when the part can show its image
/// (it has a texture coordinate per vertex) or it has none; else `material` without its image,
/// in its flat colour ([`Material::without_image`]), as imported textures were written before
/// parts kept their texture coordinates.
pub(crate) fn worn<'a>(part: &MeshPart, material: &'a Material) -> Cow<'a, Material> {
    if material.texture.is_none() || part.textured_uvs(material).is_some() {
        return Cow::Borrowed(material);
    }
    Cow::Owned(material.without_image())
}

/// A key equal for two materials exactly when the writers may share one material between
/// them: the same name, every factor bit for bit and the same image.
pub(crate) fn material_key(m: &Material) -> String {
    let mut key = format!(
        "{}|{:?}|{}|{}",
        m.name,
        m.base_color.map(f32::to_bits),
        m.roughness.to_bits(),
        m.metallic.to_bits()
    );
    if let Some(image) = &m.texture {
        key.push_str(&format!("|{}", image.digest_hex()));
    }
    key
}

/// The file name of an imported image beside the text formats: `image_<digest>.png`.
pub(crate) fn image_file_name(image: &TextureImage) -> String {
    format!("image_{}.png", image.digest_hex())
}

/// How a part's surface maps to images, for [`shade`].
#[derive(Clone, Copy)]
pub(crate) enum Mapping<'a> {
    /// No image: plain colour.
    Plain,
    /// A library material's maps, box-projected in tiles of the material.
    Library(&'a LibraryMaterial),
    /// The material's own image, at the part's texture coordinates (one per vertex).
    Image(&'a [[f32; 2]]),
}

impl<'a> Mapping<'a> {
    /// The mapping of `part` wearing `material` (as [`worn`] gives it).
    pub fn of(part: &'a MeshPart, material: &'a Material) -> Self {
        if let Some((uvs, _)) = part.textured_uvs(material) {
            return Mapping::Image(uvs);
        }
        library_of(material).map_or(Mapping::Plain, Mapping::Library)
    }
}

impl<'a> From<Option<&'a LibraryMaterial>> for Mapping<'a> {
    fn from(library: Option<&'a LibraryMaterial>) -> Self {
        library.map_or(Mapping::Plain, Mapping::Library)
    }
}

pub(crate) fn shade<'a>(part: &MeshPart, mapping: impl Into<Mapping<'a>>) -> ShadedPart {
    let mapping = mapping.into();
    let texture = match mapping {
        Mapping::Library(library) => Some(library),
        _ => None,
    };
    let own_uvs = match mapping {
        Mapping::Image(uvs) => Some(uvs),
        _ => None,
    };
    let face_normals: Vec<Vector3<f32>> = part
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = part.triangle_points(t);
            (b - a).cross(&(c - a))
        })
        .collect();
    let mut faces_at: Vec<Vec<usize>> = vec![Vec::new(); part.positions.len()];
    for (f, t) in part.triangles.iter().enumerate() {
        for &i in t {
            faces_at[i as usize].push(f);
        }
    }
    let projection = texture.map(|m| BoxProjection::new(m.tile_size_m, &part.positions));
    let cos_crease = CREASE_ANGLE_DEG.to_radians().cos();
    let unit = |v: &Vector3<f32>| v.try_normalize(1e-20).unwrap_or_else(Vector3::zeros);
    let mut out = ShadedPart {
        positions: Vec::with_capacity(part.positions.len()),
        normals: Vec::with_capacity(part.positions.len()),
        indices: Vec::with_capacity(part.triangles.len() * 3),
        uvs: Vec::new(),
        tangents: Vec::new(),
    };
    // A split vertex is identified by its source vertex, the set of faces it averages and the
    // axis its face is projected along; output order follows the triangles, so the map's
    // iteration order never matters.
    let mut seen: HashMap<(u32, Vec<usize>, usize), u32> = HashMap::new();
    for (f, t) in part.triangles.iter().enumerate() {
        let nf = unit(&face_normals[f]);
        let face = projection.map(|p| p.face([nf.x, nf.y, nf.z]));
        for &i in t {
            let group: Vec<usize> = faces_at[i as usize]
                .iter()
                .copied()
                .filter(|&g| unit(&face_normals[g]).dot(&nf) >= cos_crease)
                .collect();
            let axis = face.map_or(0, |f| f.axis);
            let index = *seen.entry((i, group.clone(), axis)).or_insert_with(|| {
                // Area-weighted average (the raw cross products carry twice the area).
                let sum: Vector3<f32> = group.iter().map(|&g| face_normals[g]).sum();
                let n = sum.try_normalize(1e-20).unwrap_or(nf);
                let p = part.positions[i as usize];
                out.positions.push(p);
                out.normals.push([n.x, n.y, n.z]);
                if let Some(face) = face {
                    out.uvs.push(face.uv(p));
                    out.tangents.push(face.tangent([n.x, n.y, n.z]));
                } else if let Some(uvs) = own_uvs {
                    out.uvs.push(uvs[i as usize]);
                }
                out.positions.len() as u32 - 1
            });
            out.indices.push(index);
        }
    }
    out
}

trait TrianglePoints {
    fn triangle_points(&self, t: &[u32; 3]) -> [Vector3<f32>; 3];
}

impl TrianglePoints for MeshPart {
    fn triangle_points(&self, t: &[u32; 3]) -> [Vector3<f32>; 3] {
        t.map(|i| Vector3::from(self.positions[i as usize]))
    }
}

/// Mass, centre of mass and inertia of a solid of uniform density bounded by closed,
/// outward-oriented parts (summed part by part, so overlapping parts count twice).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// Mass in kilograms.
    pub mass: f64,
    /// Centre of mass in the frame of the vertices.
    pub center_of_mass: Vector3<f64>,
    /// Inertia tensor about the centre of mass, axes of the frame of the vertices, kg·m².
    pub inertia: Matrix3<f64>,
}

impl MassProperties {
    /// Mass properties of `mesh` scaled uniformly by `scale`, at `density` kg/m³. Parts with a
    /// non-positive volume (open or inward-facing) are skipped; `None` when nothing remains.
    pub fn of_mesh(mesh: &Mesh, scale: f64, density: f64) -> Option<MassProperties> {
        // Integrate over signed tetrahedra (origin, a, b, c) with the divergence theorem.
        let mut volume = 0.0;
        let mut first = Vector3::zeros();
        let mut second = Matrix3::zeros();
        for part in &mesh.parts {
            let (mut v, mut m1, mut m2) = (0.0, Vector3::zeros(), Matrix3::zeros());
            for t in &part.triangles {
                let [a, b, c] =
                    t.map(|i| Vector3::from(part.positions[i as usize]).cast::<f64>() * scale);
                let tv = a.dot(&b.cross(&c)) / 6.0;
                let s = a + b + c;
                v += tv;
                m1 += tv * s / 4.0;
                m2 += tv / 20.0
                    * (a * a.transpose()
                        + b * b.transpose()
                        + c * c.transpose()
                        + s * s.transpose());
            }
            if v > 0.0 {
                volume += v;
                first += m1;
                second += m2;
            }
        }
        if volume <= 0.0 {
            return None;
        }
        let mass = density * volume;
        let com = first / volume;
        let covariance = density * second - mass * com * com.transpose();
        let inertia = Matrix3::identity() * covariance.trace() - covariance;
        Some(MassProperties {
            mass,
            center_of_mass: com,
            inertia,
        })
    }
}

/// The rotation taking the scene's +Y-up frame to a +Z-up frame (MuJoCo, ROS): +90° about +X,
/// so `(x, y, z)` becomes `(x, −z, y)`.
pub(crate) fn y_up_to_z_up() -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::FRAC_PI_2)
}

/// A +Y-up point or vector in +Z-up coordinates.
pub(crate) fn to_z_up(v: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(v.x, -v.z, v.y)
}

/// Names made safe for formats with identifier rules (letters, digits, `_` and, when
/// `allow_dash`, `-`; not starting with a digit), kept unique by numeric suffixes, in the order
/// the ids are given.
pub(crate) struct Identifiers {
    used: BTreeSet<String>,
    allow_dash: bool,
    /// The longest name made, in bytes (names are ASCII), suffix included.
    max_len: usize,
}

/// The longest file name [`Identifiers::file_names`] makes, before an extension: far under the
/// 255-byte limit of common file systems, whatever the length of the id it comes from.
pub(crate) const MAX_FILE_STEM: usize = 120;

impl Identifiers {
    pub fn new(allow_dash: bool) -> Self {
        Self {
            used: BTreeSet::new(),
            allow_dash,
            max_len: usize::MAX,
        }
    }

    /// Names for files: letters, digits, `_` and `-`, at most [`MAX_FILE_STEM`] bytes, unique.
    pub fn file_names() -> Self {
        Self {
            max_len: MAX_FILE_STEM,
            ..Self::new(true)
        }
    }

    /// Reserves a name without sanitising it.
    pub fn reserve(&mut self, name: &str) {
        self.used.insert(name.to_owned());
    }

    /// A fresh identifier derived from `raw`.
    pub fn make(&mut self, raw: &str) -> String {
        let mut base: String = raw
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '_' || (self.allow_dash && c == '-') {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        if base.is_empty() || base.starts_with(|c: char| c.is_ascii_digit()) {
            base.insert(0, '_');
        }
        // Room for a `_k` suffix; every character is ASCII, so any byte is a boundary.
        base.truncate(self.max_len.saturating_sub(12).max(1));
        let mut name = base.clone();
        let mut k = 1;
        while self.used.contains(&name) {
            name = format!("{base}_{k}");
            k += 1;
        }
        self.used.insert(name.clone());
        name
    }
}

/// Formats a float for text formats: shortest round-trip representation, `-0` as `0`.
pub(crate) fn num(v: f64) -> String {
    if v == 0.0 {
        "0".to_owned()
    } else {
        format!("{v}")
    }
}

/// Formats an `f32` for text formats, as [`num`].
pub(crate) fn num32(v: f32) -> String {
    if v == 0.0 {
        "0".to_owned()
    } else {
        format!("{v}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use scenethesis_scene_graph::Material;

    fn cube(size: f32) -> MeshPart {
        MeshPart::cuboid("cube", 0, [0.0; 3], [size; 3])
    }

    #[test]
    fn cube_gets_flat_normals_pointing_out() {
        let shaded = shade(&cube(1.0), None);
        // 6 faces × 4 corners: every corner is a crease.
        assert_eq!(shaded.positions.len(), 24);
        assert_eq!(shaded.indices.len(), 36);
        for tri in shaded.indices.chunks(3) {
            let p: Vec<Vector3<f32>> = tri
                .iter()
                .map(|&i| Vector3::from(shaded.positions[i as usize]))
                .collect();
            let centre = (p[0] + p[1] + p[2]) / 3.0 - Vector3::repeat(0.5);
            for &i in tri {
                let n = Vector3::from(shaded.normals[i as usize]);
                assert!((n.norm() - 1.0).abs() < 1e-5);
                assert!(n.dot(&centre) > 0.0, "normal points inward");
            }
        }
    }

    #[test]
    fn cube_mass_properties_match_closed_form() {
        let mesh = Mesh {
            parts: vec![cube(1.0)],
            materials: vec![Material::new("m", [1.0; 3], 0.5)],
        };
        let props = MassProperties::of_mesh(&mesh, 2.0, 1000.0).unwrap();
        assert!((props.mass - 8000.0).abs() < 1e-6);
        assert!((props.center_of_mass - Vector3::repeat(1.0)).norm() < 1e-9);
        // Solid cube of side 2: I = m (s² + s²) / 12 on the diagonal.
        let expected = 8000.0 * 8.0 / 12.0;
        for i in 0..3 {
            assert!((props.inertia[(i, i)] - expected).abs() < 1e-6);
            for j in 0..3 {
                if i != j {
                    assert!(props.inertia[(i, j)].abs() < 1e-6);
                }
            }
        }
    }

    #[test]
    fn identifiers_are_valid_and_unique() {
        let mut ids = Identifiers::new(false);
        assert_eq!(ids.make("chair_0"), "chair_0");
        assert_eq!(ids.make("chair 0"), "chair_0_1");
        assert_eq!(ids.make("3d-print"), "_3d_print");
        assert_eq!(ids.make(""), "_");
        let mut dashed = Identifiers::new(true);
        assert_eq!(dashed.make("a-b"), "a-b");
    }

    #[test]
    fn file_names_are_bounded_and_unique_for_long_ids() {
        let long = "x".repeat(256);
        let mut files = Identifiers::file_names();
        let names: Vec<String> = (0..12).map(|_| files.make(&long)).collect();
        assert!(names.iter().all(|n| n.len() <= MAX_FILE_STEM), "{names:?}");
        let unique: BTreeSet<&String> = names.iter().collect();
        assert_eq!(unique.len(), names.len());
        assert_eq!(files.make("short"), "short");
    }

    #[test]
    fn z_up_conversion_matches_the_rotation() {
        let v = Vector3::new(0.3, 1.2, -0.7);
        assert!((y_up_to_z_up() * v - to_z_up(&v)).norm() < 1e-12);
    }
}
