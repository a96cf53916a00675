//! Image generators, segmenters, depth estimators and text embedders.

use scenethesis_imagery::{DepthMap, Intrinsics, Mask};
use serde::{Deserialize, Serialize};

use crate::error::ProviderError;
use crate::image::ImageData;

/// A text-to-image request.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ImageRequest {
    /// What to draw.
    pub prompt: String,
    /// Width and height in pixels.
    pub size: [u32; 2],
    /// Seed, for providers that honour one.
    pub seed: Option<u64>,
}

/// An image-edit request: repaint `image` (where `mask` is transparent, when given) after
/// `prompt`.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ImageEditRequest {
    /// What the result should show.
    pub prompt: String,
    /// The image to edit (PNG for most providers).
    pub image: ImageData,
    /// Optional PNG mask; transparent pixels are the ones to repaint.
    pub mask: Option<ImageData>,
    /// Width and height of the result in pixels.
    pub size: [u32; 2],
    /// Seed, for providers that honour one.
    pub seed: Option<u64>,
}

/// A generated or edited image.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct GeneratedImage {
    /// The image.
    pub image: ImageData,
    /// The prompt the provider actually used, when it rewrote it.
    pub revised_prompt: Option<String>,
}

/// Makes and edits images from text (the guidance image of the vision path).
pub trait ImageGenerator: Send + Sync {
    /// `provider/model`, recorded in reports and cache keys.
    fn name(&self) -> String;

    /// Draws a new image.
    fn generate(&self, request: &ImageRequest) -> Result<GeneratedImage, ProviderError>;

    /// Edits an existing image.
    fn edit(&self, request: &ImageEditRequest) -> Result<GeneratedImage, ProviderError>;
}

impl<M: ImageGenerator + ?Sized> ImageGenerator for Box<M> {
    fn name(&self) -> String {
        (**self).name()
    }

    fn generate(&self, request: &ImageRequest) -> Result<GeneratedImage, ProviderError> {
        (**self).generate(request)
    }

    fn edit(&self, request: &ImageEditRequest) -> Result<GeneratedImage, ProviderError> {
        (**self).edit(request)
    }
}

/// A box prompt for segmentation: a label and a box in normalised image coordinates
/// `[x_min, y_min, x_max, y_max]` in [0, 1], origin top left.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BoxPrompt {
    /// What the box holds (an object id or category).
    pub label: String,
    /// The box.
    pub bbox: [f32; 4],
}

/// One prompted object as a segmenter sees it: its mask (the image's size), the prompt's label
/// and the model's confidence. In JSON (a recorded answer) the mask's `width`, `height` and
/// `pixels` sit beside `label` and `score`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Segment {
    /// The prompt's label.
    pub label: String,
    /// The object's pixels.
    #[serde(flatten)]
    pub mask: Mask,
    /// The model's confidence in [0, 1].
    pub score: f32,
}

/// Segments prompted objects of an image.
pub trait Segmenter: Send + Sync {
    /// `provider/model`, recorded in reports and cache keys.
    fn name(&self) -> String;

    /// One mask per box, in the order of `boxes`, each the size of the image.
    fn segment(
        &self,
        image: &ImageData,
        boxes: &[BoxPrompt],
    ) -> Result<Vec<Segment>, ProviderError>;
}

/// A depth estimator's answer: metric depth at the image's size and the intrinsics the model
/// used or estimated. In JSON (a recorded answer) the depth map's `width`, `height` and
/// `metres` sit beside `intrinsics`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DepthEstimate {
    /// Distance along the optical axis in metres, per pixel.
    #[serde(flatten)]
    pub depth: DepthMap,
    /// The intrinsics used or estimated (the image's size).
    pub intrinsics: Intrinsics,
}

/// Estimates metric depth from one image.
pub trait DepthEstimator: Send + Sync {
    /// `provider/model`, recorded in reports and cache keys.
    fn name(&self) -> String;

    /// Depth for `image`; `intrinsics` when the camera is known, else the estimator infers them.
    fn estimate(
        &self,
        image: &ImageData,
        intrinsics: Option<Intrinsics>,
    ) -> Result<DepthEstimate, ProviderError>;
}

/// Turns texts into vectors whose cosine similarity reflects meaning.
pub trait TextEmbedder: Send + Sync {
    /// `provider/model`, recorded in reports and cache keys.
    fn name(&self) -> String;

    /// One vector per text, in order, all of the same length.
    fn embed(&self, texts: &[&str]) -> Result<Vec<Vec<f32>>, ProviderError>;
}

/// Cosine similarity of two vectors (0 when either is zero or their lengths differ).
pub fn cosine(a: &[f32], b: &[f32]) -> f32 {
    if a.len() != b.len() {
        return 0.0;
    }
    let (mut dot, mut na, mut nb) = (0.0f64, 0.0f64, 0.0f64);
    for (x, y) in a.iter().zip(b) {
        dot += f64::from(*x) * f64::from(*y);
        na += f64::from(*x) * f64::from(*x);
        nb += f64::from(*y) * f64::from(*y);
    }
    if na == 0.0 || nb == 0.0 {
        0.0
    } else {
        (dot / (na.sqrt() * nb.sqrt())) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_segment_records_its_mask_beside_its_label_and_score() {
        let mut mask = Mask::new(2, 1);
        mask.set(1, 0, true);
        let segment = Segment {
            label: "sofa_0".into(),
            mask,
            score: 0.5,
        };
        let json = serde_json::to_value(&segment).unwrap();
        assert_eq!(
            json,
            serde_json::json!({"label": "sofa_0", "width": 2, "height": 1,
                "pixels": [false, true], "score": 0.5})
        );
        assert_eq!(serde_json::from_value::<Segment>(json).unwrap(), segment);
    }

    #[test]
    fn a_depth_estimate_records_unknown_depth_as_zero() {
        let estimate = DepthEstimate {
            depth: DepthMap::from_fn(2, 1, |x, _| if x == 0 { f32::NAN } else { 1.5 }),
            intrinsics: Intrinsics::from_vertical_fov(2, 1, 1.0),
        };
        let json = serde_json::to_value(&estimate).unwrap();
        assert_eq!(json["metres"], serde_json::json!([0.0, 1.5]));
        let back: DepthEstimate = serde_json::from_value(json).unwrap();
        assert_eq!(
            (back.depth.get(0, 0), back.depth.get(1, 0)),
            (None, Some(1.5))
        );
        assert_eq!(back.intrinsics, estimate.intrinsics);
    }
}
