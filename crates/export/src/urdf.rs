//! URDF writer.
//!
//! ROS tools expect +Z up, so link frames are in the same Z-up world as [`crate::mjcf`]: a
//! scene point `(x, y, z)` is `(x, −z, y)`. The tree's root is a `world` link; the floor and
//! each wall are links fixed to it with box visuals and collisions (walls split around door
//! openings); each object is a link with a `floating` joint (or `fixed`, for
//! [`crate::Dynamics::Fixed`] objects) whose origin is the object's position and yaw (about Z).
//! Each part of an object's mesh is a visual and a collision referring to its own OBJ file,
//! written in the asset's frame (+Y up) and turned up by the element's `rpy` of π/2 about X,
//! scaled by the pose. Masses and inertias come from the closed parts at [`crate::DENSITY`].
//! A material wearing a library material names its base-colour map as its `<texture>` and its
//! parts' OBJ files carry box-projected `vt`s; one with an imported image names that image
//! (`image_<digest>.png`) and its parts carry their own texture coordinates; a part of such a
//! material without texture coordinates wears its flat colour (the material's colour times the
//! image's mean).
//!
//! An articulated object's link holds its fixed body; each joint adds a link (named
//! `<object>_<joint>`, its parts' OBJ files in the joint's frame, origin at the anchor) and a
//! `revolute` or `prismatic` joint from the parent link, with the axis in the parent's frame,
//! `<limit>` in radians or metres (scaled by the pose) and `<dynamics>` damping and friction as
//! in MJCF. The zero configuration is closed. A room door's leaf is such a link
//! (`<door>_leaf`, a double door's second leaf `<door>_leaf_2`) on a `revolute` joint from
//! `world`, its origin the hinge.

use std::collections::BTreeMap;
use std::fmt::Write;

use nalgebra::{Matrix3, Vector3};

use crate::architecture::{leaves, pieces, OrientedBox};
use crate::articulation::{Articulation, JOINT_DAMPING};
use crate::geometry::{
    image_file_name, library_of, num, num32, shade, to_z_up, worn, y_up_to_z_up, Identifiers,
    MassProperties,
};
use crate::mjcf::{attr, comment};
use crate::textures;
use crate::{Dynamics, ExportScene, DENSITY};
use scenethesis_materials::MapKind;
use scenethesis_scene_graph::{JointKind, Material, Mesh, MeshPart};

/// The effort limit of every revolute and prismatic joint (N·m or N).
pub const JOINT_EFFORT: f64 = 100.0;

/// The velocity limit of every revolute and prismatic joint (rad/s or m/s).
pub const JOINT_VELOCITY: f64 = 2.0;

/// The folder, relative to the URDF file, that [`crate::Format::Urdf`] writes meshes into.
pub const MESH_DIR: &str = "meshes";

/// A URDF document and the mesh files it refers to.
#[derive(Debug, Clone, PartialEq)]
pub struct UrdfPackage {
    /// The URDF XML text.
    pub urdf: String,
    /// OBJ files by file name, to be written into the mesh folder given to [`to_urdf`].
    pub meshes: BTreeMap<String, String>,
}

/// The scene as a URDF robot description whose mesh references are `mesh_dir/<file>.obj`
/// and whose textures are in [`crate::TEXTURE_DIR`].
pub fn to_urdf(export: &ExportScene<'_>, mesh_dir: &str) -> UrdfPackage {
    to_urdf_textured(export, mesh_dir, crate::TEXTURE_DIR)
}

/// The scene as a URDF robot description whose mesh references are `mesh_dir/<file>.obj`
/// (with texture coordinates where a part wears a library material) and whose materials name
/// their base-colour texture as `texture_dir/<file>.png` beside their colour.
pub fn to_urdf_textured(
    export: &ExportScene<'_>,
    mesh_dir: &str,
    texture_dir: &str,
) -> UrdfPackage {
    let scene = export.scene();
    let mut w = Writer {
        links: Identifiers::new(true),
        files: Identifiers::file_names(),
        meshes: BTreeMap::new(),
        materials: Vec::new(),
        material_names: Identifiers::new(true),
        body: String::new(),
        mesh_dir,
    };
    w.links.reserve("world");
    w.body.push_str("  <link name=\"world\"/>\n");
    for piece in pieces(&scene.architecture, &scene.look) {
        let name = w.links.make(&piece.id);
        let mat = w.material(&piece.to_mesh().materials[0]);
        let _ = writeln!(w.body, "  <link name=\"{}\">", attr(&name));
        for b in &piece.boxes {
            let geometry = box_geometry(b);
            let _ = writeln!(
                w.body,
                "    <visual>\n{geometry}      <material name=\"{}\"/>\n    </visual>\n    <collision>\n{geometry}    </collision>",
                attr(&mat)
            );
        }
        let _ = writeln!(
            w.body,
            "  </link>\n  <joint name=\"{n}_joint\" type=\"fixed\">\n    <parent link=\"world\"/>\n    <child link=\"{n}\"/>\n  </joint>",
            n = attr(&name)
        );
    }

    for object in &scene.objects {
        let name = w.links.make(&object.id);
        let mesh = export.mesh(object);
        let pose = &object.pose;
        let articulation = Articulation::of(object, mesh);
        let body = articulation.as_ref().map_or(mesh, |a| &a.body);
        w.link(&name, &object.id, body, pose.scale);
        let kind = match export.dynamics(object) {
            Dynamics::Free => "floating",
            Dynamics::Fixed => "fixed",
        };
        let _ = writeln!(
            w.body,
            "  <joint name=\"{n}_joint\" type=\"{kind}\">\n    <parent link=\"world\"/>\n    <child link=\"{n}\"/>\n    <origin xyz=\"{}\" rpy=\"0 0 {}\"/>\n  </joint>",
            vec3(&to_z_up(&pose.translation)),
            num(pose.yaw),
            n = attr(&name),
        );
        if let Some(articulation) = &articulation {
            w.joints((&object.id, pose.scale), articulation, &name);
        }
    }
    for leaf in &leaves(&scene.architecture) {
        w.joints((&leaf.door, 1.0), &Articulation::of_leaf(leaf), "world");
    }

    let mut urdf = String::new();
    let _ = writeln!(
        urdf,
        "<?xml version=\"1.0\"?>\n<!-- {} -->\n<robot name=\"scenethesis_scene\">",
        comment(&scene.prompt)
    );
    for (name, m) in &w.materials {
        let c = m.base_color;
        let file = match (&m.texture, library_of(m)) {
            (Some(image), _) => Some(image_file_name(image)),
            (None, Some(l)) => Some(textures::file_name(l, MapKind::BaseColor)),
            (None, None) => None,
        };
        let texture = file.map_or(String::new(), |file| {
            format!(
                "\n    <texture filename=\"{}/{}\"/>",
                attr(texture_dir),
                file
            )
        });
        let _ = writeln!(
            urdf,
            "  <material name=\"{}\">\n    <color rgba=\"{} {} {} {}\"/>{texture}\n  </material>",
            attr(name),
            num32(c[0]),
            num32(c[1]),
            num32(c[2]),
            num32(c[3])
        );
    }
    urdf.push_str(&w.body);
    urdf.push_str("</robot>\n");
    UrdfPackage {
        urdf,
        meshes: w.meshes,
    }
}

/// The document being written: unique link and file names, the OBJ files and materials met so
/// far, and the links and joints.
struct Writer<'a> {
    links: Identifiers,
    files: Identifiers,
    meshes: BTreeMap<String, String>,
    materials: Vec<(String, Material)>,
    material_names: Identifiers,
    body: String,
    mesh_dir: &'a str,
}

impl Writer<'_> {
    /// The name of material `m`, added on first use.
    fn material(&mut self, m: &Material) -> String {
        if let Some((name, _)) = self.materials.iter().find(|(_, known)| known == m) {
            return name.clone();
        }
        let name = self.material_names.make(&m.name);
        self.materials.push((name.clone(), m.clone()));
        name
    }

    /// A `<link>` named `name` holding `mesh` (in the link's +Y-up frame, scaled by `scale`):
    /// its inertial from the closed parts, and a visual and a collision per part, each part an
    /// OBJ file named after `id` and the part.
    fn link(&mut self, name: &str, id: &str, mesh: &Mesh, scale: f64) {
        let up = y_up_to_z_up().to_rotation_matrix();
        let s = num(scale);
        let _ = writeln!(self.body, "  <link name=\"{}\">", attr(name));
        if let Some(props) = MassProperties::of_mesh(mesh, scale, DENSITY) {
            let com = up * props.center_of_mass;
            let inertia: Matrix3<f64> = up.matrix() * props.inertia * up.matrix().transpose();
            let _ = writeln!(
                self.body,
                "    <inertial>\n      <origin xyz=\"{}\" rpy=\"0 0 0\"/>\n      <mass value=\"{}\"/>\n      <inertia ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"/>\n    </inertial>",
                vec3(&com),
                num(props.mass),
                num(inertia[(0, 0)]),
                num(inertia[(0, 1)]),
                num(inertia[(0, 2)]),
                num(inertia[(1, 1)]),
                num(inertia[(1, 2)]),
                num(inertia[(2, 2)]),
            );
        }
        for part in mesh.parts.iter().filter(|p| !p.triangles.is_empty()) {
            let file = format!("{}.obj", self.files.make(&format!("{id}_{}", part.name)));
            let material = worn(part, &mesh.materials[part.material]);
            self.meshes.insert(file.clone(), obj(part, &material));
            let geometry = format!(
                "      <origin xyz=\"0 0 0\" rpy=\"{} 0 0\"/>\n      <geometry>\n        <mesh filename=\"{}/{}\" scale=\"{s} {s} {s}\"/>\n      </geometry>\n",
                num(std::f64::consts::FRAC_PI_2),
                attr(self.mesh_dir),
                attr(&file),
            );
            let mat = self.material(&material);
            let _ = writeln!(
                self.body,
                "    <visual name=\"{p}\">\n{geometry}      <material name=\"{}\"/>\n    </visual>\n    <collision name=\"{p}\">\n{geometry}    </collision>",
                attr(&mat),
                p = attr(&part.name),
            );
        }
        self.body.push_str("  </link>\n");
    }

    /// A link per joint of an articulated object and its `revolute` or `prismatic` joint to
    /// its parent link (`root`, the object's link, or another joint's), origin at the anchor in
    /// the parent's frame. URDF's zero configuration is closed: the scene's state is not
    /// written (it is in `scene.json`).
    /// `owner` is the object's (or door's) id and scale; a door's leaf hangs on `world`.
    fn joints(&mut self, owner: (&str, f64), articulation: &Articulation<'_>, root: &str) {
        let (owner, scale) = owner;
        let mut names: Vec<String> = Vec::with_capacity(articulation.links.len());
        for (i, link) in articulation.links.iter().enumerate() {
            let joint = link.joint;
            let id = format!("{owner}_{}", joint.name);
            let name = self.links.make(&id);
            self.link(&name, &id, &link.mesh, scale);
            let parent = link.parent.map_or(root, |p| names[p].as_str());
            let (kind, unit) = match joint.kind {
                JointKind::Revolute => ("revolute", 1.0),
                JointKind::Prismatic => ("prismatic", scale),
            };
            let [lo, hi] = link.limits();
            let _ = writeln!(
                self.body,
                "  <joint name=\"{n}_joint\" type=\"{kind}\">\n    <parent link=\"{}\"/>\n    <child link=\"{n}\"/>\n    <origin xyz=\"{}\" rpy=\"0 0 0\"/>\n    <axis xyz=\"{}\"/>\n    <limit lower=\"{}\" upper=\"{}\" effort=\"{}\" velocity=\"{}\"/>\n    <dynamics damping=\"{}\" friction=\"{}\"/>\n  </joint>",
                attr(parent),
                vec3(&to_z_up(&(articulation.offset(i) * scale))),
                vec3(&to_z_up(&link.axis())),
                num(lo * unit),
                num(hi * unit),
                num(JOINT_EFFORT),
                num(JOINT_VELOCITY),
                num(JOINT_DAMPING),
                num(articulation.holding_friction(i, scale)),
                n = attr(&name),
            );
            names.push(name);
        }
    }
}

fn box_geometry(b: &OrientedBox) -> String {
    let c = to_z_up(&b.center.coords);
    let h = b.half_extents * 2.0;
    format!(
        "      <origin xyz=\"{}\" rpy=\"0 0 {}\"/>\n      <geometry>\n        <box size=\"{} {} {}\"/>\n      </geometry>\n",
        vec3(&c),
        num(b.yaw),
        num(h.x),
        num(h.z),
        num(h.y)
    )
}

fn vec3(v: &Vector3<f64>) -> String {
    format!("{} {} {}", num(v.x), num(v.y), num(v.z))
}

/// A part as Wavefront OBJ text (positions and 1-based triangles); a part wearing a library
/// material also has box-projected texture coordinates (`vt`, v up as OBJ has it), its
/// vertices split where the projection changes; a part showing an imported image has its own
/// (v flipped up).
fn obj(part: &MeshPart, material: &Material) -> String {
    let mut out = format!("# scenethesis part {}\no {}\n", part.name, part.name);
    if let Some((uvs, _)) = part.textured_uvs(material) {
        for p in &part.positions {
            let _ = writeln!(out, "v {} {} {}", num32(p[0]), num32(p[1]), num32(p[2]));
        }
        for uv in uvs {
            let _ = writeln!(out, "vt {} {}", num32(uv[0]), num32(1.0 - uv[1]));
        }
        for t in &part.triangles {
            let [a, b, c] = [t[0] + 1, t[1] + 1, t[2] + 1];
            let _ = writeln!(out, "f {a}/{a} {b}/{b} {c}/{c}");
        }
        return out;
    }
    let Some(library) = library_of(material) else {
        for p in &part.positions {
            let _ = writeln!(out, "v {} {} {}", num32(p[0]), num32(p[1]), num32(p[2]));
        }
        for t in &part.triangles {
            let _ = writeln!(out, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
        }
        return out;
    };
    let shaded = shade(part, Some(library));
    for p in &shaded.positions {
        let _ = writeln!(out, "v {} {} {}", num32(p[0]), num32(p[1]), num32(p[2]));
    }
    for uv in &shaded.uvs {
        let _ = writeln!(out, "vt {} {}", num32(uv[0]), num32(-uv[1]));
    }
    for t in shaded.indices.chunks(3) {
        let [a, b, c] = [t[0] + 1, t[1] + 1, t[2] + 1];
        let _ = writeln!(out, "f {a}/{a} {b}/{b} {c}/{c}");
    }
    out
}
