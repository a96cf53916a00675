//! Writing one format to a file the user names, e.g. `kitchen.usda` or `robot/scene.urdf`.

use std::path::{Path, PathBuf};

use std::collections::BTreeSet;

use crate::textures::{self, TEXTURE_DIR};
use crate::{glb, mjcf, urdf, usd, write, ExportError, ExportScene, Format};

impl Format {
    /// The format a file name's suffix asks for: `.glb`, `.usda` / `.usd`, `.xml` (MJCF, e.g.
    /// `scene.mjcf.xml`) or `.urdf`; `None` for any other suffix.
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "glb" => Some(Format::Glb),
            "usda" | "usd" => Some(Format::Usd),
            "xml" | "mjcf" => Some(Format::Mjcf),
            "urdf" => Some(Format::Urdf),
            _ => None,
        }
    }

    /// The folder beside a URDF file at `path` that [`Format::write_file`] puts its OBJ meshes
    /// in: `<stem>_meshes` (so two URDFs in one folder keep their own meshes).
    pub fn urdf_mesh_dir(path: &Path) -> String {
        let stem = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".to_owned());
        format!("{stem}_meshes")
    }

    /// The folder beside a text-format file at `path` that [`Format::write_file`] puts its
    /// textures in: `<stem>_textures`.
    pub fn texture_dir(path: &Path) -> String {
        let stem = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".to_owned());
        format!("{stem}_textures")
    }

    /// Writes the scene in this format into `dir` (which must exist) under its
    /// [`Format::file_name`] (a URDF's meshes in `meshes/`, the text formats' textures in
    /// `textures/`), all or nothing as
    /// [`write_formats`], and returns the path of the main file.
    pub fn write(&self, export: &ExportScene<'_>, dir: &Path) -> Result<PathBuf, ExportError> {
        let path = dir.join(self.file_name());
        write_formats(&[*self], export, dir)?;
        Ok(path)
    }

    /// Writes the scene in this format to `path` (whose folder must exist) and returns the
    /// files written: the main file, for a URDF its mesh folder `<stem>_meshes/`, and for the
    /// text formats (USD, MJCF, URDF) of a textured scene their texture folder
    /// `<stem>_textures/`. All or nothing, as [`write_formats`].
    pub fn write_file(
        &self,
        export: &ExportScene<'_>,
        path: &Path,
    ) -> Result<Vec<PathBuf>, ExportError> {
        let parent = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| self.file_name().to_owned());
        let dirs = Dirs {
            meshes: Format::urdf_mesh_dir(path),
            textures: Format::texture_dir(path),
        };
        let output = Encoded::new(*self, export, name, &dirs);
        let folders: Vec<PathBuf> = output.folders.iter().map(|(d, _)| parent.join(d)).collect();
        stage_and_move(parent, vec![output])?;
        Ok(std::iter::once(path.to_owned()).chain(folders).collect())
    }

    /// The scene in this format, in memory, as [`Encoded`].
    fn encode(&self, export: &ExportScene<'_>, dirs: &Dirs) -> (Vec<u8>, Vec<(String, Files)>) {
        let textures = || {
            let files = textures::files(export);
            (!files.is_empty()).then(|| (dirs.textures.clone(), files))
        };
        match self {
            Format::Glb => (glb::to_glb(export), Vec::new()),
            Format::Usd => (
                usd::to_usda_textured(export, &dirs.textures).into_bytes(),
                textures().into_iter().collect(),
            ),
            Format::Mjcf => (
                mjcf::to_mjcf_textured(export, &dirs.textures).into_bytes(),
                textures().into_iter().collect(),
            ),
            Format::Urdf => {
                let package = urdf::to_urdf_textured(export, &dirs.meshes, &dirs.textures);
                let meshes: Files = package
                    .meshes
                    .into_iter()
                    .map(|(name, text)| (name, text.into_bytes()))
                    .collect();
                let folders = std::iter::once((dirs.meshes.clone(), meshes))
                    .chain(textures())
                    .collect();
                (package.urdf.into_bytes(), folders)
            }
        }
    }
}

/// Files of a side folder by file name: a URDF's OBJ meshes, the text formats' textures.
type Files = std::collections::BTreeMap<String, Vec<u8>>;

/// The side folders' names an output refers to.
struct Dirs {
    meshes: String,
    textures: String,
}

/// One format's output, built in memory before anything is written.
struct Encoded {
    /// The main file's name in the target folder.
    name: String,
    /// The main file's bytes.
    bytes: Vec<u8>,
    /// Side folders (a URDF's meshes, textures) by folder name, with their files. Formats
    /// written together share a folder of the same name (its files are the same).
    folders: Vec<(String, Files)>,
}

impl Encoded {
    fn new(format: Format, export: &ExportScene<'_>, name: String, dirs: &Dirs) -> Self {
        let (bytes, folders) = format.encode(export, dirs);
        Self {
            name,
            bytes,
            folders,
        }
    }
}

/// Writes `formats` into `dir` (which must exist), each under its [`Format::file_name`] (a
/// URDF's meshes in `meshes/`, the textures of USD, MJCF and URDF once in `textures/`), and
/// returns the paths of the main files. All or nothing: every
/// format is encoded in memory first, then every file is written into a staging folder inside
/// `dir`, and only when all are written are they moved into place. A failure leaves `dir` as
/// it was.
pub fn write_formats(
    formats: &[Format],
    export: &ExportScene<'_>,
    dir: &Path,
) -> Result<Vec<PathBuf>, ExportError> {
    let dirs = Dirs {
        meshes: urdf::MESH_DIR.to_owned(),
        textures: TEXTURE_DIR.to_owned(),
    };
    let mut outputs: Vec<Encoded> = formats
        .iter()
        .map(|f| Encoded::new(*f, export, f.file_name().to_owned(), &dirs))
        .collect();
    // A folder shared by several formats (textures) is written by the first only.
    let mut seen = BTreeSet::new();
    for output in &mut outputs {
        output.folders.retain(|(name, _)| seen.insert(name.clone()));
    }
    let paths = outputs.iter().map(|o| dir.join(&o.name)).collect();
    stage_and_move(dir, outputs)?;
    Ok(paths)
}

/// Writes `outputs` into a staging folder inside `dir`, then moves each into `dir` (its side
/// folders first replace the old ones, then the main file naming them). The staging folder is
/// removed whatever happens.
fn stage_and_move(dir: &Path, outputs: Vec<Encoded>) -> Result<(), ExportError> {
    let staging = dir.join(format!(".export-staging-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&staging);
    let result = outputs
        .iter()
        .try_for_each(|o| check_targets(dir, o))
        .and_then(|()| create_dir(&staging))
        .and_then(|()| outputs.iter().try_for_each(|o| stage(&staging, o)))
        .and_then(|()| outputs.iter().try_for_each(|o| move_in(&staging, dir, o)));
    let _ = std::fs::remove_dir_all(&staging);
    result
}

/// Refuses, before anything is written, a target the move could not replace: a folder where
/// a main file goes, or a file where a side folder goes.
fn check_targets(dir: &Path, output: &Encoded) -> Result<(), ExportError> {
    let occupied = |path: &Path, expected: &str| {
        failed(
            path,
            std::io::Error::new(
                std::io::ErrorKind::AlreadyExists,
                format!("something other than {expected} is in the way; nothing was written"),
            ),
        )
    };
    let main = dir.join(&output.name);
    if main.is_dir() {
        return Err(occupied(&main, "a file"));
    }
    for (name, _) in &output.folders {
        let folder = dir.join(name);
        if folder.exists() && !folder.is_dir() {
            return Err(occupied(&folder, "a folder"));
        }
    }
    Ok(())
}

/// Writes one output's files into `staging`.
fn stage(staging: &Path, output: &Encoded) -> Result<(), ExportError> {
    for (name, files) in &output.folders {
        let folder = staging.join(name);
        create_dir(&folder)?;
        for (file, bytes) in files {
            write(&folder.join(file), bytes)?;
        }
    }
    write(&staging.join(&output.name), &output.bytes)
}

/// Moves one staged output into `dir`: its side folders (replacing the old ones), then its
/// main file.
fn move_in(staging: &Path, dir: &Path, output: &Encoded) -> Result<(), ExportError> {
    for (name, _) in &output.folders {
        let target = dir.join(name);
        if target.is_dir() {
            std::fs::remove_dir_all(&target).map_err(|e| failed(&target, e))?;
        }
        rename(&staging.join(name), &target)?;
    }
    rename(&staging.join(&output.name), &dir.join(&output.name))
}

fn create_dir(path: &Path) -> Result<(), ExportError> {
    std::fs::create_dir(path).map_err(|e| failed(path, e))
}

fn rename(from: &Path, to: &Path) -> Result<(), ExportError> {
    std::fs::rename(from, to).map_err(|e| failed(to, e))
}

fn failed(path: &Path, source: std::io::Error) -> ExportError {
    ExportError::Write {
        path: path.to_owned(),
        source,
    }
}
