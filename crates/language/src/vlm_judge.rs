//! [`VlmJudge`]: the geometric judge first, then a vision-language model looking at rendered
//! previews of the scene (and the guidance image, when the guide had one), as the paper's VLM
//! judge does.

use std::collections::{BTreeMap, BTreeSet};

use scenethesis_judge::{
    Failure, FailureKind, GeometricJudge, Judge, JudgeError, JudgeInput, Verdict,
};
use scenethesis_models::{ChatModel, ChatRequest, ImageData, JsonSchema, Message};
use scenethesis_render_api::{render_previews, SceneRenderer};
use scenethesis_scene_graph::limits::MAX_ID_BYTES;
use serde::{Deserialize, Serialize};
use serde_json::json;

use crate::review::{
    read_review, ObjectReason, ReadReview, MAX_REVIEW_OBJECTS, MAX_REVIEW_TEXT_CHARS,
};
use crate::salvage::close_truncated;

const INSTRUCTIONS: &str = "You judge 3D scenes made for a physics simulator from a text prompt. \
You see rendered previews of the scene and a list of its objects (id, category, position in \
metres with +Y up and the front of the room towards +Z, yaw in degrees about +Y). Score in [0, 1]: \
`category_accuracy` (does every object look like its category and fit the prompt), \
`orientation_alignment` (do objects face sensible directions: chairs towards tables, shelves \
away from walls, screens towards seats) and `spatial_coherence` (is the arrangement plausible as \
a whole). List under `objects` every object that is wrong, with its id and the reason in one \
sentence. Physics (collisions, stability) is checked elsewhere; judge what a person would see.";

/// The name the guidance image goes by in the judge's message and its review's `views`.
const GUIDANCE_VIEW: &str = "guidance.png";
const GUIDANCE_NOTE: &str =
    "\nThe first image (guidance.png) is the guidance image the layout was \
lifted from: the scene should show the same objects in the same arrangement; judge \
`spatial_coherence` against it.";

/// Scores below which the [`VlmJudge`] rejects a scene.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct VlmThresholds {
    /// Smallest acceptable object-category accuracy.
    pub category_accuracy: f64,
    /// Smallest acceptable orientation alignment.
    pub orientation_alignment: f64,
    /// Smallest acceptable overall spatial coherence.
    pub spatial_coherence: f64,
}

impl Default for VlmThresholds {
    /// 0.6 for each score.
    fn default() -> Self {
        Self {
            category_accuracy: 0.6,
            orientation_alignment: 0.6,
            spatial_coherence: 0.6,
        }
    }
}

/// The model's review of a scene, as recorded in `report.json` (`verdict.review`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VlmReview {
    /// The model (`provider/model`).
    pub model: String,
    /// Object-category accuracy in [0, 1].
    pub category_accuracy: f64,
    /// Orientation alignment in [0, 1].
    pub orientation_alignment: f64,
    /// Overall spatial coherence in [0, 1].
    pub spatial_coherence: f64,
    /// Objects the model found wrong, with reasons.
    pub objects: Vec<ObjectReason>,
    /// The model's summary.
    pub summary: String,
    /// The thresholds applied.
    pub thresholds: VlmThresholds,
    /// Whether every score reached its threshold.
    pub accepted: bool,
    /// The preview images the model saw.
    pub views: Vec<String>,
    /// How the answer was read, when it was not a complete, valid review: format fallbacks,
    /// a cut-off or partly invalid answer salvaged, what was dropped (absent when empty).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
}

/// The `max_tokens` of a review request: scores and summary (300 tokens: about 100 for the
/// summary's 400 characters, the rest for the scores and syntax) plus up to
/// [`MAX_REVIEW_OBJECTS`] objects of an id and a reason (180 tokens each: about 64 for an id,
/// 100 for a reason).
pub const fn review_max_tokens() -> u32 {
    300 + 180 * MAX_REVIEW_OBJECTS as u32
}

/// The structured answer asked of the model.
pub fn review_schema() -> JsonSchema {
    let score = json!({"type": "number", "minimum": 0.0, "maximum": 1.0});
    JsonSchema::new(
        "scene_review",
        json!({
            "type": "object",
            "additionalProperties": false,
            "required": ["category_accuracy", "orientation_alignment", "spatial_coherence",
                         "objects", "summary"],
            "properties": {
                "category_accuracy": score,
                "orientation_alignment": score,
                "spatial_coherence": score,
                "objects": {"type": "array", "maxItems": MAX_REVIEW_OBJECTS, "items": {
                    "type": "object",
                    "additionalProperties": false,
                    "required": ["id", "reason"],
                    "properties": {
                        "id": {"type": "string", "maxLength": MAX_ID_BYTES},
                        "reason": {"type": "string", "maxLength": MAX_REVIEW_TEXT_CHARS}
                    }
                }},
                "summary": {"type": "string", "maxLength": MAX_REVIEW_TEXT_CHARS}
            }
        }),
    )
    .expect("the review schema is valid")
}

/// A [`Judge`] that runs the [`GeometricJudge`] first (physics is never delegated to a model)
/// and, when the geometry passes, shows a [`ChatModel`] with vision the rendered previews. A
/// score below its [`VlmThresholds`] rejects the scene with one [`FailureKind::Visual`]
/// failure per object the model blamed (or one for the whole scene), so the pipeline re-plans
/// with the model's reasons. The review goes into the verdict (`verdict.review` of
/// `report.json`). Provider failures are [`JudgeError::Provider`] errors naming the endpoint
/// and model.
pub struct VlmJudge<M> {
    model: M,
    renderer: Box<dyn SceneRenderer>,
    geometric: GeometricJudge,
    thresholds: VlmThresholds,
    size: [u32; 2],
    name: String,
}

impl<M> std::fmt::Debug for VlmJudge<M> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("VlmJudge")
            .field("name", &self.name)
            .field("renderer", &self.renderer.name())
            .field("thresholds", &self.thresholds)
            .field("size", &self.size)
            .finish_non_exhaustive()
    }
}

impl<M: ChatModel> VlmJudge<M> {
    /// A judge asking `model` about previews drawn by `renderer` (640 × 480), with the default
    /// thresholds.
    pub fn new(model: M, renderer: impl SceneRenderer + 'static) -> Self {
        let name = format!("geometric+vlm:{}", model.name());
        Self {
            model,
            renderer: Box::new(renderer),
            geometric: GeometricJudge::default(),
            thresholds: VlmThresholds::default(),
            size: [640, 480],
            name,
        }
    }

    /// Sets the thresholds.
    pub fn with_thresholds(mut self, thresholds: VlmThresholds) -> Self {
        self.thresholds = thresholds;
        self
    }

    /// Sets the preview size in pixels.
    pub fn with_preview_size(mut self, size: [u32; 2]) -> Self {
        self.size = size;
        self
    }

    fn provider_error(&self, message: impl Into<String>) -> JudgeError {
        JudgeError::Provider {
            judge: self.name.clone(),
            message: message.into(),
        }
    }

    /// Asks the model for a review of the scene `messages` show, read leniently: an answer
    /// cut off part way or partly off the schema keeps what is valid (see [`read_review`]);
    /// only one without the three scores is an error.
    fn ask(&self, messages: Vec<Message>) -> Result<ReadReview, JudgeError> {
        let mut request = ChatRequest::structured(messages, review_schema());
        request.max_tokens = Some(review_max_tokens());
        request.lenient = true;
        let response = self
            .model
            .chat(&request)
            .map_err(|e| self.provider_error(e.to_string()))?;
        let unusable = |what: String| {
            self.provider_error(format!(
                "model `{}`: the review {what}{}",
                self.model.name(),
                if response.notes.is_empty() {
                    String::new()
                } else {
                    format!(" ({})", response.notes.join("; "))
                }
            ))
        };
        let (value, salvaged) = match &response.json {
            Some(v) => (v.clone(), !review_schema().violations(v).is_empty()),
            None => match close_truncated(&response.text) {
                Some(v) => (v, true),
                None => return Err(unusable("holds no JSON object".to_owned())),
            },
        };
        let mut read = read_review(&value).map_err(unusable)?;
        let mut notes = response.notes.clone();
        if salvaged {
            notes.push(
                "salvaged from an answer that does not fit schema `scene_review`: what is \
                 valid is kept"
                    .to_owned(),
            );
        }
        notes.append(&mut read.notes);
        read.notes = notes;
        Ok(read)
    }

    /// Renders the previews and asks the model; the review of `input`'s scene.
    pub fn review(&self, input: &JudgeInput<'_>) -> Result<VlmReview, JudgeError> {
        let previews =
            render_previews(self.renderer.as_ref(), input.scene, input.meshes, self.size).map_err(
                |e| {
                    self.provider_error(format!(
                        "cannot render previews with `{}`: {e}",
                        self.renderer.name()
                    ))
                },
            )?;
        if previews.is_empty() {
            return Err(self.provider_error(format!(
                "renderer `{}` drew no previews",
                self.renderer.name()
            )));
        }
        let mut listing = String::new();
        for o in &input.scene.objects {
            let p = o.pose.translation;
            listing.push_str(&format!(
                "- {} ({}): position ({:.2}, {:.2}, {:.2}), yaw {:.0}°\n",
                o.id,
                o.category,
                p.x,
                p.y,
                p.z,
                o.pose.yaw.to_degrees()
            ));
        }
        let mut views: Vec<&str> = previews.iter().map(|(n, _)| n.as_str()).collect();
        if input.guidance.is_some() {
            views.insert(0, GUIDANCE_VIEW);
        }
        let mut user = Message::user(format!(
            "Prompt: {}\nScene description: {}\nObjects ({}):\n{listing}Views: {}{}",
            input.scene.prompt.trim(),
            input.plan.description.trim(),
            input.scene.objects.len(),
            views.join(", "),
            if input.guidance.is_some() {
                GUIDANCE_NOTE
            } else {
                ""
            }
        ));
        if let Some(guidance) = input.guidance {
            let image = ImageData::from_bytes(guidance.image.to_png(), GUIDANCE_VIEW)
                .map_err(|e| self.provider_error(format!("{GUIDANCE_VIEW}: {e}")))?;
            user = user.with_image(image);
        }
        for (name, png) in &previews {
            let image = ImageData::from_bytes(png.clone(), name)
                .map_err(|e| self.provider_error(format!("preview {name}: {e}")))?;
            user = user.with_image(image);
        }
        let answer = self.ask(vec![Message::system(INSTRUCTIONS), user])?;
        let [c, o, s] = answer.scores;
        let t = self.thresholds;
        Ok(VlmReview {
            model: self.model.name(),
            category_accuracy: c,
            orientation_alignment: o,
            spatial_coherence: s,
            objects: answer.objects,
            summary: answer.summary,
            notes: answer.notes,
            thresholds: t,
            accepted: c >= t.category_accuracy
                && o >= t.orientation_alignment
                && s >= t.spatial_coherence,
            views: input
                .guidance
                .map(|_| GUIDANCE_VIEW.to_owned())
                .into_iter()
                .chain(previews.into_iter().map(|(n, _)| n))
                .collect(),
        })
    }
}

/// The failures a rejecting review gives: one per blamed object present in the scene, or one
/// for the whole scene when the model blamed none of them.
fn failures(review: &VlmReview, present: &BTreeSet<&str>) -> Vec<Failure> {
    let scores = format!(
        "category accuracy {:.2}, orientation alignment {:.2}, spatial coherence {:.2} (thresholds {:.2}, {:.2}, {:.2})",
        review.category_accuracy,
        review.orientation_alignment,
        review.spatial_coherence,
        review.thresholds.category_accuracy,
        review.thresholds.orientation_alignment,
        review.thresholds.spatial_coherence
    );
    let mut by_object: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    let mut order: Vec<&str> = Vec::new();
    for r in &review.objects {
        if present.contains(r.id.as_str()) {
            if !by_object.contains_key(r.id.as_str()) {
                order.push(r.id.as_str());
            }
            by_object
                .entry(r.id.as_str())
                .or_default()
                .push(r.reason.as_str());
        }
    }
    if order.is_empty() {
        return vec![Failure {
            kind: FailureKind::Visual,
            objects: vec![],
            detail: format!("{}: {scores}: {}", review.model, review.summary),
        }];
    }
    order
        .into_iter()
        .map(|id| Failure {
            kind: FailureKind::Visual,
            objects: vec![id.to_owned()],
            detail: format!(
                "{}: `{id}`: {} ({scores})",
                review.model,
                by_object[id].join("; ")
            ),
        })
        .collect()
}

impl<M: ChatModel> Judge for VlmJudge<M> {
    fn name(&self) -> &str {
        &self.name
    }

    fn judge(&self, input: &JudgeInput<'_>) -> Result<Verdict, JudgeError> {
        let mut verdict = self.geometric.judge(input)?;
        if !verdict.accepted {
            // Physics first: a scene the geometry rejects is re-planned without asking.
            return Ok(verdict);
        }
        let review = self.review(input)?;
        if !review.accepted {
            let present: BTreeSet<&str> =
                input.scene.objects.iter().map(|o| o.id.as_str()).collect();
            verdict.failures.extend(failures(&review, &present));
            verdict.accepted = false;
        }
        verdict.review = Some(
            serde_json::to_value(&review)
                .map_err(|e| self.provider_error(format!("cannot record the review: {e}")))?,
        );
        Ok(verdict)
    }
}
