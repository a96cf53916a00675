//! Limits of the asset readers (`docs/limits.md` lists them with every other limit): what a
//! single GLB/glTF/OBJ file or an `assets.json` may hold before it is refused.

/// Largest `.glb`/`.gltf` file read, in bytes (256 MiB).
pub const MAX_GLTF_BYTES: u64 = 256 * 1024 * 1024;
/// Largest total of a glTF file's buffers (embedded or external), in bytes (256 MiB).
pub const MAX_BUFFER_BYTES: u64 = 256 * 1024 * 1024;
/// Largest `.obj` file read, in bytes (256 MiB).
pub const MAX_OBJ_BYTES: u64 = 256 * 1024 * 1024;
/// Largest `.mtl` material library read, in bytes (4 MiB).
pub const MAX_MTL_BYTES: u64 = 4 * 1024 * 1024;
/// Largest `assets.json`, in bytes (16 MiB).
pub const MAX_MANIFEST_BYTES: u64 = 16 * 1024 * 1024;
/// Most entries in one `assets.json`.
pub const MAX_MANIFEST_ENTRIES: usize = 10_000;
/// Deepest glTF node hierarchy.
pub const MAX_NODE_DEPTH: usize = 64;
/// Most node instances in one glTF scene (a node reached through several parents counts once
/// per path), so that shared sub-graphs cannot multiply without bound.
pub const MAX_NODE_INSTANCES: usize = 100_000;
/// Most vertices in one file (summed over node instances).
pub const MAX_VERTICES: usize = 5_000_000;
/// Most triangles in one file (summed over node instances).
pub const MAX_TRIANGLES: usize = 5_000_000;
/// Largest absolute vertex coordinate or transform entry, in file units (before `unit_scale`).
pub const MAX_FILE_COORDINATE: f64 = 1.0e6;
/// Largest side of an imported asset after normalisation to metres.
pub const MAX_ASSET_SIZE: f64 = 50.0;
/// Largest value of a `scale_range` bound.
pub const MAX_ASSET_SCALE: f32 = 10.0;
/// Most synonyms of one manifest entry.
pub const MAX_SYNONYMS: usize = 64;
/// Most joints of one manifest entry.
pub const MAX_JOINTS: usize = 64;
/// Largest texture image an imported material names, in bytes (64 MiB).
pub const MAX_TEXTURE_BYTES: u64 = 64 * 1024 * 1024;
/// Largest texture image, in pixels (8192 × 8192).
pub const MAX_TEXTURE_PIXELS: u64 = 8192 * 8192;
