//! The offline pipeline end to end: generate, judge, write outputs atomically, export, batch.

use std::collections::BTreeMap;
use std::path::Path;

use scenethesis_pipeline::batch::{self, BatchOptions, JobStatus, Shard};
use scenethesis_pipeline::{
    export_folder, CatalogSource, FailureKind, Format, GenerateOptions, GeometricJudge, Judge,
    JudgeInput, NoProgress, OutputDir, Pipeline, Stage,
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
    let scene = a.scene.clone();
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
    assert_eq!(a.report.attempts, a.report.replans.len() + 1);
    assert_eq!(a.report.objects, scene.objects.len());
    assert_eq!(a.report.verdict.metrics.objects, scene.objects.len());
    assert_eq!(a.report.accepted, a.report.verdict.failures.is_empty());

    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("office");
    a.write_outputs(&dir).unwrap();
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

    // scene.json round-trips and names every object; the GLB loads in the eval crate's
    // reader with one node per object named by its id.
    let saved = Scene::read_json(&dir.join("scene.json")).unwrap();
    assert_eq!(&saved.objects.len(), &scene.objects.len());
    let glb = scenethesis_eval::load_glb(&dir.join("scene.glb")).unwrap();
    let mut glb_ids: Vec<&str> = glb.objects.iter().map(|o| o.id.as_str()).collect();
    let mut ids: Vec<&str> = scene.objects.iter().map(|o| o.id.as_str()).collect();
    glb_ids.sort();
    ids.sort();
    assert_eq!(glb_ids, ids);

    // Same prompt and seed: byte-identical scene files.
    let mut b = pipeline
        .generate(PROMPT, 7, &options(), &mut NoProgress)
        .unwrap();
    let dir_b = tmp.path().join("office_again");
    b.write_outputs(&dir_b).unwrap();
    for file in ["scene.glb", "scene.json"] {
        assert_eq!(
            std::fs::read(dir.join(file)).unwrap(),
            std::fs::read(dir_b.join(file)).unwrap(),
            "{file} differs between identical runs"
        );
    }

    // Exports of the saved folder, regenerating meshes from scene.json.
    let written = export_folder(&dir, &Format::ALL, &CatalogSource).unwrap();
    assert_eq!(written.len(), 4);
    for path in &written {
        assert!(path.is_file());
    }
    let mjcf = std::fs::read_to_string(dir.join("scene.mjcf.xml")).unwrap();
    assert_eq!(mjcf.matches("<body ").count(), scene.objects.len());

    // Re-writing replaces an earlier output atomically (the exports written into it above are
    // ours too), and no staging folders are left beside it.
    a.write_outputs(&dir).unwrap();
    assert!(
        !dir.join("scene.usda").exists(),
        "the old folder was replaced"
    );
    assert!(dir.join("scene.glb").is_file());
    // A file scenethesis did not write makes the folder foreign: refused without `force`,
    // untouched; replaced with it.
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    let err = a.write_outputs(&dir).unwrap_err();
    assert!(err.to_string().contains("notes.txt"), "{err}");
    assert!(dir.join("notes.txt").is_file());
    a.write_to(&OutputDir::prepare(&dir, true).unwrap())
        .unwrap();
    assert!(!dir.join("notes.txt").exists());
    assert!(dir.join("scene.glb").is_file());
    let leftovers: Vec<_> = std::fs::read_dir(tmp.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect();
    assert!(leftovers.is_empty(), "staging left behind: {leftovers:?}");

    // A failing write (an object without a mesh) leaves the previous folder intact.
    let before = std::fs::read(dir.join("scene.json")).unwrap();
    let victim = a.scene.objects[0].id.clone();
    a.meshes.remove(&victim);
    let err = a.write_outputs(&dir).unwrap_err();
    assert!(err.to_string().contains(&victim), "{err}");
    assert_eq!(std::fs::read(dir.join("scene.json")).unwrap(), before);
    let leftovers = std::fs::read_dir(tmp.path())
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .file_name()
                .to_string_lossy()
                .starts_with('.')
        })
        .count();
    assert_eq!(leftovers, 0);

    // The judge rejects a scene with an object pushed into another one, naming both.
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
    let prompts = vec![
        "a bathroom".to_owned(),
        "a kids playroom with toys".to_owned(),
    ];
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
    std::fs::write(&file, "# benchmark\n\na garage\n  a beach  \n").unwrap();
    let prompts = batch::read_prompts(&file).unwrap();
    assert_eq!(prompts, ["a garage", "a beach"]);
    let jobs = batch::jobs(&prompts, 2, 10);
    assert_eq!(jobs.len(), 4);
    assert_eq!(jobs[3].folder, "002_a_beach_s11");
    std::fs::write(&file, "# nothing\n").unwrap();
    assert!(batch::read_prompts(&file).is_err());
}
