//! Limits of the evaluator (`docs/limits.md` lists them with every other limit). A scene loaded
//! from files is checked against them ([`crate::EvalScene::check_limits`]) before any geometry
//! reaches parry or rapier, so evaluation does bounded work with bounded memory.

/// Most objects in an evaluated scene.
pub const MAX_OBJECTS: usize = scenethesis_scene_graph::limits::MAX_OBJECTS;
/// Most walls in an evaluated scene (after splitting wall nodes of a foreign scene into pieces).
pub const MAX_WALLS: usize = 1024;
/// Most triangles of one object.
pub const MAX_TRIANGLES_PER_OBJECT: usize = 1_000_000;
/// Largest absolute world coordinate (m) of any vertex, floor corner or wall end.
pub const MAX_COORDINATE: f64 = scenethesis_scene_graph::limits::MAX_COORDINATE;
/// Most area-uniform surface samples per object for the collision test (one per cm² up to
/// this many; a 50 m² surface reaches it).
pub const MAX_SAMPLES_PER_OBJECT: usize = 500_000;
