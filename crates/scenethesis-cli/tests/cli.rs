//! The `scenethesis` binary as a user runs it.

use std::process::Command;

fn scenethesis(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_scenethesis"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .output()
        .expect("run scenethesis")
}

#[test]
fn help_lists_working_subcommands() {
    let out = scenethesis(&["--help"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("validate"), "{text}");
}

#[test]
fn validate_accepts_a_valid_scene_and_prints_the_order() {
    let out = scenethesis(&["validate", "fixtures/scenes/valid_living_room.json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("sofa_0 → coffee_table_0"), "{text}");
}

#[test]
fn validate_rejects_an_invalid_scene_with_a_clear_message() {
    let out = scenethesis(&["validate", "fixtures/scenes/invalid_unknown_parent.json"]);
    assert!(!out.status.success());
    let text = String::from_utf8_lossy(&out.stderr);
    assert!(text.starts_with("error: "), "{text}");
    assert!(
        text.contains("mug_0") && text.contains("side_table_9"),
        "{text}"
    );
}
