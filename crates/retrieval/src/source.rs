//! The retrieve stage's seam: where each planned object's asset (mesh and metadata) comes from.
//!
//! It lives here, beside the index, so that a provider crate can implement it without
//! depending on the pipeline that calls it.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError};

use crate::index::AssetIndex;
use scenethesis_import::{
    import_directory, AssetResolver, ImportWarning, ResolveError, MANIFEST_FILE,
};
use scenethesis_procedural::catalog;
use scenethesis_scene_graph::Asset;
use scenethesis_scene_graph::{AssetLook, AssetRef, Mesh};

/// Why an asset could not be retrieved or regenerated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AssetError {
    /// No asset of the source fits the object's category.
    #[error(
        "object `{id}`: the asset source `{source_name}` has no asset of category `{category}`"
    )]
    NoAsset {
        /// The planned object's id.
        id: String,
        /// Its category.
        category: String,
        /// The asset source's name.
        source_name: String,
    },
    /// A bring-your-own asset directory could not be imported.
    #[error("asset directory {}: {reason}", dir.display())]
    Import {
        /// The directory.
        dir: PathBuf,
        /// What went wrong.
        reason: String,
    },
    /// An asset reference cannot be turned back into a mesh by this source.
    #[error("asset {asset}: {reason}")]
    Unresolvable {
        /// The asset reference, as displayed.
        asset: String,
        /// Why not.
        reason: String,
    },
}

/// What an asset source is asked for: one planned object, by id and category, and the look
/// (room style, requested colours and materials) a generated asset should wear.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AssetQuery<'a> {
    /// The planned object's id (it seeds the choice among equal candidates).
    pub id: &'a str,
    /// The category the object must be.
    pub category: &'a str,
    /// The look a procedural asset is generated with (recorded in its
    /// [`AssetRef`](scenethesis_scene_graph::AssetRef)); imported assets keep their own
    /// materials.
    pub look: Option<&'a AssetLook>,
}

impl<'a> AssetQuery<'a> {
    /// A query for object `id` of `category`, with the generator's own materials.
    pub fn new(id: &'a str, category: &'a str) -> Self {
        Self {
            id,
            category,
            look: None,
        }
    }

    /// The same query for an asset wearing `look`.
    pub fn with_look(self, look: &'a AssetLook) -> Self {
        Self {
            look: Some(look),
            ..self
        }
    }
}

/// Where assets come from: the categories offered to the planner, one asset per planned object,
/// and the mesh behind an [`AssetRef`] stored in a `scene.json` (to re-export a saved scene).
///
/// Calling the seam with the built-in procedural library: the same object and variant give the
/// same asset, and its reference gives its mesh back.
///
/// ```
/// use scenethesis_retrieval::{AssetQuery, AssetSource, CatalogSource};
///
/// let source: &dyn AssetSource = &CatalogSource;
/// assert!(source.categories().contains("mug"));
/// let query = AssetQuery::new("mug_0", "mug");
/// let mug = source.retrieve(&query, 0).unwrap();
/// assert_eq!(mug.info.category, "mug");
/// assert_eq!(source.retrieve(&query, 0).unwrap().mesh, mug.mesh);
/// assert_eq!(source.mesh(&mug.info.source).unwrap(), mug.mesh);
/// assert!(source.retrieve(&AssetQuery::new("x_0", "spaceship"), 0).is_err());
/// ```
pub trait AssetSource: Send + Sync {
    /// A short name for reports.
    fn name(&self) -> &str;

    /// The categories this source can provide (what the planner may use).
    fn categories(&self) -> BTreeSet<String>;

    /// The asset for `object`. `variant` selects among equally good candidates (a different
    /// seed of a procedural generator, the next-ranked retrieval hit); the same object and
    /// variant always give the same asset.
    fn retrieve(&self, object: &AssetQuery<'_>, variant: u64) -> Result<Asset, AssetError>;

    /// The asset-frame mesh behind a reference this source produced.
    fn mesh(&self, asset: &AssetRef) -> Result<Mesh, AssetError>;
}

/// The built-in procedural library (`scenethesis_procedural::catalog`): every category the registry
/// lists, each object's asset generated with the seed [`catalog::object_seed`] gives its id and
/// the variant (the seed the guide's catalog metadata sizes it with). It
/// never retrieves imported assets, but [`AssetSource::mesh`] re-imports those a saved scene
/// references from their file's directory.
#[derive(Debug, Clone, Copy, Default)]
pub struct CatalogSource;

impl AssetSource for CatalogSource {
    fn name(&self) -> &str {
        "procedural-catalog"
    }

    fn categories(&self) -> BTreeSet<String> {
        catalog::categories().map(|c| c.name.to_owned()).collect()
    }

    fn retrieve(&self, object: &AssetQuery<'_>, variant: u64) -> Result<Asset, AssetError> {
        let category = catalog::category(object.category).ok_or_else(|| AssetError::NoAsset {
            id: object.id.to_owned(),
            category: object.category.to_owned(),
            source_name: self.name().to_owned(),
        })?;
        Ok(catalog::generate_with_look(
            category,
            catalog::object_seed(object.id, variant),
            object.look,
        ))
    }

    fn mesh(&self, asset: &AssetRef) -> Result<Mesh, AssetError> {
        match asset {
            AssetRef::Procedural {
                generator,
                seed,
                look,
            } => {
                let category =
                    catalog::category(generator).ok_or_else(|| AssetError::Unresolvable {
                        asset: asset.to_string(),
                        reason: format!("no built-in generator named `{generator}`"),
                    })?;
                Ok(catalog::generate_with_look(category, *seed, look.as_ref()).mesh)
            }
            AssetRef::Imported { id, path } => Ok(load_imported(asset, id, path)?.mesh),
        }
    }
}

/// Retrieval through an [`AssetIndex`]: each planned object's category is
/// the query and the best candidate is used. Built-in candidates are generated with a
/// procedural seed [`catalog::object_seed`] gives the object's id and the variant (the same
/// asset [`CatalogSource`] generates); imported (bring-your-own)
/// assets — see [`RetrievalSource::with_imported`] — rank above the built-in generator of the
/// same category and are used as loaded. Where several imported assets share the best score,
/// the variant picks among them.
pub struct RetrievalSource {
    index: AssetIndex,
    /// Imported assets by their id (`AssetRef::Imported::id`).
    imported: BTreeMap<String, Asset>,
    /// Asset directories re-imported for references not in `imported` (a saved scene being
    /// exported), each read once however many of its assets the scene uses.
    reimported: Mutex<AssetResolver>,
}

impl std::fmt::Debug for RetrievalSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RetrievalSource")
            .field("index", &self.index)
            .field("imported", &self.imported.keys().collect::<Vec<_>>())
            .finish()
    }
}

impl Default for RetrievalSource {
    fn default() -> Self {
        Self::new(AssetIndex::builtin())
    }
}

impl RetrievalSource {
    /// Retrieval over `index`. Imported entries of the index can only be used if their assets
    /// are also given (see [`RetrievalSource::with_imported`]); otherwise they are loaded from
    /// their file's directory when retrieved.
    pub fn new(index: AssetIndex) -> Self {
        Self::from_parts(index, BTreeMap::new())
    }

    /// Retrieval over the built-in library plus `assets` (e.g. the
    /// [`ImportReport::assets`](scenethesis_import::ImportReport) of
    /// [`scenethesis_import::import_directory`]). Assets that are not imported ones
    /// (their source is procedural) are ignored.
    pub fn with_imported(assets: impl IntoIterator<Item = Asset>) -> Self {
        let imported: BTreeMap<String, Asset> = assets
            .into_iter()
            .filter_map(|a| match &a.info.source {
                AssetRef::Imported { id, .. } => Some((id.clone(), a)),
                AssetRef::Procedural { .. } => None,
            })
            .collect();
        let index = AssetIndex::with_imported(imported.values().map(|a| &a.info));
        Self::from_parts(index, imported)
    }

    fn from_parts(index: AssetIndex, imported: BTreeMap<String, Asset>) -> Self {
        Self {
            index,
            imported,
            reimported: Mutex::default(),
        }
    }

    /// The built-in library plus every asset of the bring-your-own directory `dir` (an
    /// `assets.json` manifest and GLB/glTF/OBJ files), and the import's warnings for files that
    /// were skipped.
    pub fn from_directory(dir: &Path) -> Result<(Self, Vec<ImportWarning>), AssetError> {
        let report = import_directory(dir).map_err(|e| AssetError::Import {
            dir: dir.to_owned(),
            reason: e.to_string(),
        })?;
        if report.assets.is_empty() {
            return Err(AssetError::Import {
                dir: dir.to_owned(),
                reason: format!(
                    "no asset could be imported ({} skipped); expected GLB, glTF or OBJ files, \
                     optionally listed in {MANIFEST_FILE}",
                    report.warnings.len()
                ),
            });
        }
        Ok((Self::with_imported(report.assets), report.warnings))
    }

    /// How many imported assets this source holds.
    pub fn imported_count(&self) -> usize {
        self.imported.len()
    }

    /// The imported asset `asset` (with these `id` and `path`): from memory, else from its
    /// directory, re-imported once.
    fn imported_asset(&self, asset: &AssetRef, id: &str, path: &str) -> Result<Asset, AssetError> {
        if let Some(a) = self.imported.get(id) {
            return Ok(a.clone());
        }
        let _ = path;
        self.reimported
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .asset(asset)
            .map_err(|e| unresolvable(asset, e))
    }
}

impl AssetSource for RetrievalSource {
    fn name(&self) -> &str {
        "retrieval-index"
    }

    fn categories(&self) -> BTreeSet<String> {
        self.index.categories().map(str::to_owned).collect()
    }

    fn retrieve(&self, object: &AssetQuery<'_>, variant: u64) -> Result<Asset, AssetError> {
        let no_asset = || AssetError::NoAsset {
            id: object.id.to_owned(),
            category: object.category.to_owned(),
            source_name: self.name().to_owned(),
        };
        let seed = catalog::object_seed(object.id, variant);
        let hit = self
            .index
            .search(object.category, 1, seed)
            .into_iter()
            .next()
            .ok_or_else(no_asset)?;
        match &hit.asset {
            AssetRef::Procedural {
                generator, seed, ..
            } => {
                let category = catalog::category(generator).ok_or_else(no_asset)?;
                Ok(catalog::generate_with_look(category, *seed, object.look))
            }
            AssetRef::Imported { id, path } => self.imported_asset(&hit.asset, id, path),
        }
    }

    fn mesh(&self, asset: &AssetRef) -> Result<Mesh, AssetError> {
        match asset {
            AssetRef::Procedural { .. } => CatalogSource.mesh(asset),
            AssetRef::Imported { id, path } => Ok(self.imported_asset(asset, id, path)?.mesh),
        }
    }
}

/// Loads the imported asset `asset` through the import crate's resolver (its asset folder
/// imported again, so the manifest's units, axes and front apply).
fn load_imported(asset: &AssetRef, _id: &str, _path: &str) -> Result<Asset, AssetError> {
    AssetResolver::new()
        .asset(asset)
        .map_err(|e| unresolvable(asset, e))
}

fn unresolvable(asset: &AssetRef, e: ResolveError) -> AssetError {
    AssetError::Unresolvable {
        asset: scenethesis_scene_graph::printable(&asset.to_string()).into_owned(),
        reason: match e {
            ResolveError::Imported { reason, .. } => reason,
            other => other.to_string(),
        },
    }
}
