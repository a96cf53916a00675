//! MuJoCo XML (MJCF) writer.
//!
//! MuJoCo's world is +Z up, so the scene is turned +90° about +X: a scene point `(x, y, z)` is
//! `(x, −z, y)` in the file and gravity is `0 0 −9.81`. Every object is a body at the top of the
//! world body with a free joint (or none, when [`crate::Dynamics::Fixed`]), holding one
//! `type="mesh"` geom per part; each part becomes its own inline `<mesh>` asset in the asset's
//! frame, scaled by the pose. MuJoCo collides with the convex hull of each mesh geom, and the
//! procedural parts are convex, so shelf compartments and crate interiors stay open. Density is
//! [`crate::DENSITY`], sliding friction [`crate::FRICTION`], time step 1 ms. The floor is a
//! plane and walls are static boxes, split around door openings.

use std::fmt::Write;

use nalgebra::{UnitQuaternion, Vector3};

use crate::architecture::{pieces, OrientedBox, Piece, PieceKind};
use crate::geometry::{num, num32, to_z_up, y_up_to_z_up, Identifiers};
use crate::{Dynamics, ExportScene, DENSITY, FRICTION};
use scenethesis_scene_graph::{Material, SceneObject};

/// The simulation time step written into the file, in seconds.
pub const TIMESTEP: f64 = 0.001;

/// The scene as an MJCF document (meshes inline, no other files needed).
pub fn to_mjcf(export: &ExportScene<'_>) -> String {
    let scene = export.scene();
    let mut doc = MjcfParts {
        names: Identifiers::new(true),
        materials: Vec::new(),
        meshes: String::new(),
        world: String::new(),
    };
    for piece in &pieces(&scene.architecture) {
        doc.add_architecture(piece);
    }
    for object in &scene.objects {
        doc.add_object(export, object);
    }
    doc.into_document(&scene.prompt)
}

/// The MJCF document being written: unique names, the materials met so far, the `<asset>`
/// meshes and the `<worldbody>` contents.
struct MjcfParts {
    names: Identifiers,
    materials: Vec<(String, Material)>,
    meshes: String,
    world: String,
}

impl MjcfParts {
    /// The name of material `m`, added on first use.
    fn material_name(&mut self, m: &Material) -> String {
        if let Some((name, _)) = self.materials.iter().find(|(_, known)| known == m) {
            return name.clone();
        }
        let name = self.names.make(&format!("mat_{}", m.name));
        self.materials.push((name.clone(), m.clone()));
        name
    }

    /// A piece of the architecture: the floor as a plane, a wall as its boxes.
    fn add_architecture(&mut self, piece: &Piece) {
        let mesh = piece.to_mesh();
        let mat = self.material_name(&mesh.materials[0]);
        match piece.kind {
            PieceKind::Floor => {
                let b = &piece.boxes[0];
                let c = to_z_up(&(b.center.coords + Vector3::new(0.0, b.half_extents.y, 0.0)));
                let name = self.names.make(&piece.id);
                let _ = writeln!(
                    self.world,
                    "    <geom name=\"{}\" type=\"plane\" pos=\"{} {} 0\" size=\"{} {} 0.1\" material=\"{mat}\" condim=\"3\"/>",
                    attr(&name),
                    num(c.x),
                    num(c.y),
                    num(b.half_extents.x),
                    num(b.half_extents.z),
                );
            }
            PieceKind::Wall => {
                for (i, b) in piece.boxes.iter().enumerate() {
                    let name = self.names.make(&format!("{}_{i}", piece.id));
                    let _ = writeln!(
                        self.world,
                        "    <geom name=\"{}\" type=\"box\" {} material=\"{mat}\"/>",
                        attr(&name),
                        box_attributes(b)
                    );
                }
            }
        }
    }

    /// An object: a body at its pose (free when it moves), with one mesh geom per part.
    fn add_object(&mut self, export: &ExportScene<'_>, object: &SceneObject) {
        let body = self.names.make(&object.id);
        let pose = &object.pose;
        let pos = to_z_up(&pose.translation);
        let q = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), pose.yaw) * y_up_to_z_up();
        let _ = writeln!(
            self.world,
            "    <body name=\"{}\" pos=\"{} {} {}\" quat=\"{}\">",
            attr(&body),
            num(pos.x),
            num(pos.y),
            num(pos.z),
            quat(&q),
        );
        if export.dynamics(object) == Dynamics::Free {
            let _ = writeln!(self.world, "      <freejoint name=\"{}\"/>", attr(&body));
        }
        let mesh = export.mesh(object);
        for part in mesh.parts.iter().filter(|p| !p.triangles.is_empty()) {
            let name = self.names.make(&format!("{}_{}", object.id, part.name));
            let vertices: Vec<String> = part
                .positions
                .iter()
                .map(|p| format!("{} {} {}", num32(p[0]), num32(p[1]), num32(p[2])))
                .collect();
            let faces: Vec<String> = part
                .triangles
                .iter()
                .map(|t| format!("{} {} {}", t[0], t[1], t[2]))
                .collect();
            let s = num(pose.scale);
            let _ = writeln!(
                self.meshes,
                "    <mesh name=\"{}\" scale=\"{s} {s} {s}\" vertex=\"{}\" face=\"{}\"/>",
                attr(&name),
                vertices.join("  "),
                faces.join("  "),
            );
            let mat = self.material_name(&mesh.materials[part.material]);
            let _ = writeln!(
                self.world,
                "      <geom name=\"{n}\" type=\"mesh\" mesh=\"{n}\" material=\"{mat}\"/>",
                n = attr(&name),
            );
        }
        self.world.push_str("    </body>\n");
    }

    /// The whole document: header and defaults, the materials and meshes, the world.
    fn into_document(self, prompt: &str) -> String {
        let mut out = String::new();
        let _ = write!(
            out,
            "<mujoco model=\"scenethesis\">\n  <!-- {} -->\n  <compiler angle=\"radian\" autolimits=\"true\"/>\n  <option timestep=\"{}\" gravity=\"0 0 -9.81\"/>\n  <visual>\n    <headlight ambient=\"0.4 0.4 0.4\" diffuse=\"0.6 0.6 0.6\"/>\n  </visual>\n  <default>\n    <geom density=\"{}\" friction=\"{} 0.005 0.0001\"/>\n  </default>\n  <asset>\n",
            comment(prompt),
            num(TIMESTEP),
            num(DENSITY),
            num(FRICTION),
        );
        for (name, m) in &self.materials {
            let c = m.base_color;
            let _ = writeln!(
                out,
                "    <material name=\"{}\" rgba=\"{} {} {} {}\" specular=\"{}\" shininess=\"{}\" reflectance=\"0\"/>",
                attr(name),
                num32(c[0]),
                num32(c[1]),
                num32(c[2]),
                num32(c[3]),
                num32(0.5 * (1.0 - m.roughness.clamp(0.0, 1.0))),
                num32(1.0 - m.roughness.clamp(0.0, 1.0)),
            );
        }
        out.push_str(&self.meshes);
        out.push_str("  </asset>\n  <worldbody>\n    <light name=\"sun\" directional=\"true\" pos=\"0 0 10\" dir=\"0.3 0.2 -1\"/>\n");
        out.push_str(&self.world);
        out.push_str("  </worldbody>\n</mujoco>\n");
        out
    }
}

/// `pos`, `quat` and `size` of a static box in Z-up: the box's local up (y) becomes z.
fn box_attributes(b: &OrientedBox) -> String {
    let c = to_z_up(&b.center.coords);
    let q = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), b.yaw);
    let h = b.half_extents;
    format!(
        "pos=\"{} {} {}\" quat=\"{}\" size=\"{} {} {}\"",
        num(c.x),
        num(c.y),
        num(c.z),
        quat(&q),
        num(h.x),
        num(h.z),
        num(h.y)
    )
}

/// MuJoCo's quaternion order: w x y z.
fn quat(q: &UnitQuaternion<f64>) -> String {
    format!("{} {} {} {}", num(q.w), num(q.i), num(q.j), num(q.k))
}

/// Escapes text for an XML attribute value.
pub(crate) fn attr(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '"' => out.push_str("&quot;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            // Kept as character references so attribute normalisation does not eat them.
            '\t' => out.push_str("&#9;"),
            '\n' => out.push_str("&#10;"),
            '\r' => out.push_str("&#13;"),
            // Other control characters are not allowed in XML 1.0 at all.
            c if c.is_control() => out.push('\u{fffd}'),
            c => out.push(c),
        }
    }
    out
}

/// Text safe inside an XML comment (no `--`).
pub(crate) fn comment(s: &str) -> String {
    let mut out = attr(s);
    while out.contains("--") {
        out = out.replace("--", "- -");
    }
    format!("scenethesis scene: {out}")
}
