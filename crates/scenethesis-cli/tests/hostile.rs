//! Hostile input, as an attacker would hand it to the built binary: every case must end in a
//! clear error (or a warning and a good result), never a panic, an abort, a huge allocation, a
//! raw escape sequence on the terminal, or a file read from outside an asset folder.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn scenethesis(args: &[&str], cwd: Option<&Path>) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_scenethesis"));
    cmd.args(args).env_remove("RUST_LOG");
    if let Some(dir) = cwd {
        cmd.current_dir(dir);
    }
    cmd.output().expect("run scenethesis")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Fails unless the run ended with a clean error (exit 1) whose text contains every needle.
fn assert_clean_failure(out: &Output, needles: &[&str]) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(1), "expected exit 1: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!err.contains("overflow"), "{err}");
    assert!(
        !err.contains('\u{1b}'),
        "raw escape on the terminal: {err:?}"
    );
    for n in needles {
        assert!(err.contains(n), "missing `{n}` in: {err}");
    }
}

fn fixture() -> serde_json::Value {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/scenes/valid_living_room.json"
    );
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn write_scene(dir: &Path, scene: &serde_json::Value) -> PathBuf {
    let path = dir.join("scene.json");
    std::fs::write(&path, serde_json::to_string_pretty(scene).unwrap()).unwrap();
    path
}

/// A minimal GLB: one triangle mesh and the given nodes.
fn glb(nodes: serde_json::Value) -> Vec<u8> {
    let mut bin = Vec::new();
    for v in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for c in v {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    for i in [0u32, 1, 2] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let doc = serde_json::json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": nodes,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5125, "count": 3, "type": "SCALAR"}
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 12}
        ],
        "buffers": [{"byteLength": 48}]
    });
    let mut json = serde_json::to_vec(&doc).unwrap();
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
    out
}

#[test]
fn eval_of_a_glb_with_a_node_cycle_is_an_error_not_a_stack_overflow() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("cycle.glb");
    let nodes = serde_json::json!([
        {"name": "chair", "mesh": 0, "children": [1]},
        {"name": "seat", "mesh": 0, "children": [0]}
    ]);
    std::fs::write(&path, glb(nodes)).unwrap();
    let out = scenethesis(&["eval", path.to_str().unwrap()], None);
    assert_clean_failure(&out, &["cycle.glb"]);
}

#[test]
fn eval_of_dev_zero_and_of_truncated_files_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    #[cfg(unix)]
    {
        let link = dir.path().join("zero.glb");
        std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
        let out = scenethesis(&["eval", link.to_str().unwrap()], None);
        assert_clean_failure(&out, &["zero.glb", "regular file"]);
    }
    let bytes = glb(serde_json::json!([{"name": "chair", "mesh": 0}]));
    let cut = dir.path().join("cut.glb");
    std::fs::write(&cut, &bytes[..bytes.len() - 10]).unwrap();
    let out = scenethesis(&["eval", cut.to_str().unwrap()], None);
    assert_clean_failure(&out, &["cut.glb"]);
}

#[test]
fn eval_of_a_glb_with_nan_or_absurd_transforms_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("far.glb");
    std::fs::write(
        &path,
        glb(serde_json::json!([{"name": "chair", "mesh": 0, "translation": [1e20, 0, 0]}])),
    )
    .unwrap();
    let out = scenethesis(&["eval", path.to_str().unwrap()], None);
    assert_clean_failure(&out, &["far.glb", "nodes[0]"]);
}

#[test]
fn a_1e308_translation_is_refused_by_validate_and_eval_with_object_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let mut scene = fixture();
    scene["objects"]["sofa_0"]["pose"]["translation"][0] = serde_json::json!(1e308);
    let path = write_scene(dir.path(), &scene);
    let out = scenethesis(&["validate", path.to_str().unwrap()], None);
    assert_clean_failure(&out, &["sofa_0", "pose.translation", "1e308"]);
    let out = scenethesis(&["eval", path.to_str().unwrap()], None);
    assert_clean_failure(&out, &["sofa_0", "pose.translation"]);
    let out = scenethesis(
        &["export", dir.path().to_str().unwrap(), "--format", "glb"],
        None,
    );
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(!stderr(&out).contains("panicked"));
}

#[test]
fn a_sofa_at_scale_100_is_refused_before_eval_allocates_anything() {
    let dir = tempfile::tempdir().unwrap();
    let mut scene = fixture();
    scene["objects"]["sofa_0"]["pose"]["scale"] = serde_json::json!(100.0);
    let path = write_scene(dir.path(), &scene);
    let start = std::time::Instant::now();
    let out = scenethesis(&["eval", path.to_str().unwrap()], None);
    assert_clean_failure(&out, &["sofa_0", "pose.scale"]);
    assert!(start.elapsed().as_secs() < 30);
}

#[test]
fn ids_with_escape_sequences_and_unknown_generators_are_refused_and_printed_escaped() {
    let dir = tempfile::tempdir().unwrap();
    let mut scene = fixture();
    let objects = scene["objects"].as_object_mut().unwrap();
    let mut sofa = objects.remove("sofa_0").unwrap();
    sofa["category"] = serde_json::json!("sofa\u{1b}[2J");
    objects.insert("evil\u{1b}]0;owned\u{7}".into(), sofa);
    let path = write_scene(dir.path(), &scene);
    let out = scenethesis(&["validate", path.to_str().unwrap()], None);
    assert_clean_failure(&out, &["\\u{1b}", "field `id`", "field `category`"]);
    assert!(!stderr(&out).contains('\u{7}'));

    let mut scene = fixture();
    scene["objects"]["sofa_0"]["asset"]["generator"] = serde_json::json!("warp_drive");
    let path = write_scene(dir.path(), &scene);
    let out = scenethesis(&["validate", path.to_str().unwrap()], None);
    assert_clean_failure(&out, &["warp_drive", "not a built-in generator"]);
}

#[test]
fn errors_are_printed_once() {
    let dir = tempfile::tempdir().unwrap();
    let out = scenethesis(
        &[
            "generate",
            "",
            "--out",
            dir.path().join("o").to_str().unwrap(),
        ],
        None,
    );
    assert_clean_failure(&out, &["prompt is empty"]);
    let err = stderr(&out);
    assert_eq!(err.matches("prompt is empty").count(), 1, "{err}");
    assert!(
        !err.contains("Error {") && !err.contains("Os {"),
        "no Debug dumps: {err}"
    );
}

#[test]
fn an_unknown_open_state_is_refused_naming_the_flag_and_the_choices() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("o");
    let out = scenethesis(
        &[
            "generate",
            "a kitchen",
            "--open-state",
            "ajar",
            "--out",
            out_dir.to_str().unwrap(),
        ],
        None,
    );
    let err = stderr(&out);
    assert!(!out.status.success() && !err.contains("panicked"), "{err}");
    for needle in ["--open-state", "closed, random or open", "ajar"] {
        assert!(err.contains(needle), "missing `{needle}` in: {err}");
    }
    assert!(!out_dir.exists(), "nothing is written");
}

#[test]
fn a_hostile_asset_pack_cannot_pull_files_in_and_bad_assets_only_warn() {
    let outer = tempfile::tempdir().unwrap();
    let pack = outer.path().join("pack");
    std::fs::create_dir(&pack).unwrap();
    // A file outside the pack with a recognisable marker in its bytes.
    let marker = b"TOP-SECRET-MARKER-0123456789";
    let mut secret = glb(serde_json::json!([{"name": "secret", "mesh": 0}]));
    secret.extend_from_slice(marker);
    std::fs::write(outer.path().join("secret.glb"), &secret).unwrap();
    // A good sofa (a closed box, 2 x 0.8 x 0.9 m) as OBJ.
    let mut obj = String::new();
    for (x, y, z) in [
        (-1.0, 0.0, -0.45),
        (1.0, 0.0, -0.45),
        (1.0, 0.8, -0.45),
        (-1.0, 0.8, -0.45),
        (-1.0, 0.0, 0.45),
        (1.0, 0.0, 0.45),
        (1.0, 0.8, 0.45),
        (-1.0, 0.8, 0.45),
    ] {
        obj.push_str(&format!("v {x} {y} {z}\n"));
    }
    obj.push_str("f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n");
    std::fs::write(pack.join("sofa.obj"), obj).unwrap();
    std::fs::write(
        pack.join("flat.obj"),
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
    )
    .unwrap();
    let abs = outer.path().join("secret.glb");
    std::fs::write(
        pack.join("assets.json"),
        serde_json::json!([
            {"file": "../secret.glb", "category": "sofa"},
            {"file": abs.to_str().unwrap(), "category": "sofa"},
            {"file": "flat.obj", "category": "sofa"},
            {"file": "sofa.obj", "category": "sofa", "scale_range": [2.0, 1.0]},
            {"file": "sofa.obj", "id": "my_sofa", "category": "sofa"}
        ])
        .to_string(),
    )
    .unwrap();
    let out_dir = outer.path().join("out");
    let out = generate_with("a living room with a sofa", &pack, &out_dir);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    for needle in [
        "entry #0",
        "outside the asset folder",
        "entry #1",
        "absolute",
        "zero surface area",
        "scale_range",
    ] {
        assert!(err.contains(needle), "missing `{needle}` in: {err}");
    }
    for name in ["../secret.glb", "zero surface area", "scale_range"] {
        assert_eq!(err.matches(name).count(), 1, "warning printed once: {err}");
    }
    let glb_bytes = std::fs::read(out_dir.join("scene.glb")).unwrap();
    assert!(
        !glb_bytes.windows(marker.len()).any(|w| w == marker),
        "bytes from outside the pack ended up in scene.glb"
    );
    let scene = std::fs::read_to_string(out_dir.join("scene.json")).unwrap();
    assert!(scene.contains("my_sofa"), "the good asset is used");
    let stored = pack.join("sofa.obj").canonicalize().unwrap();
    assert!(
        scene.contains(&stored.display().to_string().replace('\\', "\\\\")),
        "canonical absolute asset path stored"
    );
    // Export works from any working directory.
    let elsewhere = tempfile::tempdir().unwrap();
    let out = scenethesis(
        &["export", out_dir.to_str().unwrap(), "--format", "usd"],
        Some(elsewhere.path()),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    // `render DIR` draws the imported assets too (it used to skip them and exit 0).
    let out = scenethesis(
        &[
            "render",
            out_dir.to_str().unwrap(),
            "--views",
            "1",
            "--size",
            "64x48",
            "--supersample",
            "1",
        ],
        Some(elsewhere.path()),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let objects = scene.matches("\"local_bounds\"").count();
    assert!(
        stdout.contains(&format!("rendering {objects} of {objects} objects")),
        "{stdout}"
    );
    // Eval without scene.glb regenerates the imported asset instead of failing.
    std::fs::remove_file(out_dir.join("scene.glb")).unwrap();
    let out = scenethesis(&["eval", out_dir.to_str().unwrap()], Some(elsewhere.path()));
    assert!(out.status.success(), "{}", stderr(&out));
}

#[test]
fn node_names_with_escape_sequences_are_printed_escaped_by_eval() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("evil.glb");
    std::fs::write(
        &path,
        glb(serde_json::json!([{"name": "chair\u{1b}[2J\u{1b}]0;owned\u{7}", "mesh": 0}])),
    )
    .unwrap();
    let out = scenethesis(&["eval", path.to_str().unwrap()], None);
    let all = [out.stdout.clone(), out.stderr.clone()].concat();
    assert!(
        !all.contains(&0x1b) && !all.contains(&0x07),
        "{}",
        String::from_utf8_lossy(&all)
    );
    assert!(!stderr(&out).contains("panicked"));
}

/// An asset folder holding a 1 × 2 × 0.6 m wardrobe as OBJ (a `body` group and a 2 cm `door`
/// group in front of it) and a manifest giving the door the hinge `joint`.
fn wardrobe_pack(dir: &Path, joint: serde_json::Value) -> PathBuf {
    let pack = dir.join("pack");
    std::fs::create_dir(&pack).unwrap();
    let mut obj = String::new();
    let boxes = [
        ("body", [-0.5, 0.0, -0.3], [0.5, 2.0, 0.28]),
        ("door", [-0.5, 0.0, 0.28], [0.5, 2.0, 0.3]),
    ];
    for (k, (name, lo, hi)) in boxes.into_iter().enumerate() {
        let part = scenethesis_scene_graph::MeshPart::cuboid(name, 0, lo, hi);
        obj.push_str(&format!("g {name}\n"));
        for [x, y, z] in &part.positions {
            obj.push_str(&format!("v {x} {y} {z}\n"));
        }
        for t in &part.triangles {
            let [a, b, c] = t.map(|i| i as usize + 1 + 8 * k);
            obj.push_str(&format!("f {a} {b} {c}\n"));
        }
    }
    std::fs::write(pack.join("wardrobe.obj"), obj).unwrap();
    let manifest = serde_json::json!([{"file": "wardrobe.obj", "id": "my_wardrobe",
                                       "category": "wardrobe", "joints": [joint]}]);
    std::fs::write(pack.join("assets.json"), manifest.to_string()).unwrap();
    pack
}

/// The wardrobe door's hinge: its left edge seen from the front, turning out about −Y.
fn wardrobe_door() -> serde_json::Value {
    serde_json::json!({"part": "door", "name": "door", "kind": "revolute", "axis": [0, -1, 0],
                       "anchor": [-0.5, 0, 0.3], "limits": [0, 1.7], "opens_to": "left"})
}

/// `generate PROMPT --no-preview` with the asset folder `pack`, into `out`.
fn generate_with(prompt: &str, pack: &Path, out: &Path) -> Output {
    scenethesis(
        &[
            "generate",
            prompt,
            "--no-preview",
            "--assets",
            pack.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        None,
    )
}

#[test]
fn a_malformed_joint_in_assets_json_is_one_error_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let mut joint = wardrobe_door();
    joint["axis"] = serde_json::json!([0, 0, 0]);
    let pack = wardrobe_pack(dir.path(), joint);
    // --out inside a folder that does not exist yet: not even that folder is made.
    let out_dir = dir.path().join("scenes").join("out");
    let out = generate_with("a bedroom with a wardrobe", &pack, &out_dir);
    let field = "entry #0 (file `wardrobe.obj`): joints[0].axis is [0, 0, 0]; expected a finite, \
                 non-zero direction";
    assert_clean_failure(&out, &["assets.json", field]);
    let err = stderr(&out);
    assert_eq!(err.matches("joints[0]").count(), 1, "printed once: {err}");
    assert!(!out_dir.parent().unwrap().exists(), "nothing is written");
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(left.len(), 1, "only the pack is left: {left:?}");
}

#[test]
fn a_declared_joint_reaches_the_scene_object() {
    let dir = tempfile::tempdir().unwrap();
    let pack = wardrobe_pack(dir.path(), wardrobe_door());
    let out_dir = dir.path().join("out");
    let out = generate_with("a bedroom with a wardrobe", &pack, &out_dir);
    assert!(out.status.success(), "{}", stderr(&out));
    let scene: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out_dir.join("scene.json")).unwrap()).unwrap();
    let wardrobe = scene["objects"]
        .as_object()
        .unwrap()
        .values()
        .find(|o| o["asset"]["id"] == "my_wardrobe")
        .expect("the imported wardrobe is placed");
    let joint = &wardrobe["joints"][0];
    assert_eq!(joint["name"], "door", "{wardrobe}");
    assert_eq!(joint["kind"], "revolute", "{wardrobe}");
    assert_eq!(joint["state"], 0.0, "{wardrobe}");
}
