//! Hand-built scenes whose metrics are known.

mod support;

use nalgebra::{Point3, Vector3};
use scenethesis_eval::{evaluate, load_path, MetricsSummary, SceneMetrics};
use scenethesis_scene_graph::{Aabb, AssetRef, ParentRef, Pose, RelationKind, Scene, SceneObject};
use support::*;

fn on_floor(
    id: &str,
    category: &str,
    asset: &scenethesis_scene_graph::Mesh,
    pose: Pose,
) -> scenethesis_eval::EvalObject {
    place(id, category, asset, pose, None, RelationKind::OnFloor)
}

fn table_with(item_id: &str, item: &scenethesis_scene_graph::Mesh, y: f64) -> SceneMetrics {
    let t = table(1.2, 0.8, 0.75, 0.05);
    evaluate(&room(vec![
        on_floor("table", "table", &t, at(0.0, 0.0, 0.0, 0.0)),
        place(
            item_id,
            item_id,
            item,
            at(0.1, y, 0.05, 0.4),
            Some("table"),
            RelationKind::On,
        ),
    ]))
}

#[test]
fn two_interpenetrating_boxes_collide_by_their_overlap() {
    let b = block(1.0, 1.0, 1.0);
    let m = evaluate(&room(vec![
        on_floor("a", "box", &b, at(-0.5, 0.0, 0.0, 0.0)),
        on_floor("b", "box", &b, at(0.3, 0.0, 0.0, 0.0)),
    ]));
    assert_eq!(m.col_o, 1.0, "{m:#?}");
    assert!(m.col_s);
    assert_eq!(m.colliding_objects, ["a", "b"]);
    assert_eq!(m.colliding_pairs.len(), 1);
    let depth = m.colliding_pairs[0].depth;
    assert!(
        (depth - 0.2).abs() < 2e-3,
        "overlap is 0.2 m, measured {depth}"
    );
    assert!(m.arch_penetrations.is_empty(), "{:?}", m.arch_penetrations);
}

#[test]
fn boxes_touching_side_by_side_do_not_collide() {
    let b = block(1.0, 1.0, 1.0);
    let m = evaluate(&room(vec![
        on_floor("a", "box", &b, at(-0.5, 0.0, 0.0, 0.0)),
        on_floor("b", "box", &b, at(0.5, 0.0, 0.0, 0.0)),
    ]));
    assert_eq!(
        m.pairs_tested, 1,
        "touching boxes are tested with their meshes"
    );
    assert_eq!(m.col_o, 0.0, "{:?}", m.colliding_pairs);
    assert_eq!(m.inst_o, 0.0, "{:?}", m.unstable);
}

#[test]
fn book_sunk_two_centimetres_into_a_table_collides_by_two_centimetres() {
    let m = table_with("book", &block(0.2, 0.04, 0.3), 0.73);
    assert_eq!(m.colliding_objects, ["table", "book"], "{m:#?}");
    let depth = m.colliding_pairs[0].depth;
    assert!((depth - 0.02).abs() < 1e-3, "sunk 2 cm, measured {depth}");
}

#[test]
fn book_resting_on_a_table_is_collision_free_and_stable() {
    let m = table_with("book", &block(0.2, 0.04, 0.3), 0.75);
    assert_eq!(m.col_o, 0.0, "{:?}", m.colliding_pairs);
    assert_eq!(m.col_arch, 0.0, "{:?}", m.arch_penetrations);
    assert_eq!(m.stability_tested, 2);
    assert!(m.unstable.is_empty(), "{:?}", m.unstable);
}

#[test]
fn cup_floating_five_centimetres_above_a_table_is_unstable() {
    let m = table_with("cup", &cup(), 0.80);
    assert_eq!(m.col_o, 0.0, "{:?}", m.colliding_pairs);
    assert_eq!(m.unstable.len(), 1, "{:?}", m.unstable);
    let u = &m.unstable[0];
    assert_eq!(u.id, "cup");
    assert!(
        (u.displacement - 0.05).abs() < 0.01,
        "falls 5 cm, moved {}",
        u.displacement
    );
    assert_eq!(m.inst_o, 0.5);
    assert!(m.inst_s);
}

#[test]
fn cup_resting_on_a_table_is_stable() {
    let m = table_with("cup", &cup(), 0.75);
    assert_eq!(m.col_o, 0.0, "{:?}", m.colliding_pairs);
    assert!(m.unstable.is_empty(), "{:?}", m.unstable);
}

#[test]
fn box_inside_a_shelf_compartment_neither_collides_nor_moves() {
    let m = evaluate(&room(vec![
        place(
            "shelf",
            "shelf",
            &shelf(),
            at(0.0, 0.0, -1.8, 0.0),
            None,
            RelationKind::AgainstWall,
        ),
        place(
            "box",
            "box",
            &block(0.3, 0.3, 0.25),
            at(0.05, 0.42, -1.75, 0.1),
            Some("shelf"),
            RelationKind::Inside,
        ),
    ]));
    // The box lies inside the shelf's bounding box and its convex hull, yet touches nothing.
    assert_eq!(m.pairs_tested, 1);
    assert_eq!(m.col_o, 0.0, "{:?}", m.colliding_pairs);
    assert_eq!(m.col_arch, 0.0, "{:?}", m.arch_penetrations);
    assert_eq!(m.stability_tested, 2);
    assert!(m.unstable.is_empty(), "{:?}", m.unstable);
}

#[test]
fn objects_sunk_into_the_floor_or_a_wall_count_as_col_arch() {
    let b = block(0.4, 0.4, 0.4);
    let m = evaluate(&room(vec![
        on_floor("sunk", "box", &b, at(0.0, -0.03, 0.0, 0.0)),
        // The back wall's inner face is at z = −2; this box reaches 5 cm into it.
        on_floor("in_wall", "box", &b, at(1.0, 0.0, -1.85, 0.0)),
        on_floor("fine", "box", &b, at(-1.0, 0.0, 0.0, 0.0)),
    ]));
    let found: Vec<(&str, &str, f64)> = m
        .arch_penetrations
        .iter()
        .map(|p| (p.object.as_str(), p.architecture.as_str(), p.depth))
        .collect();
    assert_eq!(found.len(), 2, "{found:?}");
    assert_eq!((found[0].0, found[0].1), ("sunk", "floor"));
    assert!((found[0].2 - 0.03).abs() < 1e-4, "{found:?}");
    assert_eq!((found[1].0, found[1].1), ("in_wall", "wall_0"));
    assert!((found[1].2 - 0.05).abs() < 1e-3, "{found:?}");
    assert!((m.col_arch - 2.0 / 3.0).abs() < 1e-9);
    assert_eq!(m.col_o, 0.0);
}

#[test]
fn chair_blocking_the_only_doorway_splits_the_walkable_floor() {
    let open = evaluate(&two_rooms(Vec::new()));
    assert!(
        open.walk > 0.999,
        "the doorway connects both rooms: {}",
        open.walk
    );
    let blocked = evaluate(&two_rooms(vec![on_floor(
        "chair",
        "chair",
        &chair(),
        at(0.0, 0.0, 0.0, 0.0),
    )]));
    assert!(
        blocked.walk < 0.6 && blocked.walk > 0.4,
        "two halves: {}",
        blocked.walk
    );
    // A painting high on a wall is no obstacle for Walk.
    let painting = place(
        "painting",
        "painting",
        &block(0.8, 0.6, 0.03),
        at(-1.0, 1.4, -1.985, 0.0),
        None,
        RelationKind::AgainstWall,
    );
    let with_painting = evaluate(&two_rooms(vec![painting]));
    assert!(with_painting.walk > 0.999, "{}", with_painting.walk);
}

#[test]
fn reach_weights_each_component_by_area_and_by_the_objects_touching_it() {
    let b = block(0.5, 0.8, 0.5);
    // Chair in the doorway: left room holds two boxes, right room one; the chair touches both.
    let m = evaluate(&two_rooms(vec![
        on_floor("chair", "chair", &chair(), at(0.0, 0.0, 0.0, 0.0)),
        on_floor("left_a", "box", &b, at(-2.0, 0.0, -1.0, 0.0)),
        on_floor("left_b", "box", &b, at(-2.0, 0.0, 1.0, 0.0)),
        on_floor("right", "box", &b, at(2.0, 0.0, 0.0, 0.0)),
    ]));
    // Components of about equal area: (3/4)·½ + (2/4)·½ = 0.625.
    let reach = m.reach_floor.unwrap();
    assert!((reach - 0.625).abs() < 0.02, "reach {reach}");
    assert!(m.unreachable_floor_objects.is_empty());
    // In one open room every object reaches the single component.
    let open = evaluate(&room(vec![
        on_floor("a", "box", &b, at(-2.0, 0.0, -1.0, 0.0)),
        on_floor("b", "box", &b, at(2.0, 0.0, 1.0, 0.5)),
    ]));
    assert_eq!(open.reach_floor, Some(1.0));
}

#[test]
fn small_objects_in_the_middle_of_a_table_count_only_in_reach_all() {
    let m = table_with("cup", &cup(), 0.75);
    assert_eq!(m.reach_floor, Some(1.0));
    assert_eq!(
        m.reach_all,
        Some(0.5),
        "the cup's footprint lies inside the table's"
    );
}

#[test]
fn mounted_objects_are_welded_and_floating_ones_are_unstable() {
    let painting = |support| {
        place(
            "painting",
            "painting",
            &block(0.8, 0.6, 0.03),
            at(0.0, 1.4, -1.985, 0.0),
            None,
            support,
        )
    };
    // Mounted on the back wall: welded, excluded from Inst-O, still a floor-reached object.
    let mounted = painting(RelationKind::Mounted);
    assert!(mounted.welded());
    let m = evaluate(&room(vec![mounted]));
    assert_eq!(m.welded, ["painting"]);
    assert_eq!(m.stability_tested, 0);
    assert!(m.unstable.is_empty());
    assert_eq!(m.inst_o, 0.0);
    assert_eq!(m.reach_floor, Some(1.0));

    // The same painting at the same height without a mounted support floats: it is simulated,
    // falls, and counts in Inst-O (a wall category is not welded by its name).
    let floating = painting(RelationKind::AgainstWall);
    assert!(!floating.welded());
    let m = evaluate(&room(vec![floating]));
    assert!(m.welded.is_empty());
    assert_eq!(m.stability_tested, 1);
    assert_eq!(m.unstable.len(), 1, "{:?}", m.unstable);
    assert_eq!(m.unstable[0].id, "painting");
    assert_eq!(m.inst_o, 1.0);
    assert!(m.inst_s);
}

#[test]
fn foreign_glb_nodes_become_objects_and_architecture() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("foreign.glb");
    let floor = block(4.0, 0.1, 4.0).transformed(&at(0.0, -0.1, 0.0, 0.0));
    let wall = block(4.0, 2.5, 0.1).transformed(&at(0.0, 0.0, -2.05, 0.0));
    let t = table(1.2, 0.8, 0.75, 0.05).transformed(&at(0.0, 0.0, 0.0, 0.0));
    let sunk_book = block(0.2, 0.04, 0.3).transformed(&at(0.2, 0.73, 0.0, 0.0));
    let lamp = cup().transformed(&at(1.5, 0.0, 1.5, 0.0));
    write_glb(
        &path,
        &[
            ("Floor", &floor),
            ("wall_0", &wall),
            ("Table.001", &t),
            ("book_3", &sunk_book),
            ("floor_lamp", &lamp),
        ],
    );
    let scene = load_path(&path).unwrap();
    let ids: Vec<&str> = scene.objects.iter().map(|o| o.id.as_str()).collect();
    assert_eq!(ids, ["Table.001", "book_3", "floor_lamp"]);
    assert_eq!(scene.objects[0].category, "table");
    assert_eq!(scene.objects[1].parent.as_deref(), Some("Table.001"));
    assert_eq!(scene.objects[2].parent, None);
    assert_eq!(scene.architecture.walls.len(), 1);
    let rect = &scene.architecture.floor;
    assert!((rect.min.x + 2.0).abs() < 1e-6 && (rect.max.y - 2.0).abs() < 1e-6);
    let m = evaluate(&scene);
    assert_eq!(m.colliding_objects, ["Table.001", "book_3"]);
    assert!((m.colliding_pairs[0].depth - 0.02).abs() < 1e-3);
    assert_eq!(m.objects, 3);
    assert_eq!(m.categories, 3);
    // The same nodes under one wrapper root load the same way.
    let wrapped = dir.path().join("wrapped.glb");
    write_glb_under(
        &wrapped,
        Some("RootNode"),
        &[
            ("Floor", &floor),
            ("wall_0", &wall),
            ("Table.001", &t),
            ("book_3", &sunk_book),
            ("floor_lamp", &lamp),
        ],
    );
    assert_eq!(load_path(&wrapped).unwrap(), scene);
}

#[test]
fn output_folder_takes_meshes_from_scene_glb_nodes_by_id() {
    let dir = tempfile::tempdir().unwrap();
    let t = table(1.2, 0.8, 0.75, 0.05);
    let b = block(0.5, 0.5, 0.5);
    let object =
        |id: &str, category: &str, mesh: &scenethesis_scene_graph::Mesh, pose: Pose| SceneObject {
            id: id.into(),
            category: category.into(),
            asset: AssetRef::Imported {
                id: category.into(),
                path: format!("{category}.glb"),
            },
            pose,
            parent: ParentRef::Ground,
            support: RelationKind::OnFloor,
            relations: vec![scenethesis_scene_graph::Relation::new(
                RelationKind::Beside,
                if id == "table_0" { "box_0" } else { "table_0" },
            )],
            local_bounds: mesh
                .bounds()
                .unwrap_or(Aabb::new(Point3::origin(), Point3::origin())),
            joints: Vec::new(),
            parent_link: None,
            room: None,
        };
    let mut scene = Scene::new(scenethesis_scene_graph::Architecture::rectangular_room(
        6.0, 4.0, 2.8, 0.9,
    ));
    let table_pose = Pose::new(1.0, 0.3, Vector3::new(1.0, 0.0, 0.5));
    // The box overlaps the table's legs region by 10 cm.
    let box_pose = Pose::new(1.0, 0.0, Vector3::new(0.2, 0.0, 0.5));
    scene
        .objects
        .push(object("table_0", "table", &t, table_pose));
    scene.objects.push(object("box_0", "box", &b, box_pose));
    scene
        .write_json_atomic(&dir.path().join("scene.json"))
        .unwrap();
    let floor = block(6.0, 0.05, 4.0).transformed(&at(0.0, -0.05, 0.0, 0.0));
    write_glb(
        &dir.path().join("scene.glb"),
        &[
            ("floor", &floor),
            ("box_0", &b.transformed(&box_pose)),
            ("table_0", &t.transformed(&table_pose)),
        ],
    );
    let loaded = load_path(dir.path()).unwrap();
    assert_eq!(loaded.objects.len(), 2);
    assert_eq!(loaded.objects[0].id, "table_0");
    assert!((loaded.objects[0].yaw - 0.3).abs() < 1e-12);
    let m = evaluate(&loaded);
    assert_eq!(m.relation_kind_names, ["beside"]);
    assert_eq!(m.categories, 2);
    assert!(m.walk > 0.99);
    // Missing nodes are named in the error.
    write_glb(&dir.path().join("scene.glb"), &[("floor", &floor)]);
    let err = load_path(dir.path()).unwrap_err().to_string();
    assert!(err.contains("table_0"), "{err}");
}

#[test]
fn summary_pools_objects_over_scenes_and_scenes_over_scenes() {
    let b = block(1.0, 1.0, 1.0);
    let colliding = evaluate(&room(vec![
        on_floor("a", "box", &b, at(-0.5, 0.0, 0.0, 0.0)),
        on_floor("b", "box", &b, at(0.3, 0.0, 0.0, 0.0)),
    ]));
    let clean = evaluate(&room(vec![
        on_floor("a", "box", &b, at(-2.0, 0.0, 0.0, 0.0)),
        on_floor("b", "box", &b, at(0.0, 0.0, 0.0, 0.0)),
        on_floor("c", "box", &b, at(2.0, 0.0, 0.0, 0.0)),
        on_floor("d", "box", &b, at(0.0, 0.0, 1.2, 0.0)),
        on_floor("e", "box", &b, at(0.0, 0.0, -1.2, 0.0)),
        on_floor("f", "box", &b, at(-2.0, 0.0, -1.2, 0.0)),
    ]));
    let s = MetricsSummary::from_scenes(&[colliding.clone(), clean.clone()]);
    assert_eq!(s.scenes, 2);
    assert_eq!(s.objects, 8);
    assert_eq!(s.col_o, 2.0 / 8.0, "pooled over objects");
    assert_eq!(s.col_s, 0.5, "pooled over scenes");
    assert!((s.walk - (colliding.walk + clean.walk) / 2.0).abs() < 1e-12);
    let json = serde_json::to_string(&s).unwrap();
    let back: MetricsSummary = serde_json::from_str(&json).unwrap();
    assert_eq!(back, s);
    let json = serde_json::to_string(&colliding).unwrap();
    let back: SceneMetrics = serde_json::from_str(&json).unwrap();
    assert_eq!(back, colliding);
    assert!(colliding.to_table().contains("Col-O"));
}

#[test]
fn thirty_object_scene_is_clean_and_deterministic() {
    let scene = thirty_objects();
    assert_eq!(scene.objects.len(), 30);
    let m = evaluate(&scene);
    assert_eq!(m.col_o, 0.0, "{:?}", m.colliding_pairs);
    assert_eq!(m.col_arch, 0.0, "{:?}", m.arch_penetrations);
    assert!(m.unstable.is_empty(), "{:?}", m.unstable);
    assert!(m.walk > 0.99, "{}", m.walk);
    assert_eq!(evaluate(&scene), m, "same scene, same metrics");
}

/// A 0.6 m wide cabinet whose door (hinged on its left edge, opening toward +Z) is part of
/// the mesh, with a box of side 0.3 m standing `gap` metres in front of it.
fn cabinet_and_box(gap: f64, box_parent_link: Option<&str>) -> SceneMetrics {
    evaluate(&cabinet_and_box_scene(gap, box_parent_link))
}

/// The scene of [`cabinet_and_box`].
fn cabinet_and_box_scene(gap: f64, box_parent_link: Option<&str>) -> scenethesis_eval::EvalScene {
    use scenethesis_scene_graph::{Joint, JointKind, JointState, Material, MeshPart, OpensTo};
    let mut cabinet = scenethesis_scene_graph::Mesh::cuboid(
        "body",
        Material::new("oak", [0.6, 0.4, 0.2], 0.6),
        [-0.3, 0.0, -0.25],
        [0.3, 0.8, 0.23],
    );
    let mut door = MeshPart::cuboid("door", 0, [-0.3, 0.0, 0.23], [0.3, 0.8, 0.25]);
    door.joint = Some("door".into());
    cabinet.parts.push(door);
    let object = |id: &str, mesh: &scenethesis_scene_graph::Mesh, x: f64, z: f64| SceneObject {
        id: id.into(),
        category: id.into(),
        asset: AssetRef::Procedural {
            generator: id.into(),
            seed: 0,
            look: None,
        },
        pose: Pose::new(1.0, 0.3, Vector3::new(x, 0.0, z)),
        parent: ParentRef::Ground,
        support: RelationKind::OnFloor,
        relations: Vec::new(),
        local_bounds: mesh.bounds().unwrap(),
        joints: Vec::new(),
        parent_link: None,
        room: None,
    };
    let mut cab = object("cabinet", &cabinet, 0.0, 0.0);
    cab.joints = vec![JointState {
        joint: Joint {
            name: "door".into(),
            kind: JointKind::Revolute,
            axis: [0.0, -1.0, 0.0],
            anchor: [-0.3, 0.0, 0.25],
            limits: [0.0, 1.9],
            opens_to: OpensTo::Left,
            parent: None,
        },
        state: 0.0,
    }];
    let b = block(0.3, 0.3, 0.3);
    let front = cab.pose.front();
    let mut item = object("box", &b, front.x * (0.25 + gap), front.z * (0.25 + gap));
    if let Some(link) = box_parent_link {
        item.parent = ParentRef::Object("cabinet".into());
        item.parent_link = Some(link.into());
    }
    let objects = vec![
        scenethesis_eval::EvalObject::from_scene_object(&cab, &cabinet),
        scenethesis_eval::EvalObject::from_scene_object(&item, &b),
    ];
    room(objects)
}

#[test]
fn collisions_and_openings_sharing_part_fields_answer_as_each_alone() {
    use scenethesis_eval::{collision::collisions, evaluate_timed, opening::opening_clearances};
    // The box stands 2 cm into the closed door: a collision, and a door that cannot open.
    let scene = cabinet_and_box_scene(-0.02, None);
    let (m, timings) = evaluate_timed(&scene, &scenethesis_eval::DecompositionCache::new());
    assert!(!m.colliding_pairs.is_empty(), "the box is in the door");
    assert_eq!(m.colliding_pairs, collisions(&scene).pairs);
    assert!(m.blocked_openings().count() == 1, "{:?}", m.openings);
    assert_eq!(m.openings, opening_clearances(&scene));
    assert_eq!(m, evaluate(&scene));
    for (part, seconds) in [
        ("collisions", timings.collisions),
        ("stability", timings.stability),
        ("walk-reach", timings.walk_reach),
        ("openings", timings.openings),
    ] {
        assert!(seconds > 0.0 && seconds < 60.0, "{part}: {seconds} s");
    }
}

#[test]
fn a_door_opens_freely_only_when_nothing_stands_in_its_swing() {
    let blocked = cabinet_and_box(0.25, None);
    assert_eq!(blocked.openings.len(), 1, "{:?}", blocked.openings);
    let o = &blocked.openings[0];
    assert!(!o.held, "{o:?}");
    assert_eq!(o.blocked_by.as_deref(), Some("box"));
    assert!(o.free_share < 0.9);
    assert!(blocked.to_table().contains("opening: cabinet joint door"));

    let free = cabinet_and_box(0.9, None);
    assert!(free.openings[0].held, "{:?}", free.openings);
    assert_eq!(free.openings[0].free_share, 0.9f32 as f64);

    // What the door carries rides with it and never blocks it.
    let carried = cabinet_and_box(0.25, Some("door"));
    assert!(carried.openings[0].held, "{:?}", carried.openings);

    let summary = MetricsSummary::from_scenes(&[blocked, free]);
    assert_eq!((summary.openable_objects, summary.joints), (2, 2));
    assert_eq!(summary.opening_clearance, Some(0.5));
}
