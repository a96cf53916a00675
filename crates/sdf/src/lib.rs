//! Signed distance fields for triangle meshes and whole scenes: exact BVH-accelerated queries,
//! baked grids with trilinear interpolation, and scene-level queries over posed objects. It is
//! the engine under physics-aware optimization and evaluation, and depends on no GPU or async
//! runtime so other projects can use it alone.
