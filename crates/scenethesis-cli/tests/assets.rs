//! `scenethesis assets list` as a user runs it.

use std::process::Command;

fn scenethesis(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_scenethesis"))
        .args(args)
        .output()
        .expect("run scenethesis")
}

#[test]
fn assets_list_prints_one_line_per_category() {
    let out = scenethesis(&["assets", "list"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let count = scenethesis_procedural::catalog::categories().count();
    // Header, one line per category, summary.
    assert_eq!(lines.len(), count + 2, "{text}");
    assert!(lines
        .last()
        .unwrap()
        .starts_with(&format!("{count} categories")));
    let bookshelf = lines
        .iter()
        .find(|l| l.starts_with("bookshelf "))
        .expect("bookshelf line");
    assert!(
        bookshelf.contains("floor") && bookshelf.contains("bookcase"),
        "{bookshelf}"
    );
    let pendant = lines
        .iter()
        .find(|l| l.starts_with("pendant_lamp "))
        .expect("pendant line");
    assert!(pendant.contains("ceiling"), "{pendant}");
}

#[test]
fn assets_list_json_matches_the_library() {
    let out = scenethesis(&["assets", "list", "--json", "--seed", "3"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let rows: Vec<serde_json::Value> = serde_json::from_slice(&out.stdout).expect("valid JSON");
    assert_eq!(
        rows.len(),
        scenethesis_procedural::catalog::categories().count()
    );
    let desk = rows.iter().find(|r| r["name"] == "desk").expect("desk row");
    let expected = scenethesis_procedural::catalog::generate(
        scenethesis_procedural::catalog::category("desk").unwrap(),
        3,
    );
    let size: Vec<f32> = desk["size"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap() as f32)
        .collect();
    assert_eq!(size, expected.info.size.to_vec());
    let surfaces: Vec<&str> = desk["support_surfaces"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert!(
        surfaces.contains(&"top") && surfaces.contains(&"under"),
        "{surfaces:?}"
    );
}
