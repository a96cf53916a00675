//! Guide selection for `generate`: the procedural guide (default) or the vision guide, from
//! given guidance files or from an image model's edit of the empty room's render.

use std::path::PathBuf;

use anyhow::{Context, Result};
use scenethesis_openai::OpenAiClient;
use scenethesis_pipeline::{GuidedSettings, Pipeline, ShapeMatcher};
use scenethesis_vision_guide::{
    photo_scene, GivenGuidance, GuidanceFiles, PhotoScene, VisionGuide,
};

use super::providers::ProviderArgs;

/// Size of the empty-room render the image model edits (3:2, so a 1536 × 1024 answer of
/// GPT image models is resampled to it).
pub const EDIT_SIZE: [u32; 2] = [768, 512];

/// Which guide lays the plan out.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum GuideChoice {
    /// Rule-based layout (the offline default).
    Procedural,
    /// Layout lifted from a guidance image (given with --guide-image, or drawn by the image
    /// model into a render of the empty room).
    Vision,
}

/// How the correspond stage matches assets to the guidance image.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum MatcherChoice {
    /// Silhouette and depth agreement of each asset rendered at its pose (the default).
    #[default]
    Shape,
    /// No correspond stage: the optimizer starts from the lifted poses.
    None,
}

/// The guide flags of `generate`.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct GuideArgs {
    /// The guide: `procedural` (default) or `vision` (default when --guide-image is given).
    #[arg(long, value_enum, value_name = "GUIDE")]
    pub guide: Option<GuideChoice>,
    /// The guidance image (PNG) the vision guide lifts; without it, `--guide vision` renders the
    /// empty room and has the image model (--image-model) furnish it.
    #[arg(long, value_name = "FILE")]
    pub guide_image: Option<PathBuf>,
    /// Instance masks of the guidance image: a 16-bit PNG of instance values (0 = none);
    /// needs --guide-labels. Without masks the VLM (--vlm-model) boxes the objects; with them,
    /// a --vlm-model given is asked only for the support relations.
    #[arg(long, value_name = "IDS_PNG", requires_all = ["guide_image", "guide_labels"])]
    pub guide_masks: Option<PathBuf>,
    /// Labels of --guide-masks: {"VALUE": {"id": "sofa_0", "category": "sofa"}, …}.
    #[arg(long, value_name = "LABELS_JSON", requires_all = ["guide_image", "guide_masks"])]
    pub guide_labels: Option<PathBuf>,
    /// Metric depth of the guidance image: depth.npy (float32 metres) or a 16-bit PNG
    /// (millimetres).
    #[arg(long, value_name = "FILE", requires = "guide_image")]
    pub guide_depth: Option<PathBuf>,
    /// The guidance image's camera (docs/guidance.md); without it, it is estimated from the
    /// floor of the depth.
    #[arg(long, value_name = "CAMERA_JSON", requires = "guide_image")]
    pub camera: Option<PathBuf>,
    /// With the vision guide: also place the planned objects the image does not show, offline
    /// around what the image fixes (by default they are left out and reported).
    #[arg(long)]
    pub keep_plan: bool,
    /// With the vision guide: align each asset to the guidance before optimizing (`shape`,
    /// the default) or not (`none`).
    #[arg(long, value_enum, value_name = "MATCHER", default_value_t = MatcherChoice::Shape)]
    pub matcher: MatcherChoice,
    /// Depth and segmentation models run through ONNX Runtime (feature `onnx`).
    #[command(flatten)]
    pub onnx: Box<super::onnx::OnnxArgs>,
}

impl GuideArgs {
    /// The guide these flags select.
    pub fn choice(&self) -> GuideChoice {
        match (self.guide, &self.guide_image) {
            (Some(g), _) => g,
            (None, Some(_)) => GuideChoice::Vision,
            (None, None) => GuideChoice::Procedural,
        }
    }

    /// Installs the selected guide. The procedural default leaves `pipeline` as it is; the
    /// vision guide reads and checks its files first (any problem stops the run before anything
    /// is written). The models it uses report their use in `report.json` like the others.
    /// With `photo_alone` (no prompt, no plan) the given guidance must show its objects and
    /// floor, and the returned [`PhotoScene`] holds the prompt read from it.
    pub fn apply(
        &self,
        pipeline: Pipeline,
        models: &ProviderArgs,
        photo_alone: bool,
    ) -> Result<(Pipeline, Option<PhotoScene>)> {
        if photo_alone && (self.choice() != GuideChoice::Vision || self.guide_image.is_none()) {
            anyhow::bail!(
                "no prompt: give one, a --plan, or a --guide-image to build the scene it shows"
            );
        }
        let mut photo = None;
        if self.choice() == GuideChoice::Procedural {
            if let Some(image) = &self.guide_image {
                anyhow::bail!(
                    "--guide-image {}: given with --guide procedural, which reads no image; use --guide vision",
                    image.display()
                );
            }
            if self.keep_plan {
                anyhow::bail!(
                    "--keep-plan: given with --guide procedural, which places every planned object anyway; it keeps the plan's objects beside what a guidance image (--guide vision) shows"
                );
            }
            self.onnx.reject_unused()?;
            return Ok((pipeline, None));
        }
        if let (MatcherChoice::None, Some(model)) = (self.matcher, &self.onnx.match_model) {
            anyhow::bail!(
                "--match-model {}: given with --matcher none, which turns the correspond stage off, so the model would not be used",
                model.display()
            );
        }
        let onnx = self.onnx.load()?;
        let guide = match &self.guide_image {
            Some(image) => {
                let files = GuidanceFiles {
                    image: image.clone(),
                    masks: self.guide_masks.clone(),
                    labels: self.guide_labels.clone(),
                    depth: self.guide_depth.clone(),
                    camera: self.camera.clone(),
                };
                let categories = pipeline.assets().categories();
                let given = GivenGuidance::read(&files, &categories)
                    .context("reading the guidance files")?;
                if photo_alone {
                    photo = Some(photo_scene(&given)?);
                }
                let guide = VisionGuide::from_files(given);
                if self.guide_masks.is_some() {
                    // Masks given: a VLM named with --vlm-model still cross-checks the supports.
                    match &models.vlm_model {
                        Some(_) => {
                            let chat = client(models)?
                                .vlm()
                                .context("the vision guide asks --vlm-model for the supports")?;
                            guide.with_vlm(models.wrap(chat)?)
                        }
                        None => guide,
                    }
                } else {
                    let client = client(models)?;
                    let chat = client
                        .vlm()
                        .context("the vision guide boxes the objects of --guide-image without --guide-masks with a vision-language model")?;
                    guide.with_vlm(models.wrap(chat)?)
                }
            }
            None => {
                let client = client(models)?;
                let images = models.wrap_images(client.image_model().context(
                    "--guide vision without --guide-image has an image model furnish the empty room",
                )?)?;
                let chat = client
                    .vlm()
                    .context("the vision guide boxes the objects with a vision-language model")?;
                let vlm = models.wrap(chat)?;
                let renderer = scenethesis_render::Renderer::from_env().context(
                    "--guide vision without --guide-image renders the empty room and needs a renderer",
                )?;
                VisionGuide::edit_render(renderer, images, EDIT_SIZE).with_vlm(vlm)
            }
        };
        let guide = guide.with_keep_plan(self.keep_plan);
        let (pipeline, dense) = onnx.install(guide, pipeline);
        let pipeline = match self.matcher {
            _ if dense => pipeline,
            MatcherChoice::Shape => {
                pipeline.with_matcher(ShapeMatcher::default(), GuidedSettings::default())
            }
            MatcherChoice::None => pipeline,
        };
        Ok((pipeline, photo))
    }
}

fn client(models: &ProviderArgs) -> Result<OpenAiClient> {
    models.client()
}
