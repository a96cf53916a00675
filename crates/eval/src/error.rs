use std::path::PathBuf;

/// Why a scene could not be loaded for evaluation.
#[derive(Debug, thiserror::Error)]
pub enum EvalError {
    /// A file could not be read.
    #[error("cannot read {path}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The `scene.json` could not be read or is invalid.
    #[error(transparent)]
    Scene(#[from] scenethesis_scene_graph::SceneIoError),
    /// A glTF / GLB file could not be parsed.
    #[error("{path} is not a readable glTF / GLB file")]
    Gltf {
        /// The file.
        path: PathBuf,
        /// The parser's error.
        #[source]
        source: gltf::Error,
    },
    /// A glTF file parsed but cannot be used.
    #[error("{path}: {reason}")]
    BadGltf {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// A folder holds no `scene.json`.
    #[error("{path} holds no scene.json (expected an output folder, a scene.json or a .glb)")]
    NotAScene {
        /// The folder.
        path: PathBuf,
    },
    /// A path is neither a folder, a `scene.json` nor a glTF / GLB file.
    #[error("{path}: expected an output folder, a scene.json, or a .glb / .gltf file")]
    UnsupportedInput {
        /// The path.
        path: PathBuf,
    },
    /// An object's procedural generator is not in the built-in library.
    #[error("object {object}: unknown procedural generator {generator:?}")]
    UnknownGenerator {
        /// Object id.
        object: String,
        /// The generator name.
        generator: String,
    },
    /// No mesh could be found for an object.
    #[error("object {object}: no mesh ({reason})")]
    MissingMesh {
        /// Object id.
        object: String,
        /// Where it was looked for.
        reason: String,
    },
    /// The scene is over one of the evaluator's limits ([`crate::limits`]) or holds a value the
    /// geometry code cannot take.
    #[error("{what}: {reason} (see docs/limits.md)")]
    OverLimit {
        /// The object or element concerned (or `scene`).
        what: String,
        /// The value found and the limit.
        reason: String,
    },
}
