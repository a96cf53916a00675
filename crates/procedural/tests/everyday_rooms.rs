//! The categories everyday rooms need (bathrooms, kitchens, bedrooms, halls, studies): they are
//! registered, hollow where the real object is hollow, offer the support surfaces people use,
//! and stand stably on their base. The structural checks every category gets (closed parts,
//! size ranges, surfaces that hold a box) are in `catalog.rs`.

use scenethesis_procedural::catalog::{self, Category};
use scenethesis_scene_graph::nalgebra::Point3;
use scenethesis_scene_graph::{Asset, Placement, SurfaceKind};

/// The categories added for everyday rooms.
const EVERYDAY: &[&str] = &[
    "toilet",
    "bathtub",
    "shower",
    "towel_rack",
    "bath_mat",
    "standing_mirror",
    "laundry_hamper",
    "washing_machine",
    "dishwasher",
    "kitchen_island",
    "wall_cabinet",
    "range_hood",
    "fireplace",
    "curtain",
    "window_blind",
    "wall_clock",
    "shoe_rack",
    "suitcase",
    "filing_cabinet",
    "microwave",
    "toaster",
    "coffee_machine",
    "kettle",
    "pot",
    "pan",
    "cutlery",
    "cutting_board",
    "knife_block",
    "dish_rack",
    "towel",
    "toilet_paper",
    "soap",
    "toothbrush_holder",
    "remote_control",
    "phone",
    "keys",
    "alarm_clock",
    "printer",
];

fn category(name: &str) -> &'static Category {
    catalog::category(name).unwrap_or_else(|| panic!("`{name}` is not registered"))
}

fn kinds(asset: &Asset) -> Vec<SurfaceKind> {
    asset.info.support_surfaces.iter().map(|s| s.kind).collect()
}

/// Whether `p` lies inside the convex hull of some part (every part is convex).
fn inside_some_part(asset: &Asset, p: Point3<f32>) -> Option<String> {
    asset.mesh.parts.iter().find_map(|part| {
        let inside = part.triangles.iter().all(|t| {
            let [a, b, c] = t.map(|i| Point3::from(part.positions[i as usize]));
            (b - a).cross(&(c - a)).dot(&(p - a)) <= 0.0
        });
        inside.then(|| part.name.clone())
    })
}

#[test]
fn every_everyday_category_is_registered_once() {
    for name in EVERYDAY {
        assert_eq!(
            catalog::categories().filter(|c| c.name == *name).count(),
            1,
            "{name}"
        );
    }
}

#[test]
fn hollow_things_have_real_cavities() {
    for name in [
        "bathtub",
        "shower",
        "laundry_hamper",
        "pot",
        "pan",
        "dish_rack",
    ] {
        for seed in 0..6 {
            let asset = catalog::generate(category(name), seed);
            let interior = asset
                .info
                .support_surfaces
                .iter()
                .find(|s| s.kind == SurfaceKind::Interior)
                .unwrap_or_else(|| panic!("{name} #{seed}: no interior"));
            let [cx, cz] = interior.center();
            // Just above the inner floor and halfway up the walls: no part fills the hollow.
            let top = asset.info.size[1];
            for y in [interior.height + 0.005, 0.5 * (interior.height + top)] {
                if let Some(part) = inside_some_part(&asset, Point3::new(cx, y, cz)) {
                    panic!("{name} #{seed}: part `{part}` fills the cavity at y = {y:.3}");
                }
            }
            assert!(
                interior.height < 0.5 * top,
                "{name} #{seed}: the inner floor is not low in the object"
            );
        }
    }
    // A dishwasher's tub behind its closed door is hollow: between the racks, from the back
    // wall to the door, no part fills it.
    for seed in 0..6 {
        let dw = catalog::generate(category("dishwasher"), seed);
        let part = |name: &str| {
            let p = dw
                .mesh
                .parts
                .iter()
                .find(|p| p.name == name)
                .unwrap_or_else(|| panic!("dishwasher #{seed}: no `{name}`"));
            let ys = p.positions.iter().map(|v| v[1]);
            (
                ys.clone().fold(f32::MAX, f32::min),
                ys.fold(f32::MIN, f32::max),
            )
        };
        let (_, lower) = part("rack_lower");
        let (upper, _) = part("rack_upper");
        let y = 0.5 * (lower + upper);
        let b = dw.mesh.bounds().unwrap();
        let depth = (b.max.z - b.min.z) as f32;
        for f in [0.2f32, 0.5, 0.75] {
            let z = b.min.z as f32 + f * depth;
            if let Some(part) = inside_some_part(&dw, Point3::new(0.0, y, z)) {
                panic!("dishwasher #{seed}: part `{part}` fills the tub at z = {z:.3}");
            }
        }
        assert!(upper - lower > 0.2, "dishwasher #{seed}: racks too close");
    }
    // A toaster's slots and a toilet roll's core are open from top to bottom of the body.
    for seed in 0..6 {
        let roll = catalog::generate(category("toilet_paper"), seed);
        let b = roll.mesh.bounds().unwrap();
        let n = roll
            .mesh
            .parts
            .iter()
            .filter(|p| p.name.starts_with("roll_") && p.name.ends_with("_0"))
            .count();
        assert!(n >= 1, "toilet_paper #{seed}: no roll");
        // The first roll's axis: the mean of its wall slabs' vertices.
        let verts: Vec<[f32; 3]> = roll
            .mesh
            .parts
            .iter()
            .filter(|p| p.name.starts_with("roll_0_"))
            .flat_map(|p| p.positions.iter().copied())
            .collect();
        let ax = verts.iter().map(|v| v[0]).sum::<f32>() / verts.len() as f32;
        let az = verts.iter().map(|v| v[2]).sum::<f32>() / verts.len() as f32;
        let mid = 0.5 * (b.min.y + b.max.y) as f32;
        assert!(
            inside_some_part(&roll, Point3::new(ax, mid, az)).is_none(),
            "toilet_paper #{seed}: the core is filled"
        );
    }
}

#[test]
fn things_people_put_things_on_have_the_surfaces_for_it() {
    let expect = [
        ("toilet", SurfaceKind::Top),
        ("washing_machine", SurfaceKind::Top),
        ("dishwasher", SurfaceKind::Top),
        ("kitchen_island", SurfaceKind::Top),
        ("kitchen_island", SurfaceKind::Shelf),
        ("kitchen_island", SurfaceKind::Under),
        ("wall_cabinet", SurfaceKind::Shelf),
        ("shoe_rack", SurfaceKind::Shelf),
        ("fireplace", SurfaceKind::Top),
        ("filing_cabinet", SurfaceKind::Top),
        ("microwave", SurfaceKind::Top),
        ("coffee_machine", SurfaceKind::Shelf),
        ("cutting_board", SurfaceKind::Top),
        ("towel", SurfaceKind::Top),
        ("printer", SurfaceKind::Top),
        ("bath_mat", SurfaceKind::Top),
    ];
    for (name, kind) in expect {
        for seed in 0..4 {
            let asset = catalog::generate(category(name), seed);
            assert!(
                kinds(&asset).contains(&kind),
                "{name} #{seed}: no {kind:?} surface (has {:?})",
                kinds(&asset)
            );
        }
    }
    // The coffee machine's cup bay fits a mug (≥ 0.09 m clear).
    for seed in 0..8 {
        let asset = catalog::generate(category("coffee_machine"), seed);
        let bay = asset
            .info
            .support_surfaces
            .iter()
            .find(|s| s.kind == SurfaceKind::Shelf)
            .unwrap();
        assert!(
            bay.clearance.unwrap() >= 0.09,
            "coffee_machine #{seed}: cup bay {:?}",
            bay.clearance
        );
    }
}

/// The volume-weighted centre of mass of all parts (parts are closed and outward-oriented).
fn centre_of_mass(asset: &Asset) -> [f32; 3] {
    let (mut m, mut c) = (0.0f64, [0.0f64; 3]);
    for part in &asset.mesh.parts {
        for t in &part.triangles {
            let [a, b, d] = t.map(|i| part.positions[i as usize].map(f64::from));
            let v = (a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0])
                + a[2] * (b[0] * d[1] - b[1] * d[0]))
                / 6.0;
            m += v;
            for k in 0..3 {
                c[k] += v * (a[k] + b[k] + d[k]) / 4.0;
            }
        }
    }
    c.map(|x| (x / m) as f32)
}

#[test]
fn floor_and_surface_objects_stand_stably_on_their_base() {
    for name in EVERYDAY {
        let c = category(name);
        if matches!(c.placement, Placement::Wall | Placement::Ceiling) {
            continue;
        }
        for seed in 0..8 {
            let asset = catalog::generate(c, seed);
            // The contact points: every vertex within 3 mm of the lowest point.
            let contact: Vec<[f32; 2]> = asset
                .mesh
                .parts
                .iter()
                .flat_map(|p| p.positions.iter())
                .filter(|v| v[1] < 0.003)
                .map(|v| [v[0], v[2]])
                .collect();
            assert!(
                !contact.is_empty(),
                "{name} #{seed}: nothing touches the ground"
            );
            let (x0, x1) = contact
                .iter()
                .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), p| {
                    (lo.min(p[0]), hi.max(p[0]))
                });
            let (z0, z1) = contact
                .iter()
                .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), p| {
                    (lo.min(p[1]), hi.max(p[1]))
                });
            let com = centre_of_mass(&asset);
            // Inside the contact rectangle with a margin of 10 % of its extent (2 mm at least).
            let mx = (0.1 * (x1 - x0)).max(0.002);
            let mz = (0.1 * (z1 - z0)).max(0.002);
            assert!(
                com[0] > x0 + mx && com[0] < x1 - mx && com[2] > z0 + mz && com[2] < z1 - mz,
                "{name} #{seed}: centre of mass ({:.3}, {:.3}) outside the base [{x0:.3}, {x1:.3}] × [{z0:.3}, {z1:.3}]",
                com[0],
                com[2]
            );
        }
    }
}

#[test]
fn wall_pieces_are_flat_against_the_wall() {
    for name in EVERYDAY {
        let c = category(name);
        if c.placement != Placement::Wall {
            continue;
        }
        for seed in 0..6 {
            let asset = catalog::generate(c, seed);
            let size = asset.info.size;
            assert!(
                size[2] < 0.6 && size[2] < size[0],
                "{name} #{seed}: {size:?} is too deep for a wall piece"
            );
        }
    }
}
