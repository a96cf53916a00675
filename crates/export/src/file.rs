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

    /// Writes the scene in this format to `path` (whose folder must exist) and returns the
    /// files written. All or nothing: the main file is written atomically, and a URDF's meshes
    /// are written into a staging folder that replaces `<stem>_meshes/` only once complete,
    /// before the URDF that names them.
    pub fn write_file(
        &self,
        export: &ExportScene<'_>,
        path: &Path,
    ) -> Result<Vec<PathBuf>, ExportError> {
        match self {
            Format::Glb => write(path, &glb::to_glb(export))?,
            Format::Usd => write(path, usd::to_usda(export).as_bytes())?,
            Format::Mjcf => write(path, mjcf::to_mjcf(export).as_bytes())?,
            Format::Urdf => return write_urdf(export, path),
        }
        Ok(vec![path.to_owned()])
    }
}

/// A URDF and its mesh folder, the folder staged and swapped in before the URDF is written.
fn write_urdf(export: &ExportScene<'_>, path: &Path) -> Result<Vec<PathBuf>, ExportError> {
    let name = Format::urdf_mesh_dir(path);
    let package = urdf::to_urdf(export, &name);
    let parent = path.parent().unwrap_or(Path::new("."));
    let mesh_dir = parent.join(&name);
    let staging = parent.join(format!(".{name}.staging-{}", std::process::id()));
    let failed = |path: &Path, source| ExportError::Write {
        path: path.to_owned(),
        source,
    };
    let _ = std::fs::remove_dir_all(&staging);
    std::fs::create_dir(&staging).map_err(|e| failed(&staging, e))?;
    let staged = package
        .meshes
        .iter()
        .try_for_each(|(file, text)| write(&staging.join(file), text.as_bytes()));
    if let Err(e) = staged {
        let _ = std::fs::remove_dir_all(&staging);
        return Err(e);
    }
    if mesh_dir.is_dir() {
        std::fs::remove_dir_all(&mesh_dir).map_err(|e| failed(&mesh_dir, e))?;
    }
    std::fs::rename(&staging, &mesh_dir).map_err(|e| failed(&mesh_dir, e))?;
    write(path, package.urdf.as_bytes())?;
    Ok(vec![path.to_owned(), mesh_dir])
}
