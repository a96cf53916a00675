//! Place reading: the prompts of `tests/place_prompts.toml` (natural phrasings of at least 150
//! place types) plan the content their place holds and none of the clearly wrong categories,
//! and every place of the thesaurus plans its documented `core`.
//!
//! Plans only (no layout), with the offline `KnowledgePlanner` over the built-in library.
//! Prompts flagged `known_misread` are misread by the prompt reader (not the knowledge): they
//! are skipped, counted and printed, with a note when one of them passes.

mod common;

use std::collections::BTreeSet;

use serde::Deserialize;

use common::plan;
use scenethesis_agents::{Knowledge, Thesaurus};

/// The test data: `[[prompt]]` entries.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PromptsFile {
    prompt: Vec<PlacePrompt>,
}

/// One prompt and what its plan must and must not hold.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PlacePrompt {
    /// The prompt as a user would type it.
    text: String,
    /// Categories the plan must hold.
    expect: Vec<String>,
    /// Categories the plan must not hold.
    #[serde(default)]
    forbid: Vec<String>,
    /// The prompt reader (not the knowledge) misreads this prompt: skipped, counted, printed.
    #[serde(default)]
    known_misread: bool,
    /// Why it is misread.
    #[serde(default)]
    why: Option<String>,
}

fn prompts() -> Vec<PlacePrompt> {
    let file: PromptsFile = toml::from_str(include_str!("place_prompts.toml"))
        .unwrap_or_else(|e| panic!("tests/place_prompts.toml: {e}"));
    file.prompt
}

/// What is wrong with the plan of `p` at `seed`, if anything.
fn check(p: &PlacePrompt, seed: u64) -> Option<String> {
    let plan = plan(&p.text, seed);
    let held: BTreeSet<&str> = plan.objects.iter().map(|o| o.category.as_str()).collect();
    let missing: Vec<&str> = p
        .expect
        .iter()
        .map(String::as_str)
        .filter(|c| !held.contains(c))
        .collect();
    let wrong: Vec<&str> = p
        .forbid
        .iter()
        .map(String::as_str)
        .filter(|c| held.contains(c))
        .collect();
    (!missing.is_empty() || !wrong.is_empty()).then(|| {
        format!(
            "\"{}\" #{seed}: read as `{}`; missing {missing:?}; forbidden {wrong:?}",
            p.text, plan.scene_type
        )
    })
}

#[test]
fn at_least_155_place_types_and_150_prompts() {
    let k = Knowledge::builtin();
    let t = Thesaurus::builtin();
    let mut names: BTreeSet<&str> = k.archetypes.iter().map(|a| a.name.as_str()).collect();
    names.extend(t.places.iter().map(|p| p.name.as_str()));
    assert!(names.len() >= 155, "{} place types", names.len());
    let prompts = prompts();
    assert!(prompts.len() >= 150, "{} prompts", prompts.len());
    for p in &prompts {
        assert!(!p.expect.is_empty(), "\"{}\": expects nothing", p.text);
        for c in p.expect.iter().chain(&p.forbid) {
            assert!(
                k.prior(c).is_some(),
                "\"{}\": unknown category `{c}`",
                p.text
            );
        }
        assert!(
            !p.known_misread || p.why.as_deref().is_some_and(|w| !w.is_empty()),
            "\"{}\": a known misread says why",
            p.text
        );
    }
}

#[test]
fn place_prompts_plan_their_content_and_nothing_clearly_wrong() {
    let prompts = prompts();
    let mut failures = Vec::new();
    let mut skipped = Vec::new();
    for p in &prompts {
        let problems: Vec<String> = (0..2).filter_map(|seed| check(p, seed)).collect();
        if p.known_misread {
            let now = if problems.is_empty() {
                " (passes now: remove the flag)".to_owned()
            } else {
                format!(": {}", problems.join(" | "))
            };
            skipped.push(format!(
                "\"{}\" — {}{now}",
                p.text,
                p.why.as_deref().unwrap_or_default()
            ));
        } else {
            failures.extend(problems);
        }
    }
    println!(
        "{} prompts; {} known misreads skipped:\n{}",
        prompts.len(),
        skipped.len(),
        skipped.join("\n")
    );
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn every_place_plans_its_core() {
    let t = Thesaurus::builtin();
    let mut failures = Vec::new();
    for p in &t.places {
        assert!(
            !p.core.is_empty() && !p.source.trim().is_empty(),
            "{}",
            p.name
        );
        let prompt = format!("a {}", p.phrases[0].join(" "));
        for seed in 0..3 {
            let plan = plan(&prompt, seed);
            if plan.scene_type != p.name {
                failures.push(format!("{prompt} #{seed}: read as `{}`", plan.scene_type));
                continue;
            }
            let held: BTreeSet<&str> = plan.objects.iter().map(|o| o.category.as_str()).collect();
            let missing: Vec<&String> = p
                .core
                .iter()
                .filter(|c| !held.contains(c.as_str()))
                .collect();
            if !missing.is_empty() {
                failures.push(format!("{prompt} #{seed}: missing {missing:?}"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_place_core_outside_its_groups_is_named_in_the_error() {
    let k = Knowledge::builtin();
    let nouns = "[[noun]]\nwords = [\"x\"]\n";
    let base = "[[family]]\nname = \"shop\"\nroom = \"convenience_store\"\nwords = [\"shop\"]\n\
                [[place]]\nname = \"kiosk\"\nwords = [\"news kiosk\"]\nfamily = \"shop\"\n\
                gloss = \"a small shop\"\nlike = \"convenience_store\"\n";
    let err = Thesaurus::from_toml(
        &format!("{base}core = [\"bathtub\"]\nsource = \"ours\"\n"),
        nouns,
        k,
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("places.toml") && err.contains("kiosk") && err.contains("bathtub"),
        "{err}"
    );
    let err = Thesaurus::from_toml(&format!("{base}core = [\"store_shelf\"]\n"), nouns, k)
        .unwrap_err()
        .to_string();
    assert!(err.contains("source"), "{err}");
    let err = Thesaurus::from_toml(
        &format!(
            "{base}core = [\"store_shelf\"]\nsource = \"ours\"\n\
             [[place]]\nname = \"stand\"\nwords = [\"news kiosk\"]\nfamily = \"shop\"\n\
             gloss = \"a stand\"\nlike = \"kiosk\"\ncore = [\"store_shelf\"]\nsource = \"ours\"\n"
        ),
        nouns,
        k,
    )
    .unwrap_err()
    .to_string();
    assert!(err.contains("stand") && err.contains("news kiosk"), "{err}");
    assert!(Thesaurus::from_toml(
        &format!("{base}core = [\"store_shelf\", \"cash_register\"]\nsource = \"ours\"\n"),
        nouns,
        k
    )
    .is_ok());
}

#[test]
fn outdoor_places_plan_their_ground_and_rooms_none() {
    for (prompt, ground) in [
        ("a peaceful beach during sunset", Some("sand")),
        ("a beach bar with stools", Some("sand")),
        ("a city park with benches", Some("grass")),
        ("a backyard with a picnic table", Some("grass")),
        ("a zen garden", Some("gravel")),
        ("a town square", Some("paving")),
        ("a cozy living room", None),
    ] {
        let p = plan(prompt, 0);
        assert_eq!(p.ground.as_deref(), ground, "{prompt} ({})", p.scene_type);
    }
}

#[test]
fn a_ground_indoors_or_outside_the_library_is_named_in_the_error() {
    let k = Knowledge::builtin();
    let nouns = "[[noun]]\nwords = [\"x\"]\n";
    let place = |like: &str, ground: &str| {
        format!(
            "[[family]]\nname = \"outdoor\"\nroom = \"park\"\nwords = [\"park\"]\n\
             [[place]]\nname = \"lot\"\nwords = [\"empty lot\"]\nfamily = \"outdoor\"\n\
             gloss = \"an empty lot\"\nlike = \"{like}\"\nground = \"{ground}\"\n\
             core = [\"bench\"]\nsource = \"ours\"\n"
        )
    };
    let err = Thesaurus::from_toml(&place("park", "lava"), nouns, k)
        .unwrap_err()
        .to_string();
    assert!(err.contains("lot") && err.contains("lava"), "{err}");
    let err = Thesaurus::from_toml(&place("warehouse", "gravel"), nouns, k)
        .unwrap_err()
        .to_string();
    assert!(err.contains("lot") && err.contains("outdoor"), "{err}");
    let ok = Thesaurus::from_toml(&place("park", "gravel"), nouns, k).unwrap();
    let lot = ok.archetype("lot", k).unwrap();
    assert_eq!(lot.ground.as_deref(), Some("gravel"));
}
