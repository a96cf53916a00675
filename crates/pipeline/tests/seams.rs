//! Every stage seam proven by a second implementation: the pipeline runs with a fixed planner
//! (a saved plan), a guide that is not the procedural one, a judge that accepts everything and
//! the null progress, and reports which ran.

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use scenethesis_agents::{AssetLookup, Guide, GuideError, GuidedLayout, Plan, ProceduralGuide};
use scenethesis_pipeline::{
    plan_json, write_plan, AcceptAll, FixedPlanner, GenerateOptions, Judge, JudgeInput, Pipeline,
    PipelineError,
};

const PROMPT: &str = "a small office with a desk, a chair and a bookshelf with books";

/// A guide of its own name that delegates the layout to the procedural guide and counts its
/// calls: a stand-in for any other guide.
struct CountingGuide {
    inner: ProceduralGuide,
    calls: AtomicUsize,
}

impl Guide for CountingGuide {
    fn name(&self) -> &str {
        "counting"
    }

    fn layout(
        &self,
        plan: &Plan,
        assets: &dyn AssetLookup,
        seed: u64,
    ) -> Result<GuidedLayout, GuideError> {
        self.calls.fetch_add(1, Ordering::SeqCst);
        let layout = self.inner.layout(plan, assets, seed)?;
        assert!(
            layout.guidance.is_none(),
            "the procedural guide reads no image"
        );
        Ok(layout)
    }
}

fn options() -> GenerateOptions {
    GenerateOptions {
        max_replans: 3,
        previews: false,
        ..GenerateOptions::default()
    }
}

#[test]
fn planner_guide_and_judge_swap_together() {
    let offline = Pipeline::offline();
    let plan = offline
        .plan(PROMPT, 5)
        .expect("the knowledge planner plans");
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("plan.json");
    write_plan(&path, &plan, false).unwrap();
    let fixed = FixedPlanner::from_file(&path).expect("a written plan reads back");
    assert_eq!(fixed.as_plan(), &plan);

    let guide = CountingGuide {
        inner: ProceduralGuide::default(),
        calls: AtomicUsize::new(0),
    };
    let pipeline = Pipeline::offline()
        .with_planner(fixed)
        .with_guide(guide)
        .with_judge(AcceptAll::new());
    // The prompt given to `generate` is ignored by the fixed planner.
    let scene = pipeline
        .generate("ignored", 5, &options(), &mut ())
        .expect("the swapped pipeline generates");
    let report = &scene.report;
    assert_eq!(report.planner, "fixed");
    assert_eq!(report.guide, "counting");
    assert_eq!(report.judge, "accept-all");
    assert!(report.accepted);
    assert_eq!(report.attempts, 1, "an accepting judge never re-plans");
    assert!(report.verdict.failures.is_empty());
    assert_eq!(report.verdict.metrics.objects, scene.scene.objects.len());
    assert_eq!(scene.plan, plan);
    for object in &scene.scene.objects {
        assert!(
            plan.object(&object.id).is_some(),
            "{} not planned",
            object.id
        );
    }

    // The default pipeline names its own stages.
    let default = offline
        .generate(PROMPT, 5, &options(), &mut ())
        .expect("offline generation");
    assert_eq!(default.report.planner, "knowledge");
    assert_eq!(default.report.guide, "procedural");
    assert_eq!(default.report.judge, "geometric");
    // Same plan, same seed, same first layout: the fixed plan reproduces the first attempt.
    if default.report.chosen_attempt == 0 {
        assert_eq!(default.scene.objects, scene.scene.objects);
    }
}

#[test]
fn the_accept_all_judge_accepts_what_the_geometric_judge_rejects() {
    let pipeline = Pipeline::offline();
    let mut generated = pipeline
        .generate(PROMPT, 1, &options(), &mut ())
        .expect("offline generation");
    // Push the second object into the first: a collision.
    let first = generated.scene.objects[0].pose.translation;
    generated.scene.objects[1].pose.translation = first;
    let input = JudgeInput {
        plan: &generated.plan,
        scene: &generated.scene,
        meshes: &generated.meshes,
        guidance: None,
        cores_shared: false,
    };
    let strict = scenethesis_pipeline::GeometricJudge::default()
        .judge(&input)
        .unwrap();
    assert!(!strict.accepted);
    let lenient = AcceptAll::new().judge(&input).unwrap();
    assert!(lenient.accepted);
    assert!(lenient.failures.is_empty());
    assert_eq!(
        lenient.metrics, strict.metrics,
        "both measure the same scene"
    );
}

#[test]
fn a_plan_with_an_unavailable_category_fails_in_the_plan_stage() {
    let mut plan = Pipeline::offline().plan(PROMPT, 0).unwrap();
    plan.objects[1].category = "hoverboard".into();
    let fixed = FixedPlanner::from_json(&plan_json(&plan), Path::new("edited.json")).unwrap();
    let err = Pipeline::offline()
        .with_planner(fixed)
        .generate("", 0, &options(), &mut ())
        .unwrap_err();
    assert!(matches!(err, PipelineError::Plan(_)), "{err}");
    let text = format!("{err}");
    assert!(text.contains("objects[1].category"), "{text}");
}

#[test]
fn write_plan_is_atomic_and_never_replaces_without_force() {
    let plan = Pipeline::offline().plan(PROMPT, 0).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("plan.json");
    write_plan(&path, &plan, false).unwrap();
    let before = std::fs::read_to_string(&path).unwrap();
    assert_eq!(before, plan_json(&plan));
    let err = write_plan(&path, &plan, false).unwrap_err();
    assert!(err.to_string().contains("already exists"), "{err}");
    let mut other = plan.clone();
    other.notes.push("edited".into());
    write_plan(&path, &other, true).unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), plan_json(&other));
    // No temporary file is left behind.
    let names: Vec<_> = std::fs::read_dir(tmp.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, vec![std::ffi::OsString::from("plan.json")]);
    let err = write_plan(tmp.path(), &plan, true).unwrap_err();
    assert!(err.to_string().contains("is a directory"), "{err}");
}

/// A judge that looks as long as the run's whole time limit and then rejects: the limit is
/// spent during the first attempt, whatever the machine's speed before it.
struct SlowRejecting {
    inner: AcceptAll,
    pause: std::time::Duration,
    calls: AtomicUsize,
}

impl Judge for SlowRejecting {
    fn name(&self) -> &str {
        "slow-rejecting"
    }

    fn judge(
        &self,
        input: &JudgeInput<'_>,
    ) -> Result<scenethesis_pipeline::Verdict, scenethesis_pipeline::JudgeError> {
        self.calls.fetch_add(1, Ordering::SeqCst);
        let mut verdict = self.inner.judge(input)?;
        std::thread::sleep(self.pause);
        verdict.accepted = false;
        Ok(verdict)
    }
}

#[test]
fn a_spent_time_limit_keeps_the_best_scene_so_far() {
    // The limit must outlast the first attempt's stages before the judge, whose time depends
    // on the machine and its load: a limit they overrun is doubled and the run repeated.
    let mut seconds = 3;
    let scene = loop {
        let limit = std::time::Duration::from_secs(seconds);
        let judge = SlowRejecting {
            inner: AcceptAll::new(),
            pause: limit,
            calls: AtomicUsize::new(0),
        };
        let options = GenerateOptions {
            time_limit: Some(limit),
            ..options()
        };
        match Pipeline::offline()
            .with_judge(judge)
            .generate(PROMPT, 0, &options, &mut ())
        {
            Ok(scene) => break scene,
            Err(PipelineError::OutOfTime { round: 0, .. }) if seconds < 48 => seconds *= 2,
            Err(e) => panic!("the first attempt's scene is kept: {e}"),
        }
    };
    assert!(!scene.report.accepted);
    let notes = scene.report.notes.join("\n");
    let expected = format!(
        "time limit of {seconds} s was reached before the retrieve stage of re-plan round 1"
    );
    assert!(notes.contains(&expected), "{notes}");
    assert!(!scene.scene.objects.is_empty());
}

#[test]
fn a_run_out_of_time_before_any_scene_fails_naming_the_stage() {
    let options = GenerateOptions {
        time_limit: Some(std::time::Duration::ZERO),
        ..options()
    };
    let err = Pipeline::offline()
        .generate(PROMPT, 0, &options, &mut ())
        .unwrap_err();
    assert!(
        matches!(
            err,
            PipelineError::OutOfTime {
                stage: scenethesis_pipeline::Stage::Plan,
                ..
            }
        ),
        "{err}"
    );
    assert!(err.to_string().contains("--time-limit"), "{err}");
}

/// A renderer of its own: every view is one flat colour made from a hash of the objects' ids
/// and poses, so two scenes laid out differently give different images. Counts its calls in
/// a counter the test keeps.
struct PoseColourRenderer {
    calls: std::sync::Arc<AtomicUsize>,
}

impl scenethesis_render_api::SceneRenderer for PoseColourRenderer {
    fn name(&self) -> String {
        "pose-colour".into()
    }

    fn render_views(
        &self,
        scene: &scenethesis_scene_graph::Scene,
        _meshes: &std::collections::BTreeMap<String, scenethesis_scene_graph::Mesh>,
        requests: &[scenethesis_render_api::ViewRequest],
    ) -> Result<Vec<scenethesis_render_api::ViewImage>, scenethesis_render_api::RendererError> {
        self.calls.fetch_add(1, Ordering::SeqCst);
        let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
        for object in &scene.objects {
            let t = object.pose.translation;
            for bits in [t.x, t.y, t.z, object.pose.yaw].map(f64::to_bits) {
                hash = (hash ^ bits).wrapping_mul(0x0100_0000_01b3);
            }
        }
        let [r, g, b, ..] = hash.to_le_bytes();
        Ok(requests
            .iter()
            .map(|request| {
                let [w, h] = request.size;
                let intrinsics = scenethesis_imagery::Intrinsics::from_vertical_fov(w, h, 1.0);
                scenethesis_render_api::ViewImage {
                    camera: scenethesis_imagery::Camera::look_at(
                        intrinsics,
                        nalgebra::Point3::new(0.0, 2.0, 4.0),
                        nalgebra::Point3::origin(),
                        nalgebra::Vector3::y(),
                    ),
                    color: image::RgbaImage::from_pixel(w, h, image::Rgba([r, g, b, 255])),
                }
            })
            .collect())
    }
}

/// A judge that rejects every attempt, each with one failure fewer than the one before
/// (blaming the scene's first object), so the last attempt is the one delivered.
struct FewerFailuresEachRound {
    calls: AtomicUsize,
}

impl Judge for FewerFailuresEachRound {
    fn name(&self) -> &str {
        "fewer-failures"
    }

    fn judge(
        &self,
        input: &JudgeInput<'_>,
    ) -> Result<scenethesis_pipeline::Verdict, scenethesis_pipeline::JudgeError> {
        let round = self.calls.fetch_add(1, Ordering::SeqCst);
        let mut verdict = AcceptAll::new().judge(input)?;
        let blamed = input.scene.objects[0].id.clone();
        verdict.failures = (round..3)
            .map(|_| scenethesis_pipeline::Failure {
                kind: scenethesis_pipeline::FailureKind::Collision,
                objects: vec![blamed.clone()],
                detail: format!("`{blamed}` is blamed by the test judge"),
            })
            .collect();
        verdict.accepted = false;
        Ok(verdict)
    }
}

#[test]
fn the_previews_drawn_beside_the_judge_are_the_delivered_attempts() {
    let calls = std::sync::Arc::new(AtomicUsize::new(0));
    let options = GenerateOptions {
        max_replans: 2,
        previews: true,
        ..GenerateOptions::default()
    };
    let scene = Pipeline::offline()
        .with_judge(FewerFailuresEachRound {
            calls: AtomicUsize::new(0),
        })
        .with_renderer(PoseColourRenderer {
            calls: calls.clone(),
        })
        .generate(PROMPT, 3, &options, &mut ())
        .expect("a scene, not accepted");
    assert!(!scene.report.accepted);
    assert_eq!(scene.report.attempts, 3);
    // Drawn beside the judges (an attempt not delivered lets its drawing run out unread).
    assert!(calls.load(Ordering::SeqCst) >= 1);
    let expected = scenethesis_render_api::render_previews(
        &PoseColourRenderer { calls },
        &scene.scene,
        &scene.meshes,
        options.preview_size,
    )
    .unwrap();
    assert_eq!(scene.previews, expected, "the delivered attempt's previews");
}
