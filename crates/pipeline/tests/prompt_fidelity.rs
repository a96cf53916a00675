//! The offline pipeline honours its prompts: every prompt naming an unknown kind of place gets
//! an accepted scene saying what was assumed, every object the prompt names is in the scene (or
//! the run says it is not), and the relations of detailed prompts hold.

use scenethesis_pipeline::{FailureKind, GenerateOptions, NoProgress, Pipeline};

fn options() -> GenerateOptions {
    GenerateOptions {
        previews: false,
        ..GenerateOptions::default()
    }
}

/// The prompts of `fixtures/prompts/unknown_places.txt`.
fn unknown_places() -> Vec<&'static str> {
    include_str!("../../../fixtures/prompts/unknown_places.txt")
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .collect()
}

#[test]
fn every_unknown_place_gets_an_accepted_scene_that_says_what_was_assumed() {
    let pipeline = Pipeline::offline();
    let prompts = unknown_places();
    assert!(prompts.len() >= 60);
    let mut rejected = Vec::new();
    for prompt in prompts {
        let generated = pipeline
            .generate(prompt, 0, &options(), &mut NoProgress)
            .unwrap_or_else(|e| panic!("{prompt}: {e}"));
        let report = &generated.report;
        assert!(!report.assumptions.is_empty(), "{prompt}");
        let line = report.summary_line();
        assert!(line.contains("assumed: "), "{line}");
        if !report.accepted || !report.prompt_check.complete() {
            rejected.push(format!("{prompt}: {line}"));
        }
    }
    assert!(rejected.is_empty(), "{}", rejected.join("\n"));
}

#[test]
fn a_requested_object_is_never_silently_lost() {
    let pipeline = Pipeline::offline();
    // The island is a kitchen counter standing free in the middle; three chairs are three.
    let g = pipeline
        .generate(
            "a kitchen with an island and three chairs",
            0,
            &options(),
            &mut NoProgress,
        )
        .unwrap();
    let check = &g.report.prompt_check;
    assert!(g.report.accepted, "{}", g.report.summary_line());
    assert_eq!((check.present, check.requested), (4, 4), "{check:?}");
    assert_eq!(
        g.scene
            .objects
            .iter()
            .filter(|o| o.category == "chair")
            .count(),
        3
    );
    assert!(g.report.summary_line().contains("requested 4/4 present"));

    // Nothing close in the library: listed, not silently dropped.
    let g = pipeline
        .generate(
            "a living room with a fireplace",
            0,
            &options(),
            &mut NoProgress,
        )
        .unwrap();
    assert_eq!(g.report.prompt_check.unavailable, ["fireplace"]);
    assert!(g.report.summary_line().contains("unavailable: fireplace"));

    // More than fits: the cap is reported, and a scene that cannot hold every requested
    // object is not accepted, with the reason.
    let g = pipeline
        .generate("500 chairs in a bathroom", 0, &options(), &mut NoProgress)
        .unwrap();
    let line = g.report.summary_line();
    assert!(line.contains("capped: ") && line.contains("500"), "{line}");
    let check = &g.report.prompt_check;
    assert_eq!(check.requested, 50);
    if check.present < check.requested {
        assert!(!g.report.accepted, "{line}");
        assert!(g
            .report
            .verdict
            .failures
            .iter()
            .any(|f| f.kind == FailureKind::MissingObject && f.detail.contains("chair")));
    }
}
