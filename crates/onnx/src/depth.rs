//! Monocular depth through a Depth-Anything-V2-style ONNX model.
//!
//! Expected signature (names configurable in [`DepthConfig`]):
//! - one input, float32 `[1, 3, H, W]`: RGB scaled to 0..1 and normalised with
//!   [`DepthConfig::normalisation`] (ImageNet by default). When the model's `H` and `W` are
//!   static the image is resized to exactly that size; when they are dynamic it is resized so
//!   the shorter side is [`DepthConfig::input_size`] (518 for Depth Anything V2), keeping the
//!   aspect ratio, with both sides rounded to multiples of [`DepthConfig::multiple_of`] (14,
//!   the ViT patch size).
//! - one output, float32 `[1, h, w]`, `[1, 1, h, w]` or `[h, w]`: depth (metric models) or
//!   relative inverse depth (disparity) at any resolution covering the whole input; it is
//!   resized back to the image size bilinearly and converted by [`DepthOutput`].

use scenethesis_imagery::{DepthMap, Intrinsics};
use scenethesis_models::DepthEstimate;

use crate::raster::Normalisation;

/// What the depth model's output means and how it becomes metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DepthOutput {
    /// Metric depth: metres = value x `scale` (1 for Depth Anything V2 metric models, which
    /// already output metres).
    Metric {
        /// Multiplier from the model's unit to metres.
        scale: f32,
    },
    /// Relative inverse depth (disparity, larger is nearer), as Depth Anything's relative
    /// models give: metres = `scale` / value. The result is right only up to scale (and the
    /// model's unknown shift); callers align it to known geometry.
    RelativeInverse {
        /// The numerator.
        scale: f32,
    },
}

/// How images are fed to a depth model and how its output is read.
#[derive(Debug, Clone, PartialEq)]
pub struct DepthConfig {
    /// The input tensor's name; `None` takes the model's only input.
    pub input: Option<String>,
    /// The output tensor's name; `None` takes the model's first output.
    pub output: Option<String>,
    /// Shorter side of the model input when the model's input size is dynamic.
    pub input_size: u32,
    /// Both input sides are rounded to a multiple of this when the size is dynamic.
    pub multiple_of: u32,
    /// Pixel normalisation.
    pub normalisation: Normalisation,
    /// The meaning of the output.
    pub output_kind: DepthOutput,
    /// Horizontal field of view (degrees) assumed for the returned intrinsics when the caller
    /// gives none; the model does not estimate them.
    pub assumed_hfov_deg: f32,
}

impl Default for DepthConfig {
    fn default() -> Self {
        Self {
            input: None,
            output: None,
            input_size: 518,
            multiple_of: 14,
            normalisation: Normalisation::IMAGENET,
            output_kind: DepthOutput::Metric { scale: 1.0 },
            assumed_hfov_deg: 60.0,
        }
    }
}

impl DepthConfig {
    /// The model input size (width, height) for an image of `width` x `height` when the model
    /// accepts any size: shorter side `input_size`, aspect kept, sides rounded to the nearest
    /// multiple of `multiple_of` (at least one multiple).
    pub fn dynamic_input_size(&self, width: u32, height: u32) -> (u32, u32) {
        let scale = self.input_size as f64 / f64::from(width.min(height).max(1));
        let m = f64::from(self.multiple_of.max(1));
        let round = |side: u32| {
            let k = (f64::from(side) * scale / m).round().max(1.0);
            (k * m) as u32
        };
        (round(width), round(height))
    }

    /// Intrinsics for an image of `width` x `height` from [`Self::assumed_hfov_deg`], principal
    /// point at the centre.
    pub fn assumed_intrinsics(&self, width: u32, height: u32) -> Intrinsics {
        let half = (f64::from(self.assumed_hfov_deg).to_radians() / 2.0).tan();
        let f = f64::from(width) / 2.0 / half;
        Intrinsics {
            width,
            height,
            fx: f,
            fy: f,
            cx: f64::from(width) / 2.0,
            cy: f64::from(height) / 2.0,
        }
    }

    pub(crate) fn validate(&self) -> Result<(), crate::OnnxError> {
        let bad = |what: &str, message: String| {
            Err(crate::OnnxError::Config {
                what: format!("depth setting `{what}`"),
                message,
            })
        };
        if self.input_size == 0 || self.multiple_of == 0 {
            return bad(
                "input_size/multiple_of",
                format!(
                    "both must be positive, got {} and {}",
                    self.input_size, self.multiple_of
                ),
            );
        }
        if !(self.assumed_hfov_deg > 1.0 && self.assumed_hfov_deg < 179.0) {
            return bad(
                "assumed_hfov_deg",
                format!(
                    "expected degrees in (1, 179), got {}",
                    self.assumed_hfov_deg
                ),
            );
        }
        let scale = match self.output_kind {
            DepthOutput::Metric { scale } | DepthOutput::RelativeInverse { scale } => scale,
        };
        if !(scale.is_finite() && scale > 0.0) {
            return bad(
                "output_kind",
                format!("the scale must be positive and finite, got {scale}"),
            );
        }
        Ok(())
    }

    /// Metres from one output value (0 where the value gives no valid depth).
    pub fn metres(&self, value: f32) -> f32 {
        let metres = match self.output_kind {
            DepthOutput::Metric { scale } => value * scale,
            DepthOutput::RelativeInverse { scale } => {
                if value > 0.0 {
                    scale / value
                } else {
                    0.0
                }
            }
        };
        if metres.is_finite() && metres > 0.0 {
            metres
        } else {
            0.0
        }
    }
}

/// The spatial size `(w, h)` of a depth output of `shape` (`[1, h, w]`, `[1, 1, h, w]` or
/// `[h, w]`), or a description of what was expected.
pub(crate) fn output_plane(shape: &[i64]) -> Result<(usize, usize), String> {
    let spatial = match shape {
        [h, w] | [1, h, w] | [1, 1, h, w] => (*w, *h),
        _ => {
            return Err(format!(
                "expected shape [1, H, W], [1, 1, H, W] or [H, W], got {shape:?}"
            ))
        }
    };
    if spatial.0 <= 0 || spatial.1 <= 0 {
        return Err(format!("expected a non-empty depth plane, got {shape:?}"));
    }
    Ok((spatial.0 as usize, spatial.1 as usize))
}

/// The depth map at the image size from an output plane covering the whole image.
pub(crate) fn depth_map(
    config: &DepthConfig,
    plane: &[f32],
    plane_size: (usize, usize),
    image_size: (u32, u32),
    intrinsics: Intrinsics,
) -> DepthEstimate {
    let (w, h) = (image_size.0 as usize, image_size.1 as usize);
    let resized = crate::raster::resize_plane(plane, plane_size.0, plane_size.1, w, h);
    let mut metres = resized.into_iter().map(|v| config.metres(v));
    DepthEstimate {
        depth: DepthMap::from_fn(image_size.0, image_size.1, |_, _| {
            metres.next().expect("one value per pixel")
        }),
        intrinsics,
    }
}

#[cfg(feature = "runtime")]
pub use provider::OnnxDepth;

#[cfg(feature = "runtime")]
mod provider {
    use std::path::Path;

    use scenethesis_imagery::Intrinsics;
    use scenethesis_models::{
        DepthEstimate, DepthEstimator, ImageData, ProviderError, ProviderErrorKind,
    };

    use super::{depth_map, output_plane, DepthConfig};
    use crate::raster::{decode_rgb, resize_rgb, to_nchw};
    use crate::runtime::{Model, Runtime, TensorF32};
    use crate::signature::Signature;
    use crate::{OnnxError, ENDPOINT};

    /// A [`DepthEstimator`] running a Depth-Anything-style ONNX model (see the
    /// [module documentation](crate::depth) for the signature it expects).
    pub struct OnnxDepth {
        model: Model,
        config: DepthConfig,
        input: String,
        output: String,
        /// The model's static input size (width, height), when it has one.
        fixed_size: Option<(u32, u32)>,
    }

    impl std::fmt::Debug for OnnxDepth {
        fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.debug_struct("OnnxDepth")
                .field("model", &self.model.path)
                .field("input", &self.input)
                .field("output", &self.output)
                .field("fixed_size", &self.fixed_size)
                .finish()
        }
    }

    impl OnnxDepth {
        /// Opens the depth model at `path` and checks its signature against `config`.
        pub fn new(
            runtime: &Runtime,
            path: impl AsRef<Path>,
            config: DepthConfig,
        ) -> Result<Self, OnnxError> {
            config.validate()?;
            let path = path.as_ref();
            let model = Model::open(runtime, path)?;
            let signature = Signature::new(&model, "model");
            let (input, h, w) = signature.rgb_input(config.input.as_deref(), "[1, 3, H, W]")?;
            let fixed_size = (h > 0 && w > 0).then_some((w as u32, h as u32));
            let output = signature.output_or_first(config.output.as_deref())?;
            let output_ok = output.float32
                && matches!(output.shape.as_deref(), Some(s) if (2..=4).contains(&s.len()));
            if !output_ok {
                return Err(signature.error(format!(
                    "output {} should be float32 [1, H, W], [1, 1, H, W] or [H, W]",
                    output.describe()
                )));
            }
            Ok(Self {
                input: input.name.clone(),
                output: output.name.clone(),
                fixed_size,
                config,
                model,
            })
        }

        /// The model file.
        pub fn model_path(&self) -> &Path {
            &self.model.path
        }

        /// The size (width, height) an image of `width` x `height` is resized to before it
        /// enters the model.
        pub fn input_size_for(&self, width: u32, height: u32) -> (u32, u32) {
            self.fixed_size
                .unwrap_or_else(|| self.config.dynamic_input_size(width, height))
        }

        fn error(&self, kind: ProviderErrorKind) -> ProviderError {
            ProviderError::new(ENDPOINT, self.model.path.display().to_string(), kind)
        }
    }

    impl DepthEstimator for OnnxDepth {
        fn name(&self) -> String {
            format!("onnx/{}", crate::model_stem(&self.model.path))
        }

        fn estimate(
            &self,
            image: &ImageData,
            intrinsics: Option<Intrinsics>,
        ) -> Result<DepthEstimate, ProviderError> {
            let rgb = decode_rgb(image)
                .map_err(|message| self.error(ProviderErrorKind::InvalidRequest { message }))?;
            let (width, height) = rgb.dimensions();
            let (iw, ih) = self.input_size_for(width, height);
            let resized = resize_rgb(&rgb, iw, ih);
            let tensor = TensorF32 {
                shape: vec![1, 3, i64::from(ih), i64::from(iw)],
                data: to_nchw(&resized, &self.config.normalisation, iw, ih),
            };
            let mut outputs = self
                .model
                .run(vec![(self.input.clone(), tensor)], &[&self.output])
                .map_err(|message| {
                    self.error(ProviderErrorKind::Malformed {
                        message,
                        source: None,
                    })
                })?;
            let out = outputs.remove(0);
            let plane = output_plane(&out.shape).map_err(|e| {
                self.error(ProviderErrorKind::Malformed {
                    message: format!("output `{}`: {e}", self.output),
                    source: None,
                })
            })?;
            let intrinsics =
                intrinsics.unwrap_or_else(|| self.config.assumed_intrinsics(width, height));
            Ok(depth_map(
                &self.config,
                &out.data,
                plane,
                (width, height),
                intrinsics,
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dynamic_sizes_keep_aspect_in_multiples_of_14() {
        let c = DepthConfig::default();
        assert_eq!(c.dynamic_input_size(640, 480), (686, 518));
        assert_eq!(c.dynamic_input_size(480, 640), (518, 686));
        assert_eq!(c.dynamic_input_size(518, 518), (518, 518));
        let small = DepthConfig {
            input_size: 28,
            ..c
        };
        assert_eq!(small.dynamic_input_size(40, 30), (42, 28));
        assert_eq!(small.dynamic_input_size(1, 1000), (28, 28000));
    }

    #[test]
    fn outputs_convert_to_metres() {
        let metric = DepthConfig {
            output_kind: DepthOutput::Metric { scale: 2.0 },
            ..DepthConfig::default()
        };
        assert_eq!(metric.metres(1.5), 3.0);
        assert_eq!(metric.metres(-1.0), 0.0);
        assert_eq!(metric.metres(f32::NAN), 0.0);
        let relative = DepthConfig {
            output_kind: DepthOutput::RelativeInverse { scale: 4.0 },
            ..DepthConfig::default()
        };
        assert_eq!(relative.metres(2.0), 2.0);
        assert_eq!(relative.metres(0.0), 0.0);
    }

    #[test]
    fn output_shapes_are_checked() {
        assert_eq!(output_plane(&[1, 3, 5]), Ok((5, 3)));
        assert_eq!(output_plane(&[1, 1, 3, 5]), Ok((5, 3)));
        assert_eq!(output_plane(&[3, 5]), Ok((5, 3)));
        assert!(output_plane(&[2, 3, 5]).unwrap_err().contains("[2, 3, 5]"));
        assert!(output_plane(&[1, 0, 5]).is_err());
    }

    #[test]
    fn assumed_intrinsics_follow_the_field_of_view() {
        let k = DepthConfig {
            assumed_hfov_deg: 90.0,
            ..DepthConfig::default()
        }
        .assumed_intrinsics(200, 100);
        assert!((k.fx - 100.0).abs() < 1e-3 && k.fx == k.fy);
        assert_eq!((k.cx, k.cy), (100.0, 50.0));
    }

    #[test]
    fn depth_map_is_resized_to_the_image() {
        let c = DepthConfig::default();
        let k = c.assumed_intrinsics(4, 2);
        let map = depth_map(&c, &[1.0, 3.0], (2, 1), (4, 2), k);
        assert_eq!((map.depth.width(), map.depth.height()), (4, 2));
        assert_eq!(map.depth.values(), [1.0, 1.5, 2.5, 3.0, 1.0, 1.5, 2.5, 3.0]);
    }
}
