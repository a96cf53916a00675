//! `scenethesis eval` on a GLB scene written here.

use std::path::Path;
use std::process::Command;

use scenethesis_scene_graph::MeshPart;

/// Writes a GLB with one box node per (name, min, max).
fn write_boxes_glb(path: &Path, boxes: &[(&str, [f32; 3], [f32; 3])]) {
    let mut bin = Vec::new();
    let (mut views, mut accessors, mut meshes, mut nodes) = (vec![], vec![], vec![], vec![]);
    for (k, (name, min, max)) in boxes.iter().enumerate() {
        let MeshPart {
            positions,
            triangles,
            ..
        } = MeshPart::cuboid(*name, 0, *min, *max);
        let pos_offset = bin.len();
        for p in &positions {
            for v in p {
                bin.extend_from_slice(&v.to_le_bytes());
            }
        }
        let idx_offset = bin.len();
        for t in &triangles {
            for i in t {
                bin.extend_from_slice(&(*i).to_le_bytes());
            }
        }
        views.push(serde_json::json!({"buffer": 0, "byteOffset": pos_offset, "byteLength": 96}));
        views.push(serde_json::json!({"buffer": 0, "byteOffset": idx_offset, "byteLength": 144}));
        accessors.push(serde_json::json!({"bufferView": 2 * k, "componentType": 5126, "count": 8, "type": "VEC3", "min": min, "max": max}));
        accessors.push(serde_json::json!({"bufferView": 2 * k + 1, "componentType": 5125, "count": 36, "type": "SCALAR"}));
        meshes.push(serde_json::json!({"primitives": [{"attributes": {"POSITION": 2 * k}, "indices": 2 * k + 1}]}));
        nodes.push(serde_json::json!({"name": name, "mesh": k}));
    }
    let json = serde_json::json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": (0..boxes.len()).collect::<Vec<_>>()}],
        "nodes": nodes, "meshes": meshes, "accessors": accessors, "bufferViews": views,
        "buffers": [{"byteLength": bin.len()}],
    });
    let mut json = serde_json::to_vec(&json).unwrap();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    std::fs::write(path, out).unwrap();
}

fn scenethesis(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_scenethesis"))
        .args(args)
        .output()
        .expect("run scenethesis")
}

#[test]
fn eval_reports_colliding_boxes_of_a_foreign_glb_as_json_and_as_a_table() {
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("boxes.glb");
    write_boxes_glb(
        &glb,
        &[
            ("floor", [-2.0, -0.1, -2.0], [2.0, 0.0, 2.0]),
            ("crate_0", [-0.5, 0.0, -0.25], [0.0, 0.5, 0.25]),
            // Overlaps crate_0 by 10 cm.
            ("crate_1", [-0.1, 0.0, -0.25], [0.4, 0.5, 0.25]),
            ("stool", [1.0, 0.0, 1.0], [1.4, 0.45, 1.4]),
        ],
    );
    let glb_arg = glb.to_str().unwrap();
    let out = scenethesis(&["eval", glb_arg, "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let metrics: serde_json::Value = serde_json::from_slice(&out.stdout).expect("one JSON object");
    assert_eq!(metrics["objects"], 3);
    assert_eq!(metrics["categories"], 2);
    assert!(
        (metrics["col_o"].as_f64().unwrap() - 2.0 / 3.0).abs() < 1e-9,
        "{metrics}"
    );
    let depth = metrics["colliding_pairs"][0]["depth"].as_f64().unwrap();
    assert!((depth - 0.1).abs() < 2e-3, "{depth}");
    assert_eq!(metrics["reach_floor"], 1.0);

    let out = scenethesis(&["eval", glb_arg]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("Col-O") && text.contains("66.7 %"), "{text}");
    assert!(text.contains("crate_0 / crate_1"), "{text}");
}

#[test]
fn eval_names_a_missing_path_in_its_error() {
    let out = scenethesis(&["eval", "/nonexistent/scene.glb"]);
    assert!(!out.status.success());
    let text = String::from_utf8_lossy(&out.stderr);
    assert!(text.contains("/nonexistent/scene.glb"), "{text}");
}
