//! Wall-mounted objects: a wall as parent, the `mounted` support, and the one "fixed to the
//! world" rule every consumer reads.

use scenethesis_scene_graph::nalgebra::{Point3, Vector3};
use scenethesis_scene_graph::{
    relation_holds, Aabb, Architecture, AssetRef, ParentRef, Pose, Relation, RelationKind, Scene,
    SceneObject, ValidationError,
};

fn object(id: &str, parent: ParentRef, support: RelationKind, at: Vector3<f64>) -> SceneObject {
    SceneObject {
        id: id.into(),
        category: "painting".into(),
        asset: AssetRef::Procedural {
            generator: "painting".into(),
            seed: 3,
            look: None,
        },
        pose: Pose::new(1.0, 0.0, at),
        parent,
        support,
        relations: Vec::new(),
        local_bounds: Aabb::new(Point3::new(-0.4, 0.0, -0.02), Point3::new(0.4, 0.6, 0.02)),
        joints: Vec::new(),
        parent_link: None,
        room: None,
    }
}

/// A 6 × 4 m room (back wall `wall_0`, inner face at z = −2) with a sofa and a painting hung
/// on the back wall 1.3 m up, its back 1 cm off the wall.
fn room() -> Scene {
    let mut scene = Scene::new(Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9));
    let sofa = SceneObject {
        category: "sofa".into(),
        local_bounds: Aabb::new(Point3::new(-1.0, 0.0, -0.45), Point3::new(1.0, 0.9, 0.45)),
        ..object(
            "sofa_0",
            ParentRef::Ground,
            RelationKind::OnFloor,
            Vector3::new(0.0, 0.0, 0.5),
        )
    };
    let painting = object(
        "painting_0",
        ParentRef::Wall("wall_0".into()),
        RelationKind::Mounted,
        Vector3::new(0.0, 1.3, -1.97),
    );
    scene.anchor = Some("sofa_0".into());
    scene.objects = vec![painting, sofa];
    scene
}

#[test]
fn a_mounted_object_round_trips_with_its_wall_as_a_plain_string_parent() {
    let scene = room();
    assert_eq!(scene.validate(), Ok(()));
    let text = scene.to_json_string();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let painting = &json["objects"]["painting_0"];
    assert_eq!(painting["parent"], "wall_0");
    assert_eq!(painting["support"], "mounted");
    assert_eq!(json["objects"]["sofa_0"]["parent"], "ground");
    let back = Scene::from_json_str(&text).unwrap();
    assert_eq!(back, scene);
    assert_eq!(
        back.object("painting_0").unwrap().parent,
        ParentRef::Wall("wall_0".into())
    );
    assert_eq!(back.validate(), Ok(()));
    // Walls are roots of the walk like the ground: the anchor first, then the painting.
    let order: Vec<&str> = back
        .bfs_order()
        .unwrap()
        .iter()
        .map(|o| o.id.as_str())
        .collect();
    assert_eq!(order, ["sofa_0", "painting_0"]);
}

#[test]
fn fixed_to_the_world_means_a_mounted_support_and_nothing_else() {
    let scene = room();
    assert!(scene.object("painting_0").unwrap().fixed_to_world());
    assert!(!scene.object("sofa_0").unwrap().fixed_to_world());
    // A painting at the same height on the ground link floats: it is not welded.
    let mut floating = scene.object("painting_0").unwrap().clone();
    floating.parent = ParentRef::Ground;
    floating.support = RelationKind::AgainstWall;
    assert!(!floating.fixed_to_world());
    for kind in RelationKind::ALL {
        assert_eq!(
            kind.fixes_to_world(),
            kind == RelationKind::Mounted,
            "{kind}"
        );
    }
    assert!(RelationKind::Mounted.is_support());
    assert_eq!(RelationKind::Mounted.as_str(), "mounted");
}

#[test]
fn validation_refuses_mounted_objects_off_walls_and_ids_that_are_wall_ids() {
    let problems = |scene: &Scene| scene.validate().err().unwrap_or_default();

    // Mounted on the ground, on an object, on a door, on a wall that does not exist.
    for parent in [
        ParentRef::Ground,
        ParentRef::Object("sofa_0".into()),
        ParentRef::Object("door_0".into()),
        ParentRef::Wall("wall_9".into()),
    ] {
        let mut scene = room();
        scene.object_mut("painting_0").unwrap().parent = parent.clone();
        let p = problems(&scene);
        assert!(!p.is_empty(), "{parent} accepted");
        let text: Vec<String> = p.iter().map(ToString::to_string).collect();
        assert!(
            text.iter()
                .any(|t| t.contains("painting_0") && t.contains(parent.as_str())),
            "{text:?}"
        );
    }
    let mut scene = room();
    scene.object_mut("painting_0").unwrap().parent = ParentRef::Object("sofa_0".into());
    assert!(problems(&scene).contains(&ValidationError::MountedOffWall {
        id: "painting_0".into(),
        parent: "sofa_0".into(),
    }));

    // A wall parent with another support.
    let mut scene = room();
    scene.object_mut("painting_0").unwrap().support = RelationKind::AgainstWall;
    assert_eq!(
        problems(&scene),
        [ValidationError::WallParentNotMounted {
            id: "painting_0".into(),
            wall: "wall_0".into(),
            support: "against-wall".into(),
        }]
    );

    // An object whose id is a wall's id: refused, so a parent string is never ambiguous.
    let mut scene = room();
    scene.object_mut("sofa_0").unwrap().id = "wall_1".into();
    scene.anchor = Some("wall_1".into());
    assert!(
        problems(&scene).contains(&ValidationError::DuplicateId {
            id: "wall_1".into(),
            first: "wall",
            second: "object",
        }),
        "{:?}",
        problems(&scene)
    );

    // In a file, a parent naming a door stays an unknown object parent.
    let mut json: serde_json::Value = serde_json::from_str(&room().to_json_string()).unwrap();
    json["objects"]["painting_0"]["parent"] = "door_0".into();
    let scene = Scene::from_json_str(&json.to_string()).unwrap();
    assert_eq!(
        scene.object("painting_0").unwrap().parent,
        ParentRef::Object("door_0".into())
    );
    assert!(problems(&scene)
        .iter()
        .any(|e| matches!(e, ValidationError::UnknownParent { parent, .. } if parent == "door_0")));
}

#[test]
fn mounted_holds_with_the_back_on_the_wall_and_the_bottom_off_the_floor() {
    let mut scene = room();
    let on_wall = Relation::new(RelationKind::Mounted, "wall_0");
    assert_eq!(relation_holds(&scene, "painting_0", &on_wall), Some(true));
    assert_eq!(
        relation_holds(
            &scene,
            "painting_0",
            &Relation::new(RelationKind::Mounted, "wall_1")
        ),
        Some(false),
        "the left wall is 3 m away"
    );
    assert_eq!(
        relation_holds(
            &scene,
            "painting_0",
            &Relation::new(RelationKind::Mounted, "wall_7")
        ),
        None
    );
    // Pulled 30 cm off the wall: no longer hanging on it.
    scene.object_mut("painting_0").unwrap().pose.translation.z += 0.3;
    assert_eq!(relation_holds(&scene, "painting_0", &on_wall), Some(false));
    // Back on the wall but standing on the floor: against the wall, not mounted.
    let p = scene.object_mut("painting_0").unwrap();
    p.pose.translation.z -= 0.3;
    p.pose.translation.y = 0.0;
    assert_eq!(relation_holds(&scene, "painting_0", &on_wall), Some(false));
    assert_eq!(
        relation_holds(
            &scene,
            "painting_0",
            &Relation::new(RelationKind::AgainstWall, "wall_0")
        ),
        Some(true)
    );
}

/// A turned round planter touching the back wall stands against it, though the corners of its
/// turned box lie in the wall; pushed into the wall, or square to it and 3 cm in, it does not.
#[test]
fn a_turned_round_object_touching_the_wall_stands_against_it() {
    let mut scene = room();
    let planter = SceneObject {
        category: "plant".into(),
        local_bounds: Aabb::new(Point3::new(-0.3, 0.0, -0.3), Point3::new(0.3, 1.2, 0.3)),
        pose: Pose::new(1.0, 0.7, Vector3::new(2.0, 0.0, -1.69)),
        ..object(
            "plant_0",
            ParentRef::Ground,
            RelationKind::AgainstWall,
            Vector3::zeros(),
        )
    };
    scene.objects.push(planter);
    let against = Relation::new(RelationKind::AgainstWall, "wall_0");
    // The pot's rim is 1 cm off the wall; its turned box reaches 0.3 (cos 0.7 + sin 0.7) =
    // 0.42 m from the centre, 11 cm into the wall.
    assert_eq!(relation_holds(&scene, "plant_0", &against), Some(true));
    scene.object_mut("plant_0").unwrap().pose.translation.z = -1.64;
    assert_eq!(relation_holds(&scene, "plant_0", &against), Some(true));
    // 5 cm into the wall.
    scene.object_mut("plant_0").unwrap().pose.translation.z = -1.75;
    assert_eq!(relation_holds(&scene, "plant_0", &against), Some(false));
    // Square to the wall and 3 cm into it.
    let p = scene.object_mut("plant_0").unwrap();
    p.pose.yaw = 0.0;
    p.pose.translation.z = -1.73;
    assert_eq!(relation_holds(&scene, "plant_0", &against), Some(false));
}
