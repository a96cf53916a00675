//! The resolver: the one place that turns an asset reference of a scene back into an asset.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use scenethesis_procedural::catalog;
use scenethesis_scene_graph::{Asset, AssetRef, Mesh};

use crate::{printable, Importer, MANIFEST_FILE};

/// Why an asset reference could not be turned into an asset.
#[derive(Debug, thiserror::Error)]
pub enum ResolveError {
    /// A procedural reference names a generator the built-in library does not have.
    #[error("unknown procedural generator `{generator}`")]
    UnknownGenerator {
        /// The generator name (escaped for printing).
        generator: String,
    },
    /// An imported asset's folder could not be imported again, or no longer holds the asset.
    #[error("imported asset `{id}` ({path}): {reason}")]
    Imported {
        /// The asset id (escaped for printing).
        id: String,
        /// The stored path of its file (escaped for printing).
        path: String,
        /// What went wrong.
        reason: String,
    },
}

/// The one place that turns an [`AssetRef`] back into an [`Asset`] (mesh in the asset frame
/// plus metadata), used by export, `render` and `eval`: a procedural reference is regenerated
/// from its generator and seed; an imported one by importing its asset folder again (so the
/// manifest's units, axes and front apply) and picking the asset by id. The asset folder is the
/// nearest folder above the file that holds an `assets.json`, else the file's own folder.
/// Imported folders are cached, so resolving many objects of one pack imports it once.
/// Imported folders are read with an [`Importer`]: the built-in loaders by default, or those
/// given to [`AssetResolver::with_importer`].
#[derive(Debug, Default)]
pub struct AssetResolver {
    importer: Importer,
    folders: BTreeMap<PathBuf, Vec<Asset>>,
}

impl AssetResolver {
    /// A resolver with an empty cache and the built-in loaders (GLB/glTF and OBJ).
    pub fn new() -> Self {
        Self::default()
    }

    /// A resolver with an empty cache that re-imports folders with `importer` (and so with its
    /// loaders).
    pub fn with_importer(importer: Importer) -> Self {
        Self {
            importer,
            folders: BTreeMap::new(),
        }
    }

    /// The asset a reference names.
    pub fn asset(&mut self, asset: &AssetRef) -> Result<Asset, ResolveError> {
        match asset {
            AssetRef::Procedural {
                generator,
                seed,
                look,
            } => {
                let category =
                    catalog::category(generator).ok_or_else(|| ResolveError::UnknownGenerator {
                        generator: printable(generator).into_owned(),
                    })?;
                Ok(catalog::generate_with_look(category, *seed, look.as_ref()))
            }
            AssetRef::Imported { id, path } => self.imported(id, path),
        }
    }

    /// The mesh (asset frame) of the asset a reference names.
    pub fn mesh(&mut self, asset: &AssetRef) -> Result<Mesh, ResolveError> {
        self.asset(asset).map(|a| a.mesh)
    }

    fn imported(&mut self, id: &str, path: &str) -> Result<Asset, ResolveError> {
        let err = |reason: String| ResolveError::Imported {
            id: printable(id).into_owned(),
            path: printable(path).into_owned(),
            reason,
        };
        let file = Path::new(path);
        if !file.is_absolute() {
            tracing::debug!(
                "imported asset path {path} is relative: resolved from the working directory"
            );
        }
        let folder = asset_folder(file).ok_or_else(|| err("its file no longer exists".into()))?;
        if !self.folders.contains_key(&folder) {
            let report = self
                .importer
                .import_directory(&folder)
                .map_err(|e| err(format!("cannot re-import {}: {e}", folder.display())))?;
            self.folders.insert(folder.clone(), report.assets);
        }
        self.folders[&folder]
            .iter()
            .find(|a| matches!(&a.info.source, AssetRef::Imported { id: found, .. } if found == id))
            .cloned()
            .ok_or_else(|| {
                err(format!(
                    "the asset folder {} no longer holds an asset with this id",
                    folder.display()
                ))
            })
    }
}

/// The canonical asset folder of an imported file: the nearest of its (up to eight) ancestor
/// folders holding an `assets.json`, else its own folder. `None` when the file cannot be found.
fn asset_folder(file: &Path) -> Option<PathBuf> {
    let file = file.canonicalize().ok()?;
    let own = file.parent()?.to_owned();
    own.ancestors()
        .take(8)
        .find(|d| d.join(MANIFEST_FILE).is_file())
        .map(Path::to_owned)
        .or(Some(own))
}
