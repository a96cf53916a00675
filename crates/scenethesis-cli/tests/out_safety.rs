//! `--out` never loses a user's data: it refuses folders scenethesis did not write (unless
//! `--force`), never replaces a file, checks the path before any work, and resolves relative
//! paths once (so `--out ../b` from inside `b` works).

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
