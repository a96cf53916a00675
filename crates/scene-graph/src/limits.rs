//! Limits on what a scene may hold, so that every tool reading one does bounded work with
//! bounded memory. [`crate::Scene::validate`] enforces them; `docs/limits.md` lists every limit
//! of the workspace with its reason.

/// Largest `scene.json` read, in bytes (64 MiB).
pub const MAX_SCENE_JSON_BYTES: u64 = 64 * 1024 * 1024;
/// Largest `plan.json` read, in bytes (16 MiB).
pub const MAX_PLAN_JSON_BYTES: u64 = 16 * 1024 * 1024;
/// Largest batch prompts file read, in bytes (64 MiB).
pub const MAX_PROMPTS_FILE_BYTES: u64 = 64 * 1024 * 1024;
/// Most objects in one scene.
pub const MAX_OBJECTS: usize = 2000;
/// Most walls in one scene.
pub const MAX_WALLS: usize = 256;
/// Most door openings in one scene.
pub const MAX_DOORS: usize = 256;
/// Most windows in one scene.
pub const MAX_WINDOWS: usize = 256;
/// Most rooms in one scene (a house).
pub const MAX_ROOMS: usize = 256;
/// Most corners of one room's floor outline.
pub const MAX_ROOM_CORNERS: usize = 64;
/// Most relations on one object.
pub const MAX_RELATIONS: usize = 256;
/// Longest id, category or generator name, in bytes.
pub const MAX_ID_BYTES: usize = 256;
/// Largest absolute coordinate (m) of a translation, floor corner or wall end point.
pub const MAX_COORDINATE: f64 = 1000.0;
/// Largest extent (m) of an object: every local bound within ±this, and every scaled side at
/// most this long.
pub const MAX_OBJECT_SIZE: f64 = 50.0;
/// Largest absolute yaw (rad) of an object's pose.
pub const MAX_YAW: f64 = 1000.0;
/// Smallest uniform scale of an object.
pub const MIN_SCALE: f64 = 0.01;
/// Largest uniform scale of an object.
pub const MAX_SCALE: f64 = 10.0;
/// Tallest wall or door opening (m).
pub const MAX_WALL_HEIGHT: f64 = 100.0;
/// Thickest wall (m).
pub const MAX_WALL_THICKNESS: f64 = 10.0;
