//! An imported asset's base-colour texture survives every export: a cube modelled in a GLB
//! whose material's `baseColorTexture` is a red and blue checker, each face mapping the whole
//! image through `TEXCOORD_0`, is imported and written in every format. The GLB is read back
//! with the workspace's glTF reader (`scenethesis_import::GltfFile`); USD, MJCF and URDF must
//! reference the written image file. When `SCENETHESIS_EXPORT_DIR` is set, the exports are
//! also written there for the consumer checks (OpenUSD, MuJoCo, the Khronos glTF validator).

use std::collections::BTreeMap;
use std::path::Path;

use nalgebra::Vector3;
use scenethesis_export::{glb, ExportScene, Format};
use scenethesis_import::{import_directory, GltfFile};
use scenethesis_scene_graph::{
    Architecture, Mesh, ParentRef, Pose, RelationKind, Scene, TextureImage,
};
use serde_json::json;

mod common;

const RED: [u8; 3] = [220, 30, 30];
const BLUE: [u8; 3] = [30, 40, 220];

/// A 4 × 4 checker of red and blue pixels as PNG bytes.
fn checker_png() -> Vec<u8> {
    let image = image::RgbImage::from_fn(4, 4, |x, y| {
        image::Rgb(if (x + y) % 2 == 0 { RED } else { BLUE })
    });
    let mut bytes = Vec::new();
    image
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .unwrap();
    bytes
}

/// A cube of side `size` standing on y = 0, four vertices per face, each face mapping the
/// whole image (glTF's v down): positions, texture coordinates, triangles.
fn textured_cube(size: f32) -> (Vec<[f32; 3]>, Vec<[f32; 2]>, Vec<u32>) {
    let h = size / 2.0;
    // (normal, u, v) with u × v = normal.
    let faces: [([f32; 3], [f32; 3], [f32; 3]); 6] = [
        ([1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]),
        ([-1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]),
        ([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]),
        ([0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([0.0, 0.0, -1.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
    ];
    let (mut positions, mut uvs, mut indices) = (Vec::new(), Vec::new(), Vec::new());
    for (n, u, v) in faces {
        let base = positions.len() as u32;
        for (su, sv, uv) in [
            (-1.0, -1.0, [0.0, 1.0]),
            (1.0, -1.0, [1.0, 1.0]),
            (1.0, 1.0, [1.0, 0.0]),
            (-1.0, 1.0, [0.0, 0.0]),
        ] {
            positions.push(std::array::from_fn(|k| {
                h * (n[k] + su * u[k] + sv * v[k]) + if k == 1 { h } else { 0.0 }
            }));
            uvs.push(uv);
        }
        indices.extend([base, base + 1, base + 2, base, base + 2, base + 3]);
    }
    (positions, uvs, indices)
}

/// The cube as a GLB: one primitive with POSITION, TEXCOORD_0 and indices, its material
/// `checker` (base colour factor white) textured by the checker PNG in the binary buffer.
fn cube_glb() -> Vec<u8> {
    let (positions, uvs, indices) = textured_cube(0.4);
    let mut bin = Vec::new();
    let mut push = |bytes: Vec<u8>| {
        while bin.len() % 4 != 0 {
            bin.push(0);
        }
        let offset = bin.len();
        bin.extend_from_slice(&bytes);
        json!({"buffer": 0, "byteOffset": offset, "byteLength": bytes.len()})
    };
    let f32s = |v: &[f32]| v.iter().flat_map(|c| c.to_le_bytes()).collect::<Vec<u8>>();
    let views = vec![
        push(f32s(&positions.concat())),
        push(f32s(&uvs.concat())),
        push(indices.iter().flat_map(|i| i.to_le_bytes()).collect()),
        push(checker_png()),
    ];
    let doc = json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "cube", "mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
        "materials": [{"name": "checker", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0, "roughnessFactor": 0.8}}],
        "textures": [{"source": 0}],
        "images": [{"bufferView": 3, "mimeType": "image/png"}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": positions.len(), "type": "VEC3",
             "min": [-0.2, 0.0, -0.2], "max": [0.2, 0.4, 0.2]},
            {"bufferView": 1, "componentType": 5126, "count": uvs.len(), "type": "VEC2"},
            {"bufferView": 2, "componentType": 5125, "count": indices.len(), "type": "SCALAR"}
        ],
        "bufferViews": views,
        "buffers": [{"byteLength": bin.len()}],
    });
    let mut json = serde_json::to_vec(&doc).unwrap();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::new();
    for word in [
        0x4654_6C67u32,
        2,
        total as u32,
        json.len() as u32,
        0x4E4F_534A,
    ] {
        out.extend_from_slice(&word.to_le_bytes());
    }
    out.extend_from_slice(&json);
    for word in [bin.len() as u32, 0x004E_4942] {
        out.extend_from_slice(&word.to_le_bytes());
    }
    out.extend_from_slice(&bin);
    out
}

/// Whether an image holds pixels near both checker colours.
fn shows_both_colours(png: &[u8]) -> bool {
    let image = image::load_from_memory(png).unwrap().to_rgb8();
    let near = |p: &image::Rgb<u8>, c: [u8; 3]| (0..3).all(|k| p.0[k].abs_diff(c[k]) < 8);
    image.pixels().any(|p| near(p, RED)) && image.pixels().any(|p| near(p, BLUE))
}

/// The imported cube's mesh, with its texture.
fn imported_cube(dir: &Path) -> Mesh {
    std::fs::write(dir.join("checker_cube.glb"), cube_glb()).unwrap();
    std::fs::write(
        dir.join("assets.json"),
        r#"[{ "file": "checker_cube.glb", "category": "crate" }]"#,
    )
    .unwrap();
    let report = import_directory(dir).unwrap();
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    report.assets.into_iter().next().unwrap().mesh
}

fn scene_with(mesh: &Mesh) -> (Scene, BTreeMap<String, Mesh>) {
    let mut scene = Scene::new(Architecture::rectangular_room(3.0, 3.0, 2.5, 0.9));
    scene.objects.push(common::object(
        "cube",
        "crate",
        mesh,
        Pose::new(1.0, 0.3, Vector3::new(0.4, 0.0, -0.2)),
        ParentRef::Ground,
        RelationKind::OnFloor,
    ));
    let meshes = BTreeMap::from([("cube".to_owned(), mesh.clone())]);
    (scene, meshes)
}

#[test]
fn an_imported_texture_and_its_coordinates_are_kept_on_import() {
    let pack = tempfile::tempdir().unwrap();
    let mesh = imported_cube(pack.path());
    let material = &mesh.materials[0];
    let texture = material
        .texture
        .as_ref()
        .expect("the material keeps its image");
    assert!(shows_both_colours(texture.png()));
    assert_eq!(material.base_color, [1.0; 4], "the factor stays the factor");
    let part = &mesh.parts[0];
    let uvs = part
        .uvs
        .as_ref()
        .expect("the part keeps its texture coordinates");
    assert_eq!(uvs.len(), part.positions.len());
    assert!(uvs.contains(&[0.0, 0.0]) && uvs.contains(&[1.0, 1.0]));
    // The colour it shows as one colour is the checker's mean (what URDF and scene.json say).
    let flat = material.flat_color();
    assert!(flat[0] > 0.2 && flat[2] > 0.2 && flat[1] < 0.1, "{flat:?}");
}

#[test]
fn the_glb_embeds_the_image_as_base_colour_texture_with_the_coordinates() {
    let pack = tempfile::tempdir().unwrap();
    let mesh = imported_cube(pack.path());
    let original: &TextureImage = mesh.materials[0].texture.as_ref().unwrap();
    let (scene, meshes) = scene_with(&mesh);
    let export = ExportScene::new(&scene, &meshes).unwrap();
    let bytes = glb::to_glb(&export);
    assert_eq!(bytes, glb::to_glb(&export), "deterministic");
    let out = tempfile::tempdir().unwrap();
    let path = out.path().join("scene.glb");
    std::fs::write(&path, &bytes).unwrap();
    let file = GltfFile::read(&path, None).unwrap();
    assert!(
        file.texture_warnings.is_empty(),
        "{:?}",
        file.texture_warnings
    );
    let (image, set) = file
        .materials
        .iter()
        .find(|m| m.name.as_deref() == Some("checker"))
        .and_then(|m| m.texture.clone())
        .expect("the material has the image as its base-colour texture");
    assert_eq!(set, 0);
    assert_eq!(image.digest(), original.digest(), "the same image");
    assert!(shows_both_colours(image.png()));
    let cube = file
        .roots
        .iter()
        .find(|n| n.name.as_deref() == Some("cube"))
        .unwrap();
    let primitive = &cube.primitives[0];
    let uvs = primitive.uvs.as_ref().expect("TEXCOORD_0 is written");
    assert_eq!(uvs.len(), primitive.positions.len());
    let source = mesh.parts[0].uvs.as_ref().unwrap();
    for uv in uvs {
        assert!(source.contains(uv), "{uv:?} is one of the part's own");
    }
    // The library's textures stay as they were: the floor still wears its oak maps.
    let json = String::from_utf8_lossy(&bytes);
    assert!(json.contains("oak_floorboards_color") && json.contains("image_"));
}

#[test]
fn the_text_formats_reference_the_written_image() {
    let pack = tempfile::tempdir().unwrap();
    let mesh = imported_cube(pack.path());
    let image = mesh.materials[0].texture.clone().unwrap();
    let (scene, meshes) = scene_with(&mesh);
    let export = ExportScene::new(&scene, &meshes).unwrap();
    let temp = tempfile::tempdir().unwrap();
    let dir = common::export_dir(temp.path());
    scenethesis_export::write_formats(&Format::ALL, &export, &dir).unwrap();
    let file = format!("image_{}.png", image.digest_hex());
    let written = std::fs::read(dir.join("textures").join(&file)).unwrap();
    assert_eq!(
        written,
        image.png(),
        "the image's own bytes, beside the files"
    );
    let usda = std::fs::read_to_string(dir.join("scene.usda")).unwrap();
    assert!(
        usda.contains(&format!("asset inputs:file = @textures/{file}@")),
        "{usda}"
    );
    assert!(usda.contains("color3f inputs:diffuseColor.connect"));
    // USD's t runs up: the image's top-left corner (0, 0) is written (0, 1).
    assert!(usda.contains("(0, 1)") && usda.contains("(1, 0)"));
    let xml = std::fs::read_to_string(dir.join("scene.mjcf.xml")).unwrap();
    assert!(xml.contains(&format!("file=\"textures/{file}\"")), "{xml}");
    assert!(xml.contains(&format!("texture=\"tex_image_{}\"", image.digest_hex())));
    let urdf = std::fs::read_to_string(dir.join("scene.urdf")).unwrap();
    assert!(urdf.contains(&format!("<texture filename=\"textures/{file}\"/>")));
    scene.write_json_atomic(&dir.join("scene.json")).unwrap();
}

#[test]
fn a_part_without_coordinates_wears_the_flat_colour_and_no_image() {
    let pack = tempfile::tempdir().unwrap();
    let mut mesh = imported_cube(pack.path());
    mesh.parts[0].uvs = None;
    let (scene, meshes) = scene_with(&mesh);
    let export = ExportScene::new(&scene, &meshes).unwrap();
    let bytes = glb::to_glb(&export);
    let json = String::from_utf8_lossy(&bytes);
    assert!(!json.contains("image_"), "no image is embedded");
    let xml = scenethesis_export::mjcf::to_mjcf(&export);
    assert!(!xml.contains("tex_image_"));
}
