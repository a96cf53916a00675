//! Articulated assets: the categories with moving parts carry joints that check out, every
//! joint moves parts, opening a door, lid or drawer to its upper limit really moves it clear of
//! the body (not through it), and drawers are hollow boxes with an inside to put things in.

use std::collections::BTreeSet;

use scenethesis_procedural::catalog;
use scenethesis_scene_graph::{Asset, Joint, JointKind, MeshPart, SurfaceKind};

/// Categories whose generators build moving parts.
const ARTICULATED: [&str; 35] = [
    "cabinet",
    "wall_cabinet",
    "kitchen_counter",
    "kitchen_island",
    "wardrobe",
    "tv_stand",
    "locker",
    "chemical_cabinet",
    "display_case",
    "refrigerator",
    "drinks_fridge",
    "dishwasher",
    "microwave",
    "stove",
    "washing_machine",
    "dresser",
    "nightstand",
    "desk",
    "filing_cabinet",
    "tool_cabinet",
    "medical_cart",
    "toilet",
    "chest_freezer",
    "toy_box",
    "cooler",
    "laptop",
    "changing_table",
    "exam_table",
    "kiln",
    "recliner",
    "vending_machine",
    "server_rack",
    "photocopier",
    "safe",
    "treasure_chest",
];

/// Categories only some of whose assets have moving parts (a dartboard hangs bare or in a
/// cabinet with doors): their jointed assets get the same checks, and some seed must have one.
const SOMETIMES_ARTICULATED: [&str; 1] = ["dartboard"];

/// Seeds every check runs over.
const SEEDS: [u64; 6] = [0, 1, 2, 7, 42, 1234];

/// How deep (m) an opened part's box may reach into a body part's box: hinges sit on the
/// body's edge, so a part turning about one grazes it.
const GRAZE: f32 = 0.015;

fn assets() -> impl Iterator<Item = (String, Asset)> {
    let sometimes = SOMETIMES_ARTICULATED.iter().flat_map(|name| {
        let c = catalog::category(name).unwrap_or_else(|| panic!("no category `{name}`"));
        SEEDS
            .iter()
            .map(move |&s| (format!("{name} #{s}"), catalog::generate(c, s)))
            .filter(|(_, a)| !a.info.joints.is_empty())
    });
    ARTICULATED
        .iter()
        .flat_map(|name| {
            let c = catalog::category(name).unwrap_or_else(|| panic!("no category `{name}`"));
            SEEDS
                .iter()
                .map(move |&s| (format!("{name} #{s}"), catalog::generate(c, s)))
        })
        .chain(sometimes)
}

fn link<'a>(asset: &'a Asset, joint: &'a str) -> impl Iterator<Item = &'a MeshPart> + 'a {
    asset
        .mesh
        .parts
        .iter()
        .filter(move |p| p.joint.as_deref() == Some(joint))
}

type Aabb = ([f32; 3], [f32; 3]);

fn aabb<'a>(points: impl IntoIterator<Item = &'a [f32; 3]>) -> Aabb {
    points.into_iter().fold(
        ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]),
        |(lo, hi), p| {
            (
                std::array::from_fn(|k| lo[k].min(p[k])),
                std::array::from_fn(|k| hi[k].max(p[k])),
            )
        },
    )
}

/// How deep two boxes interpenetrate: the smallest overlap over the axes (≤ 0 when apart).
fn depth(a: &Aabb, b: &Aabb) -> f32 {
    (0..3)
        .map(|k| a.1[k].min(b.1[k]) - a.0[k].max(b.0[k]))
        .fold(f32::INFINITY, f32::min)
}

/// The part's vertices at the joint's limit farthest from closed: the upper limit, or the
/// lower one of a part drawn open (a laptop's screen folds shut toward its lower limit).
fn opened(j: &Joint, part: &MeshPart) -> Vec<[f32; 3]> {
    let state = if -j.limits[0] > j.limits[1] {
        j.limits[0]
    } else {
        j.limits[1]
    };
    part.positions
        .iter()
        .map(|&p| j.moved_point(state, p))
        .collect()
}

#[test]
fn at_least_25_categories_are_articulated() {
    assert!(ARTICULATED.len() >= 25);
    assert_eq!(
        ARTICULATED.iter().collect::<BTreeSet<_>>().len(),
        ARTICULATED.len()
    );
}

#[test]
fn sometimes_articulated_categories_have_jointed_assets_among_the_seeds() {
    for name in SOMETIMES_ARTICULATED {
        let c = catalog::category(name).unwrap_or_else(|| panic!("no category `{name}`"));
        let jointed = SEEDS
            .iter()
            .filter(|&&s| !catalog::generate(c, s).info.joints.is_empty())
            .count();
        assert!(jointed > 0, "{name}: no seed has joints");
    }
}

#[test]
fn every_joint_checks_out_and_moves_closed_oriented_parts() {
    for (who, asset) in assets() {
        let joints = &asset.info.joints;
        assert!(!joints.is_empty(), "{who}: no joints");
        let mut names = BTreeSet::new();
        for j in joints {
            j.check().unwrap_or_else(|e| panic!("{who}: {e}"));
            assert!(
                names.insert(j.name.as_str()),
                "{who}: joint `{}` twice",
                j.name
            );
            if let Some(parent) = &j.parent {
                assert!(
                    names.contains(parent.as_str()),
                    "{who}: `{}` parent",
                    j.name
                );
            }
            assert!(
                j.limits[0] <= 0.0 && j.limits[1] > 0.0,
                "{who}: `{}`",
                j.name
            );
            let parts: Vec<_> = link(&asset, &j.name).collect();
            assert!(!parts.is_empty(), "{who}: joint `{}` moves nothing", j.name);
            for p in parts {
                assert!(
                    p.is_closed_and_oriented() && p.signed_volume() > 0.0,
                    "{who}: part `{}` of `{}` is not a closed outward solid",
                    p.name,
                    j.name
                );
            }
        }
        for p in &asset.mesh.parts {
            if let Some(j) = &p.joint {
                assert!(
                    names.contains(j.as_str()),
                    "{who}: `{}` names `{j}`",
                    p.name
                );
            }
        }
    }
}

#[test]
fn opening_moves_every_link_clear_of_the_body() {
    for (who, asset) in assets() {
        let body: Vec<(&str, Aabb)> = asset
            .mesh
            .parts
            .iter()
            .filter(|p| p.joint.is_none())
            .map(|p| (p.name.as_str(), aabb(&p.positions)))
            .collect();
        for j in &asset.info.joints {
            let mut moved = 0.0f32;
            for p in link(&asset, &j.name) {
                let open = opened(j, p);
                for (a, b) in p.positions.iter().zip(&open) {
                    let d: f32 = (0..3).map(|k| (a[k] - b[k]).powi(2)).sum();
                    moved = moved.max(d.sqrt());
                }
                let open_box = aabb(&open);
                for (name, b) in &body {
                    let d = depth(&open_box, b);
                    assert!(
                        d <= GRAZE,
                        "{who}: `{}` of `{}` opened runs {d:.3} m into `{name}`",
                        p.name,
                        j.name
                    );
                }
            }
            assert!(
                moved > 0.1,
                "{who}: `{}` opens by only {moved:.3} m",
                j.name
            );
        }
    }
}

#[test]
fn drawers_are_hollow_and_slide_out_the_front() {
    let mut drawers = 0;
    for (who, asset) in assets() {
        let front = asset.info.size[2] / 2.0;
        for j in asset
            .info
            .joints
            .iter()
            .filter(|j| j.kind == JointKind::Prismatic)
        {
            drawers += 1;
            assert_eq!(j.axis, [0.0, 0.0, 1.0], "{who}: `{}` slides out +Z", j.name);
            let parts: Vec<_> = link(&asset, &j.name).collect();
            let whole = aabb(parts.iter().flat_map(|p| &p.positions));
            let outer: f32 = (0..3).map(|k| whole.1[k] - whole.0[k]).product();
            let solid = parts.iter().map(|p| p.signed_volume()).sum::<f64>() as f32;
            assert!(
                solid < 0.5 * outer,
                "{who}: `{}` fills {solid:.4} of its {outer:.4} m³ box",
                j.name
            );
            let depth = whole.1[2] - whole.0[2];
            assert!(
                j.open_state() >= 0.6 * depth && j.open_state() < depth,
                "{who}: `{}` slides {:.3} of {depth:.3} m",
                j.name,
                j.open_state()
            );
            assert!(whole.1[2] <= front + 1e-4 && whole.1[2] > front - 0.05);
            let inside = asset
                .info
                .support_surfaces
                .iter()
                .find(|s| s.name == format!("{}_interior", j.name))
                .unwrap_or_else(|| panic!("{who}: `{}` has no interior", j.name));
            assert_eq!(inside.kind, SurfaceKind::Interior);
            assert!(
                inside.clearance.is_some_and(|c| c > 0.03),
                "{who}: clearance"
            );
            assert!(inside.height > whole.0[1] && inside.height < whole.1[1]);
            for p in &inside.polygon {
                assert!(p[0] > whole.0[0] && p[0] < whole.1[0], "{who}: interior x");
                assert!(p[1] > whole.0[2] && p[1] < whole.1[2], "{who}: interior z");
            }
        }
    }
    assert!(drawers > 50, "only {drawers} drawers");
}
