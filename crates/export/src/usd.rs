//! OpenUSD text (`.usda`) writer.
//!
//! The layer's default prim `/World` holds one `Xform` per architecture piece (geometry in world
//! coordinates) and per object (translate / rotateY / scale ops from its pose, geometry in the
//! asset frame), each with one `Mesh` per part bound to a `UsdPreviewSurface` material under
//! `/World/Looks`. Stage metadata: `upAxis = "Y"`, `metersPerUnit = 1`. Prim names are the ids
//! when they are valid USD identifiers, otherwise sanitised; the original id is kept in the
//! custom attribute `scenethesis:id`.

use std::collections::BTreeMap;
use std::fmt::Write;

use crate::architecture::pieces;
use crate::geometry::{num, num32, shade, Identifiers};
use crate::ExportScene;
use scenethesis_scene_graph::{Material, Mesh};

/// The scene as a USD text layer.
pub fn to_usda(export: &ExportScene<'_>) -> String {
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
    let arch: Vec<(String, Mesh)> = pieces(&scene.architecture)
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
    out.push_str("    def Scope \"Looks\"\n    {\n");
    for (name, m) in &looks.materials {
        write_material(&mut out, name, m);
    }
    out.push_str("    }\n");

    let mut prims = Identifiers::new(false);
    prims.reserve("Looks");
    for (id, mesh) in &arch {
        let name = prims.make(id);
        let _ = write!(
            out,
            "\n    def Xform {}\n    {{\n        custom string scenethesis:id = {}\n        custom string scenethesis:kind = \"architecture\"\n",
            quote(&name),
            quote(id)
        );
        write_meshes(&mut out, mesh, &looks);
        out.push_str("    }\n");
    }
    for object in &scene.objects {
        let name = prims.make(&object.id);
        let pose = &object.pose;
        let t = pose.translation;
        let _ = write!(
            out,
            "\n    def Xform {}\n    {{\n        custom string scenethesis:id = {}\n        custom string scenethesis:category = {}\n        custom string scenethesis:parent = {}\n        custom string scenethesis:support = {}\n        double3 xformOp:translate = ({}, {}, {})\n        double xformOp:rotateY = {}\n        double3 xformOp:scale = ({s}, {s}, {s})\n        uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:rotateY\", \"xformOp:scale\"]\n",
            quote(&name),
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
        write_meshes(&mut out, export.mesh(object), &looks);
        out.push_str("    }\n");
    }
    out.push_str("}\n");
    out
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
    fn key(m: &Material) -> String {
        format!(
            "{}|{:?}|{}|{}",
            m.name,
            m.base_color.map(f32::to_bits),
            m.roughness.to_bits(),
            m.metallic.to_bits()
        )
    }

    fn register(&mut self, mesh: &Mesh) {
        for m in &mesh.materials {
            let key = Self::key(m);
            if self.by_key.contains_key(&key) {
                continue;
            }
            let name = self
                .names
                .get_or_insert_with(|| Identifiers::new(false))
                .make(&m.name);
            self.materials.push((name, m.clone()));
            self.by_key.insert(key, self.materials.len() - 1);
        }
    }

    fn path(&self, m: &Material) -> String {
        format!(
            "/World/Looks/{}",
            self.materials[self.by_key[&Self::key(m)]].0
        )
    }
}

fn write_material(out: &mut String, name: &str, m: &Material) {
    let c = m.base_color;
    let _ = write!(
        out,
        "        def Material {q}\n        {{\n            custom string scenethesis:name = {n}\n            token outputs:surface.connect = </World/Looks/{name}/PreviewSurface.outputs:surface>\n\n            def Shader \"PreviewSurface\"\n            {{\n                uniform token info:id = \"UsdPreviewSurface\"\n                color3f inputs:diffuseColor = ({}, {}, {})\n                float inputs:metallic = {}\n                float inputs:opacity = {}\n                float inputs:roughness = {}\n                token outputs:surface\n            }}\n        }}\n",
        num32(c[0]),
        num32(c[1]),
        num32(c[2]),
        num32(m.metallic),
        num32(c[3]),
        num32(m.roughness),
        q = quote(name),
        n = quote(&m.name),
    );
}

fn write_meshes(out: &mut String, mesh: &Mesh, looks: &Looks) {
    let mut names = Identifiers::new(false);
    for part in mesh.parts.iter().filter(|p| !p.triangles.is_empty()) {
        let shaded = shade(part);
        let material = &mesh.materials[part.material];
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
            "\n        def Mesh {} (\n            prepend apiSchemas = [\"MaterialBindingAPI\"]\n        )\n        {{\n            uniform bool doubleSided = 0\n            float3[] extent = [{}, {}]\n",
            quote(&names.make(&part.name)),
            tuple(&min),
            tuple(&max),
        );
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
