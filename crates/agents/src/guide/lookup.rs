//! Asset lookups: nominal priors from the knowledge files, and the built-in catalog.

use scenethesis_procedural::catalog;
use scenethesis_scene_graph::AssetRef;
use scenethesis_scene_graph::{AssetInfo, Placement, SupportSurface, SurfaceKind};

use super::AssetLookup;
use crate::knowledge::{Knowledge, Mount, NominalShape};
use crate::plan::PlannedObject;

/// Box-shaped metadata from the category priors (the `plan` rows of `crates/procedural/data/categories.toml`): nominal size
/// and support surfaces by shape. For planning and layout before real assets are chosen, and
/// for categories no generator provides.
#[derive(Debug, Clone, Copy)]
pub struct NominalAssets<'k> {
    knowledge: &'k Knowledge,
}

impl Default for NominalAssets<'static> {
    fn default() -> Self {
        Self {
            knowledge: Knowledge::builtin(),
        }
    }
}

impl<'k> NominalAssets<'k> {
    /// Nominal assets from `knowledge`'s priors.
    pub fn new(knowledge: &'k Knowledge) -> Self {
        Self { knowledge }
    }

    /// The nominal metadata of a category, or `None` if it has no prior.
    pub fn info(&self, category: &str, seed: u64) -> Option<AssetInfo> {
        let prior = self.knowledge.prior(category)?;
        let [w, h, d] = prior.size;
        let rect = |x0: f64, z0: f64, x1: f64, z1: f64| -> Vec<[f32; 2]> {
            vec![
                [x0 as f32, z0 as f32],
                [x0 as f32, z1 as f32],
                [x1 as f32, z1 as f32],
                [x1 as f32, z0 as f32],
            ]
        };
        let (hw, hd) = (w / 2.0, d / 2.0);
        let top = |inset: f64, height: f64| SupportSurface {
            name: "top".into(),
            kind: SurfaceKind::Top,
            polygon: rect(-hw + inset, -hd + inset, hw - inset, hd - inset),
            height: height as f32,
            clearance: None,
        };
        let shelves = |n: u32| -> Vec<SupportSurface> {
            let pitch = (h - 0.06) / n as f64;
            (0..n)
                .map(|i| SupportSurface {
                    name: format!("shelf_{i}"),
                    kind: SurfaceKind::Shelf,
                    polygon: rect(-hw + 0.04, -hd + 0.03, hw - 0.04, hd - 0.02),
                    height: (0.04 + i as f64 * pitch) as f32,
                    clearance: Some((pitch - 0.03) as f32),
                })
                .collect()
        };
        let surfaces = match prior.shape {
            NominalShape::Table => vec![
                top(0.03, h),
                SupportSurface {
                    name: "under".into(),
                    kind: SurfaceKind::Under,
                    polygon: rect(-hw + 0.1, -hd + 0.1, hw - 0.1, hd - 0.1),
                    height: 0.0,
                    clearance: Some((h - 0.08) as f32),
                },
            ],
            NominalShape::Seat => {
                let seat = (h * 0.5).min(0.46);
                vec![SupportSurface {
                    name: "seat".into(),
                    kind: SurfaceKind::Top,
                    polygon: rect(-hw + 0.12, -hd + 0.2, hw - 0.12, hd - 0.05),
                    height: seat as f32,
                    clearance: None,
                }]
            }
            NominalShape::Shelves => shelves(prior.shelves),
            NominalShape::Cabinet => {
                let mut s = shelves(prior.shelves);
                s.push(top(0.03, h));
                s
            }
            NominalShape::Container => vec![SupportSurface {
                name: "interior".into(),
                kind: SurfaceKind::Interior,
                polygon: rect(-hw + 0.04, -hd + 0.04, hw - 0.04, hd - 0.04),
                height: 0.03_f64.min(h / 4.0) as f32,
                clearance: None,
            }],
            NominalShape::Solid => vec![top(0.03, h)],
            NominalShape::Bed => vec![top(0.1_f64.min(hw / 4.0), h)],
            NominalShape::None => vec![],
        };
        let placement = match prior.mount {
            Mount::Floor => Placement::Floor,
            Mount::Wall => Placement::Wall,
            Mount::Surface => Placement::Surface,
            Mount::Ceiling => Placement::Ceiling,
        };
        Some(AssetInfo {
            source: AssetRef::Procedural {
                generator: category.to_owned(),
                seed,
                look: None,
            },
            category: category.to_owned(),
            synonyms: prior.words.clone(),
            size: [w as f32, h as f32, d as f32],
            placement,
            front: [0.0, 0.0, 1.0],
            support_surfaces: surfaces,
            scale_range: if prior.mount == Mount::Surface {
                [0.5, 1.3]
            } else {
                [0.8, 1.2]
            },
            joints: Vec::new(),
            opening_bounds: None,
        })
    }
}

impl AssetLookup for NominalAssets<'_> {
    fn asset_info(&self, object: &PlannedObject) -> Option<AssetInfo> {
        self.info(&object.category, catalog::object_seed(&object.id, 0))
    }
}

/// Metadata of the built-in procedural library: each object's asset is generated by its
/// category's generator with the seed [`catalog::object_seed`] gives the object id at the
/// scene seed — the asset retrieval generates for the object in round 0 of a run with that
/// seed, so the layout is planned with the sizes of the meshes the scene will hold. Categories
/// the registry does not (yet) provide fall back to [`NominalAssets`].
#[derive(Debug, Clone, Copy)]
pub struct CatalogAssets {
    seed: u64,
}

impl CatalogAssets {
    /// The catalog with per-object seeds derived from `seed`.
    pub fn new(seed: u64) -> Self {
        Self { seed }
    }
}

impl AssetLookup for CatalogAssets {
    fn asset_info(&self, object: &PlannedObject) -> Option<AssetInfo> {
        let seed = catalog::object_seed(&object.id, self.seed);
        match catalog::category(&object.category) {
            Some(category) => Some(catalog::generate(category, seed).info),
            None => NominalAssets::default().info(&object.category, seed),
        }
    }
}
