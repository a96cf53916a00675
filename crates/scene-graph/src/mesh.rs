use std::collections::HashMap;

use nalgebra::{Point3, Vector3};
use serde::{Deserialize, Serialize};

use crate::{Aabb, Pose, TextureImage};

/// A surface material: linear-space base colour and roughness (metallic-roughness PBR model,
/// as in glTF).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// Human-readable name, e.g. `oak` or `fabric_grey`.
    pub name: String,
    /// Linear RGBA base colour, each channel in [0, 1].
    pub base_color: [f32; 4],
    /// Perceptual roughness in [0, 1].
    pub roughness: f32,
    /// Metalness in [0, 1].
    pub metallic: f32,
    /// The base-colour image `base_color` multiplies, sampled at the texture coordinates of
    /// the parts wearing the material ([`MeshPart::uvs`]): an imported asset's texture. `None`
    /// for a plain colour and for the library's materials, which the exporters and the
    /// renderer project in metres instead.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub texture: Option<TextureImage>,
}

impl Material {
    /// An opaque dielectric material.
    pub fn new(name: impl Into<String>, rgb: [f32; 3], roughness: f32) -> Self {
        Self {
            name: name.into(),
            base_color: [rgb[0], rgb[1], rgb[2], 1.0],
            roughness,
            metallic: 0.0,
            texture: None,
        }
    }

    /// Whether the material is see-through (glass): its opacity, `base_color`'s alpha, is
    /// below 0.999. The renderer draws such surfaces over the opaque ones and leaves their
    /// depth and instance to what lies behind, as depth sensors see through glass.
    ///
    /// ```
    /// use scenethesis_scene_graph::Material;
    ///
    /// let mut pane = Material::new("glass", [0.9, 0.95, 0.95], 0.05);
    /// assert!(!pane.is_see_through());
    /// pane.base_color[3] = 0.2;
    /// assert!(pane.is_see_through());
    /// ```
    pub fn is_see_through(&self) -> bool {
        self.base_color[3] < 0.999
    }

    /// The colour the material shows as one colour (what formats without its image write, and
    /// what a scene records it wears): `base_color`, its RGB multiplied by the image's mean
    /// colour when it has an image.
    pub fn flat_color(&self) -> [f32; 4] {
        let [r, g, b, a] = self.base_color;
        match &self.texture {
            Some(t) => {
                let m = t.mean_color();
                [r * m[0], g * m[1], b * m[2], a]
            }
            None => [r, g, b, a],
        }
    }

    /// The material without its image, in its [`Material::flat_color`]: what a part that
    /// cannot show the image (it has no texture coordinates) wears.
    ///
    /// ```
    /// use scenethesis_scene_graph::Material;
    ///
    /// let red = Material::new("red", [0.8, 0.1, 0.1], 0.5);
    /// assert_eq!(red.without_image(), red);
    /// ```
    pub fn without_image(&self) -> Material {
        Material {
            base_color: self.flat_color(),
            texture: None,
            ..self.clone()
        }
    }
}

/// One part of a mesh: an indexed triangle list with one material. Parts of procedural assets
/// are closed and consistently oriented (counter-clockwise seen from outside), and parts may
/// overlap one another (a table top and its legs).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct MeshPart {
    /// Name of the part, e.g. `leg_0`.
    pub name: String,
    /// Index into [`Mesh::materials`].
    pub material: usize,
    /// Vertex positions in the asset's frame, metres.
    pub positions: Vec<[f32; 3]>,
    /// Triangles as vertex indices, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// The joint whose moving link carries this part (a door leaf, a drawer box, its handle),
    /// as drawn closed; `None` for the asset's fixed body. See [`Joint`](crate::Joint).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub joint: Option<String>,
    /// Texture coordinates, one per vertex of `positions`, in images (1 = the image's width or
    /// height; the image repeats beyond) with glTF's convention: u to the right and v down from
    /// the image's top-left corner. Read through the part's [`Material::texture`], and only
    /// then: imported parts whose material has an image carry them; `None` for every other
    /// part (procedural parts are box-projected in metres by the exporters and the renderer).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub uvs: Option<Vec<[f32; 2]>>,
}

impl MeshPart {
    /// The 12 triangles of a box over 8 corners numbered by bits: bit 0 of a corner's index
    /// selects the far side along the first edge direction (x), bit 1 along the second (y) and
    /// bit 2 along the third (z). The triangles are counter-clockwise seen from outside when
    /// those three directions form a right-handed frame, as in [`MeshPart::cuboid`].
    pub const BOX_TRIANGLES: [[u32; 3]; 12] = [
        [0, 2, 1],
        [1, 2, 3], // first direction's near face (z = min for a cuboid)
        [4, 5, 6],
        [5, 7, 6], // z = max
        [0, 1, 4],
        [1, 5, 4], // y = min
        [2, 6, 3],
        [3, 6, 7], // y = max
        [0, 4, 2],
        [2, 4, 6], // x = min
        [1, 3, 5],
        [3, 7, 5], // x = max
    ];

    /// A box (any hexahedron) from its 8 corners, numbered as for
    /// [`MeshPart::BOX_TRIANGLES`]; outward-oriented when the corner numbering is right-handed
    /// (an axis-aligned or rotated box). 8 vertices, 12 triangles.
    pub fn from_box_corners(
        name: impl Into<String>,
        material: usize,
        corners: [[f32; 3]; 8],
    ) -> Self {
        Self {
            name: name.into(),
            material,
            positions: corners.to_vec(),
            triangles: Self::BOX_TRIANGLES.to_vec(),
            joint: None,
            uvs: None,
        }
    }

    /// A closed, outward-oriented axis-aligned box from `min` to `max`: 8 vertices (corner `i`
    /// takes `max` along x, y, z where bit 0, 1, 2 of `i` is set, `min` elsewhere) and 12
    /// triangles.
    pub fn cuboid(name: impl Into<String>, material: usize, min: [f32; 3], max: [f32; 3]) -> Self {
        let corners = std::array::from_fn(|i| {
            std::array::from_fn(|k| if i & (1 << k) == 0 { min[k] } else { max[k] })
        });
        Self::from_box_corners(name, material, corners)
    }

    /// The texture coordinates of the part when it has one per vertex and its material
    /// `material` has an image: what a textured part is drawn with; `None` otherwise.
    pub fn textured_uvs<'a>(
        &'a self,
        material: &'a Material,
    ) -> Option<(&'a [[f32; 2]], &'a TextureImage)> {
        let uvs = self.uvs.as_deref()?;
        let texture = material.texture.as_ref()?;
        (uvs.len() == self.positions.len()).then_some((uvs, texture))
    }

    /// The position of vertex `i` as a point.
    pub fn point(&self, i: u32) -> Point3<f32> {
        Point3::from(self.positions[i as usize])
    }

    /// The three corners of triangle `t`.
    pub fn triangle(&self, t: usize) -> [Point3<f32>; 3] {
        self.triangles[t].map(|i| self.point(i))
    }

    /// Signed volume enclosed by the part (positive when faces point outward).
    pub fn signed_volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| Vector3::from(self.positions[i as usize]).cast::<f64>());
                a.dot(&b.cross(&c)) / 6.0
            })
            .sum()
    }

    /// Whether the part is a closed 2-manifold whose faces are consistently oriented: every
    /// directed edge occurs exactly once and its reverse occurs exactly once, no triangle is
    /// degenerate in its indices, and every index is in range.
    pub fn is_closed_and_oriented(&self) -> bool {
        let n = self.positions.len() as u32;
        let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
        for t in &self.triangles {
            if t.iter().any(|&i| i >= n) || t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                return false;
            }
            for k in 0..3 {
                *edges.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
            }
        }
        !self.triangles.is_empty()
            && edges
                .iter()
                .all(|(&(a, b), &count)| count == 1 && edges.get(&(b, a)) == Some(&1))
    }
}

/// A triangle mesh made of parts, each with a material: the geometry of one asset.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Mesh {
    /// The parts; each references one of `materials`.
    pub parts: Vec<MeshPart>,
    /// The materials the parts use.
    pub materials: Vec<Material>,
}

impl Mesh {
    /// A one-part mesh: the closed, outward-oriented axis-aligned box from `min` to `max`
    /// ([`MeshPart::cuboid`], part `name`) in `material`, the mesh's only material.
    ///
    /// ```
    /// use scenethesis_scene_graph::{Material, Mesh};
    ///
    /// let grey = Material::new("grey", [0.5, 0.5, 0.5], 0.8);
    /// let crate_box = Mesh::cuboid("body", grey, [-0.2, 0.0, -0.3], [0.2, 0.4, 0.3]);
    /// assert_eq!((crate_box.vertex_count(), crate_box.triangle_count()), (8, 12));
    /// assert!(crate_box.parts[0].is_closed_and_oriented());
    /// let b = crate_box.bounds().unwrap();
    /// assert_eq!((b.min.y, b.max.y), (0.0, 0.4_f32 as f64));
    /// ```
    pub fn cuboid(
        name: impl Into<String>,
        material: Material,
        min: [f32; 3],
        max: [f32; 3],
    ) -> Self {
        Self {
            parts: vec![MeshPart::cuboid(name, 0, min, max)],
            materials: vec![material],
        }
    }

    /// Total number of triangles over all parts.
    pub fn triangle_count(&self) -> usize {
        self.parts.iter().map(|p| p.triangles.len()).sum()
    }

    /// Total number of vertices over all parts.
    pub fn vertex_count(&self) -> usize {
        self.parts.iter().map(|p| p.positions.len()).sum()
    }

    /// The box around every vertex, or `None` for an empty mesh.
    pub fn bounds(&self) -> Option<Aabb> {
        let mut it = self.parts.iter().flat_map(|p| p.positions.iter());
        let first = it.next()?;
        let start = Point3::from(*first).cast::<f64>();
        Some(it.fold(Aabb::new(start, start), |b, p| {
            b.including(&Point3::from(*p).cast())
        }))
    }

    /// All parts merged into one vertex and triangle list (indices rebased), e.g. to build a
    /// signed distance field of the whole asset.
    pub fn merged(&self) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
        let mut positions = Vec::with_capacity(self.vertex_count());
        let mut triangles = Vec::with_capacity(self.triangle_count());
        for part in &self.parts {
            let base = positions.len() as u32;
            positions.extend_from_slice(&part.positions);
            triangles.extend(part.triangles.iter().map(|t| t.map(|i| i + base)));
        }
        (positions, triangles)
    }

    /// A copy with every vertex mapped through `pose` (asset frame → world).
    pub fn transformed(&self, pose: &Pose) -> Mesh {
        let mut out = self.clone();
        for part in &mut out.parts {
            for p in &mut part.positions {
                let w = pose.transform_point(&Point3::from(*p).cast::<f64>());
                *p = [w.x as f32, w.y as f32, w.z as f32];
            }
        }
        out
    }

    /// A copy with every moving part posed at its joint's state: a part whose
    /// [`MeshPart::joint`] names one of `joints` moves by that joint's motion and then by each
    /// parent joint's in turn (the mesh is drawn closed, state 0). Parts of joints not listed
    /// stay as drawn.
    ///
    /// ```
    /// use scenethesis_scene_graph::{Joint, JointKind, JointState, Material, Mesh, OpensTo};
    ///
    /// let mut drawer = Mesh::cuboid("box", Material::new("oak", [0.6, 0.4, 0.2], 0.5),
    ///     [-0.2, 0.1, -0.2], [0.2, 0.3, 0.2]);
    /// drawer.parts[0].joint = Some("drawer_0".into());
    /// let open = JointState {
    ///     joint: Joint {
    ///         name: "drawer_0".into(),
    ///         kind: JointKind::Prismatic,
    ///         axis: [0.0, 0.0, 1.0],
    ///         anchor: [0.0, 0.2, 0.2],
    ///         limits: [0.0, 0.3],
    ///         opens_to: OpensTo::Out,
    ///         parent: None,
    ///     },
    ///     state: 0.3,
    /// };
    /// let moved = drawer.with_joint_states(&[open]).bounds().unwrap();
    /// assert!((moved.max.z - 0.5).abs() < 1e-6);
    /// ```
    pub fn with_joint_states(&self, joints: &[crate::JointState]) -> Mesh {
        let mut out = self.clone();
        if joints.is_empty() {
            return out;
        }
        let find = |name: &str| joints.iter().find(|j| j.joint.name == name);
        for part in &mut out.parts {
            let mut next = part.joint.as_deref().and_then(find);
            // Own motion first, then each parent's; a depth bound stops a malformed cycle.
            for _ in 0..joints.len() {
                let Some(js) = next else { break };
                for p in &mut part.positions {
                    *p = js.joint.moved_point(js.state, *p);
                }
                next = js.joint.parent.as_deref().and_then(find);
            }
        }
        out
    }

    /// Appends another mesh's parts and materials (material indices rebased).
    pub fn append(&mut self, other: &Mesh) {
        let base = self.materials.len();
        self.materials.extend(other.materials.iter().cloned());
        self.parts.extend(other.parts.iter().cloned().map(|mut p| {
            p.material += base;
            p
        }));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit cube with outward faces.
    pub fn cube() -> MeshPart {
        MeshPart::cuboid("cube", 0, [0.0; 3], [1.0; 3])
    }

    #[test]
    fn cube_is_closed_with_unit_volume() {
        let c = cube();
        assert!(c.is_closed_and_oriented());
        assert!((c.signed_volume() - 1.0).abs() < 1e-9);
        let mut open = c.clone();
        open.triangles.pop();
        assert!(!open.is_closed_and_oriented());
        let mut flipped = c;
        flipped.triangles[0].swap(1, 2);
        assert!(!flipped.is_closed_and_oriented());
    }

    #[test]
    fn cuboid_spans_min_to_max_with_bit_numbered_corners() {
        let b = MeshPart::cuboid("b", 2, [1.0, 2.0, 3.0], [2.0, 4.0, 6.0]);
        assert!(b.is_closed_and_oriented());
        assert!((b.signed_volume() - 6.0).abs() < 1e-9);
        assert_eq!((b.name.as_str(), b.material), ("b", 2));
        assert_eq!(b.positions[0], [1.0, 2.0, 3.0]);
        assert_eq!(b.positions[5], [2.0, 2.0, 6.0]);
        assert_eq!(b.positions[7], [2.0, 4.0, 6.0]);
        // A left-handed corner order (x mirrored) turns the faces inward.
        let mut mirrored: [[f32; 3]; 8] = b.positions.clone().try_into().unwrap();
        for c in &mut mirrored {
            c[0] = -c[0];
        }
        assert!(MeshPart::from_box_corners("m", 0, mirrored).signed_volume() < 0.0);
    }

    #[test]
    fn merged_rebases_indices_and_transform_moves_bounds() {
        let mesh = Mesh {
            parts: vec![cube(), cube()],
            materials: vec![Material::new("m", [0.5, 0.5, 0.5], 0.8)],
        };
        let (p, t) = mesh.merged();
        assert_eq!(p.len(), 16);
        assert_eq!(t[12], [8, 10, 9]);
        let moved = mesh.transformed(&Pose::new(2.0, 0.0, Vector3::new(1.0, 0.0, 0.0)));
        let b = moved.bounds().unwrap();
        assert_eq!(b.min, Point3::new(1.0, 0.0, 0.0));
        assert_eq!(b.max, Point3::new(3.0, 2.0, 2.0));
    }
}
