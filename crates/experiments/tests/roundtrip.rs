//! The vision round trip on a generated scene: render its guidance, lift it back to boxes and
//! compare with the truth (Mesa's software renderer in CI).

use scenethesis_experiments::roundtrip::{roundtrip, Perturbation, RoundtripOptions};
use scenethesis_pipeline::{GenerateOptions, GeneratedScene, NoProgress, Pipeline};
use scenethesis_render::Renderer;

/// The offline scene of `prompt` (seed 0) and a renderer.
fn generated(prompt: &str) -> (GeneratedScene, Renderer) {
    generated_with_seed(prompt, 0)
}

/// The offline scene of `prompt` and `seed`, and a renderer.
fn generated_with_seed(prompt: &str, seed: u64) -> (GeneratedScene, Renderer) {
    let options = GenerateOptions {
        max_replans: 1,
        previews: false,
        ..GenerateOptions::default()
    };
    let generated = Pipeline::offline()
        .generate(prompt, seed, &options, &mut NoProgress)
        .expect("offline generation works");
    let renderer = Renderer::from_env().expect("a graphics adapter (Mesa llvmpipe in CI)");
    (generated, renderer)
}

#[test]
fn unperturbed_round_trip_recovers_the_scene() {
    let (generated, renderer) = generated("a bedroom with a bed, two nightstands and a wardrobe");
    let opts = RoundtripOptions {
        size: [400, 300],
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

/// The paper's ablation against ground truth, on a generated living room with the default
/// perturbation: the rows come in order, pose alignment brings the objects markedly closer to
/// where they truly are than the raw lift, and the full optimizer leaves no collision and nothing unstable.
#[test]
fn ablation_alignment_beats_the_raw_lift_and_the_full_optimizer_is_clean() {
    use scenethesis_experiments::ablation::{ablation, AblationStage};

    let (generated, renderer) =
        generated("a living room with a sofa, a coffee table, a tv stand and a bookshelf");
    let opts = RoundtripOptions {
        size: [480, 360],
        perturb: Perturbation::Default,
        ..RoundtripOptions::default()
    };
    let report = ablation(&renderer, &generated.scene, &generated.meshes, &opts).unwrap();
    let stages: Vec<AblationStage> = report.rows.iter().map(|r| r.stage).collect();
    assert_eq!(
        stages,
        [
            AblationStage::Raw,
            AblationStage::Alignment,
            AblationStage::Collision,
            AblationStage::Stability
        ]
    );
    let [raw, aligned, collision, full] = &report.rows[..] else {
        unreachable!()
    };
    // On the 14 benchmark prompts the cut is over 30 % (README); here about 35 %.
    assert!(
        aligned.translation_median_m < 0.8 * raw.translation_median_m,
        "alignment cut the raw lift's translation error by less than 20 %: {report:#?}"
    );
    assert!(aligned.yaw_median_deg < 5.0, "{report:#?}");
    assert_eq!(collision.col_o, 0.0, "{report:#?}");
    assert_eq!(full.col_o, 0.0, "{report:#?}");
    assert_eq!(full.inst_o, 0.0, "{report:#?}");
    assert!(
        full.translation_median_m < aligned.translation_median_m + 0.02,
        "the physical losses cost more than 2 cm: {report:#?}"
    );
    // The JSON the CLI prints has the documented keys.
    let json = serde_json::to_value(&report).unwrap();
    let row = &json["rows"][1];
    assert_eq!(row["stage"], "alignment");
    for key in [
        "translation_median_m",
        "yaw_median_deg",
        "scale_error_median",
        "iou_median",
        "col_o",
        "inst_o",
    ] {
        assert!(row[key].is_number(), "missing {key}: {json}");
    }
}

/// The ablation of `prompt` at `seed` with the default perturbation.
fn ablation_of(prompt: &str, seed: u64) -> scenethesis_experiments::ablation::AblationReport {
    let (generated, renderer) = generated_with_seed(prompt, seed);
    let opts = RoundtripOptions {
        size: [480, 360],
        perturb: Perturbation::Default,
        seed,
    };
    scenethesis_experiments::ablation::ablation(
        &renderer,
        &generated.scene,
        &generated.meshes,
        &opts,
    )
    .unwrap()
}

/// The alignment's cut of the raw lift's median translation error (negative: better), and
/// whether the final row keeps Col-O 0 and stays within 2 cm of the alignment row.
fn cut_and_final(report: &scenethesis_experiments::ablation::AblationReport) -> (f64, bool) {
    let [raw, aligned, _, full] = &report.rows[..] else {
        unreachable!()
    };
    let cut = aligned.translation_median_m / raw.translation_median_m.max(1e-9) - 1.0;
    let clean =
        full.col_o == 0.0 && full.translation_median_m <= aligned.translation_median_m + 0.02;
    (cut, clean)
}

/// Prompts outside the benchmark list, as a new user would try them.
const UNSEEN: [&str; 5] = [
    "a teenager's bedroom",
    "a farmhouse kitchen",
    "a home office with two desks",
    "a dining room with a long table and six chairs",
    "a small studio apartment",
];

/// On scenes nobody tuned for, the alignment never leaves a scene's median translation error
/// above its raw lift's (an object keeps its lift when that agrees with the image better), and
/// the final row keeps Col-O 0 within 2 cm of the alignment row.
#[test]
fn alignment_is_never_worse_than_the_raw_lift_on_unseen_prompts() {
    for (prompt, seed) in [(UNSEEN[0], 0), (UNSEEN[1], 1), (UNSEEN[0], 1)] {
        let report = ablation_of(prompt, seed);
        let (cut, clean) = cut_and_final(&report);
        assert!(
            cut <= 0.0,
            "`{prompt}` seed {seed}: alignment made the median error worse: {report:#?}"
        );
        assert!(
            clean,
            "`{prompt}` seed {seed}: final row collides or moved > 2 cm: {report:#?}"
        );
    }
}

/// The median cut over ten unseen scenes (five prompts, seeds 0 and 1), printed as JSON lines
/// (`cargo test -p scenethesis-experiments --test roundtrip -- --ignored --nocapture`): at
/// least 30 %, no scene worse than its raw lift, every final row without collisions and
/// within 2 cm of its alignment row.
#[test]
#[ignore = "ten generated scenes: minutes in the test profile"]
fn alignment_cuts_the_error_by_thirty_percent_over_ten_unseen_scenes() {
    let mut cuts = Vec::new();
    let mut moved = Vec::new();
    for seed in 0..2 {
        for prompt in UNSEEN {
            let report = ablation_of(prompt, seed);
            let (cut, clean) = cut_and_final(&report);
            println!(
                "{}",
                serde_json::json!({"prompt": prompt, "seed": seed, "cut": cut, "report": report})
            );
            assert!(
                cut <= 0.0,
                "`{prompt}` seed {seed}: alignment made it worse"
            );
            assert_eq!(report.rows[3].col_o, 0.0, "`{prompt}` seed {seed} collides");
            cuts.push(cut);
            if !clean {
                moved.push(format!("{prompt} seed {seed}"));
            }
        }
    }
    cuts.sort_by(f64::total_cmp);
    let median = (cuts[4] + cuts[5]) / 2.0;
    println!("median cut {median:.3}, cuts {cuts:?}; final row > 2 cm off: {moved:?}");
    assert!(median <= -0.3, "median cut {median:.3}: {cuts:?}");
    assert!(
        moved.is_empty(),
        "final row > 2 cm off its alignment row: {moved:?}"
    );
}
