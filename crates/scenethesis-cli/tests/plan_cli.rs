//! The plan seam as a user meets it: `scenethesis plan` writes `plan.json`, a hand edit, then
//! `scenethesis generate --plan` builds the edited plan; broken plans are refused naming the
//! field.

use std::path::Path;
use std::process::{Command, Output};

fn scenethesis_in(cwd: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_scenethesis"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("run scenethesis")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn read_json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn plan_then_edit_then_generate_from_the_plan() {
    let tmp = tempfile::tempdir().unwrap();
    let cwd = tmp.path();
    let out = scenethesis_in(
        cwd,
        &["plan", "a garage", "--out", "plan.json", "--seed", "2"],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.starts_with("wrote plan.json: garage"), "{stdout}");
    let mut plan = read_json(&cwd.join("plan.json"));
    assert_eq!(plan["prompt"], "a garage");

    // Never replaced without --force.
    let again = scenethesis_in(cwd, &["plan", "a garage", "--out", "plan.json"]);
    assert!(!again.status.success());
    assert!(
        stderr(&again).contains("already exists"),
        "{}",
        stderr(&again)
    );

    // A hand edit: drop every object that is neither the anchor nor on the ground, and rename
    // the prompt.
    let anchor = plan["anchor"].as_str().unwrap().to_owned();
    let objects = plan["objects"].as_array_mut().unwrap();
    objects.retain(|o| {
        o["parent"] == "ground" && o["relations"].as_array().unwrap().is_empty()
            || o["id"] == anchor.as_str()
    });
    let kept: Vec<String> = objects
        .iter()
        .map(|o| o["id"].as_str().unwrap().to_owned())
        .collect();
    plan["constraints"] = serde_json::json!([]);
    plan["prompt"] = "my own garage".into();
    std::fs::write(
        cwd.join("edited.json"),
        serde_json::to_string_pretty(&plan).unwrap(),
    )
    .unwrap();

    let out = scenethesis_in(
        cwd,
        &[
            "generate",
            "--plan",
            "edited.json",
            "--out",
            "scene",
            "--no-preview",
            "--seed",
            "2",
        ],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let scene = read_json(&cwd.join("scene/scene.json"));
    assert_eq!(scene["prompt"], "my own garage");
    let objects = scene["objects"].as_object().unwrap();
    assert!(!objects.is_empty());
    for id in objects.keys() {
        assert!(
            kept.iter().any(|k| k == id),
            "`{id}` was not in the edited plan"
        );
    }
    let report = read_json(&cwd.join("scene/report.json"));
    assert_eq!(report["planner"], "fixed");
    assert_eq!(report["guide"], "procedural");
}

#[test]
fn broken_plans_are_refused_naming_the_field() {
    let tmp = tempfile::tempdir().unwrap();
    let cwd = tmp.path();
    let out = scenethesis_in(cwd, &["plan", "a bedroom", "--out", "plan.json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let plan = read_json(&cwd.join("plan.json"));
    let generate = |name: &str, plan: &serde_json::Value| {
        std::fs::write(cwd.join(name), serde_json::to_string(plan).unwrap()).unwrap();
        scenethesis_in(
            cwd,
            &["generate", "--plan", name, "--out", "out", "--no-preview"],
        )
    };

    let mut duplicate = plan.clone();
    let first = duplicate["objects"][0]["id"].clone();
    duplicate["objects"][1]["id"] = first;
    let out = generate("duplicate.json", &duplicate);
    assert!(!out.status.success());
    assert!(
        stderr(&out).contains("objects[1].id: duplicate id"),
        "{}",
        stderr(&out)
    );

    let mut unknown = plan.clone();
    unknown["objects"][0]["category"] = "hoverboard".into();
    let out = generate("unknown.json", &unknown);
    assert!(!out.status.success());
    assert!(
        stderr(&out).contains("objects[0].category: unknown category `hoverboard`"),
        "{}",
        stderr(&out)
    );

    let mut relation = plan.clone();
    relation["objects"][0]["relations"] =
        serde_json::json!([{"kind": "beside", "target": "unicorn_0"}]);
    let out = generate("relation.json", &relation);
    assert!(!out.status.success());
    assert!(
        stderr(&out).contains("objects[0].relations[0].target: unknown object `unicorn_0`"),
        "{}",
        stderr(&out)
    );

    let mut typo = plan.clone();
    typo["room_size"] = "large".into();
    let out = generate("typo.json", &typo);
    assert!(!out.status.success());
    assert!(
        stderr(&out).contains("field `room_size`"),
        "{}",
        stderr(&out)
    );
    assert!(
        !cwd.join("out").exists(),
        "nothing is written for a broken plan"
    );

    let both = scenethesis_in(
        cwd,
        &["generate", "a bedroom", "--plan", "plan.json", "--out", "x"],
    );
    assert!(!both.status.success());
}
