//! The ONNX model flags of `generate` (`--depth-model`, `--segment-encoder`/`--segment-decoder`,
//! `--onnx-runtime`): rejected without the vision guide, rejected with a rebuild hint by a binary
//! built without the `onnx` feature, and, with the feature, loaded through ONNX Runtime before
//! any other work (`cargo test -p scenethesis-cli --features onnx --test onnx_flags`, with
//! ORT_DYLIB_PATH set).

use std::path::PathBuf;
use std::process::Output;

mod common;

const PROMPT: &str = "a bedroom with a bed, a nightstand and a wardrobe";

fn scenethesis(args: &[&str]) -> Output {
    common::scenethesis_with_key(None, args)
}

fn failure(out: &Output) -> String {
    assert!(!out.status.success(), "expected a failure");
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn fixture(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/onnx")
        .join(name)
        .display()
        .to_string()
}

#[test]
fn model_flags_without_the_vision_guide_are_rejected() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("out");
    let out = dir.path().join("out").display().to_string();
    let model = fixture("depth_dynamic.onnx");
    let err = failure(&scenethesis(&[
        "generate",
        PROMPT,
        "--out",
        &out,
        "--no-preview",
        "--depth-model",
        &model,
    ]));
    assert!(err.contains("--depth-model feeds the vision path"), "{err}");
    assert!(!out_dir.exists(), "nothing is written");
}

#[cfg(not(feature = "onnx"))]
#[test]
fn a_build_without_the_feature_says_how_to_get_it() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out").display().to_string();
    let err = failure(&scenethesis(&[
        "generate",
        PROMPT,
        "--out",
        &out,
        "--guide-image",
        "room.png",
        "--segment-encoder",
        "encoder.onnx",
        "--segment-decoder",
        "decoder.onnx",
    ]));
    assert!(
        err.contains("--segment-encoder: this scenethesis was built without the `onnx` feature")
            && err.contains("--features onnx"),
        "{err}"
    );
    let err = failure(&scenethesis(&[
        "generate",
        PROMPT,
        "--out",
        &out,
        "--guide-image",
        "room.png",
        "--match-model",
        "loftr.onnx",
    ]));
    assert!(
        err.contains("--match-model: this scenethesis was built without the `onnx` feature"),
        "{err}"
    );
}

#[test]
fn a_match_model_with_the_correspond_stage_off_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("out");
    let out = out_dir.display().to_string();
    let model = fixture("matcher_centroid.onnx");
    let err = failure(&scenethesis(&[
        "generate",
        PROMPT,
        "--out",
        &out,
        "--guide-image",
        "room.png",
        "--matcher",
        "none",
        "--match-model",
        &model,
    ]));
    assert!(
        err.contains("--match-model") && err.contains("--matcher none"),
        "{err}"
    );
    assert!(!out_dir.exists(), "nothing is written");
}

/// The dense matcher runs in the correspond stage of a whole `generate` from guidance files
/// (rendered from an offline scene), through ONNX Runtime, and the report names it.
#[cfg(feature = "onnx")]
#[test]
fn a_dense_match_model_aligns_the_objects_of_a_guided_run() {
    assert!(
        std::env::var_os("ORT_DYLIB_PATH").is_some(),
        "set ORT_DYLIB_PATH to an ONNX Runtime library (pip install onnxruntime)"
    );
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("scene");
    let s = scene.display().to_string();
    let run = |args: &[&str]| {
        let out = scenethesis(args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    run(&[
        "generate",
        PROMPT,
        "--out",
        &s,
        "--no-preview",
        "--max-replans",
        "0",
    ]);
    run(&["render", &s, "--guidance", "--size", "384x256"]);
    let g = |name: &str| scene.join("guidance").join(name).display().to_string();
    let model = fixture("matcher_centroid.onnx");
    let guided = |name: &str, extra: &[&str]| {
        let out_dir = dir.path().join(name);
        let out = out_dir.display().to_string();
        let mut args = vec![
            "generate",
            PROMPT,
            "--out",
            &out,
            "--no-preview",
            "--max-replans",
            "0",
        ];
        let files = [
            ("--guide-image", g("rgb.png")),
            ("--guide-masks", g("ids.png")),
            ("--guide-labels", g("labels.json")),
            ("--guide-depth", g("depth.npy")),
            ("--camera", g("camera.json")),
        ];
        for (flag, file) in &files {
            args.extend([*flag, file.as_str()]);
        }
        args.extend(extra);
        run(&args);
        let report: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out_dir.join("report.json")).unwrap()).unwrap();
        (std::fs::read(out_dir.join("scene.json")).unwrap(), report)
    };
    let (dense_scene, report) = guided("dense", &["--match-model", &model]);
    assert_eq!(report["guide"], "vision");
    assert_eq!(report["matcher"], "onnx/matcher_centroid", "{report}");
    assert!(
        report["timings"]
            .as_array()
            .unwrap()
            .iter()
            .any(|t| t["stage"] == "correspond"),
        "no correspond stage ran: {}",
        report["timings"]
    );
    // The alignment followed the model's matches, not the shape matcher's.
    let (shape_scene, report) = guided("shape", &[]);
    assert_eq!(report["matcher"], "shape");
    assert_ne!(dense_scene, shape_scene);
}

#[cfg(feature = "onnx")]
#[test]
fn models_load_through_onnx_runtime_before_the_guidance_is_read() {
    assert!(
        std::env::var_os("ORT_DYLIB_PATH").is_some(),
        "set ORT_DYLIB_PATH to an ONNX Runtime library (pip install onnxruntime; the wheel's \
         onnxruntime/capi/libonnxruntime.so.<version>)"
    );
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out").display().to_string();
    let missing_image = dir.path().join("room.png").display().to_string();
    let (depth, encoder, decoder) = (
        fixture("depth_dynamic.onnx"),
        fixture("sam_encoder.onnx"),
        fixture("sam_decoder.onnx"),
    );
    let base = [
        "generate",
        PROMPT,
        "--out",
        &out,
        "--guide-image",
        &missing_image,
    ];
    // Good models load; the run then stops at the missing guidance image.
    let mut args = base.to_vec();
    args.extend([
        "--depth-model",
        &depth,
        "--depth-kind",
        "relative",
        "--segment-encoder",
        &encoder,
        "--segment-decoder",
        &decoder,
    ]);
    let err = failure(&scenethesis(&args));
    assert!(err.contains("room.png") && !err.contains("ONNX"), "{err}");

    // A depth model given as the decoder is named with what it lacks.
    let mut args = base.to_vec();
    args.extend(["--segment-encoder", &encoder, "--segment-decoder", &depth]);
    let err = failure(&scenethesis(&args));
    assert!(
        err.contains("depth_dynamic.onnx") && err.contains("no input `image_embeddings`"),
        "{err}"
    );

    // A library that is not there is named.
    let mut args = base.to_vec();
    args.extend([
        "--depth-model",
        &depth,
        "--onnx-runtime",
        "/nonexistent/libonnxruntime.so.1",
    ]);
    let err = failure(&scenethesis(&args));
    assert!(
        err.contains("/nonexistent/libonnxruntime.so.1") && err.contains("pip install onnxruntime"),
        "{err}"
    );
}
