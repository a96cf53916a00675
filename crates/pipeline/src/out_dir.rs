//! The output folder of a run (`--out DIR`): checked before any work, written into a private
//! staging folder beside it, and swapped into place atomically.
//!
//! The rules, so that a run never loses a user's data:
//! - an existing `DIR` is replaced only when it is a previous scenethesis output (every entry is
//!   a file scenethesis writes, and `scene.json` or `report.json` is among them) or empty;
//!   anything else needs `force`;
//! - a regular file, a symbolic link or another non-folder at `DIR` is never replaced;
//! - the path is resolved to an absolute one first, so `--out ../b` from inside `b` works;
//! - the swap is one `renameat2(RENAME_EXCHANGE)` where the system has it, else two renames
//!   with a rollback on every error path; the previous output is deleted only afterwards;
//! - staging (`.DIR.partial-PID-…`) and set-aside (`.DIR.old-PID-…`) folders left by killed
//!   runs are swept when their process is gone, and a set-aside previous output whose swap was
//!   interrupted is put back where it was.

use std::ffi::OsString;
use std::path::{Component, Path, PathBuf};

use crate::error::PipelineError;

/// The scene graph file of an output folder.
pub const SCENE_JSON: &str = "scene.json";
/// The report file of an output folder.
pub const REPORT_JSON: &str = "report.json";
/// Longest file name most file systems accept, in bytes.
const NAME_MAX: usize = 255;
/// Room the temporary names need beside the output's own name: `.` + `.partial-` + a process
/// id (up to 10 digits) + `-` + 6 random characters.
const TEMP_NAME_EXTRA: usize = 1 + 9 + 10 + 1 + 6;
/// Staging folders live for the seconds a write takes; one of a dead process is swept only
/// once it is older than this.
const SWEEP_AFTER: std::time::Duration = std::time::Duration::from_secs(60);
/// Longest output folder name, in bytes.
pub const MAX_OUTPUT_NAME: usize = NAME_MAX - TEMP_NAME_EXTRA;

/// Files a scenethesis output folder may hold (written by `generate`, `export` and `render`).
const KNOWN_FILES: &[&str] = &[
    SCENE_JSON,
    REPORT_JSON,
    "scene.glb",
    "scene.usda",
    "scene.mjcf.xml",
    "scene.urdf",
    "preview.png",
    "preview_top.png",
];
/// Sub-folders a scenethesis output folder may hold, with the file extensions inside them.
const KNOWN_FOLDERS: &[(&str, &[&str])] = &[
    ("meshes", &["obj", "stl"]),
    ("guidance", &["png", "npy", "json"]),
    (scenethesis_export::TEXTURE_DIR, &["png"]),
];

/// What an output path holds before the run.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Existing {
    /// Nothing: the folder will be created.
    Nothing,
    /// An empty folder.
    Empty,
    /// A previous scenethesis output; `accepted` is its report's verdict when it has a readable
    /// `report.json`.
    Scene {
        /// Whether the judge accepted the previous scene.
        accepted: Option<bool>,
    },
    /// A folder holding something scenethesis did not write (replaced only with `force`).
    Foreign {
        /// One entry scenethesis did not write.
        entry: String,
    },
}

/// A checked output folder: where a run's files go, and how it is swapped into place.
#[derive(Debug)]
pub struct OutputDir {
    /// The path as the user gave it (for messages).
    shown: PathBuf,
    /// The absolute output path.
    path: PathBuf,
    /// Its absolute parent folder.
    parent: PathBuf,
    /// Its file name.
    name: OsString,
    /// What it held when checked.
    existing: Existing,
}

fn bad(path: &Path, reason: impl Into<String>) -> PipelineError {
    PipelineError::BadOutput {
        path: path.to_owned(),
        reason: reason.into(),
    }
}

fn write_error(path: &Path, source: std::io::Error) -> PipelineError {
    PipelineError::Write {
        path: path.to_owned(),
        source,
    }
}

impl OutputDir {
    /// Checks `path` before any work: resolves it, refuses a file, a link, a name too long for
    /// the temporary names, or (without `force`) a folder holding anything scenethesis did not
    /// write; creates the parent folders and checks that they are writable; sweeps staging
    /// folders of earlier killed runs.
    pub fn prepare(path: &Path, force: bool) -> Result<Self, PipelineError> {
        if path.as_os_str().is_empty() {
            return Err(bad(path, "the output path is empty"));
        }
        let (parent, name) = resolve(path)?;
        if name.len() > MAX_OUTPUT_NAME {
            return Err(bad(
                path,
                format!(
                    "the folder name is {} bytes long; at most {MAX_OUTPUT_NAME} fit beside the \
                     temporary names of an atomic write",
                    name.len()
                ),
            ));
        }
        let abs = parent.join(&name);
        sweep(&parent, &name, &abs);
        let existing = classify(&abs).map_err(|reason| bad(path, reason))?;
        if let Existing::Foreign { entry } = &existing {
            if !force {
                return Err(bad(
                    path,
                    format!(
                        "the folder holds files scenethesis did not write (e.g. {entry:?}), so \
                         it is not replaced; choose another --out, or pass --force to replace it"
                    ),
                ));
            }
        }
        std::fs::create_dir_all(&parent).map_err(|e| write_error(&parent, e))?;
        // Writable? Creating (and removing) a staging-named folder answers it exactly.
        let probe = temp_dir(&parent, &name, "partial").map_err(|e| write_error(&parent, e))?;
        drop(probe);
        Ok(Self {
            shown: path.to_owned(),
            path: abs,
            parent,
            name,
            existing,
        })
    }

    /// The absolute output path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The path as given.
    pub fn shown(&self) -> &Path {
        &self.shown
    }

    /// What the path held when it was checked.
    pub fn existing(&self) -> &Existing {
        &self.existing
    }

    /// Whether the path holds a scene the judge accepted.
    pub fn holds_accepted_scene(&self) -> bool {
        matches!(
            self.existing,
            Existing::Scene {
                accepted: Some(true)
            }
        )
    }

    /// A new private staging folder beside the output, deleted when dropped unless committed.
    pub(crate) fn stage(&self) -> Result<tempfile::TempDir, PipelineError> {
        temp_dir(&self.parent, &self.name, "partial").map_err(|e| write_error(&self.parent, e))
    }

    /// Moves a finished staging folder into place, replacing the previous output only now, and
    /// deletes the previous output afterwards.
    pub(crate) fn commit(&self, staging: tempfile::TempDir) -> Result<(), PipelineError> {
        let staged = staging.keep();
        let result = self.swap_in(&staged);
        if result.is_err() {
            let _ = std::fs::remove_dir_all(&staged);
        }
        result
    }

    fn swap_in(&self, staged: &Path) -> Result<(), PipelineError> {
        match std::fs::symlink_metadata(&self.path) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                return std::fs::rename(staged, &self.path).map_err(|e| write_error(&self.path, e));
            }
            Err(e) => return Err(write_error(&self.path, e)),
            Ok(meta) if !meta.is_dir() => {
                return Err(bad(
                    &self.shown,
                    "a file appeared at the output path during the run; it is not replaced",
                ));
            }
            Ok(_) => {}
        }
        match exchange(staged, &self.path) {
            Ok(()) => {
                // `staged` now holds the previous output.
                let _ = std::fs::remove_dir_all(staged);
                Ok(())
            }
            Err(e) if exchange_unsupported(&e) => self.swap_with_rollback(staged),
            Err(e) => Err(write_error(&self.path, e)),
        }
    }

    /// Two renames: the previous output is set aside, the new one moved in; any failure puts the
    /// previous output back.
    fn swap_with_rollback(&self, staged: &Path) -> Result<(), PipelineError> {
        let aside_root = temp_dir(&self.parent, &self.name, "old")
            .map_err(|e| write_error(&self.parent, e))?
            .keep();
        let aside = aside_root.join("previous");
        if let Err(e) = std::fs::rename(&self.path, &aside) {
            let _ = std::fs::remove_dir_all(&aside_root);
            return Err(write_error(&self.path, e));
        }
        if let Err(e) = std::fs::rename(staged, &self.path) {
            let restored = std::fs::rename(&aside, &self.path).is_ok();
            if restored {
                let _ = std::fs::remove_dir_all(&aside_root);
            }
            return Err(write_error(&self.path, e));
        }
        let _ = std::fs::remove_dir_all(&aside_root);
        Ok(())
    }
}

/// Removes staging and set-aside folders of this output whose process is gone; a set-aside
/// previous output is first moved back when the output path is missing (a run killed
/// between the two renames of [`OutputDir::swap_with_rollback`]).
fn sweep(parent: &Path, name: &std::ffi::OsStr, path: &Path) {
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    let name = name.to_string_lossy();
    let partial = format!(".{name}.partial-");
    let old = format!(".{name}.old-");
    for entry in entries.flatten() {
        let file = entry.file_name().to_string_lossy().into_owned();
        let (rest, is_old) = if let Some(rest) = file.strip_prefix(&partial) {
            (rest, false)
        } else if let Some(rest) = file.strip_prefix(&old) {
            (rest, true)
        } else {
            continue;
        };
        let Some(pid) = rest.split('-').next().and_then(|p| p.parse::<u32>().ok()) else {
            continue;
        };
        // The process id is only meaningful on this host; a folder that another host's batch
        // (sharing the file system) is writing right now is young, so it is left alone.
        let young = entry
            .metadata()
            .and_then(|m| m.modified())
            .ok()
            .and_then(|t| std::time::SystemTime::now().duration_since(t).ok())
            .is_none_or(|age| age < SWEEP_AFTER);
        if pid == std::process::id() || process_alive(pid) || young {
            continue;
        }
        let stale = entry.path();
        if is_old && !path.exists() {
            let previous = stale.join("previous");
            if previous.is_dir() && std::fs::rename(&previous, path).is_ok() {
                tracing::warn!(
                    "restored {} from an interrupted earlier run",
                    path.display()
                );
            }
        }
        let _ = std::fs::remove_dir_all(&stale);
    }
}

/// A new private folder `.NAME.KIND-PID-XXXXXX` in `parent` (KIND is `partial` for staging,
/// `old` for a set-aside previous output), deleted when dropped unless kept.
fn temp_dir(
    parent: &Path,
    name: &std::ffi::OsStr,
    kind: &str,
) -> std::io::Result<tempfile::TempDir> {
    let prefix = format!(".{}.{kind}-{}-", name.to_string_lossy(), std::process::id());
    tempfile::Builder::new()
        .prefix(&prefix)
        .rand_bytes(6)
        .tempdir_in(parent)
}

/// The absolute parent folder and the file name of `path`, with the existing part of the
/// parent resolved (symbolic links and `..` included).
fn resolve(path: &Path) -> Result<(PathBuf, OsString), PipelineError> {
    let cwd = std::env::current_dir().map_err(|e| bad(path, format!("no working folder: {e}")))?;
    let abs = if path.is_absolute() {
        path.to_owned()
    } else {
        cwd.join(path)
    };
    // A path ending in `.` or `..` (or `/`) names its folder only after resolution.
    let ends_in_name = matches!(abs.components().next_back(), Some(Component::Normal(_)));
    if !ends_in_name {
        let real = abs
            .canonicalize()
            .map_err(|e| bad(path, format!("cannot resolve it: {e}")))?;
        return match (real.parent(), real.file_name()) {
            (Some(parent), Some(name)) => Ok((parent.to_owned(), name.to_owned())),
            _ => Err(bad(path, "the output path has no folder name")),
        };
    }
    let name = abs.file_name().expect("ends in a name").to_owned();
    let parent = abs.parent().unwrap_or(Path::new("/"));
    // Resolve the longest existing ancestor; the rest must be plain names to be created.
    let mut existing = parent.to_path_buf();
    let mut missing = Vec::new();
    while !existing.exists() {
        match (existing.file_name(), existing.parent()) {
            (Some(n), Some(p)) => {
                missing.push(n.to_owned());
                existing = p.to_owned();
            }
            _ => return Err(bad(path, "no part of the output path exists")),
        }
    }
    let mut resolved = existing
        .canonicalize()
        .map_err(|e| bad(path, format!("cannot resolve {}: {e}", existing.display())))?;
    if !resolved.is_dir() {
        return Err(bad(
            path,
            format!("{} is a file, not a folder", resolved.display()),
        ));
    }
    for n in missing.into_iter().rev() {
        if n == ".." || n == "." {
            return Err(bad(
                path,
                "`.` or `..` after a folder that does not exist yet",
            ));
        }
        resolved.push(n);
    }
    Ok((resolved, name))
}

/// What `path` holds; `Err` with the reason when it must never be replaced.
fn classify(path: &Path) -> Result<Existing, String> {
    let meta = match std::fs::symlink_metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Existing::Nothing),
        Err(e) => return Err(format!("cannot inspect it: {e}")),
    };
    if meta.file_type().is_symlink() {
        return Err(
            "it is a symbolic link; scenethesis does not replace links (give the folder it \
             points to)"
                .into(),
        );
    }
    if !meta.is_dir() {
        return Err("it is a file, not a folder; scenethesis never replaces a file".into());
    }
    let entries = std::fs::read_dir(path).map_err(|e| format!("cannot list it: {e}"))?;
    let mut names = Vec::new();
    for entry in entries {
        let entry = entry.map_err(|e| format!("cannot list it: {e}"))?;
        names.push((entry.file_name(), entry.path()));
    }
    if names.is_empty() {
        return Ok(Existing::Empty);
    }
    names.sort();
    let mut has_scene = false;
    for (name, full) in &names {
        let text = name.to_string_lossy();
        if !ours(&text, full) {
            return Ok(Existing::Foreign {
                entry: text.into_owned(),
            });
        }
        has_scene |= text == SCENE_JSON || text == REPORT_JSON;
    }
    if !has_scene {
        let entry = names[0].0.to_string_lossy().into_owned();
        return Ok(Existing::Foreign { entry });
    }
    Ok(Existing::Scene {
        accepted: read_accepted(&path.join(REPORT_JSON)),
    })
}

/// Whether the entry `name` at `full` is one scenethesis writes into an output folder.
fn ours(name: &str, full: &Path) -> bool {
    let Ok(meta) = std::fs::symlink_metadata(full) else {
        return false;
    };
    if meta.is_file() {
        return KNOWN_FILES.contains(&name) || is_view_png(name) || is_room_preview(name);
    }
    if !meta.is_dir() {
        return false;
    }
    let Some((_, extensions)) = KNOWN_FOLDERS.iter().find(|(n, _)| *n == name) else {
        return false;
    };
    let Ok(entries) = std::fs::read_dir(full) else {
        return false;
    };
    entries.flatten().all(|e| {
        e.file_type().is_ok_and(|t| t.is_file())
            && Path::new(&e.file_name())
                .extension()
                .and_then(|x| x.to_str())
                .is_some_and(|x| extensions.contains(&x))
    })
}

/// `preview_<room>.png`, a house room's own preview.
fn is_room_preview(name: &str) -> bool {
    name.strip_prefix("preview_")
        .and_then(|r| r.strip_suffix(".png"))
        .is_some_and(|room| !room.is_empty())
}

/// `view_K.png`, the orbit views of `render`.
fn is_view_png(name: &str) -> bool {
    name.strip_prefix("view_")
        .and_then(|r| r.strip_suffix(".png"))
        .is_some_and(|k| !k.is_empty() && k.bytes().all(|b| b.is_ascii_digit()))
}

fn read_accepted(report: &Path) -> Option<bool> {
    let text = std::fs::read_to_string(report).ok()?;
    let value: serde_json::Value = serde_json::from_str(&text).ok()?;
    value.get("accepted")?.as_bool()
}

#[cfg(target_os = "linux")]
fn process_alive(pid: u32) -> bool {
    Path::new("/proc").join(pid.to_string()).exists()
}

#[cfg(not(target_os = "linux"))]
fn process_alive(pid: u32) -> bool {
    // Without a portable liveness check, a folder is only swept by the run that made it.
    let _ = pid;
    true
}

/// Atomically exchanges two paths (both must exist).
#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
    use std::ffi::CString;
    use std::os::unix::ffi::OsStrExt;
    let a = CString::new(a.as_os_str().as_bytes())?;
    let b = CString::new(b.as_os_str().as_bytes())?;
    // SAFETY: both paths are valid NUL-terminated strings for the duration of the call, and
    // AT_FDCWD is ignored for absolute paths.
    let rc = unsafe {
        libc::renameat2(
            libc::AT_FDCWD,
            a.as_ptr(),
            libc::AT_FDCWD,
            b.as_ptr(),
            libc::RENAME_EXCHANGE,
        )
    };
    if rc == 0 {
        Ok(())
    } else {
        Err(std::io::Error::last_os_error())
    }
}

#[cfg(not(target_os = "linux"))]
fn exchange(_a: &Path, _b: &Path) -> std::io::Result<()> {
    Err(std::io::Error::from(std::io::ErrorKind::Unsupported))
}

/// Whether `exchange` failed because the system or file system lacks it.
fn exchange_unsupported(e: &std::io::Error) -> bool {
    #[cfg(target_os = "linux")]
    if matches!(
        e.raw_os_error(),
        Some(libc::EINVAL | libc::ENOSYS | libc::EOPNOTSUPP)
    ) {
        return true;
    }
    e.kind() == std::io::ErrorKind::Unsupported
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene_folder(dir: &Path, accepted: bool) {
        std::fs::create_dir_all(dir.join("meshes")).unwrap();
        std::fs::write(dir.join(SCENE_JSON), "{}").unwrap();
        std::fs::write(
            dir.join(REPORT_JSON),
            format!("{{\"accepted\": {accepted}}}"),
        )
        .unwrap();
        std::fs::write(dir.join("scene.glb"), "glb").unwrap();
        std::fs::write(dir.join("view_3.png"), "png").unwrap();
        std::fs::write(dir.join("meshes/sofa_0_seat.obj"), "o").unwrap();
    }

    #[test]
    fn classifies_what_the_path_holds() {
        let tmp = tempfile::tempdir().unwrap();
        let p = tmp.path().join("out");
        assert_eq!(classify(&p).unwrap(), Existing::Nothing);
        std::fs::create_dir(&p).unwrap();
        assert_eq!(classify(&p).unwrap(), Existing::Empty);
        scene_folder(&p, true);
        assert_eq!(
            classify(&p).unwrap(),
            Existing::Scene {
                accepted: Some(true)
            }
        );
        std::fs::write(p.join("meshes/notes.txt"), "mine").unwrap();
        assert_eq!(
            classify(&p).unwrap(),
            Existing::Foreign {
                entry: "meshes".into()
            }
        );
        let docs = tmp.path().join("docs");
        std::fs::create_dir_all(docs.join("thesis")).unwrap();
        std::fs::write(docs.join("thesis/thesis.tex"), "x").unwrap();
        assert!(matches!(classify(&docs).unwrap(), Existing::Foreign { .. }));
        // Only our previews: still not a scene folder without scene.json/report.json.
        let previews = tmp.path().join("previews");
        std::fs::create_dir(&previews).unwrap();
        std::fs::write(previews.join("preview.png"), "png").unwrap();
        assert!(matches!(
            classify(&previews).unwrap(),
            Existing::Foreign { .. }
        ));
        let file = tmp.path().join("file");
        std::fs::write(&file, "x").unwrap();
        assert!(classify(&file)
            .unwrap_err()
            .contains("never replaces a file"));
    }

    #[test]
    fn view_pngs_are_recognised_exactly() {
        assert!(is_view_png("view_0.png"));
        assert!(is_view_png("view_12.png"));
        assert!(!is_view_png("view_.png"));
        assert!(!is_view_png("view_1a.png"));
        assert!(!is_view_png("holiday.png"));
    }

    #[test]
    fn paths_resolve_to_an_absolute_parent_and_a_name() {
        let tmp = tempfile::tempdir().unwrap();
        let real = tmp.path().canonicalize().unwrap();
        // `a` does not exist, so `..` after it is refused rather than guessed.
        assert!(resolve(&real.join("a/b/../c")).is_err());
        std::fs::create_dir_all(real.join("x/y")).unwrap();
        let (parent, name) = resolve(&real.join("x/y/..")).unwrap();
        assert_eq!((parent, name), (real.clone(), OsString::from("x")));
        let (parent, name) = resolve(&real.join("x/new/deeper")).unwrap();
        assert_eq!(parent, real.join("x/new"));
        assert_eq!(name, OsString::from("deeper"));
        let (parent, name) = resolve(&real.join("x/y/../y")).unwrap();
        assert_eq!((parent, name), (real.join("x"), OsString::from("y")));
    }

    #[test]
    fn long_names_are_refused_before_any_work() {
        let tmp = tempfile::tempdir().unwrap();
        let long = "n".repeat(MAX_OUTPUT_NAME + 1);
        let e = OutputDir::prepare(&tmp.path().join(&long), false).unwrap_err();
        assert!(e.to_string().contains("bytes long"), "{e}");
        assert!(OutputDir::prepare(&tmp.path().join("n".repeat(MAX_OUTPUT_NAME)), false).is_ok());
    }

    #[test]
    fn the_exchange_swaps_folders_and_the_fallback_rolls_back() {
        let tmp = tempfile::tempdir().unwrap();
        let out = tmp.path().join("out");
        scene_folder(&out, true);
        let dir = OutputDir::prepare(&out, false).unwrap();
        let staging = dir.stage().unwrap();
        std::fs::write(staging.path().join(SCENE_JSON), "new").unwrap();
        dir.swap_with_rollback(&staging.keep()).unwrap();
        assert_eq!(
            std::fs::read_to_string(out.join(SCENE_JSON)).unwrap(),
            "new"
        );
        let left: Vec<_> = std::fs::read_dir(tmp.path()).unwrap().flatten().collect();
        assert_eq!(left.len(), 1, "{left:?}");

        // The second rename fails (its source is gone): the previous output is put back.
        let gone = tmp.path().join(".out.partial-vanished");
        let e = dir.swap_with_rollback(&gone).unwrap_err();
        assert!(matches!(e, PipelineError::Write { .. }), "{e}");
        assert_eq!(
            std::fs::read_to_string(out.join(SCENE_JSON)).unwrap(),
            "new"
        );
    }

    #[test]
    fn exchange_swaps_two_folders_or_says_it_is_unsupported() {
        let tmp = tempfile::tempdir().unwrap();
        let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
        std::fs::create_dir(&a).unwrap();
        std::fs::create_dir(&b).unwrap();
        std::fs::write(a.join("from_a"), "").unwrap();
        match exchange(&a, &b) {
            Ok(()) => {
                assert!(b.join("from_a").is_file());
                assert!(!a.join("from_a").exists());
            }
            Err(e) => assert!(exchange_unsupported(&e), "{e}"),
        }
    }

    #[test]
    fn stale_folders_of_dead_runs_are_swept_and_an_interrupted_swap_is_restored() {
        let tmp = tempfile::tempdir().unwrap();
        let out = tmp.path().join("out");
        // A run (pid 0 is never a user process) killed between the two renames: the previous
        // output sits in its set-aside folder and `out` is missing.
        let aside = tmp.path().join(".out.old-0-abcdef");
        scene_folder(&aside.join("previous"), true);
        let partial = tmp.path().join(".out.partial-0-ghijkl");
        std::fs::create_dir_all(&partial).unwrap();
        std::fs::write(partial.join("scene.glb"), "half").unwrap();
        // Someone else's hidden folder with a similar name is left alone.
        let other = tmp.path().join(".out.partial-notapid");
        std::fs::create_dir_all(&other).unwrap();
        // A young one of a pid unknown here may belong to another host's live run: kept.
        let young = tmp.path().join(".out.partial-0-young1");
        std::fs::create_dir_all(&young).unwrap();
        let long_ago = std::time::SystemTime::now() - std::time::Duration::from_secs(3600);
        for dir in [&aside, &partial] {
            std::fs::File::open(dir)
                .unwrap()
                .set_modified(long_ago)
                .unwrap();
        }
        let dir = OutputDir::prepare(&out, false).unwrap();
        assert!(out.join(SCENE_JSON).is_file(), "previous output restored");
        assert!(!aside.exists() && !partial.exists());
        assert!(other.exists() && young.exists());
        assert!(dir.holds_accepted_scene(), "{:?}", dir.existing());
    }
}
