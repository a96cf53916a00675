//! Every exporter on an articulated object: a cabinet whose door is hinged on its left edge
//! (open 0.3 rad in the scene) and whose drawer (closed) holds a soap bar, a vase on the
//! cabinet's top and a stool beside it. The GLB is parsed back with the `gltf` crate; USD,
//! MJCF and URDF are checked structurally. When `SCENETHESIS_EXPORT_DIR` is set,
//! `articulated_scene_writes_every_format` also writes the exports there for the Python
//! consumer check (`crates/export/tests/consumers/check_exports.py`: MuJoCo drives the joints,
//! OpenUSD and yourdfpy read them).

use std::collections::BTreeMap;

use nalgebra::{Matrix4, Point3, Vector3, Vector4};
use scenethesis_export::{glb, mjcf, urdf, usd, ExportScene, Format};

mod common;
use common::object;
use scenethesis_scene_graph::{
    Aabb, Architecture, Joint, JointKind, JointState, Material, Mesh, MeshPart, OpensTo, ParentRef,
    Pose, RelationKind, Scene,
};

const DOOR_STATE: f32 = 0.3;

fn part(name: &str, joint: Option<&str>, min: [f32; 3], max: [f32; 3]) -> MeshPart {
    MeshPart {
        joint: joint.map(Into::into),
        ..MeshPart::cuboid(name, 0, min, max)
    }
}

/// A 0.8 × 0.9 × 0.5 m carcass open at the front (+Z), a divider at 0.6 m, a drawer above it
/// and an overlay door below.
fn cabinet() -> Mesh {
    let d = Some("drawer");
    let door = Some("door");
    Mesh {
        parts: vec![
            part("bottom", None, [-0.4, 0.0, -0.25], [0.4, 0.02, 0.25]),
            part("top", None, [-0.4, 0.88, -0.25], [0.4, 0.9, 0.25]),
            part("left", None, [-0.4, 0.02, -0.25], [-0.38, 0.88, 0.25]),
            part("right", None, [0.38, 0.02, -0.25], [0.4, 0.88, 0.25]),
            part("back", None, [-0.38, 0.02, -0.25], [0.38, 0.88, -0.23]),
            part("divider", None, [-0.38, 0.58, -0.23], [0.38, 0.6, 0.25]),
            part("drawer_bottom", d, [-0.37, 0.61, -0.2], [0.37, 0.62, 0.23]),
            part("drawer_left", d, [-0.37, 0.62, -0.2], [-0.36, 0.75, 0.23]),
            part("drawer_right", d, [0.36, 0.62, -0.2], [0.37, 0.75, 0.23]),
            part("drawer_back", d, [-0.36, 0.62, -0.2], [0.36, 0.75, -0.19]),
            part(
                "drawer_front",
                d,
                [-0.375, 0.605, 0.23],
                [0.375, 0.875, 0.25],
            ),
            part("drawer_handle", d, [-0.08, 0.73, 0.25], [0.08, 0.75, 0.28]),
            part("door_leaf", door, [-0.4, 0.025, 0.25], [0.4, 0.575, 0.27]),
            part("door_handle", door, [0.3, 0.25, 0.27], [0.33, 0.35, 0.3]),
        ],
        materials: vec![Material::new("birch", [0.8, 0.7, 0.5], 0.7)],
    }
}

/// A joint on the body, closed, opening from 0 to `upper`.
fn closed(
    name: &str,
    kind: JointKind,
    axis: [f32; 3],
    anchor: [f32; 3],
    upper: f32,
    opens_to: OpensTo,
) -> JointState {
    JointState {
        joint: Joint {
            name: name.into(),
            kind,
            axis,
            anchor,
            limits: [0.0, upper],
            opens_to,
            parent: None,
        },
        state: 0.0,
    }
}

fn joints() -> Vec<JointState> {
    let door = closed(
        "door",
        JointKind::Revolute,
        [0.0, -1.0, 0.0],
        [-0.4, 0.3, 0.27],
        1.9,
        OpensTo::Left,
    );
    vec![
        JointState {
            state: DOOR_STATE,
            ..door
        },
        closed(
            "drawer",
            JointKind::Prismatic,
            [0.0, 0.0, 1.0],
            [0.0, 0.74, 0.25],
            0.35,
            OpensTo::Out,
        ),
    ]
}

/// A 0.5 m box on a plinth, open at the front, with a door hinged along its bottom edge that
/// drops open (an oven): gravity pulls it open, so the joint must hold it closed.
fn oven() -> Mesh {
    let door = Some("door");
    Mesh {
        parts: vec![
            part("plinth", None, [-0.25, 0.0, -0.25], [0.25, 0.1, 0.28]),
            part("top", None, [-0.25, 0.58, -0.25], [0.25, 0.6, 0.25]),
            part("left", None, [-0.25, 0.1, -0.25], [-0.23, 0.58, 0.25]),
            part("right", None, [0.23, 0.1, -0.25], [0.25, 0.58, 0.25]),
            part("back", None, [-0.23, 0.1, -0.25], [0.23, 0.58, -0.23]),
            part("door_panel", door, [-0.25, 0.1, 0.25], [0.25, 0.6, 0.28]),
        ],
        materials: vec![Material::new("enamel", [0.9, 0.9, 0.9], 0.3)],
    }
}

fn oven_door() -> JointState {
    closed(
        "door",
        JointKind::Revolute,
        [1.0, 0.0, 0.0],
        [0.0, 0.1, 0.25],
        1.5,
        OpensTo::Down,
    )
}

fn single(name: &str, min: [f32; 3], max: [f32; 3], color: [f32; 3]) -> Mesh {
    Mesh {
        parts: vec![MeshPart::cuboid(name, 0, min, max)],
        materials: vec![Material::new(name, color, 0.6)],
    }
}

/// The asset-frame box of a mesh with each part moved by its joint's state (one level).
fn posed_bounds(mesh: &Mesh, joints: &[JointState]) -> Aabb {
    let mut points = mesh.parts.iter().flat_map(|p| {
        let joint = joints
            .iter()
            .find(|j| Some(&j.joint.name) == p.joint.as_ref());
        p.positions.iter().map(move |&q| match joint {
            Some(j) => j.joint.moved_point(j.state, q),
            None => q,
        })
    });
    let first = Point3::from(points.next().unwrap()).cast::<f64>();
    points.fold(Aabb::new(first, first), |b, q| {
        b.including(&Point3::from(q).cast())
    })
}

/// The cabinet against the back wall of a 4 × 4 m room, the soap in its drawer, a vase on top
/// and a stool beside it; an oven (turned to face +X) by the left wall.
fn scene() -> (Scene, BTreeMap<String, Mesh>) {
    let mut scene = Scene::new(Architecture::rectangular_room(4.0, 4.0, 2.5, 0.9));
    scene.prompt = "a cabinet with a door and a drawer".into();
    let meshes = BTreeMap::from([
        ("cabinet".to_owned(), cabinet()),
        (
            "soap".to_owned(),
            single(
                "soap",
                [-0.05, 0.0, -0.04],
                [0.05, 0.05, 0.04],
                [0.9, 0.9, 1.0],
            ),
        ),
        (
            "vase".to_owned(),
            single(
                "vase",
                [-0.06, 0.0, -0.06],
                [0.06, 0.2, 0.06],
                [0.2, 0.4, 0.8],
            ),
        ),
        ("oven".to_owned(), oven()),
        (
            "stool".to_owned(),
            single(
                "stool",
                [-0.15, 0.0, -0.15],
                [0.15, 0.45, 0.15],
                [0.3, 0.3, 0.3],
            ),
        ),
    ]);
    let mut cabinet = object(
        "cabinet",
        "cabinet",
        &meshes["cabinet"],
        Pose::new(1.0, 0.0, Vector3::new(0.0, 0.0, -1.7)),
        ParentRef::Ground,
        RelationKind::AgainstWall,
    );
    cabinet.joints = joints();
    cabinet.local_bounds = posed_bounds(&meshes["cabinet"], &cabinet.joints);
    let mut soap = object(
        "soap",
        "soap",
        &meshes["soap"],
        Pose::new(1.0, 0.0, Vector3::new(0.0, 0.62, -1.7)),
        ParentRef::Object("cabinet".into()),
        RelationKind::Inside,
    );
    soap.parent_link = Some("drawer".into());
    let vase = object(
        "vase",
        "vase",
        &meshes["vase"],
        Pose::new(1.0, 0.0, Vector3::new(0.2, 0.9, -1.75)),
        ParentRef::Object("cabinet".into()),
        RelationKind::On,
    );
    let stool = object(
        "stool",
        "stool",
        &meshes["stool"],
        Pose::new(1.0, 0.0, Vector3::new(0.8, 0.0, -1.6)),
        ParentRef::Ground,
        RelationKind::OnFloor,
    );
    let mut oven = object(
        "oven",
        "oven",
        &meshes["oven"],
        Pose::new(
            1.0,
            std::f64::consts::FRAC_PI_2,
            Vector3::new(-1.5, 0.0, 0.0),
        ),
        ParentRef::Ground,
        RelationKind::OnFloor,
    );
    oven.joints = vec![oven_door()];
    scene.objects = vec![cabinet, soap, vase, stool, oven];
    scene.validate().unwrap();
    (scene, meshes)
}

fn export_of<'a>(scene: &'a Scene, meshes: &'a BTreeMap<String, Mesh>) -> ExportScene<'a> {
    ExportScene::new(scene, meshes).unwrap()
}

#[test]
fn articulated_scene_writes_every_format() {
    let (scene, meshes) = scene();
    let export = export_of(&scene, &meshes);
    let temp = tempfile::tempdir().unwrap();
    let dir = common::export_dir(temp.path());
    scenethesis_export::write_formats(&Format::ALL, &export, &dir).unwrap();
    assert!(dir.join("meshes/cabinet_drawer_drawer_front.obj").exists());
    scene.write_json_atomic(&dir.join("scene.json")).unwrap();
}

#[test]
fn glb_nests_a_node_per_link_pivoting_at_its_joint() {
    let (scene, meshes) = scene();
    let bytes = glb::to_glb(&export_of(&scene, &meshes));
    let gltf = gltf::Gltf::from_slice(&bytes).expect("GLB must parse");
    let blob = gltf.blob.as_deref().unwrap();
    let roots: Vec<&str> = gltf
        .default_scene()
        .unwrap()
        .nodes()
        .map(|n| n.name().unwrap())
        .collect();
    assert_eq!(
        roots,
        [
            "floor", "wall_0", "wall_1", "wall_2", "wall_3", "cabinet", "soap", "vase", "stool",
            "oven"
        ]
    );
    let cabinet = gltf.nodes().find(|n| n.name() == Some("cabinet")).unwrap();
    let children: Vec<&str> = cabinet.children().map(|n| n.name().unwrap()).collect();
    assert_eq!(children, ["cabinet_door", "cabinet_drawer"]);
    assert_eq!(cabinet.mesh().unwrap().primitives().count(), 6, "the body");
    let object_matrix = Matrix4::from(cabinet.transform().matrix());
    for link in cabinet.children() {
        let extras: serde_json::Value =
            serde_json::from_str(link.extras().as_ref().unwrap().get()).unwrap();
        let joint: JointState = serde_json::from_value(extras["joint"].clone()).unwrap();
        let original = joints()
            .into_iter()
            .find(|j| j.joint.name == joint.joint.name)
            .unwrap();
        assert_eq!(joint, original, "the joint as scene.json writes it");
        // Every link vertex, through the node's transform, lands where the joint's motion puts
        // the closed part.
        let world = object_matrix * Matrix4::from(link.transform().matrix());
        let mut drawn: Vec<[f32; 3]> = Vec::new();
        for prim in link.mesh().unwrap().primitives() {
            let positions = prim.reader(|_| Some(blob)).read_positions().unwrap();
            drawn.extend(positions.map(|p| {
                let w = world * Vector4::new(p[0], p[1], p[2], 1.0);
                [w.x, w.y, w.z]
            }));
        }
        let pose = &scene.objects[0].pose;
        for part in meshes["cabinet"]
            .parts
            .iter()
            .filter(|p| p.joint.as_deref() == Some(joint.joint.name.as_str()))
        {
            for &p in &part.positions {
                let moved = joint.joint.moved_point(joint.state, p);
                let want = pose.transform_point(&Point3::from(moved).cast::<f64>());
                assert!(
                    drawn
                        .iter()
                        .any(|d| (Vector3::from(*d).cast::<f64>() - want.coords).norm() < 1e-5),
                    "{} vertex {p:?} not drawn at {want:?}",
                    joint.joint.name
                );
            }
        }
    }
}

#[test]
fn mjcf_nests_hinge_and_slide_bodies_in_the_scene_state() {
    let (scene, meshes) = scene();
    let xml = mjcf::to_mjcf(&export_of(&scene, &meshes));
    assert!(xml.contains(
        "<joint name=\"cabinet_door\" type=\"hinge\" axis=\"0 -1 0\" range=\"0 1.899999976158142\" limited=\"true\" ref=\"0.30000001192092896\""
    ), "{xml}");
    assert!(xml.contains(
        "<joint name=\"cabinet_drawer\" type=\"slide\" axis=\"0 0 1\" range=\"0 0.3499999940395355\" limited=\"true\" ref=\"0\""
    ));
    // The drawer's body sits at its anchor inside the cabinet's body.
    let cabinet = xml.find("<body name=\"cabinet\"").unwrap();
    let drawer = xml
        .find("<body name=\"cabinet_drawer\" pos=\"0 0.7400000095367432 0.25\" quat=\"1 0 0 0\">")
        .unwrap();
    let soap = xml.find("<body name=\"soap\"").unwrap();
    assert!(cabinet < drawer && drawer < soap);
    assert_eq!(xml[cabinet..soap].matches("</body>").count(), 3);
    assert_eq!(xml.matches("<freejoint ").count(), 5);
    assert!(xml.contains("<exclude body1=\"cabinet\" body2=\"cabinet_door\"/>"));
    assert!(xml.contains("<exclude body1=\"cabinet\" body2=\"cabinet_drawer\"/>"));
    // Link geoms are in the joint frame: the drawer's front starts 2 cm behind its anchor.
    assert!(xml.contains("<mesh name=\"cabinet_drawer_drawer_front\" scale=\"1 1 1\" vertex=\"-0.375 -0.13499999 -0.019999996 "));
    // The oven door (gravity pulls it open) is held by more than the least friction; the
    // cabinet's upright door needs only that.
    assert!(
        xml.contains("<joint name=\"cabinet_door\" type=\"hinge\"")
            && xml.contains("frictionloss=\"0.05\" solreffriction=\"0.002 1\"/>")
    );
    let oven = xml.find("<joint name=\"oven_door\"").unwrap();
    let friction = &xml[oven..][xml[oven..].find("frictionloss=\"").unwrap() + 14..];
    let friction: f64 = friction[..friction.find('"').unwrap()].parse().unwrap();
    // 0.5 × 0.5 × 0.03 m at 1000 kg/m³ = 7.5 kg, its far edge 0.5 m from the hinge.
    assert!((70.0..80.0).contains(&friction), "{friction}");
}

#[test]
fn a_nested_joint_hangs_inside_its_parent_link_in_every_format() {
    let (mut scene, mut meshes) = scene();
    // The drawer's handle becomes a flap hinged on the drawer's front.
    let mut flap = closed(
        "flap",
        JointKind::Revolute,
        [1.0, 0.0, 0.0],
        [0.0, 0.75, 0.25],
        1.2,
        OpensTo::Up,
    );
    flap.joint.parent = Some("drawer".into());
    scene.objects[0].joints.push(flap);
    let cabinet = meshes.get_mut("cabinet").unwrap();
    cabinet.parts[11].joint = Some("flap".into());
    let export = export_of(&scene, &meshes);

    let xml = mjcf::to_mjcf(&export);
    let drawer = xml.find("<body name=\"cabinet_drawer\"").unwrap();
    let flap = xml.find("<body name=\"cabinet_flap\"").unwrap();
    assert!(drawer < flap && !xml[drawer..flap].contains("</body>"));
    assert!(xml.contains("<exclude body1=\"cabinet_drawer\" body2=\"cabinet_flap\"/>"));
    assert!(xml.contains("<exclude body1=\"cabinet\" body2=\"cabinet_flap\"/>"));

    let package = urdf::to_urdf(&export, "m");
    assert!(package.urdf.contains(
        "<joint name=\"cabinet_flap_joint\" type=\"revolute\">\n    <parent link=\"cabinet_drawer\"/>\n    <child link=\"cabinet_flap\"/>"
    ));

    let usda = usd::to_usda(&export);
    assert!(usda.contains("rel physics:body0 = </World/cabinet/drawer>\n            rel physics:body1 = </World/cabinet/flap>"));

    let gltf = gltf::Gltf::from_slice(&glb::to_glb(&export)).unwrap();
    let drawer = gltf
        .nodes()
        .find(|n| n.name() == Some("cabinet_drawer"))
        .unwrap();
    let children: Vec<&str> = drawer.children().map(|n| n.name().unwrap()).collect();
    assert_eq!(children, ["cabinet_flap"]);
}

#[test]
fn urdf_adds_revolute_and_prismatic_links() {
    let (scene, meshes) = scene();
    let package = urdf::to_urdf(&export_of(&scene, &meshes), "meshes");
    let xml = &package.urdf;
    assert!(xml.contains("<joint name=\"cabinet_joint\" type=\"floating\">"));
    assert!(xml.contains("<link name=\"cabinet_door\">"));
    // Origin and axis in the parent's Z-up frame: scene (x, y, z) is (x, −z, y).
    assert!(xml.contains(
        "<joint name=\"cabinet_door_joint\" type=\"revolute\">\n    <parent link=\"cabinet\"/>\n    <child link=\"cabinet_door\"/>\n    <origin xyz=\"-0.4000000059604645 -0.27000001072883606 0.30000001192092896\" rpy=\"0 0 0\"/>\n    <axis xyz=\"0 0 -1\"/>\n    <limit lower=\"0\" upper=\"1.899999976158142\" effort=\"100\" velocity=\"2\"/>"
    ), "{xml}");
    assert!(xml.contains("<joint name=\"cabinet_drawer_joint\" type=\"prismatic\">"));
    assert!(xml.contains("<limit lower=\"0\" upper=\"0.3499999940395355\""));
    assert_eq!(
        xml.matches("<inertial>").count(),
        5 + 3 + 1,
        "objects, links, door leaf"
    );
    // The link's OBJ is in its joint frame.
    let obj = &package.meshes["cabinet_drawer_drawer_handle.obj"];
    assert!(obj.contains("\nv -0.08 -0.00999999 0\n"), "{obj}");
}

#[test]
fn usd_makes_each_articulated_object_an_articulation_with_limited_joints() {
    let (scene, meshes) = scene();
    let text = usd::to_usda(&export_of(&scene, &meshes));
    // Two objects and the room's door leaf.
    assert_eq!(text.matches("PhysicsArticulationRootAPI").count(), 3);
    assert_eq!(text.matches("\"PhysicsRigidBodyAPI\"").count(), 3 + 2 + 1);
    assert!(text.contains("def PhysicsRevoluteJoint \"door_joint\""));
    assert!(text.contains("def PhysicsPrismaticJoint \"drawer_joint\""));
    // The door turns about −Y: physics:axis Y turned half a turn about Z; degrees.
    assert!(text.contains("uniform token physics:axis = \"Y\""));
    assert!(text.contains("quatf physics:localRot0 = (0, 0, 0, 1)"));
    assert!(text.contains("float physics:upperLimit = 108.86197"));
    assert!(text.contains("uniform token physics:axis = \"Z\""));
    assert!(text.contains("float physics:upperLimit = 0.3499999940395355"));
    assert!(text.contains("custom double scenethesis:state = 17.188"));
    assert!(text.contains("def PhysicsScene \"PhysicsScene\""));
    assert_eq!(text.matches('{').count(), text.matches('}').count());
    // Only the articulated objects' meshes and the door leaf collide.
    assert_eq!(text.matches("\"PhysicsCollisionAPI\"").count(), 14 + 6 + 1);
}

#[test]
fn without_joints_an_object_is_written_as_a_rigid_one() {
    let (mut scene, meshes) = scene();
    scene.objects[0].joints.clear();
    scene.objects[1].parent_link = None;
    scene.objects[4].joints.clear();
    scene.architecture.doors[0].leaf = None;
    // The same mesh with no part naming a joint.
    let mut plain = meshes.clone();
    for mesh in plain.values_mut() {
        for part in &mut mesh.parts {
            part.joint = None;
        }
    }
    let tagged = export_of(&scene, &meshes);
    let untagged = export_of(&scene, &plain);
    assert_eq!(glb::to_glb(&tagged), glb::to_glb(&untagged));
    assert_eq!(usd::to_usda(&tagged), usd::to_usda(&untagged));
    assert_eq!(mjcf::to_mjcf(&tagged), mjcf::to_mjcf(&untagged));
    assert_eq!(urdf::to_urdf(&tagged, "m"), urdf::to_urdf(&untagged, "m"));
    let usda = usd::to_usda(&tagged);
    assert!(!usda.contains("Physics"));
    let xml = mjcf::to_mjcf(&tagged);
    assert!(!xml.contains("<contact>") && !xml.contains("hinge"));
}

/// The room's door leaf: hinged on the left edge seen from the room (x = 0.445 of the front
/// wall's room face z = 2.0), turning about −Y into the room, half open in the scene.
#[test]
fn a_room_doors_leaf_hangs_on_its_hinge_in_every_format() {
    let (mut scene, meshes) = scene();
    scene.architecture.doors[0].leaf.as_mut().unwrap().state = 0.5;
    let export = export_of(&scene, &meshes);

    let xml = mjcf::to_mjcf(&export);
    let door = xml.find("<body name=\"door_0\" pos=\"0 0 0\"").unwrap();
    let leaf = xml.find("<body name=\"door_0_leaf\"").unwrap();
    assert!(door < leaf && !xml[door..leaf].contains("freejoint"));
    assert!(xml.contains("<joint name=\"door_0_leaf\" type=\"hinge\" axis=\"0 -1 0\" range=\"0 1.75\" limited=\"true\" ref=\"0.5\" damping=\"1\""), "{xml}");
    assert!(xml.contains("<exclude body1=\"world\" body2=\"door_0_leaf\"/>"));
    assert!(xml.contains("<exclude body1=\"door_0\" body2=\"door_0_leaf\"/>"));

    let urdf = urdf::to_urdf(&export, "m").urdf;
    assert!(urdf.contains("<joint name=\"door_0_leaf_joint\" type=\"revolute\">\n    <parent link=\"world\"/>\n    <child link=\"door_0_leaf\"/>\n    <origin xyz=\"0.44"), "{urdf}");
    assert!(urdf.contains("<axis xyz=\"0 0 -1\"/>\n    <limit lower=\"0\" upper=\"1.75\""));

    let usda = usd::to_usda(&export);
    let prim = usda
        .find(
            "def Xform \"door_0\" (\n        prepend apiSchemas = [\"PhysicsArticulationRootAPI\"]",
        )
        .unwrap();
    let joint = usda[prim..]
        .find("def PhysicsRevoluteJoint \"leaf_joint\"")
        .unwrap()
        + prim;
    let end = joint + usda[joint..].find("}").unwrap();
    let joint = &usda[joint..end];
    assert!(
        !joint.contains("physics:body0"),
        "joined to the world: {joint}"
    );
    assert!(joint.contains("rel physics:body1 = </World/door_0/leaf>"));
    assert!(
        joint.contains("float physics:upperLimit = 100.26761"),
        "{joint}"
    );

    let bytes = glb::to_glb(&export);
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    let wall = gltf.nodes().find(|n| n.name() == Some("wall_2")).unwrap();
    let leaf = wall.children().next().expect("the leaf under its wall");
    assert_eq!(leaf.name(), Some("door_0_leaf"));
    let (t, r, _) = leaf.transform().decomposed();
    assert!(
        (t[0] - 0.445).abs() < 1e-6 && t[1] == 0.0 && (t[2] - 2.0).abs() < 1e-6,
        "{t:?}"
    );
    // Turned 0.5 rad about −Y.
    assert!((r[1] + (0.25f32).sin()).abs() < 1e-6, "{r:?}");
    let extras: serde_json::Value =
        serde_json::from_str(leaf.extras().as_ref().unwrap().get()).unwrap();
    let joint: JointState = serde_json::from_value(extras["joint"].clone()).unwrap();
    let want = scene
        .architecture
        .door_leaf(&scene.architecture.doors[0])
        .unwrap();
    assert_eq!(joint, want.joint);
}

/// A double door: both leaves hang, mirrored on opposite jambs, each on its own joint, in
/// every format.
#[test]
fn a_double_doors_two_leaves_hang_in_every_format() {
    let (mut scene, meshes) = scene();
    let door = &mut scene.architecture.doors[0];
    door.width = 1.6;
    door.leaf.as_mut().unwrap().double = true;
    assert!(scene.validate().is_ok());
    let export = export_of(&scene, &meshes);

    let xml = mjcf::to_mjcf(&export);
    for leaf in ["door_0_leaf", "door_0_leaf_2"] {
        assert!(xml.contains(&format!("<body name=\"{leaf}\"")), "{xml}");
        assert!(xml.contains(&format!("<joint name=\"{leaf}\" type=\"hinge\"")));
        assert!(xml.contains(&format!("<exclude body1=\"world\" body2=\"{leaf}\"/>")));
    }
    // Mirrored: one turns about −Y, the other about +Y.
    assert!(xml.contains("axis=\"0 -1 0\"") && xml.contains("axis=\"0 1 0\""));

    let urdf = urdf::to_urdf(&export, "m").urdf;
    for leaf in ["door_0_leaf", "door_0_leaf_2"] {
        assert!(
            urdf.contains(&format!("<joint name=\"{leaf}_joint\" type=\"revolute\">")),
            "{urdf}"
        );
    }

    let usda = usd::to_usda(&export);
    assert!(usda.contains("def PhysicsRevoluteJoint \"leaf_joint\""));
    assert!(
        usda.contains("def PhysicsRevoluteJoint \"leaf_2_joint\""),
        "{usda}"
    );

    let bytes = glb::to_glb(&export);
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    let wall = gltf.nodes().find(|n| n.name() == Some("wall_2")).unwrap();
    let names: Vec<_> = wall
        .children()
        .filter_map(|n| n.name().map(str::to_owned))
        .collect();
    assert_eq!(names, ["door_0_leaf", "door_0_leaf_2"]);
    let hinges: Vec<f32> = wall
        .children()
        .map(|n| n.transform().decomposed().0[0])
        .collect();
    // At the jambs, x = ±(0.8 − 0.005).
    assert!(
        (hinges[0] + hinges[1]).abs() < 1e-6 && (hinges[0].abs() - 0.795).abs() < 1e-6,
        "{hinges:?}"
    );
}
