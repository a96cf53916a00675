//! Depth estimation and box-prompted segmentation through ONNX Runtime, implementing the
//! [`scenethesis_models`] provider traits with the models' real pre- and post-processing.
//!
//! - `OnnxDepth` (a [`DepthEstimator`](scenethesis_models::DepthEstimator)) runs a
//!   Depth-Anything-V2-style model; the expected signature and processing are in [`depth`].
//! - `OnnxSegmenter` (a [`Segmenter`](scenethesis_models::Segmenter)) runs a SAM / MobileSAM
//!   encoder + prompt decoder pair; see [`segment`].
//! - `OnnxMatcher` (a [`Matcher`](scenethesis_correspondence::Matcher) of the correspond
//!   stage) runs a LoFTR-style dense matcher between an asset rendered at its current pose and
//!   its object in the guidance image; see [`matcher`].
//! - `Runtime` loads the ONNX Runtime shared library at run time from `ORT_DYLIB_PATH` or an
//!   explicit path. Nothing is downloaded at build or run time: the library and the model files
//!   are the user's (`pip install onnxruntime` ships the library in
//!   `onnxruntime/capi/libonnxruntime.so.<version>`).
//!
//! The providers and `Runtime` need the `runtime` feature (which brings in `ort` with dynamic
//! loading only); without it the crate holds the configuration types and the pure pre/post-
//! processing, so depending crates build without ONNX Runtime.
//!
//! ```no_run
//! # #[cfg(feature = "runtime")]
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! use scenethesis_models::{DepthEstimator, ImageData};
//! use scenethesis_onnx::{DepthConfig, OnnxDepth, Runtime};
//!
//! let runtime = Runtime::from_env()?; // ORT_DYLIB_PATH
//! let depth = OnnxDepth::new(&runtime, "depth_anything_v2_metric_indoor.onnx", DepthConfig::default())?;
//! let image = ImageData::from_bytes(std::fs::read("room.png")?, "room.png")?;
//! let map = depth.estimate(&image, None)?;
//! println!("{} x {} depths, centre {:?} m", map.width, map.height, map.at(map.width / 2, map.height / 2));
//! # Ok(())
//! # }
//! # #[cfg(not(feature = "runtime"))]
//! # fn main() {}
//! ```
#![warn(missing_docs)]
// Without `runtime` the pre/post-processing helpers have no caller outside the unit tests.
#![cfg_attr(not(feature = "runtime"), allow(dead_code))]

pub mod depth;
mod error;
pub mod matcher;
mod raster;
#[cfg(feature = "runtime")]
mod runtime;
pub mod segment;
#[cfg(feature = "runtime")]
mod signature;

#[cfg(feature = "runtime")]
pub use depth::OnnxDepth;
pub use depth::{DepthConfig, DepthOutput};
pub use error::{OnnxError, DYLIB_ENV, DYLIB_HINT};
#[cfg(feature = "runtime")]
pub use matcher::OnnxMatcher;
pub use matcher::{Crop, MatcherConfig, RawMatches};
pub use raster::Normalisation;
#[cfg(feature = "runtime")]
pub use runtime::Runtime;
#[cfg(feature = "runtime")]
pub use segment::OnnxSegmenter;
pub use segment::{DecoderNames, LongestSide, MaskFrame, SegmenterConfig};

/// The endpoint named in [`ProviderError`](scenethesis_models::ProviderError)s of these
/// providers (the model is the model file).
pub const ENDPOINT: &str = "onnxruntime";

/// The file name of a model without its extension, for provider names.
#[cfg(feature = "runtime")]
fn model_stem(path: &std::path::Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string())
}
