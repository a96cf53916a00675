//! The optimizer's time budget (`OptimizeSettings::time_budget`): a budget that is not reached
//! changes nothing; a spent one keeps the poses so far and says so.

mod support;

use std::time::{Duration, Instant};

use scenethesis_physics_opt::{
    optimize_scene, OptimizeSettings, Optimizer, ProjectedGaussNewton, Sgd,
    DEFAULT_OPTIMIZE_BUDGET_SECS,
};
use support::thirty_object_room;

fn optimizers() -> Vec<Box<dyn Optimizer>> {
    vec![
        Box::new(ProjectedGaussNewton::default()),
        Box::new(Sgd::default()),
    ]
}

#[test]
fn a_budget_not_reached_changes_nothing() {
    let problem = thirty_object_room(3);
    for optimizer in optimizers() {
        let unbounded = OptimizeSettings {
            time_budget: f64::INFINITY,
            ..OptimizeSettings::default()
        };
        let free = optimize_scene(&problem, optimizer.as_ref(), &unbounded).unwrap();
        let bounded =
            optimize_scene(&problem, optimizer.as_ref(), &OptimizeSettings::default()).unwrap();
        assert!(!bounded.out_of_time && !free.out_of_time);
        // Byte for byte, as the exported scene and report would hold them.
        assert_eq!(
            serde_json::to_string(&free).unwrap(),
            serde_json::to_string(&bounded).unwrap(),
            "{}",
            optimizer.name()
        );
        assert!(!serde_json::to_string(&free)
            .unwrap()
            .contains("out_of_time"));
    }
    assert_eq!(
        OptimizeSettings::default().time_budget,
        DEFAULT_OPTIMIZE_BUDGET_SECS
    );
}

#[test]
fn a_spent_budget_keeps_the_starting_poses_and_says_so() {
    let problem = thirty_object_room(3);
    for optimizer in optimizers() {
        let spent = OptimizeSettings {
            time_budget: 0.0,
            ..OptimizeSettings::default()
        };
        let started = Instant::now();
        let placement = optimize_scene(&problem, optimizer.as_ref(), &spent).unwrap();
        assert!(started.elapsed() < Duration::from_secs(30));
        assert!(placement.out_of_time);
        assert_eq!(placement.objects.len(), problem.scene.objects.len());
        for report in &placement.objects {
            assert_eq!(
                (report.alignment_iterations, report.physics_iterations),
                (0, 0),
                "{}",
                report.id
            );
            let start = problem.scene.object(&report.id).unwrap().pose;
            // Only brought into its scale range, support region and the room.
            assert!(
                (report.pose.translation - start.translation).norm() < 0.5,
                "{}: {:?} from {:?}",
                report.id,
                report.pose,
                start
            );
        }
        let json = serde_json::to_value(&placement).unwrap();
        assert_eq!(json["out_of_time"], true);
    }
}

#[test]
fn a_budget_spent_mid_stage_ends_it_early() {
    let problem = thirty_object_room(5);
    let optimizer = Sgd::default();
    let started = Instant::now();
    let full = optimize_scene(&problem, &optimizer, &OptimizeSettings::default()).unwrap();
    let took = started.elapsed();
    let budget = took / 4;
    let settings = OptimizeSettings {
        time_budget: budget.as_secs_f64(),
        ..OptimizeSettings::default()
    };
    let started = Instant::now();
    let cut = optimize_scene(&problem, &optimizer, &settings).unwrap();
    let cut_took = started.elapsed();
    assert!(!full.out_of_time);
    assert!(cut.out_of_time, "{took:?} / {cut_took:?}");
    let iterations = |p: &scenethesis_physics_opt::Placement| {
        p.objects
            .iter()
            .map(|o| o.alignment_iterations + o.physics_iterations)
            .sum::<usize>()
    };
    assert!(iterations(&cut) < iterations(&full));
}

#[test]
fn an_iteration_limit_caps_each_stage_below_the_optimizers_budget() {
    use scenethesis_physics_opt::{LossSettings, ObjectProblem, Stage, Support};
    use support::{at, book, floor_and_shelf, shelf, SHELF_BOARDS};

    let (shelf, moving) = (shelf(), book());
    let obstacles = floor_and_shelf(&shelf);
    let settings = LossSettings::default();
    let support = Support::Free;
    let free = ObjectProblem::new("book_0", &moving, &obstacles, &support, &settings);
    let limited = ObjectProblem {
        iteration_limit: Some(2),
        ..free
    };
    // Sunk 3 cm into the middle board and turned across the shelf's side boards.
    let start = at(0.25, SHELF_BOARDS[1] - 0.03, 0.0, 0.3);
    for optimizer in optimizers() {
        let unlimited = optimizer.optimize(&free, Stage::Physics, start);
        let capped = optimizer.optimize(&limited, Stage::Physics, start);
        assert!(unlimited.iterations > 2, "{}", optimizer.name());
        assert!(capped.iterations <= 2, "{}", optimizer.name());
    }
    assert_eq!(limited.iteration_budget(40), 2);
    assert_eq!(free.iteration_budget(40), 40);
}
