//! The hand-written scenes in `fixtures/scenes`: valid ones load and order; each invalid one
//! fails with the error that names its fault.

use std::path::PathBuf;

use scenethesis_scene_graph::{Scene, SceneIoError, ValidationError};

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/scenes")
        .join(name)
}

fn problems(name: &str) -> Vec<ValidationError> {
    match Scene::read_json(&fixture(name)) {
        Err(SceneIoError::Invalid { all, .. }) => all,
        other => panic!("{name}: expected a validation failure, got {other:?}"),
    }
}

#[test]
fn valid_fixtures_load_and_round_trip() {
    for name in ["valid_living_room.json", "valid_outdoor.json"] {
        let scene = Scene::read_json(&fixture(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        let order = scene.bfs_order().unwrap();
        assert_eq!(order[0].id, "sofa_0", "{name}: anchor first");
        let again = Scene::from_json_str(&scene.to_json_string()).unwrap();
        assert_eq!(again, scene);
    }
}

#[test]
fn world_aabb_is_written_per_object() {
    let scene = Scene::read_json(&fixture("valid_living_room.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&scene.to_json_string()).unwrap();
    let aabb = &json["objects"]["armchair_0"]["world_aabb"];
    // A quarter turn keeps the 0.8 m square footprint.
    let min_x = aabb["min"][0].as_f64().unwrap();
    assert!((min_x - -1.8).abs() < 1e-9, "{aabb}");
}

#[test]
fn unknown_parent_names_object_and_parent() {
    let p = problems("invalid_unknown_parent.json");
    assert!(
        p.contains(&ValidationError::UnknownParent {
            id: "mug_0".into(),
            parent: "side_table_9".into()
        }),
        "{p:?}"
    );
    assert!(p[0].to_string().contains("mug_0"));
}

#[test]
fn parent_cycle_is_reported() {
    let p = problems("invalid_parent_cycle.json");
    assert!(
        p.contains(&ValidationError::ParentCycle {
            ids: vec!["book_0".into(), "mug_0".into()]
        }),
        "{p:?}"
    );
}

#[test]
fn zero_scale_is_reported() {
    let p = problems("invalid_zero_scale.json");
    assert_eq!(
        p,
        vec![ValidationError::NonPositiveScale {
            id: "book_0".into(),
            scale: 0.0
        }]
    );
}

#[test]
fn missing_relation_target_is_reported() {
    let p = problems("invalid_relation_target.json");
    assert!(
        matches!(&p[..], [ValidationError::MissingRelationTarget { id, target, .. }] if id == "armchair_0" && target == "television_0"),
        "{p:?}"
    );
}

#[test]
fn unsupported_version_is_reported() {
    let p = problems("invalid_version.json");
    assert_eq!(
        p,
        vec![ValidationError::UnsupportedVersion {
            found: 99,
            expected: 1
        }]
    );
}

#[test]
fn duplicate_ids_are_reported() {
    let p = problems("invalid_duplicate_id.json");
    assert!(
        p.contains(&ValidationError::DuplicateId {
            id: "wall_1".into(),
            first: "wall",
            second: "object"
        }),
        "{p:?}"
    );
    let p = problems("invalid_duplicate_object_key.json");
    assert!(
        p.contains(&ValidationError::DuplicateId {
            id: "mug_0".into(),
            first: "object",
            second: "object"
        }),
        "{p:?}"
    );
}

#[test]
fn malformed_json_names_file_and_position() {
    for name in ["invalid_wrong_type.json", "invalid_non_finite.json"] {
        match Scene::read_json(&fixture(name)) {
            Err(err @ SceneIoError::Parse { .. }) => {
                assert!(err.to_string().contains(name), "{err}");
                let cause = std::error::Error::source(&err).unwrap().to_string();
                assert!(cause.contains("line"), "{cause}");
            }
            other => panic!("{name}: expected a parse error, got {other:?}"),
        }
    }
}

#[test]
fn non_finite_numbers_built_in_code_are_reported() {
    let mut scene = Scene::read_json(&fixture("valid_living_room.json")).unwrap();
    scene.object_mut("mug_0").unwrap().pose.translation.y = f64::NAN;
    let p = scene.validate().unwrap_err();
    assert_eq!(
        p,
        vec![ValidationError::NonFinite {
            owner: "mug_0".into(),
            field: "pose.translation"
        }]
    );
}

#[test]
fn atomic_writes_replace_the_file_and_leave_it_readable() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.json");
    scenethesis_scene_graph::write_file_atomic(&path, b"first").unwrap();
    scenethesis_scene_graph::write_file_atomic(&path, b"second").unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), b"second");
    // Only the file itself is left: no temporary files beside it.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(&path).unwrap().permissions().mode() & 0o777;
        assert_eq!(
            mode, 0o644,
            "written files must be readable by others, got {mode:o}"
        );
    }
}
