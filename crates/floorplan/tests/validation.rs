//! Each validation error, from a hand-written plan with one fault.

use scenethesis_floorplan::{check_privacy, validate, FloorPlan, Knowledge, PlanError};

/// A hallway along the west side with a living room and a bedroom off it.
const GOOD: &str = r#"{
  "rooms": [
    {"id": "hall", "type": "hallway", "polygon": [[0, 0], [2, 0], [2, 6], [0, 6]]},
    {"id": "living", "type": "living_room", "polygon": [[2, 0], [6, 0], [6, 3], [2, 3]]},
    {"id": "bed", "type": "bedroom", "polygon": [[2, 3], [6, 3], [6, 6], [2, 6]]}
  ],
  "doors": [
    {"id": "door_in", "rooms": ["hall", "exterior"], "centre": [0, 1], "width": 0.9, "height": 2.1,
     "swing": {"into": "hall", "hinge": "left"}},
    {"id": "door_living", "rooms": ["hall", "living"], "centre": [2, 1.5], "width": 0.9, "height": 2.1},
    {"id": "door_bed", "rooms": ["hall", "bed"], "centre": [2, 4.5], "width": 0.9, "height": 2.1,
     "kind": "single", "swing": {"into": "bed", "hinge": "right"}}
  ],
  "windows": [
    {"id": "w_living", "room": "living", "centre": [6, 1.5], "width": 1.2, "height": 1.4, "sill": 0.6},
    {"id": "w_bed", "room": "bed", "centre": [4, 6], "width": 1.2, "height": 1.3, "sill": 0.8}
  ]
}"#;

fn good() -> FloorPlan {
    serde_json::from_str(GOOD).unwrap()
}

fn check(plan: &FloorPlan) -> Result<(), PlanError> {
    validate(plan, Knowledge::builtin()).map(|_| ())
}

fn fails(plan: &FloorPlan, expected: &[&str]) -> PlanError {
    let err = check(plan).expect_err("the plan should be rejected");
    let text = err.to_string();
    for needle in expected {
        assert!(text.contains(needle), "`{text}` lacks `{needle}`");
    }
    err
}

fn polygon(v: &[(f64, f64)]) -> Vec<nalgebra::Point2<f64>> {
    v.iter()
        .map(|&(x, z)| nalgebra::Point2::new(x, z))
        .collect()
}

#[test]
fn the_good_plan_passes_and_its_walls_carry_the_openings() {
    let walls = validate(&good(), Knowledge::builtin()).unwrap();
    let interior: Vec<_> = walls.iter().filter(|w| !w.is_exterior()).collect();
    assert_eq!(interior.len(), 3, "{walls:#?}");
    let holder = |id: &str| {
        walls
            .iter()
            .find(|w| w.openings.iter().any(|o| o == id))
            .unwrap()
    };
    assert!(holder("door_bed").joins("hall", "bed"));
    assert!(holder("w_bed").is_exterior());
    check_privacy(&good(), Knowledge::builtin()).unwrap();
}

#[test]
fn an_l_shaped_room_is_supported() {
    let mut plan = good();
    // The bedroom takes the hall's south end: the hall shrinks, the bedroom becomes an L.
    plan.rooms[0].polygon = polygon(&[(0.0, 0.0), (2.0, 0.0), (2.0, 5.0), (0.0, 5.0)]);
    plan.rooms[2].polygon = polygon(&[
        (2.0, 3.0),
        (6.0, 3.0),
        (6.0, 6.0),
        (0.0, 6.0),
        (0.0, 5.0),
        (2.0, 5.0),
    ]);
    check(&plan).unwrap();
}

#[test]
fn overlapping_rooms() {
    let mut plan = good();
    plan.rooms[2].polygon = polygon(&[(2.0, 2.5), (6.0, 2.5), (6.0, 6.0), (2.0, 6.0)]);
    assert!(matches!(
        fails(&plan, &["`living`", "`bed`", "overlap"]),
        PlanError::Overlap { .. }
    ));
}

#[test]
fn polygons_that_are_not_simple_and_axis_aligned() {
    let mut plan = good();
    plan.rooms[2].polygon = polygon(&[(2.0, 3.0), (6.0, 3.0), (6.0, 6.0), (2.5, 6.0)]);
    fails(
        &plan,
        &[
            "room `bed`",
            "not parallel",
            "supported are simple axis-aligned polygons",
        ],
    );
    plan.rooms[2].polygon = polygon(&[(2.0, 3.0), (6.0, 3.0), (6.0, 6.0)]);
    fails(&plan, &["room `bed`", "3 corners"]);
    plan.rooms[2].polygon = polygon(&[
        (2.0, 3.0),
        (6.0, 3.0),
        (6.0, 6.0),
        (4.0, 6.0),
        (4.0, 2.0),
        (3.0, 2.0),
        (3.0, 6.0),
        (2.0, 6.0),
    ]);
    fails(&plan, &["room `bed`", "cross"]);
}

#[test]
fn a_door_not_on_a_wall_its_rooms_share() {
    let mut plan = good();
    plan.doors[2].centre = nalgebra::Point2::new(4.0, 3.0);
    let err = fails(&plan, &["door `door_bed`", "`hall` and `bed`"]);
    assert!(matches!(err, PlanError::DoorNotOnSharedWall { .. }));
    let mut plan = good();
    plan.doors[2].width = 3.5;
    fails(&plan, &["door `door_bed`", "not on a wall shared"]);
}

#[test]
fn an_entrance_not_on_an_exterior_wall() {
    let mut plan = good();
    plan.doors[0].centre = nalgebra::Point2::new(2.0, 1.0);
    let err = fails(&plan, &["door `door_in`", "exterior wall of `hall`"]);
    assert!(matches!(err, PlanError::DoorNotOnExteriorWall { .. }));
}

#[test]
fn a_room_nobody_can_reach() {
    let mut plan = good();
    plan.doors.remove(2);
    assert_eq!(
        fails(&plan, &["room `bed`"]),
        PlanError::Unreachable { room: "bed".into() }
    );
}

#[test]
fn no_entrance() {
    let mut plan = good();
    plan.doors.remove(0);
    assert_eq!(fails(&plan, &["no entrance"]), PlanError::NoEntrance);
}

#[test]
fn a_window_on_an_interior_wall() {
    let mut plan = good();
    plan.windows[1].centre = nalgebra::Point2::new(4.0, 3.0);
    let err = fails(&plan, &["window `w_bed`", "interior wall", "`living`"]);
    assert!(matches!(err, PlanError::WindowOnInteriorWall { .. }));
}

#[test]
fn a_window_not_on_its_rooms_walls() {
    let mut plan = good();
    plan.windows[1].centre = nalgebra::Point2::new(6.0, 1.5);
    fails(&plan, &["window `w_bed`", "not on a wall of room `bed`"]);
    plan.windows[1].room = "attic".into();
    fails(&plan, &["window `w_bed`", "unknown room `attic`"]);
}

#[test]
fn a_window_overlapping_a_door() {
    let mut plan = good();
    plan.windows[0] = scenethesis_floorplan::Window {
        id: "w_hall".into(),
        room: "hall".into(),
        centre: nalgebra::Point2::new(0.0, 1.3),
        width: 0.8,
        height: 1.0,
        sill: 1.0,
    };
    assert_eq!(
        fails(&plan, &["window `w_hall`", "door `door_in`"]),
        PlanError::WindowOverlapsDoor {
            window: "w_hall".into(),
            door: "door_in".into()
        }
    );
}

#[test]
fn an_unknown_room_type() {
    let mut plan = good();
    plan.rooms[2].room_type = "dungeon".into();
    fails(&plan, &["room `bed`", "unknown type `dungeon`", "bedroom"]);
}

#[test]
fn ids_doors_and_sizes() {
    let mut plan = good();
    plan.windows[1].id = "living".into();
    fails(&plan, &["id `living` is used twice"]);
    let mut plan = good();
    plan.rooms[2].id = "exterior".into();
    fails(&plan, &["reserved"]);
    let mut plan = good();
    plan.doors[2].rooms[1] = "garage".into();
    fails(&plan, &["door `door_bed`", "no room `garage`"]);
    let mut plan = good();
    plan.doors[2].rooms[1] = "hall".into();
    fails(&plan, &["door `door_bed`", "two different sides"]);
    let mut plan = good();
    plan.doors[1].width = -1.0;
    fails(&plan, &["door `door_living`", "width"]);
    let mut plan = good();
    plan.windows[0].sill = f64::NAN;
    fails(&plan, &["window `w_living`", "sill"]);
    let mut plan = good();
    plan.doors[2].swing.as_mut().unwrap().into = "living".into();
    fails(&plan, &["door `door_bed` swings into `living`"]);
    let mut plan = good();
    plan.doors.push(scenethesis_floorplan::Door {
        id: "door_twin".into(),
        ..plan.doors[1].clone()
    });
    fails(&plan, &["doors `door_living` and `door_twin` overlap"]);
    assert_eq!(
        check(&FloorPlan {
            rooms: vec![],
            doors: vec![],
            windows: vec![]
        }),
        Err(PlanError::NoRooms)
    );
}

#[test]
fn a_bedroom_that_is_a_passage() {
    let mut plan = good();
    // Reach the living room only through the bedroom.
    plan.doors[1].rooms = ["bed".into(), "living".into()];
    plan.doors[1].centre = nalgebra::Point2::new(4.0, 3.0);
    check(&plan).unwrap();
    let err = check_privacy(&plan, Knowledge::builtin()).unwrap_err();
    assert!(
        err.to_string().contains("private room `bed` is a passage"),
        "{err}"
    );
}

#[test]
fn plan_json_rejects_unknown_fields_and_round_trips() {
    let bad = GOOD.replacen("\"width\": 1.2,", "\"width\": 1.2, \"colour\": \"red\",", 1);
    let err = serde_json::from_str::<FloorPlan>(&bad)
        .unwrap_err()
        .to_string();
    assert!(err.contains("colour"), "{err}");
    let plan = good();
    let again: FloorPlan = serde_json::from_str(&serde_json::to_string(&plan).unwrap()).unwrap();
    assert_eq!(plan, again);
}

#[test]
fn door_leaves_that_would_hit_each_other() {
    let k = Knowledge::builtin();
    let walls = validate(&good(), k).unwrap();
    assert_eq!(scenethesis_floorplan::leaf_clash(&good(), &walls), None);
    let squares = scenethesis_floorplan::leaf_squares(&good(), &walls);
    let (_, bed) = squares.iter().find(|(id, _)| id == "door_bed").unwrap();
    // The bedroom door swings into the bedroom (east of x = 2) over a 0.9 m square.
    assert!(
        (bed.min.x - 2.0).abs() < 1e-9 && (bed.max.x - 2.9).abs() < 1e-9,
        "{bed:?}"
    );
    let mut plan = good();
    // The entrance in the hall's north wall, the living-room door opening into the hall
    // next to it: both leaves sweep the hall's corner.
    plan.doors[0].centre = nalgebra::Point2::new(1.0, 0.0);
    plan.doors[1].centre = nalgebra::Point2::new(2.0, 0.6);
    plan.doors[1].swing = Some(scenethesis_floorplan::Swing {
        into: "hall".into(),
        hinge: scenethesis_floorplan::Hinge::Right,
    });
    let walls = validate(&plan, k).unwrap();
    let clash = scenethesis_floorplan::leaf_clash(&plan, &walls);
    assert_eq!(clash, Some(("door_in".into(), "door_living".into())));
}
