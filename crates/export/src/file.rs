//! Writing one format to a file the user names, e.g. `kitchen.usda` or `robot/scene.urdf`.

use std::path::{Path, PathBuf};

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

    /// Writes the scene in this format into `dir` (which must exist) under its
    /// [`Format::file_name`] (a URDF's meshes in `meshes/`), all or nothing as
    /// [`write_formats`], and returns the path of the main file.
    pub fn write(&self, export: &ExportScene<'_>, dir: &Path) -> Result<PathBuf, ExportError> {
        let path = dir.join(self.file_name());
        write_formats(&[*self], export, dir)?;
        Ok(path)
    }

    /// Writes the scene in this format to `path` (whose folder must exist) and returns the
    /// files written: the main file and, for a URDF, its mesh folder `<stem>_meshes/`. All or
    /// nothing, as [`write_formats`].
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
        let output = Encoded::new(*self, export, name, &Format::urdf_mesh_dir(path));
        let mesh_dir = output.meshes.as_ref().map(|(dir, _)| parent.join(dir));
        stage_and_move(parent, vec![output])?;
        Ok(std::iter::once(path.to_owned()).chain(mesh_dir).collect())
    }

    /// The scene in this format, in memory, as [`Encoded`].
    fn encode(&self, export: &ExportScene<'_>, mesh_dir: &str) -> (Vec<u8>, Option<MeshFiles>) {
        match self {
            Format::Glb => (glb::to_glb(export), None),
            Format::Usd => (usd::to_usda(export).into_bytes(), None),
            Format::Mjcf => (mjcf::to_mjcf(export).into_bytes(), None),
            Format::Urdf => {
                let package = urdf::to_urdf(export, mesh_dir);
                (package.urdf.into_bytes(), Some(package.meshes))
            }
        }
    }
}

/// OBJ files by file name: a URDF's meshes.
type MeshFiles = std::collections::BTreeMap<String, String>;

/// One format's output, built in memory before anything is written.
struct Encoded {
    /// The main file's name in the target folder.
    name: String,
    /// The main file's bytes.
    bytes: Vec<u8>,
    /// A URDF's mesh folder name and its files.
    meshes: Option<(String, MeshFiles)>,
}

impl Encoded {
    fn new(format: Format, export: &ExportScene<'_>, name: String, mesh_dir: &str) -> Self {
        let (bytes, meshes) = format.encode(export, mesh_dir);
        Self {
            name,
            bytes,
            meshes: meshes.map(|files| (mesh_dir.to_owned(), files)),
        }
    }
}

/// Writes `formats` into `dir` (which must exist), each under its [`Format::file_name`] (a
/// URDF's meshes in `meshes/`), and returns the paths of the main files. All or nothing: every
/// format is encoded in memory first, then every file is written into a staging folder inside
/// `dir`, and only when all are written are they moved into place. A failure leaves `dir` as
/// it was.
pub fn write_formats(
    formats: &[Format],
    export: &ExportScene<'_>,
    dir: &Path,
) -> Result<Vec<PathBuf>, ExportError> {
    let outputs: Vec<Encoded> = formats
        .iter()
        .map(|f| Encoded::new(*f, export, f.file_name().to_owned(), urdf::MESH_DIR))
        .collect();
    let paths = outputs.iter().map(|o| dir.join(&o.name)).collect();
    stage_and_move(dir, outputs)?;
    Ok(paths)
}

/// Writes `outputs` into a staging folder inside `dir`, then moves each into `dir` (a mesh
/// folder first replaces the old one, then the main file naming it). The staging folder is
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
/// a main file goes, or a file where a mesh folder goes.
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
    if let Some((name, _)) = &output.meshes {
        let folder = dir.join(name);
        if folder.exists() && !folder.is_dir() {
            return Err(occupied(&folder, "a folder"));
        }
    }
    Ok(())
}

/// Writes one output's files into `staging`.
fn stage(staging: &Path, output: &Encoded) -> Result<(), ExportError> {
    if let Some((name, files)) = &output.meshes {
        let folder = staging.join(name);
        create_dir(&folder)?;
        for (file, text) in files {
            write(&folder.join(file), text.as_bytes())?;
        }
    }
    write(&staging.join(&output.name), &output.bytes)
}

/// Moves one staged output into `dir`: its mesh folder (replacing the old one), then its main
/// file.
fn move_in(staging: &Path, dir: &Path, output: &Encoded) -> Result<(), ExportError> {
    if let Some((name, _)) = &output.meshes {
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
