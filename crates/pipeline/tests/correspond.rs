//! The correspond stage inside the pipeline: a guide that hands over guidance (drawn by the CPU
//! rasterizer from its own layout) but starts every floor object off its place; with a matcher
//! configured the stage runs between guide and optimize and brings the objects back.

use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};

use nalgebra::{Point3, Vector3};
use scenethesis_agents::{AssetLookup, Guide, GuideError, GuidedLayout, Plan, ProceduralGuide};
use scenethesis_correspondence::{rasterized_guidance, GuidedSettings, ShapeMatcher};
use scenethesis_imagery::{Camera, Intrinsics};
use scenethesis_import::AssetResolver;
use scenethesis_pipeline::{GenerateOptions, Pipeline, Progress, Stage};
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
