//! Optional model providers of the vision path run through ONNX Runtime (feature `onnx`): a
//! depth model and a box-prompted segmenter (encoder + decoder) for the vision guide, and a
//! dense matcher for the correspond stage, from model files the user supplies, with the ONNX
//! Runtime library from `--onnx-runtime` or `ORT_DYLIB_PATH`.

use std::path::PathBuf;

use anyhow::Result;
use scenethesis_pipeline::Pipeline;
use scenethesis_vision_guide::VisionGuide;

/// What a depth model's output means.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum DepthKind {
    /// Metric depth: metres = value × --depth-scale (Depth Anything V2 metric models).
    #[default]
    Metric,
    /// Relative inverse depth (disparity): metres = --depth-scale / value, right up to scale.
    Relative,
}

/// The ONNX model flags of `generate`.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct OnnxArgs {
    /// Depth model (ONNX, Depth-Anything-V2-style: image [1, 3, H, W] → depth) estimating the
    /// guidance image's depth when --guide-depth is not given. Needs a build with the `onnx`
    /// feature and the ONNX Runtime library (ORT_DYLIB_PATH or --onnx-runtime).
    #[arg(long, value_name = "ONNX")]
    pub depth_model: Option<PathBuf>,
    /// What --depth-model outputs: `metric` (default) or `relative` inverse depth.
    #[arg(long, value_enum, value_name = "KIND", requires = "depth_model")]
    pub depth_kind: Option<DepthKind>,
    /// Multiplier (metric) or numerator (relative) turning --depth-model's output into metres
    /// (default 1).
    #[arg(long, value_name = "SCALE", requires = "depth_model")]
    pub depth_scale: Option<f32>,
    /// Image encoder of a box-prompted segmenter (ONNX, SAM / MobileSAM export), refining the
    /// vision-language model's boxes into masks together with --segment-decoder.
    #[arg(long, value_name = "ONNX", requires = "segment_decoder")]
    pub segment_encoder: Option<PathBuf>,
    /// Prompt decoder of the segmenter (SAM's ONNX decoder export: image_embeddings,
    /// point_coords, point_labels, mask_input, has_mask_input, orig_im_size → masks,
    /// iou_predictions).
    #[arg(long, value_name = "ONNX", requires = "segment_encoder")]
    pub segment_decoder: Option<PathBuf>,
    /// Dense matcher (ONNX, LoFTR-style: image0, image1 [1, 1, H, W] grey → keypoints0,
    /// keypoints1 [N, 2], confidence [N]) pairing each asset rendered at its pose with its
    /// object in the guidance image; the correspond stage aligns to its matches instead of the
    /// shape matcher's (the yaw search still ranks poses by shape).
    #[arg(long, value_name = "ONNX")]
    pub match_model: Option<PathBuf>,
    /// The ONNX Runtime shared library (default: ORT_DYLIB_PATH; `pip install onnxruntime`
    /// ships it as onnxruntime/capi/libonnxruntime.so.<version>).
    #[arg(long, value_name = "LIBRARY")]
    pub onnx_runtime: Option<PathBuf>,
}

impl OnnxArgs {
    /// Whether any ONNX model is asked for.
    pub fn any(&self) -> bool {
        self.depth_model.is_some() || self.segment_encoder.is_some() || self.match_model.is_some()
    }

    /// The first flag given, for messages.
    fn first_flag(&self) -> &'static str {
        if self.depth_model.is_some() {
            "--depth-model"
        } else if self.segment_encoder.is_some() {
            "--segment-encoder"
        } else if self.match_model.is_some() {
            "--match-model"
        } else {
            "--onnx-runtime"
        }
    }

    /// Errors when ONNX flags are given to a run without the vision guide.
    pub fn reject_unused(&self) -> Result<()> {
        if self.any() || self.onnx_runtime.is_some() {
            anyhow::bail!(
                "{} feeds the vision path, which this run does not use; add --guide vision or --guide-image FILE",
                self.first_flag()
            );
        }
        Ok(())
    }

    /// Loads ONNX Runtime and the asked-for models (before any other work, so a wrong file stops
    /// the run at once).
    #[cfg(feature = "onnx")]
    pub fn load(&self) -> Result<OnnxProviders> {
        use anyhow::Context;
        use scenethesis_onnx::{
            DepthConfig, DepthOutput, MatcherConfig, OnnxDepth, OnnxMatcher, OnnxSegmenter,
            Runtime, SegmenterConfig,
        };

        let mut providers = OnnxProviders::default();
        if !self.any() {
            if let Some(library) = &self.onnx_runtime {
                anyhow::bail!(
                    "--onnx-runtime {}: given without --depth-model, --segment-encoder or --match-model, so no model would use it",
                    library.display()
                );
            }
            return Ok(providers);
        }
        let runtime = match &self.onnx_runtime {
            Some(library) => Runtime::load(library),
            None => Runtime::from_env(),
        }
        .context("loading ONNX Runtime for the ONNX models")?;
        if let Some(model) = &self.depth_model {
            let scale = self.depth_scale.unwrap_or(1.0);
            let output_kind = match self.depth_kind.unwrap_or_default() {
                DepthKind::Metric => DepthOutput::Metric { scale },
                DepthKind::Relative => DepthOutput::RelativeInverse { scale },
            };
            let config = DepthConfig {
                output_kind,
                ..DepthConfig::default()
            };
            providers.depth = Some(
                OnnxDepth::new(&runtime, model, config)
                    .with_context(|| format!("--depth-model {}", model.display()))?,
            );
        }
        if let (Some(encoder), Some(decoder)) = (&self.segment_encoder, &self.segment_decoder) {
            providers.segmenter = Some(
                OnnxSegmenter::new(&runtime, encoder, decoder, SegmenterConfig::default())
                    .with_context(|| {
                        format!(
                            "--segment-encoder {} --segment-decoder {}",
                            encoder.display(),
                            decoder.display()
                        )
                    })?,
            );
        }
        if let Some(model) = &self.match_model {
            providers.matcher = Some(
                OnnxMatcher::new(&runtime, model, MatcherConfig::default())
                    .with_context(|| format!("--match-model {}", model.display()))?,
            );
        }
        Ok(providers)
    }

    /// Without the `onnx` feature: no providers, or an error saying how to get the feature when
    /// ONNX models are asked for.
    #[cfg(not(feature = "onnx"))]
    pub fn load(&self) -> Result<OnnxProviders> {
        if self.any() || self.onnx_runtime.is_some() {
            anyhow::bail!(
                "{}: this scenethesis was built without the `onnx` feature; rebuild it with \
                 `cargo install --path crates/scenethesis-cli --features onnx` (README: \
                 \"depth and segmentation models through ONNX Runtime\")",
                self.first_flag()
            );
        }
        Ok(OnnxProviders::default())
    }
}

/// The ONNX models a run asked for, loaded.
#[derive(Default)]
pub struct OnnxProviders {
    #[cfg(feature = "onnx")]
    depth: Option<scenethesis_onnx::OnnxDepth>,
    #[cfg(feature = "onnx")]
    segmenter: Option<scenethesis_onnx::OnnxSegmenter>,
    #[cfg(feature = "onnx")]
    matcher: Option<scenethesis_onnx::OnnxMatcher>,
}

impl OnnxProviders {
    /// `pipeline` with `guide` using these models and, when a dense matcher was loaded, with it
    /// as the correspond stage's matcher; the flag says whether a matcher was installed.
    pub fn install(self, guide: VisionGuide, pipeline: Pipeline) -> (Pipeline, bool) {
        #[cfg(feature = "onnx")]
        {
            let mut guide = guide;
            if let Some(depth) = self.depth {
                guide = guide.with_depth_estimator(depth);
            }
            if let Some(segmenter) = self.segmenter {
                guide = guide.with_segmenter(segmenter);
            }
            let pipeline = pipeline.with_guide(guide);
            match self.matcher {
                Some(dense) => (
                    pipeline.with_matcher(dense, scenethesis_pipeline::GuidedSettings::default()),
                    true,
                ),
                None => (pipeline, false),
            }
        }
        #[cfg(not(feature = "onnx"))]
        (pipeline.with_guide(guide), false)
    }
}
