//! The VLM judge against a model served over real HTTP on 127.0.0.1: a low-scoring review
//! rejects the scene with the model's per-object reasons and the pipeline re-plans; the next
//! review accepts it; scores land in the report; provider failures are errors.

mod support;

use std::collections::BTreeMap;
use std::time::Duration;

use scenethesis_imagery::{Camera, Intrinsics};
use scenethesis_language::{VlmJudge, VlmThresholds};
use scenethesis_openai::{ClientConfig, OpenAiChat, OpenAiClient};
use scenethesis_pipeline::{FailureKind, GenerateOptions, NoProgress, Pipeline, PipelineError};
use scenethesis_render_api::{RendererError, SceneRenderer, ViewImage, ViewKind, ViewRequest};
use scenethesis_scene_graph::{Mesh, Scene};
use serde_json::{json, Value};
use support::{openai_completion, Reply, TestServer};

/// Draws each view one flat colour (by view, shaded by the object count).
struct FlatRenderer;

impl SceneRenderer for FlatRenderer {
    fn name(&self) -> String {
        "flat".into()
    }
    fn render_views(
        &self,
        scene: &Scene,
        _: &BTreeMap<String, Mesh>,
        views: &[ViewRequest],
    ) -> Result<Vec<ViewImage>, RendererError> {
        let shade = (scene.objects.len() * 10).min(255) as u8;
        Ok(views
            .iter()
            .map(|v| {
                let [w, h] = v.size;
                let rgba = match v.kind {
                    ViewKind::Photo => [shade, 90, 40, 255],
                    ViewKind::Top => [40, shade, 90, 255],
                };
                ViewImage {
                    camera: Camera::look_at(
                        Intrinsics::from_vertical_fov(w, h, 0.9),
                        [0.0, 3.0, 5.0].into(),
                        [0.0, 0.0, 0.0].into(),
                        nalgebra::Vector3::y(),
                    ),
                    color: image::RgbaImage::from_pixel(w, h, image::Rgba(rgba)),
                }
            })
            .collect())
    }
}

fn chat(server: &TestServer) -> OpenAiChat {
    let mut c = ClientConfig::new(&server.base_url);
    c.timeout = Duration::from_secs(5);
    c.max_attempts = 1;
    OpenAiClient::new(c).unwrap().chat("vision-model")
}

/// The id of the first object listed in a judge request's text.
fn first_listed_object(request: &Value) -> String {
    let parts = request["messages"][1]["content"].as_array().unwrap();
    let text = parts[0]["text"].as_str().unwrap();
    let line = text.lines().find(|l| l.starts_with("- ")).unwrap();
    line[2..].split(' ').next().unwrap().to_owned()
}

fn options() -> GenerateOptions {
    GenerateOptions {
        previews: false,
        ..GenerateOptions::default()
    }
}

#[test]
fn a_low_review_re_plans_with_the_models_reasons_then_accepts() {
    let server = TestServer::start(|i, request| {
        let body = request.json();
        let review = if i == 0 {
            let id = first_listed_object(&body);
            json!({"category_accuracy": 0.9, "orientation_alignment": 0.3,
                   "spatial_coherence": 0.7,
                   "objects": [{"id": id, "reason": "it faces the wall"},
                               {"id": "ghost_9", "reason": "not in the scene"}],
                   "summary": "one object is turned the wrong way"})
        } else {
            json!({"category_accuracy": 0.9, "orientation_alignment": 0.8,
                   "spatial_coherence": 0.85, "objects": [], "summary": "a tidy garage"})
        };
        Reply::json(200, &openai_completion("vision-model", &review.to_string()))
    });
    let judge = VlmJudge::new(chat(&server), FlatRenderer).with_preview_size([64, 48]);
    let pipeline = Pipeline::offline().with_judge(judge);
    let generated = pipeline
        .generate("a garage", 0, &options(), &mut NoProgress)
        .unwrap();
    let report = &generated.report;
    assert_eq!(report.judge, "geometric+vlm:openai-compatible/vision-model");
    let requests = server.requests();
    assert!(requests.len() >= 2, "asked again after the re-plan");
    // The model saw both previews as PNG data URLs.
    let first = requests[0].json();
    let parts = first["messages"][1]["content"].as_array().unwrap();
    let images: Vec<&str> = parts
        .iter()
        .filter_map(|p| p["image_url"]["url"].as_str())
        .collect();
    assert_eq!(images.len(), 2);
    assert!(images
        .iter()
        .all(|u| u.starts_with("data:image/png;base64,")));
    assert!(first.to_string().contains("scene_review"));
    // The rejection became a re-plan with the model's reason, on the blamed object only.
    let blamed = first_listed_object(&first);
    let replan = report
        .replans
        .iter()
        .find(|r| r.reasons.iter().any(|s| s.contains("it faces the wall")))
        .expect("a re-plan carries the model's reason");
    assert_eq!(replan.objects, vec![blamed.clone()]);
    assert!(replan.reasons.iter().all(|r| !r.contains("ghost_9")));
    assert!(replan.reasons[0].contains("orientation alignment 0.30"));
    // The final verdict holds the accepting review.
    assert!(report.accepted, "{:?}", report.verdict.failures);
    let review = report.verdict.review.as_ref().expect("review recorded");
    assert_eq!(review["orientation_alignment"], 0.8);
    assert_eq!(review["accepted"], true);
    assert_eq!(review["views"], json!(["preview.png", "preview_top.png"]));
    assert_eq!(review["model"], "openai-compatible/vision-model");
}

#[test]
fn thresholds_decide_and_failures_are_visual() {
    let server = TestServer::scripted(vec![Reply::json(
        200,
        &openai_completion(
            "vision-model",
            &json!({"category_accuracy": 0.5, "orientation_alignment": 0.5,
                    "spatial_coherence": 0.5, "objects": [], "summary": "so-so"})
            .to_string(),
        ),
    )]);
    // Lenient thresholds: accepted.
    let lenient = VlmThresholds {
        category_accuracy: 0.4,
        orientation_alignment: 0.4,
        spatial_coherence: 0.4,
    };
    let judge = VlmJudge::new(chat(&server), FlatRenderer)
        .with_preview_size([32, 32])
        .with_thresholds(lenient);
    let report = Pipeline::offline()
        .with_judge(judge)
        .generate("a garage", 0, &options(), &mut NoProgress)
        .unwrap()
        .report;
    assert!(report.accepted);
    assert_eq!(report.verdict.review.as_ref().unwrap()["accepted"], true);

    // Default thresholds (0.6): every attempt is rejected with one scene-wide visual failure.
    let judge = VlmJudge::new(chat(&server), FlatRenderer).with_preview_size([32, 32]);
    let mut opts = options();
    opts.max_replans = 1;
    let report = Pipeline::offline()
        .with_judge(judge)
        .generate("a garage", 0, &opts, &mut NoProgress)
        .unwrap()
        .report;
    assert!(!report.accepted);
    let visual: Vec<_> = report
        .verdict
        .failures
        .iter()
        .filter(|f| f.kind == FailureKind::Visual)
        .collect();
    assert_eq!(visual.len(), 1, "{:?}", report.verdict.failures);
    assert!(visual[0].objects.is_empty());
    assert!(visual[0].detail.contains("so-so"));
}

#[test]
fn the_judge_sees_the_guidance_image_first_when_there_is_one() {
    use scenethesis_imagery::{Camera, Guidance, Intrinsics, RgbImage};
    use scenethesis_pipeline::{Judge, JudgeInput};

    let server = TestServer::start(|_, _| {
        Reply::json(
            200,
            &openai_completion(
                "vision-model",
                &json!({"category_accuracy": 0.9, "orientation_alignment": 0.9,
                        "spatial_coherence": 0.9, "objects": [], "summary": "matches"})
                .to_string(),
            ),
        )
    });
    let generated = Pipeline::offline()
        .generate("a garage", 0, &options(), &mut NoProgress)
        .unwrap();
    let (w, h) = (24, 16);
    let pixels: Vec<u8> = (0..w * h * 3).map(|i| (i * 7 % 251) as u8).collect();
    let camera = Camera::look_at(
        Intrinsics::from_vertical_fov(w, h, 1.0),
        nalgebra::Point3::new(0.0, 1.5, 4.0),
        nalgebra::Point3::origin(),
        nalgebra::Vector3::y(),
    );
    let guidance = Guidance::new(
        camera,
        RgbImage::new(w, h, pixels.clone()).unwrap(),
        None,
        BTreeMap::new(),
    )
    .unwrap();
    let judge = VlmJudge::new(chat(&server), FlatRenderer).with_preview_size([32, 32]);
    let mut input = JudgeInput {
        plan: &generated.plan,
        scene: &generated.scene,
        meshes: &generated.meshes,
        guidance: Some(&guidance),
        cores_shared: false,
    };
    let verdict = judge.judge(&input).unwrap();
    assert!(verdict.accepted);
    let sent = server.requests()[0].json();
    let parts = sent["messages"][1]["content"].as_array().unwrap();
    let images: Vec<&str> = parts
        .iter()
        .filter_map(|p| p["image_url"]["url"].as_str())
        .collect();
    assert_eq!(images.len(), 3, "the guidance image and two previews");
    let first = image::load_from_memory(
        &scenethesis_models::ImageData::from_data_url(images[0], "sent")
            .unwrap()
            .bytes,
    )
    .unwrap()
    .to_rgb8();
    assert_eq!(
        first.as_raw(),
        &pixels,
        "the guidance image comes first, unchanged"
    );
    assert!(parts[0]["text"].as_str().unwrap().contains("guidance.png"));
    assert_eq!(
        verdict.review.as_ref().unwrap()["views"][0],
        "guidance.png",
        "{:?}",
        verdict.review
    );

    // Without guidance: only the previews.
    input.guidance = None;
    judge.judge(&input).unwrap();
    let sent = server.requests()[1].json();
    let parts = sent["messages"][1]["content"].as_array().unwrap();
    assert_eq!(
        parts.iter().filter(|p| p["image_url"].is_object()).count(),
        2
    );
}

#[test]
fn a_failing_vision_model_is_an_error_naming_endpoint_and_model() {
    let server = TestServer::scripted(vec![Reply::json(
        500,
        &json!({"error": {"message": "vision tower crashed"}}),
    )]);
    let judge = VlmJudge::new(chat(&server), FlatRenderer).with_preview_size([32, 32]);
    let err = Pipeline::offline()
        .with_judge(judge)
        .generate("a garage", 0, &options(), &mut NoProgress)
        .unwrap_err();
    assert!(matches!(err, PipelineError::Judge(_)), "{err}");
    let text = err.to_string();
    assert!(
        text.contains(&format!("{}/chat/completions", server.base_url)),
        "{text}"
    );
    assert!(text.contains("vision-model"), "{text}");
    assert!(text.contains("HTTP 500"), "{text}");
}

/// A review whose scores are all present, cut off inside its second blamed object.
fn cut_review(blamed: &str) -> String {
    // In the schema's order, as models write it (`json!` would sort the keys).
    let full = format!(
        r#"{{"category_accuracy": 0.9, "orientation_alignment": 0.2, "spatial_coherence": 0.8,
        "objects": [{{"id": "{blamed}", "reason": "it faces the wall"}},
        {{"id": "other_1", "reason": "too far from the desk"}}],
        "summary": "one object is turned the wrong way"}}"#
    );
    let cut = full.find("other_1").unwrap() + 12;
    full[..cut].to_owned()
}

#[test]
fn a_cut_off_review_keeps_its_scores_and_complete_objects() {
    use scenethesis_pipeline::{Judge, JudgeInput};
    let generated = Pipeline::offline()
        .generate("a garage", 0, &options(), &mut NoProgress)
        .unwrap();
    let input = JudgeInput {
        plan: &generated.plan,
        scene: &generated.scene,
        meshes: &generated.meshes,
        guidance: None,
        cores_shared: false,
    };
    let blamed = generated.scene.objects[0].id.clone();
    // Cut by max_tokens (`finish_reason: length`), and a stream cut off mid-answer.
    let mut length = openai_completion("vision-model", &cut_review(&blamed));
    length["choices"][0]["finish_reason"] = json!("length");
    let text = cut_review(&blamed);
    let pieces: Vec<String> = text
        .as_bytes()
        .chunks(16)
        .map(|c| String::from_utf8(c.to_vec()).unwrap())
        .collect();
    let refs: Vec<&str> = pieces.iter().map(String::as_str).collect();
    let events = support::openai_stream("vision-model", &refs);
    let streamed = Reply::events(events.clone(), Duration::ZERO).cut_after(events.len() - 3);
    for (reply, why) in [
        (Reply::json(200, &length), "cut off at max_tokens"),
        (streamed, "the connection closed after"),
    ] {
        let server = TestServer::scripted(vec![reply]);
        let judge = VlmJudge::new(chat(&server), FlatRenderer).with_preview_size([32, 32]);
        let verdict = judge.judge(&input).unwrap();
        assert_eq!(server.requests().len(), 1, "not re-asked");
        assert!(!verdict.accepted);
        let visual: Vec<_> = verdict
            .failures
            .iter()
            .filter(|f| f.kind == FailureKind::Visual)
            .collect();
        assert_eq!(visual.len(), 1, "{:?}", verdict.failures);
        assert_eq!(visual[0].objects, vec![blamed.clone()]);
        assert!(visual[0].detail.contains("it faces the wall"));
        let review = verdict.review.unwrap();
        assert_eq!(review["orientation_alignment"], 0.2);
        assert_eq!(review["summary"], "");
        let notes = review["notes"].to_string();
        assert!(notes.contains(why), "{notes}");
        assert!(notes.contains("salvaged"), "{notes}");
        assert!(notes.contains("no summary"), "{notes}");
    }
    // Cut before the scores are all there: an error naming the missing score.
    let mut early = openai_completion("vision-model", r#"{"category_accuracy": 0.9, "orient"#);
    early["choices"][0]["finish_reason"] = json!("length");
    let server = TestServer::scripted(vec![Reply::json(200, &early)]);
    let judge = VlmJudge::new(chat(&server), FlatRenderer).with_preview_size([32, 32]);
    let err = judge.judge(&input).unwrap_err().to_string();
    assert!(
        err.contains("has no `orientation_alignment` score"),
        "{err}"
    );
    assert!(err.contains("vision-model"), "{err}");
}
