//! Retrieve: one asset per planned object, cached across re-plan rounds by object and variant,
//! with each asset's optimizer preparation cached by asset source.

use std::collections::BTreeMap;
use std::sync::Arc;

use scenethesis_agents::Plan;
use scenethesis_physics_opt::{PrepareSettings, PreparedAsset};
use scenethesis_retrieval::{AssetQuery, AssetSource};
use scenethesis_scene_graph::{Asset, AssetInfo, AssetLook};

use crate::PipelineError;

/// The cache key of one retrieved asset: the object's id, its variant and the digest of the
/// look it wears (empty for none), so that a changed look is a different asset.
pub(crate) type AssetKey = (String, u64, String);

/// The assets of one round: each object's asset info and the cache key of its asset.
pub(crate) struct Retrieved {
    pub(crate) infos: BTreeMap<String, AssetInfo>,
    pub(crate) chosen: BTreeMap<String, AssetKey>,
}

/// Assets and preparations kept across the rounds of a run.
#[derive(Default)]
pub(crate) struct AssetCache {
    variants: BTreeMap<String, u64>,
    assets: BTreeMap<AssetKey, Asset>,
    prepared: BTreeMap<String, Arc<PreparedAsset>>,
}

impl AssetCache {
    /// Retrieves every object of `plan` at its current variant (the run's `seed` plus the
    /// variant number), reusing assets already retrieved.
    pub(crate) fn retrieve(
        &mut self,
        source: &dyn AssetSource,
        plan: &Plan,
        seed: u64,
    ) -> Result<Retrieved, PipelineError> {
        let mut infos = BTreeMap::new();
        let mut chosen = BTreeMap::new();
        for object in &plan.objects {
            let variant = self.variants.get(&object.id).copied().unwrap_or(0);
            let look = plan.look.as_ref().map(|l| l.asset_look(object));
            let look = look.filter(|l| !l.is_plain());
            let digest = look.as_ref().map(AssetLook::digest).unwrap_or_default();
            let key = (object.id.clone(), variant, digest);
            if !self.assets.contains_key(&key) {
                let query = AssetQuery::new(&object.id, &object.category);
                let query = match &look {
                    Some(look) => query.with_look(look),
                    None => query,
                };
                let asset = source.retrieve(&query, seed.wrapping_add(variant))?;
                self.assets.insert(key.clone(), asset);
            }
            infos.insert(object.id.clone(), self.assets[&key].info.clone());
            chosen.insert(object.id.clone(), key);
        }
        Ok(Retrieved { infos, chosen })
    }

    /// The asset retrieved under `key`.
    pub(crate) fn asset(&self, key: &AssetKey) -> &Asset {
        &self.assets[key]
    }

    /// The optimizer's preparation of the asset under `key`, made once per asset source.
    pub(crate) fn prepared(
        &mut self,
        key: &AssetKey,
        settings: &PrepareSettings,
    ) -> Result<Arc<PreparedAsset>, PipelineError> {
        let asset = &self.assets[key];
        let source = asset.info.source.to_string();
        if let Some(prepared) = self.prepared.get(&source) {
            return Ok(prepared.clone());
        }
        let prepared = Arc::new(PreparedAsset::from_asset(asset, settings)?);
        self.prepared.insert(source, prepared.clone());
        Ok(prepared)
    }

    /// The next round retrieves another variant of object `id`.
    pub(crate) fn next_variant(&mut self, id: &str) {
        *self.variants.entry(id.to_owned()).or_default() += 1;
    }
}
