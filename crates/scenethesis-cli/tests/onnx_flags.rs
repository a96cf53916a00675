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
    assert!(
        err.contains("--depth-model feeds the vision guide"),
        "{err}"
    );
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
