//! A contact check that remembers distances between poses ([`ContactMemo`]) finds exactly the
//! contacts of one that does not: a book walked through a shelf's compartments, beside another
//! book and down to the floor, in steps from a fraction of a millimetre (where the memo's
//! proofs skip queries) to several centimetres (where they must not).

mod support;

use std::f64::consts::FRAC_PI_2;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use scenethesis_physics_opt::{
    ContactMemo, LossSettings, ObjectProblem, Obstacles, PreparedAsset, Support,
};
use scenethesis_scene_graph::Pose;
use support::{at, book, floor_and_shelf, shelf, SHELF_BOARDS};

/// The shelf at the origin, a second book on its middle board and the floor slab, exact.
fn obstacles(shelf: &PreparedAsset, other: &PreparedAsset) -> Obstacles {
    let mut o = floor_and_shelf(shelf);
    let book_pose = at(0.2, SHELF_BOARDS[1] + 0.0015, 0.0, FRAC_PI_2);
    o.insert(
        "book_1",
        other.exact_field(),
        book_pose,
        false,
        other.check_points(),
    );
    o
}

/// A walk of poses around the shelf's middle board: mostly sub-millimetre steps, now and then
/// a jump of centimetres, with the scale drifting.
fn walk(seed: u64, steps: usize) -> Vec<Pose> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut pose = at(-0.15, SHELF_BOARDS[1] + 0.002, 0.0, FRAC_PI_2 + 0.05);
    let mut out = Vec::with_capacity(steps);
    for _ in 0..steps {
        let size = if rng.random::<f64>() < 0.15 {
            0.04
        } else {
            0.0015
        };
        for axis in 0..3 {
            pose.translation[axis] += size * (rng.random::<f64>() * 2.0 - 1.0);
        }
        // Between the side boards, from pressed into the board to 5 cm above it.
        pose.translation.x = pose.translation.x.clamp(-0.26, 0.1);
        pose.translation.y = pose
            .translation
            .y
            .clamp(SHELF_BOARDS[1] - 0.005, SHELF_BOARDS[1] + 0.05);
        pose.translation.z = pose.translation.z.clamp(-0.03, 0.03);
        pose.scale = (pose.scale + 0.01 * (rng.random::<f64>() - 0.5)).clamp(0.8, 1.2);
        out.push(pose);
    }
    out
}

#[test]
fn remembered_checks_find_the_same_contacts_as_fresh_ones() {
    let (shelf, moving, other) = (shelf(), book(), book());
    let obstacles = obstacles(&shelf, &other);
    let settings = LossSettings::default();
    let support = Support::Free;
    let fresh = ObjectProblem::new("book_0", &moving, &obstacles, &support, &settings);
    let memo = ContactMemo::new();
    let remembering = ObjectProblem {
        memo: Some(&memo),
        ..fresh
    };
    let mut colliding = 0;
    for (k, pose) in walk(7, 400).iter().enumerate() {
        let expected = fresh.contacts(pose);
        assert_eq!(
            remembering.contacts(pose),
            expected,
            "step {k}, pose {pose:?}"
        );
        colliding += usize::from(!expected.is_free());
    }
    // The walk must both collide and come free for the comparison to mean anything.
    assert!(
        (40..360).contains(&colliding),
        "{colliding} of 400 poses collide"
    );
}
