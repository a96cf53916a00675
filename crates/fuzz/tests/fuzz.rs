//! One byte-mutation fuzz target per parser: GLB, glTF (JSON with a data URI), OBJ,
//! `scene.json`, `assets.json`, plan files (parsed and checked) and guidance folders
//! (`camera.json`, `labels.json`, `ids.png`). Each must return (an error is fine) without
//! panicking on every mutated input; each target stops after its time budget.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use proptest::prelude::*;
use scenethesis_fuzz::{config, mutate, mutations, Budget};
use scenethesis_import::{import_directory, parse_obj, GltfFile, MANIFEST_FILE};
use scenethesis_procedural::catalog;
use scenethesis_scene_graph::{AssetRef, Mesh, Scene};
use scenethesis_vision::files::{read_guidance, GuidancePaths};

/// Seconds per target in CI.
const SECONDS: f64 = 3.0;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/scenes")
        .join(name)
}

fn living_room() -> &'static Scene {
    static SCENE: OnceLock<Scene> = OnceLock::new();
    SCENE.get_or_init(|| Scene::read_json(&fixture("valid_living_room.json")).unwrap())
}

fn meshes(scene: &Scene) -> BTreeMap<String, Mesh> {
    scene
        .objects
        .iter()
        .filter_map(|o| match &o.asset {
            AssetRef::Procedural {
                generator,
                seed,
                look,
            } => catalog::category(generator).map(|c| {
                (
                    o.id.clone(),
                    catalog::generate_with_look(c, *seed, look.as_ref()).mesh,
                )
            }),
            AssetRef::Imported { .. } => None,
        })
        .collect()
}

/// The living room exported as GLB: a real file of our own writer.
fn glb_seed() -> &'static [u8] {
    static SEED: OnceLock<Vec<u8>> = OnceLock::new();
    SEED.get_or_init(|| {
        let scene = living_room();
        let meshes = meshes(scene);
        let export = scenethesis_export::ExportScene::new(scene, &meshes).unwrap();
        scenethesis_export::glb::to_glb(&export)
    })
}

/// A one-triangle `.gltf` with its buffer in a base64 data URI.
const GLTF_SEED: &str = r#"{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
"nodes":[{"name":"root","children":[1],"translation":[0,1,0]},{"name":"tri","mesh":0,"scale":[2,2,2]}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]}],
"materials":[{"name":"m","pbrMetallicRoughness":{"baseColorFactor":[1,0,0,1]}}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],
"buffers":[{"byteLength":42,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIA"}]}"#;

const OBJ_SEED: &str = "# a unit box\no box\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nusemtl wood\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\ng top\nf 4 8 7 3\nf -8/1/1 -4/2/2 -1/3/3 -5/4/4\nf 2 3 7 6\n";

fn manifest_seed() -> String {
    r#"[{"file": "box.obj", "id": "crate", "category": "storage_box", "synonyms": ["box"], "up_axis": "z", "unit_scale": 0.5, "front": "-x", "placement": "floor", "scale_range": [0.9, 1.1]},
{"file": "box.obj", "category": "side_table", "support_surfaces": [{"name": "top", "kind": "top", "polygon": [[-0.2, -0.2], [0.2, -0.2], [0.2, 0.2]], "height": 0.5, "clearance": 0.3}],
 "joints": [{"part": "top_wood", "name": "lid", "kind": "revolute", "axis": [1, 0, 0], "anchor": [0, 1, 0], "limits": [0, 1.5], "opens_to": "up"}]}]"#
        .to_owned()
}

fn plan_seed() -> &'static [u8] {
    static SEED: OnceLock<Vec<u8>> = OnceLock::new();
    SEED.get_or_init(|| {
        use scenethesis_agents::{KnowledgePlanner, PlanRequest, Planner};
        let planner = KnowledgePlanner::new();
        let request = PlanRequest::new(
            "a cozy living room with a sofa, a coffee table and two lamps",
            planner.known_categories(),
            7,
        );
        serde_json::to_vec_pretty(&planner.plan(&request).unwrap()).unwrap()
    })
}

#[test]
fn every_seed_is_a_valid_input() {
    let tmp = tempfile::tempdir().unwrap();
    for (name, bytes) in guidance_seed() {
        std::fs::write(tmp.path().join(name), bytes).unwrap();
    }
    let (guidance, labels) = read_guidance(&GuidancePaths::in_dir(tmp.path())).unwrap();
    assert_eq!(labels.len(), 2);
    assert!(guidance.depth.is_some());
    let text = String::from_utf8_lossy(plan_seed()).into_owned();
    scenethesis_agents::FixedPlanner::from_json(&text, Path::new("plan.json")).unwrap();
    // The targets below would prove little if their seeds were already rejected.
    let dir = Path::new(".");
    let file = GltfFile::from_slice(glb_seed(), dir, dir).unwrap();
    assert!(!file.roots.is_empty());
    let file = GltfFile::from_slice(GLTF_SEED.as_bytes(), dir, dir).unwrap();
    assert_eq!(file.roots[0].children[0].primitives[0].triangles.len(), 1);
    assert_eq!(parse_obj(OBJ_SEED).unwrap().triangle_count(), 12);
    living_room().validate().unwrap();
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("box.obj"), OBJ_SEED).unwrap();
    std::fs::write(tmp.path().join(MANIFEST_FILE), manifest_seed()).unwrap();
    let report = import_directory(tmp.path()).unwrap();
    assert_eq!(report.assets.len(), 2, "{:?}", report.warnings);
    assert_eq!(
        report.assets[1].info.joints.len(),
        1,
        "the seed's lid is imported"
    );
    serde_json::from_slice::<scenethesis_agents::Plan>(plan_seed()).unwrap();
}

proptest! {
    #![proptest_config(config(300))]

    #[test]
    fn glb_reader_survives_mutations(edits in mutations()) {
        static BUDGET: OnceLock<Budget> = OnceLock::new();
        if BUDGET.get_or_init(|| Budget::new(SECONDS)).spent() {
            return Ok(());
        }
        let bytes = mutate(glb_seed(), &edits);
        let dir = Path::new(".");
        let _ = GltfFile::from_slice(&bytes, dir, dir);
        if let Ok(scene) = scenethesis_eval::glb::GlbScene::from_slice(&bytes, Path::new("fuzz.glb")) {
            for root in &scene.roots {
                let _ = root.subtree_mesh();
            }
        }
    }

    #[test]
    fn glb_scene_loading_for_eval_survives_mutations(edits in mutations()) {
        static BUDGET: OnceLock<Budget> = OnceLock::new();
        if BUDGET.get_or_init(|| Budget::new(SECONDS)).spent() {
            return Ok(());
        }
        let tmp = tempfile::tempdir().unwrap();
        let path = tmp.path().join("scene.glb");
        std::fs::write(&path, mutate(glb_seed(), &edits)).unwrap();
        if let Ok(scene) = scenethesis_eval::load_glb(&path) {
            prop_assert!(scene.check_limits().is_ok());
        }
    }

    #[test]
    fn gltf_json_reader_survives_mutations(edits in mutations()) {
        static BUDGET: OnceLock<Budget> = OnceLock::new();
        if BUDGET.get_or_init(|| Budget::new(SECONDS)).spent() {
            return Ok(());
        }
        let bytes = mutate(GLTF_SEED.as_bytes(), &edits);
        let tmp = tempfile::tempdir().unwrap();
        let _ = GltfFile::from_slice(&bytes, tmp.path(), tmp.path());
    }

    #[test]
    fn obj_parser_survives_mutations(edits in mutations()) {
        static BUDGET: OnceLock<Budget> = OnceLock::new();
        if BUDGET.get_or_init(|| Budget::new(SECONDS)).spent() {
            return Ok(());
        }
        let bytes = mutate(OBJ_SEED.as_bytes(), &edits);
        if let Ok(mesh) = parse_obj(&String::from_utf8_lossy(&bytes)) {
            prop_assert!(mesh.parts.iter().flat_map(|p| p.positions.iter().flatten()).all(|v| v.is_finite()));
        }
    }

    #[test]
    fn scene_json_reader_survives_mutations(edits in mutations()) {
        static BUDGET: OnceLock<Budget> = OnceLock::new();
        if BUDGET.get_or_init(|| Budget::new(SECONDS)).spent() {
            return Ok(());
        }
        static SEED: OnceLock<String> = OnceLock::new();
        let seed = SEED.get_or_init(|| living_room().to_json_string());
        let bytes = mutate(seed.as_bytes(), &edits);
        let Ok(scene) = Scene::from_json_str(&String::from_utf8_lossy(&bytes)) else {
            return Ok(());
        };
        if scene.validate().is_err() {
            return Ok(());
        }
        // A valid scene must be usable by every tool without a panic.
        prop_assert!(scene.bfs_order().is_ok());
        if let Ok(eval) = scenethesis_eval::EvalScene::from_scene_procedural(&scene) {
            prop_assert!(eval.check_limits().is_ok(), "a valid scene is within the evaluator's limits");
        }
        let meshes = meshes(&scene);
        if let Ok(export) = scenethesis_export::ExportScene::new(&scene, &meshes) {
            let usda = scenethesis_export::usd::to_usda(&export);
            prop_assert!(!usda.contains(char::from(0x1b)), "raw escape in USD");
            let _ = scenethesis_export::mjcf::to_mjcf(&export);
        }
    }

    #[test]
    fn assets_json_reader_survives_mutations(edits in mutations()) {
        static BUDGET: OnceLock<Budget> = OnceLock::new();
        if BUDGET.get_or_init(|| Budget::new(SECONDS)).spent() {
            return Ok(());
        }
        let tmp = tempfile::tempdir().unwrap();
        std::fs::write(tmp.path().join("box.obj"), OBJ_SEED).unwrap();
        std::fs::write(tmp.path().join(MANIFEST_FILE), mutate(manifest_seed().as_bytes(), &edits)).unwrap();
        if let Ok(report) = import_directory(tmp.path()) {
            for a in &report.assets {
                prop_assert!(a.info.scale_range[0] <= a.info.scale_range[1]);
                prop_assert!(a.info.size.iter().all(|v| v.is_finite()));
            }
        }
    }

    #[test]
    fn plan_reader_survives_mutations(edits in mutations()) {
        static BUDGET: OnceLock<Budget> = OnceLock::new();
        if BUDGET.get_or_init(|| Budget::new(SECONDS)).spent() {
            return Ok(());
        }
        let bytes = mutate(plan_seed(), &edits);
        let text = String::from_utf8_lossy(&bytes);
        let _ = scenethesis_agents::FixedPlanner::from_json(&text, Path::new("plan.json"));
    }

    #[test]
    fn guidance_readers_survive_mutations(edits in mutations(), file in 0..3usize) {
        static BUDGET: OnceLock<Budget> = OnceLock::new();
        if BUDGET.get_or_init(|| Budget::new(SECONDS)).spent() {
            return Ok(());
        }
        let name = ["camera.json", "labels.json", "ids.png"][file];
        let tmp = tempfile::tempdir().unwrap();
        for (file_name, bytes) in guidance_seed() {
            let bytes = if *file_name == name { mutate(bytes, &edits) } else { bytes.clone() };
            std::fs::write(tmp.path().join(file_name), bytes).unwrap();
        }
        let paths = GuidancePaths::in_dir(tmp.path());
        let _ = read_guidance(&paths);
    }
}

/// A 16 × 12 guidance folder's files: colour, depth, two labelled instances and the camera.
fn guidance_seed() -> &'static [(&'static str, Vec<u8>)] {
    static SEED: OnceLock<Vec<(&'static str, Vec<u8>)>> = OnceLock::new();
    SEED.get_or_init(|| {
        let (w, h) = (16u32, 12u32);
        let png = |img: image::DynamicImage| {
            let mut out = std::io::Cursor::new(Vec::new());
            img.write_to(&mut out, image::ImageFormat::Png).unwrap();
            out.into_inner()
        };
        let rgb = image::RgbImage::from_fn(w, h, |x, y| image::Rgb([x as u8 * 16, y as u8 * 20, 90]));
        let ids = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_fn(w, h, |x, y| {
            image::Luma([if y > 6 { 1 } else if x > 10 { 2 } else { 0 }])
        });
        let depth: Vec<f32> = (0..w * h).map(|i| 2.0 + (i / w) as f32 * 0.1).collect();
        let labels = r#"{"1": {"id": "sofa_0", "category": "sofa"}, "2": {"id": "lamp_0", "category": "floor_lamp"}}"#;
        let camera = r#"{"intrinsics": {"width": 16, "height": 12, "fx": 12.0, "fy": 12.0, "cx": 8.0, "cy": 6.0},
"position": [0.0, 1.5, 3.0], "rotation": [-0.13, 0.0, 0.0, 0.99]}"#;
        vec![
            ("rgb.png", png(image::DynamicImage::ImageRgb8(rgb))),
            ("depth.npy", scenethesis_vision::files::write_npy(w, h, &depth)),
            ("ids.png", png(image::DynamicImage::ImageLuma16(ids))),
            ("labels.json", labels.as_bytes().to_vec()),
            ("camera.json", camera.as_bytes().to_vec()),
        ]
    })
}
