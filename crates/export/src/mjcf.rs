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
//!
//! A material wearing a library material references its base-colour map as a `<texture>`
//! (a PNG in the texture folder beside the file), its `rgba` the tint; mesh parts carry
//! box-projected `texcoord`s, and the floor plane and wall boxes repeat the texture per metre
//! (`texuniform`). A material with an imported image references it the same way
//! (`image_<digest>.png`, its `rgba` the base colour), and the mesh parts showing it carry
//! their own texture coordinates as `texcoord` (v flipped to MuJoCo's bottom-up convention).
//!
//! An articulated object's body holds its fixed parts and one nested child body per joint
//! (`<object>_<joint>`, a nested joint's inside its parent's) at the joint's anchor, with a
//! `hinge` or `slide` joint (`range` in radians or metres, the pose's scale applied, 0 closed)
//! whose `ref` is the scene's state: the body is written posed in that state, so the model's
//! initial `qpos` is the scene. Every such joint has damping [`crate::JOINT_DAMPING`],
//! armature [`ARMATURE`] and a dry `frictionloss` that holds the part against gravity (a
//! closed oven door stays closed), made stiff by [`FRICTION_TIME_CONSTANT`]; a
//! `<contact><exclude>` keeps each link from colliding with its parent and its object's body.
//!
//! A room door's leaf is written the same way: a static body `<door>` (no free joint: it is
//! fixed to the world) holding the leaf's body `<door>_leaf` (and a double door's second,
//! `<door>_leaf_2`) on its hinge, excluded from
//! contact with the world body's floor and walls (the frame it sits in).

use std::collections::BTreeSet;
use std::fmt::Write;

use nalgebra::{UnitQuaternion, Vector3};

use crate::architecture::{leaves, pieces, Leaf, OrientedBox, Piece, PieceKind};
use crate::articulation::{Articulation, JOINT_DAMPING};
use crate::geometry::{
    image_file_name, library_of, num, num32, shade, to_z_up, worn, y_up_to_z_up, Identifiers,
};
use crate::textures;
use crate::{Dynamics, ExportScene, DENSITY, FRICTION};
use scenethesis_materials::{maps, MapKind};
use scenethesis_scene_graph::{JointKind, Material, Mesh, MeshPart, SceneObject};

/// The time constant (s) of the joints' dry friction (`solreffriction`). MuJoCo's default,
/// 0.02 s, lets a light part held against gravity creep (a laptop screen 0.04 rad in 2 s); at
/// twice the time step the creep is ten times smaller.
pub const FRICTION_TIME_CONSTANT: f64 = 0.002;

/// The simulation time step written into the file, in seconds.
pub const TIMESTEP: f64 = 0.001;

/// Rotor inertia added to every hinge and slide joint (kg·m² or kg): keeps a light part (a thin
/// door, a handle) stable at the time step.
pub const ARMATURE: f64 = 0.01;

/// The scene as an MJCF document (meshes inline) whose textures are in
/// [`crate::TEXTURE_DIR`] beside it.
pub fn to_mjcf(export: &ExportScene<'_>) -> String {
    to_mjcf_textured(export, crate::TEXTURE_DIR)
}

/// The scene as an MJCF document (meshes inline, with texture coordinates where a part wears
/// a library material) whose `<texture>` files are in the folder `texture_dir` beside it.
pub fn to_mjcf_textured(export: &ExportScene<'_>, texture_dir: &str) -> String {
    let scene = export.scene();
    let mut doc = MjcfParts {
        names: Identifiers::new(true),
        texture_dir: texture_dir.to_owned(),
        materials: Vec::new(),
        meshes: String::new(),
        world: String::new(),
        excludes: Vec::new(),
    };
    for piece in &pieces(&scene.architecture, &scene.look) {
        doc.add_architecture(piece);
    }
    for object in &scene.objects {
        doc.add_object(export, object);
    }
    for leaf in &leaves(&scene.architecture) {
        doc.add_leaf(leaf);
    }
    doc.into_document(&scene.prompt)
}

/// The MJCF document being written: unique names, the materials met so far, the `<asset>`
/// meshes and the `<worldbody>` contents.
struct MjcfParts {
    names: Identifiers,
    texture_dir: String,
    /// Name, material, and whether its texture repeats per metre of a primitive geom (the
    /// floor plane and wall boxes) rather than by a mesh's texture coordinates.
    materials: Vec<(String, Material, bool)>,
    meshes: String,
    world: String,
    /// Pairs of bodies that never collide: each link with its parent and its object's body.
    excludes: Vec<(String, String)>,
}

impl MjcfParts {
    /// The name of material `m` (on primitive geoms when `uniform`), added on first use.
    fn material_name(&mut self, m: &Material, uniform: bool) -> String {
        if let Some((name, ..)) = self
            .materials
            .iter()
            .find(|(_, known, u)| known == m && *u == uniform)
        {
            return name.clone();
        }
        let name = self.names.make(&format!("mat_{}", m.name));
        self.materials.push((name.clone(), m.clone(), uniform));
        name
    }

    /// A piece of the architecture: the floor as a plane, a wall or window pane as its boxes.
    fn add_architecture(&mut self, piece: &Piece) {
        let mesh = piece.to_mesh();
        let mat = self.material_name(&mesh.materials[0], true);
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
            PieceKind::Wall | PieceKind::Window => {
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
        match Articulation::of(object, mesh) {
            None => self.add_geoms(&object.id, mesh, pose.scale, "      "),
            Some(articulation) => {
                self.add_geoms(&object.id, &articulation.body, pose.scale, "      ");
                let mut bodies = vec![body];
                let owner = (object.id.as_str(), pose.scale);
                self.add_links(owner, &articulation, &mut bodies, None, "      ");
            }
        }
        self.world.push_str("    </body>\n");
    }

    /// One mesh geom (and inline mesh asset) per part with triangles, in the frame of the body
    /// being written, scaled by `scale`.
    fn add_geoms(&mut self, id: &str, mesh: &Mesh, scale: f64, indent: &str) {
        for part in mesh.parts.iter().filter(|p| !p.triangles.is_empty()) {
            let name = self.names.make(&format!("{id}_{}", part.name));
            let material = worn(part, &mesh.materials[part.material]);
            let material = &*material;
            let s = num(scale);
            let _ = writeln!(
                self.meshes,
                "    <mesh name=\"{}\" scale=\"{s} {s} {s}\" {}/>",
                attr(&name),
                mesh_data(part, material),
            );
            let mat = self.material_name(material, false);
            let _ = writeln!(
                self.world,
                "{indent}<geom name=\"{n}\" type=\"mesh\" mesh=\"{n}\" material=\"{mat}\"/>",
                n = attr(&name),
            );
        }
    }

    /// The links whose parent is `parent` (`None`: the body), each a child body at its joint's
    /// anchor posed in the scene's state, with a hinge or slide joint whose `ref` is that
    /// state (so the model's initial `qpos` is the scene and 0 is closed), its geoms, its own
    /// children, and contact exclusions against its parent and the object's body. `bodies`
    /// holds the body names written so far: the object's body first, then one per link.
    /// `owner` is the object's (or door's) id and scale.
    fn add_links(
        &mut self,
        owner: (&str, f64),
        articulation: &Articulation<'_>,
        bodies: &mut Vec<String>,
        parent: Option<usize>,
        indent: &str,
    ) {
        let (id, scale) = owner;
        for (i, link) in articulation.links.iter().enumerate() {
            if link.parent != parent {
                continue;
            }
            let joint = link.joint;
            let name = self.names.make(&format!("{id}_{}", joint.name));
            let local = articulation.local_pose(i);
            let pos = local.translation.vector * scale;
            let _ = writeln!(
                self.world,
                "{indent}<body name=\"{n}\" pos=\"{} {} {}\" quat=\"{}\">",
                num(pos.x),
                num(pos.y),
                num(pos.z),
                quat(&local.rotation),
                n = attr(&name),
            );
            let (kind, unit) = match joint.kind {
                JointKind::Revolute => ("hinge", 1.0),
                JointKind::Prismatic => ("slide", scale),
            };
            let [lo, hi] = link.limits();
            let axis = link.axis();
            let _ = writeln!(
                self.world,
                "{indent}  <joint name=\"{n}\" type=\"{kind}\" axis=\"{} {} {}\" range=\"{} {}\" limited=\"true\" ref=\"{}\" damping=\"{}\" armature=\"{}\" frictionloss=\"{}\" solreffriction=\"{} 1\"/>",
                num(axis.x),
                num(axis.y),
                num(axis.z),
                num(lo * unit),
                num(hi * unit),
                num(link.state * unit),
                num(JOINT_DAMPING),
                num(ARMATURE),
                num(articulation.holding_friction(i, scale)),
                num(FRICTION_TIME_CONSTANT),
                n = attr(&name),
            );
            if link.has_geometry() {
                let link_id = format!("{id}_{}", joint.name);
                self.add_geoms(&link_id, &link.mesh, scale, &format!("{indent}  "));
            } else {
                // A joint needs a body with mass: a link drawn with no triangles gets a token one.
                let _ = writeln!(
                    self.world,
                    "{indent}  <inertial pos=\"0 0 0\" mass=\"0.001\" diaginertia=\"1e-06 1e-06 1e-06\"/>"
                );
            }
            let parent_body = link.parent.map_or(0, |p| p + 1);
            let root = bodies[0].clone();
            let parent_name = bodies[parent_body].clone();
            bodies.push(name.clone());
            self.excludes.push((parent_name.clone(), name.clone()));
            if parent_name != root {
                self.excludes.push((root, name.clone()));
            }
            self.add_links(owner, articulation, bodies, Some(i), &format!("{indent}  "));
            let _ = writeln!(self.world, "{indent}</body>");
        }
    }

    /// A room door's leaf: a static body `<door>` at the world's origin (turned Z-up, so the
    /// leaf is written as an object's link) holding the leaf's body `<door>_leaf` on its
    /// hinge, which never collides with the walls and floor (the world body).
    fn add_leaf(&mut self, leaf: &Leaf) {
        let articulation = Articulation::of_leaf(leaf);
        let body = self.names.make(&leaf.door);
        let _ = writeln!(
            self.world,
            "    <body name=\"{}\" pos=\"0 0 0\" quat=\"{}\">",
            attr(&body),
            quat(&y_up_to_z_up()),
        );
        let mut bodies = vec![body];
        self.add_links(
            (&leaf.door, 1.0),
            &articulation,
            &mut bodies,
            None,
            "      ",
        );
        self.world.push_str("    </body>\n");
        for link in &bodies[1..] {
            self.excludes.push(("world".to_owned(), link.clone()));
        }
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
        let mut textures = BTreeSet::new();
        for (_, m, _) in &self.materials {
            if let Some(image) = &m.texture {
                if textures.insert(image.digest_hex()) {
                    let _ = writeln!(
                        out,
                        "    <texture name=\"tex_image_{}\" type=\"2d\" file=\"{}/{}\"/>",
                        image.digest_hex(),
                        attr(&self.texture_dir),
                        image_file_name(image),
                    );
                }
            }
            if let Some(library) = library_of(m) {
                if textures.insert(library.id.to_owned()) {
                    let _ = writeln!(
                        out,
                        "    <texture name=\"tex_{}\" type=\"2d\" file=\"{}/{}\"/>",
                        library.id,
                        attr(&self.texture_dir),
                        textures::file_name(library, MapKind::BaseColor),
                    );
                }
            }
        }
        for (name, m, uniform) in &self.materials {
            let library = library_of(m);
            let c = library.map_or(m.base_color, |l| maps(l).color_factor(m.base_color));
            let image = m
                .texture
                .as_ref()
                .map(|image| format!(" texture=\"tex_image_{}\"", image.digest_hex()));
            let texture = image.unwrap_or_else(|| {
                library.map_or(String::new(), |l| {
                    let repeat = if *uniform { 1.0 / l.tile_size_m } else { 1.0 };
                    format!(
                        " texture=\"tex_{}\" texrepeat=\"{r} {r}\" texuniform=\"{}\"",
                        l.id,
                        uniform,
                        r = num32(repeat),
                    )
                })
            });
            let _ = writeln!(
                out,
                "    <material name=\"{}\" rgba=\"{} {} {} {}\" specular=\"{}\" shininess=\"{}\" reflectance=\"0\"{texture}/>",
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
        out.push_str("  </worldbody>\n");
        if !self.excludes.is_empty() {
            out.push_str("  <contact>\n");
            for (a, b) in &self.excludes {
                let _ = writeln!(
                    out,
                    "    <exclude body1=\"{}\" body2=\"{}\"/>",
                    attr(a),
                    attr(b)
                );
            }
            out.push_str("  </contact>\n");
        }
        out.push_str("</mujoco>\n");
        out
    }
}

/// A mesh asset's `vertex` and `face` attributes, and `texcoord` (box-projected, v flipped to
/// MuJoCo's bottom-up convention) when the part wears a library material; the vertices are then
/// split where the projection changes.
fn mesh_data(part: &MeshPart, material: &Material) -> String {
    if let Some((uvs, _)) = part.textured_uvs(material) {
        return image_mesh_data(part, uvs);
    }
    let shaded = library_of(material).map(|l| shade(part, Some(l)));
    let (positions, faces): (&[[f32; 3]], Vec<[u32; 3]>) = match &shaded {
        Some(s) => (
            &s.positions,
            s.indices.chunks(3).map(|t| [t[0], t[1], t[2]]).collect(),
        ),
        None => (&part.positions, part.triangles.clone()),
    };
    let vertices: Vec<String> = positions
        .iter()
        .map(|p| format!("{} {} {}", num32(p[0]), num32(p[1]), num32(p[2])))
        .collect();
    let faces: Vec<String> = faces
        .iter()
        .map(|t| format!("{} {} {}", t[0], t[1], t[2]))
        .collect();
    let mut out = format!(
        "vertex=\"{}\" face=\"{}\"",
        vertices.join("  "),
        faces.join("  ")
    );
    if let Some(s) = &shaded {
        let uvs: Vec<String> = s
            .uvs
            .iter()
            .map(|uv| format!("{} {}", num32(uv[0]), num32(-uv[1])))
            .collect();
        let _ = write!(out, " texcoord=\"{}\"", uvs.join("  "));
    }
    out
}

/// A mesh asset's `vertex`, `face` and `texcoord` attributes for a part showing an imported
/// image: its own vertices and texture coordinates, v flipped to MuJoCo's bottom-up
/// convention.
fn image_mesh_data(part: &MeshPart, uvs: &[[f32; 2]]) -> String {
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
    let uvs: Vec<String> = uvs
        .iter()
        .map(|uv| format!("{} {}", num32(uv[0]), num32(1.0 - uv[1])))
        .collect();
    format!(
        "vertex=\"{}\" face=\"{}\" texcoord=\"{}\"",
        vertices.join("  "),
        faces.join("  "),
        uvs.join("  ")
    )
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
