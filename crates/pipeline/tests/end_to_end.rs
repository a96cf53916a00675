//! The offline pipeline end to end: generate, judge, write outputs atomically, export, batch.

use std::collections::BTreeMap;
use std::path::Path;

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use scenethesis_pipeline::batch::{self, BatchEvent, BatchOptions, JobStatus, Prompt, Shard};
use scenethesis_pipeline::{
    export_folder, CatalogSource, FailureKind, Format, GenerateOptions, GeneratedScene,
    GeometricJudge, Judge, JudgeInput, NoProgress, OutputDir, Pipeline, Stage,
};
use scenethesis_scene_graph::Scene;

fn options() -> GenerateOptions {
    GenerateOptions {
        max_replans: 2,
        previews: false,
        ..GenerateOptions::default()
    }
}

const PROMPT: &str = "a small office with a desk, a chair and a bookshelf with books";

#[test]
fn generate_writes_a_complete_deterministic_folder() {
    let pipeline = Pipeline::offline();
    let mut a = pipeline
        .generate(PROMPT, 7, &options(), &mut NoProgress)
        .expect("offline generation works");
    check_complete(&a);
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("office");
    check_written_folder(&mut a, &dir);
    let b = check_identical_rerun(&pipeline, &dir, tmp.path());
    check_exports(&dir, &a.scene);
    check_rewrites(&mut a, &dir, tmp.path());
    check_failed_write_keeps_the_folder(&mut a, &dir, tmp.path());
    check_judge_names_a_pushed_object(&b);
}

/// Every object has a mesh, every stage a timing, and the report counts agree.
fn check_complete(a: &GeneratedScene) {
    let scene = &a.scene;
    assert!(scene.objects.len() >= 3, "{} objects", scene.objects.len());
    assert!(scene.validate().is_ok(), "{:?}", scene.validate());
    for object in &scene.objects {
        assert!(
            a.meshes.contains_key(&object.id),
            "no mesh for {}",
            object.id
        );
    }
    let stages: Vec<Stage> = a.report.timings.iter().map(|t| t.stage).collect();
    for stage in [
        Stage::Plan,
        Stage::Retrieve,
        Stage::Guide,
        Stage::Optimize,
        Stage::Judge,
    ] {
        assert!(stages.contains(&stage), "no timing for {stage}");
    }
    check_stage_parts(a);
    assert_eq!(a.report.attempts, a.report.replans.len() + 1);
    assert_eq!(a.report.objects, scene.objects.len());
    assert_eq!(a.report.verdict.metrics.objects, scene.objects.len());
    assert_eq!(a.report.accepted, a.report.verdict.failures.is_empty());
}

/// The judge and the optimizer report their parts, each timed within its stage's total (parts
/// that run side by side may add up to more, but none is longer than the stage).
fn check_stage_parts(a: &GeneratedScene) {
    for (stage, names) in [
        (
            Stage::Judge,
            &[
                "meshes",
                "collisions",
                "stability",
                "relations",
                "walk-reach",
                "openings",
                "arrangement",
            ][..],
        ),
        (
            Stage::Optimize,
            &["prepare", "sweep", "final-pass", "check"][..],
        ),
    ] {
        let timing = a.report.timings.iter().find(|t| t.stage == stage).unwrap();
        let parts: Vec<&str> = timing.parts.iter().map(|p| p.part.as_str()).collect();
        assert_eq!(parts, names, "parts of {stage}");
        for part in &timing.parts {
            assert!(
                part.seconds >= 0.0 && part.seconds <= timing.seconds,
                "{stage} {}: {} s of {} s",
                part.part,
                part.seconds,
                timing.seconds
            );
        }
    }
}

/// The folder holds the three files; `scene.json` round-trips and names every object; the GLB
/// loads in the eval crate's reader with one node per object named by its id.
fn check_written_folder(a: &mut GeneratedScene, dir: &Path) {
    let scene = a.scene.clone();
    a.write_outputs(dir).unwrap();
    for file in ["scene.glb", "scene.json", "report.json"] {
        assert!(dir.join(file).is_file(), "{file} missing");
    }
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap();
    assert!(report["timings"]
        .as_array()
        .unwrap()
        .iter()
        .any(|t| t["stage"] == "export"));
    assert!(report["verdict"]["metrics"]["walk"].is_number());
    assert!(report["replans"].is_array());
    let saved = Scene::read_json(&dir.join("scene.json")).unwrap();
    assert_eq!(&saved.objects.len(), &scene.objects.len());
    let glb = scenethesis_eval::load_glb(&dir.join("scene.glb")).unwrap();
    let mut glb_ids: Vec<&str> = glb.objects.iter().map(|o| o.id.as_str()).collect();
    let mut ids: Vec<&str> = scene.objects.iter().map(|o| o.id.as_str()).collect();
    glb_ids.sort();
    ids.sort();
    assert_eq!(glb_ids, ids);
}

/// Same prompt and seed: byte-identical scene files. Returns the second run.
fn check_identical_rerun(pipeline: &Pipeline, dir: &Path, tmp: &Path) -> GeneratedScene {
    let mut b = pipeline
        .generate(PROMPT, 7, &options(), &mut NoProgress)
        .unwrap();
    let dir_b = tmp.join("office_again");
    b.write_outputs(&dir_b).unwrap();
    for file in ["scene.glb", "scene.json"] {
        assert_eq!(
            std::fs::read(dir.join(file)).unwrap(),
            std::fs::read(dir_b.join(file)).unwrap(),
            "{file} differs between identical runs"
        );
    }
    b
}

/// Exports of the saved folder, regenerating meshes from scene.json.
fn check_exports(dir: &Path, scene: &Scene) {
    let written = export_folder(dir, &Format::ALL, &CatalogSource).unwrap();
    assert_eq!(written.len(), 4);
    for path in &written {
        assert!(path.is_file());
    }
    let mjcf = std::fs::read_to_string(dir.join("scene.mjcf.xml")).unwrap();
    // One body per object, one per moving part, and a room door's body with its leaf's.
    let links: usize = scene.objects.iter().map(|o| o.joints.len()).sum();
    let leaves = scene
        .architecture
        .doors
        .iter()
        .filter(|d| d.leaf.is_some())
        .count();
    assert_eq!(
        mjcf.matches("<body ").count(),
        scene.objects.len() + links + 2 * leaves
    );
}

/// Re-writing replaces an earlier output atomically (the exports written into it are ours
/// too), and no staging folders are left beside it. A file scenethesis did not write makes
/// the folder foreign: refused without `force`, untouched; replaced with it.
fn check_rewrites(a: &mut GeneratedScene, dir: &Path, tmp: &Path) {
    a.write_outputs(dir).unwrap();
    assert!(
        !dir.join("scene.usda").exists(),
        "the old folder was replaced"
    );
    assert!(dir.join("scene.glb").is_file());
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    let err = a.write_outputs(dir).unwrap_err();
    assert!(err.to_string().contains("notes.txt"), "{err}");
    assert!(dir.join("notes.txt").is_file());
    a.write_to(&OutputDir::prepare(dir, true).unwrap()).unwrap();
    assert!(!dir.join("notes.txt").exists());
    assert!(dir.join("scene.glb").is_file());
    assert_eq!(
        staging_left(tmp),
        Vec::<String>::new(),
        "staging left behind"
    );
}

/// A failing write (an object without a mesh) leaves the previous folder intact.
fn check_failed_write_keeps_the_folder(a: &mut GeneratedScene, dir: &Path, tmp: &Path) {
    let before = std::fs::read(dir.join("scene.json")).unwrap();
    let victim = a.scene.objects[0].id.clone();
    a.meshes.remove(&victim);
    let err = a.write_outputs(dir).unwrap_err();
    assert!(err.to_string().contains(&victim), "{err}");
    assert_eq!(std::fs::read(dir.join("scene.json")).unwrap(), before);
    assert_eq!(staging_left(tmp), Vec::<String>::new());
}

/// Hidden (staging) entries of `dir`.
fn staging_left(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect()
}

/// The judge rejects a scene with an object pushed into another one, naming both.
fn check_judge_names_a_pushed_object(b: &GeneratedScene) {
    let mut broken = b.scene.clone();
    let floor_objects: Vec<String> = broken
        .objects
        .iter()
        .filter(|o| o.parent == scenethesis_scene_graph::ParentRef::Ground)
        .map(|o| o.id.clone())
        .collect();
    assert!(floor_objects.len() >= 2);
    let target = broken.object(&floor_objects[0]).unwrap().pose.translation;
    broken
        .object_mut(&floor_objects[1])
        .unwrap()
        .pose
        .translation = target;
    let verdict = GeometricJudge::default()
        .judge(&JudgeInput {
            plan: &b.plan,
            scene: &broken,
            meshes: &b.meshes,
            guidance: None,
            cores_shared: false,
        })
        .unwrap();
    assert!(!verdict.accepted);
    let collision = verdict
        .failures
        .iter()
        .find(|f| f.kind == FailureKind::Collision)
        .expect("a collision failure");
    assert!(collision.objects.contains(&floor_objects[1]));
    assert!(verdict.offenders().contains(&floor_objects[1]));
}

fn folders(dir: &Path) -> BTreeMap<String, bool> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| e.path().is_dir())
        .map(|e| {
            (
                e.file_name().to_string_lossy().into_owned(),
                e.path().join("report.json").is_file(),
            )
        })
        .collect()
}

#[test]
fn batch_shards_resume_and_summarize() {
    let prompts: Vec<Prompt> = vec!["a bathroom".into(), "a kids playroom with toys".into()];
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("batch");
    let pipeline = Pipeline::offline();
    let mut options = BatchOptions {
        jobs: 2,
        shard: "0/2".parse().unwrap(),
        seeds: 1,
        base_seed: 3,
        generate: GenerateOptions {
            max_replans: 1,
            ..options()
        },
        cancel: None,
    };
    let summary = batch::run_batch(&pipeline, &prompts, &out, &options, &|_| {}).unwrap();
    assert_eq!(summary.total_jobs, 2);
    assert_eq!(summary.finished, 1, "{summary:#?}");
    assert_eq!(folders(&out).len(), 1);
    assert!(out.join("summary.shard-0-of-2.json").is_file());

    options.shard = Shard { index: 1, count: 2 };
    let summary = batch::run_batch(&pipeline, &prompts, &out, &options, &|_| {}).unwrap();
    assert_eq!(summary.finished, 2);
    assert_eq!(summary.metrics.scenes, 2);
    assert!(summary.median_seconds.is_some());
    assert!(folders(&out).values().all(|done| *done));
    let on_disk: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(on_disk["finished"], 2);

    // Everything finished: a full run skips both jobs.
    options.shard = Shard::ALL;
    let summary = batch::run_batch(&pipeline, &prompts, &out, &options, &|_| {}).unwrap();
    assert!(summary.jobs.iter().all(|j| j.status == JobStatus::Skipped));
    assert_eq!(summary.finished, 2);

    // An edited prompt with the same folder name is not "finished": it is generated again.
    let edited: Vec<Prompt> = vec!["a bathroom!".into(), "a kids playroom with toys".into()];
    let summary = batch::run_batch(&pipeline, &edited, &out, &options, &|_| {}).unwrap();
    let statuses: Vec<JobStatus> = summary.jobs.iter().map(|j| j.status).collect();
    assert_eq!(statuses, [JobStatus::Generated, JobStatus::Skipped]);
    assert!(summary.jobs[0]
        .note
        .as_deref()
        .unwrap()
        .contains("a bathroom"));
    let report: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(out.join(&summary.jobs[0].job.folder).join("report.json"))
            .unwrap(),
    )
    .unwrap();
    assert_eq!(report["prompt"], "a bathroom!");

    // Other options: both jobs again.
    options.generate.max_replans = 0;
    let summary = batch::run_batch(&pipeline, &edited, &out, &options, &|_| {}).unwrap();
    assert!(summary
        .jobs
        .iter()
        .all(|j| j.status == JobStatus::Generated));
}

#[test]
fn batch_locks_jobs_and_writes_its_summary_when_interrupted() {
    let prompts: Vec<Prompt> = vec!["a garage".into(), "a warehouse".into()];
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("batch");
    std::fs::create_dir_all(&out).unwrap();
    let pipeline = Pipeline::offline();
    let jobs = batch::jobs(&prompts, 1, 0).unwrap();
    // A live batch (this very process) holds the first job's lock.
    std::fs::write(
        out.join(format!(".{}.lock", jobs[0].folder)),
        format!(
            "{}\n{}\n",
            std::process::id(),
            std::fs::read_to_string("/proc/sys/kernel/hostname")
                .unwrap_or_default()
                .trim()
        ),
    )
    .unwrap();
    // A dead one (pid 0 never runs a batch) held the second's: taken over.
    std::fs::write(
        out.join(format!(".{}.lock", jobs[1].folder)),
        format!(
            "0\n{}\n",
            std::fs::read_to_string("/proc/sys/kernel/hostname")
                .unwrap_or_default()
                .trim()
        ),
    )
    .unwrap();
    let cancel = Arc::new(AtomicBool::new(false));
    let options = BatchOptions {
        generate: options(),
        cancel: Some(cancel.clone()),
        ..BatchOptions::default()
    };
    // The interrupt arrives while the second job runs: nothing else starts.
    let summary = batch::run_batch(&pipeline, &prompts, &out, &options, &|event| {
        if let BatchEvent::Started(_) = event {
            cancel.store(true, Ordering::SeqCst);
        }
    })
    .unwrap();
    let statuses: Vec<JobStatus> = summary.jobs.iter().map(|j| j.status).collect();
    if cfg!(target_os = "linux") {
        assert_eq!(statuses, [JobStatus::Busy, JobStatus::Generated]);
        assert!(!out.join(format!(".{}.lock", jobs[1].folder)).exists());
    }
    assert!(out.join("summary.json").is_file());

    // Once interrupted, a run starts nothing but still writes the summary.
    std::fs::remove_file(out.join(format!(".{}.lock", jobs[0].folder))).unwrap();
    let summary = batch::run_batch(&pipeline, &prompts, &out, &options, &|_| {}).unwrap();
    assert_eq!(summary.jobs[0].status, JobStatus::Interrupted);
    assert_eq!(
        summary.jobs[1].status,
        JobStatus::Skipped,
        "finished stays finished"
    );
    assert!(out.join("summary.json").is_file());
}

#[test]
fn shard_and_prompt_parsing() {
    assert_eq!(
        "2/5".parse::<Shard>().unwrap(),
        Shard { index: 2, count: 5 }
    );
    for bad in ["5/5", "1", "a/b", "0/0"] {
        assert!(bad.parse::<Shard>().is_err(), "{bad}");
    }
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("prompts.txt");
    std::fs::write(
        &file,
        b"# benchmark\n\na garage\n\xff\xfe broken\n  a beach  \r\n".as_slice(),
    )
    .unwrap();
    let read = batch::read_prompts(&file).unwrap();
    let texts: Vec<&str> = read.prompts.iter().map(|p| p.text.as_str()).collect();
    assert_eq!(texts, ["a garage", "a beach"]);
    assert_eq!(read.prompts[1].line, 5);
    assert_eq!(read.skipped.len(), 1);
    assert_eq!(read.skipped[0].line, 4);
    let jobs = batch::jobs(&read.prompts, 2, 10).unwrap();
    assert_eq!(jobs.len(), 4);
    assert_eq!(jobs[3].folder, "002_a_beach_s11");
    assert_eq!(jobs[3].line, 5);
    std::fs::write(&file, "# nothing\n").unwrap();
    assert!(batch::read_prompts(&file).is_err());
}
