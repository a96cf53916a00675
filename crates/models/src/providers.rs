//! Image generators, segmenters, depth estimators and text embedders.

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

/// A binary mask of one prompted object.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Mask {
    /// The prompt's label.
    pub label: String,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major, one entry per pixel, `true` inside the object.
    pub pixels: Vec<bool>,
    /// The model's confidence in [0, 1].
    pub score: f32,
}

impl Mask {
    /// Number of pixels inside the object.
    pub fn area(&self) -> usize {
        self.pixels.iter().filter(|p| **p).count()
    }
}

/// Segments prompted objects of an image.
pub trait Segmenter: Send + Sync {
    /// `provider/model`, recorded in reports and cache keys.
    fn name(&self) -> String;

    /// One mask per box, in the order of `boxes`, each the size of the image.
    fn segment(&self, image: &ImageData, boxes: &[BoxPrompt]) -> Result<Vec<Mask>, ProviderError>;
}

/// Pinhole intrinsics in pixels.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Intrinsics {
    /// Focal length along x.
    pub fx: f32,
    /// Focal length along y.
    pub fy: f32,
    /// Principal point x.
    pub cx: f32,
    /// Principal point y.
    pub cy: f32,
}

/// A metric depth map.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DepthMap {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major distance along the optical axis in metres; 0 where unknown (JSON, and so the
    /// response cache, cannot hold non-finite numbers).
    pub metres: Vec<f32>,
    /// The intrinsics used or estimated.
    pub intrinsics: Intrinsics,
}

impl DepthMap {
    /// Depth at pixel (x, y), if inside the map.
    pub fn at(&self, x: u32, y: u32) -> Option<f32> {
        (x < self.width && y < self.height).then(|| self.metres[(y * self.width + x) as usize])
    }
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
    ) -> Result<DepthMap, ProviderError>;
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
