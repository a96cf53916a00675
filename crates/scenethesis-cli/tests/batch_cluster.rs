//! `scenethesis batch` on clusters: `--shard auto` from the scheduler's variables and
//! `--summarize`. No scene is generated (the shard given has no job), so these are quick.

mod common;

use std::path::Path;
use std::process::{Command, Output};

/// Every variable `--shard auto` reads, removed so that a test run inside a job array (a CI
/// runner on SLURM) sees only what the test sets.
const SCHEDULER_VARS: [&str; 10] = [
    "SLURM_ARRAY_TASK_ID",
    "SLURM_ARRAY_TASK_COUNT",
    "SLURM_ARRAY_TASK_MIN",
    "SLURM_ARRAY_TASK_MAX",
    "SLURM_ARRAY_TASK_STEP",
    "JOB_COMPLETION_INDEX",
    "AWS_BATCH_JOB_ARRAY_INDEX",
    "AWS_BATCH_JOB_ARRAY_SIZE",
    "BATCH_TASK_INDEX",
    "BATCH_TASK_COUNT",
];

/// `scenethesis batch prompts.txt --out b --no-preview ARGS` in `dir` with the scheduler
/// variables `env`.
fn batch(dir: &Path, env: &[(&str, &str)], args: &[&str]) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_scenethesis"));
    for var in SCHEDULER_VARS {
        cmd.env_remove(var);
    }
    cmd.env_remove("RUST_LOG")
        .envs(env.iter().copied())
        .current_dir(dir)
        .args(["batch", "prompts.txt", "--out", "b", "--no-preview"])
        .args(args)
        .output()
        .expect("run scenethesis")
}

#[test]
fn shard_auto_reads_the_scheduler_and_says_so() {
    let tmp = tempfile::tempdir().unwrap();
    let root = tmp.path();
    std::fs::write(root.join("prompts.txt"), "a garage\n").unwrap();

    // Outside any scheduler: one clear error, nothing written.
    let none = batch(root, &[], &["--shard", "auto"]);
    let text = common::text(&none);
    assert!(!none.status.success(), "{text}");
    for name in [
        "SLURM_ARRAY_TASK_ID",
        "JOB_COMPLETION_INDEX",
        "AWS_BATCH_JOB_ARRAY_INDEX",
        "BATCH_TASK_INDEX",
        "--shard I/N",
    ] {
        assert!(text.contains(name), "{name} in {text}");
    }
    assert!(!root.join("b").exists(), "{text}");

    // Kubernetes without the count.
    let k8s = [("JOB_COMPLETION_INDEX", "1")];
    let text = common::text(&batch(root, &k8s, &["--shard", "auto"]));
    assert!(text.contains("--shard auto/N"), "{text}");
    assert!(!root.join("b").exists(), "{text}");

    // SLURM --array=1-2, task 2: shard 1/2, which holds no job of a one-prompt batch.
    let slurm = [
        ("SLURM_ARRAY_TASK_ID", "2"),
        ("SLURM_ARRAY_TASK_MIN", "1"),
        ("SLURM_ARRAY_TASK_STEP", "1"),
        ("SLURM_ARRAY_TASK_COUNT", "2"),
    ];
    let run = batch(root, &slurm, &["--shard", "auto"]);
    let text = common::text(&run);
    assert!(run.status.success(), "{text}");
    assert!(
        text.contains("shard 1/2 from SLURM_ARRAY_TASK_ID (SLURM)"),
        "{text}"
    );
    assert!(text.contains("0/1 scenes finished"), "{text}");
    assert!(root.join("b/summary.shard-1-of-2.json").is_file());

    // A count that disagrees with the scheduler's.
    let text = common::text(&batch(root, &slurm, &["--shard", "auto/3"]));
    assert!(
        text.contains("auto/3") && text.contains("SLURM_ARRAY_TASK_COUNT=2"),
        "{text}"
    );
    // A fixed shard ignores the scheduler.
    let fixed = batch(root, &slurm, &["--shard", "1/4"]);
    let text = common::text(&fixed);
    assert!(fixed.status.success(), "{text}");
    assert!(!text.contains("from SLURM"), "{text}");
}

#[test]
fn summarize_writes_the_summary_and_runs_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let root = tmp.path();
    std::fs::write(root.join("prompts.txt"), "a garage\na warehouse\n").unwrap();
    let missing = batch(root, &[], &["--summarize"]);
    assert!(!missing.status.success());
    assert!(!root.join("b").exists());

    std::fs::create_dir(root.join("b")).unwrap();
    // --shard auto is not read when summarizing (no scheduler here).
    let run = batch(root, &[], &["--summarize", "--shard", "auto"]);
    let text = common::text(&run);
    assert!(run.status.success(), "{text}");
    assert!(text.contains("0/2 scenes finished"), "{text}");
    let names: Vec<String> = std::fs::read_dir(root.join("b"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["summary.json"], "{text}");
}
