//! A held object that perception left turned across its holder's rim: a 30 cm bar on a shelf
//! level, turned 40° so that it straddles the level's front lip, with a wide crate behind it.
//! Pushed between the crate and the lip, the smallest move frees neither; turned square to the
//! shelf it fits in front of the crate.

mod support;

use std::f64::consts::PI;
use std::sync::Arc;

use scenethesis_physics_opt::{optimize_scene, OptimizeSettings, ProjectedGaussNewton};
use scenethesis_scene_graph::RelationKind;
use support::{at, lipped_shelf, object, problem, surface_box, LIPPED_BOARD};

#[test]
fn a_held_bar_turned_across_the_lip_ends_clear_of_its_shelf() {
    let shelf = Arc::new(lipped_shelf());
    let crate_box = Arc::new(surface_box([0.7, 0.2, 0.17], [0.95, 1.05]));
    let bar = Arc::new(surface_box([0.3, 0.06, 0.08], [0.95, 1.05]));
    let y = LIPPED_BOARD;
    let objects = vec![
        (
            object(
                "shelf",
                None,
                RelationKind::OnFloor,
                &shelf,
                at(0.0, 0.0, -1.5, 0.0),
            ),
            shelf.clone(),
        ),
        (
            object(
                "crate",
                Some("shelf"),
                RelationKind::Inside,
                &crate_box,
                at(0.0, y, -1.5 - 0.055, 0.0),
            ),
            crate_box.clone(),
        ),
        (
            object(
                "bar",
                Some("shelf"),
                RelationKind::Inside,
                &bar,
                at(0.05, y, -1.5 + 0.12, 40.0 * PI / 180.0),
            ),
            bar.clone(),
        ),
    ];
    let problem = problem("shelf", objects);
    let placement = optimize_scene(
        &problem,
        &ProjectedGaussNewton::default(),
        &OptimizeSettings::default(),
    )
    .unwrap();
    for r in &placement.objects {
        assert!(r.is_ok(), "{r}");
    }
    // The bar rests on the level in front of the crate, square to the shelf.
    let bar = placement.object("bar").unwrap();
    assert!(
        (bar.pose.translation.y - LIPPED_BOARD).abs() < 0.005,
        "{:?}",
        bar.pose
    );
    let turn = bar.pose.yaw.rem_euclid(PI / 2.0);
    assert!(turn.min(PI / 2.0 - turn) < 0.2, "{:?}", bar.pose);
}
