//! The retrieve stage's seam: where each planned object's asset (mesh and metadata) comes from.

use std::collections::BTreeSet;

use scenethesis_agents::PlannedObject;
use scenethesis_assets::{catalog, Asset};
use scenethesis_retrieval::AssetIndex;
use scenethesis_scene_graph::{AssetRef, Mesh};

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
    /// An asset reference cannot be turned back into a mesh by this source.
    #[error("asset {asset}: {reason}")]
    Unresolvable {
        /// The asset reference, as displayed.
        asset: String,
        /// Why not.
        reason: String,
    },
}

/// Where assets come from: the categories offered to the planner, one asset per planned object,
/// and the mesh behind an [`AssetRef`] stored in a `scene.json` (to re-export a saved scene).
pub trait AssetSource: Send + Sync {
    /// A short name for reports.
    fn name(&self) -> &str;

    /// The categories this source can provide (what the planner may use).
    fn categories(&self) -> BTreeSet<String>;

    /// The asset for `object`. `variant` selects among equally good candidates (a different
    /// seed of a procedural generator, the next-ranked retrieval hit); the same object and
    /// variant always give the same asset.
    fn retrieve(&self, object: &PlannedObject, variant: u64) -> Result<Asset, AssetError>;

    /// The asset-frame mesh behind a reference this source produced.
    fn mesh(&self, asset: &AssetRef) -> Result<Mesh, AssetError>;
}

/// The built-in procedural library (`scenethesis_assets::catalog`): every category the registry
/// lists, each object's asset generated with a seed derived from its id and the variant.
#[derive(Debug, Clone, Copy, Default)]
pub struct CatalogSource;

impl AssetSource for CatalogSource {
    fn name(&self) -> &str {
        "procedural-catalog"
    }

    fn categories(&self) -> BTreeSet<String> {
        catalog::categories().map(|c| c.name.to_owned()).collect()
    }

    fn retrieve(&self, object: &PlannedObject, variant: u64) -> Result<Asset, AssetError> {
        let category = catalog::category(&object.category).ok_or_else(|| AssetError::NoAsset {
            id: object.id.clone(),
            category: object.category.clone(),
            source_name: self.name().to_owned(),
        })?;
        Ok(catalog::generate(
            category,
            object_seed(&object.id, variant),
        ))
    }

    fn mesh(&self, asset: &AssetRef) -> Result<Mesh, AssetError> {
        match asset {
            AssetRef::Procedural { generator, seed } => {
                let category =
                    catalog::category(generator).ok_or_else(|| AssetError::Unresolvable {
                        asset: asset.to_string(),
                        reason: format!("no built-in generator named `{generator}`"),
                    })?;
                Ok(catalog::generate(category, *seed).mesh)
            }
            AssetRef::Imported { .. } => Err(AssetError::Unresolvable {
                asset: asset.to_string(),
                reason: "an imported asset; the procedural catalog cannot regenerate it".into(),
            }),
        }
    }
}

/// Retrieval through a [`scenethesis_retrieval::AssetIndex`]: each planned object's category is
/// the query and the best candidate is used, its procedural seed drawn from the object's id and
/// the variant. The default index holds the built-in library; imported assets in the index are
/// not supported by this source yet (their meshes are not loaded) and are reported as errors.
pub struct RetrievalSource {
    index: AssetIndex,
}

impl std::fmt::Debug for RetrievalSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RetrievalSource")
            .field("index", &self.index)
            .finish()
    }
}

impl Default for RetrievalSource {
    fn default() -> Self {
        Self::new(AssetIndex::builtin())
    }
}

impl RetrievalSource {
    /// Retrieval over `index`.
    pub fn new(index: AssetIndex) -> Self {
        Self { index }
    }
}

impl AssetSource for RetrievalSource {
    fn name(&self) -> &str {
        "retrieval-index"
    }

    fn categories(&self) -> BTreeSet<String> {
        self.index.categories().map(str::to_owned).collect()
    }

    fn retrieve(&self, object: &PlannedObject, variant: u64) -> Result<Asset, AssetError> {
        let no_asset = || AssetError::NoAsset {
            id: object.id.clone(),
            category: object.category.clone(),
            source_name: self.name().to_owned(),
        };
        let hit = self
            .index
            .search(&object.category, 1, object_seed(&object.id, variant))
            .into_iter()
            .next()
            .ok_or_else(no_asset)?;
        match &hit.asset {
            AssetRef::Procedural { generator, seed } => {
                let category = catalog::category(generator).ok_or_else(no_asset)?;
                Ok(catalog::generate(category, *seed))
            }
            AssetRef::Imported { .. } => Err(AssetError::Unresolvable {
                asset: hit.asset.to_string(),
                reason: "imported assets are not loaded by the pipeline's retrieval source yet"
                    .into(),
            }),
        }
    }

    fn mesh(&self, asset: &AssetRef) -> Result<Mesh, AssetError> {
        CatalogSource.mesh(asset)
    }
}

/// A stable per-object seed: FNV-1a of the object id, mixed with the variant.
pub fn object_seed(id: &str, variant: u64) -> u64 {
    let h = id.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |h, b| {
        (h ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3)
    });
    // splitmix64 finaliser so neighbouring variants give unrelated seeds.
    let mut z = h ^ variant.wrapping_mul(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}
