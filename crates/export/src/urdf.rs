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

use std::collections::BTreeMap;
use std::fmt::Write;

use nalgebra::{Matrix3, Vector3};

use crate::architecture::{pieces, OrientedBox};
use crate::geometry::{num, num32, to_z_up, y_up_to_z_up, Identifiers, MassProperties};
use crate::mjcf::{attr, comment};
use crate::{Dynamics, ExportScene, DENSITY};
use scenethesis_scene_graph::{Material, MeshPart};

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

/// The scene as a URDF robot description whose mesh references are `mesh_dir/<file>.obj`.
pub fn to_urdf(export: &ExportScene<'_>, mesh_dir: &str) -> UrdfPackage {
    let scene = export.scene();
    let mut links = Identifiers::new(true);
    links.reserve("world");
    let mut files = Identifiers::file_names();
    let mut meshes = BTreeMap::new();
    let mut materials: Vec<(String, Material)> = Vec::new();
    let mut material_names = Identifiers::new(true);
    let mut material = |m: &Material| -> String {
        if let Some((name, _)) = materials.iter().find(|(_, known)| known == m) {
            return name.clone();
        }
        let name = material_names.make(&m.name);
        materials.push((name.clone(), m.clone()));
        name
    };

    let mut body = String::new();
    body.push_str("  <link name=\"world\"/>\n");
    for piece in pieces(&scene.architecture) {
        let name = links.make(&piece.id);
        let mat = material(&piece.to_mesh().materials[0]);
        let _ = writeln!(body, "  <link name=\"{}\">", attr(&name));
        for b in &piece.boxes {
            let geometry = box_geometry(b);
            let _ = writeln!(
                body,
                "    <visual>\n{geometry}      <material name=\"{}\"/>\n    </visual>\n    <collision>\n{geometry}    </collision>",
                attr(&mat)
            );
        }
        let _ = writeln!(
            body,
            "  </link>\n  <joint name=\"{n}_joint\" type=\"fixed\">\n    <parent link=\"world\"/>\n    <child link=\"{n}\"/>\n  </joint>",
            n = attr(&name)
        );
    }

    let up = y_up_to_z_up().to_rotation_matrix();
    for object in &scene.objects {
        let name = links.make(&object.id);
        let mesh = export.mesh(object);
        let pose = &object.pose;
        let s = num(pose.scale);
        let _ = writeln!(body, "  <link name=\"{}\">", attr(&name));
        if let Some(props) = MassProperties::of_mesh(mesh, pose.scale, DENSITY) {
            let com = up * props.center_of_mass;
            let inertia: Matrix3<f64> = up.matrix() * props.inertia * up.matrix().transpose();
            let _ = writeln!(
                body,
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
            let file = format!(
                "{}.obj",
                files.make(&format!("{}_{}", object.id, part.name))
            );
            meshes.insert(file.clone(), obj(part));
            let geometry = format!(
                "      <origin xyz=\"0 0 0\" rpy=\"{} 0 0\"/>\n      <geometry>\n        <mesh filename=\"{}/{}\" scale=\"{s} {s} {s}\"/>\n      </geometry>\n",
                num(std::f64::consts::FRAC_PI_2),
                attr(mesh_dir),
                attr(&file),
            );
            let mat = material(&mesh.materials[part.material]);
            let _ = writeln!(
                body,
                "    <visual name=\"{p}\">\n{geometry}      <material name=\"{}\"/>\n    </visual>\n    <collision name=\"{p}\">\n{geometry}    </collision>",
                attr(&mat),
                p = attr(&part.name),
            );
        }
        let kind = match export.dynamics(object) {
            Dynamics::Free => "floating",
            Dynamics::Fixed => "fixed",
        };
        let _ = writeln!(
            body,
            "  </link>\n  <joint name=\"{n}_joint\" type=\"{kind}\">\n    <parent link=\"world\"/>\n    <child link=\"{n}\"/>\n    <origin xyz=\"{}\" rpy=\"0 0 {}\"/>\n  </joint>",
            vec3(&to_z_up(&pose.translation)),
            num(pose.yaw),
            n = attr(&name),
        );
    }

    let mut urdf = String::new();
    let _ = writeln!(
        urdf,
        "<?xml version=\"1.0\"?>\n<!-- {} -->\n<robot name=\"scenethesis_scene\">",
        comment(&scene.prompt)
    );
    for (name, m) in &materials {
        let c = m.base_color;
        let _ = writeln!(
            urdf,
            "  <material name=\"{}\">\n    <color rgba=\"{} {} {} {}\"/>\n  </material>",
            attr(name),
            num32(c[0]),
            num32(c[1]),
            num32(c[2]),
            num32(c[3])
        );
    }
    urdf.push_str(&body);
    urdf.push_str("</robot>\n");
    UrdfPackage { urdf, meshes }
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

/// A part as Wavefront OBJ text (positions and 1-based triangles).
fn obj(part: &MeshPart) -> String {
    let mut out = format!("# scenethesis part {}\no {}\n", part.name, part.name);
    for p in &part.positions {
        let _ = writeln!(out, "v {} {} {}", num32(p[0]), num32(p[1]), num32(p[2]));
    }
    for t in &part.triangles {
        let _ = writeln!(out, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    out
}
