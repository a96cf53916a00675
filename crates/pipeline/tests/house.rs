//! Houses end to end (issue #26): a dwelling prompt gets a furnished floor plan, every object
//! in its room, the robot reaching every room from the entrance; a user's floor plan is
//! furnished as given and a bad one is refused naming what is at fault.

use std::collections::BTreeSet;
use std::path::Path;

use scenethesis_pipeline::{
    GenerateOptions, GeneratedScene, HousePlanFile, NoProgress, Pipeline, PipelineError,
};
use scenethesis_scene_graph::{ParentRef, Scene, SceneObject, EXTERIOR};

fn options() -> GenerateOptions {
    GenerateOptions {
        max_replans: 2,
        previews: false,
        ..GenerateOptions::default()
    }
}

/// Every object names a room of the house and stands inside its floor outline; ids are unique
/// and start with the room's id.
fn check_objects_in_their_rooms(scene: &Scene) {
    let mut ids = BTreeSet::new();
    for o in &scene.objects {
        assert!(ids.insert(o.id.as_str()), "duplicate id {}", o.id);
        let room_id = o
            .room
            .as_deref()
            .unwrap_or_else(|| panic!("{} names no room", o.id));
        assert!(o.id.starts_with(&format!("{room_id}.")), "{}", o.id);
        let room = scene.architecture.room(room_id).expect("its room exists");
        let c = o.world_aabb().center();
        assert!(
            room.contains_xz(c.x, c.z),
            "{} at ({:.2}, {:.2}) is outside {room_id}",
            o.id,
            c.x,
            c.z
        );
    }
}

/// The floor kept free on each side of a door (m), as the house's rooms keep it.
const APPROACH: f64 = 0.6;

/// No floor or hung object of the house reaches (by more than a centimetre) into the 0.6 m
/// before any door, on either side, over the door's width and 0.1 m beyond each jamb.
fn check_doorways_clear(scene: &Scene) {
    let arch = &scene.architecture;
    for door in &arch.doors {
        let wall = arch.walls.iter().find(|w| w.id == door.wall).unwrap();
        let (dir, n) = (wall.direction(), wall.inward_normal());
        let centre = wall.start + dir * door.offset;
        for side in [1.0, -1.0] {
            let face = centre + n * (side * wall.thickness / 2.0);
            let half = door.width / 2.0 + 0.1 - 0.01;
            let a = face - dir * half + n * (side * 0.01);
            let b = face + dir * half + n * (side * (APPROACH - 0.01));
            let (lo, hi) = ([a.x.min(b.x), a.y.min(b.y)], [a.x.max(b.x), a.y.max(b.y)]);
            for o in scene
                .objects
                .iter()
                .filter(|o| matches!(o.parent, ParentRef::Ground | ParentRef::Wall(_)))
            {
                assert!(
                    !footprint_overlaps(o, lo, hi),
                    "{} stands in the approach of {} ({:?}–{:?})",
                    o.id,
                    door.id,
                    lo,
                    hi
                );
            }
        }
    }
}

/// Whether the turned floor rectangle of `o`'s box overlaps the axis-aligned `lo`–`hi`.
fn footprint_overlaps(o: &SceneObject, lo: [f64; 2], hi: [f64; 2]) -> bool {
    let (b, pose) = (&o.local_bounds, &o.pose);
    let (s, c) = pose.yaw.sin_cos();
    let at = |x: f64, z: f64| {
        let (x, z) = (x * pose.scale, z * pose.scale);
        [
            pose.translation.x + c * x + s * z,
            pose.translation.z - s * x + c * z,
        ]
    };
    let corners = [
        at(b.min.x, b.min.z),
        at(b.max.x, b.min.z),
        at(b.max.x, b.max.z),
        at(b.min.x, b.max.z),
    ];
    let zone = [lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]];
    let edge = |k: usize| {
        let (p, q) = (corners[k], corners[(k + 1) % 4]);
        [q[0] - p[0], q[1] - p[1]]
    };
    [[1.0, 0.0], [0.0, 1.0], edge(0), edge(1)]
        .iter()
        .all(|axis: &[f64; 2]| {
            let span = |ps: &[[f64; 2]; 4]| {
                ps.iter()
                    .map(|p| p[0] * axis[0] + p[1] * axis[1])
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                        (a.min(v), b.max(v))
                    })
            };
            let ((a0, a1), (b0, b1)) = (span(&corners), span(&zone));
            a1 > b0 && b1 > a0
        })
}

/// The house's report: Col-O and Col-arch 0 over the house, a line per room.
fn check_house_report(generated: &GeneratedScene) {
    let report = &generated.report;
    let house = report.house.as_ref().expect("a house report");
    let m = &report.verdict.metrics;
    assert_eq!(m.col_o, 0.0, "{:?}", m.colliding_pairs);
    assert_eq!(m.col_arch, 0.0, "{:?}", m.arch_penetrations);
    // Every door's approach is kept free: the robot drives from the entrance into (nearly)
    // all of every room's free floor.
    assert_eq!(house.rooms.len(), generated.scene.architecture.rooms.len());
    assert!(
        house.entrance_reach.is_some_and(|r| r >= 0.99),
        "entrance reach {:?}",
        house.entrance_reach
    );
    assert!(
        (0.0..=1.0).contains(&house.walk),
        "house Walk {}",
        house.walk
    );
    assert!(
        report.summary_line().contains("house:"),
        "{}",
        report.summary_line()
    );
}

#[test]
fn a_two_bedroom_apartment_is_furnished_room_by_room() {
    let pipeline = Pipeline::offline();
    let mut generated = pipeline
        .generate("a two-bedroom apartment", 3, &options(), &mut NoProgress)
        .expect("a house is generated");
    let arch = &generated.scene.architecture;
    let count = |t: &str| arch.rooms.iter().filter(|r| r.room_type == t).count();
    assert!(count("bedroom") >= 2, "{:?}", arch.rooms);
    assert!(
        count("kitchen") >= 1 && count("bathroom") >= 1,
        "{:?}",
        arch.rooms
    );
    let entrances: Vec<_> = arch
        .doors
        .iter()
        .filter(|d| {
            d.joins
                .as_ref()
                .is_some_and(|j| j.iter().any(|r| r == EXTERIOR))
        })
        .collect();
    assert_eq!(entrances.len(), 1);
    assert!(!arch.windows.is_empty());
    for window in &arch.windows {
        let wall = arch.walls.iter().find(|w| w.id == window.wall).unwrap();
        assert!(arch.doors.iter().all(|d| d.wall != wall.id
            || (d.offset - window.offset).abs() >= (d.width + window.width) / 2.0));
    }
    generated
        .scene
        .validate()
        .expect("the house scene is valid");
    check_objects_in_their_rooms(&generated.scene);
    check_doorways_clear(&generated.scene);
    check_house_report(&generated);
    // Every bed stands in a bedroom: "two bedrooms" is two rooms, not two beds a room.
    for o in generated
        .scene
        .objects
        .iter()
        .filter(|o| o.category == "bed")
    {
        assert!(
            o.room.as_deref().unwrap().starts_with("bedroom"),
            "{}",
            o.id
        );
    }
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("apartment");
    generated.write_outputs(&dir).unwrap();
    let back = Scene::read_json(&dir.join("scene.json")).unwrap();
    assert_eq!(back.architecture.rooms, generated.scene.architecture.rooms);
    assert_eq!(back.objects.len(), generated.scene.objects.len());
}

/// A living room and a kitchen-diner (3.5 × 3.9 m inside its walls: a kitchen run and a
/// table for two) joined by a passage, the entrance into the living room.
const PLAN: &str = r#"{
  "prompt": "a living room and a kitchen with a dining table",
  "rooms": [
    {"id": "living", "type": "living_room",
     "polygon": [[0, 0], [5, 0], [5, 4], [0, 4]]},
    {"id": "kitchen", "type": "kitchen",
     "polygon": [[5, 0], [8.6, 0], [8.6, 4], [5, 4]]}
  ],
  "doors": [
    {"id": "front", "rooms": ["living", "exterior"], "centre": [2, 4], "width": 0.9,
     "height": 2.1, "swing": {"into": "living", "hinge": "left"}},
    {"id": "pass", "rooms": ["living", "kitchen"], "centre": [5, 2], "width": 1.4,
     "height": 2.1, "kind": "passage"}
  ],
  "windows": [
    {"id": "w_living", "room": "living", "centre": [0, 2], "width": 1.4, "height": 1.4,
     "sill": 0.6},
    {"id": "w_kitchen", "room": "kitchen", "centre": [8.6, 2], "width": 1.0, "height": 1.0,
     "sill": 1.05}
  ]
}"#;

fn write(dir: &Path, text: &str) -> std::path::PathBuf {
    let path = dir.join("plan.json");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_users_floor_plan_is_furnished_as_given() {
    let tmp = tempfile::tempdir().unwrap();
    let file = HousePlanFile::from_file(&write(tmp.path(), PLAN))
        .unwrap()
        .expect("a house plan");
    let generated = Pipeline::offline()
        .generate_house(&file, 0, &options(), &mut NoProgress)
        .expect("the plan is furnished");
    let arch = &generated.scene.architecture;
    let ids: Vec<&str> = arch.rooms.iter().map(|r| r.id.as_str()).collect();
    assert_eq!(ids, ["living", "kitchen"]);
    let kitchen = arch.room("kitchen").unwrap();
    assert!(
        (kitchen.area() - 3.5 * 3.9).abs() < 1e-9,
        "{}",
        kitchen.area()
    );
    let front = arch.doors.iter().find(|d| d.id == "front").unwrap();
    assert!(front.leaf.is_some());
    let passage = arch.doors.iter().find(|d| d.id == "pass").unwrap();
    assert!(passage.leaf.is_none());
    assert_eq!(arch.windows.len(), 2);
    check_objects_in_their_rooms(&generated.scene);
    check_doorways_clear(&generated.scene);
    check_house_report(&generated);
    assert!(
        generated.report.verdict.accepted,
        "{:?}",
        generated.report.verdict.failures
    );
    assert!(generated
        .scene
        .objects
        .iter()
        .any(|o| o.room.as_deref() == Some("kitchen") && o.category.contains("table")));
}

#[test]
fn a_bad_floor_plan_is_refused_naming_what_is_at_fault() {
    let tmp = tempfile::tempdir().unwrap();
    let cases = [
        // The kitchen overlaps the living room.
        (
            PLAN.replace(
                "[[5, 0], [8.6, 0], [8.6, 4], [5, 4]]",
                "[[4, 0], [8.6, 0], [8.6, 4], [4, 4]]",
            ),
            "kitchen",
        ),
        // The passage is not on the wall the two rooms share.
        (
            PLAN.replace("\"centre\": [5, 2]", "\"centre\": [6, 4]"),
            "pass",
        ),
        // A window on the interior wall.
        (
            PLAN.replace("\"centre\": [8.6, 2]", "\"centre\": [5, 1]"),
            "w_kitchen",
        ),
        // Nothing joins the kitchen to the living room.
        (
            PLAN.replace(
                "\"rooms\": [\"living\", \"kitchen\"]",
                "\"rooms\": [\"living\", \"exterior\"]",
            )
            .replace("\"centre\": [5, 2]", "\"centre\": [3, 0]"),
            "kitchen",
        ),
    ];
    for (text, named) in cases {
        let err = HousePlanFile::from_file(&write(tmp.path(), &text)).unwrap_err();
        assert!(matches!(err, PipelineError::FloorPlan(_)), "{err}");
        assert!(
            err.to_string().contains(named),
            "`{err}` should name {named}"
        );
    }
    let single = r#"{"prompt": "a bedroom"}"#;
    assert!(HousePlanFile::from_file(&write(tmp.path(), single))
        .unwrap()
        .is_none());
}
