//! Built-in generators for containers and small items (things that stand on the floor or rest on,
//! in and under furniture). Dimensions per category are documented on each generator, in metres.

mod bathroom;
pub(crate) mod builder;
pub(crate) mod containers;
mod craft;
mod electronics;
mod home;
mod household;
mod kitchen;
mod lab;
mod media;
mod service;
mod tableware;

use crate::category::Generator;

/// The container and small-item generators of the registry, by category name (their rows are
/// in `data/categories.toml`).
pub(crate) const GENERATORS: &[(&str, Generator)] = &[
    // Containers.
    ("crate", containers::wooden_crate),
    ("box", containers::cardboard_box),
    ("storage_bin", containers::storage_bin),
    ("basket", containers::basket),
    ("barrel", containers::barrel),
    ("pallet", containers::pallet),
    ("shopping_basket", containers::shopping_basket),
    ("toolbox", containers::toolbox),
    ("cooler", containers::cooler),
    ("trash_can", containers::trash_can),
    ("bucket", containers::bucket),
    // Small items.
    ("book", home::book),
    ("magazine", home::magazine),
    ("mug", tableware::mug),
    ("cup", tableware::cup),
    ("plate", tableware::plate),
    ("bowl", tableware::bowl),
    ("vase", tableware::vase),
    ("bottle", tableware::bottle),
    ("can", tableware::can),
    ("fruit", tableware::fruit),
    ("cushion", home::cushion),
    ("picture_frame", home::picture_frame),
    ("toy_car", home::toy_car),
    ("teddy_bear", home::teddy_bear),
    ("toy_blocks", home::toy_blocks),
    ("ball", home::ball),
    ("dumbbell", home::dumbbell),
    ("kettlebell", home::kettlebell),
    ("water_bottle", tableware::water_bottle),
    ("beaker", lab::beaker),
    ("flask", lab::flask),
    ("test_tube_rack", lab::test_tube_rack),
    ("microscope", lab::microscope),
    ("paint_can", tableware::paint_can),
    ("table_lamp", home::table_lamp),
    ("laptop", electronics::laptop),
    ("monitor", electronics::monitor),
    ("keyboard", electronics::keyboard),
    ("television", electronics::television),
    ("cash_register", electronics::cash_register),
    ("patient_monitor", lab::patient_monitor),
    ("billiard_ball", home::billiard_ball),
    ("sculpture", home::sculpture),
    ("clock", home::clock),
    // Kitchen items.
    ("microwave", kitchen::microwave),
    ("toaster", kitchen::toaster),
    ("coffee_machine", kitchen::coffee_machine),
    ("kettle", kitchen::kettle),
    ("pot", kitchen::pot),
    ("pan", kitchen::pan),
    ("cutlery", kitchen::cutlery),
    ("cutting_board", kitchen::cutting_board),
    ("knife_block", kitchen::knife_block),
    ("dish_rack", kitchen::dish_rack),
    // Bathroom items.
    ("towel", bathroom::towel),
    ("toilet_paper", bathroom::toilet_paper),
    ("soap", bathroom::soap),
    ("toothbrush_holder", bathroom::toothbrush_holder),
    // Household items.
    ("remote_control", household::remote_control),
    ("phone", household::phone),
    ("keys", household::keys),
    ("alarm_clock", household::alarm_clock),
    ("printer", household::printer),
    // Craft machines.
    ("sewing_machine", craft::sewing_machine),
    ("pottery_wheel", craft::pottery_wheel),
    ("kiln", craft::kiln),
    // Media items.
    ("projector", media::projector),
    ("headphones", media::headphones),
    // Work, worship and service items.
    ("candle", service::candle),
    ("globe", service::globe),
];

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::catalog::generate;
    use scenethesis_scene_graph::{Asset, SurfaceKind};

    /// Checks the conventions every built-in asset must meet; returns the asset for more checks.
    pub(crate) fn check_asset(category: &crate::catalog::Category, seed: u64) -> Asset {
        let asset = generate(category, seed);
        let name = category.name;
        assert!(!asset.mesh.parts.is_empty(), "{name}: no parts");
        for part in &asset.mesh.parts {
            assert!(
                part.is_closed_and_oriented(),
                "{name}#{seed}: part {} not closed and oriented",
                part.name
            );
            assert!(
                part.signed_volume() > 0.0,
                "{name}#{seed}: part {} has no volume",
                part.name
            );
            assert!(
                part.material < asset.mesh.materials.len(),
                "{name}: bad material index"
            );
        }
        let b = asset.mesh.bounds().unwrap();
        assert!(
            b.min.y.abs() < 1e-5,
            "{name}#{seed}: lowest point at {}",
            b.min.y
        );
        assert!(
            (b.min.x + b.max.x).abs() < 1e-4 && (b.min.z + b.max.z).abs() < 1e-4,
            "{name}#{seed}: footprint not centred"
        );
        let size = asset.info.size;
        for k in 0..3 {
            assert!(
                ((b.max[k] - b.min[k]) as f32 - size[k]).abs() < 1e-4,
                "{name}: size mismatch"
            );
            let [lo, hi] = category.size_range[k];
            assert!(
                (lo..=hi).contains(&size[k]),
                "{name}#{seed}: size {size:?} outside {:?}",
                category.size_range
            );
        }
        assert_eq!(asset.info.front, [0.0, 0.0, 1.0]);
        assert_eq!(asset.info.placement, category.placement);
        for s in &asset.info.support_surfaces {
            assert!(s.area() > 0.0, "{name}: empty surface {}", s.name);
            assert!(
                s.height >= 0.0 && s.height <= size[1] + 1e-4,
                "{name}: surface {} at {}",
                s.name,
                s.height
            );
            let c = s.center();
            assert!(
                c[0].abs() <= size[0] / 2.0 && c[1].abs() <= size[2] / 2.0,
                "{name}: surface {} outside",
                s.name
            );
            if s.kind == SurfaceKind::Interior {
                assert!(
                    s.clearance.is_none(),
                    "{name}: open containers are open above"
                );
            }
        }
        asset
    }

    #[test]
    fn every_item_category_meets_the_conventions_for_several_seeds() {
        for category in
            crate::catalog::categories().filter(|c| GENERATORS.iter().any(|(n, _)| *n == c.name))
        {
            for seed in 0..6 {
                check_asset(category, seed);
            }
        }
    }

    #[test]
    fn generators_are_deterministic_and_vary_with_the_seed() {
        for category in
            crate::catalog::categories().filter(|c| GENERATORS.iter().any(|(n, _)| *n == c.name))
        {
            let a = generate(category, 11);
            assert_eq!(a, generate(category, 11), "{}", category.name);
            let varied = (12..20).any(|s| {
                let b = generate(category, s);
                b.info.size != a.info.size || b.mesh.materials != a.mesh.materials
            });
            assert!(varied, "{} does not vary with the seed", category.name);
        }
    }

    #[test]
    fn sizes_fall_in_the_documented_real_world_ranges() {
        let size = |name: &str, seed| {
            generate(crate::catalog::category(name).unwrap(), seed)
                .info
                .size
        };
        for seed in 0..8 {
            let mug = size("mug", seed);
            assert!(
                (0.075..=0.09).contains(&mug[2]) && (0.088..=0.105).contains(&mug[1]),
                "mug {mug:?}"
            );
            let book = size("book", seed);
            assert!(
                (0.02..=0.05).contains(&book[0])
                    && (0.21..=0.30).contains(&book[1])
                    && (0.15..=0.24).contains(&book[2]),
                "book {book:?}"
            );
            let tv = size("television", seed);
            assert!((0.72..=1.45).contains(&tv[0]), "television {tv:?}");
            let pallet = size("pallet", seed);
            assert!(
                (pallet[0] - 1.2).abs() < 1e-3 && pallet[1] < 0.16,
                "pallet {pallet:?}"
            );
        }
    }

    #[test]
    fn hollow_items_have_open_interiors_below_their_rims() {
        use nalgebra::Point3;
        for name in [
            "mug",
            "cup",
            "bowl",
            "bucket",
            "crate",
            "basket",
            "trash_can",
            "storage_bin",
            "shopping_basket",
            "beaker",
        ] {
            let asset = generate(crate::catalog::category(name).unwrap(), 3);
            let interior = asset
                .info
                .support_surfaces
                .iter()
                .find(|s| s.kind == SurfaceKind::Interior)
                .unwrap_or_else(|| panic!("{name} has no interior"));
            let c = interior.center();
            // A point just above the inner floor at the centre lies inside no part's convex hull:
            // the cavity is real, not a painted top.
            let probe = Point3::new(c[0], interior.height + 0.01, c[1]);
            for part in &asset.mesh.parts {
                let inside = part.triangles.iter().all(|t| {
                    let [a, b, c] = t.map(|i| Point3::from(part.positions[i as usize]));
                    (b - a).cross(&(c - a)).dot(&(probe - a)) <= 0.0
                });
                assert!(!inside, "{name}: part {} fills the cavity", part.name);
            }
            assert!(
                interior.height < asset.info.size[1] * 0.5,
                "{name}: interior floor too high"
            );
        }
    }
}
