//! Every exporter on a hand-built scene: a table against the back wall with a mug on it, a
//! crate with a ball inside, a stool under the table and a painting hanging on a wall. The GLB
//! is parsed back with the `gltf` crate; USD, MJCF and URDF are checked structurally. When
//! `SCENETHESIS_EXPORT_DIR` is set, the exports are also written there for the Python consumer
//! check (`crates/export/tests/consumers/check_exports.py`).

use std::collections::BTreeMap;
use std::f64::consts::FRAC_PI_2;

use nalgebra::{Point2, Vector3};
use scenethesis_export::{Dynamics, ExportError, ExportScene, Format};
use scenethesis_primitives::{cuboid, cylinder, sphere};

mod common;
use common::object;
use scenethesis_scene_graph::{
    Architecture, DoorLeaf, DoorOpening, Material, Mesh, MeshPart, ParentRef, Pose, RelationKind,
    RoomArea, Scene, Wall, WindowOpening, EXTERIOR,
};

fn mesh(parts: Vec<MeshPart>, materials: Vec<Material>) -> Mesh {
    Mesh { parts, materials }
}

fn table() -> Mesh {
    let mut parts = vec![cuboid("top", 0, [-0.6, 0.70, -0.4], [0.6, 0.75, 0.4])];
    for (i, (x, z)) in [(-0.55, -0.35), (0.55, -0.35), (-0.55, 0.35), (0.55, 0.35)]
        .into_iter()
        .enumerate()
    {
        parts.push(cuboid(
            &format!("leg_{i}"),
            0,
            [x - 0.03, 0.0, z - 0.03],
            [x + 0.03, 0.70, z + 0.03],
        ));
    }
    mesh(parts, vec![Material::new("oak", [0.55, 0.38, 0.2], 0.6)])
}

fn mug() -> Mesh {
    mesh(
        vec![cylinder("body", 0, [0.0, 0.0], 0.04, 0.0, 0.1, 24)],
        vec![Material {
            name: "ceramic".into(),
            base_color: [0.9, 0.9, 0.85, 1.0],
            roughness: 0.3,
            metallic: 0.0,
            texture: None,
        }],
    )
}

/// An open crate: a floor and four convex walls, so its interior stays open under per-part
/// convex hulls.
fn crate_mesh() -> Mesh {
    let m = 0;
    mesh(
        vec![
            cuboid("bottom", m, [-0.25, 0.0, -0.2], [0.25, 0.02, 0.2]),
            cuboid("wall_back", m, [-0.25, 0.02, -0.2], [0.25, 0.3, -0.18]),
            cuboid("wall_front", m, [-0.25, 0.02, 0.18], [0.25, 0.3, 0.2]),
            cuboid("wall_left", m, [-0.25, 0.02, -0.18], [-0.23, 0.3, 0.18]),
            cuboid("wall_right", m, [0.23, 0.02, -0.18], [0.25, 0.3, 0.18]),
        ],
        vec![Material {
            name: "steel".into(),
            base_color: [0.6, 0.6, 0.62, 1.0],
            roughness: 0.35,
            metallic: 1.0,
            texture: None,
        }],
    )
}

fn ball() -> Mesh {
    mesh(
        vec![sphere("ball", 0, [0.0, 0.08, 0.0], 0.08, 8, 12)],
        vec![Material::new("rubber_red", [0.8, 0.1, 0.1], 0.9)],
    )
}

fn stool() -> Mesh {
    mesh(
        vec![
            cylinder("seat", 0, [0.0, 0.0], 0.15, 0.40, 0.43, 16),
            cylinder("post", 1, [0.0, 0.0], 0.03, 0.02, 0.40, 12),
            cylinder("foot", 1, [0.0, 0.0], 0.14, 0.0, 0.02, 16),
        ],
        vec![
            Material::new("oak", [0.55, 0.38, 0.2], 0.6),
            Material {
                name: "chrome".into(),
                base_color: [0.8, 0.8, 0.8, 1.0],
                roughness: 0.1,
                metallic: 1.0,
                texture: None,
            },
        ],
    )
}

fn painting() -> Mesh {
    mesh(
        vec![
            cuboid("frame", 0, [-0.4, 0.0, -0.02], [0.4, 0.6, 0.0]),
            cuboid("canvas", 1, [-0.37, 0.03, 0.0], [0.37, 0.57, 0.005]),
        ],
        vec![
            Material::new("frame_black", [0.05, 0.05, 0.05], 0.5),
            Material::new("canvas_blue", [0.2, 0.3, 0.7], 0.95),
        ],
    )
}

/// The hand-built scene and its meshes.
fn scene() -> (Scene, BTreeMap<String, Mesh>) {
    let mut scene = Scene::new(Architecture::rectangular_room(5.0, 4.0, 2.6, 0.9));
    scene.prompt = "a small test room".into();
    scene.seed = 3;
    let meshes = BTreeMap::from([
        ("table".to_owned(), table()),
        ("mug".to_owned(), mug()),
        ("crate".to_owned(), crate_mesh()),
        ("ball".to_owned(), ball()),
        ("stool".to_owned(), stool()),
        ("painting".to_owned(), painting()),
    ]);
    let ground = || ParentRef::Ground;
    scene.objects = vec![
        object(
            "table",
            "table",
            &meshes["table"],
            Pose::new(1.0, 0.0, Vector3::new(0.0, 0.0, -1.5)),
            ground(),
            RelationKind::AgainstWall,
        ),
        object(
            "mug",
            "mug",
            &meshes["mug"],
            Pose::new(1.0, 0.3, Vector3::new(0.2, 0.75, -1.4)),
            ParentRef::Object("table".into()),
            RelationKind::On,
        ),
        object(
            "crate",
            "crate",
            &meshes["crate"],
            Pose::new(1.2, FRAC_PI_2, Vector3::new(1.8, 0.0, 1.0)),
            ground(),
            RelationKind::OnFloor,
        ),
        object(
            "ball",
            "ball",
            &meshes["ball"],
            // Inside the crate: its floor is 0.02 × 1.2 = 0.024 high.
            Pose::new(1.0, 0.0, Vector3::new(1.8, 0.024, 1.0)),
            ParentRef::Object("crate".into()),
            RelationKind::Inside,
        ),
        object(
            "stool",
            "stool",
            &meshes["stool"],
            Pose::new(1.0, 0.0, Vector3::new(-0.2, 0.0, -1.4)),
            ground(),
            RelationKind::Under,
        ),
        object(
            "painting",
            "painting",
            &meshes["painting"],
            // Mounted on the left wall (x = −2.5), facing +x.
            Pose::new(1.0, FRAC_PI_2, Vector3::new(-2.48, 1.4, 0.0)),
            ParentRef::Wall("wall_1".into()),
            RelationKind::Mounted,
        ),
    ];
    scene.anchor = Some("table".into());
    (scene, meshes)
}

#[test]
fn glb_parses_back_with_names_materials_and_transforms() {
    let (scene, meshes) = scene();
    let export = ExportScene::new(&scene, &meshes).unwrap();
    let bytes = scenethesis_export::glb::to_glb(&export);
    assert_eq!(bytes.len() % 4, 0);
    let gltf = gltf::Gltf::from_slice(&bytes).expect("GLB must parse");
    let blob = gltf.blob.as_deref().expect("BIN chunk present");

    let names: Vec<&str> = gltf.nodes().map(|n| n.name().unwrap()).collect();
    assert_eq!(
        names,
        [
            "floor",
            "wall_0",
            "wall_1",
            "wall_2",
            "wall_3",
            "table",
            "mug",
            "crate",
            "ball",
            "stool",
            "painting",
            "door_0_leaf"
        ]
    );
    let root: Vec<usize> = gltf
        .default_scene()
        .unwrap()
        .nodes()
        .map(|n| n.index())
        .collect();
    assert_eq!(
        root.len(),
        names.len() - 1,
        "the door leaf hangs under its wall"
    );

    // Materials: shared `oak`, plus every other distinct one and the floor's and walls'
    // library materials.
    let mut material_names: Vec<&str> = gltf.materials().map(|m| m.name().unwrap()).collect();
    material_names.sort();
    assert_eq!(
        material_names,
        [
            "canvas_blue",
            "ceramic",
            "chrome",
            "door_leaf",
            "frame_black",
            "oak",
            "oak_floorboards",
            "rubber_red",
            "steel",
            "wall_paint"
        ]
    );
    let steel = gltf
        .materials()
        .find(|m| m.name() == Some("steel"))
        .unwrap();
    let pbr = steel.pbr_metallic_roughness();
    assert_eq!(pbr.metallic_factor(), 1.0);
    // The maps multiply the factors: on average the surface keeps its own colour and roughness.
    let maps = scenethesis_materials::maps(scenethesis_materials::by_id("steel").unwrap());
    assert!((pbr.roughness_factor() * maps.mean_roughness - 0.35).abs() < 1e-3);
    let color = pbr.base_color_factor();
    for (k, want) in [0.6, 0.6, 0.62].into_iter().enumerate() {
        assert!(
            (color[k] * maps.mean_albedo[k] - want).abs() < 1e-3,
            "{color:?}"
        );
    }
    // Every material whose name the library knows wears three textures (one it does not know
    // stays plain); the images are embedded once per map of each library material, and every
    // primitive of a textured material has UVs and tangents.
    let known = |name: Option<&str>| scenethesis_materials::resolve(name.unwrap()).is_some();
    let textured = |m: &gltf::Material| {
        m.normal_texture().is_some()
            && m.pbr_metallic_roughness().base_color_texture().is_some()
            && m.pbr_metallic_roughness()
                .metallic_roughness_texture()
                .is_some()
    };
    for m in gltf.materials() {
        assert_eq!(textured(&m), known(m.name()), "{:?}", m.name());
    }
    let image_names: std::collections::BTreeSet<_> = gltf
        .images()
        .map(|i| i.name().unwrap().to_owned())
        .collect();
    assert_eq!(
        image_names.len(),
        gltf.images().count(),
        "an image is embedded twice"
    );
    assert!(image_names.contains("oak_color") && image_names.contains("wall_paint_normal"));
    for mesh in gltf.meshes() {
        for p in mesh.primitives() {
            let plain = !known(p.material().name());
            assert_eq!(p.get(&gltf::Semantic::TexCoords(0)).is_none(), plain);
            assert_eq!(p.get(&gltf::Semantic::Tangents).is_none(), plain);
        }
    }

    for node in gltf.nodes() {
        let name = node.name().unwrap();
        let mesh = node.mesh().expect("every node has a mesh");
        let expected_parts = match meshes.get(name) {
            Some(m) => m.parts.len(),
            None if name == "wall_2" => 3, // split around the door
            None => 1,
        };
        assert_eq!(mesh.primitives().count(), expected_parts, "{name}");
        for prim in mesh.primitives() {
            let reader = prim.reader(|_| Some(blob));
            let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
            let normals: Vec<[f32; 3]> = reader.read_normals().unwrap().collect();
            let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
            assert_eq!(positions.len(), normals.len());
            assert_eq!(indices.len() % 3, 0);
            assert!(indices.iter().all(|&i| (i as usize) < positions.len()));
            let bb = prim.bounding_box();
            for p in &positions {
                for (k, v) in p.iter().enumerate() {
                    assert!(bb.min[k] <= *v && *v <= bb.max[k]);
                }
            }
        }
        if let Some(object) = scene.object(name) {
            let (t, r, s) = node.transform().decomposed();
            let pose = object.pose;
            assert!((Vector3::from(t).cast::<f64>() - pose.translation).norm() < 1e-6);
            assert!((s[0] as f64 - pose.scale).abs() < 1e-6 && s[0] == s[1] && s[1] == s[2]);
            // Quaternion (x, y, z, w) about +Y by yaw.
            assert!(r[0] == 0.0 && r[2] == 0.0);
            assert!((r[1] as f64 - (pose.yaw / 2.0).sin()).abs() < 1e-6);
            let extras = node.extras().as_ref().expect("object nodes carry extras");
            let extras: serde_json::Value = serde_json::from_str(extras.get()).unwrap();
            assert_eq!(extras["category"], object.category);
            assert_eq!(extras["parent"], object.parent.to_string());
        } else if name != "door_0_leaf" {
            // Architecture is in world coordinates; the leaf pivots at its hinge (joints.rs).
            assert_eq!(node.transform().decomposed().0, [0.0; 3], "{name}");
        }
    }
}

#[test]
fn glb_places_the_mug_on_the_table_in_world_space() {
    let (scene, meshes) = scene();
    let export = ExportScene::new(&scene, &meshes).unwrap();
    let bytes = scenethesis_export::glb::to_glb(&export);
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    let world_min_y = |name: &str| -> f32 {
        let node = gltf.nodes().find(|n| n.name() == Some(name)).unwrap();
        let m = nalgebra::Matrix4::from(node.transform().matrix());
        let blob = gltf.blob.as_deref().unwrap();
        node.mesh()
            .unwrap()
            .primitives()
            .flat_map(|p| {
                p.reader(|_| Some(blob))
                    .read_positions()
                    .unwrap()
                    .collect::<Vec<_>>()
            })
            .map(|p| (m * nalgebra::Vector4::new(p[0], p[1], p[2], 1.0)).y)
            .fold(f32::INFINITY, f32::min)
    };
    assert!((world_min_y("mug") - 0.75).abs() < 1e-5);
    assert!(world_min_y("table").abs() < 1e-6);
    assert!((world_min_y("ball") - 0.024).abs() < 1e-5);
    assert!((world_min_y("floor") + 0.05).abs() < 1e-6);
}

#[test]
fn exports_are_deterministic() {
    let (scene, meshes) = scene();
    let export = ExportScene::new(&scene, &meshes).unwrap();
    let (scene2, meshes2) = self::scene();
    let export2 = ExportScene::new(&scene2, &meshes2).unwrap();
    use scenethesis_export::{glb, mjcf, urdf, usd};
    assert_eq!(glb::to_glb(&export), glb::to_glb(&export2));
    assert_eq!(usd::to_usda(&export), usd::to_usda(&export2));
    assert_eq!(mjcf::to_mjcf(&export), mjcf::to_mjcf(&export2));
    assert_eq!(urdf::to_urdf(&export, "m"), urdf::to_urdf(&export2, "m"));
}

#[test]
fn usda_has_stage_metadata_xforms_and_bound_materials() {
    let (scene, meshes) = scene();
    let export = ExportScene::new(&scene, &meshes).unwrap();
    let text = scenethesis_export::usd::to_usda(&export);
    assert!(text.starts_with("#usda 1.0\n"));
    assert!(text.contains("upAxis = \"Y\""));
    assert!(text.contains("metersPerUnit = 1"));
    assert!(text.contains("defaultPrim = \"World\""));
    for id in ["floor", "wall_0", "wall_3", "table", "mug", "painting"] {
        assert!(
            text.contains(&format!("def Xform \"{id}\"")),
            "missing Xform {id}"
        );
    }
    // The painting's yaw of 90° becomes rotateY = 90 (degrees).
    assert!(text.contains("double xformOp:rotateY = 90\n"));
    let mesh_prims = text.matches("def Mesh ").count();
    let parts: usize = meshes.values().map(|m| m.parts.len()).sum();
    // Floor, 3 plain walls, door wall in 3 boxes, door leaf.
    assert_eq!(mesh_prims, parts + 1 + 3 + 3 + 1);
    assert_eq!(
        text.matches("rel material:binding = </World/Looks/")
            .count(),
        mesh_prims
    );
    assert!(text.contains("def Material \"steel\""));
    assert!(text.contains("uniform token info:id = \"UsdPreviewSurface\""));
    assert_eq!(text.matches('{').count(), text.matches('}').count());
}

#[test]
fn mjcf_has_free_bodies_mesh_geoms_and_static_architecture() {
    let (scene, meshes) = scene();
    let export = ExportScene::new(&scene, &meshes).unwrap();
    assert_eq!(
        export.dynamics(scene.object("painting").unwrap()),
        Dynamics::Fixed
    );
    assert_eq!(
        export.dynamics(scene.object("table").unwrap()),
        Dynamics::Free
    );
    let xml = scenethesis_export::mjcf::to_mjcf(&export);
    assert!(xml.contains("<option timestep=\"0.001\" gravity=\"0 0 -9.81\"/>"));
    assert!(xml.contains("density=\"1000\" friction=\"0.5 0.005 0.0001\""));
    // Six objects, the door and its leaf.
    assert_eq!(xml.matches("<body ").count(), 8);
    assert_eq!(xml.matches("<freejoint ").count(), 5, "painting is welded");
    assert!(!xml.contains("<freejoint name=\"painting\""));
    assert!(xml.contains("<freejoint name=\"table\""));
    let parts: usize = meshes.values().map(|m| m.parts.len()).sum();
    // Every part and the door leaf.
    assert_eq!(xml.matches("type=\"mesh\"").count(), parts + 1);
    assert_eq!(xml.matches("<mesh name=").count(), parts + 1);
    assert_eq!(xml.matches("type=\"plane\"").count(), 1);
    assert_eq!(xml.matches("type=\"box\"").count(), 3 + 3);
    // The table stands at scene (0, 0, −1.5): MuJoCo (0, 1.5, 0).
    assert!(xml.contains("<body name=\"table\" pos=\"0 1.5 0\""));
    assert!(xml.contains("<mesh name=\"crate_bottom\" scale=\"1.2 1.2 1.2\""));
}

#[test]
fn only_mounted_objects_are_welded_and_a_floating_one_stays_free() {
    let (mut scene, meshes) = scene();
    assert_eq!(scene.validate(), Ok(()));
    let painting = scene.object("painting").unwrap();
    assert!(painting.fixed_to_world());
    let usd = scenethesis_export::usd::to_usda(&ExportScene::new(&scene, &meshes).unwrap());
    assert!(usd.contains("custom string scenethesis:parent = \"wall_1\""));
    assert!(usd.contains("custom string scenethesis:support = \"mounted\""));
    let urdf = scenethesis_export::urdf::to_urdf(&ExportScene::new(&scene, &meshes).unwrap(), "m");
    assert!(urdf
        .urdf
        .contains("<joint name=\"painting_joint\" type=\"fixed\">"));
    assert!(urdf
        .urdf
        .contains("<joint name=\"table_joint\" type=\"floating\">"));

    // The same painting at the same height on the ground link, leaning on nothing: it floats,
    // and the exports keep it a free body (the simulation shows the defect; nothing welds it).
    let p = scene.object_mut("painting").unwrap();
    p.parent = ParentRef::Ground;
    p.support = RelationKind::AgainstWall;
    let export = ExportScene::new(&scene, &meshes).unwrap();
    assert_eq!(
        export.dynamics(scene.object("painting").unwrap()),
        Dynamics::Free
    );
    let xml = scenethesis_export::mjcf::to_mjcf(&export);
    assert_eq!(xml.matches("<freejoint ").count(), 6);
    assert!(xml.contains("<freejoint name=\"painting\""));
    let urdf = scenethesis_export::urdf::to_urdf(&export, "m");
    assert!(urdf
        .urdf
        .contains("<joint name=\"painting_joint\" type=\"floating\">"));
}

#[test]
fn urdf_links_joints_meshes_and_inertia() {
    let (scene, meshes) = scene();
    let export = ExportScene::new(&scene, &meshes).unwrap();
    let package = scenethesis_export::urdf::to_urdf(&export, "meshes");
    let xml = &package.urdf;
    assert!(xml.contains("<robot name=\"scenethesis_scene\">"));
    assert!(xml.contains("<link name=\"world\"/>"));
    assert_eq!(xml.matches("type=\"floating\"").count(), 5);
    // Floor and four walls plus the painting are fixed.
    assert_eq!(xml.matches("type=\"fixed\"").count(), 6);
    let parts: usize = meshes.values().map(|m| m.parts.len()).sum();
    // Every part and the door leaf.
    assert_eq!(package.meshes.len(), parts + 1);
    assert_eq!(
        xml.matches("<mesh filename=\"meshes/").count(),
        2 * (parts + 1)
    );
    assert_eq!(xml.matches("<inertial>").count(), 6 + 1);
    let obj = &package.meshes["mug_body.obj"];
    let vertices = obj.lines().filter(|l| l.starts_with("v ")).count();
    let faces = obj.lines().filter(|l| l.starts_with("f ")).count();
    // The mug's ceramic is textured: its vertices are split where the box projection changes
    // axis, one texture coordinate each.
    let uvs = obj.lines().filter(|l| l.starts_with("vt ")).count();
    assert!(vertices >= meshes["mug"].parts[0].positions.len());
    assert_eq!(uvs, vertices);
    assert_eq!(faces, meshes["mug"].parts[0].triangles.len());
    // The ball: 1000 kg/m³ × a slightly-less-than-sphere volume.
    let ball_mass = 1000.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.08f64.powi(3);
    let start = xml.find("<link name=\"ball\">").unwrap();
    let mass_at = xml[start..].find("<mass value=\"").unwrap() + start + 13;
    let mass: f64 = xml[mass_at..xml[mass_at..].find('"').unwrap() + mass_at]
        .parse()
        .unwrap();
    assert!(
        mass < ball_mass && mass > 0.75 * ball_mass,
        "ball mass {mass}"
    );
}

#[test]
fn missing_and_broken_meshes_are_named() {
    let (scene, mut meshes) = scene();
    meshes.remove("mug");
    let err = ExportScene::new(&scene, &meshes).unwrap_err();
    assert!(matches!(&err, ExportError::MissingMesh { id } if id == "mug"));
    assert!(err.to_string().contains("`mug`"));
    let mut broken = mug();
    broken.parts[0].triangles.push([0, 1, 9999]);
    meshes.insert("mug".into(), broken);
    let err = ExportScene::new(&scene, &meshes).unwrap_err();
    assert!(matches!(&err, ExportError::InvalidMesh { id, .. } if id == "mug"));
}

#[test]
fn formats_write_their_files() {
    let (scene, meshes) = scene();
    let export = ExportScene::new(&scene, &meshes).unwrap();
    let temp = tempfile::tempdir().unwrap();
    let dir = common::export_dir(temp.path());
    for format in Format::ALL {
        let path = format.write(&export, &dir).unwrap();
        assert!(path.exists(), "{format} did not write {}", path.display());
        assert_eq!(format.as_str().parse::<Format>().unwrap(), format);
    }
    assert!(dir.join("meshes/table_top.obj").exists());
    // The text formats' textures are in one folder beside them, each map once.
    let usda = std::fs::read_to_string(dir.join("scene.usda")).unwrap();
    let xml = std::fs::read_to_string(dir.join("scene.mjcf.xml")).unwrap();
    let urdf = std::fs::read_to_string(dir.join("scene.urdf")).unwrap();
    for file in [
        "oak_color.png",
        "oak_normal.png",
        "oak_mr.png",
        "wall_paint_color.png",
    ] {
        assert!(dir.join("textures").join(file).is_file(), "{file}");
    }
    assert!(usda.contains("asset inputs:file = @textures/oak_normal.png@"));
    assert!(usda.contains("texCoord2f[] primvars:st = ["));
    assert!(xml.contains("file=\"textures/oak_color.png\"") && xml.contains("texcoord=\""));
    assert!(urdf.contains("<texture filename=\"textures/oak_color.png\"/>"));
    let obj = std::fs::read_to_string(dir.join("meshes/table_top.obj")).unwrap();
    assert!(
        obj.contains("\nvt ") && obj.contains("/"),
        "the OBJ has texture coordinates"
    );
    scene.write_json_atomic(&dir.join("scene.json")).unwrap();
}

#[test]
fn one_file_written_alone_keeps_its_textures_in_a_folder_of_its_own() {
    let (scene, meshes) = scene();
    let export = ExportScene::new(&scene, &meshes).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let written = Format::Usd
        .write_file(&export, &dir.path().join("kitchen.usda"))
        .unwrap();
    assert_eq!(
        written,
        [
            dir.path().join("kitchen.usda"),
            dir.path().join("kitchen_textures")
        ]
    );
    let text = std::fs::read_to_string(&written[0]).unwrap();
    assert!(text.contains("@kitchen_textures/oak_color.png@"));
    assert!(dir.path().join("kitchen_textures/oak_color.png").is_file());
    // A GLB carries its textures inside: nothing beside it.
    let glb = Format::Glb
        .write_file(&export, &dir.path().join("k.glb"))
        .unwrap();
    assert_eq!(glb, [dir.path().join("k.glb")]);
}

/// A scene whose table has the longest id the validator allows (256 bytes).
fn scene_with_long_id() -> (Scene, BTreeMap<String, Mesh>) {
    let (mut scene, mut meshes) = scene();
    let long = "t".repeat(scenethesis_scene_graph::limits::MAX_ID_BYTES);
    let table = meshes.remove("table").unwrap();
    meshes.insert(long.clone(), table);
    for object in &mut scene.objects {
        if object.id == "table" {
            object.id = long.clone();
        }
        if object.parent == ParentRef::Object("table".into()) {
            object.parent = ParentRef::Object(long.clone());
        }
        for relation in &mut object.relations {
            if relation.target == "table" {
                relation.target = long.clone();
            }
        }
    }
    if scene.anchor.as_deref() == Some("table") {
        scene.anchor = Some(long);
    }
    scene.validate().unwrap();
    (scene, meshes)
}

#[test]
fn every_format_writes_a_scene_whose_ids_are_as_long_as_allowed() {
    let (scene, meshes) = scene_with_long_id();
    let export = ExportScene::new(&scene, &meshes).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let written = scenethesis_export::write_formats(&Format::ALL, &export, dir.path()).unwrap();
    assert_eq!(written.len(), 4);
    for entry in std::fs::read_dir(dir.path().join("meshes")).unwrap() {
        let name = entry.unwrap().file_name();
        assert!(name.len() <= 130, "{name:?}");
    }
}

#[test]
fn a_failed_export_leaves_the_folder_as_it_was() {
    let (scene, meshes) = scene();
    let export = ExportScene::new(&scene, &meshes).unwrap();
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("scene.usda"), "old").unwrap();
    // A folder where the URDF file goes blocks the last format.
    std::fs::create_dir(dir.path().join("scene.urdf")).unwrap();
    std::fs::write(dir.path().join("scene.urdf").join("keep"), "x").unwrap();
    let err = scenethesis_export::write_formats(&Format::ALL, &export, dir.path()).unwrap_err();
    assert!(matches!(err, ExportError::Write { .. }), "{err}");
    let left: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(
        !left.iter().any(|n| n.starts_with(".export-staging")),
        "{left:?}"
    );
    assert!(
        !left.iter().any(|n| n == "scene.glb" || n == "meshes"),
        "{left:?}"
    );
    let usd = std::fs::read_to_string(dir.path().join("scene.usda")).unwrap();
    assert_eq!(usd, "old");
}

#[test]
fn values_no_format_can_hold_are_refused_before_writing() {
    let (mut scene, meshes) = scene();
    // 1e39 overflows the f32 a GLB stores.
    scene.objects[0].pose.translation.x = 1e39;
    let err = ExportScene::new(&scene, &meshes).unwrap_err();
    assert!(
        matches!(&err, ExportError::InvalidPose { id } if id == "table"),
        "{err}"
    );
    let (mut scene, meshes) = crate::scene();
    scene.architecture.walls[0].height = f64::INFINITY;
    let err = ExportScene::new(&scene, &meshes).unwrap_err();
    assert!(err.to_string().contains("wall_0"), "{err}");
    let (scene, mut meshes) = crate::scene();
    meshes.get_mut("mug").unwrap().parts[0].positions[0][1] = f32::NAN;
    let err = ExportScene::new(&scene, &meshes).unwrap_err();
    assert!(matches!(&err, ExportError::InvalidMesh { id, .. } if id == "mug"));
}

#[test]
fn ids_and_names_are_escaped_in_every_text_format() {
    use scenethesis_export::{mjcf, usd};
    let (mut scene, mut meshes) = scene();
    let evil = "mug\u{1b}[2J\"<x>&\n";
    let mesh = meshes.remove("mug").unwrap();
    meshes.insert(evil.to_owned(), mesh);
    for o in &mut scene.objects {
        if o.id == "mug" {
            o.id = evil.to_owned();
            o.category = "cup\u{7}".into();
        }
    }
    let export = ExportScene::new(&scene, &meshes).unwrap();
    let usda = usd::to_usda(&export);
    assert!(
        !usda.contains('\u{1b}') && !usda.contains('\u{7}'),
        "raw control characters in USD"
    );
    assert!(usda.contains("\\x1b"), "escaped in the USD string");
    let xml = mjcf::to_mjcf(&export);
    assert!(!xml.contains('\u{1b}') && !xml.contains('\u{7}'));
    assert!(!xml.contains("<x>"), "no raw markup from an id");
}

/// A window of `width` × 1.2 m, its sill 0.9 m up, centred `offset` m along `wall`.
fn window(id: &str, wall: &str, offset: f64, room: Option<&str>) -> WindowOpening {
    WindowOpening {
        id: id.into(),
        wall: wall.into(),
        offset,
        width: 1.0,
        height: 1.2,
        sill: 0.9,
        room: room.map(Into::into),
    }
}

/// The hand-built room of [`scene`] with a window in its back and left walls.
fn room_with_windows() -> (Scene, BTreeMap<String, Mesh>) {
    let (mut scene, meshes) = scene();
    scene.architecture.windows = vec![
        window("window_0", "wall_0", 1.2, None),
        window("window_1", "wall_1", 2.5, None),
    ];
    (scene, meshes)
}

/// A two-room house, 8 × 4 m: `living_room` (x < 0, with the entrance door in the front wall)
/// and `bedroom` (x > 0), parted by the wall `wall_4` at x = 0 with the door `door_1`; a window
/// on the exterior wall of each room.
fn two_room_house() -> (Scene, BTreeMap<String, Mesh>) {
    let mut arch = Architecture::rectangular_room(8.0, 4.0, 2.6, 0.9);
    arch.doors[0].offset = 2.0;
    arch.doors[0].joins = Some(["living_room".into(), EXTERIOR.into()]);
    arch.walls.push(Wall {
        id: "wall_4".into(),
        start: Point2::new(0.0, 2.0),
        end: Point2::new(0.0, -2.0),
        height: 2.6,
        thickness: 0.1,
    });
    arch.doors.push(DoorOpening {
        id: "door_1".into(),
        wall: "wall_4".into(),
        offset: 1.0,
        width: 0.8,
        height: 2.0,
        leaf: Some(DoorLeaf::default()),
        joins: Some(["living_room".into(), "bedroom".into()]),
    });
    let rect = |id: &str, kind: &str, x0: f64, x1: f64| RoomArea {
        id: id.into(),
        room_type: kind.into(),
        polygon: [(x0, -2.0), (x1, -2.0), (x1, 2.0), (x0, 2.0)]
            .iter()
            .map(|&(x, z)| Point2::new(x, z))
            .collect(),
    };
    arch.rooms = vec![
        rect("living_room", "living room", -4.0, -0.05),
        rect("bedroom", "bedroom", 0.05, 4.0),
    ];
    // wall_0 runs from x = 4.05 to −4.05 along the back: 2.05 m in is the bedroom's.
    arch.windows = vec![
        window("window_0", "wall_0", 2.05, Some("bedroom")),
        window("window_1", "wall_0", 6.05, Some("living_room")),
        window("window_2", "wall_1", 2.05, Some("living_room")),
    ];
    let mut scene = Scene::new(arch);
    scene.prompt = "a two-room test house".into();
    let meshes = BTreeMap::from([
        ("table".to_owned(), table()),
        ("crate".to_owned(), crate_mesh()),
    ]);
    let ground = || ParentRef::Ground;
    let mut table = object(
        "table",
        "table",
        &meshes["table"],
        Pose::new(1.0, 0.0, Vector3::new(-2.0, 0.0, -1.4)),
        ground(),
        RelationKind::OnFloor,
    );
    table.room = Some("living_room".into());
    let mut crate_ = object(
        "crate",
        "crate",
        &meshes["crate"],
        Pose::new(1.0, 0.0, Vector3::new(2.0, 0.0, 1.0)),
        ground(),
        RelationKind::OnFloor,
    );
    crate_.room = Some("bedroom".into());
    scene.objects = vec![table, crate_];
    (scene, meshes)
}

/// Every format of `scene` written into `dir` with its `scene.json`.
fn write_every_format(scene: &Scene, meshes: &BTreeMap<String, Mesh>, dir: &std::path::Path) {
    scene.validate().expect("the hand-built scene is valid");
    let export = ExportScene::new(scene, meshes).unwrap();
    std::fs::create_dir_all(dir).unwrap();
    for format in Format::ALL {
        format.write(&export, dir).unwrap();
    }
    scene.write_json_atomic(&dir.join("scene.json")).unwrap();
}

#[test]
fn windows_and_houses_write_their_files() {
    let temp = tempfile::tempdir().unwrap();
    let dir = common::export_dir(temp.path());
    let (room, room_meshes) = room_with_windows();
    write_every_format(&room, &room_meshes, &dir.join("window"));
    let (house, house_meshes) = two_room_house();
    write_every_format(&house, &house_meshes, &dir.join("house"));

    let bytes = std::fs::read(dir.join("house/scene.glb")).unwrap();
    let gltf = gltf::Gltf::from_slice(&bytes).expect("GLB must parse");
    let roots: Vec<_> = gltf.default_scene().unwrap().nodes().collect();
    let root_names: Vec<_> = roots.iter().map(|n| n.name().unwrap()).collect();
    assert_eq!(
        root_names,
        [
            "floor",
            "wall_0",
            "wall_1",
            "wall_2",
            "wall_3",
            "wall_4",
            "window_0",
            "window_1",
            "window_2",
            "living_room",
            "bedroom"
        ]
    );
    let children = |name: &str| -> Vec<String> {
        let node = roots.iter().find(|n| n.name() == Some(name)).unwrap();
        node.children()
            .map(|c| c.name().unwrap().to_owned())
            .collect()
    };
    assert_eq!(children("living_room"), ["table"]);
    assert_eq!(children("bedroom"), ["crate"]);
    // A window's pane is glass that lets light through.
    let pane = roots.iter().find(|n| n.name() == Some("window_0")).unwrap();
    let material = pane.mesh().unwrap().primitives().next().unwrap().material();
    assert_eq!(material.name(), Some("glass"));
    assert!(
        gltf.extensions_used()
            .any(|e| e == "KHR_materials_transmission"),
        "the pane transmits light"
    );
    // The back wall has two window holes: pier, sill, lintel, pier, sill, lintel, pier.
    let wall = roots.iter().find(|n| n.name() == Some("wall_0")).unwrap();
    assert_eq!(wall.mesh().unwrap().primitives().count(), 7);

    let xml = std::fs::read_to_string(dir.join("house/scene.mjcf.xml")).unwrap();
    let urdf = std::fs::read_to_string(dir.join("house/scene.urdf")).unwrap();
    let usda = std::fs::read_to_string(dir.join("house/scene.usda")).unwrap();
    for id in ["window_0", "window_1", "window_2"] {
        assert!(
            xml.contains(&format!("<geom name=\"{id}_0\" type=\"box\"")),
            "{id}"
        );
        assert!(urdf.contains(&format!("<link name=\"{id}\">")), "{id}");
        assert!(usda.contains(&format!("def Xform \"{id}\"")), "{id}");
    }
}
