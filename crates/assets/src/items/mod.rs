//! Built-in generators for containers and small items (things that stand on the floor or rest on,
//! in and under furniture). Dimensions per category are documented on each generator, in metres.

mod bathroom;
pub(crate) mod builder;
pub(crate) mod containers;
mod electronics;
mod home;
mod household;
mod kitchen;
mod lab;
mod tableware;

use crate::catalog::Category;
use crate::Placement::{Floor, Surface};

macro_rules! category {
    ($name:literal, [$($syn:literal),* $(,)?], $placement:expr, $size:expr, $generate:path) => {
        Category {
            name: $name,
            synonyms: &[$($syn),*],
            placement: $placement,
            size_range: $size,
            generate: $generate,
        }
    };
}

/// The container and small-item categories of the registry.
pub(crate) const CATEGORIES: &[Category] = &[
    // Containers.
    category!(
        "crate",
        ["wooden crate", "fruit crate", "slatted crate"],
        Floor,
        [[0.388, 0.618], [0.252, 0.371], [0.291, 0.432]],
        containers::wooden_crate
    ),
    category!(
        "box",
        ["cardboard box", "carton", "moving box", "parcel", "package"],
        Floor,
        [[0.247, 0.618], [0.176, 0.465], [0.216, 0.466]],
        containers::cardboard_box
    ),
    category!(
        "storage_bin",
        ["plastic bin", "tote", "storage box"],
        Floor,
        [[0.368, 0.639], [0.194, 0.371], [0.271, 0.433]],
        containers::storage_bin
    ),
    category!(
        "basket",
        ["wicker basket", "fruit basket", "bread basket"],
        Surface,
        [[0.221, 0.42], [0.116, 0.268], [0.221, 0.42]],
        containers::basket
    ),
    category!(
        "barrel",
        ["cask", "keg", "wine barrel"],
        Floor,
        [[0.523, 0.696], [0.777, 1.01], [0.523, 0.696]],
        containers::barrel
    ),
    category!(
        "pallet",
        ["skid", "wooden pallet", "shipping pallet"],
        Floor,
        [[1.164, 1.236], [0.135, 0.155], [0.776, 1.03]],
        containers::pallet
    ),
    category!(
        "shopping_basket",
        ["shop basket", "grocery basket", "hand basket"],
        Floor,
        [[0.388, 0.494], [0.194, 0.258], [0.298, 0.369]],
        containers::shopping_basket
    ),
    category!(
        "toolbox",
        ["tool box", "tool case"],
        Floor,
        [[0.376, 0.586], [0.198, 0.273], [0.195, 0.281]],
        containers::toolbox
    ),
    category!(
        "cooler",
        ["ice chest", "cool box", "esky", "ice box"],
        Floor,
        [[0.489, 0.766], [0.33, 0.474], [0.32, 0.464]],
        containers::cooler
    ),
    category!(
        "trash_can",
        [
            "garbage can",
            "bin",
            "waste bin",
            "wastebasket",
            "dustbin",
            "rubbish bin",
            "trash bin"
        ],
        Floor,
        [[0.213, 0.413], [0.292, 0.772], [0.213, 0.413]],
        containers::trash_can
    ),
    category!(
        "bucket",
        ["pail"],
        Floor,
        [[0.258, 0.357], [0.232, 0.33], [0.249, 0.347]],
        containers::bucket
    ),
    // Small items.
    category!(
        "book",
        ["novel", "hardcover", "textbook", "volume"],
        Surface,
        [[0.019, 0.052], [0.204, 0.309], [0.145, 0.248]],
        home::book
    ),
    category!(
        "magazine",
        ["journal", "periodical", "comic"],
        Surface,
        [[0.194, 0.237], [0.002, 0.011], [0.261, 0.309]],
        home::magazine
    ),
    category!(
        "mug",
        ["coffee mug", "tea mug"],
        Surface,
        [[0.099, 0.129], [0.085, 0.109], [0.072, 0.093]],
        tableware::mug
    ),
    category!(
        "cup",
        ["glass", "tumbler", "drinking glass", "paper cup", "teacup"],
        Surface,
        [[0.067, 0.093], [0.068, 0.124], [0.067, 0.093]],
        tableware::cup
    ),
    category!(
        "plate",
        ["dish", "dinner plate", "saucer"],
        Surface,
        [[0.194, 0.288], [0.017, 0.029], [0.194, 0.288]],
        tableware::plate
    ),
    category!(
        "bowl",
        ["salad bowl", "soup bowl", "cereal bowl"],
        Surface,
        [[0.116, 0.227], [0.048, 0.102], [0.116, 0.227]],
        tableware::bowl
    ),
    category!(
        "vase",
        ["flower vase", "urn", "jar"],
        Surface,
        [[0.077, 0.185], [0.175, 0.411], [0.077, 0.185]],
        tableware::vase
    ),
    category!(
        "bottle",
        ["wine bottle", "beer bottle", "glass bottle"],
        Surface,
        [[0.059, 0.085], [0.213, 0.33], [0.059, 0.085]],
        tableware::bottle
    ),
    category!(
        "can",
        ["soda can", "tin can", "drink can", "beer can", "soda"],
        Surface,
        [[0.06, 0.068], [0.111, 0.174], [0.06, 0.068]],
        tableware::can
    ),
    category!(
        "fruit",
        ["apple", "orange", "banana", "pear", "lemon"],
        Surface,
        [[0.052, 0.237], [0.032, 0.136], [0.034, 0.093]],
        tableware::fruit
    ),
    category!(
        "cushion",
        ["pillow", "throw pillow", "scatter cushion"],
        Surface,
        [[0.337, 0.563], [0.097, 0.165], [0.217, 0.563]],
        home::cushion
    ),
    category!(
        "picture_frame",
        ["photo frame", "photo", "framed photo"],
        Surface,
        [[0.126, 0.33], [0.126, 0.326], [0.054, 0.156]],
        home::picture_frame
    ),
    category!(
        "toy_car",
        ["model car", "toy truck", "toy vehicle"],
        Surface,
        [[0.05, 0.172], [0.037, 0.14], [0.097, 0.309]],
        home::toy_car
    ),
    category!(
        "teddy_bear",
        [
            "teddy",
            "stuffed animal",
            "plush toy",
            "soft toy",
            "plushie"
        ],
        Surface,
        [[0.113, 0.272], [0.18, 0.431], [0.103, 0.248]],
        home::teddy_bear
    ),
    category!(
        "toy_blocks",
        ["building blocks", "wooden blocks", "blocks"],
        Surface,
        [[0.091, 0.266], [0.087, 0.258], [0.033, 0.06]],
        home::toy_blocks
    ),
    category!(
        "ball",
        [
            "football",
            "soccer ball",
            "basketball",
            "volleyball",
            "tennis ball"
        ],
        Surface,
        [[0.064, 0.248], [0.064, 0.248], [0.064, 0.248]],
        home::ball
    ),
    category!(
        "dumbbell",
        ["hand weight", "free weight", "barbell"],
        Surface,
        [[0.242, 0.433], [0.097, 0.206], [0.097, 0.206]],
        home::dumbbell
    ),
    category!(
        "kettlebell",
        ["kettle bell"],
        Surface,
        [[0.135, 0.227], [0.179, 0.299], [0.135, 0.227]],
        home::kettlebell
    ),
    category!(
        "water_bottle",
        [
            "drinking bottle",
            "flask bottle",
            "sports bottle",
            "thermos"
        ],
        Surface,
        [[0.063, 0.083], [0.194, 0.279], [0.063, 0.083]],
        tableware::water_bottle
    ),
    category!(
        "beaker",
        ["lab beaker", "measuring beaker"],
        Surface,
        [[0.048, 0.093], [0.068, 0.134], [0.052, 0.097]],
        lab::beaker
    ),
    category!(
        "flask",
        ["erlenmeyer flask", "conical flask", "lab flask"],
        Surface,
        [[0.058, 0.134], [0.097, 0.206], [0.058, 0.134]],
        lab::flask
    ),
    category!(
        "test_tube_rack",
        ["test tubes", "test tube", "tube rack"],
        Surface,
        [[0.114, 0.262], [0.107, 0.154], [0.058, 0.062]],
        lab::test_tube_rack
    ),
    category!(
        "microscope",
        ["light microscope", "lab microscope"],
        Surface,
        [[0.129, 0.192], [0.276, 0.41], [0.169, 0.252]],
        lab::microscope
    ),
    category!(
        "paint_can",
        ["paint tin", "paint bucket", "paint pot"],
        Surface,
        [[0.117, 0.207], [0.116, 0.206], [0.109, 0.199]],
        tableware::paint_can
    ),
    category!(
        "table_lamp",
        ["desk lamp", "bedside lamp", "lamp"],
        Surface,
        [[0.194, 0.35], [0.31, 0.639], [0.194, 0.35]],
        home::table_lamp
    ),
    category!(
        "laptop",
        ["notebook computer", "notebook", "macbook", "computer"],
        Surface,
        [[0.291, 0.392], [0.192, 0.277], [0.251, 0.405]],
        electronics::laptop
    ),
    category!(
        "monitor",
        ["computer monitor", "computer screen", "display", "screen"],
        Surface,
        [[0.468, 0.741], [0.367, 0.565], [0.174, 0.248]],
        electronics::monitor
    ),
    category!(
        "keyboard",
        ["computer keyboard"],
        Surface,
        [[0.339, 0.474], [0.017, 0.031], [0.116, 0.165]],
        electronics::keyboard
    ),
    category!(
        "television",
        ["tv", "tv set", "telly", "flat screen", "flatscreen"],
        Surface,
        [[0.699, 1.492], [0.471, 0.949], [0.194, 0.309]],
        electronics::television
    ),
    category!(
        "cash_register",
        ["till", "register", "pos terminal", "checkout register"],
        Surface,
        [[0.32, 0.431], [0.378, 0.433], [0.349, 0.454]],
        electronics::cash_register
    ),
    category!(
        "patient_monitor",
        [
            "vital signs monitor",
            "heart monitor",
            "ecg monitor",
            "medical monitor"
        ],
        Surface,
        [[0.252, 0.371], [0.252, 0.33], [0.12, 0.19]],
        lab::patient_monitor
    ),
    category!(
        "billiard_ball",
        ["pool ball", "snooker ball", "cue ball"],
        Surface,
        [[0.055, 0.059], [0.051, 0.059], [0.055, 0.059]],
        home::billiard_ball
    ),
    category!(
        "sculpture",
        ["statue", "statuette", "figurine", "art piece", "bust"],
        Surface,
        [[0.1, 0.386], [0.187, 0.547], [0.1, 0.386]],
        home::sculpture
    ),
    category!(
        "clock",
        ["desk clock", "table clock", "mantel clock"],
        Surface,
        [[0.097, 0.227], [0.106, 0.249], [0.021, 0.06]],
        home::clock
    ),
    // Kitchen items.
    category!(
        "microwave",
        ["microwave oven", "micro wave"],
        Surface,
        [[0.431, 0.571], [0.257, 0.339], [0.352, 0.459]],
        kitchen::microwave
    ),
    category!(
        "toaster",
        ["bread toaster", "pop-up toaster"],
        Surface,
        [[0.18, 0.344], [0.176, 0.215], [0.162, 0.219]],
        kitchen::toaster
    ),
    category!(
        "coffee_machine",
        [
            "coffee maker",
            "espresso machine",
            "coffee brewer",
            "coffeemaker"
        ],
        Surface,
        [[0.177, 0.326], [0.294, 0.428], [0.245, 0.408]],
        kitchen::coffee_machine
    ),
    category!(
        "kettle",
        ["electric kettle", "tea kettle", "water kettle"],
        Surface,
        [[0.137, 0.204], [0.197, 0.286], [0.213, 0.28]],
        kitchen::kettle
    ),
    category!(
        "pot",
        [
            "cooking pot",
            "saucepan",
            "stock pot",
            "stockpot",
            "casserole"
        ],
        Surface,
        [[0.235, 0.366], [0.098, 0.224], [0.156, 0.284]],
        kitchen::pot
    ),
    category!(
        "pan",
        ["frying pan", "skillet", "fry pan", "frypan"],
        Surface,
        [[0.363, 0.56], [0.063, 0.092], [0.196, 0.306]],
        kitchen::pan
    ),
    category!(
        "cutlery",
        [
            "silverware",
            "flatware",
            "utensils",
            "knife and fork",
            "fork",
            "spoon",
            "knife"
        ],
        Surface,
        [[0.086, 0.115], [0.009, 0.013], [0.166, 0.225]],
        kitchen::cutlery
    ),
    category!(
        "cutting_board",
        ["chopping board", "chopping block", "bread board"],
        Surface,
        [[0.276, 0.467], [0.014, 0.036], [0.195, 0.325]],
        kitchen::cutting_board
    ),
    category!(
        "knife_block",
        ["knife holder", "knife stand"],
        Surface,
        [[0.098, 0.164], [0.266, 0.355], [0.174, 0.224]],
        kitchen::knife_block
    ),
    category!(
        "dish_rack",
        [
            "dish drainer",
            "drying rack",
            "dish drying rack",
            "plate rack"
        ],
        Surface,
        [[0.333, 0.51], [0.118, 0.204], [0.254, 0.367]],
        kitchen::dish_rack
    ),
    // Bathroom items.
    category!(
        "towel",
        ["towels", "bath towel", "hand towel", "folded towel"],
        Surface,
        [[0.255, 0.423], [0.029, 0.145], [0.176, 0.305]],
        bathroom::towel
    ),
    category!(
        "toilet_paper",
        [
            "toilet roll",
            "loo roll",
            "toilet tissue",
            "bathroom tissue"
        ],
        Surface,
        [[0.098, 0.249], [0.093, 0.118], [0.098, 0.123]],
        bathroom::toilet_paper
    ),
    category!(
        "soap",
        [
            "bar of soap",
            "soap bar",
            "soap dispenser",
            "hand soap",
            "soap dish"
        ],
        Surface,
        [[0.058, 0.143], [0.023, 0.209], [0.069, 0.101]],
        bathroom::soap
    ),
    category!(
        "toothbrush_holder",
        ["toothbrush", "toothbrushes", "toothbrush cup", "tooth mug"],
        Surface,
        [[0.062, 0.086], [0.19, 0.219], [0.062, 0.084]],
        bathroom::toothbrush_holder
    ),
    // Household items.
    category!(
        "remote_control",
        ["remote", "tv remote", "remote controller", "clicker"],
        Surface,
        [[0.039, 0.062], [0.016, 0.026], [0.137, 0.224]],
        household::remote_control
    ),
    category!(
        "phone",
        [
            "smartphone",
            "mobile phone",
            "cell phone",
            "telephone",
            "cellphone"
        ],
        Surface,
        [[0.063, 0.225], [0.008, 0.1], [0.137, 0.214]],
        household::phone
    ),
    category!(
        "keys",
        ["key", "keyring", "key ring", "bunch of keys", "house keys"],
        Surface,
        [[0.041, 0.161], [0.002, 0.004], [0.071, 0.098]],
        household::keys
    ),
    category!(
        "alarm_clock",
        ["bedside clock", "travel clock", "digital clock"],
        Surface,
        [[0.098, 0.159], [0.068, 0.141], [0.041, 0.082]],
        household::alarm_clock
    ),
    category!(
        "printer",
        [
            "inkjet printer",
            "laser printer",
            "printing machine",
            "all-in-one printer"
        ],
        Surface,
        [[0.372, 0.51], [0.201, 0.344], [0.356, 0.502]],
        household::printer
    ),
];

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::catalog::generate;
    use crate::{Asset, SurfaceKind};

    /// Checks the conventions every built-in asset must meet; returns the asset for more checks.
    pub(crate) fn check_asset(category: &Category, seed: u64) -> Asset {
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
        for category in CATEGORIES {
            for seed in 0..6 {
                check_asset(category, seed);
            }
        }
    }

    #[test]
    fn generators_are_deterministic_and_vary_with_the_seed() {
        for category in CATEGORIES {
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
