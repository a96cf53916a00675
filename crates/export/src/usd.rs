//! OpenUSD text (`.usda`) writer.
//!
//! The layer's default prim `/World` holds one `Xform` per architecture piece (geometry in world
//! coordinates) and per object (translate / rotateY / scale ops from its pose, geometry in the
//! asset frame), each with one `Mesh` per part bound to a `UsdPreviewSurface` material under
//! `/World/Looks`; a material wearing a library material reads its base-colour,
//! metallic-roughness and normal maps through `UsdUVTexture` shaders (files in the texture
//! folder beside the layer, `primvars:st` box-projected in tiles of the material); one with an
//! imported image reads it as its diffuse colour the same way (`image_<digest>.png` in that
//! folder, `primvars:st` the part's own texture coordinates, t up as USD has it). Stage metadata: `upAxis = "Y"`, `metersPerUnit = 1`. Prim names are the ids
//! when they are valid USD identifiers, otherwise sanitised; the original id is kept in the
//! custom attribute `scenethesis:id`.
//!
//! An articulated object (one with joints) is a UsdPhysics articulation: its `Xform` carries
//! `PhysicsArticulationRootAPI`; a `body` Xform and one Xform per link (named by the joint,
//! posed at its anchor in the scene's state) are rigid bodies (density [`crate::DENSITY`])
//! whose meshes collide as convex hulls; a `PhysicsRevoluteJoint` (limits in degrees) or
//! `PhysicsPrismaticJoint` (limits in metres, the pose's scale applied) joins each link to its
//! parent, with `scenethesis:state` and `scenethesis:opensTo` beside; the stage then has a
//! `PhysicsScene` with gravity −Y. Objects without joints are written as before, without
//! physics schemas.
//!
//! A room door's leaf is an `Xform` named by the door after the architecture pieces, an
//! articulation root holding the leaf's rigid body (`leaf`, posed at the hinge in the scene's
//! state, in world coordinates) and its `PhysicsRevoluteJoint` with no `physics:body0`: it is
//! joined to the world; a double door's `Xform` holds both leaves (`leaf`, `leaf_2`), each
//! with its joint.

use std::collections::BTreeMap;
use std::fmt::Write;

use nalgebra::{Quaternion, UnitQuaternion, Vector3};

use crate::architecture::{leaves, pieces, Leaf};
use crate::articulation::Articulation;
use crate::geometry::{
    image_file_name, library_of, material_key, num, num32, shade, worn, Identifiers, Mapping,
};
use crate::textures;
use crate::{Dynamics, ExportScene, DENSITY};
use scenethesis_materials::{maps, LibraryMaterial, MapKind};
use scenethesis_scene_graph::{JointKind, Material, Mesh, OpensTo, SceneObject, TextureImage};

/// The scene as a USD text layer whose textures are in [`crate::TEXTURE_DIR`] beside it.
pub fn to_usda(export: &ExportScene<'_>) -> String {
    to_usda_textured(export, crate::TEXTURE_DIR)
}

/// The scene as a USD text layer whose textures are in the folder `texture_dir` beside it
/// (the files [`crate::write_formats`] writes there).
pub fn to_usda_textured(export: &ExportScene<'_>, texture_dir: &str) -> String {
    let scene = export.scene();
    let mut out = String::new();
    let doc = if scene.prompt.is_empty() {
        "scenethesis scene".to_owned()
    } else {
        format!("scenethesis scene: {}", scene.prompt)
    };
    let _ = write!(
        out,
        "#usda 1.0\n(\n    defaultPrim = \"World\"\n    doc = {}\n    metersPerUnit = 1\n    upAxis = \"Y\"\n)\n\ndef Xform \"World\"\n{{\n",
        quote(&doc)
    );

    // Materials first, so bindings point at prims defined above them (not required by USD,
    // but easier to read).
    let mut looks = Looks::default();
    let arch: Vec<(String, Mesh)> = pieces(&scene.architecture, &scene.look)
        .into_iter()
        .map(|p| {
            let mesh = p.to_mesh();
            (p.id, mesh)
        })
        .collect();
    for (_, mesh) in &arch {
        looks.register(mesh);
    }
    for object in &scene.objects {
        looks.register(export.mesh(object));
    }
    let leaves = leaves(&scene.architecture);
    for leaf in &leaves {
        looks.register(&leaf.mesh);
    }
    out.push_str("    def Scope \"Looks\"\n    {\n");
    for (name, m) in &looks.materials {
        write_material(&mut out, name, m, texture_dir);
    }
    out.push_str("    }\n");

    let mut prims = Identifiers::new(false);
    prims.reserve("Looks");
    let has_joints = !leaves.is_empty() || scene.objects.iter().any(|o| !o.joints.is_empty());
    if has_joints {
        prims.reserve("PhysicsScene");
    }
    for (id, mesh) in &arch {
        let name = prims.make(id);
        let _ = write!(
            out,
            "\n    def Xform {}\n    {{\n        custom string scenethesis:id = {}\n        custom string scenethesis:kind = \"architecture\"\n",
            quote(&name),
            quote(id)
        );
        write_meshes(&mut out, mesh, &looks, false);
        out.push_str("    }\n");
    }
    for leaf in &leaves {
        let name = prims.make(&leaf.door);
        write_leaf(&mut out, &name, leaf, &looks);
    }
    for object in &scene.objects {
        let name = prims.make(&object.id);
        let pose = &object.pose;
        let t = pose.translation;
        let _ = write!(
            out,
            "\n    def Xform {}{}\n    {{\n        custom string scenethesis:id = {}\n        custom string scenethesis:category = {}\n        custom string scenethesis:parent = {}\n        custom string scenethesis:support = {}\n        double3 xformOp:translate = ({}, {}, {})\n        double xformOp:rotateY = {}\n        double3 xformOp:scale = ({s}, {s}, {s})\n        uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:rotateY\", \"xformOp:scale\"]\n",
            quote(&name),
            if object.joints.is_empty() {
                ""
            } else {
                " (\n        prepend apiSchemas = [\"PhysicsArticulationRootAPI\"]\n    )"
            },
            quote(&object.id),
            quote(&object.category),
            quote(&object.parent.to_string()),
            quote(object.support.as_str()),
            num(t.x),
            num(t.y),
            num(t.z),
            num(pose.yaw.to_degrees()),
            s = num(pose.scale),
        );
        match Articulation::of(object, export.mesh(object)) {
            None => write_meshes(&mut out, export.mesh(object), &looks, false),
            Some(articulation) => write_articulation(
                &mut out,
                &format!("/World/{name}"),
                object,
                &articulation,
                export.dynamics(object),
                &looks,
            ),
        }
        out.push_str("    }\n");
    }
    if has_joints {
        out.push_str("\n    def PhysicsScene \"PhysicsScene\"\n    {\n        vector3f physics:gravityDirection = (0, -1, 0)\n        float physics:gravityMagnitude = 9.81\n    }\n");
    }
    out.push_str("}\n");
    out
}

/// An articulated object's prims inside its `Xform` (which carries the
/// `PhysicsArticulationRootAPI`): the body and one `Xform` per link, posed at the joint's
/// anchor in the scene's state, each a rigid body whose meshes collide as convex hulls, and a
/// `PhysicsRevoluteJoint` or `PhysicsPrismaticJoint` per joint. The joint frame maps
/// `physics:axis` (the asset axis nearest the joint's) onto the joint's axis through
/// `localRot0` / `localRot1`, so the joint position is the state: 0 closed. A mounted object's
/// body is held by a `PhysicsFixedJoint` to the world.
fn write_articulation(
    out: &mut String,
    path: &str,
    object: &SceneObject,
    articulation: &Articulation<'_>,
    dynamics: Dynamics,
    looks: &Looks,
) {
    let mut names = Identifiers::new(false);
    let body = names.make("body");
    let _ = write!(
        out,
        "\n        def Xform \"{body}\" (\n            {RIGID}\n        )\n        {{\n            float physics:density = {}\n",
        num(DENSITY)
    );
    out.push_str(&indented(&meshes_text(&articulation.body, looks, true)));
    out.push_str("        }\n");
    let owner = Owner {
        path,
        body: Some(&body),
        scale: object.pose.scale,
    };
    write_links(out, &owner, &mut names, articulation, looks);
    if dynamics == Dynamics::Fixed {
        let pose = &object.pose;
        let t = pose.translation;
        let half = pose.yaw / 2.0;
        let _ = write!(
            out,
            "\n        def PhysicsFixedJoint {}\n        {{\n            rel physics:body1 = <{path}/{body}>\n            point3f physics:localPos0 = ({}, {}, {})\n            point3f physics:localPos1 = (0, 0, 0)\n            quatf physics:localRot0 = ({}, 0, {}, 0)\n            quatf physics:localRot1 = (1, 0, 0, 0)\n        }}\n",
            quote(&names.make("world_joint")),
            num(t.x),
            num(t.y),
            num(t.z),
            num(half.cos()),
            num(half.sin()),
        );
    }
}

/// The API schemas of a rigid body.
const RIGID: &str = "prepend apiSchemas = [\"PhysicsRigidBodyAPI\", \"PhysicsMassAPI\"]";

/// Whose links [`write_links`] writes: the prim path they are written under, the rigid body
/// their root links hang on (`None`: the world), and the scale of prismatic limits.
struct Owner<'a> {
    path: &'a str,
    body: Option<&'a str>,
    scale: f64,
}

/// One rigid-body `Xform` per link, posed at its joint's anchor in the scene's state, and a
/// `PhysicsRevoluteJoint` or `PhysicsPrismaticJoint` per joint joining it to its parent link,
/// or to `owner.body` (no `physics:body0`, the world, when there is none: a door's leaf). The
/// joint frame maps `physics:axis` (the asset axis nearest the joint's) onto the joint's axis
/// through `localRot0` / `localRot1`, so the joint position is the state: 0 closed.
fn write_links(
    out: &mut String,
    owner: &Owner<'_>,
    names: &mut Identifiers,
    articulation: &Articulation<'_>,
    looks: &Looks,
) {
    let path = owner.path;
    let mut links: Vec<String> = Vec::with_capacity(articulation.links.len());
    for (i, link) in articulation.links.iter().enumerate() {
        let name = names.make(&link.joint.name);
        let pose = articulation.pose(i);
        let t = pose.translation.vector;
        let q = pose.rotation;
        let _ = write!(
            out,
            "\n        def Xform {} (\n            {RIGID}\n        )\n        {{\n            custom string scenethesis:joint = {}\n            float physics:density = {}\n            double3 xformOp:translate = ({}, {}, {})\n            quatd xformOp:orient = ({}, {}, {}, {})\n            uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:orient\"]\n",
            quote(&name),
            quote(&link.joint.name),
            num(DENSITY),
            num(t.x),
            num(t.y),
            num(t.z),
            num(q.w),
            num(q.i),
            num(q.j),
            num(q.k),
        );
        out.push_str(&indented(&meshes_text(&link.mesh, looks, true)));
        out.push_str("        }\n");
        links.push(name);
    }
    for (i, link) in articulation.links.iter().enumerate() {
        let joint = link.joint;
        let body0 = match link.parent.map(|p| links[p].as_str()).or(owner.body) {
            Some(parent) => format!("            rel physics:body0 = <{path}/{parent}>\n"),
            None => String::new(),
        };
        let (kind, unit) = match joint.kind {
            JointKind::Revolute => ("PhysicsRevoluteJoint", 180.0 / std::f64::consts::PI),
            JointKind::Prismatic => ("PhysicsPrismaticJoint", owner.scale),
        };
        let (token, frame) = joint_frame(&link.axis());
        let rot = format!(
            "({}, {}, {}, {})",
            num(frame.w),
            num(frame.i),
            num(frame.j),
            num(frame.k)
        );
        let at = articulation.offset(i);
        let [lo, hi] = link.limits();
        let _ = write!(
            out,
            "\n        def {kind} {}\n        {{\n            custom string scenethesis:opensTo = {}\n            custom double scenethesis:state = {}\n            uniform token physics:axis = \"{token}\"\n{body0}            rel physics:body1 = <{path}/{}>\n            point3f physics:localPos0 = ({}, {}, {})\n            point3f physics:localPos1 = (0, 0, 0)\n            quatf physics:localRot0 = {rot}\n            quatf physics:localRot1 = {rot}\n            float physics:lowerLimit = {}\n            float physics:upperLimit = {}\n        }}\n",
            quote(&names.make(&format!("{}_joint", joint.name))),
            quote(&opens_to(joint.opens_to)),
            num(link.state * unit),
            links[i],
            num(at.x),
            num(at.y),
            num(at.z),
            num(lo * unit),
            num(hi * unit),
        );
    }
}

/// A room door's leaf: an `Xform` named by the door (`scenethesis:kind` `door_leaf`) that is
/// an articulation root holding the leaf's rigid body and its revolute joint to the world.
fn write_leaf(out: &mut String, name: &str, leaf: &Leaf, looks: &Looks) {
    let _ = write!(
        out,
        "\n    def Xform {} (\n        prepend apiSchemas = [\"PhysicsArticulationRootAPI\"]\n    )\n    {{\n        custom string scenethesis:id = {}\n        custom string scenethesis:kind = \"door_leaf\"\n        custom string scenethesis:wall = {}\n",
        quote(name),
        quote(&leaf.door),
        quote(&leaf.wall),
    );
    let owner = Owner {
        path: &format!("/World/{name}"),
        body: None,
        scale: 1.0,
    };
    let articulation = Articulation::of_leaf(leaf);
    write_links(
        out,
        &owner,
        &mut Identifiers::new(false),
        &articulation,
        looks,
    );
    out.push_str("    }\n");
}

/// The `physics:axis` token nearest a unit joint axis, and the rotation taking that token's
/// axis onto the joint's (identity when they agree).
fn joint_frame(axis: &Vector3<f64>) -> (&'static str, UnitQuaternion<f64>) {
    let k = axis.iamax();
    let token = ["X", "Y", "Z"][k];
    let e = Vector3::ith(k, 1.0);
    let rotation = if axis.dot(&e) < -1.0 + 1e-12 {
        // Opposite: half a turn about the next axis, written exactly.
        UnitQuaternion::new_unchecked(Quaternion::from_parts(0.0, Vector3::ith((k + 1) % 3, 1.0)))
    } else {
        UnitQuaternion::rotation_between(&e, axis).unwrap_or_else(UnitQuaternion::identity)
    };
    (token, rotation)
}

/// The `opens_to` word of `scene.json`.
fn opens_to(o: OpensTo) -> String {
    match serde_json::to_value(o) {
        Ok(serde_json::Value::String(word)) => word,
        _ => String::new(),
    }
}

/// Text indented by one more level (four spaces).
fn indented(text: &str) -> String {
    text.lines()
        .map(|l| {
            if l.is_empty() {
                "\n".to_owned()
            } else {
                format!("    {l}\n")
            }
        })
        .collect()
}

/// Materials under `/World/Looks`, shared when name and factors agree.
#[derive(Default)]
struct Looks {
    /// Prim name → material, in first-use order of the names.
    materials: Vec<(String, Material)>,
    by_key: BTreeMap<String, usize>,
    names: Option<Identifiers>,
}

impl Looks {
    /// Registers the materials of `mesh` in material order: each as it is, or for a material
    /// with an image, as the parts wear it ([`worn`]: with the image where a part shows it,
    /// flat where one cannot).
    fn register(&mut self, mesh: &Mesh) {
        for (i, m) in mesh.materials.iter().enumerate() {
            if m.texture.is_none() {
                self.add(m);
                continue;
            }
            let parts = mesh.parts.iter().filter(|p| p.material == i);
            let mut worn_by: Vec<std::borrow::Cow<'_, Material>> = Vec::new();
            for part in parts {
                let w = worn(part, m);
                if !worn_by.iter().any(|known| **known == *w) {
                    worn_by.push(w);
                }
            }
            if worn_by.is_empty() {
                worn_by.push(worn(&Default::default(), m));
            }
            for w in &worn_by {
                self.add(w);
            }
        }
    }

    /// Adds `m` under a fresh prim name unless an equal material is registered.
    fn add(&mut self, m: &Material) {
        let key = material_key(m);
        if self.by_key.contains_key(&key) {
            return;
        }
        let name = self
            .names
            .get_or_insert_with(|| Identifiers::new(false))
            .make(&m.name);
        self.materials.push((name, m.clone()));
        self.by_key.insert(key, self.materials.len() - 1);
    }

    fn path(&self, m: &Material) -> String {
        format!(
            "/World/Looks/{}",
            self.materials[self.by_key[&material_key(m)]].0
        )
    }
}

fn write_material(out: &mut String, name: &str, m: &Material, texture_dir: &str) {
    let c = m.base_color;
    let library = library_of(m);
    let look = format!("/World/Looks/{name}");
    let input = |ty: &str, input: &str, value: String, shader: &str, output: &str| match library {
        Some(_) => format!("{ty} inputs:{input}.connect = <{look}/{shader}.outputs:{output}>"),
        None if m.texture.is_some() && input == "diffuseColor" => {
            format!("{ty} inputs:{input}.connect = <{look}/{shader}.outputs:{output}>")
        }
        None => format!("{ty} inputs:{input} = {value}"),
    };
    let _ = write!(
        out,
        "        def Material {q}\n        {{\n            custom string scenethesis:name = {n}\n            token outputs:surface.connect = <{look}/PreviewSurface.outputs:surface>\n\n            def Shader \"PreviewSurface\"\n            {{\n                uniform token info:id = \"UsdPreviewSurface\"\n                {}\n                {}\n{}                float inputs:opacity = {}\n                {}\n                token outputs:surface\n            }}\n",
        input(
            "color3f",
            "diffuseColor",
            format!("({}, {}, {})", num32(c[0]), num32(c[1]), num32(c[2])),
            "BaseColor",
            "rgb"
        ),
        input("float", "metallic", num32(m.metallic), "MetallicRoughness", "b"),
        if library.is_some() {
            format!("                normal3f inputs:normal.connect = <{look}/Normal.outputs:rgb>\n")
        } else {
            String::new()
        },
        num32(c[3]),
        input("float", "roughness", num32(m.roughness), "MetallicRoughness", "g"),
        q = quote(name),
        n = quote(&m.name),
    );
    if let Some(library) = library {
        write_textures(out, &look, m, library, texture_dir);
    } else if let Some(image) = &m.texture {
        write_image(out, &look, m, image, texture_dir);
    }
    out.push_str("        }\n");
}

/// The shaders of a material showing an imported image: a `UsdPrimvarReader_float2` reading
/// `st` and a `UsdUVTexture` of the image whose `scale` is the material's base colour.
fn write_image(
    out: &mut String,
    look: &str,
    m: &Material,
    image: &TextureImage,
    texture_dir: &str,
) {
    let c = m.base_color;
    let _ = write!(
        out,
        "\n            def Shader \"TexCoord\"\n            {{\n                uniform token info:id = \"UsdPrimvarReader_float2\"\n                token inputs:varname = \"st\"\n                float2 outputs:result\n            }}\n\n            def Shader \"BaseColor\"\n            {{\n                uniform token info:id = \"UsdUVTexture\"\n                asset inputs:file = @{}/{}@\n                float4 inputs:scale = ({}, {}, {}, 1)\n                token inputs:sourceColorSpace = \"sRGB\"\n                float2 inputs:st.connect = <{look}/TexCoord.outputs:result>\n                token inputs:wrapS = \"repeat\"\n                token inputs:wrapT = \"repeat\"\n                float3 outputs:rgb\n            }}\n",
        texture_dir,
        image_file_name(image),
        num32(c[0]),
        num32(c[1]),
        num32(c[2]),
    );
}

/// The texture shaders of a material wearing `library`: a `UsdPrimvarReader_float2` reading
/// `st`, and a `UsdUVTexture` per map whose `scale` carries the material's own colour,
/// roughness and metalness (the normal map's scale and bias take it from [0, 1] to [−1, 1]).
fn write_textures(
    out: &mut String,
    look: &str,
    m: &Material,
    library: &LibraryMaterial,
    texture_dir: &str,
) {
    let maps = maps(library);
    let color = maps.color_factor(m.base_color);
    let roughness = maps.roughness_factor(m.roughness.clamp(0.0, 1.0));
    let metallic = m.metallic.clamp(0.0, 1.0);
    let _ = write!(
        out,
        "\n            def Shader \"TexCoord\"\n            {{\n                uniform token info:id = \"UsdPrimvarReader_float2\"\n                token inputs:varname = \"st\"\n                float2 outputs:result\n            }}\n"
    );
    let maps_written = [
        (
            MapKind::BaseColor,
            "BaseColor",
            "sRGB",
            [color[0], color[1], color[2], 1.0],
            None,
            "float3 outputs:rgb",
        ),
        (
            MapKind::MetallicRoughness,
            "MetallicRoughness",
            "raw",
            [1.0, roughness, metallic, 1.0],
            None,
            "float outputs:b\n                float outputs:g",
        ),
        (
            MapKind::Normal,
            "Normal",
            "raw",
            [2.0, 2.0, 2.0, 1.0],
            Some([-1.0, -1.0, -1.0, 0.0]),
            "float3 outputs:rgb",
        ),
    ];
    for (kind, shader, space, scale, bias, outputs) in maps_written {
        let tuple4 = |v: [f32; 4]| {
            format!(
                "({}, {}, {}, {})",
                num32(v[0]),
                num32(v[1]),
                num32(v[2]),
                num32(v[3])
            )
        };
        let bias = bias.map_or(String::new(), |b| {
            format!("                float4 inputs:bias = {}\n", tuple4(b))
        });
        let _ = write!(
            out,
            "\n            def Shader \"{shader}\"\n            {{\n                uniform token info:id = \"UsdUVTexture\"\n{bias}                asset inputs:file = @{}/{}@\n                float4 inputs:scale = {}\n                token inputs:sourceColorSpace = \"{space}\"\n                float2 inputs:st.connect = <{look}/TexCoord.outputs:result>\n                token inputs:wrapS = \"repeat\"\n                token inputs:wrapT = \"repeat\"\n                {outputs}\n            }}\n",
            texture_dir,
            textures::file_name(library, kind),
            tuple4(scale),
        );
    }
}

/// One `Mesh` prim per part with triangles. With `collision`, each also collides
/// (`PhysicsCollisionAPI`, as its convex hull).
fn write_meshes(out: &mut String, mesh: &Mesh, looks: &Looks, collision: bool) {
    let mut names = Identifiers::new(false);
    for part in mesh.parts.iter().filter(|p| !p.triangles.is_empty()) {
        let material = worn(part, &mesh.materials[part.material]);
        let material = &*material;
        let mapping = Mapping::of(part, material);
        let shaded = shade(part, mapping);
        let mut min = [f32::INFINITY; 3];
        let mut max = [f32::NEG_INFINITY; 3];
        for p in &shaded.positions {
            for k in 0..3 {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
            }
        }
        let _ = write!(
            out,
            "\n        def Mesh {} (\n            prepend apiSchemas = [\"MaterialBindingAPI\"{}]\n        )\n        {{\n            uniform bool doubleSided = 0\n            float3[] extent = [{}, {}]\n",
            quote(&names.make(&part.name)),
            if collision {
                ", \"PhysicsCollisionAPI\", \"PhysicsMeshCollisionAPI\""
            } else {
                ""
            },
            tuple(&min),
            tuple(&max),
        );
        if collision {
            out.push_str("            uniform token physics:approximation = \"convexHull\"\n");
        }
        let counts = vec!["3"; shaded.indices.len() / 3].join(", ");
        let _ = writeln!(out, "            int[] faceVertexCounts = [{counts}]");
        let indices: Vec<String> = shaded.indices.iter().map(|i| i.to_string()).collect();
        let _ = writeln!(
            out,
            "            int[] faceVertexIndices = [{}]",
            indices.join(", ")
        );
        let _ = writeln!(
            out,
            "            rel material:binding = <{}>",
            looks.path(material)
        );
        let normals: Vec<String> = shaded.normals.iter().map(tuple).collect();
        let _ = writeln!(
            out,
            "            normal3f[] normals = [{}] (\n                interpolation = \"vertex\"\n            )",
            normals.join(", ")
        );
        let points: Vec<String> = shaded.positions.iter().map(tuple).collect();
        let _ = writeln!(
            out,
            "            point3f[] points = [{}]",
            points.join(", ")
        );
        if !shaded.uvs.is_empty() {
            // An image's coordinates have v down from its top (glTF's way); USD's t runs up.
            let flip = matches!(mapping, Mapping::Image(_));
            let st: Vec<String> = shaded
                .uvs
                .iter()
                .map(|uv| {
                    let t = if flip { 1.0 - uv[1] } else { uv[1] };
                    format!("({}, {})", num32(uv[0]), num32(t))
                })
                .collect();
            let _ = writeln!(
                out,
                "            texCoord2f[] primvars:st = [{}] (\n                interpolation = \"vertex\"\n            )",
                st.join(", ")
            );
        }
        let c = material.base_color;
        let _ = writeln!(
            out,
            "            color3f[] primvars:displayColor = [({}, {}, {})]",
            num32(c[0]),
            num32(c[1]),
            num32(c[2])
        );
        out.push_str("            uniform token subdivisionScheme = \"none\"\n        }\n");
    }
}

/// [`write_meshes`] into a string of its own.
fn meshes_text(mesh: &Mesh, looks: &Looks, collision: bool) -> String {
    let mut text = String::new();
    write_meshes(&mut text, mesh, looks, collision);
    text
}

fn tuple(v: &[f32; 3]) -> String {
    format!("({}, {}, {})", num32(v[0]), num32(v[1]), num32(v[2]))
}

/// A USD string literal.
fn quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            // Other control characters never go into the file raw.
            c if c.is_ascii_control() => {
                let _ = write!(out, "\\x{:02x}", c as u32);
            }
            c if c.is_control() => out.push('\u{fffd}'),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}
