//! The correspond stage inside the pipeline: a guide that hands over guidance (drawn by the CPU
//! rasterizer from its own layout) but starts every floor object off its place; with a matcher
//! configured the stage runs between guide and optimize and brings the objects back. And the
//! re-plan rounds of a guide that reads an image.

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use nalgebra::{Point3, Vector3};
use scenethesis_agents::{
    AssetLookup, DroppedObject, Guide, GuideError, GuidedLayout, Plan, ProceduralGuide,
};
use scenethesis_correspondence::{
    rasterized_guidance, GuidedSettings, Matcher, PixelMatch, RenderedView, ShapeMatcher,
    TargetRegion,
};
use scenethesis_imagery::{Camera, Intrinsics};
use scenethesis_import::AssetResolver;
use scenethesis_judge::{
    Failure, FailureKind, GeometricJudge, Judge, JudgeError, JudgeInput, Verdict,
};
use scenethesis_pipeline::{GenerateOptions, NoProgress, Pipeline, Progress, Stage};
use scenethesis_scene_graph::{ParentRef, Pose, Scene};

/// The procedural layout as guidance, with the floor objects' starting poses shifted by
/// (6, −5) cm and turned 8°. Remembers the unshifted layouts.
#[derive(Default)]
struct ShiftedGuide {
    truths: Arc<Mutex<Vec<Scene>>>,
}

impl Guide for ShiftedGuide {
    fn name(&self) -> &str {
        "shifted-procedural"
    }

    fn layout(
        &self,
        plan: &Plan,
        assets: &dyn AssetLookup,
        seed: u64,
    ) -> Result<GuidedLayout, GuideError> {
        let mut layout = ProceduralGuide::default().layout(plan, assets, seed)?;
        let mut resolver = AssetResolver::new();
        let meshes: BTreeMap<_, _> = layout
            .scene
            .objects
            .iter()
            .map(|o| (o.id.clone(), resolver.asset(&o.asset).unwrap().mesh))
            .collect();
        let floor = &layout.scene.architecture.floor;
        let camera = Camera::look_at(
            Intrinsics::from_vertical_fov(480, 360, 1.0),
            Point3::new(floor.min.x + 0.3, 1.7, floor.max.y - 0.3),
            Point3::new(
                (floor.min.x + floor.max.x) / 2.0,
                0.4,
                (floor.min.y + floor.max.y) / 2.0,
            ),
            Vector3::y(),
        );
        layout.guidance = Some(rasterized_guidance(&layout.scene, &meshes, &camera));
        self.truths.lock().unwrap().push(layout.scene.clone());
        for o in &mut layout.scene.objects {
            if o.parent == ParentRef::Ground && o.pose.translation.y < 0.05 {
                o.pose = Pose::new(
                    o.pose.scale,
                    o.pose.yaw + 8f64.to_radians(),
                    o.pose.translation + Vector3::new(0.06, 0.0, -0.05),
                );
            }
        }
        Ok(layout)
    }
}

#[derive(Default)]
struct Stages(Vec<Stage>);

impl Progress for Stages {
    fn stage_started(&mut self, stage: Stage, _round: usize) {
        self.0.push(stage);
    }
}

#[test]
fn correspond_runs_between_guide_and_optimize_and_undoes_the_shift() {
    let guide = ShiftedGuide::default();
    let truths = guide.truths.clone();
    let options = GenerateOptions {
        previews: false,
        ..GenerateOptions::default()
    };
    let prompt = "a bedroom with a bed, a wardrobe and a desk";
    let mut stages = Stages::default();
    let generated = Pipeline::offline()
        .with_guide(guide)
        .with_matcher(ShapeMatcher::default(), GuidedSettings::default())
        .generate(prompt, 0, &options, &mut stages)
        .unwrap();
    let guide_at = stages.0.iter().position(|s| *s == Stage::Guide).unwrap();
    assert_eq!(stages.0[guide_at + 1], Stage::Correspond, "{:?}", stages.0);
    assert_eq!(stages.0[guide_at + 2], Stage::Optimize, "{:?}", stages.0);
    // Without a matcher the stage does not run.
    let mut plain = Stages::default();
    Pipeline::offline()
        .generate(prompt, 0, &options, &mut plain)
        .unwrap();
    assert!(!plain.0.contains(&Stage::Correspond));
    // The floor objects end nearer their unshifted places than the 7.8 cm shift (judged
    // against the layout the chosen attempt came from: the one it is nearest to).
    let truths = truths.lock().unwrap();
    let median_error = |truth: &Scene| {
        let mut errors: Vec<f64> = generated
            .scene
            .objects
            .iter()
            .filter_map(|o| {
                let t = truth.object(&o.id)?;
                (t.parent == ParentRef::Ground && t.pose.translation.y < 0.05)
                    .then(|| (o.pose.translation - t.pose.translation).norm())
            })
            .collect();
        errors.sort_by(f64::total_cmp);
        errors
            .get(errors.len() / 2)
            .copied()
            .unwrap_or(f64::INFINITY)
    };
    let median = truths
        .iter()
        .map(median_error)
        .fold(f64::INFINITY, f64::min);
    // Without the stage the floor objects would stay ~7.8 cm off; with it they come back to
    // within 5 cm (median; 4.4 cm measured on this bedroom since its archetype draws optional
    // extras per seed, which crowd the floor the optimizer then resolves).
    assert!(median < 0.05, "median floor-object error {median} m");
}

/// Like a guide that reads a photo: the first round's layout of [`ShiftedGuide`] fixes every
/// object's place for good; later rounds get it again, less the objects the plan dropped.
#[derive(Default)]
struct SameEveryRound {
    shifted: ShiftedGuide,
    first: Mutex<Option<GuidedLayout>>,
}

impl Guide for SameEveryRound {
    fn name(&self) -> &str {
        "same-every-round"
    }

    fn layout(
        &self,
        plan: &Plan,
        assets: &dyn AssetLookup,
        seed: u64,
    ) -> Result<GuidedLayout, GuideError> {
        let mut first = self.first.lock().unwrap();
        if first.is_none() {
            *first = Some(self.shifted.layout(plan, assets, seed)?);
        }
        let mut layout = first.clone().unwrap();
        let planned = |id: &str| plan.objects.iter().any(|o| o.id == id);
        layout.scene.objects.retain(|o| planned(&o.id));
        if let Some(g) = &mut layout.guidance {
            g.masks.retain(|id, _| planned(id));
        }
        Ok(layout)
    }
}

/// The shape matcher, counting the views it matches.
#[derive(Default, Clone)]
struct CountingMatcher(Arc<AtomicUsize>);

impl Matcher for CountingMatcher {
    fn name(&self) -> &str {
        "counting-shape"
    }

    fn match_view(&self, view: &RenderedView, target: &TargetRegion<'_>) -> Vec<PixelMatch> {
        self.0.fetch_add(1, Ordering::Relaxed);
        ShapeMatcher::default().match_view(view, target)
    }
}

/// The geometric judge, but every scene it sees is refused for a made-up wobble of its
/// first object (so the pipeline re-plans until its rounds run out).
struct RefusingJudge(GeometricJudge);

impl Judge for RefusingJudge {
    fn name(&self) -> &str {
        "refusing"
    }

    fn judge(&self, input: &JudgeInput<'_>) -> Result<Verdict, JudgeError> {
        let mut verdict = self.0.judge(input)?;
        verdict.accepted = false;
        verdict.failures.push(Failure {
            kind: FailureKind::Unstable,
            objects: vec![input.scene.objects[0].id.clone()],
            detail: "refused by the test".into(),
        });
        Ok(verdict)
    }
}

#[test]
fn a_replan_round_reuses_the_alignments_whose_inputs_are_unchanged() {
    let prompt = "a bedroom with a bed, a wardrobe and a desk";
    let matched_views = |max_replans: usize| {
        let matcher = CountingMatcher::default();
        let options = GenerateOptions {
            previews: false,
            max_replans,
            ..GenerateOptions::default()
        };
        let generated = Pipeline::offline()
            .with_guide(SameEveryRound::default())
            .with_judge(RefusingJudge(GeometricJudge::default()))
            .with_matcher(matcher.clone(), GuidedSettings::default())
            .generate(prompt, 0, &options, &mut NoProgress)
            .unwrap();
        assert_eq!(generated.report.replans.len(), max_replans);
        matcher.0.load(Ordering::Relaxed)
    };
    let one_round = matched_views(0);
    let three_rounds = matched_views(2);
    assert!(one_round > 0);
    // Each re-plan moves the blamed object; the others start where they started, in front
    // of the same guidance, and keep their alignment.
    assert!(
        three_rounds < one_round * 3 / 2,
        "{one_round} views matched in one round, {three_rounds} in three"
    );
}

/// [`ShiftedGuide`] whose image does not show the desk (nor what rests on it): it leaves them
/// out as a guide reading a photo would.
#[derive(Default)]
struct DeskUnseen {
    shifted: ShiftedGuide,
}

impl Guide for DeskUnseen {
    fn name(&self) -> &str {
        "desk-unseen"
    }

    fn layout(
        &self,
        plan: &Plan,
        assets: &dyn AssetLookup,
        seed: u64,
    ) -> Result<GuidedLayout, GuideError> {
        let mut layout = self.shifted.layout(plan, assets, seed)?;
        let unseen: Vec<String> = layout
            .scene
            .objects
            .iter()
            .filter(|o| {
                o.category == "desk" || o.parent.object_id().is_some_and(|p| p.starts_with("desk"))
            })
            .map(|o| o.id.clone())
            .collect();
        layout.scene.objects.retain(|o| !unseen.contains(&o.id));
        if let Some(g) = &mut layout.guidance {
            g.masks.retain(|id, _| !unseen.contains(id));
        }
        layout
            .dropped
            .extend(unseen.into_iter().map(|id| DroppedObject {
                id,
                reason: "not found in the guidance image (no mask)".into(),
            }));
        Ok(layout)
    }
}

#[test]
fn an_asked_for_object_the_image_does_not_show_costs_no_replan() {
    let guide = DeskUnseen::default();
    let options = GenerateOptions {
        previews: false,
        max_replans: 2,
        ..GenerateOptions::default()
    };
    let prompt = "a bedroom with a bed, a wardrobe and a desk";
    let pipeline = Pipeline::offline()
        .with_guide(guide)
        .with_matcher(ShapeMatcher::default(), GuidedSettings::default());
    let generated = pipeline
        .generate(prompt, 0, &options, &mut NoProgress)
        .unwrap();
    let report = &generated.report;
    assert!(!report.accepted);
    assert!(report.replans.is_empty(), "{:?}", report.replans);
    assert!(
        report
            .notes
            .iter()
            .any(|n| n.starts_with("no re-plan") && n.contains("desk_0")),
        "{:?}",
        report.notes
    );
}
