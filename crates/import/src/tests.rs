//! Import tests: every file is written here, byte by byte, into a temporary directory.

use std::path::Path;

use serde_json::json;

use super::*;
use scenethesis_scene_graph::SurfaceKind;

/// One glTF mesh primitive: positions and triangle indices, with a material index.
struct Prim {
    positions: Vec<[f32; 3]>,
    indices: Vec<u32>,
    material: usize,
}

/// An axis-aligned box from `min` to `max`, outward triangles.
fn box_prim(min: [f32; 3], max: [f32; 3], material: usize) -> Prim {
    let part = scenethesis_primitives::cuboid("b", 0, min, max);
    Prim {
        positions: part.positions,
        indices: part.triangles.iter().flatten().copied().collect(),
        material,
    }
}

/// Builds a glTF document (JSON) and its binary buffer. `nodes` are (mesh index, translation,
/// scale, children); node 0 is the scene root.
fn gltf_document(
    meshes: &[Vec<Prim>],
    nodes: serde_json::Value,
    uri: Option<&str>,
) -> (serde_json::Value, Vec<u8>) {
    let mut bin = Vec::new();
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut json_meshes = Vec::new();
    for prims in meshes {
        let mut json_prims = Vec::new();
        for p in prims {
            let offset = bin.len();
            for v in &p.positions {
                for c in v {
                    bin.extend_from_slice(&c.to_le_bytes());
                }
            }
            let (mut min, mut max) = ([f32::MAX; 3], [f32::MIN; 3]);
            for v in &p.positions {
                for k in 0..3 {
                    min[k] = min[k].min(v[k]);
                    max[k] = max[k].max(v[k]);
                }
            }
            views.push(
                json!({"buffer": 0, "byteOffset": offset, "byteLength": p.positions.len() * 12}),
            );
            accessors.push(json!({"bufferView": views.len() - 1, "componentType": 5126, "count": p.positions.len(), "type": "VEC3", "min": min, "max": max}));
            let pos = accessors.len() - 1;
            let offset = bin.len();
            for i in &p.indices {
                bin.extend_from_slice(&i.to_le_bytes());
            }
            views.push(
                json!({"buffer": 0, "byteOffset": offset, "byteLength": p.indices.len() * 4}),
            );
            accessors.push(json!({"bufferView": views.len() - 1, "componentType": 5125, "count": p.indices.len(), "type": "SCALAR"}));
            json_prims.push(json!({"attributes": {"POSITION": pos}, "indices": accessors.len() - 1, "material": p.material}));
        }
        json_meshes.push(json!({"primitives": json_prims}));
    }
    let mut buffer = json!({"byteLength": bin.len()});
    if let Some(uri) = uri {
        buffer["uri"] = json!(uri);
    }
    let doc = json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": nodes,
        "meshes": json_meshes,
        "materials": [
            {"name": "oak", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.4, 0.2, 1.0], "roughnessFactor": 0.7, "metallicFactor": 0.0}},
            {"name": "steel", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1.0], "roughnessFactor": 0.3, "metallicFactor": 1.0}}
        ],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [buffer],
    });
    (doc, bin)
}

/// Packs a document and its buffer into GLB bytes (header, JSON chunk, BIN chunk).
fn glb_bytes(doc: &serde_json::Value, bin: &[u8]) -> Vec<u8> {
    let mut json = serde_json::to_vec(doc).unwrap();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    let mut bin = bin.to_vec();
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}

/// A side table modelled Z-up in centimetres, facing −X: a 60 × 40 top 70 cm high (z), four
/// steel legs as child nodes placed by translation.
fn table_in_centimetres() -> (serde_json::Value, Vec<u8>) {
    let top = vec![box_prim([-30.0, -20.0, 67.0], [30.0, 20.0, 70.0], 0)];
    let leg = vec![box_prim([-2.0, -2.0, 0.0], [2.0, 2.0, 67.0], 1)];
    let nodes = json!([
        {"name": "table", "mesh": 0, "children": [1, 2, 3, 4], "translation": [100.0, 50.0, 5.0]},
        {"name": "leg0", "mesh": 1, "translation": [-27.0, -17.0, -0.0]},
        {"name": "leg1", "mesh": 1, "translation": [27.0, -17.0, 0.0]},
        {"name": "leg2", "mesh": 1, "translation": [-27.0, 17.0, 0.0]},
        {"name": "leg3", "mesh": 1, "translation": [27.0, 17.0, 0.0]}
    ]);
    gltf_document(&[top, leg], nodes, None)
}

fn write(dir: &Path, name: &str, bytes: &[u8]) {
    std::fs::write(dir.join(name), bytes).unwrap();
}

#[test]
fn glb_is_normalised_to_metres_y_up_front_z_with_a_found_table_top() {
    let dir = tempfile::tempdir().unwrap();
    let (doc, bin) = table_in_centimetres();
    write(dir.path(), "table.glb", &glb_bytes(&doc, &bin));
    write(
        dir.path(),
        MANIFEST_FILE,
        json!([{"file": "table.glb", "category": "side_table", "synonyms": ["end table"], "up_axis": "z", "unit_scale": 0.01, "front": "-x"}])
            .to_string()
            .as_bytes(),
    );
    let report = import_directory(dir.path()).unwrap();
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    assert_eq!(report.assets.len(), 1);
    let asset = &report.assets[0];
    assert_eq!(asset.mesh.parts.len(), 5, "one part per primitive per node");
    // 60 cm along file x (the depth axis once the −X front turns to +Z), 40 cm along file y.
    let [w, h, d] = asset.info.size;
    assert!(
        (w - 0.4).abs() < 1e-4 && (h - 0.7).abs() < 1e-4 && (d - 0.6).abs() < 1e-4,
        "{:?}",
        asset.info.size
    );
    let b = asset.mesh.bounds().unwrap();
    assert!(
        b.min.y.abs() < 1e-6
            && (b.min.x + b.max.x).abs() < 1e-5
            && (b.min.z + b.max.z).abs() < 1e-5
    );
    assert_eq!(asset.info.front, [0.0, 0.0, 1.0]);
    assert_eq!(
        asset.info.placement,
        scenethesis_scene_graph::Placement::Floor
    );
    assert_eq!(asset.info.category, "side_table");
    assert_eq!(asset.info.synonyms, vec!["end table".to_string()]);
    match &asset.info.source {
        scenethesis_scene_graph::AssetRef::Imported { id, path } => {
            assert_eq!(id, "table");
            assert!(path.ends_with("table.glb"));
        }
        other => panic!("unexpected source {other:?}"),
    }
    let steel = asset
        .mesh
        .materials
        .iter()
        .find(|m| m.name == "steel")
        .unwrap();
    assert_eq!((steel.roughness, steel.metallic), (0.3, 1.0));
    let top = asset
        .info
        .support_surfaces
        .iter()
        .find(|s| s.kind == SurfaceKind::Top)
        .expect("table top found");
    assert!((top.height - 0.7).abs() < 1e-4, "{top:?}");
    assert!(
        (top.area() - 0.38 * 0.58).abs() < 2e-3,
        "area {}",
        top.area()
    );
    // The legs (file −X side is the front) end up under the top; every part is still closed.
    assert!(asset.mesh.parts.iter().all(|p| p.is_closed_and_oriented()));
}

#[test]
fn gltf_with_external_buffer_and_mirrored_node_keeps_outward_faces() {
    let dir = tempfile::tempdir().unwrap();
    let nodes = json!([{"name": "crate", "mesh": 0, "scale": [-1.0, 1.0, 1.0]}]);
    let (doc, bin) = gltf_document(
        &[vec![box_prim([0.0, 0.0, 0.0], [0.5, 0.4, 0.3], 0)]],
        nodes,
        Some("crate%20data.bin"),
    );
    write(
        dir.path(),
        "crate.gltf",
        serde_json::to_string(&doc).unwrap().as_bytes(),
    );
    write(dir.path(), "crate data.bin", &bin);
    let mesh = load_mesh(&dir.path().join("crate.gltf")).unwrap();
    assert_eq!(mesh.parts.len(), 1);
    assert!(mesh.parts[0].is_closed_and_oriented());
    assert!(
        mesh.parts[0].signed_volume() > 0.0,
        "a mirroring node must not turn faces inward"
    );
    let b = mesh.bounds().unwrap();
    assert!((b.min.x + 0.5).abs() < 1e-6, "scale −1 on x applied");
}

#[test]
fn obj_with_mtl_imports_with_its_colours_and_an_open_box_interior() {
    let dir = tempfile::tempdir().unwrap();
    // An open-top bin 40 × 30 (h) × 40 units, in millimetres/10 (unit_scale 0.01), drawn as
    // quads: a floor slab and four wall slabs.
    let mut obj = String::from("mtllib bin.mtl\nusemtl blue\n");
    let mut base = 0;
    let mut slab = |min: [f32; 3], max: [f32; 3], obj: &mut String| {
        let p = scenethesis_primitives::cuboid("s", 0, min, max);
        for v in &p.positions {
            obj.push_str(&format!("v {} {} {}\n", v[0], v[1], v[2]));
        }
        for t in &p.triangles {
            obj.push_str(&format!(
                "f {} {} {}\n",
                t[0] + 1 + base,
                t[1] + 1 + base,
                t[2] + 1 + base
            ));
        }
        base += p.positions.len() as u32;
    };
    slab([-20.0, 0.0, -20.0], [20.0, 2.0, 20.0], &mut obj);
    slab([-20.0, 0.0, -20.0], [20.0, 30.0, -19.0], &mut obj);
    slab([-20.0, 0.0, 19.0], [20.0, 30.0, 20.0], &mut obj);
    slab([-20.0, 0.0, -20.0], [-19.0, 30.0, 20.0], &mut obj);
    slab([19.0, 0.0, -20.0], [20.0, 30.0, 20.0], &mut obj);
    write(dir.path(), "bin.obj", obj.as_bytes());
    write(
        dir.path(),
        "bin.mtl",
        b"newmtl blue\nKd 0.1 0.2 0.8\nNs 10\n",
    );
    write(
        dir.path(),
        MANIFEST_FILE,
        json!({"assets": [{"file": "bin.obj", "id": "blue_bin", "category": "storage_bin", "unit_scale": 0.01}]}).to_string().as_bytes(),
    );
    let report = import_directory(dir.path()).unwrap();
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    let asset = &report.assets[0];
    assert_eq!(asset.mesh.materials[0].base_color, [0.1, 0.2, 0.8, 1.0]);
    assert!((asset.info.size[1] - 0.3).abs() < 1e-5);
    let interior = asset
        .info
        .support_surfaces
        .iter()
        .find(|s| s.kind == SurfaceKind::Interior)
        .expect("interior found");
    assert!((interior.height - 0.02).abs() < 1e-4);
    assert!(interior.clearance.is_none());
}

#[test]
fn broken_and_missing_files_are_skipped_with_a_warning_naming_them() {
    let dir = tempfile::tempdir().unwrap();
    let (doc, bin) = table_in_centimetres();
    write(dir.path(), "good.glb", &glb_bytes(&doc, &bin));
    write(dir.path(), "broken.glb", b"glTF\x02\x00\x00\x00garbage");
    write(dir.path(), "bad.obj", b"v 0 0 0\nf 1 2 3\n");
    write(
        dir.path(),
        MANIFEST_FILE,
        json!([
            {"file": "broken.glb", "category": "chair"},
            {"file": "missing.obj", "category": "chair"},
            {"file": "bad.obj", "category": "chair"},
            {"file": "good.glb", "category": "side_table", "up_axis": "z", "unit_scale": 0.01},
            {"file": "good.glb", "category": "side_table", "up_axis": "z", "unit_scale": 0.01}
        ])
        .to_string()
        .as_bytes(),
    );
    let report = import_directory(dir.path()).unwrap();
    assert_eq!(report.assets.len(), 2, "the good file is still imported");
    let ids: Vec<String> = report
        .assets
        .iter()
        .map(|a| match &a.info.source {
            scenethesis_scene_graph::AssetRef::Imported { id, .. } => id.clone(),
            _ => unreachable!(),
        })
        .collect();
    assert_eq!(ids, vec!["good", "good_2"], "ids are unique");
    assert_eq!(report.warnings.len(), 3);
    for (w, name) in report
        .warnings
        .iter()
        .zip(["broken.glb", "missing.obj", "bad.obj"])
    {
        assert!(
            w.path.ends_with(name) || w.path.ends_with(MANIFEST_FILE),
            "{w}"
        );
        assert!(w.to_string().contains(name));
    }
    assert!(
        report.warnings[2].reason.contains("line 2"),
        "{}",
        report.warnings[2]
    );
}

#[test]
fn manifest_errors_and_directories_without_a_manifest() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), MANIFEST_FILE, b"{\"file\": 3}");
    let e = import_directory(dir.path()).unwrap_err();
    assert!(e.to_string().contains("assets.json"), "{e}");
    assert!(e.to_string().contains("`assets` array"), "{e}");
    // A bad entry is skipped with a warning naming the entry and the field.
    write(
        dir.path(),
        MANIFEST_FILE,
        b"[{\"file\": 3, \"category\": \"x\"}]",
    );
    let report = import_directory(dir.path()).unwrap();
    assert!(report.assets.is_empty());
    assert_eq!(report.warnings.len(), 1);
    let w = report.warnings[0].to_string();
    assert!(w.contains("entry #0") && w.contains("field `file`"), "{w}");
    assert!(!w.contains("untagged"), "{w}");
    let dir = tempfile::tempdir().unwrap();
    let (doc, bin) = gltf_document(
        &[vec![box_prim([0.0; 3], [0.4, 0.5, 0.4], 0)]],
        json!([{"mesh": 0}]),
        None,
    );
    write(dir.path(), "stool.glb", &glb_bytes(&doc, &bin));
    write(dir.path(), "notes.txt", b"not a mesh");
    let report = import_directory(dir.path()).unwrap();
    assert_eq!(report.assets.len(), 1);
    assert_eq!(report.assets[0].info.category, "stool");
    assert_eq!(
        report.warnings.len(),
        1,
        "one note that no manifest was found"
    );
    assert!(import_directory(dir.path().join("nope")).is_err());
}

/// A one-triangle glTF document with the given nodes, positions and (optional) buffer URI.
fn triangle_doc(
    nodes: serde_json::Value,
    positions: Vec<[f32; 3]>,
) -> (serde_json::Value, Vec<u8>) {
    let prim = Prim {
        positions,
        indices: vec![0, 1, 2],
        material: 0,
    };
    gltf_document(&[vec![prim]], nodes, None)
}

fn good_triangle() -> Vec<[f32; 3]> {
    vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
}

fn import_one(dir: &Path, name: &str, bytes: &[u8], entry: serde_json::Value) -> ImportReport {
    write(dir, name, bytes);
    write(dir, MANIFEST_FILE, json!([entry]).to_string().as_bytes());
    import_directory(dir).unwrap()
}

fn only_warning(report: &ImportReport) -> String {
    assert!(report.assets.is_empty(), "nothing may be imported");
    assert_eq!(report.warnings.len(), 1, "{:?}", report.warnings);
    report.warnings[0].to_string()
}

#[test]
fn a_node_cycle_is_refused_not_a_stack_overflow() {
    let dir = tempfile::tempdir().unwrap();
    let nodes = json!([
        {"name": "a", "mesh": 0, "children": [1]},
        {"name": "b", "children": [0]}
    ]);
    let (doc, bin) = triangle_doc(nodes, good_triangle());
    // glTF validation may refuse the cycle itself; either way it is a warning, not a crash.
    let r = import_one(
        dir.path(),
        "cycle.glb",
        &glb_bytes(&doc, &bin),
        json!({"file": "cycle.glb", "category": "x"}),
    );
    let w = only_warning(&r);
    assert!(w.contains("cycle.glb"), "{w}");
    // Exponential sharing (each node lists the next twice) is bounded by the instance limit.
    let mut nodes = Vec::new();
    for k in 0..40 {
        nodes.push(json!({"mesh": 0, "children": [k + 1, k + 1]}));
    }
    nodes.push(json!({"mesh": 0}));
    let (doc, bin) = triangle_doc(json!(nodes), good_triangle());
    let r = import_one(
        dir.path(),
        "fan.glb",
        &glb_bytes(&doc, &bin),
        json!({"file": "fan.glb", "category": "x"}),
    );
    let w = only_warning(&r);
    assert!(w.contains("limit"), "{w}");
}

#[test]
fn nan_vertices_absurd_transforms_and_zero_area_meshes_are_skipped() {
    let dir = tempfile::tempdir().unwrap();
    let nan = vec![[0.0, 0.0, 0.0], [f32::NAN, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let (doc, bin) = triangle_doc(json!([{"mesh": 0}]), nan);
    let w = only_warning(&import_one(
        dir.path(),
        "nan.glb",
        &glb_bytes(&doc, &bin),
        json!({"file": "nan.glb", "category": "x"}),
    ));
    assert!(w.contains("accessors[0]") && w.contains("NaN"), "{w}");
    let (doc, bin) = triangle_doc(
        json!([{"mesh": 0, "scale": [1e30, 1e30, 1e30]}]),
        good_triangle(),
    );
    let w = only_warning(&import_one(
        dir.path(),
        "huge.glb",
        &glb_bytes(&doc, &bin),
        json!({"file": "huge.glb", "category": "x"}),
    ));
    assert!(w.contains("nodes[0]"), "{w}");
    let (doc, bin) = triangle_doc(
        json!([{"mesh": 0, "translation": [1e300, 0.0, 0.0]}]),
        good_triangle(),
    );
    let w = only_warning(&import_one(
        dir.path(),
        "far.glb",
        &glb_bytes(&doc, &bin),
        json!({"file": "far.glb", "category": "x"}),
    ));
    assert!(w.contains("out of range"), "{w}");
    let (doc, bin) = triangle_doc(
        json!([{"mesh": 0, "translation": [1e20, 0.0, 0.0]}]),
        good_triangle(),
    );
    let w = only_warning(&import_one(
        dir.path(),
        "farther.glb",
        &glb_bytes(&doc, &bin),
        json!({"file": "farther.glb", "category": "x"}),
    ));
    assert!(w.contains("nodes[0]"), "{w}");
    let flat = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
    let (doc, bin) = triangle_doc(json!([{"mesh": 0}]), flat);
    let w = only_warning(&import_one(
        dir.path(),
        "flat.glb",
        &glb_bytes(&doc, &bin),
        json!({"file": "flat.glb", "category": "x"}),
    ));
    assert!(w.contains("zero surface area"), "{w}");
    // 60 m wide once scaled: over the asset size limit.
    let (doc, bin) = triangle_doc(json!([{"mesh": 0}]), good_triangle());
    let w = only_warning(&import_one(
        dir.path(),
        "big.glb",
        &glb_bytes(&doc, &bin),
        json!({"file": "big.glb", "category": "x", "unit_scale": 60.0}),
    ));
    assert!(w.contains("larger than the limit"), "{w}");
}

#[test]
fn truncated_files_and_dev_zero_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let (doc, bin) = table_in_centimetres();
    let bytes = glb_bytes(&doc, &bin);
    for cut in [10, 40, bytes.len() / 2, bytes.len() - 4] {
        let w = only_warning(&import_one(
            dir.path(),
            "cut.glb",
            &bytes[..cut],
            json!({"file": "cut.glb", "category": "x"}),
        ));
        assert!(w.contains("cut.glb"), "{w}");
    }
    #[cfg(unix)]
    {
        let e = GltfFile::read(Path::new("/dev/zero"), None).unwrap_err();
        assert!(e.to_string().contains("expected a regular file"), "{e}");
        let big = dir.path().join("big.glb");
        std::fs::write(&big, vec![0u8; 2000]).unwrap();
        let e = scenethesis_scene_graph::read_bounded(&big, 1000).unwrap_err();
        assert_eq!(e.kind(), std::io::ErrorKind::FileTooLarge);
        assert!(e.to_string().contains("limit of 1000 bytes"), "{e}");
    }
}

#[test]
fn asset_packs_cannot_reach_outside_their_folder() {
    let outer = tempfile::tempdir().unwrap();
    let pack = outer.path().join("pack");
    std::fs::create_dir(&pack).unwrap();
    let (doc, bin) = table_in_centimetres();
    write(outer.path(), "secret.glb", &glb_bytes(&doc, &bin));
    write(outer.path(), "secret.bin", &bin);
    let abs = outer.path().join("secret.glb");
    let (gltf_doc, _) = gltf_document(
        &[vec![box_prim([0.0; 3], [1.0; 3], 0)]],
        json!([{"mesh": 0}]),
        Some("../secret.bin"),
    );
    write(
        &pack,
        "escape.gltf",
        serde_json::to_string(&gltf_doc).unwrap().as_bytes(),
    );
    write(&pack, "ok.glb", &glb_bytes(&doc, &bin));
    write(
        &pack,
        MANIFEST_FILE,
        json!([
            {"file": "../secret.glb", "category": "a"},
            {"file": abs.to_str().unwrap(), "category": "b"},
            {"file": "escape.gltf", "category": "c"},
            {"file": "ok.glb", "category": "d", "scale_range": [2.0, 1.0]},
            {"file": "ok.glb", "category": "e", "up_axis": "z", "unit_scale": 0.01}
        ])
        .to_string()
        .as_bytes(),
    );
    let report = import_directory(&pack).unwrap();
    assert_eq!(report.assets.len(), 1, "{:?}", report.warnings);
    assert_eq!(report.assets[0].info.category, "e");
    match &report.assets[0].info.source {
        scenethesis_scene_graph::AssetRef::Imported { path, .. } => {
            assert!(Path::new(path).is_absolute(), "stored canonical: {path}");
        }
        other => panic!("{other:?}"),
    }
    let text: Vec<String> = report.warnings.iter().map(|w| w.to_string()).collect();
    assert_eq!(text.len(), 4, "{text:?}");
    assert!(
        text[0].contains("entry #0") && text[0].contains("outside the asset folder"),
        "{}",
        text[0]
    );
    assert!(
        text[1].contains("entry #1") && text[1].contains("absolute"),
        "{}",
        text[1]
    );
    assert!(
        text[2].contains("buffers[0].uri") && text[2].contains("outside the asset folder"),
        "{}",
        text[2]
    );
    assert!(
        text[3].contains("entry #3") && text[3].contains("scale_range"),
        "{}",
        text[3]
    );
}

#[test]
fn the_resolver_finds_imported_assets_from_any_working_directory() {
    let dir = tempfile::tempdir().unwrap();
    let (doc, bin) = table_in_centimetres();
    write(dir.path(), "table.glb", &glb_bytes(&doc, &bin));
    write(
        dir.path(),
        MANIFEST_FILE,
        json!([{"file": "table.glb", "id": "t", "category": "side_table", "up_axis": "z", "unit_scale": 0.01}])
            .to_string()
            .as_bytes(),
    );
    let report = import_directory(dir.path()).unwrap();
    let source = report.assets[0].info.source.clone();
    let mut resolver = AssetResolver::new();
    let mesh = resolver.mesh(&source).unwrap();
    assert_eq!(mesh, report.assets[0].mesh);
    let missing = scenethesis_scene_graph::AssetRef::Imported {
        id: "nope".into(),
        path: dir.path().join("table.glb").display().to_string(),
    };
    let e = resolver.mesh(&missing).unwrap_err().to_string();
    assert!(e.contains("no longer holds"), "{e}");
    let unknown = scenethesis_scene_graph::AssetRef::Procedural {
        generator: "warp_drive".into(),
        seed: 1,
        look: None,
    };
    assert!(resolver.mesh(&unknown).is_err());
}

#[test]
fn a_position_accessor_index_past_the_end_is_an_error_not_a_panic_in_gltf_json() {
    // Found by the fuzz target: the gltf crate's own validation indexes this without a check.
    let doc = json!({
        "asset": {"version": "2.0"},
        "meshes": [{"primitives": [{"attributes": {"POSITION": 5}}]}],
        "nodes": [{"mesh": 0}],
    });
    let e = GltfFile::from_slice(doc.to_string().as_bytes(), Path::new("."), Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(e.contains("meshes[0].primitives[0].attributes"), "{e}");
}

#[test]
fn repeated_and_degenerate_triangles_are_dropped_before_the_distance_field() {
    let dir = tempfile::tempdir().unwrap();
    // 20 000 copies of one triangle, each with its own three vertices.
    let mut obj = String::new();
    for k in 0..20_000 {
        obj.push_str("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
        obj.push_str(&format!("f {} {} {}\n", 3 * k + 1, 3 * k + 2, 3 * k + 3));
    }
    let report = import_one(
        dir.path(),
        "same.obj",
        obj.as_bytes(),
        json!({"file": "same.obj", "category": "x"}),
    );
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    let mesh = &report.assets[0].mesh;
    assert_eq!(
        (mesh.triangle_count(), mesh.parts[0].positions.len()),
        (1, 3)
    );
    // Only lines and repeated corners: nothing is left, and the warning names the file.
    let obj = "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\nf 3 2 1\n";
    let w = only_warning(&import_one(
        dir.path(),
        "lines.obj",
        obj.as_bytes(),
        json!({"file": "lines.obj", "category": "x"}),
    ));
    assert!(
        w.contains("lines.obj") && w.contains("no triangle is left after dropping"),
        "{w}"
    );
}

mod joints;

/// PNG bytes of a `w` × `h` image of one sRGB colour.
fn png_of(w: u32, h: u32, rgb: [u8; 3]) -> Vec<u8> {
    let image = image::RgbImage::from_pixel(w, h, image::Rgb(rgb));
    let mut bytes = Vec::new();
    image
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .unwrap();
    bytes
}

/// The side table with its `oak` material (base colour 0.6, 0.4, 0.2) textured by an image at
/// `uri`: a file next to it or a data URI.
fn textured_table(uri: &str) -> Vec<u8> {
    let (mut doc, bin) = table_in_centimetres();
    doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = json!({"index": 0});
    doc["textures"] = json!([{"source": 0}]);
    doc["images"] = json!([{"uri": uri}]);
    glb_bytes(&doc, &bin)
}

fn import_table(dir: &Path, glb: &[u8]) -> ImportReport {
    import_one(
        dir,
        "table.glb",
        glb,
        json!({"file": "table.glb", "category": "side_table", "up_axis": "z", "unit_scale": 0.01}),
    )
}

#[test]
fn a_readable_texture_is_kept_and_shows_as_its_mean_colour_where_no_part_maps_it() {
    let dir = tempfile::tempdir().unwrap();
    // sRGB 188 is linear ~0.5: the oak factor is halved.
    write(dir.path(), "oak.png", &png_of(4, 4, [188, 188, 188]));
    let report = import_table(dir.path(), &textured_table("oak.png"));
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    let oak = &report.assets[0].mesh.materials[0];
    assert_eq!(oak.name, "oak");
    assert!(oak.texture.is_some(), "the image is kept");
    assert_eq!(
        oak.base_color,
        [0.6, 0.4, 0.2, 1.0],
        "the factor stays the factor"
    );
    // The table has no TEXCOORD_0: its parts keep no coordinates and show the flat colour.
    assert!(report.assets[0].mesh.parts.iter().all(|p| p.uvs.is_none()));
    let expected = [0.6, 0.4, 0.2].map(|c| c * 0.5029);
    for (got, want) in oak.flat_color().iter().zip(expected) {
        assert!((got - want).abs() < 2e-3, "{oak:?}");
    }
}

#[test]
fn a_missing_or_broken_texture_is_one_warning_naming_the_file_and_a_plain_material() {
    for (file, bytes, says) in [
        ("missing.png", None, "missing.png"),
        (
            "broken.png",
            Some(b"\x89PNG not really".to_vec()),
            "broken.png",
        ),
        ("../outside.png", None, "outside the asset folder"),
    ] {
        // The pack is a folder inside `root`, where a readable image sits just outside it.
        let root = tempfile::tempdir().unwrap();
        write(root.path(), "outside.png", &png_of(2, 2, [0, 0, 0]));
        let pack = root.path().join("pack");
        std::fs::create_dir(&pack).unwrap();
        if let Some(bytes) = bytes {
            write(&pack, file, &bytes);
        }
        let report = import_table(&pack, &textured_table(file));
        assert_eq!(report.assets.len(), 1, "the asset still imports ({file})");
        assert_eq!(report.warnings.len(), 1, "{:?}", report.warnings);
        let warning = report.warnings[0].to_string();
        assert!(warning.contains("table.glb"), "names the asset: {warning}");
        assert!(warning.contains(says), "names the texture: {warning}");
        assert!(warning.contains("`oak`"), "names the material: {warning}");
        let oak = &report.assets[0].mesh.materials[0];
        assert_eq!(
            oak.base_color,
            [0.6, 0.4, 0.2, 1.0],
            "plain factor ({file})"
        );
        assert!(oak.texture.is_none(), "no image ({file})");
    }
}

#[test]
fn obj_diffuse_textures_tint_or_warn() {
    let dir = tempfile::tempdir().unwrap();
    let p = scenethesis_primitives::cuboid("s", 0, [0.0, 0.0, 0.0], [1.0, 1.0, 1.0]);
    let mut obj = String::from("mtllib box.mtl\n");
    for v in &p.positions {
        obj.push_str(&format!("v {} {} {}\n", v[0], v[1], v[2]));
    }
    for (k, t) in p.triangles.iter().enumerate() {
        let material = if k < 6 { "painted" } else { "lost" };
        obj.push_str(&format!(
            "usemtl {material}\nf {} {} {}\n",
            t[0] + 1,
            t[1] + 1,
            t[2] + 1
        ));
    }
    write(dir.path(), "box.obj", obj.as_bytes());
    write(
        dir.path(),
        "box.mtl",
        b"newmtl painted\nKd 1 1 1\nmap_Kd -s 1 1 1 red.png\nnewmtl lost\nKd 0.5 0.5 0.5\nmap_Kd gone.jpg\n",
    );
    write(dir.path(), "red.png", &png_of(2, 2, [255, 0, 0]));
    let report = import_directory(dir.path()).unwrap();
    let asset = &report.assets[0];
    let colour = |name: &str| {
        asset
            .mesh
            .materials
            .iter()
            .find(|m| m.name == name)
            .unwrap()
            .flat_color()
    };
    assert_eq!(colour("painted"), [1.0, 0.0, 0.0, 1.0]);
    assert_eq!(colour("lost"), [0.5, 0.5, 0.5, 1.0]);
    let texture_warnings: Vec<String> = report
        .warnings
        .iter()
        .map(ToString::to_string)
        .filter(|w| w.contains("texture"))
        .collect();
    assert_eq!(texture_warnings.len(), 1, "{:?}", report.warnings);
    assert!(
        texture_warnings[0].contains("gone.jpg") && texture_warnings[0].contains("box.obj"),
        "{texture_warnings:?}"
    );
}

#[test]
fn obj_texture_coordinates_are_kept_for_a_textured_material_and_v_flipped() {
    let dir = tempfile::tempdir().unwrap();
    write(
        dir.path(),
        "quad.mtl",
        b"newmtl tiles\nKd 1 1 1\nmap_Kd tiles.png\n",
    );
    write(dir.path(), "tiles.png", &png_of(2, 2, [200, 100, 50]));
    // A closed tetrahedron whose corner 1 has two texture coordinates (a seam).
    let obj = "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n\
               vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nvt 0.5 0.25\n\
               usemtl tiles\nf 1/1 3/3 2/2\nf 1/1 2/5 4/4\nf 1/1 4/4 3/3\nf 2/2 3/3 4/4\n";
    write(dir.path(), "quad.obj", obj.as_bytes());
    let report = import_directory(dir.path()).unwrap();
    let mesh = &report.assets[0].mesh;
    assert!(mesh.materials[0].texture.is_some());
    let part = &mesh.parts[0];
    let uvs = part.uvs.as_ref().expect("the part keeps its coordinates");
    assert_eq!(uvs.len(), part.positions.len());
    assert_eq!(part.positions.len(), 5, "vertex 2 is split at its seam");
    assert!(
        uvs.contains(&[0.5, 0.75]),
        "v flipped to glTF's v down: {uvs:?}"
    );
    // The same file without its image: no coordinates, one vertex per position, as before.
    std::fs::remove_file(dir.path().join("tiles.png")).unwrap();
    let report = import_directory(dir.path()).unwrap();
    let part = &report.assets[0].mesh.parts[0];
    assert!(part.uvs.is_none());
    assert_eq!(part.positions.len(), 4);
}
