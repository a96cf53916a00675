//! Hand-built scenes with known answers, solved by both optimizers.

mod support;

use std::sync::Arc;

use nalgebra::{Point3, Vector3};
use scenethesis_correspondence::{Correspondence, PoseAlignment};
use scenethesis_imagery::{Camera, Intrinsics};
use scenethesis_physics_opt::{
    optimize_scene, Issue, OptimizeSettings, Optimizer, Placement, PreparedAsset,
    ProjectedGaussNewton, SceneProblem, Sgd,
};
use scenethesis_scene_graph::{Pose, RelationKind};
use support::*;

fn optimizers() -> Vec<Box<dyn Optimizer>> {
    vec![
        Box::new(Sgd::default()),
        Box::new(ProjectedGaussNewton::default()),
    ]
}

fn run(problem: &SceneProblem, optimizer: &dyn Optimizer) -> Placement {
    optimize_scene(problem, optimizer, &OptimizeSettings::default()).unwrap()
}

fn assert_all_ok(placement: &Placement) {
    let failures: Vec<String> = placement
        .objects
        .iter()
        .filter(|o| !o.is_ok() || o.penetration > 0.001)
        .map(|o| {
            format!(
                "{o} (iterations {}, polished {}, pose {:?})",
                o.physics_iterations, o.polished, o.pose
            )
        })
        .collect();
    assert!(
        failures.is_empty(),
        "[{}] {failures:#?}",
        placement.optimizer
    );
}

fn gap(placement: &Placement, id: &str) -> f64 {
    placement.object(id).unwrap().support_gap.unwrap()
}

#[test]
fn two_interpenetrating_boxes_are_pushed_apart() {
    let b = Arc::new(boxed([0.5, 0.5, 0.5], [0.9, 1.1]));
    let problem = problem(
        "box_a",
        vec![
            (
                object(
                    "box_a",
                    None,
                    RelationKind::OnFloor,
                    &b,
                    at(0.0, 0.0, 0.0, 0.0),
                ),
                b.clone(),
            ),
            (
                object(
                    "box_b",
                    None,
                    RelationKind::OnFloor,
                    &b,
                    at(0.4, 0.0, 0.05, 0.0),
                ),
                b.clone(),
            ),
        ],
    );
    for opt in optimizers() {
        let placement = run(&problem, opt.as_ref());
        assert_all_ok(&placement);
        let a = placement.pose("box_a").unwrap();
        let bp = placement.pose("box_b").unwrap();
        // The anchor goes first and has nothing to avoid; the second box moves away from it.
        assert!(
            a.translation.xz().norm() < 1e-3,
            "[{}] {a:?}",
            placement.optimizer
        );
        let ax = a.translation.x + 0.25 * a.scale;
        let bx = bp.translation.x - 0.25 * bp.scale;
        assert!(
            bx - ax >= 0.0
                || (bp.translation.z - a.translation.z).abs() >= 0.25 * (a.scale + bp.scale),
            "[{}] boxes still overlap: {a:?} {bp:?}",
            placement.optimizer
        );
        for id in ["box_a", "box_b"] {
            let g = gap(&placement, id);
            assert!(
                (0.0..=0.002).contains(&g),
                "[{}] {id} gap {g}",
                placement.optimizer
            );
        }
    }
}

/// The table standing at `table_pose` with the item `id` on it at `item_pose`.
fn item_on_table(
    table_pose: Pose,
    id: &str,
    item: &Arc<PreparedAsset>,
    item_pose: Pose,
) -> SceneProblem {
    let table = Arc::new(table());
    problem(
        "table",
        vec![
            (
                object("table", None, RelationKind::OnFloor, &table, table_pose),
                table.clone(),
            ),
            (
                object(id, Some("table"), RelationKind::On, item, item_pose),
                item.clone(),
            ),
        ],
    )
}

#[test]
fn book_sunk_into_table_is_lifted_onto_it() {
    let book = Arc::new(book());
    let problem = item_on_table(
        at(0.0, 0.0, 0.0, 0.0),
        "book",
        &book,
        at(0.1, TABLE_TOP - 0.02, 0.05, 0.3),
    );
    for opt in optimizers() {
        let placement = run(&problem, opt.as_ref());
        assert_all_ok(&placement);
        let g = gap(&placement, "book");
        assert!(
            (0.0..=0.002).contains(&g),
            "[{}] gap {g}",
            placement.optimizer
        );
        let p = placement.pose("book").unwrap();
        assert!(
            (p.translation.xz() - nalgebra::Vector2::new(0.1, 0.05)).norm() < 0.01,
            "[{}] {p:?}",
            placement.optimizer
        );
        assert_eq!(p.yaw, 0.3);
    }
}

#[test]
fn cup_floating_above_table_is_lowered_onto_it() {
    let cup = Arc::new(cup());
    let problem = item_on_table(
        at(0.0, 0.0, 0.0, 0.0),
        "cup",
        &cup,
        at(-0.2, TABLE_TOP + 0.05, 0.1, 0.0),
    );
    for opt in optimizers() {
        let placement = run(&problem, opt.as_ref());
        assert_all_ok(&placement);
        let g = gap(&placement, "cup");
        assert!(
            (0.0..=0.002).contains(&g),
            "[{}] gap {g}",
            placement.optimizer
        );
        let p = placement.pose("cup").unwrap();
        assert!((p.translation.xz() - nalgebra::Vector2::new(-0.2, 0.1)).norm() < 0.005);
    }
}

/// The shelf against the back wall (z = −1.8) with `item` inside it at `item_pose`.
fn item_in_shelf(item: &Arc<PreparedAsset>, item_pose: Pose) -> SceneProblem {
    let shelf = Arc::new(shelf());
    problem(
        "shelf",
        vec![
            (
                object(
                    "shelf",
                    None,
                    RelationKind::AgainstWall,
                    &shelf,
                    at(0.0, 0.0, -1.8, 0.0),
                ),
                shelf.clone(),
            ),
            (
                object("item", Some("shelf"), RelationKind::Inside, item, item_pose),
                item.clone(),
            ),
        ],
    )
}

#[test]
fn box_in_a_shelf_compartment_stays_in_it() {
    let item = Arc::new(boxed([0.3, 0.25, 0.2], [0.8, 1.2]));
    let start = at(0.05, SHELF_BOARDS[1] + 0.001, 0.0, 0.0);
    let problem = item_in_shelf(
        &item,
        Pose {
            translation: start.translation + Vector3::new(0.0, 0.0, -1.8),
            ..start
        },
    );
    for opt in optimizers() {
        let placement = run(&problem, opt.as_ref());
        assert_all_ok(&placement);
        let report = placement.object("item").unwrap();
        let moved = (report.pose.translation - report.initial_pose.translation).norm();
        assert!(moved < 0.002, "[{}] moved {moved}", placement.optimizer);
        assert_eq!(report.support.plane().unwrap().surface, "shelf_1");
        assert!((report.pose.scale - 1.0).abs() < 1e-9);
    }
}

#[test]
fn box_too_wide_for_its_compartment_shrinks_to_fit() {
    // 0.80 m wide, the compartment is 0.76 m: it touches both side boards (two clusters).
    let item = Arc::new(boxed([0.8, 0.2, 0.2], [0.85, 1.1]));
    let problem = item_in_shelf(&item, at(0.0, SHELF_BOARDS[1], -1.8, 0.0));
    for opt in optimizers() {
        let placement = run(&problem, opt.as_ref());
        assert_all_ok(&placement);
        let p = placement.pose("item").unwrap();
        assert!(
            p.scale < 0.95 && p.scale >= 0.85,
            "[{}] {p:?}",
            placement.optimizer
        );
        assert!((p.translation.x).abs() < 0.02);
    }
}

#[test]
fn object_that_cannot_fit_is_reported_with_what_it_hits() {
    // 1.0 m wide and may shrink only to 0.95: it cannot fit the 0.76 m compartment.
    let item = Arc::new(boxed([1.0, 0.2, 0.2], [0.95, 1.05]));
    let problem = item_in_shelf(&item, at(0.0, SHELF_BOARDS[1], -1.8, 0.0));
    for opt in optimizers() {
        let placement = run(&problem, opt.as_ref());
        assert!(!placement.is_ok());
        let failed: Vec<_> = placement.failures().map(|o| o.id.as_str()).collect();
        assert!(
            failed.contains(&"item"),
            "[{}] {failed:?}",
            placement.optimizer
        );
        let report = placement.object("item").unwrap();
        assert!(
            report.issues.iter().any(|i| matches!(i, Issue::Collision { with, depth } if with == "shelf" && *depth > 0.001)),
            "[{}] {report}",
            placement.optimizer
        );
        assert!(report.to_string().contains("penetrates `shelf`"));
    }
}

#[test]
fn object_through_a_wall_is_brought_inside_the_room() {
    let b = Arc::new(boxed([0.6, 0.8, 0.6], [0.9, 1.1]));
    // The room spans x in [-3, 3]; this box sticks 0.2 m into the wall at +x.
    let problem = problem(
        "box",
        vec![(
            object(
                "box",
                None,
                RelationKind::AgainstWall,
                &b,
                at(2.9, 0.0, 0.0, 0.0),
            ),
            b.clone(),
        )],
    );
    for opt in optimizers() {
        let placement = run(&problem, opt.as_ref());
        assert_all_ok(&placement);
        let p = placement.pose("box").unwrap();
        assert!(
            p.translation.x + 0.3 * p.scale <= 3.0,
            "[{}] {p:?}",
            placement.optimizer
        );
        assert!(
            p.translation.x > 2.6,
            "[{}] moved too far: {p:?}",
            placement.optimizer
        );
    }
}

/// A house's two rooms, x < 0 and x > 0, split by a 10 cm interior wall along x = 0, with a
/// 60 cm cabinet of the west room started across that wall, centred in it: the wall's own
/// field cannot say which side the cabinet belongs on.
fn cabinet_across_an_interior_wall() -> SceneProblem {
    use scenethesis_scene_graph::{nalgebra::Point2, RoomArea, Wall};
    let b = Arc::new(boxed([0.6, 0.8, 0.4], [0.95, 1.05]));
    let mut cabinet = object(
        "cabinet",
        None,
        RelationKind::OnFloor,
        &b,
        at(0.0, 0.0, 0.0, 0.0),
    );
    cabinet.room = Some("west".into());
    let mut problem = problem("cabinet", vec![(cabinet, b)]);
    let architecture = &mut problem.scene.architecture;
    architecture.walls.push(Wall {
        id: "wall_inner".into(),
        start: Point2::new(0.0, -2.0),
        end: Point2::new(0.0, 2.0),
        height: 2.8,
        thickness: 0.1,
    });
    let area =
        |id: &str, x0: f64, x1: f64| RoomArea::rectangle(id, "bedroom", [x0, -2.0], [x1, 2.0]);
    architecture.rooms = vec![area("west", -3.0, -0.05), area("east", 0.05, 3.0)];
    problem
}

#[test]
fn an_object_across_an_interior_wall_comes_out_into_its_own_room() {
    let problem = cabinet_across_an_interior_wall();
    for opt in optimizers() {
        let placement = run(&problem, opt.as_ref());
        assert_all_ok(&placement);
        let p = placement.pose("cabinet").unwrap();
        // Its east face at the wall's west face, not through the wall in the east room.
        let east_face = p.translation.x + 0.3 * p.scale;
        assert!(east_face <= -0.049, "[{}] {p:?}", placement.optimizer);
        assert!(
            east_face > -0.1,
            "[{}] moved too far: {p:?}",
            placement.optimizer
        );
    }
}

#[test]
fn children_follow_their_parent_when_it_moves() {
    let cup = Arc::new(cup());
    // The table pokes 0.1 m into the +x wall; the cup sits on its right end.
    let problem = item_on_table(
        at(2.5, 0.0, 0.0, 0.0),
        "cup",
        &cup,
        at(3.0, TABLE_TOP, 0.0, 0.0),
    );
    for opt in optimizers() {
        let placement = run(&problem, opt.as_ref());
        assert_all_ok(&placement);
        let t = placement.pose("table").unwrap();
        let c = placement.pose("cup").unwrap();
        assert!(
            t.translation.x <= 2.4 + 1e-6,
            "[{}] {t:?}",
            placement.optimizer
        );
        assert!(
            ((c.translation.x - t.translation.x) - 0.5).abs() < 0.01,
            "[{}] {c:?}",
            placement.optimizer
        );
    }
}

#[test]
fn alignment_recovers_a_pose_from_synthetic_correspondences() {
    let b = Arc::new(boxed([0.6, 0.5, 0.4], [0.7, 1.3]));
    let truth = Pose::new(1.1, 0.35, Vector3::new(0.3, 0.0, -0.2));
    let camera = Camera::look_at(
        Intrinsics::from_vertical_fov(640, 480, 1.0),
        Point3::new(1.5, 1.8, 2.5),
        Point3::new(0.0, 0.3, 0.0),
        Vector3::y(),
    );
    let correspondences: Vec<Correspondence> = b
        .surface_points()
        .iter()
        .step_by(8)
        .map(|p| Correspondence::exact(&camera, *p, truth.transform_point(p), 0.9).unwrap())
        .collect();
    // Start 8 cm off, 0.25 rad turned and 10 % too small.
    let start = Pose::new(1.0, 0.1, Vector3::new(0.36, 0.0, -0.14));
    let mut problem = problem(
        "box",
        vec![(
            object("box", None, RelationKind::OnFloor, &b, start),
            b.clone(),
        )],
    );
    problem.set_alignment("box", PoseAlignment::new(camera, correspondences));
    for opt in optimizers() {
        let placement = run(&problem, opt.as_ref());
        assert_all_ok(&placement);
        let report = placement.object("box").unwrap();
        assert!(report.alignment_iterations > 0);
        let p = report.pose;
        assert!(
            (p.scale - truth.scale).abs() < 0.01,
            "[{}] {p:?}",
            placement.optimizer
        );
        assert!(
            (p.yaw - truth.yaw).abs() < 0.01,
            "[{}] {p:?}",
            placement.optimizer
        );
        assert!(
            (p.translation.xz() - truth.translation.xz()).norm() < 0.005,
            "[{}] {p:?}",
            placement.optimizer
        );
    }
}

#[test]
fn same_problem_gives_bit_identical_poses() {
    let problem = thirty_object_room(7);
    let opt = ProjectedGaussNewton::default();
    let mut a = run(&problem, &opt);
    let mut b = run(&problem, &opt);
    // Wall-clock timings are the one part that differs from run to run.
    a.timings = Default::default();
    b.timings = Default::default();
    assert_eq!(a, b);
}

#[test]
fn thirty_object_room_meets_every_post_condition() {
    let problem = thirty_object_room(3);
    let eval_scene = |scene: &scenethesis_scene_graph::Scene| {
        scenethesis_eval::EvalScene::from_scene(scene, |o| Ok(thirty_object_room_mesh(&o.id)))
            .unwrap()
    };
    let before = scenethesis_eval::evaluate(&eval_scene(&problem.scene));
    assert!(before.col_o > 0.0);
    for opt in optimizers() {
        let placement = run(&problem, opt.as_ref());
        assert_eq!(placement.objects.len(), 30);
        assert_all_ok(&placement);
        // The eval crate's metrics (dense mesh sampling, rigid-body simulation) agree.
        let mut scene = problem.scene.clone();
        placement.apply_to(&mut scene);
        let m = scenethesis_eval::evaluate(&eval_scene(&scene));
        let name = &placement.optimizer;
        assert_eq!(m.col_o, 0.0, "[{name}] {:?}", m.colliding_pairs);
        assert_eq!(m.col_arch, 0.0, "[{name}] {:?}", m.arch_penetrations);
        assert_eq!(m.inst_o, 0.0, "[{name}] {:?}", m.unstable);
    }
}

#[test]
fn siblings_wedged_in_a_compartment_make_room_in_turn() {
    // Two 0.3 m boxes in the 0.76 m compartment: the second starts 5 cm into the first and
    // 2 cm into the side board. Placed after the first, it has only 0.23 m between the first
    // and the side and cannot shrink enough; the final pass moves the first box aside.
    let b = Arc::new(boxed([0.3, 0.2, 0.2], [0.98, 1.02]));
    let shelf = Arc::new(shelf());
    let y = SHELF_BOARDS[1] + 0.001;
    let problem = problem(
        "shelf",
        vec![
            (
                object(
                    "shelf",
                    None,
                    RelationKind::AgainstWall,
                    &shelf,
                    at(0.0, 0.0, -1.8, 0.0),
                ),
                shelf.clone(),
            ),
            (
                object(
                    "box_a",
                    Some("shelf"),
                    RelationKind::Inside,
                    &b,
                    at(0.0, y, -1.8, 0.0),
                ),
                b.clone(),
            ),
            (
                object(
                    "box_b",
                    Some("shelf"),
                    RelationKind::Inside,
                    &b,
                    at(0.25, y, -1.8, 0.0),
                ),
                b.clone(),
            ),
        ],
    );
    let opt = ProjectedGaussNewton::default();
    let swept = optimize_scene(
        &problem,
        &opt,
        &OptimizeSettings {
            skip_finish: true,
            ..OptimizeSettings::default()
        },
    )
    .unwrap();
    assert!(!swept.is_ok(), "the sweep alone should leave box_b wedged");
    let placement = run(&problem, &opt);
    assert_all_ok(&placement);
    let a = placement.pose("box_a").unwrap();
    assert!(a.translation.x < -0.05, "box_a did not make room: {a:?}");
    assert!((placement.pose("shelf").unwrap().translation.x).abs() < 1e-9);
}

/// A 1.0 × 0.6 m coffee table, 0.45 m high, with a lower shelf board at 0.12 m; the floor
/// beneath the shelf has 10 cm of clearance.
fn coffee_table() -> PreparedAsset {
    use scenethesis_primitives::cuboid;
    use scenethesis_scene_graph::{Placement, SupportSurface, SurfaceKind};
    let mut parts = vec![
        cuboid("top", 0, [-0.5, 0.42, -0.3], [0.5, 0.45, 0.3]),
        cuboid("shelf", 0, [-0.45, 0.1, -0.25], [0.45, 0.12, 0.25]),
    ];
    for (i, (x, z)) in [(-0.47, -0.27), (0.47, -0.27), (-0.47, 0.27), (0.47, 0.27)]
        .into_iter()
        .enumerate()
    {
        parts.push(cuboid(
            &format!("leg_{i}"),
            0,
            [x - 0.02, 0.0, z - 0.02],
            [x + 0.02, 0.42, z + 0.02],
        ));
    }
    let rect = |h: f32| vec![[-h, -0.23], [-h, 0.23], [h, 0.23], [h, -0.23]];
    let surfaces = vec![
        SupportSurface {
            name: "top".into(),
            kind: SurfaceKind::Top,
            polygon: rect(0.48),
            height: 0.45,
            clearance: None,
        },
        SupportSurface {
            name: "lower_shelf".into(),
            kind: SurfaceKind::Shelf,
            polygon: rect(0.43),
            height: 0.12,
            clearance: Some(0.3),
        },
        SupportSurface {
            name: "under".into(),
            kind: SurfaceKind::Under,
            polygon: rect(0.43),
            height: 0.0,
            clearance: Some(0.1),
        },
    ];
    let mesh = scenethesis_scene_graph::Mesh {
        parts,
        materials: vec![scenethesis_scene_graph::Material::new(
            "wood",
            [0.6, 0.45, 0.3],
            0.7,
        )],
    };
    PreparedAsset::new(
        "coffee_table",
        &mesh,
        surfaces,
        [0.9, 1.1],
        Placement::Floor,
        &scenethesis_physics_opt::PrepareSettings::default(),
    )
    .unwrap()
}

#[test]
fn basket_too_tall_for_the_floor_under_a_table_rests_on_its_low_shelf() {
    let table = Arc::new(coffee_table());
    let basket = Arc::new(boxed([0.22, 0.24, 0.22], [0.9, 1.1]));
    // The lift put the basket on the floor beneath the shelf, where only 10 cm are free.
    let problem = problem(
        "coffee_table",
        vec![
            (
                object(
                    "coffee_table",
                    None,
                    RelationKind::OnFloor,
                    &table,
                    at(0.0, 0.0, 0.0, 0.0),
                ),
                table.clone(),
            ),
            (
                object(
                    "basket",
                    Some("coffee_table"),
                    RelationKind::Under,
                    &basket,
                    at(-0.2, 0.0, 0.0, 0.0),
                ),
                basket.clone(),
            ),
        ],
    );
    for opt in optimizers() {
        let placement = run(&problem, opt.as_ref());
        assert_all_ok(&placement);
        let report = placement.object("basket").unwrap();
        assert_eq!(
            report.support.plane().unwrap().surface,
            "lower_shelf",
            "[{}]",
            placement.optimizer
        );
        assert!((report.pose.translation.y - 0.12).abs() < 0.003);
    }
}

/// A photo frame on a kickstand: the frame's bottom bar in front (−z), the kickstand's foot
/// 10 cm behind it (+z), and the frame leaning back over the foot (its centre of mass 2 cm in
/// front of the foot).
fn kickstand_frame() -> PreparedAsset {
    use scenethesis_primitives::cuboid;
    let parts = vec![
        cuboid("bar", 0, [-0.1, 0.0, -0.05], [0.1, 0.01, -0.04]),
        cuboid("foot", 0, [-0.02, 0.0, 0.04], [0.02, 0.01, 0.05]),
        cuboid("frame", 0, [-0.1, 0.03, -0.01], [0.1, 0.25, 0.05]),
    ];
    let mesh = scenethesis_scene_graph::Mesh {
        parts,
        materials: vec![scenethesis_scene_graph::Material::new(
            "wood",
            [0.6, 0.45, 0.3],
            0.7,
        )],
    };
    PreparedAsset::new(
        "frame",
        &mesh,
        Vec::new(),
        [0.9, 1.1],
        scenethesis_scene_graph::Placement::Surface,
        &scenethesis_physics_opt::PrepareSettings::default(),
    )
    .unwrap()
}

#[test]
fn frame_whose_kickstand_hangs_off_the_table_moves_onto_it() {
    let frame = Arc::new(kickstand_frame());
    // The table's support region ends at z = 0.38; the foot stands at 0.39–0.40.
    let problem = item_on_table(
        at(0.0, 0.0, 0.0, 0.0),
        "frame",
        &frame,
        at(0.0, TABLE_TOP, 0.35, 0.0),
    );
    let opt = ProjectedGaussNewton::default();
    let swept = optimize_scene(
        &problem,
        &opt,
        &OptimizeSettings {
            skip_finish: true,
            ..OptimizeSettings::default()
        },
    )
    .unwrap();
    assert!((swept.pose("frame").unwrap().translation.z - 0.35).abs() < 1e-6);
    let placement = run(&problem, &opt);
    assert_all_ok(&placement);
    let p = placement.pose("frame").unwrap();
    assert!(
        p.translation.z + 0.05 * p.scale <= 0.38 && p.translation.z > 0.3,
        "{p:?}"
    );
}

/// An object the image placed 4 cm above the floor rests by a change of scale that keeps its
/// top where the image shows it; one that would grow into its neighbour is put down instead.
#[test]
fn an_image_placed_object_off_the_floor_keeps_its_top_unless_growing_would_touch_a_neighbour() {
    let b = Arc::new(boxed([0.5, 0.8, 0.5], [0.8, 1.2]));
    let floating = |x: f64| at(x, 0.04, 0.0, 0.0);
    let mut problem = problem(
        "cabinet_a",
        vec![
            (
                object(
                    "cabinet_a",
                    None,
                    RelationKind::OnFloor,
                    &b,
                    at(-1.0, 0.0, 0.0, 0.0),
                ),
                b.clone(),
            ),
            // Free all round: it grows by 5 % about its top.
            (
                object("cabinet_b", None, RelationKind::OnFloor, &b, floating(1.0)),
                b.clone(),
            ),
            // 5 mm beside cabinet_a: 5 % wider it would touch it.
            (
                object(
                    "cabinet_c",
                    None,
                    RelationKind::OnFloor,
                    &b,
                    floating(-0.495),
                ),
                b.clone(),
            ),
        ],
    );
    let camera = Camera::look_at(
        Intrinsics::from_vertical_fov(640, 480, 1.0),
        Point3::new(0.0, 1.8, 3.0),
        Point3::new(0.0, 0.4, 0.0),
        Vector3::y(),
    );
    for id in ["cabinet_b", "cabinet_c"] {
        problem.set_alignment(id, PoseAlignment::new(camera, Vec::new()));
    }
    for opt in optimizers() {
        let placement = run(&problem, opt.as_ref());
        assert_all_ok(&placement);
        let grown = placement.object("cabinet_b").unwrap().pose;
        let top = grown.translation.y + 0.8 * grown.scale;
        assert!(
            (top - 0.84).abs() < 1e-3,
            "[{}] {grown:?}",
            placement.optimizer
        );
        assert!(
            (grown.scale - 1.05).abs() < 2e-3,
            "[{}] {grown:?}",
            placement.optimizer
        );
        let put_down = placement.object("cabinet_c").unwrap().pose;
        assert_eq!(
            put_down.scale, 1.0,
            "[{}] {put_down:?}",
            placement.optimizer
        );
        assert!(
            put_down.translation.y < 0.005,
            "[{}] {put_down:?}",
            placement.optimizer
        );
    }
}
