//! Box-prompted segmentation through a SAM / MobileSAM-style pair of ONNX models: an image
//! encoder run once per image and a prompt decoder run once per box.
//!
//! Expected signatures (every name configurable in [`SegmenterConfig`] and [`DecoderNames`]):
//! - **encoder**: one input, float32 `[1, 3, S, S]`: the image resized so its longest side is
//!   `S` (1024 for SAM and MobileSAM; read from the model when static, else
//!   [`SegmenterConfig::input_size`]), normalised with [`SegmenterConfig::normalisation`]
//!   (ImageNet) and zero-padded at the bottom and right to `S` x `S`. Its output (the first, or
//!   the named one; `[1, 256, 64, 64]` for SAM) is handed to the decoder unchanged.
//! - **decoder**, with the input names of SAM's ONNX export:
//!   `image_embeddings` (the encoder output), `point_coords` float32 `[1, 2, 2]` (the box's
//!   top-left and bottom-right corners in input-frame pixels), `point_labels` float32 `[1, 2]`
//!   = `[2, 3]` (box corners), and, when the model has them, `mask_input` float32
//!   `[1, 1, S/4, S/4]` of zeros, `has_mask_input` float32 `[1]` = `[0]`, `orig_im_size`
//!   float32 `[2]` = `[height, width]`. Outputs: `masks` float32 `[1, M, h, w]` mask logits and
//!   `iou_predictions` float32 `[1, M]` (may be absent when `M` = 1). When `h` x `w` is the image
//!   size (SAM's export upsamples inside the model) the logits are read as they are; otherwise
//!   they cover the padded `S` x `S` input frame (the low-resolution 256 x 256 masks of other
//!   exports) and are sampled bilinearly at each image pixel. Of the `M` masks the one with the
//!   highest predicted IoU is kept (its IoU is the mask's score); logits above
//!   [`SegmenterConfig::mask_threshold`] (0) are inside.

use scenethesis_models::BoxPrompt;

use crate::raster::{sample_bilinear, Normalisation};

/// The decoder's input and output names.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DecoderNames {
    /// Input: the encoder's output.
    pub image_embeddings: String,
    /// Input: prompt point coordinates `[1, N, 2]`.
    pub point_coords: String,
    /// Input: prompt point labels `[1, N]`.
    pub point_labels: String,
    /// Optional input: a previous mask `[1, 1, S/4, S/4]` (fed zeros).
    pub mask_input: String,
    /// Optional input: whether `mask_input` is used `[1]` (fed 0).
    pub has_mask_input: String,
    /// Optional input: the original image size `[2]` as (height, width).
    pub orig_im_size: String,
    /// Output: mask logits `[1, M, h, w]`.
    pub masks: String,
    /// Output: predicted IoU per mask `[1, M]`.
    pub iou_predictions: String,
}

impl Default for DecoderNames {
    fn default() -> Self {
        Self {
            image_embeddings: "image_embeddings".into(),
            point_coords: "point_coords".into(),
            point_labels: "point_labels".into(),
            mask_input: "mask_input".into(),
            has_mask_input: "has_mask_input".into(),
            orig_im_size: "orig_im_size".into(),
            masks: "masks".into(),
            iou_predictions: "iou_predictions".into(),
        }
    }
}

/// Which raster the decoder's mask logits cover.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MaskFrame {
    /// The image when the logits have the image's size, else the padded input frame.
    Auto,
    /// The original image (SAM's export with `orig_im_size`).
    Image,
    /// The padded `S` x `S` input frame (low-resolution masks).
    InputFrame,
}

/// How images and prompts are fed to the encoder and decoder and how masks are read.
#[derive(Debug, Clone, PartialEq)]
pub struct SegmenterConfig {
    /// Side `S` of the square input frame when the encoder's input size is dynamic.
    pub input_size: u32,
    /// Pixel normalisation.
    pub normalisation: Normalisation,
    /// The encoder's image input; `None` takes its only input.
    pub encoder_input: Option<String>,
    /// The encoder output handed to the decoder; `None` takes its first output.
    pub encoder_output: Option<String>,
    /// The decoder's tensor names.
    pub decoder: DecoderNames,
    /// Logits above this are inside the mask.
    pub mask_threshold: f32,
    /// Which raster the mask logits cover.
    pub mask_frame: MaskFrame,
}

impl Default for SegmenterConfig {
    fn default() -> Self {
        Self {
            input_size: 1024,
            normalisation: Normalisation::IMAGENET,
            encoder_input: None,
            encoder_output: None,
            decoder: DecoderNames::default(),
            mask_threshold: 0.0,
            mask_frame: MaskFrame::Auto,
        }
    }
}

/// SAM's "resize longest side" transform: the image scaled so its longer side is the frame
/// side, placed in the top-left corner of the square frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LongestSide {
    /// The original image size (width, height).
    pub image: (u32, u32),
    /// The resized image size (width, height), each side rounded to the nearest pixel.
    pub resized: (u32, u32),
    /// Side of the square frame.
    pub frame: u32,
}

impl LongestSide {
    /// The transform of a `width` x `height` image into a `frame` x `frame` input.
    pub fn new(width: u32, height: u32, frame: u32) -> Self {
        let scale = f64::from(frame) / f64::from(width.max(height).max(1));
        let side = |s: u32| ((f64::from(s) * scale + 0.5).floor() as u32).clamp(1, frame);
        Self {
            image: (width, height),
            resized: (side(width), side(height)),
            frame,
        }
    }

    /// A normalised `[x_min, y_min, x_max, y_max]` box as frame pixel coordinates.
    pub fn box_in_frame(&self, bbox: [f32; 4]) -> [f32; 4] {
        let (rw, rh) = (self.resized.0 as f32, self.resized.1 as f32);
        [bbox[0] * rw, bbox[1] * rh, bbox[2] * rw, bbox[3] * rh]
    }

    /// The frame coordinates of the centre of image pixel (x, y).
    pub fn pixel_in_frame(&self, x: u32, y: u32) -> (f32, f32) {
        let sx = self.resized.0 as f32 / self.image.0 as f32;
        let sy = self.resized.1 as f32 / self.image.1 as f32;
        ((x as f32 + 0.5) * sx, (y as f32 + 0.5) * sy)
    }
}

/// Checks a box prompt: finite, inside [0, 1], with positive width and height.
pub(crate) fn check_box(prompt: &BoxPrompt) -> Result<(), String> {
    let [x0, y0, x1, y1] = prompt.bbox;
    let inside = |v: f32| v.is_finite() && (0.0..=1.0).contains(&v);
    if ![x0, y0, x1, y1].into_iter().all(inside) || x0 >= x1 || y0 >= y1 {
        return Err(format!(
            "box prompt `{}` is {:?}; expected normalised [x_min, y_min, x_max, y_max] in [0, 1] \
             with x_min < x_max and y_min < y_max",
            prompt.label, prompt.bbox
        ));
    }
    Ok(())
}

/// The number of masks and their grid size `(M, w, h)` from a `[1, M, h, w]` or `[M, h, w]`
/// logits shape.
pub(crate) fn mask_grid(shape: &[i64]) -> Result<(usize, usize, usize), String> {
    let (m, h, w) = match shape {
        [1, m, h, w] | [m, h, w] => (*m, *h, *w),
        _ => return Err(format!("expected shape [1, M, H, W], got {shape:?}")),
    };
    if m <= 0 || h <= 0 || w <= 0 {
        return Err(format!(
            "expected at least one non-empty mask, got {shape:?}"
        ));
    }
    Ok((m as usize, w as usize, h as usize))
}

/// The index of the mask with the highest predicted IoU (the first on ties) and that IoU
/// clamped to [0, 1]; `None` for `iou` means a single mask of score 1.
pub(crate) fn best_mask(count: usize, iou: Option<&[f32]>) -> Result<(usize, f32), String> {
    let Some(iou) = iou else {
        return if count == 1 {
            Ok((0, 1.0))
        } else {
            Err(format!(
                "{count} masks but no IoU predictions to choose among them"
            ))
        };
    };
    if iou.len() != count {
        return Err(format!(
            "{} IoU predictions for {count} masks; expected one per mask",
            iou.len()
        ));
    }
    let mut best = 0;
    for (k, v) in iou.iter().enumerate() {
        if *v > iou[best] || iou[best].is_nan() {
            best = k;
        }
    }
    let score = if iou[best].is_finite() {
        iou[best].clamp(0.0, 1.0)
    } else {
        0.0
    };
    Ok((best, score))
}

/// Thresholds one mask's logits (a `w` x `h` grid) into an image-size mask.
pub(crate) fn mask_pixels(
    logits: &[f32],
    grid: (usize, usize),
    transform: &LongestSide,
    frame: MaskFrame,
    threshold: f32,
) -> Vec<bool> {
    let (width, height) = transform.image;
    let at_image_size = grid == (width as usize, height as usize);
    let in_image = match frame {
        MaskFrame::Auto => at_image_size,
        MaskFrame::Image => true,
        MaskFrame::InputFrame => false,
    };
    let mut out = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        for x in 0..width {
            let value = if in_image && at_image_size {
                logits[y as usize * grid.0 + x as usize]
            } else if in_image {
                // Logits of another size covering the image: bilinear, centres aligned.
                let gx = (x as f32 + 0.5) * grid.0 as f32 / width as f32 - 0.5;
                let gy = (y as f32 + 0.5) * grid.1 as f32 / height as f32 - 0.5;
                sample_bilinear(logits, grid.0, grid.1, gx, gy)
            } else {
                let (fx, fy) = transform.pixel_in_frame(x, y);
                let side = transform.frame as f32;
                let gx = fx * grid.0 as f32 / side - 0.5;
                let gy = fy * grid.1 as f32 / side - 0.5;
                sample_bilinear(logits, grid.0, grid.1, gx, gy)
            };
            out.push(value > threshold);
        }
    }
    out
}

#[cfg(feature = "runtime")]
pub use provider::OnnxSegmenter;

#[cfg(feature = "runtime")]
mod provider {
    use std::path::Path;

    use scenethesis_imagery::Mask;
    use scenethesis_models::{
        BoxPrompt, ImageData, ProviderError, ProviderErrorKind, Segment, Segmenter,
    };

    use super::{best_mask, check_box, mask_grid, mask_pixels, LongestSide, SegmenterConfig};
    use crate::raster::{decode_rgb, resize_rgb, to_nchw};
    use crate::runtime::{Model, Runtime, TensorF32};
    use crate::signature::Signature;
    use crate::{OnnxError, ENDPOINT};

    /// A [`Segmenter`] running a SAM-style encoder/decoder pair (see the
    /// [module documentation](crate::segment) for the signatures it expects).
    pub struct OnnxSegmenter {
        encoder: Model,
        decoder: Model,
        config: SegmenterConfig,
        encoder_input: String,
        encoder_output: String,
        /// Side of the square input frame.
        frame: u32,
        /// Shape of the decoder's `mask_input`, when it has one.
        mask_input: Option<Vec<i64>>,
        has_mask_flag: bool,
        has_orig_size: bool,
        has_iou: bool,
    }

    impl std::fmt::Debug for OnnxSegmenter {
        fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.debug_struct("OnnxSegmenter")
                .field("encoder", &self.encoder.path)
                .field("decoder", &self.decoder.path)
                .field("frame", &self.frame)
                .finish()
        }
    }

    impl OnnxSegmenter {
        /// Opens the encoder and decoder models and checks their signatures against `config`.
        pub fn new(
            runtime: &Runtime,
            encoder: impl AsRef<Path>,
            decoder: impl AsRef<Path>,
            config: SegmenterConfig,
        ) -> Result<Self, OnnxError> {
            if config.input_size == 0 || !config.mask_threshold.is_finite() {
                return Err(OnnxError::Config {
                    what: "segmenter setting `input_size`/`mask_threshold`".into(),
                    message: format!(
                        "expected a positive input size and a finite threshold, got {} and {}",
                        config.input_size, config.mask_threshold
                    ),
                });
            }
            let encoder = Model::open(runtime, encoder.as_ref())?;
            let decoder = Model::open(runtime, decoder.as_ref())?;
            let enc = Signature::new(&encoder, "encoder");
            let (input, h, w) = enc.rgb_input(config.encoder_input.as_deref(), "[1, 3, S, S]")?;
            let frame = match (h, w) {
                (h, w) if h > 0 && h == w => h as u32,
                (h, w) if h <= 0 && w <= 0 => config.input_size,
                _ => {
                    return Err(enc.error(format!(
                        "input {} should be a square frame [1, 3, S, S]",
                        input.describe()
                    )))
                }
            };
            let encoder_input = input.name.clone();
            let encoder_output = enc
                .output_or_first(config.encoder_output.as_deref())?
                .name
                .clone();

            let names = &config.decoder;
            let dec = Signature::new(&decoder, "decoder");
            for required in [
                &names.image_embeddings,
                &names.point_coords,
                &names.point_labels,
            ] {
                dec.input(required, "")?;
            }
            let known = [
                &names.image_embeddings,
                &names.point_coords,
                &names.point_labels,
                &names.mask_input,
                &names.has_mask_input,
                &names.orig_im_size,
            ];
            if let Some(other) = decoder.inputs.iter().find(|p| !known.contains(&&p.name)) {
                return Err(dec.error(format!(
                    "input {} is not one the segmenter feeds (it feeds {})",
                    other.describe(),
                    known
                        .iter()
                        .map(|n| format!("`{n}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                )));
            }
            dec.output(&names.masks)?;
            let low_res = i64::from(frame / 4);
            let mask_input =
                decoder
                    .input(&names.mask_input)
                    .map(|port| match port.shape.as_deref() {
                        Some(dims) if dims.len() == 4 => dims
                            .iter()
                            .zip([1, 1, low_res, low_res])
                            .map(|(d, default)| if *d > 0 { *d } else { default })
                            .collect(),
                        _ => vec![1, 1, low_res, low_res],
                    });
            Ok(Self {
                has_mask_flag: decoder.input(&names.has_mask_input).is_some(),
                has_orig_size: decoder.input(&names.orig_im_size).is_some(),
                has_iou: decoder.output(&names.iou_predictions).is_some(),
                mask_input,
                encoder_input,
                encoder_output,
                frame,
                config,
                encoder,
                decoder,
            })
        }

        /// Side of the square input frame the encoder takes.
        pub fn input_size(&self) -> u32 {
            self.frame
        }

        fn error(&self, model: &Model, kind: ProviderErrorKind) -> ProviderError {
            ProviderError::new(ENDPOINT, model.path.display().to_string(), kind)
        }

        fn malformed(&self, model: &Model, message: String) -> ProviderError {
            self.error(
                model,
                ProviderErrorKind::Malformed {
                    message,
                    source: None,
                },
            )
        }

        /// Runs the decoder for one box and thresholds the best mask.
        fn decode(
            &self,
            embeddings: &TensorF32,
            transform: &LongestSide,
            prompt: &BoxPrompt,
        ) -> Result<Segment, ProviderError> {
            let names = &self.config.decoder;
            let [x0, y0, x1, y1] = transform.box_in_frame(prompt.bbox);
            let mut inputs = vec![
                (names.image_embeddings.clone(), embeddings.clone()),
                (
                    names.point_coords.clone(),
                    TensorF32 {
                        shape: vec![1, 2, 2],
                        data: vec![x0, y0, x1, y1],
                    },
                ),
                (
                    names.point_labels.clone(),
                    TensorF32 {
                        shape: vec![1, 2],
                        data: vec![2.0, 3.0],
                    },
                ),
            ];
            if let Some(shape) = &self.mask_input {
                let len = shape.iter().product::<i64>() as usize;
                inputs.push((
                    names.mask_input.clone(),
                    TensorF32 {
                        shape: shape.clone(),
                        data: vec![0.0; len],
                    },
                ));
            }
            if self.has_mask_flag {
                inputs.push((
                    names.has_mask_input.clone(),
                    TensorF32 {
                        shape: vec![1],
                        data: vec![0.0],
                    },
                ));
            }
            let (width, height) = transform.image;
            if self.has_orig_size {
                inputs.push((
                    names.orig_im_size.clone(),
                    TensorF32 {
                        shape: vec![2],
                        data: vec![height as f32, width as f32],
                    },
                ));
            }
            let mut wanted = vec![names.masks.as_str()];
            if self.has_iou {
                wanted.push(names.iou_predictions.as_str());
            }
            let outputs = self.decoder.run(inputs, &wanted).map_err(|m| {
                self.malformed(&self.decoder, format!("box `{}`: {m}", prompt.label))
            })?;
            let masks = &outputs[0];
            let (count, gw, gh) = mask_grid(&masks.shape).map_err(|e| {
                self.malformed(&self.decoder, format!("output `{}`: {e}", names.masks))
            })?;
            let iou = outputs.get(1).map(|t| t.data.as_slice());
            let (best, score) = best_mask(count, iou).map_err(|e| {
                self.malformed(
                    &self.decoder,
                    format!("outputs `{}`/`{}`: {e}", names.masks, names.iou_predictions),
                )
            })?;
            let plane = &masks.data[best * gw * gh..(best + 1) * gw * gh];
            let pixels = mask_pixels(
                plane,
                (gw, gh),
                transform,
                self.config.mask_frame,
                self.config.mask_threshold,
            );
            let mask = Mask::from_flags(width, height, pixels).map_err(|e| {
                self.malformed(&self.decoder, format!("box `{}`: {e}", prompt.label))
            })?;
            Ok(Segment {
                label: prompt.label.clone(),
                mask,
                score,
            })
        }
    }

    impl Segmenter for OnnxSegmenter {
        fn name(&self) -> String {
            format!(
                "onnx/{}+{}",
                crate::model_stem(&self.encoder.path),
                crate::model_stem(&self.decoder.path)
            )
        }

        fn segment(
            &self,
            image: &ImageData,
            boxes: &[BoxPrompt],
        ) -> Result<Vec<Segment>, ProviderError> {
            for prompt in boxes {
                check_box(prompt).map_err(|message| {
                    self.error(&self.decoder, ProviderErrorKind::InvalidRequest { message })
                })?;
            }
            if boxes.is_empty() {
                return Ok(Vec::new());
            }
            let rgb = decode_rgb(image).map_err(|message| {
                self.error(&self.encoder, ProviderErrorKind::InvalidRequest { message })
            })?;
            let transform = LongestSide::new(rgb.width(), rgb.height(), self.frame);
            let resized = resize_rgb(&rgb, transform.resized.0, transform.resized.1);
            let input = TensorF32 {
                shape: vec![1, 3, i64::from(self.frame), i64::from(self.frame)],
                data: to_nchw(&resized, &self.config.normalisation, self.frame, self.frame),
            };
            let embeddings = self
                .encoder
                .run(
                    vec![(self.encoder_input.clone(), input)],
                    &[&self.encoder_output],
                )
                .map_err(|m| self.malformed(&self.encoder, m))?
                .remove(0);
            boxes
                .iter()
                .map(|prompt| self.decode(&embeddings, &transform, prompt))
                .collect()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn longest_side_scales_and_rounds_like_sam() {
        let t = LongestSide::new(200, 120, 1024);
        assert_eq!(t.resized, (1024, 614)); // 120 * 5.12 = 614.4
        let t = LongestSide::new(90, 160, 1024);
        assert_eq!(t.resized, (576, 1024));
        assert_eq!(
            t.box_in_frame([0.5, 0.25, 1.0, 1.0]),
            [288.0, 256.0, 576.0, 1024.0]
        );
        let (fx, fy) = t.pixel_in_frame(0, 0);
        assert!((fx - 3.2).abs() < 1e-5 && (fy - 3.2).abs() < 1e-5);
    }

    #[test]
    fn boxes_are_checked() {
        let ok = BoxPrompt {
            label: "sofa_0".into(),
            bbox: [0.1, 0.2, 0.5, 0.9],
        };
        assert!(check_box(&ok).is_ok());
        for bbox in [
            [0.5, 0.2, 0.1, 0.9],
            [0.1, 0.2, 1.5, 0.9],
            [f32::NAN, 0.0, 1.0, 1.0],
        ] {
            let err = check_box(&BoxPrompt { bbox, ..ok.clone() }).unwrap_err();
            assert!(err.contains("sofa_0"), "{err}");
        }
    }

    #[test]
    fn the_best_mask_has_the_highest_iou() {
        assert_eq!(best_mask(3, Some(&[0.2, 0.9, 0.5])), Ok((1, 0.9)));
        assert_eq!(best_mask(2, Some(&[1.3, 0.1])), Ok((0, 1.0)));
        assert_eq!(best_mask(1, None), Ok((0, 1.0)));
        assert!(best_mask(2, None).is_err());
        assert!(best_mask(2, Some(&[0.1])).unwrap_err().contains("1 IoU"));
        assert_eq!(mask_grid(&[1, 3, 256, 128]), Ok((3, 128, 256)));
        assert!(mask_grid(&[2, 3, 4, 4, 4]).is_err());
    }

    #[test]
    fn frame_logits_map_back_through_the_resize_and_padding() {
        // A 100 x 50 image in a 64 frame: resized to 64 x 32, the rest is padding. Logits on an
        // 8 x 8 grid are the frame x coordinate minus 32 (inside = right half of the image).
        let t = LongestSide::new(100, 50, 64);
        let grid: Vec<f32> = (0..8)
            .flat_map(|_| (0..8).map(|gx| (gx as f32 + 0.5) * 8.0 - 32.0))
            .collect();
        let mask = mask_pixels(&grid, (8, 8), &t, MaskFrame::Auto, 0.0);
        assert_eq!(mask.len(), 100 * 50);
        for y in 0..50 {
            for x in 0..100 {
                assert_eq!(mask[y * 100 + x], x >= 50, "pixel ({x}, {y})");
            }
        }
        // Logits already at the image size are thresholded as they are.
        let direct: Vec<f32> = (0..100 * 50)
            .map(|i| if i % 2 == 0 { 1.0 } else { -1.0 })
            .collect();
        let mask = mask_pixels(&direct, (100, 50), &t, MaskFrame::Auto, 0.0);
        assert!(mask.iter().enumerate().all(|(i, m)| *m == (i % 2 == 0)));
    }
}
