//! Built-in furniture generators: seating, tables, storage, beds and care, equipment, music,
//! media and games, wall and ceiling assets, nursery, salon and clothing pieces, and work,
//! worship and service pieces (the furniture rows of `docs/asset-categories.md`).
//!
//! Generators are written as parametric families — a seat family, a table family and a carcass
//! family of boards with compartments — plus special cases. Every part is a convex primitive;
//! cavities (compartments, knee holes, the space under a table) come from arrangements of parts.
//! Each generator's doc comment gives the parameter ranges of its main body in metres; the
//! `size_range` of its row in the category table ([`crate::category::Category::size_range`])
//! gives the full extent over all seeds, including doors left open, lifted lids and protruding
//! parts, and crate tests check it.

mod bathroom;
mod beds;
mod carcass;
mod care;
mod equipment;
mod kitchen;
mod living;
mod media;
mod seating;
mod service;
mod storage;
mod tables;
mod wall;

use rand_chacha::ChaCha8Rng;

use crate::category::Generator;
use crate::materials::{pick_material, Palette};
use scenethesis_primitives::AssetBuilder;

/// The default range of uniform scale furniture may be given.
const SCALE: [f32; 2] = [0.85, 1.15];

/// Draws a material from `palette` and registers it with the builder.
fn mat(b: &mut AssetBuilder, palette: Palette, rng: &mut ChaCha8Rng) -> usize {
    let m = pick_material(palette, rng);
    b.material(m)
}

/// Draws a material from `likely` with probability `p`, otherwise from `otherwise`, and
/// registers it with the builder.
fn mat_either(
    b: &mut AssetBuilder,
    p: f64,
    likely: Palette,
    otherwise: Palette,
    rng: &mut ChaCha8Rng,
) -> usize {
    let palette = if crate::random::coin(rng, p) {
        likely
    } else {
        otherwise
    };
    mat(b, palette, rng)
}

/// The furniture generators of the registry, by category name (their names, words, placement
/// and size ranges are rows of `data/categories.toml`).
pub(crate) const GENERATORS: &[(&str, Generator)] = &[
    // Seating.
    ("sofa", seating::sofa),
    ("armchair", seating::armchair),
    ("chair", seating::chair),
    ("dining_chair", seating::dining_chair),
    ("office_chair", seating::office_chair),
    ("stool", seating::stool),
    ("bar_stool", seating::bar_stool),
    ("bench", seating::bench),
    ("piano_bench", seating::piano_bench),
    ("kids_chair", seating::kids_chair),
    ("bean_bag", seating::bean_bag),
    ("ottoman", seating::ottoman),
    ("camping_chair", seating::camping_chair),
    ("log_bench", seating::log_bench),
    ("lab_stool", seating::lab_stool),
    ("wheelchair", seating::wheelchair),
    // Tables.
    ("coffee_table", tables::coffee_table),
    ("side_table", tables::side_table),
    ("dining_table", tables::dining_table),
    ("desk", tables::desk),
    ("kids_table", tables::kids_table),
    ("display_table", tables::display_table),
    ("picnic_table", tables::picnic_table),
    ("high_table", tables::high_table),
    ("lab_bench", tables::lab_bench),
    ("workbench", tables::workbench),
    ("nightstand", tables::nightstand),
    ("pool_table", tables::pool_table),
    ("checkout_counter", tables::checkout_counter),
    ("bar_counter", tables::bar_counter),
    ("kitchen_counter", tables::kitchen_counter),
    // Storage.
    ("bookshelf", storage::bookshelf),
    ("display_shelf", storage::display_shelf),
    ("store_shelf", storage::store_shelf),
    ("cabinet", storage::cabinet),
    ("tool_cabinet", storage::tool_cabinet),
    ("chemical_cabinet", storage::chemical_cabinet),
    ("locker", storage::locker),
    ("wardrobe", storage::wardrobe),
    ("dresser", storage::dresser),
    ("tv_stand", storage::tv_stand),
    ("display_case", storage::display_case),
    ("toy_box", storage::toy_box),
    ("pallet_rack", storage::pallet_rack),
    ("shelving_unit", storage::shelving_unit),
    ("medical_cart", storage::medical_cart),
    ("refrigerator", storage::refrigerator),
    ("drinks_fridge", storage::drinks_fridge),
    ("chest_freezer", storage::chest_freezer),
    ("fume_hood", storage::fume_hood),
    ("magazine_rack", storage::magazine_rack),
    ("dumbbell_rack", storage::dumbbell_rack),
    ("cue_rack", storage::cue_rack),
    // Beds and care.
    ("bed", beds::bed),
    ("hospital_bed", beds::hospital_bed),
    ("iv_stand", beds::iv_stand),
    ("privacy_screen", beds::privacy_screen),
    // Equipment.
    ("treadmill", equipment::treadmill),
    ("exercise_bike", equipment::exercise_bike),
    ("weight_bench", equipment::weight_bench),
    ("squat_rack", equipment::squat_rack),
    ("grand_piano", equipment::grand_piano),
    ("upright_piano", equipment::upright_piano),
    ("music_stand", equipment::music_stand),
    ("easel", equipment::easel),
    ("rocking_horse", equipment::rocking_horse),
    ("stove", equipment::stove),
    ("sink", equipment::sink),
    ("ladder", equipment::ladder),
    ("tire", equipment::tire),
    ("coat_rack", equipment::coat_rack),
    ("pedestal", equipment::pedestal),
    ("stanchion", equipment::stanchion),
    ("floor_lamp", equipment::floor_lamp),
    ("plant", equipment::plant),
    ("rug", equipment::rug),
    ("yoga_mat", equipment::yoga_mat),
    // Bathroom and laundry.
    ("toilet", bathroom::toilet),
    ("bathtub", bathroom::bathtub),
    ("shower", bathroom::shower),
    ("towel_rack", bathroom::towel_rack),
    ("bath_mat", bathroom::bath_mat),
    ("standing_mirror", bathroom::standing_mirror),
    ("laundry_hamper", bathroom::laundry_hamper),
    ("washing_machine", bathroom::washing_machine),
    // Kitchen.
    ("kitchen_island", kitchen::kitchen_island),
    ("wall_cabinet", kitchen::wall_cabinet),
    ("range_hood", kitchen::range_hood),
    ("dishwasher", kitchen::dishwasher),
    // Living, hall and study.
    ("fireplace", living::fireplace),
    ("curtain", living::curtain),
    ("window_blind", living::window_blind),
    ("wall_clock", living::wall_clock),
    ("shoe_rack", living::shoe_rack),
    ("suitcase", living::suitcase),
    ("filing_cabinet", living::filing_cabinet),
    // Music, media and games.
    ("guitar", media::guitar),
    ("drum_kit", media::drum_kit),
    ("amplifier", media::amplifier),
    ("speaker", media::speaker),
    ("microphone_stand", media::microphone_stand),
    ("mixing_console", media::mixing_console),
    ("recliner", media::recliner),
    ("arcade_cabinet", media::arcade_cabinet),
    ("foosball_table", media::foosball_table),
    ("ping_pong_table", media::ping_pong_table),
    ("projector_screen", media::projector_screen),
    ("dartboard", media::dartboard),
    // Wall.
    ("painting", wall::painting),
    ("whiteboard", wall::whiteboard),
    ("wall_shelf", wall::wall_shelf),
    ("mirror", wall::mirror),
    // Ceiling.
    ("pendant_lamp", wall::pendant_lamp),
    // Care, nursery, salon and clothing.
    ("crib", care::crib),
    ("changing_table", care::changing_table),
    ("rocking_chair", care::rocking_chair),
    ("high_chair", care::high_chair),
    ("clothes_rack", care::clothes_rack),
    ("mannequin", care::mannequin),
    ("exam_table", care::exam_table),
    ("dental_chair", care::dental_chair),
    ("massage_table", care::massage_table),
    ("barber_chair", care::barber_chair),
    ("ironing_board", care::ironing_board),
    // Work, worship and service.
    ("vending_machine", service::vending_machine),
    ("wine_rack", service::wine_rack),
    ("server_rack", service::server_rack),
    ("pew", service::pew),
    ("altar", service::altar),
    ("lectern", service::lectern),
    ("water_cooler", service::water_cooler),
    ("photocopier", service::photocopier),
    ("safe", service::safe),
    ("treasure_chest", service::treasure_chest),
    ("punching_bag", service::punching_bag),
    ("bunk_bed", service::bunk_bed),
];
