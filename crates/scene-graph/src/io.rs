use std::io::Write;
use std::path::{Path, PathBuf};

use crate::{Scene, ValidationError};

/// Why a `scene.json` could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum SceneIoError {
    /// The file could not be read.
    #[error("cannot read scene file {path}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The OS error (or the size limit that was exceeded).
        #[source]
        source: std::io::Error,
    },
    /// The file is not a `scene.json` of the expected shape.
    #[error("{path} is not a valid scene.json")]
    Parse {
        /// The file.
        path: PathBuf,
        /// What the parser expected, with line and column.
        #[source]
        source: serde_json::Error,
    },
    /// The file parsed but the scene breaks a rule; the first problem is the source.
    #[error("{path} describes an invalid scene ({count} problem(s))")]
    Invalid {
        /// The file.
        path: PathBuf,
        /// How many problems were found.
        count: usize,
        /// The first problem.
        #[source]
        first: Box<ValidationError>,
        /// Every problem found.
        all: Vec<ValidationError>,
    },
    /// The file could not be written.
    #[error("cannot write {path}")]
    Write {
        /// The file.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
}

impl Scene {
    /// Parses `scene.json` text without validating it.
    pub fn from_json_str(text: &str) -> Result<Scene, serde_json::Error> {
        serde_json::from_str(text)
    }

    /// The scene as pretty-printed `scene.json` text (objects keyed by id, in stored order).
    pub fn to_json_string(&self) -> String {
        serde_json::to_string_pretty(self).expect("scene serialization cannot fail") + "\n"
    }

    /// Reads, parses and validates a `scene.json` file.
    pub fn read_json(path: &Path) -> Result<Scene, SceneIoError> {
        let bytes = read_bounded(path, crate::limits::MAX_SCENE_JSON_BYTES).map_err(|source| {
            SceneIoError::Read {
                path: path.to_owned(),
                source,
            }
        })?;
        let text = String::from_utf8(bytes).map_err(|e| SceneIoError::Read {
            path: path.to_owned(),
            source: std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!(
                    "not UTF-8 text (invalid byte at offset {})",
                    e.utf8_error().valid_up_to()
                ),
            ),
        })?;
        let scene = Scene::from_json_str(&text).map_err(|source| SceneIoError::Parse {
            path: path.to_owned(),
            source,
        })?;
        scene.validate().map_err(|all| SceneIoError::Invalid {
            path: path.to_owned(),
            count: all.len(),
            first: Box::new(all[0].clone()),
            all,
        })?;
        Ok(scene)
    }

    /// Writes the scene as `scene.json` atomically (see [`write_file_atomic`]).
    pub fn write_json_atomic(&self, path: &Path) -> Result<(), SceneIoError> {
        write_file_atomic(path, self.to_json_string().as_bytes()).map_err(|source| {
            SceneIoError::Write {
                path: path.to_owned(),
                source,
            }
        })
    }
}

/// Reads a whole file, refusing one larger than `limit` bytes (checked while reading, so a
/// pipe or a file that grows is never read without bound). Directories, devices (such as
/// `/dev/zero`) and sockets are refused. The error names the limit; the caller adds the path.
pub fn read_bounded(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let file = std::fs::File::open(path)?;
    let meta = file.metadata()?;
    if meta.is_dir() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            "is a directory, expected a file",
        ));
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = meta.file_type();
        if t.is_char_device() || t.is_block_device() || t.is_socket() {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "is a device or socket, expected a regular file",
            ));
        }
    }
    let too_large = || {
        std::io::Error::new(
            std::io::ErrorKind::FileTooLarge,
            format!("larger than the limit of {limit} bytes (see docs/limits.md)"),
        )
    };
    if meta.is_file() && meta.len() > limit {
        return Err(too_large());
    }
    let capacity = if meta.is_file() {
        meta.len().min(limit)
    } else {
        0
    };
    let mut bytes = Vec::with_capacity(usize::try_from(capacity).unwrap_or(0));
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_large());
    }
    Ok(bytes)
}

/// Writes `bytes` to `path` atomically: into a temporary file in the same directory, flushed to
/// disk, then renamed over `path`. A failure leaves any earlier file at `path` untouched and no
/// partial file behind.
pub fn write_file_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    // Temporary files are created private (0600); the result is an ordinary readable file.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o644));
    }
    let mut tmp = builder.tempfile_in(dir)?;
    tmp.write_all(bytes)?;
    tmp.as_file().sync_all()?;
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}
