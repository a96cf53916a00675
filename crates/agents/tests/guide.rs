//! The procedural guide: valid, walkable, reachable layouts that keep the plan's relations.

mod common;

use std::collections::BTreeSet;

use common::{footprint, layout, walk_and_reach, BENCHMARK, DETAILED};
use scenethesis_agents::{relation_holds, ConstraintTarget, Guide, NominalAssets, ProceduralGuide};
use scenethesis_scene_graph::{Environment, ParentRef, Relation, RelationKind, Scene, SceneObject};

fn sat_overlap(a: &SceneObject, b: &SceneObject, tolerance: f64) -> bool {
    let (ca, ya, ha) = footprint(a);
    let (cb, yb, hb) = footprint(b);
    let axes = |y: f64| [[y.cos(), -y.sin()], [y.sin(), y.cos()]];
    let extent = |y: f64, h: [f64; 2], d: [f64; 2]| {
        let [r, f] = axes(y);
        h[0] * (r[0] * d[0] + r[1] * d[1]).abs() + h[1] * (f[0] * d[0] + f[1] * d[1]).abs()
    };
    let d = [cb[0] - ca[0], cb[1] - ca[1]];
    for axis in axes(ya).into_iter().chain(axes(yb)) {
        let dist = (d[0] * axis[0] + d[1] * axis[1]).abs();
        if dist + tolerance >= extent(ya, ha, axis) + extent(yb, hb, axis) {
            return false;
        }
    }
    true
}

fn check_scene(prompt: &str, scene: &Scene) {
    scene
        .validate()
        .unwrap_or_else(|e| panic!("{prompt}: invalid scene {e:?}"));
    let floor = &scene.architecture.floor;
    let ground: Vec<&SceneObject> = scene
        .objects
        .iter()
        .filter(|o| matches!(o.parent, ParentRef::Ground | ParentRef::Wall(_)))
        .collect();
    for o in &ground {
        let b = o.world_aabb();
        assert!(
            b.min.x >= floor.min.x - 1e-6
                && b.max.x <= floor.max.x + 1e-6
                && b.min.z >= floor.min.y - 1e-6
                && b.max.z <= floor.max.y + 1e-6,
            "{prompt}: {} leaves the floor",
            o.id
        );
    }
    let standing: Vec<&&SceneObject> = ground
        .iter()
        .filter(|o| o.world_aabb().min.y < 0.01)
        .collect();
    for (i, a) in standing.iter().enumerate() {
        for b in &standing[i + 1..] {
            assert!(
                !sat_overlap(a, b, 0.005),
                "{prompt}: floor footprints of {} and {} overlap",
                a.id,
                b.id
            );
        }
    }
    // Children sit on their parents (or hang on their walls) and never overlap their siblings
    // on a surface (or a wall).
    for o in scene
        .objects
        .iter()
        .filter(|o| o.parent != ParentRef::Ground)
    {
        let parent = o.parent.as_str();
        let held = relation_holds(scene, &o.id, &Relation::new(o.support, parent)).unwrap();
        assert!(held, "{prompt}: {} is not {} {parent}", o.id, o.support);
        for s in scene
            .objects
            .iter()
            .filter(|s| s.parent == o.parent && s.id < o.id)
        {
            let (a, b) = (o.world_aabb(), s.world_aabb());
            if a.overlaps(&b, 0.002) {
                panic!("{prompt}: {} and {} overlap on {parent}", o.id, s.id);
            }
        }
    }
    // Walk and Reach by the metric rules.
    let (walk, reach) = walk_and_reach(scene);
    assert!(walk >= 0.99, "{prompt}: Walk {walk:.4}");
    assert!(reach >= 0.98, "{prompt}: Reach {reach:.4}");
}

#[test]
fn benchmark_layouts_are_valid_walkable_and_reachable() {
    for (prompt, _) in BENCHMARK {
        for seed in [0, 1] {
            let (plan, guided) = layout(prompt, seed);
            check_scene(prompt, &guided.scene);
            assert!(
                guided.walkway.door_reachable || plan.environment == Environment::Outdoor,
                "{prompt}"
            );
            assert!(
                guided.walkway.unreachable.is_empty(),
                "{prompt}: {:?}",
                guided.walkway.unreachable
            );
            assert!(
                guided.walkway.walk_ratio >= 0.99,
                "{prompt}: {}",
                guided.walkway.walk_ratio
            );
            assert_eq!(
                guided.scene.anchor.as_deref(),
                Some(plan.anchor.as_str()),
                "{prompt}: anchor kept"
            );
            // Almost everything planned finds a place.
            assert!(
                guided.dropped.len() * 5 <= plan.objects.len(),
                "{prompt} seed {seed}: dropped {:?}",
                guided.dropped
            );
        }
    }
}

#[test]
fn simple_prompts_meet_the_content_goal() {
    for (prompt, _) in BENCHMARK.iter().filter(|(p, _)| *p != DETAILED) {
        let (_, guided) = layout(prompt, 3);
        let scene = &guided.scene;
        let cats: BTreeSet<&str> = scene.objects.iter().map(|o| o.category.as_str()).collect();
        let kinds: BTreeSet<RelationKind> = scene
            .objects
            .iter()
            .flat_map(|o| std::iter::once(o.support).chain(o.relations.iter().map(|r| r.kind)))
            .filter(|k| *k != RelationKind::OnFloor)
            .collect();
        assert!(
            scene.objects.len() >= 20,
            "{prompt}: {} objects",
            scene.objects.len()
        );
        assert!(cats.len() >= 10, "{prompt}: {} categories", cats.len());
        assert!(kinds.len() >= 4, "{prompt}: relation kinds {kinds:?}");
    }
}

#[test]
fn detailed_prompt_relations_hold_in_the_guided_layout() {
    for seed in 0..3 {
        let (plan, guided) = layout(DETAILED, seed);
        let scene = &guided.scene;
        check_scene(DETAILED, scene);
        assert!(!plan.constraints.is_empty());
        for c in &plan.constraints {
            let o = scene.object(&c.subject).unwrap_or_else(|| {
                panic!(
                    "seed {seed}: {} was dropped: {:?}",
                    c.subject, guided.dropped
                )
            });
            match &c.target {
                ConstraintTarget::Object(t) => {
                    assert!(scene.object(t).is_some(), "{t} dropped");
                    let in_graph = o
                        .relations
                        .iter()
                        .any(|r| r.kind == c.kind && &r.target == t)
                        || (o.support == c.kind && o.parent == ParentRef::Object(t.clone()));
                    assert!(
                        in_graph,
                        "seed {seed}: {} {} {t} missing from the scene graph",
                        c.subject, c.kind
                    );
                    assert_eq!(
                        relation_holds(scene, &c.subject, &Relation::new(c.kind, t.clone())),
                        Some(true),
                        "seed {seed}: {} {} {t} does not hold",
                        c.subject,
                        c.kind
                    );
                }
                ConstraintTarget::Wall(w) => {
                    assert!(
                        o.relations
                            .contains(&Relation::new(RelationKind::AgainstWall, w.clone())),
                        "seed {seed}: {:?}",
                        o.relations
                    );
                    assert_eq!(
                        relation_holds(
                            scene,
                            &c.subject,
                            &Relation::new(RelationKind::AgainstWall, w.clone())
                        ),
                        Some(true)
                    );
                }
                ConstraintTarget::AnyWall => assert_eq!(
                    relation_holds(
                        scene,
                        &c.subject,
                        &Relation::new(RelationKind::AgainstWall, "ground")
                    ),
                    Some(true)
                ),
                ConstraintTarget::Corner => {
                    // Against two walls at once.
                    let near = scene
                        .architecture
                        .walls
                        .iter()
                        .filter(|w| {
                            relation_holds(
                                scene,
                                &c.subject,
                                &Relation::new(RelationKind::AgainstWall, w.id.clone()),
                            ) == Some(true)
                                || {
                                    let b = o.world_aabb();
                                    let wb = w.aabb();
                                    let gap_x = (wb.min.x - b.max.x).max(b.min.x - wb.max.x);
                                    let gap_z = (wb.min.z - b.max.z).max(b.min.z - wb.max.z);
                                    gap_x.max(gap_z) <= 0.15
                                }
                        })
                        .count();
                    assert!(near >= 2, "seed {seed}: {} is not in a corner", c.subject);
                }
            }
        }
        // The two armchairs sit on opposite sides of the coffee table.
        let left = relation_holds(
            scene,
            "armchair_0",
            &Relation::new(RelationKind::LeftOf, "coffee_table_0"),
        );
        let right = relation_holds(
            scene,
            "armchair_1",
            &Relation::new(RelationKind::RightOf, "coffee_table_0"),
        );
        assert_eq!((left, right), (Some(true), Some(true)), "seed {seed}");
    }
}

#[test]
fn the_same_seed_gives_the_identical_scene() {
    for prompt in ["a gym room", "a peaceful beach during sunset", DETAILED] {
        let (_, a) = layout(prompt, 11);
        let (_, b) = layout(prompt, 11);
        assert_eq!(
            a.scene.to_json_string(),
            b.scene.to_json_string(),
            "{prompt}"
        );
        assert_eq!(a.dropped, b.dropped);
    }
}

#[test]
fn different_seeds_give_visibly_different_layouts() {
    for prompt in [
        "a cozy living room with reading materials",
        "a garage",
        DETAILED,
    ] {
        let scenes: Vec<Scene> = (0..4).map(|s| layout(prompt, s).1.scene).collect();
        for i in 0..scenes.len() {
            for j in i + 1..scenes.len() {
                let (a, b) = (&scenes[i], &scenes[j]);
                // Some object shared by both scenes moved by at least 0.5 m, or the room changed.
                let moved = a
                    .objects
                    .iter()
                    .filter(|o| o.parent == ParentRef::Ground)
                    .any(|o| {
                        b.object(&o.id)
                            .is_some_and(|p| (p.pose.translation - o.pose.translation).norm() > 0.5)
                    });
                assert!(
                    moved || a.architecture != b.architecture,
                    "{prompt}: seeds {i} and {j} look alike"
                );
            }
        }
    }
}

#[test]
fn rooms_have_walls_and_a_door_and_outdoor_scenes_open_ground() {
    let (_, guided) = layout("a garage", 0);
    let arch = &guided.scene.architecture;
    assert_eq!((arch.walls.len(), arch.doors.len()), (4, 1));
    let (_, guided) = layout("a peaceful beach during sunset", 0);
    let arch = &guided.scene.architecture;
    assert_eq!(arch.environment, Environment::Outdoor);
    assert!(arch.walls.is_empty() && arch.doors.is_empty());
}

#[test]
fn several_items_share_a_shelf_compartment_and_tops() {
    let (_, guided) = layout("a bookstore", 2);
    let scene = &guided.scene;
    // Books inside one bookshelf: several stand at the same height (one compartment level).
    let shelf = scene
        .objects
        .iter()
        .find(|o| o.category == "bookshelf")
        .unwrap();
    let books: Vec<&SceneObject> = scene
        .objects
        .iter()
        .filter(|o| o.category == "book" && o.parent == ParentRef::Object(shelf.id.clone()))
        .collect();
    assert!(books.len() >= 4, "{} books in {}", books.len(), shelf.id);
    let mut heights: Vec<i64> = books
        .iter()
        .map(|b| (b.pose.translation.y * 100.0).round() as i64)
        .collect();
    heights.sort();
    let shared = heights.windows(2).filter(|w| w[0] == w[1]).count();
    assert!(shared >= 1, "books spread one per level: {heights:?}");
}

#[test]
fn nominal_assets_lay_out_plans_before_retrieval() {
    let plan = common::plan("a hospital ward", 4);
    let guided = ProceduralGuide::default()
        .layout(&plan, &NominalAssets::default(), 4)
        .unwrap();
    check_scene("a hospital ward (nominal)", &guided.scene);
}

#[test]
fn wall_mounted_objects_name_their_wall_and_hang_on_it() {
    use scenethesis_agents::Zone;
    for prompt in [
        "a museum gallery",
        "a bedroom with a bed, a wardrobe, a mirror and a painting above the bed",
    ] {
        let (plan, guided) = layout(prompt, 0);
        let scene = &guided.scene;
        let mut mounted = 0;
        for o in &scene.objects {
            let planned = plan.objects.iter().find(|p| p.id == o.id).unwrap();
            if planned.zone != Zone::WallMounted {
                assert!(!o.fixed_to_world(), "{prompt}: {} is welded", o.id);
                assert!(o.parent.wall_id().is_none(), "{prompt}: {}", o.id);
                continue;
            }
            mounted += 1;
            let wall = o
                .parent
                .wall_id()
                .unwrap_or_else(|| panic!("{prompt}: {} hangs on no wall: {}", o.id, o.parent));
            assert!(scene.architecture.wall(wall).is_some());
            assert_eq!(o.support, RelationKind::Mounted, "{prompt}: {}", o.id);
            assert!(o.fixed_to_world());
            assert!(
                o.relations
                    .iter()
                    .all(|r| r.kind != RelationKind::AgainstWall),
                "{prompt}: {} repeats its wall as a relation",
                o.id
            );
            assert_eq!(
                relation_holds(scene, &o.id, &Relation::new(RelationKind::Mounted, wall)),
                Some(true),
                "{prompt}: {} is not on {wall}",
                o.id
            );
        }
        assert!(mounted > 0, "{prompt}: nothing hangs on a wall");
    }
}
