//! Errors of setting up the ONNX Runtime providers (loading the library, opening models,
//! checking their signatures). Failures while running a model are
//! [`ProviderError`](scenethesis_models::ProviderError)s naming the model file.

use std::path::PathBuf;

/// The environment variable that names the ONNX Runtime shared library.
pub const DYLIB_ENV: &str = "ORT_DYLIB_PATH";

/// How to obtain the ONNX Runtime library, appended to errors about it.
pub const DYLIB_HINT: &str = "install the library with `pip install onnxruntime` and set \
ORT_DYLIB_PATH to the wheel's onnxruntime/capi/libonnxruntime.so.<version> (on Linux; \
onnxruntime.dll on Windows, libonnxruntime.<version>.dylib on macOS)";

/// Why an ONNX Runtime provider could not be set up.
#[derive(Debug, thiserror::Error)]
pub enum OnnxError {
    /// No library path was given and `ORT_DYLIB_PATH` is unset or empty.
    #[error(
        "ORT_DYLIB_PATH is not set, so the ONNX Runtime library cannot be found; {DYLIB_HINT}"
    )]
    LibraryNotSet,
    /// The ONNX Runtime library could not be loaded.
    #[error("cannot load the ONNX Runtime library {}: {message}; {DYLIB_HINT}", path.display())]
    Library {
        /// The library path.
        path: PathBuf,
        /// What failed (missing file, not a shared library, too old a version).
        message: String,
    },
    /// ONNX Runtime could not open a model file.
    #[error("cannot open the ONNX model {}: {message}", path.display())]
    Model {
        /// The model file.
        path: PathBuf,
        /// ONNX Runtime's message.
        message: String,
    },
    /// A model's inputs or outputs are not the ones the provider feeds and reads.
    #[error("the ONNX model {} does not have the expected signature: {message}", path.display())]
    Signature {
        /// The model file.
        path: PathBuf,
        /// Which tensor is missing or has the wrong type or shape, and what was expected.
        message: String,
    },
    /// A configuration value is out of range.
    #[error("invalid {what}: {message}")]
    Config {
        /// The setting.
        what: String,
        /// What is wrong and what is allowed.
        message: String,
    },
}
