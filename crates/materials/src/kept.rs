//! Where a material's maps come from: made once per process ([`maps`]) and, when a folder is
//! named, kept on disk between processes. Each command-line run would otherwise generate
//! again, from scratch, the maps of every material its scene wears (about a fifth of a small
//! scene's CPU time).
//!
//! Keeping is off until [`keep_maps_in`] names a folder. Maps live in
//! `<folder>/maps-<digest>/<id>.maps`, where the digest covers this crate's version and every
//! one of its source files, so a file written by a build whose generator differs is never read. A file is the texels and the
//! averages with a checksum; one that is missing, short, foreign or corrupt is ignored and
//! written again. Files are written to a temporary name and renamed into place, so a process
//! that reads while another writes sees a whole file or none. A build that starts its folder
//! removes the other builds' `maps-*` folders beside it. The folder is a cache: failing to
//! read or write it only means the maps are generated as they would be without it.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::{OnceLock, RwLock};

use scenethesis_scene_graph::fnv1a64;

use crate::library::{library, LibraryMaterial};
use crate::maps::{generate, MapKind, Maps, TEXTURE_SIZE};

/// Names the files of this build's generator.
const SOURCE_DIGEST: &str = env!("SCENETHESIS_MATERIALS_SOURCE_DIGEST");

/// The first bytes of a kept file.
const MAGIC: &[u8; 8] = b"SCNMAPS1";

/// Bytes before the maps: the magic and the texture size (`u32`).
const HEADER: usize = MAGIC.len() + 4;

static FOLDER: RwLock<Option<PathBuf>> = RwLock::new(None);

/// Keeps the maps this process generates from now on in `folder` (created when missing),
/// and reads the maps earlier processes kept there instead of generating them again; `None`
/// stops keeping and reading. Maps already generated in this process stay as they are.
///
/// ```
/// use scenethesis_materials::{by_id, keep_maps_in, kept_maps_folder, maps, MapKind};
///
/// let folder = std::env::temp_dir().join(format!("scenethesis-doc-{}", std::process::id()));
/// keep_maps_in(Some(folder.clone()));
/// assert_eq!(kept_maps_folder(), Some(folder.clone()));
/// let felt = maps(by_id("felt").unwrap());
/// assert_eq!(&felt.png(MapKind::BaseColor)[1..4], b"PNG");
/// keep_maps_in(None);
/// # let _ = std::fs::remove_dir_all(&folder);
/// ```
pub fn keep_maps_in(folder: Option<PathBuf>) {
    if let Ok(mut kept) = FOLDER.write() {
        *kept = folder;
    }
}

/// The folder the command line and the Python package keep maps in: `SCENETHESIS_CACHE_DIR`
/// (an empty value: none), else `$XDG_CACHE_HOME/scenethesis` (when absolute), else
/// `$HOME/.cache/scenethesis`; `None` when none of them is set. A library that wants maps kept
/// passes this (or its own folder) to [`keep_maps_in`]; nothing is kept unless it does.
pub fn default_maps_folder() -> Option<PathBuf> {
    let named = |var: &str| std::env::var_os(var).map(PathBuf::from);
    match named("SCENETHESIS_CACHE_DIR") {
        Some(dir) if dir.as_os_str().is_empty() => None,
        Some(dir) => Some(dir),
        None => named("XDG_CACHE_HOME")
            .filter(|d| d.is_absolute())
            .or_else(|| named("HOME").map(|home| home.join(".cache")))
            .map(|cache| cache.join("scenethesis")),
    }
}

/// The folder [`keep_maps_in`] named, if any.
pub fn kept_maps_folder() -> Option<PathBuf> {
    FOLDER.read().ok().and_then(|kept| kept.clone())
}

/// The maps of `material`, made on the first call for it and shared afterwards: read from
/// the folder [`keep_maps_in`] names when an earlier process kept them
/// there, else generated (and kept there when a folder is named).
pub fn maps(material: &LibraryMaterial) -> &'static Maps {
    static CACHE: OnceLock<Vec<OnceLock<Maps>>> = OnceLock::new();
    let cache = CACHE.get_or_init(|| library().iter().map(|_| OnceLock::new()).collect());
    cache[material.index()].get_or_init(|| {
        let folder = kept_maps_folder();
        if let Some(kept) = folder.as_deref().and_then(|f| load(f, material)) {
            return kept;
        }
        let made = generate(material);
        if let Some(folder) = &folder {
            store(folder, material, &made);
        }
        made
    })
}

/// Generates the maps of every material in `materials` that no earlier call generated, and
/// encodes them as PNG files, so that a later [`maps`] or [`Maps::png`] finds them ready.
///
/// Meant for a spare thread while other work runs (the pipeline calls it beside the judge):
/// the maps are the same whoever makes them first.
///
/// ```
/// use scenethesis_materials::{by_id, make_maps, maps, MapKind};
///
/// let oak = by_id("oak").unwrap();
/// make_maps([oak]);
/// assert_eq!(&maps(oak).png(MapKind::Normal)[1..4], b"PNG");
/// ```
pub fn make_maps(materials: impl IntoIterator<Item = &'static LibraryMaterial>) {
    for material in materials {
        let made = maps(material);
        for kind in MapKind::ALL {
            made.png(kind);
        }
    }
}

/// The file that keeps `material`'s maps under `folder`.
fn file_of(folder: &Path, material: &LibraryMaterial) -> PathBuf {
    folder
        .join(format!("maps-{SOURCE_DIGEST}"))
        .join(format!("{}.maps", material.id))
}

/// The maps of `material` kept under `folder`, if a whole, valid file holds them.
pub(crate) fn load(folder: &Path, material: &LibraryMaterial) -> Option<Maps> {
    let bytes = fs::read(file_of(folder, material)).ok()?;
    decode(&bytes)
}

/// Keeps `maps` of `material` under `folder`; a failure leaves no file behind.
pub(crate) fn store(folder: &Path, material: &LibraryMaterial, maps: &Maps) {
    let file = file_of(folder, material);
    let Some(dir) = file.parent() else {
        return;
    };
    let first = !dir.is_dir();
    if fs::create_dir_all(dir).is_err() {
        return;
    }
    if first {
        remove_other_builds(folder, dir);
    }
    let temporary = dir.join(format!(
        ".{}.{}.{:?}.tmp",
        material.id,
        std::process::id(),
        std::thread::current().id()
    ));
    let written = fs::File::create(&temporary)
        .and_then(|mut f| f.write_all(&encode(maps)).and_then(|_| f.sync_data()))
        .and_then(|_| fs::rename(&temporary, &file));
    if written.is_err() {
        let _ = fs::remove_file(&temporary);
    }
}

/// Removes the map folders of other builds under `folder` (all but `ours`): each build of
/// the generator keeps its own, and only the newest one is read again as a rule.
fn remove_other_builds(folder: &Path, ours: &Path) {
    let Ok(entries) = fs::read_dir(folder) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        let named = entry.file_name().to_string_lossy().starts_with("maps-");
        if named && path != ours && path.is_dir() {
            let _ = fs::remove_dir_all(&path);
        }
    }
}

/// Bytes of one map (RGB8).
fn map_len() -> usize {
    (TEXTURE_SIZE * TEXTURE_SIZE * 3) as usize
}

/// The bytes of a kept file: magic, size, the three maps, the four averages, checksum.
fn encode(maps: &Maps) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEADER + 3 * map_len() + 16 + 8);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&TEXTURE_SIZE.to_le_bytes());
    out.extend_from_slice(&maps.base_color);
    out.extend_from_slice(&maps.normal);
    out.extend_from_slice(&maps.metallic_roughness);
    for value in maps.mean_albedo.iter().chain([&maps.mean_roughness]) {
        out.extend_from_slice(&value.to_le_bytes());
    }
    let sum = fnv1a64(&out);
    out.extend_from_slice(&sum.to_le_bytes());
    out
}

/// The maps of a kept file's bytes, or `None` when they are not exactly what [`encode`]
/// writes for this texture size.
fn decode(bytes: &[u8]) -> Option<Maps> {
    let n = map_len();
    let body_len = HEADER + 3 * n + 16;
    if bytes.len() != body_len + 8 || &bytes[..MAGIC.len()] != MAGIC {
        return None;
    }
    let (body, sum) = bytes.split_at(body_len);
    if fnv1a64(body).to_le_bytes() != sum || body[MAGIC.len()..HEADER] != TEXTURE_SIZE.to_le_bytes()
    {
        return None;
    }
    let maps = &body[HEADER..HEADER + 3 * n];
    let float = |k: usize| {
        let at = HEADER + 3 * n + 4 * k;
        f32::from_le_bytes([body[at], body[at + 1], body[at + 2], body[at + 3]])
    };
    Some(Maps::from_parts(
        maps[..n].to_vec(),
        maps[n..2 * n].to_vec(),
        maps[2 * n..].to_vec(),
        [float(0), float(1), float(2)],
        float(3),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::library::by_id;

    #[test]
    fn maps_are_made_once_per_process() {
        let oak = by_id("oak").unwrap();
        let first = maps(oak);
        assert!(std::ptr::eq(first, maps(oak)), "made once");
        assert_eq!(*first, generate(oak));
    }

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("scenethesis-kept-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        dir
    }

    #[test]
    fn kept_maps_read_back_exactly_and_bad_files_are_ignored() {
        let folder = scratch("round-trip");
        let oak = by_id("oak").unwrap();
        assert!(load(&folder, oak).is_none(), "nothing kept yet");
        let made = generate(oak);
        store(&folder, oak, &made);
        let read = load(&folder, oak).expect("the kept file reads back");
        assert_eq!(read, made);
        // Only the file itself is left: no temporary beside it.
        let dir = file_of(&folder, oak).parent().unwrap().to_owned();
        assert_eq!(fs::read_dir(&dir).unwrap().count(), 1);
        // A flipped texel, a cut file or another size: ignored.
        let file = file_of(&folder, oak);
        let good = fs::read(&file).unwrap();
        let mut flipped = good.clone();
        flipped[100] ^= 1;
        let mut resized = good.clone();
        resized[8] ^= 1;
        for bad in [flipped, good[..good.len() - 1].to_vec(), resized] {
            fs::write(&file, bad).unwrap();
            assert!(load(&folder, oak).is_none());
        }
        // Another material's file does not stand in.
        fs::write(&file, &good).unwrap();
        assert!(load(&folder, by_id("walnut").unwrap()).is_none());
        let _ = fs::remove_dir_all(&folder);
    }

    #[test]
    fn a_new_build_removes_the_folders_of_other_builds_only() {
        let folder = scratch("builds");
        let old = folder.join("maps-0123456789abcdef");
        fs::create_dir_all(&old).unwrap();
        fs::write(old.join("oak.maps"), b"an older build's").unwrap();
        let mine = folder.join("notes");
        fs::create_dir_all(&mine).unwrap();
        let felt = by_id("felt").unwrap();
        store(&folder, felt, &generate(felt));
        assert!(!old.exists(), "the other build's folder stays");
        assert!(mine.exists(), "a folder not named maps-* was removed");
        assert!(load(&folder, felt).is_some());
        let _ = fs::remove_dir_all(&folder);
    }

    #[test]
    fn an_unwritable_folder_keeps_nothing_and_fails_nothing() {
        let folder = scratch("unwritable");
        // A file where the folder should be: nothing can be created under it.
        fs::write(&folder, b"not a folder").unwrap();
        let felt = by_id("felt").unwrap();
        store(&folder, felt, &generate(felt));
        assert!(load(&folder, felt).is_none());
        let _ = fs::remove_file(&folder);
    }
}
