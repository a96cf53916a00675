//! Loading ONNX Runtime from a file that is not the library fails naming the file, and leaves the
//! process free to load the real library afterwards. A test binary of its own, because a
//! process loads ONNX Runtime once.
#![cfg(feature = "runtime")]

use std::path::PathBuf;

use scenethesis_onnx::{OnnxError, Runtime};

#[test]
fn a_file_that_is_not_the_library_is_named_and_the_real_one_still_loads() {
    let not_a_library =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/onnx/depth_static.onnx");
    let err = Runtime::load(&not_a_library).unwrap_err();
    let text = err.to_string();
    assert!(matches!(err, OnnxError::Library { .. }), "{text}");
    assert!(
        text.contains("depth_static.onnx") && text.contains("pip install onnxruntime"),
        "{text}"
    );

    let runtime = Runtime::from_env()
        .unwrap_or_else(|e| panic!("this test loads ONNX Runtime after the failure: {e}"));
    assert!(runtime.library().is_file());
}
