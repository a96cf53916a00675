//! Houses for scenethesis: from a dwelling *program* (which rooms, how many) to a floor plan of
//! rooms, doors, windows and walls, and the validation of floor plans users give.
//!
//! - [`knowledge`]: the dwelling knowledge (`knowledge/dwellings.toml`): room types with area
//!   ranges and their sources, privacy, doors and windows; dwelling kinds and their rooms.
//! - [`program`]: [`Program`], the rooms to build, from a kind and counts or a prompt's words.
//! - [`layout`]: [`generate`], the seeded floor-plan generator.
//! - [`validate()`]: the checks every plan (generated or a user's) must pass.
//! - [`walls()`]: the wall segments derived from a plan's rooms.
//!
//! Coordinates are (x, z) on the floor plane, metres, as in scene-graph's `Architecture`.
//!
//! ```
//! use scenethesis_floorplan::{generate, validate, Knowledge, Program};
//! let k = Knowledge::builtin();
//! let program = Program::new(k, "house", &[("bedroom", 3), ("bathroom", 2)]).unwrap();
//! let house = generate(k, &program, 1).unwrap();
//! assert!(house.hallway);
//! assert!(validate(&house.plan, k).is_ok());
//! ```

#![warn(missing_docs)]

mod doors;
pub mod geometry;
pub mod knowledge;
pub mod layout;
pub mod plan;
pub mod program;
pub mod validate;
pub mod walls;
mod windows;

pub use doors::{
    leaf_clash, leaf_squares, CORNER_CLEARANCE, DOOR_HEIGHT, DOUBLE_WIDTHS, ENTRANCE_WIDTH,
    PASSAGE_MAX, PASSAGE_MIN, PASSAGE_SIDE_WALL, SERVICE_ROOMS,
};
pub use knowledge::{
    DwellingKind, Knowledge, KnowledgeError, Privacy, RoomKind, WindowSpec, HALLWAY,
};
pub use layout::{generate, AreaNote, Generated, LayoutError, AREA_TOLERANCE};
pub use plan::{Door, DoorKind, FloorPlan, Hinge, Room, Swing, Window, EXTERIOR};
pub use program::{Program, ProgramError, RoomCount};
pub use validate::{check_privacy, validate, PlanError};
pub use walls::{walls, Wall};
pub use windows::{WINDOW_DOOR_CLEARANCE, WINDOW_END_CLEARANCE};
