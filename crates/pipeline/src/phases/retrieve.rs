//! Retrieve: one asset per planned object, cached across re-plan rounds by object, variant and
//! look, with each asset's optimizer preparation cached by asset source.

use std::collections::BTreeMap;
use std::sync::Arc;

use scenethesis_agents::{Plan, PlannedObject};
use scenethesis_physics_opt::{PrepareSettings, PreparedAsset};
use scenethesis_retrieval::{AssetQuery, AssetSource};
use scenethesis_scene_graph::{Asset, AssetInfo, AssetLook};

use crate::PipelineError;

/// The cache key of one retrieved asset: the object's id, its variant and the digest of the
/// look it wears (empty for none), so that a changed look is a different asset.
pub(crate) type AssetKey = (String, u64, String);

/// Asset variants compared with the size the guide's image shows
/// ([`AssetCache::fit_variants`]).
pub(crate) const FIT_VARIANTS: u64 = 4;

/// How much better (|log ratio| of the heights) another variant must fit than the first to
/// replace it.
pub(crate) const FIT_MARGIN: f64 = 0.1;

/// How far an asset's size `[x, y, z]` is from a seen box's `[long side, height, short side]`:
/// the |log ratio| of the heights. The height is what a lift measures best (the robust vertical
/// extent); the footprint's hidden side is completed from a size prior, so it cannot tell
/// variants apart.
fn size_misfit(asset: [f32; 3], seen: &[f64; 3]) -> f64 {
    (f64::from(asset[1]).max(1e-3) / seen[1].max(1e-3))
        .ln()
        .abs()
}

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
            let key = self.fetch(source, plan, object, seed, variant)?;
            infos.insert(object.id.clone(), self.assets[&key].info.clone());
            chosen.insert(object.id.clone(), key);
        }
        Ok(Retrieved { infos, chosen })
    }

    /// The key of `object`'s asset at `variant` in its look, retrieving it unless cached.
    fn fetch(
        &mut self,
        source: &dyn AssetSource,
        plan: &Plan,
        object: &PlannedObject,
        seed: u64,
        variant: u64,
    ) -> Result<AssetKey, PipelineError> {
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
        Ok(key)
    }

    /// Starts every object whose size the guide's image shows (`sizes`, `[long side, height,
    /// short side]` by id) at the variant among the first [`FIT_VARIANTS`] whose asset fits
    /// that size best (the least |log ratio| of the heights; another variant than the first only
    /// when it fits by [`FIT_MARGIN`] better, since a lifted box is itself off by a few per
    /// cent): the image shows one particular sofa, and the variant nearest to it needs
    /// the least scaling and pushing to stand where the image shows it. Re-plans move on from
    /// that variant.
    pub(crate) fn fit_variants(
        &mut self,
        source: &dyn AssetSource,
        plan: &Plan,
        seed: u64,
        sizes: &BTreeMap<String, [f64; 3]>,
    ) -> Result<(), PipelineError> {
        for object in &plan.objects {
            let Some(seen) = sizes.get(&object.id) else {
                continue;
            };
            let mut best: Option<(f64, u64)> = None;
            for variant in 0..FIT_VARIANTS {
                let key = self.fetch(source, plan, object, seed, variant)?;
                let misfit = size_misfit(self.assets[&key].info.size, seen);
                let margin = if variant == 0 { 0.0 } else { FIT_MARGIN };
                if best.is_none_or(|(m, _)| misfit < m - margin) {
                    best = Some((misfit, variant));
                }
            }
            if let Some((_, variant)) = best.filter(|(_, v)| *v > 0) {
                self.variants.insert(object.id.clone(), variant);
            }
        }
        Ok(())
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
