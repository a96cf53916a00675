//! Joints declared in `assets.json`: carried into the asset frame with the mesh, or refused
//! with one error naming the manifest, the entry and the field.

use super::*;

/// A 40 × 50 × 80 cm cabinet modelled Z-up in centimetres, its front toward −Y (the normalised
/// +Z): a `body` node and, in front of it, a 2 cm thick `door` node.
fn cabinet_z_up_cm() -> Vec<u8> {
    let body = vec![box_prim([-20.0, -25.0, 0.0], [20.0, 25.0, 80.0], 0)];
    let door = vec![box_prim([-20.0, -27.0, 0.0], [20.0, -25.0, 80.0], 1)];
    let nodes = json!([
        {"name": "cabinet", "children": [1, 2]},
        {"name": "body", "mesh": 0},
        {"name": "door", "mesh": 1}
    ]);
    let (doc, bin) = gltf_document(&[body, door], nodes, None);
    glb_bytes(&doc, &bin)
}

/// The door's hinge in the file: its left edge seen from the front (x = −20) at the door's
/// outer face (y = −27), turning about −Z (the normalised −Y) so that it swings out.
fn door_joint() -> serde_json::Value {
    json!({"part": "door", "name": "door", "kind": "revolute", "axis": [0, 0, -1],
           "anchor": [-20, -27, 0], "limits": [0, 1.7], "opens_to": "left"})
}

/// A folder holding the cabinet and a manifest entry with `joints`.
fn cabinet_folder(joints: serde_json::Value) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "cabinet.glb", &cabinet_z_up_cm());
    let entry = json!([{"file": "cabinet.glb", "category": "cabinet", "up_axis": "z",
                        "unit_scale": 0.01, "joints": joints}]);
    write(dir.path(), MANIFEST_FILE, entry.to_string().as_bytes());
    dir
}

#[test]
fn a_declared_door_hinge_lands_on_the_normalised_door_edge() {
    let dir = cabinet_folder(json!([door_joint()]));
    let report = import_directory(dir.path()).unwrap();
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    let asset = &report.assets[0];
    let [joint] = &asset.info.joints[..] else {
        panic!("one joint: {:?}", asset.info.joints);
    };
    // Metres, +Y up, origin at the footprint centre: z spans −0.25 .. 0.27 before centring.
    let near = |a: [f32; 3], b: [f32; 3]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-5);
    assert!(near(joint.anchor, [-0.2, 0.0, 0.26]), "{:?}", joint.anchor);
    assert!(near(joint.axis, [0.0, -1.0, 0.0]), "{:?}", joint.axis);
    assert_eq!(joint.limits, [0.0, 1.7]);
    for part in &asset.mesh.parts {
        let moves = part.name.starts_with("door");
        assert_eq!(
            part.joint.as_deref(),
            moves.then_some("door"),
            "{}",
            part.name
        );
    }
    // The 40 cm leaf swings out in front of the cabinet, past square (0.9 × 1.7 rad).
    let swept = asset.info.opening_bounds.expect("the door sweeps a box");
    assert!((swept.max.z - (0.26 + 0.4)).abs() < 0.01, "{swept:?}");
    assert!(
        swept.min.x >= -0.2 - 0.03 && swept.max.x <= 0.2 + 1e-4,
        "{swept:?}"
    );
    assert!((swept.max.y - 0.8).abs() < 1e-4, "{swept:?}");
    assert!(
        near(asset.info.size, [0.4, 0.8, 0.52]),
        "{:?}",
        asset.info.size
    );
}

#[test]
fn a_drawer_slides_its_file_units_scaled_to_metres() {
    let drawer = json!({"part": "door", "name": "drawer", "kind": "prismatic",
                        "axis": [0, -2, 0], "anchor": [0, -27, 40], "limits": [0, 30],
                        "opens_to": "out"});
    let report = import_directory(cabinet_folder(json!([drawer])).path()).unwrap();
    let joint = &report.assets[0].info.joints[0];
    assert_eq!(joint.limits, [0.0, 30.0 * 0.01]);
    assert!((joint.axis[2] - 1.0).abs() < 1e-6, "{:?}", joint.axis);
    let swept = report.assets[0].info.opening_bounds.unwrap();
    assert!((swept.max.z - (0.26 + 0.9 * 0.3)).abs() < 1e-4, "{swept:?}");
}

/// The error importing the cabinet with `joints`, as displayed.
fn joint_error(joints: serde_json::Value) -> String {
    let dir = cabinet_folder(joints);
    let before: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    let e = import_directory(dir.path()).unwrap_err();
    assert!(matches!(e, ImportError::Joint { .. }), "{e:?}");
    let after: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(before.len(), after.len(), "nothing is written");
    let text = e.to_string();
    assert!(
        text.contains("assets.json: entry #0 (file `cabinet.glb`): joints"),
        "{text}"
    );
    text
}

#[test]
fn malformed_joints_fail_the_import_naming_file_entry_and_field() {
    let with = |patch: serde_json::Value| {
        let mut j = door_joint();
        for (k, v) in patch.as_object().unwrap() {
            j[k] = v.clone();
        }
        j
    };
    let cases = [
        (json!([with(json!({"axis": [0, 0, 0]}))]), "joints[0].axis is [0, 0, 0]; expected a finite, non-zero direction"),
        (json!([with(json!({"limits": [1.7, 0]}))]), "joints[0].limits is [1.7, 0]; expected [lower, upper] with lower <= 0 <= upper"),
        (json!([with(json!({"limits": [0.5, 1.7]}))]), "joints[0].limits is [0.5, 1.7]"),
        (json!([with(json!({"limits": [0, 100]}))]), "joints[0].limits is [0, 100]; expected limits within"),
        (json!([with(json!({"part": "drawer"}))]), "joints[0].part is \"drawer\", which the file does not hold; expected one of its parts: \"body\", \"door\""),
        (json!([door_joint(), door_joint()]), "joints[1].name is \"door\", as joints[0]'s"),
        (json!([with(json!({"parent": "body"}))]), "joints[0].parent is \"body\"; expected the name of a joint listed before it"),
        (json!([door_joint(), with(json!({"name": "door_2"}))]), "joints[1].part is \"door\", which joints[0] already moves"),
        (json!([with(json!({"kind": "hinge"}))]), "joints[0].kind is \"hinge\"; expected \"revolute\" or \"prismatic\""),
        (json!([with(json!({"hinge": 1}))]), "joints[0].hinge is not a joint field"),
        (json!([{"part": "door", "name": "door"}]), "joints[0].kind is missing"),
        (json!([with(json!({"anchor": [0, 0, 1e7]}))]), "joints[0].anchor is"),
    ];
    for (joints, expected) in cases {
        let text = joint_error(joints);
        assert!(text.contains(expected), "expected `{expected}` in: {text}");
    }
    let text = joint_error(json!({"part": "door"}));
    assert!(text.contains("joints is {"), "{text}");
}

#[test]
fn a_malformed_joint_fails_even_when_its_file_is_missing() {
    let dir = tempfile::tempdir().unwrap();
    let mut joint = door_joint();
    joint["axis"] = json!([0, 0, 0]);
    let entry = json!([{"file": "gone.glb", "category": "cabinet", "joints": [joint]}]);
    write(dir.path(), MANIFEST_FILE, entry.to_string().as_bytes());
    let e = import_directory(dir.path()).unwrap_err().to_string();
    assert!(
        e.contains("entry #0 (file `gone.glb`): joints[0].axis"),
        "{e}"
    );
}
