//! `--out` never loses a user's data: it refuses folders scenethesis did not write (unless
//! `--force`), never replaces a file, checks the path before the pipeline starts, and resolves
//! relative paths once (so `--out ../b` from inside `b` works).

use std::path::Path;
use std::process::{Command, Output};

fn scenethesis_in(cwd: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_scenethesis"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("run scenethesis")
}

fn generate_in(cwd: &Path, out: &str, extra: &[&str]) -> Output {
    let mut args = vec!["generate", "a garage", "--no-preview", "--out", out];
    args.extend_from_slice(extra);
    scenethesis_in(cwd, &args)
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A refusal happens before any pipeline stage runs and names the path.
fn assert_refused_early(out: &Output, needle: &str) {
    let text = stderr(out);
    assert!(!out.status.success(), "{text}");
    assert!(text.starts_with("error: "), "{text}");
    assert!(text.contains(needle), "{text}");
    assert!(
        !text.contains("plan"),
        "work started before the check: {text}"
    );
}

#[test]
fn foreign_folders_files_and_the_working_folder_are_never_replaced() {
    let tmp = tempfile::tempdir().unwrap();
    let root = tmp.path();

    // A folder holding someone's thesis.
    let docs = root.join("docs");
    std::fs::create_dir_all(docs.join("chapters")).unwrap();
    std::fs::write(docs.join("thesis.tex"), "my thesis").unwrap();
    let out = generate_in(root, "docs", &[]);
    assert_refused_early(&out, "did not write (e.g. \"chapters\")");
    assert!(stderr(&out).contains("--force"), "{}", stderr(&out));
    assert_eq!(
        std::fs::read_to_string(docs.join("thesis.tex")).unwrap(),
        "my thesis"
    );

    // A regular file, even with --force.
    std::fs::write(root.join("notes"), "keep me").unwrap();
    let out = generate_in(root, "notes", &["--force"]);
    assert_refused_early(&out, "never replaces a file");
    assert_eq!(
        std::fs::read_to_string(root.join("notes")).unwrap(),
        "keep me"
    );

    // The current folder given as an absolute path.
    let abs = docs.canonicalize().unwrap();
    let out = generate_in(&docs, abs.to_str().unwrap(), &[]);
    assert_refused_early(&out, "did not write");
    assert!(docs.join("thesis.tex").is_file());
    assert!(docs.join("chapters").is_dir());

    // A name too long for the temporary names of an atomic write.
    let long = "x".repeat(250);
    let out = generate_in(root, &long, &[]);
    assert_refused_early(&out, "bytes long");

    // Nothing was left behind by the refusals.
    let mut names: Vec<String> = std::fs::read_dir(root)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["docs", "notes"]);
}

#[test]
fn earlier_outputs_are_replaced_also_from_inside_them_and_force_replaces_foreign_folders() {
    let tmp = tempfile::tempdir().unwrap();
    let root = tmp.path();
    let b = root.join("b");

    let first = generate_in(root, "b", &[]);
    assert!(first.status.success(), "{}", stderr(&first));
    let scene = std::fs::read(b.join("scene.json")).unwrap();

    // From inside `b`, `--out ../b` replaces `b` itself (not a folder inside the old one).
    let again = generate_in(&b, "../b", &["--seed", "1"]);
    assert!(again.status.success(), "{}", stderr(&again));
    assert!(b.join("scene.json").is_file());
    assert_ne!(std::fs::read(b.join("scene.json")).unwrap(), scene);
    let names: Vec<String> = std::fs::read_dir(root)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["b"], "no staging or set-aside folders left");

    // A user's file inside makes it foreign; --force replaces it.
    std::fs::write(b.join("mine.txt"), "x").unwrap();
    let refused = generate_in(root, "b", &[]);
    assert_refused_early(&refused, "mine.txt");
    let forced = generate_in(root, "b", &["--force"]);
    assert!(forced.status.success(), "{}", stderr(&forced));
    assert!(!b.join("mine.txt").exists());
    assert_eq!(std::fs::read(b.join("scene.json")).unwrap(), scene);
}

#[test]
fn batch_reports_bad_lines_by_number_and_refuses_zero_seeds() {
    let tmp = tempfile::tempdir().unwrap();
    let root = tmp.path();
    std::fs::write(
        root.join("prompts.txt"),
        b"a garage\n\xc3\x28 bad\n".as_slice(),
    )
    .unwrap();
    let zero = scenethesis_in(
        root,
        &["batch", "prompts.txt", "--out", "b", "--seeds", "0"],
    );
    assert!(!zero.status.success());
    assert!(stderr(&zero).contains("--seeds"), "{}", stderr(&zero));
    assert!(
        !root.join("b").exists(),
        "nothing written for a bad argument"
    );

    let run = scenethesis_in(
        root,
        &["batch", "prompts.txt", "--out", "b", "--no-preview"],
    );
    let text = stderr(&run);
    assert!(run.status.success(), "{text}");
    assert!(
        text.contains("prompts.txt line 2: not valid UTF-8; skipped"),
        "{text}"
    );
    assert!(root.join("b/001_a_garage_s0/scene.json").is_file());
    assert!(root.join("b/summary.json").is_file());
}

#[test]
fn an_interrupted_batch_finishes_its_running_job_and_writes_the_summary() {
    use std::io::{BufRead, BufReader};
    let tmp = tempfile::tempdir().unwrap();
    let root = tmp.path();
    std::fs::write(
        root.join("prompts.txt"),
        "a garage\na warehouse\na gym room\n",
    )
    .unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_scenethesis"))
        .args(["batch", "prompts.txt", "--out", "b", "--no-preview"])
        .current_dir(root)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(child.stderr.take().unwrap()).lines();
    let mut seen = Vec::new();
    for line in lines.by_ref() {
        let line = line.unwrap();
        let first_done = line.starts_with("done ");
        seen.push(line);
        if first_done {
            break;
        }
    }
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    seen.extend(lines.map(|l| l.unwrap()));
    let status = child.wait().unwrap();
    let text = seen.join("\n");
    assert!(!status.success(), "{text}");
    assert!(text.contains("interrupted"), "{text}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(root.join("b/summary.json")).unwrap())
            .unwrap();
    let statuses: Vec<&str> = summary["jobs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| j["status"].as_str().unwrap())
        .collect();
    assert_eq!(statuses[0], "generated", "{summary}");
    assert!(statuses.contains(&"interrupted"), "{summary}");
    // Resuming finishes the rest and skips the first.
    let resumed = scenethesis_in(
        root,
        &["batch", "prompts.txt", "--out", "b", "--no-preview"],
    );
    let text = stderr(&resumed);
    assert!(resumed.status.success(), "{text}");
    assert!(text.contains("skip 001_a_garage_s0"), "{text}");
}
