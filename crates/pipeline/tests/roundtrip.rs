//! The vision round trip on a generated scene: render its guidance, lift it back to boxes and
//! compare with the truth (Mesa's software renderer in CI).

#![cfg(feature = "render")]

use scenethesis_pipeline::roundtrip::{roundtrip, Perturbation, RoundtripOptions};
use scenethesis_pipeline::{GenerateOptions, NoProgress, Pipeline};
use scenethesis_render::Renderer;

#[test]
fn unperturbed_round_trip_recovers_the_scene() {
    let options = GenerateOptions {
        max_replans: 1,
        previews: false,
        ..GenerateOptions::default()
    };
    let generated = Pipeline::offline()
        .generate(
            "a bedroom with a bed, two nightstands and a wardrobe",
            0,
            &options,
            &mut NoProgress,
        )
        .expect("offline generation works");
    let renderer = Renderer::from_env().expect("a graphics adapter (Mesa llvmpipe in CI)");
    let opts = RoundtripOptions {
        size: [320, 240],
        ..RoundtripOptions::default()
    };
    let report = roundtrip(&renderer, &generated.scene, &generated.meshes, &opts).unwrap();
    // Never invented: every scene object is either compared or listed missing, once.
    assert_eq!(report.objects + report.missing.len(), report.scene_objects);
    assert!(
        report.objects * 3 >= report.scene_objects * 2,
        "{report:#?}"
    );
    assert!(report.translation_median_m < 0.03, "{report:#?}");
    assert!(report.yaw_median_deg < 5.0, "{report:#?}");
    assert!(report.parent_accuracy >= 0.9, "{report:#?}");
    assert!(report.iou_median > 0.6, "{report:#?}");

    // The perturbed round trip runs, is deterministic, and drops 10 % of the masks.
    let perturbed = RoundtripOptions {
        perturb: Perturbation::Default,
        ..opts
    };
    let a = roundtrip(&renderer, &generated.scene, &generated.meshes, &perturbed).unwrap();
    let b = roundtrip(&renderer, &generated.scene, &generated.meshes, &perturbed).unwrap();
    assert_eq!(a, b);
    assert!(a.missing.len() >= (report.scene_objects as f64 * 0.1).round() as usize);
}
