//! Built-in furniture generators: seating, tables, storage, beds and care, equipment, wall and
//! ceiling assets (the furniture rows of `docs/asset-categories.md`).
//!
//! Generators are written as parametric families — a seat family, a table family and a carcass
//! family of boards with compartments — plus special cases. Every part is a convex primitive;
//! cavities (compartments, knee holes, the space under a table) come from arrangements of parts.
//! Each generator's doc comment gives the parameter ranges of its main body in metres; the
//! registry's [`Category::size_range`] gives the full extent over all seeds, including doors
//! left open, lifted lids and protruding parts, and crate tests check it.

mod bathroom;
mod beds;
mod carcass;
mod equipment;
mod kitchen;
mod living;
mod seating;
mod storage;
mod tables;
mod wall;

use rand_chacha::ChaCha8Rng;

use crate::catalog::Category;
use crate::primitives::{pick_material, AssetBuilder, Palette};
use crate::Placement;

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

macro_rules! furniture {
    ($name:literal, $placement:ident, [$($syn:literal),* $(,)?], $size:expr, $generate:path) => {
        Category {
            name: $name,
            synonyms: &[$($syn),*],
            placement: Placement::$placement,
            size_range: $size,
            generate: $generate,
        }
    };
}

/// The furniture categories of the registry.
pub(crate) const CATEGORIES: &[Category] = &[
    // Seating.
    furniture!(
        "sofa",
        Floor,
        [
            "couch",
            "settee",
            "loveseat",
            "three-seat sofa",
            "sectional"
        ],
        [[1.6, 2.4], [0.75, 0.95], [0.82, 1.0]],
        seating::sofa
    ),
    furniture!(
        "armchair",
        Floor,
        ["easy chair", "lounge chair", "club chair", "reading chair"],
        [[0.75, 0.98], [0.75, 0.95], [0.78, 0.95]],
        seating::armchair
    ),
    furniture!(
        "chair",
        Floor,
        ["side chair", "seat", "wooden chair"],
        [[0.42, 0.56], [0.76, 1.0], [0.44, 0.6]],
        seating::chair
    ),
    furniture!(
        "dining_chair",
        Floor,
        ["kitchen chair", "upholstered chair"],
        [[0.44, 0.56], [0.82, 1.05], [0.48, 0.64]],
        seating::dining_chair
    ),
    furniture!(
        "office_chair",
        Floor,
        ["desk chair", "swivel chair", "task chair", "computer chair"],
        [[0.5, 0.72], [0.86, 1.25], [0.5, 0.75]],
        seating::office_chair
    ),
    furniture!(
        "stool",
        Floor,
        ["round stool"],
        [[0.3, 0.6], [0.44, 0.54], [0.3, 0.6]],
        seating::stool
    ),
    furniture!(
        "bar_stool",
        Floor,
        ["counter stool", "high stool", "barstool"],
        [[0.3, 0.62], [0.64, 1.12], [0.3, 0.66]],
        seating::bar_stool
    ),
    furniture!(
        "bench",
        Floor,
        ["seating bench", "wooden bench", "park bench"],
        [[0.9, 1.8], [0.42, 0.48], [0.32, 0.45]],
        seating::bench
    ),
    furniture!(
        "piano_bench",
        Floor,
        ["piano stool", "piano seat", "keyboard bench"],
        [[0.75, 0.95], [0.48, 0.52], [0.33, 0.4]],
        seating::piano_bench
    ),
    furniture!(
        "kids_chair",
        Floor,
        [
            "child chair",
            "children's chair",
            "toddler chair",
            "small chair"
        ],
        [[0.3, 0.4], [0.48, 0.66], [0.3, 0.4]],
        seating::kids_chair
    ),
    furniture!(
        "bean_bag",
        Floor,
        ["beanbag", "bean bag chair", "floor cushion", "pouf"],
        [[0.7, 1.0], [0.6, 0.9], [0.7, 1.0]],
        seating::bean_bag
    ),
    furniture!(
        "ottoman",
        Floor,
        ["footrest", "pouffe", "hassock", "footstool"],
        [[0.45, 0.9], [0.38, 0.46], [0.45, 0.7]],
        seating::ottoman
    ),
    furniture!(
        "camping_chair",
        Floor,
        ["folding chair", "camp chair", "deck chair", "lawn chair"],
        [[0.5, 0.7], [0.78, 0.95], [0.5, 0.72]],
        seating::camping_chair
    ),
    furniture!(
        "log_bench",
        Floor,
        ["log seat", "tree trunk bench", "rustic bench"],
        [[1.0, 2.0], [0.4, 0.48], [0.24, 0.42]],
        seating::log_bench
    ),
    furniture!(
        "lab_stool",
        Floor,
        ["laboratory stool", "drafting stool", "swivel stool"],
        [[0.5, 0.62], [0.55, 0.76], [0.5, 0.62]],
        seating::lab_stool
    ),
    furniture!(
        "wheelchair",
        Floor,
        ["wheel chair", "transport chair"],
        [[0.6, 0.72], [0.86, 0.98], [0.8, 1.05]],
        seating::wheelchair
    ),
    // Tables.
    furniture!(
        "coffee_table",
        Floor,
        [
            "cocktail table",
            "low table",
            "centre table",
            "center table"
        ],
        [[0.7, 1.3], [0.38, 0.46], [0.5, 1.0]],
        tables::coffee_table
    ),
    furniture!(
        "side_table",
        Floor,
        [
            "end table",
            "accent table",
            "lamp table",
            "occasional table"
        ],
        [[0.4, 0.6], [0.5, 0.65], [0.4, 0.6]],
        tables::side_table
    ),
    furniture!(
        "dining_table",
        Floor,
        ["kitchen table", "dinner table", "table"],
        [[1.0, 2.0], [0.74, 0.78], [0.8, 1.3]],
        tables::dining_table
    ),
    furniture!(
        "desk",
        Floor,
        ["writing desk", "office desk", "computer desk", "study desk"],
        [[1.1, 1.7], [0.72, 0.77], [0.6, 0.8]],
        tables::desk
    ),
    furniture!(
        "kids_table",
        Floor,
        [
            "children's table",
            "play table",
            "activity table",
            "child table"
        ],
        [[0.6, 1.2], [0.45, 0.55], [0.5, 0.9]],
        tables::kids_table
    ),
    furniture!(
        "display_table",
        Floor,
        [
            "merchandise table",
            "book table",
            "exhibition table",
            "showcase table"
        ],
        [[1.0, 1.8], [0.75, 0.92], [0.6, 0.95]],
        tables::display_table
    ),
    furniture!(
        "picnic_table",
        Floor,
        ["picnic bench", "outdoor table", "park table"],
        [[1.5, 2.1], [0.72, 0.78], [1.6, 2.0]],
        tables::picnic_table
    ),
    furniture!(
        "high_table",
        Floor,
        ["bar table", "pub table", "standing table", "bistro table"],
        [[0.6, 0.9], [1.0, 1.1], [0.6, 0.9]],
        tables::high_table
    ),
    furniture!(
        "lab_bench",
        Floor,
        [
            "laboratory bench",
            "lab table",
            "laboratory workbench",
            "lab counter"
        ],
        [[1.5, 2.4], [1.3, 1.55], [0.75, 0.9]],
        tables::lab_bench
    ),
    furniture!(
        "workbench",
        Floor,
        ["work bench", "work table", "tool bench", "garage bench"],
        [[1.2, 2.0], [0.85, 1.75], [0.6, 0.8]],
        tables::workbench
    ),
    furniture!(
        "nightstand",
        Floor,
        ["bedside table", "night table", "bedside cabinet"],
        [[0.4, 0.56], [0.5, 0.68], [0.35, 0.48]],
        tables::nightstand
    ),
    furniture!(
        "pool_table",
        Floor,
        ["billiard table", "snooker table", "billiards table"],
        [[2.3, 2.91], [0.78, 0.82], [1.3, 1.66]],
        tables::pool_table
    ),
    furniture!(
        "checkout_counter",
        Floor,
        [
            "cash desk",
            "checkout",
            "till counter",
            "sales counter",
            "register counter"
        ],
        [[1.4, 2.42], [0.9, 1.0], [0.6, 0.8]],
        tables::checkout_counter
    ),
    furniture!(
        "bar_counter",
        Floor,
        ["bar", "bar top", "serving counter"],
        [[1.8, 3.02], [1.05, 1.15], [0.55, 0.75]],
        tables::bar_counter
    ),
    furniture!(
        "kitchen_counter",
        Floor,
        ["countertop", "kitchen cabinet", "base cabinet", "worktop"],
        [[1.2, 2.57], [0.88, 0.92], [0.6, 1.27]],
        tables::kitchen_counter
    ),
    // Storage.
    furniture!(
        "bookshelf",
        Floor,
        [
            "bookcase",
            "book shelf",
            "shelf",
            "shelves",
            "tall bookshelf"
        ],
        [[0.6, 1.2], [1.6, 2.1], [0.28, 0.38]],
        storage::bookshelf
    ),
    furniture!(
        "display_shelf",
        Floor,
        ["display rack", "etagere", "open shelf", "showcase shelf"],
        [[0.8, 1.4], [1.2, 1.9], [0.3, 0.45]],
        storage::display_shelf
    ),
    furniture!(
        "store_shelf",
        Floor,
        [
            "gondola",
            "shop shelf",
            "supermarket shelf",
            "retail shelving",
            "grocery shelf"
        ],
        [[0.9, 1.33], [1.4, 2.0], [0.45, 0.6]],
        storage::store_shelf
    ),
    furniture!(
        "cabinet",
        Floor,
        ["cupboard", "storage cabinet", "sideboard", "credenza"],
        [[0.6, 1.36], [0.8, 1.9], [0.4, 1.2]],
        storage::cabinet
    ),
    furniture!(
        "tool_cabinet",
        Floor,
        [
            "tool chest",
            "rolling tool cabinet",
            "toolbox cabinet",
            "tool cart"
        ],
        [[0.6, 1.05], [0.85, 1.15], [0.45, 0.55]],
        storage::tool_cabinet
    ),
    furniture!(
        "chemical_cabinet",
        Floor,
        [
            "safety cabinet",
            "flammables cabinet",
            "reagent cabinet",
            "acid cabinet"
        ],
        [[0.6, 1.39], [0.9, 1.8], [0.45, 1.24]],
        storage::chemical_cabinet
    ),
    furniture!(
        "locker",
        Floor,
        ["lockers", "locker bank", "gym locker", "school locker"],
        [[0.3, 1.69], [1.7, 1.95], [0.42, 0.95]],
        storage::locker
    ),
    furniture!(
        "wardrobe",
        Floor,
        ["closet", "armoire", "clothes cabinet"],
        [[0.9, 1.73], [1.9, 2.2], [0.55, 1.45]],
        storage::wardrobe
    ),
    furniture!(
        "dresser",
        Floor,
        ["chest of drawers", "bureau", "drawer chest", "commode"],
        [[0.8, 1.5], [0.75, 1.05], [0.45, 0.58]],
        storage::dresser
    ),
    furniture!(
        "tv_stand",
        Floor,
        [
            "tv cabinet",
            "media console",
            "entertainment unit",
            "tv bench",
            "media unit"
        ],
        [[1.2, 2.0], [0.4, 0.6], [0.35, 0.5]],
        storage::tv_stand
    ),
    furniture!(
        "display_case",
        Floor,
        [
            "vitrine",
            "showcase",
            "glass cabinet",
            "curio cabinet",
            "museum case"
        ],
        [[0.6, 1.5], [0.95, 2.0], [0.4, 0.6]],
        storage::display_case
    ),
    furniture!(
        "toy_box",
        Floor,
        ["toy chest", "toy storage", "toy bin"],
        [[0.6, 1.0], [0.75, 1.1], [0.41, 0.75]],
        storage::toy_box
    ),
    furniture!(
        "pallet_rack",
        Floor,
        [
            "warehouse rack",
            "racking",
            "industrial shelving",
            "storage rack"
        ],
        [[1.8, 2.8], [2.0, 3.4], [0.9, 1.1]],
        storage::pallet_rack
    ),
    furniture!(
        "shelving_unit",
        Floor,
        [
            "metal shelving",
            "wire shelf",
            "utility shelf",
            "storage shelf",
            "garage shelf"
        ],
        [[0.9, 1.2], [1.5, 1.9], [0.35, 0.6]],
        storage::shelving_unit
    ),
    furniture!(
        "medical_cart",
        Floor,
        [
            "medicine cart",
            "crash cart",
            "hospital trolley",
            "procedure cart"
        ],
        [[0.55, 0.9], [0.85, 0.98], [0.42, 0.56]],
        storage::medical_cart
    ),
    furniture!(
        "refrigerator",
        Floor,
        ["fridge", "refrigerator freezer", "icebox"],
        [[0.6, 0.93], [1.7, 1.95], [0.65, 1.5]],
        storage::refrigerator
    ),
    furniture!(
        "drinks_fridge",
        Floor,
        [
            "beverage cooler",
            "drinks cooler",
            "display fridge",
            "glass door fridge",
            "merchandiser"
        ],
        [[0.55, 0.75], [1.75, 2.05], [0.6, 0.7]],
        storage::drinks_fridge
    ),
    furniture!(
        "chest_freezer",
        Floor,
        ["deep freezer", "freezer", "ice cream freezer"],
        [[0.9, 1.6], [1.4, 1.65], [0.65, 0.96]],
        storage::chest_freezer
    ),
    furniture!(
        "fume_hood",
        Floor,
        ["fume cupboard", "laboratory hood", "extraction hood"],
        [[1.2, 1.8], [2.3, 2.5], [0.77, 0.92]],
        storage::fume_hood
    ),
    furniture!(
        "magazine_rack",
        Floor,
        [
            "magazine stand",
            "newspaper rack",
            "literature rack",
            "brochure stand"
        ],
        [[0.45, 0.9], [0.8, 1.3], [0.28, 0.4]],
        storage::magazine_rack
    ),
    furniture!(
        "dumbbell_rack",
        Floor,
        ["weight rack", "dumbbell stand", "free weight rack"],
        [[1.0, 2.0], [0.65, 0.9], [0.45, 0.6]],
        storage::dumbbell_rack
    ),
    furniture!(
        "cue_rack",
        Floor,
        ["cue stand", "billiard cue rack", "cue holder"],
        [[0.45, 0.8], [1.2, 1.5], [0.25, 0.35]],
        storage::cue_rack
    ),
    // Beds and care.
    furniture!(
        "bed",
        Floor,
        [
            "double bed",
            "single bed",
            "queen bed",
            "king bed",
            "twin bed"
        ],
        [[0.98, 1.9], [0.85, 1.3], [2.05, 2.26]],
        beds::bed
    ),
    furniture!(
        "hospital_bed",
        Floor,
        ["patient bed", "medical bed", "ward bed", "gurney"],
        [[0.95, 1.12], [0.9, 1.2], [2.15, 2.4]],
        beds::hospital_bed
    ),
    furniture!(
        "iv_stand",
        Floor,
        ["iv pole", "drip stand", "infusion stand"],
        [[0.45, 0.62], [1.7, 2.1], [0.45, 0.65]],
        beds::iv_stand
    ),
    furniture!(
        "privacy_screen",
        Floor,
        [
            "folding screen",
            "room divider",
            "partition",
            "medical screen"
        ],
        [[1.0, 2.12], [1.6, 1.85], [0.15, 0.55]],
        beds::privacy_screen
    ),
    // Equipment.
    furniture!(
        "treadmill",
        Floor,
        ["running machine", "treadmill machine"],
        [[0.75, 0.92], [1.3, 1.5], [1.7, 2.0]],
        equipment::treadmill
    ),
    furniture!(
        "exercise_bike",
        Floor,
        ["stationary bike", "spin bike", "exercise bicycle"],
        [[0.5, 0.65], [1.09, 1.35], [1.0, 1.34]],
        equipment::exercise_bike
    ),
    furniture!(
        "weight_bench",
        Floor,
        ["workout bench", "flat bench", "bench press"],
        [[0.5, 0.66], [0.43, 1.2], [1.0, 1.4]],
        equipment::weight_bench
    ),
    furniture!(
        "squat_rack",
        Floor,
        ["power rack", "squat cage", "barbell rack"],
        [[2.0, 2.2], [2.1, 2.4], [1.0, 1.56]],
        equipment::squat_rack
    ),
    furniture!(
        "grand_piano",
        Floor,
        ["baby grand piano", "piano", "concert grand"],
        [[1.45, 1.6], [1.3, 2.2], [1.75, 2.6]],
        equipment::grand_piano
    ),
    furniture!(
        "upright_piano",
        Floor,
        ["vertical piano", "console piano"],
        [[1.45, 1.55], [1.1, 1.32], [0.55, 0.65]],
        equipment::upright_piano
    ),
    furniture!(
        "music_stand",
        Floor,
        ["sheet music stand", "score stand"],
        [[0.45, 0.55], [1.0, 1.45], [0.39, 0.6]],
        equipment::music_stand
    ),
    furniture!(
        "easel",
        Floor,
        ["painting easel", "art easel", "display easel"],
        [[0.5, 0.75], [1.5, 1.9], [0.55, 0.8]],
        equipment::easel
    ),
    furniture!(
        "rocking_horse",
        Floor,
        ["toy horse", "hobby horse", "rocker"],
        [[0.3, 0.42], [0.6, 0.95], [0.85, 1.17]],
        equipment::rocking_horse
    ),
    furniture!(
        "stove",
        Floor,
        ["range", "cooker", "oven", "cooktop", "kitchen stove"],
        [[0.6, 0.9], [0.97, 1.12], [0.6, 0.78]],
        equipment::stove
    ),
    furniture!(
        "sink",
        Floor,
        ["basin", "vanity", "wash basin", "kitchen sink", "lab sink"],
        [[0.5, 1.0], [0.95, 1.2], [0.45, 0.6]],
        equipment::sink
    ),
    furniture!(
        "ladder",
        Floor,
        ["step ladder", "stepladder", "step stool"],
        [[0.45, 0.55], [0.9, 1.9], [0.4, 0.95]],
        equipment::ladder
    ),
    furniture!(
        "tire",
        Floor,
        ["tyre", "car tire", "wheel", "rubber tire"],
        [[0.55, 0.82], [0.16, 0.3], [0.55, 0.82]],
        equipment::tire
    ),
    furniture!(
        "coat_rack",
        Floor,
        ["coat stand", "hat stand", "hall tree", "coat tree"],
        [[0.4, 0.65], [1.7, 1.97], [0.4, 0.65]],
        equipment::coat_rack
    ),
    furniture!(
        "pedestal",
        Floor,
        [
            "plinth",
            "display pedestal",
            "column stand",
            "sculpture stand"
        ],
        [[0.3, 0.6], [0.75, 1.15], [0.3, 0.6]],
        equipment::pedestal
    ),
    furniture!(
        "stanchion",
        Floor,
        [
            "queue post",
            "barrier post",
            "rope stanchion",
            "crowd control post"
        ],
        [[0.3, 0.36], [0.9, 1.0], [0.3, 0.36]],
        equipment::stanchion
    ),
    furniture!(
        "floor_lamp",
        Floor,
        [
            "standing lamp",
            "standard lamp",
            "torchiere",
            "reading lamp"
        ],
        [[0.28, 0.55], [1.4, 1.85], [0.28, 0.55]],
        equipment::floor_lamp
    ),
    furniture!(
        "plant",
        Floor,
        [
            "potted plant",
            "houseplant",
            "indoor plant",
            "fern",
            "ficus",
            "plant pot"
        ],
        [[0.24, 1.0], [0.5, 1.8], [0.24, 1.0]],
        equipment::plant
    ),
    furniture!(
        "rug",
        Floor,
        ["carpet", "area rug", "mat", "runner"],
        [[1.2, 3.0], [0.008, 0.015], [0.8, 2.4]],
        equipment::rug
    ),
    furniture!(
        "yoga_mat",
        Floor,
        ["exercise mat", "fitness mat", "gym mat"],
        [[0.58, 0.66], [0.004, 0.15], [0.12, 1.85]],
        equipment::yoga_mat
    ),
    // Bathroom and laundry.
    furniture!(
        "toilet",
        Floor,
        ["wc", "loo", "water closet", "lavatory", "toilet bowl"],
        [[0.352, 0.428], [0.711, 0.902], [0.562, 0.693]],
        bathroom::toilet
    ),
    furniture!(
        "bathtub",
        Floor,
        ["bath", "tub", "bath tub", "clawfoot tub", "soaking tub"],
        [[1.472, 1.833], [0.609, 0.807], [0.686, 0.816]],
        bathroom::bathtub
    ),
    furniture!(
        "shower",
        Floor,
        [
            "shower stall",
            "shower cubicle",
            "shower enclosure",
            "walk-in shower",
            "shower cabin"
        ],
        [[0.786, 1.019], [1.911, 2.061], [0.784, 1.019]],
        bathroom::shower
    ),
    furniture!(
        "towel_rack",
        Wall,
        [
            "towel rail",
            "towel bar",
            "towel holder",
            "heated towel rail"
        ],
        [[0.447, 0.814], [0.058, 0.916], [0.081, 0.119]],
        bathroom::towel_rack
    ),
    furniture!(
        "bath_mat",
        Floor,
        ["bathmat", "bath rug", "shower mat"],
        [[0.489, 0.914], [0.009, 0.026], [0.393, 0.61]],
        bathroom::bath_mat
    ),
    furniture!(
        "standing_mirror",
        Floor,
        [
            "wardrobe mirror",
            "floor mirror",
            "full-length mirror",
            "full length mirror",
            "cheval mirror",
            "dressing mirror"
        ],
        [[0.392, 0.906], [1.429, 1.929], [0.295, 0.623]],
        bathroom::standing_mirror
    ),
    furniture!(
        "laundry_hamper",
        Floor,
        ["hamper", "laundry basket", "clothes hamper", "laundry bin"],
        [[0.343, 0.559], [0.49, 0.713], [0.325, 0.47]],
        bathroom::laundry_hamper
    ),
    furniture!(
        "washing_machine",
        Floor,
        [
            "washer",
            "washing-machine",
            "laundry machine",
            "clothes washer"
        ],
        [[0.583, 0.612], [0.804, 0.979], [0.544, 0.684]],
        bathroom::washing_machine
    ),
    // Kitchen.
    furniture!(
        "kitchen_island",
        Floor,
        ["island", "island counter", "breakfast bar", "island unit"],
        [[1.18, 2.274], [0.882, 0.969], [0.83, 1.194]],
        kitchen::kitchen_island
    ),
    furniture!(
        "wall_cabinet",
        Wall,
        [
            "wall cupboard",
            "upper cabinet",
            "overhead cabinet",
            "medicine cabinet",
            "wall unit"
        ],
        [[0.396, 1.224], [0.49, 0.918], [0.275, 0.368]],
        kitchen::wall_cabinet
    ),
    furniture!(
        "range_hood",
        Wall,
        [
            "cooker hood",
            "extractor",
            "extractor fan",
            "kitchen hood",
            "vent hood",
            "stove hood"
        ],
        [[0.588, 0.918], [0.556, 1.027], [0.447, 0.537]],
        kitchen::range_hood
    ),
    // Living, hall and study.
    furniture!(
        "fireplace",
        Floor,
        [
            "hearth",
            "fire place",
            "mantelpiece",
            "mantel",
            "chimney piece"
        ],
        [[1.178, 1.734], [1.024, 1.337], [0.294, 0.51]],
        living::fireplace
    ),
    furniture!(
        "curtain",
        Wall,
        ["curtains", "drapes", "drape", "draperies"],
        [[1.231, 2.698], [1.472, 2.465], [0.091, 0.148]],
        living::curtain
    ),
    furniture!(
        "window_blind",
        Wall,
        [
            "blind",
            "blinds",
            "venetian blind",
            "roller blind",
            "window shade"
        ],
        [[0.595, 1.623], [0.692, 1.625], [0.039, 0.062]],
        living::window_blind
    ),
    furniture!(
        "wall_clock",
        Wall,
        ["kitchen clock", "round clock"],
        [[0.245, 0.458], [0.245, 0.458], [0.034, 0.062]],
        living::wall_clock
    ),
    furniture!(
        "shoe_rack",
        Floor,
        ["shoe shelf", "shoe stand", "shoe storage", "shoe cabinet"],
        [[0.588, 1.019], [0.441, 0.969], [0.256, 0.369]],
        living::shoe_rack
    ),
    furniture!(
        "suitcase",
        Floor,
        ["luggage", "trolley case", "travel case", "valise"],
        [[0.352, 0.508], [0.609, 0.918], [0.216, 0.312]],
        living::suitcase
    ),
    furniture!(
        "filing_cabinet",
        Floor,
        ["file cabinet", "filing drawers", "file drawers"],
        [[0.373, 0.51], [0.64, 1.397], [0.515, 0.668]],
        living::filing_cabinet
    ),
    // Wall.
    furniture!(
        "painting",
        Wall,
        [
            "picture",
            "artwork",
            "canvas",
            "framed art",
            "art print",
            "poster"
        ],
        [[0.3, 1.5], [0.3, 1.2], [0.02, 0.05]],
        wall::painting
    ),
    furniture!(
        "whiteboard",
        Wall,
        ["dry erase board", "marker board", "white board"],
        [[0.9, 2.4], [0.62, 1.22], [0.07, 0.09]],
        wall::whiteboard
    ),
    furniture!(
        "wall_shelf",
        Wall,
        ["floating shelf", "wall-mounted shelf", "hanging shelf"],
        [[0.5, 1.2], [0.08, 0.75], [0.15, 0.3]],
        wall::wall_shelf
    ),
    furniture!(
        "mirror",
        Wall,
        ["wall mirror", "looking glass", "vanity mirror"],
        [[0.3, 1.0], [0.4, 1.6], [0.015, 0.04]],
        wall::mirror
    ),
    // Ceiling.
    furniture!(
        "pendant_lamp",
        Ceiling,
        [
            "ceiling lamp",
            "hanging lamp",
            "pendant light",
            "chandelier",
            "ceiling light"
        ],
        [[0.12, 0.6], [0.4, 1.2], [0.12, 0.6]],
        wall::pendant_lamp
    ),
];
